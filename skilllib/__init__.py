"""skilllib: smoothness-based prototypical task executions and their transfer to robot arms.

The companion library of the executable book reproducing Maldonado & Zetzsche (KI 2020). One module
per idea: :mod:`~skilllib.smoothness` (SPARC, LDLJ), :mod:`~skilllib.cohort` (the synthetic
experiment), :mod:`~skilllib.data` (the recordings format), :mod:`~skilllib.features` (segmentation and
per-trial features), :mod:`~skilllib.prototypes` (silhouettes, K-means prototypes),
:mod:`~skilllib.robots` and :mod:`~skilllib.transfer` (joint velocities on an arm),
:mod:`~skilllib.workspace` and :mod:`~skilllib.ik` (reach and inverse kinematics),
:mod:`~skilllib.dynamics`, :mod:`~skilllib.execution` and :mod:`~skilllib.feasibility` (accelerations,
torques, every limit, time scaling, the executed motion),
:mod:`~skilllib.figures` and :mod:`~skilllib.pipeline` (``python -m skilllib run``); at scale
:mod:`~skilllib.batch` (the features of many trials at once), :mod:`~skilllib.silhouette` (exact or
estimated), :mod:`~skilllib.columnar` (Parquet), :mod:`~skilllib.trialtable` (trials.parquet) and
:mod:`~skilllib.partitions` (a Dask cluster).

Every name is loaded on first use (PEP 562), so that ``import skilllib`` and ``python -m skilllib
--help`` do not pay for importing pandas, scikit-learn, roboticstoolbox or matplotlib.
"""
from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.2.0"

#: public name -> the submodule that defines it
_LAZY = {
    **dict.fromkeys(["sparc", "sparc_many", "sparc_spectrum", "sparc_bands", "SparcSpectrum", "ldlj",
                     "ldlj_many", "SPARC_PARAMS", "minimum_jerk_speed"], "smoothness"),
    **dict.fromkeys(["read_recordings", "write_recordings", "DataFormatError"], "data"),
    **dict.fromkeys(["trial_features", "select", "segment"], "features"),
    **dict.fromkeys(["fit_prototypes", "silhouette_sweep", "PrototypeResult", "SilhouetteSweep",
                     "seed_stability", "bootstrap_stability"], "prototypes"),
    **dict.fromkeys(["simple6", "DEFAULT_POSE_DEG", "get_robot"], "robots"),
    **dict.fromkeys(["TransferResult", "transfer_summary", "time_scale_factor", "apply_time_scale",
                     "EXP_TO_BASE"], "transfer"),
}

#: the submodules, importable as attributes (``skilllib.cohort``) after ``import skilllib``
_SUBMODULES = {"smoothness", "cohort", "calibration", "data", "datasets", "duration", "features", "filtering",
               "participants", "pipeline", "prototypes", "robots", "sensitivity", "transfer", "figures",
               "batch", "checks", "columnar", "kinematics", "partitions", "ragged", "silhouette", "trialtable"}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    if name in _SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'skilllib' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY, *_SUBMODULES})


__all__ = ["__version__", *_LAZY]
