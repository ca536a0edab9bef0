"""From a trial's samples to its features: filtering, onset and contact, the segment, PV and SPARC.

:func:`trial_features` gives the per-trial table (status and reason for every trial), :func:`select`
the paper's window, :func:`segment` one trial's analysed segment. Behind it: the positions' low-pass
filter and Winter's residual analysis (``_filtering``), one trial's segmentation (``_segmentation``),
the same for many trials at once (``_vectorised``) and for a Parquet dataset on a Dask cluster (``_dask``).
"""

import lazy_loader as _lazy

__getattr__, __dir__, __all__ = _lazy.attach(
    __name__,
    submod_attrs={
        "_dask": ["cluster_features"],
        "_filtering": [
            "choose_lowpass",
            "Lowpass",
            "combine_rest_noise",
            "measure_rest_noise",
            "rest_noise_rows",
            "NO_FILTER",
            "NOISE_FIT_RANGE",
            "parse_lowpass",
            "residual_analysis",
            "ResidualAnalysis",
            "residual_trials",
            "rest_window",
            "RestNoise",
        ],
        "_rules": [
            "DEFAULT_HOLD_S",
            "EndRule",
            "PAPER_END",
            "PAPER_START",
            "parse_end",
            "parse_start",
            "RuleError",
            "SpeedThreshold",
            "StartRule",
        ],
        "_selection": [
            "apply_selection",
            "feature_label",
            "feature_name",
            "FEATURE_UNITS",
            "PAPER_FEATURES",
            "PAPER_SELECTION",
            "parse_features",
            "parse_selection",
            "parse_window",
            "SelectionError",
            "Window",
        ],
        "_segmentation": [
            "Segment",
            "CONTACT_WINDOW",
            "DIFF_SPAN_S",
            "diff_window",
            "MIN_DIFF_WINDOW",
            "MIN_SEGMENT_SAMPLES",
            "ONSET_SPEED",
            "path_length",
            "peak_acceleration",
            "segment_arrays",
            "segmentation_detail",
            "SegmentationDetail",
            "start_rule",
            "velocity",
        ],
        "_split": [
            "event_pieces",
            "find_movements",
            "MIN_MOVEMENT_SAMPLES",
            "movement_pieces",
            "NOISE_FACTOR",
            "split_movements",
        ],
        "_table": [
            "approaches",
            "FEATURE_COLUMNS",
            "participant_summary",
            "rest_speed",
            "run_lowpass",
            "segment",
            "select",
            "SPARC_PARAMS",
            "status_counts",
            "trial_events",
            "trial_features",
        ],
    },
)
