"""The figures of the pipeline; the chapters draw the same ones.

Every function takes data (arrays, DataFrames, result objects) and returns a matplotlib Figure;
:func:`save` writes it as PNG and SVG. Axes carry units. One submodule per chapter's idea:
``smoothness`` (SPARC), ``experiment`` (the data), ``clusters`` (prototypes), ``robot`` (transfer),
``dynamics`` (accelerations, torques, execution, time scales), ``recordings`` (noise and
filters), ``scale`` (time and memory against N), ``segmentation`` (every trial's segmentation, page by page),
``measures`` (clusterings on measures of corrections), ``measurement`` (SPARC's measurement spread),
``draws`` (the headline results over many draws of the cohort), ``limits`` (the robot verdicts against
the assumed limits). ``_style`` holds the book's figure style: every figure function draws in it, at
most :data:`WIDE` in wide with no text below :data:`MIN_FONT` pt (:func:`book_style` applies it globally).
This package may import the other skilllib modules; none of them imports it.
"""

from __future__ import annotations

import matplotlib.pyplot as plt

from ._common import CLUSTER_COLORS, save
from ._style import FULL_WIDTH, MIN_FONT, SINGLE, WIDE, book_style
from .clusters import (
    plot_cluster_participants,
    plot_clusters,
    plot_prototype_profiles,
    plot_silhouette_sweep,
    plot_silhouettes,
    plot_sparc_sensitivity,
    plot_stability,
)
from .draws import plot_draws
from .dynamics import (
    dynamics_figures,
    plot_executed_speed,
    plot_joint_accelerations,
    plot_joint_torques,
    plot_time_scales,
)
from .experiment import (
    MAX_FIGURE_PARTICIPANTS,
    PARTICIPANT_COLORS,
    few_participants,
    plot_contact_speeds,
    plot_estimates_vs_truth,
    plot_feature_overview,
    plot_feature_space,
    plot_participant_features,
    plot_segmentation,
    plot_sparc_vs_length,
    plot_trials_by_participant,
    segmentation_examples,
    threshold_bound,
    trials_window,
)
from .limits import plot_limit_sensitivity
from .measurement import plot_estimator_spread, plot_phase_clusters, plot_phase_spread, plot_spread_estimate
from .measures import plot_measure_clusters
from .recordings import plot_residual_analysis, plot_sparc_against_reference
from .robot import (
    JOINT_COLORS,
    plot_frame_mapping,
    plot_joint_velocities,
    plot_robot_joints,
    plot_robot_pose,
    plot_simple6_figure,
    plot_sparc_stretch,
    plot_start_poses,
    plot_time_scaled_plane,
)
from .scale import plot_scaling
from .segmentation import (
    MAX_SEGMENTATION_PAGES,
    MAX_SEGMENTATION_TRIALS,
    plot_segmentation_pages,
    save_page,
    segmentation_keys,
)
from .smoothness import (
    plot_padded_spectra,
    plot_short_segments,
    plot_sparc_against,
    plot_sparc_spectra,
    plot_spectra_side_by_side,
    plot_speed_profiles,
    plot_speeds_and_spectra,
)

__all__ = [
    "plt",
    "save",
    "book_style",
    "FULL_WIDTH",
    "WIDE",
    "SINGLE",
    "MIN_FONT",
    "CLUSTER_COLORS",
    "PARTICIPANT_COLORS",
    "JOINT_COLORS",
    "few_participants",
    "MAX_FIGURE_PARTICIPANTS",
    "plot_sparc_spectra",
    "plot_speed_profiles",
    "plot_spectra_side_by_side",
    "plot_speeds_and_spectra",
    "plot_sparc_against",
    "plot_padded_spectra",
    "plot_short_segments",
    "plot_trials_by_participant",
    "trials_window",
    "plot_segmentation",
    "segmentation_examples",
    "plot_segmentation_pages",
    "segmentation_keys",
    "MAX_SEGMENTATION_PAGES",
    "MAX_SEGMENTATION_TRIALS",
    "save_page",
    "plot_participant_features",
    "plot_contact_speeds",
    "plot_feature_space",
    "plot_feature_overview",
    "plot_estimates_vs_truth",
    "plot_sparc_vs_length",
    "plot_residual_analysis",
    "plot_sparc_against_reference",
    "threshold_bound",
    "plot_silhouette_sweep",
    "plot_silhouettes",
    "plot_clusters",
    "plot_prototype_profiles",
    "plot_stability",
    "plot_sparc_sensitivity",
    "plot_cluster_participants",
    "plot_robot_joints",
    "plot_robot_pose",
    "plot_simple6_figure",
    "plot_start_poses",
    "plot_joint_velocities",
    "plot_frame_mapping",
    "plot_sparc_stretch",
    "plot_time_scaled_plane",
    "plot_joint_accelerations",
    "plot_joint_torques",
    "plot_executed_speed",
    "plot_time_scales",
    "dynamics_figures",
    "plot_limit_sensitivity",
    "plot_draws",
    "plot_measure_clusters",
    "plot_scaling",
    "plot_phase_spread",
    "plot_spread_estimate",
    "plot_estimator_spread",
    "plot_phase_clusters",
]
