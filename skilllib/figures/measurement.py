"""Figures of how precisely SPARC is measured: the sampling phase, the estimate of it, the estimators, the
clusters under the phase (:mod:`skilllib.features._uncertainty`)."""

from __future__ import annotations

from collections.abc import Mapping

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from ..prototypes import PrototypeResult
from ._common import CLUSTER_COLORS
from ._style import WIDE, book_figure

_PHASE_COLORS = ("#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e")


def _values(table: pd.DataFrame) -> tuple[list[float], list[str]]:
    """The phases (or shifts) of a spread table and their columns, in order."""
    col = table.attrs.get("column", "sparc")
    shifts = list(table.attrs.get("shifts", ()))
    return shifts, [f"{col}_{d:g}" for d in shifts]


def _gaps(centres: pd.DataFrame) -> np.ndarray:
    """|SPARC difference| between centres neighbouring in PV (centres ordered by PV)."""
    return np.abs(np.diff(centres.sort_values("pv")["sparc"].to_numpy(dtype=float)))


@book_figure
def plot_phase_spread(spread: pd.DataFrame, centres: pd.DataFrame) -> plt.Figure:
    """SPARC of each trial at every sampling phase against its SPARC at the first, and the per-trial SDs
    beside the SPARC gaps between neighbouring cluster centres.

    Parameters
    ----------
    spread : pandas.DataFrame
        :func:`skilllib.features.phase_spread` (or :func:`skilllib.features.sparc_shift_spread`): one
        ``sparc_<phase>`` column per phase and ``sparc_sd`` (dimensionless).
    centres : pandas.DataFrame
        Cluster centres with ``pv`` (m/s) and ``sparc`` (dimensionless), as ``PrototypeResult.centres``.

    Returns
    -------
    matplotlib.figure.Figure
        Left: SPARC at the other phases (dimensionless) against SPARC at the first; right: histogram of
        the per-trial SD over the phases (dimensionless) with the centre gaps as vertical lines.
    """
    shifts, cols = _values(spread)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(WIDE, 4.2))
    x = spread[cols[0]].to_numpy(dtype=float)
    for j, (d, c) in enumerate(zip(shifts[1:], cols[1:]), start=1):
        ax.scatter(x, spread[c], s=7, alpha=0.55, color=_PHASE_COLORS[j % len(_PHASE_COLORS)], lw=0, label=f"{d:g}")
    lo = np.nanmin(spread[cols].to_numpy(dtype=float))
    hi = np.nanmax(spread[cols].to_numpy(dtype=float))
    ax.plot([lo, hi], [lo, hi], color="0.3", lw=0.8, ls="--", label="same value")
    ax.set_xlabel(f"SPARC, samples at phase {shifts[0]:g}")
    ax.set_ylabel("SPARC, samples at a later phase")
    ax.legend(title="phase (fraction of 1/fs)", fontsize=8, title_fontsize=8, loc="upper left")
    ax.set_title("the same movements, sampled later", fontsize=10)
    sd = spread["sparc_sd"].dropna().to_numpy(dtype=float)
    gaps = _gaps(centres)
    top = max(float(np.quantile(sd, 0.995)), float(gaps.max())) * 1.05
    bx.hist(np.clip(sd, 0, top), bins=np.linspace(0, top, 45), color="0.55", edgecolor="white", lw=0.4)
    for i, g in enumerate(gaps):
        bx.axvline(g, color=CLUSTER_COLORS[3], lw=1.2, label="SPARC gap of neighbouring centres" if i == 0 else None)
    bx.axvline(np.median(sd), color="k", lw=1.2, ls=":", label=f"median SD {np.median(sd):.3f}")
    bx.set_xlabel("SD of a trial's SPARC over the phases")
    bx.set_ylabel("trials")
    bx.set_xlim(0, top)
    bx.legend(fontsize=8, loc="upper right")
    bx.set_title("per-trial spread and the centres' gaps", fontsize=10)
    fig.tight_layout()
    return fig


@book_figure
def plot_spread_estimate(exact: pd.DataFrame, estimate: pd.DataFrame) -> plt.Figure:
    """The library's per-trial SPARC uncertainty (sub-sample shifts of the recording) against the exact
    phase spread of the same trials.

    Parameters
    ----------
    exact : pandas.DataFrame
        :func:`skilllib.features.phase_spread`: participant, trial, ``sparc_sd`` (dimensionless).
    estimate : pandas.DataFrame
        :func:`skilllib.features.sparc_shift_spread` of the reference phase's recordings: the same
        columns.

    Returns
    -------
    matplotlib.figure.Figure
        Estimated SD (dimensionless) against exact SD (dimensionless), both logarithmic, and the two
        distributions.
    """
    both = exact[["participant", "trial", "sparc_sd"]].merge(
        estimate[["participant", "trial", "sparc_sd"]], on=["participant", "trial"], suffixes=("_exact", "_est")
    )
    x, y = both["sparc_sd_exact"].to_numpy(dtype=float), both["sparc_sd_est"].to_numpy(dtype=float)
    floor = 1e-4
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(WIDE, 4.2))
    ax.scatter(np.maximum(x, floor), np.maximum(y, floor), s=7, alpha=0.5, color=CLUSTER_COLORS[0], lw=0)
    lim = [floor, max(x.max(), y.max()) * 1.3]
    ax.plot(lim, lim, color="0.3", lw=0.8, ls="--", label="estimate = exact")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(lim)
    ax.set_ylim(lim)
    ax.set_xlabel("exact SD over the sampling phase")
    ax.set_ylabel("estimated SD (spline, sub-sample shifts)")
    ax.legend(fontsize=8, loc="upper left")
    ax.set_title(f"per trial (values below {floor:g} drawn at it)", fontsize=10)
    bins = np.logspace(np.log10(floor), np.log10(lim[1]), 40)
    bx.hist(np.maximum(x, floor), bins=bins, histtype="step", lw=1.5, color="k", label="exact")
    bx.hist(np.maximum(y, floor), bins=bins, histtype="step", lw=1.5, color=CLUSTER_COLORS[0], label="estimate")
    bx.set_xscale("log")
    bx.set_xlabel("SD of a trial's SPARC")
    bx.set_ylabel("trials")
    bx.legend(fontsize=8)
    bx.set_title("the two distributions", fontsize=10)
    fig.tight_layout()
    return fig


@book_figure
def plot_estimator_spread(table: pd.DataFrame) -> plt.Figure:
    """SPARC with a plain central difference of the positions against SPARC with the book's speed.

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`skilllib.features.sparc_by_estimator`: ``sparc``, ``sparc_gradient``,
        ``sparc_gradient_trial`` (dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        One panel per central difference: its SPARC (dimensionless) against the book's.
    """
    fig, axes = plt.subplots(1, 2, figsize=(WIDE, 4.2), sharex=True, sharey=True)
    x = table["sparc"].to_numpy(dtype=float)
    titles = {
        "sparc_gradient": "numpy.gradient of the approach\n(2-point backward difference at the last sample)",
        "sparc_gradient_trial": "numpy.gradient of the whole trial\n(the last sample's difference spans contact)",
    }
    lo, hi = (
        np.nanmin(table[list(titles) + ["sparc"]].to_numpy()),
        np.nanmax(table[list(titles) + ["sparc"]].to_numpy()),
    )
    for ax, (col, title) in zip(axes, titles.items()):
        y = table[col].to_numpy(dtype=float)
        r = np.corrcoef(x, y)[0, 1]
        ax.scatter(x, y, s=7, alpha=0.5, color=CLUSTER_COLORS[1], lw=0)
        ax.plot([lo, hi], [lo, hi], color="0.3", lw=0.8, ls="--")
        ax.set_title(f"{title}\nr = {r:.3f}, SD of the difference {np.std(y - x):.3f}", fontsize=9)
        ax.set_xlabel("SPARC, the book's speed (approach only, 3-point)")
    axes[0].set_ylabel("SPARC, central difference")
    fig.tight_layout()
    return fig


@book_figure
def plot_phase_clusters(fits: Mapping[float, PrototypeResult]) -> plt.Figure:
    """The K-means centres and prototypes of the same movements sampled at several phases.

    Parameters
    ----------
    fits : mapping of float to PrototypeResult
        Phase (fraction of a sample interval, dimensionless) -> the fit of that phase's selected trials
        (:func:`skilllib.prototypes.fit_prototypes`; PV m/s, SPARC dimensionless). The first is drawn
        with its trials.

    Returns
    -------
    matplotlib.figure.Figure
        SPARC (dimensionless) against PV (m/s): the first fit's trials by cluster, every fit's centres
        (crosses) and prototypes (circles), one colour per phase.
    """
    phases = list(fits)
    ref = fits[phases[0]]
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for c in range(ref.k):
        d = ref.data[ref.labels == c]
        ax.scatter(d["pv"], d["sparc"], s=6, alpha=0.25, color=CLUSTER_COLORS[c % len(CLUSTER_COLORS)], lw=0)
    for j, ph in enumerate(phases):
        f = fits[ph]
        col = _PHASE_COLORS[j % len(_PHASE_COLORS)]
        ax.scatter(
            f.centres["pv"], f.centres["sparc"], marker="x", s=60, color=col, lw=1.8, label=f"centres, phase {ph:g}"
        )
        ax.scatter(
            f.prototypes["pv"],
            f.prototypes["sparc"],
            marker="o",
            s=70,
            facecolor="none",
            edgecolor=col,
            lw=1.4,
            label=f"prototypes, phase {ph:g}",
        )
    ax.set_xlabel("peak speed PV (m/s)")
    ax.set_ylabel("SPARC")
    ax.legend(fontsize="small", ncol=2, loc="lower right")
    ax.set_title(
        f"trials (phase {phases[0]:g}) by cluster; centres and prototypes at every phase (k = {ref.k})", fontsize=10
    )
    fig.tight_layout()
    return fig
