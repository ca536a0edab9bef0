"""The book's synthetic cohort: the seeded generative model of the VR touch experiment and its calibration.

:func:`generate_cohort` draws recordings from :class:`CohortModel`; the calibration against the paper's
published numbers and the seed survey are in ``_calibration`` (the survey is package data).
"""

import lazy_loader as _lazy

__getattr__, __dir__, __all__ = _lazy.attach(
    __name__,
    submod_attrs={
        "_calibration": ["calibration_table", "seed_survey", "SURVEY_CSV", "survey_summary"],
        "_model": ["CohortModel", "generate_cohort", "model_table", "SEED"],
        "_replication": [
            "DRAW_QUANTITIES",
            "draw_recordings",
            "draw_results",
            "read_replication",
            "REPLICATION_CSV",
            "replication_summary",
            "replication_table",
            "within_draws",
        ],
    },
)
