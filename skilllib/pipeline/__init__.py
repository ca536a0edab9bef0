"""The whole pipeline on one input: :func:`run` (``python -m skilllib run``), results.json and the output folder.

:func:`run` reads, segments, selects, clusters and transfers (``_run``); the per-trial table
(``_trials_file``), the output folder that never mixes runs (``_output``), the printed summary
(``_summary``) and the command line (``_cli``, :func:`main`).
"""

import lazy_loader as _lazy

__getattr__, __dir__, __all__ = _lazy.attach(
    __name__,
    submod_attrs={
        "_analysis": ["Analysis", "analyse"],
        "_cli": ["main", "run_command"],
        "_output": ["check_output", "MANIFEST", "output_folder", "OutputError", "RUN_FILES"],
        "_run": ["DEFAULT_DATA", "OptionError", "run"],
        "_summary": ["reason_kind", "summary_lines"],
        "_trials_file": ["read_trials", "TRIALS_IN_JSON_MAX"],
    },
)
