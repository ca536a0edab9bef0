"""skilllib: smoothness-based prototypical task executions and their transfer to robot arms.

The companion library of the executable book reproducing Maldonado & Zetzsche (KI 2020). One
sub-package per step of the paper's pipeline, each importing only those above it in this list:

* :mod:`skilllib.smoothness`: SPARC and LDLJ (the paper's Eq. 1);
* :mod:`skilllib.recordings`: every input (CSV, Parquet, C3D, TRC, folders) as one validated
  :class:`~skilllib.recordings.Recordings`;
* :mod:`skilllib.features`: filtering, onset and contact, the segment, the per-trial features, selection;
* :mod:`skilllib.prototypes`: silhouettes, K-means prototypes, stability, sensitivity, participants;
* :mod:`skilllib.robot`: arms and their limits, reach, IK, the velocity transfer, dynamics, execution;
* :mod:`skilllib.cohort`: the book's synthetic cohort (generative model, calibration);
* :mod:`skilllib.figures`: the figures of the pipeline and of the chapters;
* :mod:`skilllib.pipeline`: :func:`~skilllib.pipeline.run` (``python -m skilllib run``), results.json,
  the output folder;

and :mod:`skilllib.datasets`, the data shipped with the package. ``import skilllib as sk`` is the
chapters' front door: ``sk.sparc``, ``sk.load_recordings``, ``sk.trial_features``, ... Every name is
loaded on first use (``lazy_loader``), so that ``import skilllib`` and ``python -m skilllib --help`` do
not pay for importing pandas, scikit-learn, roboticstoolbox or matplotlib.
"""

import lazy_loader as _lazy

__version__ = "0.2.0"

__getattr__, __dir__, _names = _lazy.attach(
    __name__,
    submodules=[
        "smoothness",
        "recordings",
        "features",
        "prototypes",
        "robot",
        "cohort",
        "figures",
        "pipeline",
        "datasets",
    ],
    submod_attrs={
        "smoothness": [
            "sparc",
            "sparc_many",
            "sparc_spectrum",
            "sparc_bands",
            "SparcSpectrum",
            "ldlj",
            "ldlj_many",
            "SPARC_PARAMS",
            "minimum_jerk_speed",
        ],
        "recordings": ["Recordings", "load_recordings", "read_recordings", "write_recordings", "DataFormatError"],
        "features": ["trial_features", "select", "segment"],
        "prototypes": [
            "fit_prototypes",
            "silhouette_sweep",
            "PrototypeResult",
            "SilhouetteSweep",
            "seed_stability",
            "bootstrap_stability",
        ],
        "robot": [
            "simple6",
            "DEFAULT_POSE_DEG",
            "get_robot",
            "transfer",
            "TransferResult",
            "transfer_summary",
            "time_scale_factor",
            "apply_time_scale",
            "EXP_TO_BASE",
        ],
        "pipeline": ["run"],
    },
)
__all__ = ["__version__", *_names]
