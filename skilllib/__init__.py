"""skilllib: smoothness-based prototypical task executions and their transfer to robot arms.

The companion library of the executable book reproducing Maldonado & Zetzsche (KI 2020). One module
per idea: :mod:`~skilllib.smoothness` (SPARC, LDLJ), :mod:`~skilllib.cohort` (the synthetic
experiment), :mod:`~skilllib.data` (the CSV format), :mod:`~skilllib.features` (segmentation and
per-trial features), :mod:`~skilllib.prototypes` (silhouettes, K-means prototypes),
:mod:`~skilllib.robots` and :mod:`~skilllib.transfer` (joint velocities on an arm),
:mod:`~skilllib.workspace` and :mod:`~skilllib.ik` (reach and inverse kinematics),
:mod:`~skilllib.dynamics`, :mod:`~skilllib.execution` and :mod:`~skilllib.feasibility` (accelerations,
torques, every limit, time scaling, the executed motion),
:mod:`~skilllib.figures` and :mod:`~skilllib.pipeline` (``python -m skilllib run``).

The robot names (``simple6``, ``get_robot``, ...) are loaded on first use, so that ``import skilllib``
does not pay for importing roboticstoolbox. The transfer itself is ``skilllib.transfer.transfer``.
"""
from __future__ import annotations

import importlib
from typing import Any

from .data import DataFormatError, read_recordings, write_recordings
from .features import segment, select, trial_features
from .prototypes import (
    PrototypeResult,
    SilhouetteSweep,
    bootstrap_stability,
    fit_prototypes,
    seed_stability,
    silhouette_sweep,
)
from .smoothness import (
    SPARC_PARAMS,
    SparcSpectrum,
    ldlj,
    ldlj_many,
    minimum_jerk_speed,
    sparc,
    sparc_many,
    sparc_spectrum,
)

_LAZY = {
    "simple6": "robots", "DEFAULT_POSE_DEG": "robots", "get_robot": "robots",
    "TransferResult": "transfer", "transfer_summary": "transfer",
    "time_scale_factor": "transfer", "apply_time_scale": "transfer", "EXP_TO_BASE": "transfer",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        module = importlib.import_module(f".{_LAZY[name]}", __name__)
        value = getattr(module, name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'skilllib' has no attribute {name!r}")


__all__ = [
    "sparc", "sparc_many", "sparc_spectrum", "SparcSpectrum", "ldlj", "ldlj_many", "SPARC_PARAMS",
    "minimum_jerk_speed", "read_recordings", "write_recordings", "DataFormatError", "trial_features",
    "select", "segment", "fit_prototypes", "silhouette_sweep", "PrototypeResult", "SilhouetteSweep",
    "seed_stability", "bootstrap_stability", *_LAZY,
]
