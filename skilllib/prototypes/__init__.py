"""Prototypical executions: silhouette analysis, K-means prototypes, and how far to trust them.

:func:`silhouette_sweep` and :func:`fit_prototypes` are the paper's Sect. 6 (exact or estimated
silhouettes in ``_silhouette``); :func:`seed_stability` and :func:`bootstrap_stability` the clustering's
stability; :func:`sparc_sensitivity` the procedure under other SPARC settings; the clusters against the
participants (``_participants``) and SPARC against the segment's length (``_segment_length``).
"""

import lazy_loader as _lazy

__getattr__, __dir__, __all__ = _lazy.attach(
    __name__,
    submod_attrs={
        "_settings": ["DEFAULT_K"],
        "_json": ["json_value"],
        "_kmeans": [
            "bootstrap_stability",
            "feature_frame",
            "fit_prototypes",
            "PrototypeResult",
            "results_section",
            "seed_stability",
            "silhouette_sweep",
            "SilhouetteSweep",
        ],
        "_participants": [
            "between_participant_share",
            "cluster_composition",
            "cluster_participant_table",
            "participant_dependence",
            "participant_spread",
        ],
        "_segment_length": [
            "adjusted_sparc",
            "LENGTH_EDGES",
            "partial_correlation",
            "sparc_by_length",
            "variance_explained",
            "with_covariates",
        ],
        "_sensitivity": ["CHANGE_TOL", "complete_params", "setting_label", "sparc_sensitivity", "SparcSensitivity"],
        "_silhouette": ["failing_clusters", "is_valid", "SILHOUETTE_EXACT_MAX"],
    },
)
