"""Clusterings on the paper's (PV, SPARC) and on (PV, another measure) side by side, corrected trials marked."""

from __future__ import annotations

from collections.abc import Mapping

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.lines import Line2D
from numpy.typing import ArrayLike

from ..features import FEATURE_UNITS
from ..prototypes import PrototypeResult
from ._common import CLUSTER_COLORS
from ._style import book_figure, grid


def _axis_label(name: str) -> str:
    label, unit = FEATURE_UNITS.get(name, (name.replace("_", " "), ""))
    return f"{label} ({unit})" if unit else f"{label} (dimensionless)"


@book_figure
def plot_measure_clusters(
    fits: Mapping[str, PrototypeResult],
    corrected: ArrayLike,
    labels: Mapping[str, str] | None = None,
) -> plt.Figure:
    """One panel per clustering: the trials in its two features, coloured by cluster, corrected trials filled.

    Each panel plots the second feature of the fit against the first (PV), one colour per cluster
    (numbered by centre PV); a trial the truth marks as corrected is a filled dot, an uncorrected one an
    open ring. Each centre (black cross) is labelled with its cluster's share of corrected trials.

    Parameters
    ----------
    fits : mapping of str to PrototypeResult
        Panel title (text) to a clustering of :func:`skilllib.prototypes.fit_prototypes` of the same trials
        in the same order (first feature PV in m/s; the second in its unit, e.g. SPARC or LDLJ,
        dimensionless).
    corrected : array_like of bool
        Per trial, in the fits' row order, whether it has a corrective submovement (the generator's truth;
        dimensionless flags).
    labels : mapping of str to str or None
        Axis label (text, with its unit) per feature name; None or a missing name: the feature's name and
        unit from :data:`skilllib.features.FEATURE_UNITS`.

    Returns
    -------
    matplotlib.figure.Figure
        The figure: one panel per fit, the second feature against PV (m/s).
    """
    corrected = np.asarray(corrected, dtype=bool)
    labels = dict(labels or {})
    rows, cols, width = grid(len(fits), 3, 3.0 if len(fits) > 2 else 4.5)
    fig, axes = plt.subplots(rows, cols, figsize=(width, 3.9 * rows + 0.4), squeeze=False)
    for ax in axes.flat[len(fits) :]:
        ax.set_visible(False)
    for ax, (title, fit) in zip(axes.flat, fits.items()):
        d = fit.data
        if len(d) != corrected.size:
            raise ValueError(f"{title!r}: {len(d)} trials clustered but {corrected.size} corrected flags")
        fx, fy = tuple(fit.features)[:2]
        lab = d["cluster"].to_numpy()
        for c in range(fit.k):
            color = CLUSTER_COLORS[c % len(CLUSTER_COLORS)]
            for done, face in ((False, "none"), (True, color)):
                m = (lab == c) & (corrected == done)
                ax.scatter(d.loc[m, fx], d.loc[m, fy], s=14, facecolor=face, edgecolor=color, lw=0.7, alpha=0.7)
            share = corrected[lab == c].mean()
            cx, cy = fit.centres.loc[c, fx], fit.centres.loc[c, fy]
            ax.scatter(cx, cy, marker="X", s=80, color="k", edgecolor="white", lw=0.8, zorder=3, gid="centre")
            ax.annotate(
                f"{share:.0%}",
                (cx, cy),
                xytext=(5, 5),
                textcoords="offset points",
                fontsize=9,
                fontweight="bold",
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.8},
                zorder=4,
            )
        ax.set_xlabel(labels.get(fx, _axis_label(fx)))
        ax.set_ylabel(labels.get(fy, _axis_label(fy)))
        ax.set_title(f"{title}\nsilhouette {fit.silhouette:.2f}", fontsize=10)
    keys = [
        Line2D([], [], ls="", marker="o", mfc="0.4", mec="0.4", label="corrected (truth)"),
        Line2D([], [], ls="", marker="o", mfc="none", mec="0.4", label="not corrected"),
        Line2D([], [], ls="", marker="X", mfc="k", mec="white", ms=9, label="centre: share corrected"),
    ]
    fig.legend(handles=keys, loc="lower center", ncol=3, frameon=False, bbox_to_anchor=(0.5, -0.02))
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    return fig
