"""Figures of the recordings chapters: Winter's residual analysis and SPARC after a low-pass filter."""

from __future__ import annotations

from collections.abc import Mapping

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from ..features import NOISE_FIT_RANGE, ResidualAnalysis
from ._common import CLUSTER_COLORS
from ._style import SINGLE, book_figure, grid


@book_figure
def plot_residual_analysis(ra: ResidualAnalysis, fs: float, ax: plt.Axes | None = None) -> plt.Figure:
    """Winter's residual analysis: the RMS residual (mm) between raw and filtered positions against cut-off.

    The residual R(f) of every cut-off scanned (dots), the straight line fitted to its noise-only part
    (solid over the fitted range, dashed down to 0 Hz), its value at 0 Hz (the noise's RMS amplitude,
    dotted) and the cut-off chosen where R(f) first falls to that value (Winter 2009, sec. 2.2.4). The
    residual axis ends at four times the noise; residuals above it (the lowest cut-offs, which remove the
    movement itself) are drawn as triangles at its top, the first one labelled with its value.

    Parameters
    ----------
    ra : ResidualAnalysis
        The analysis, as :func:`skilllib.features.residual_analysis` returns it (cut-offs in Hz,
        residual and noise in m, slope in m/Hz).
    fs : float
        The sampling rate (Hz): the fitted range is a fraction of its Nyquist frequency.
    ax : matplotlib.axes.Axes or None
        The axes to draw into; None: a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; residual (mm) against the filter's cut-off frequency (Hz).
    """
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(SINGLE, 3.4), layout="constrained")
    mm = 1e3
    top = 4 * ra.noise_m * mm if ra.noise_m > 0 else float(np.max(ra.residual)) * mm * 1.05  # mm
    lo, hi = (r * fs / 2 for r in NOISE_FIT_RANGE)
    fitted = (ra.cutoffs >= lo) & (ra.cutoffs <= hi)
    r_mm = ra.residual * mm
    shown = r_mm <= top
    ax.plot(ra.cutoffs[shown], r_mm[shown], "o", ms=3, color=CLUSTER_COLORS[0], label="residual R(f)")
    if (~shown).any():  # the lowest cut-offs remove the movement itself: far above the noise
        ax.plot(ra.cutoffs[~shown], np.full((~shown).sum(), top), "^", ms=4, color=CLUSTER_COLORS[0], clip_on=False)
        first = int(np.flatnonzero(~shown)[0])
        ax.annotate(
            f"R({ra.cutoffs[first]:.0f} Hz) = {r_mm[first]:.1f} mm (above the scale)",
            (ra.cutoffs[first], top),
            xytext=(0.2, 0.9),
            textcoords="axes fraction",
            fontsize="small",
            va="center",
            arrowprops={"arrowstyle": "->", "color": "0.4", "lw": 0.8},
        )
    f_all = np.array([0.0, ra.cutoffs[-1]])
    ax.plot(f_all, (ra.noise_m + ra.slope * f_all) * mm, "--", color="0.4", lw=1)
    f_fit = ra.cutoffs[fitted][[0, -1]]
    ax.plot(f_fit, (ra.noise_m + ra.slope * f_fit) * mm, color="0.2", lw=2, label="line fitted to the noise")
    ax.axhline(ra.noise_m * mm, color="0.3", ls=":", lw=1)
    ax.text(
        ra.cutoffs[-1], ra.noise_m * mm, f"noise {ra.noise_m * mm:.2f} mm", ha="right", va="bottom", fontsize="small"
    )
    if ra.cutoff_hz is not None:
        ax.axvline(ra.cutoff_hz, color=CLUSTER_COLORS[3], lw=1.2, label=f"cut-off {ra.cutoff_hz:.1f} Hz")
    ax.set_xlim(0, ra.cutoffs[-1] * 1.02)
    ax.set_ylim(0, top)
    ax.set_xlabel("cut-off frequency of the low-pass filter (Hz)")
    ax.set_ylabel("RMS residual, raw - filtered (mm)")
    ax.legend(fontsize="small", loc="upper right")
    return fig


@book_figure
def plot_sparc_against_reference(
    features: Mapping[str, pd.DataFrame],
    reference: pd.DataFrame,
    *,
    xlabel: str = "SPARC, reference",
    ylabel: str = "SPARC",
) -> plt.Figure:
    """SPARC of each trial in one or more feature tables against the same trial's in a reference table.

    One panel per table, each point a trial valid (not ``invalid``) in both tables, matched by
    participant and trial; the diagonal is equality. Each panel's title gives its label, the number of
    trials drawn and Spearman's rank correlation of the two SPARC values.

    Parameters
    ----------
    features : mapping of str to pandas.DataFrame
        Label (text) -> a per-trial table as :func:`skilllib.features.trial_features` gives it
        (``participant``, ``trial``, ``status``, ``sparc`` dimensionless).
    reference : pandas.DataFrame
        The table to compare with, in the same layout (for instance the same movements without noise).
    xlabel, ylabel : str
        The axis labels (SPARC is dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; SPARC (dimensionless) against reference SPARC (dimensionless).
    """
    n = len(features)
    rows, cols, width = grid(n, 2, 4.5)
    fig, axes = plt.subplots(
        rows, cols, figsize=(width, 3.8 * rows), sharex=True, sharey=True, layout="constrained", squeeze=False
    )
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    for ax, (label, table) in zip(axes.flat, features.items()):
        both = table.merge(reference, on=["participant", "trial"], suffixes=("", "_ref"))
        both = both[(both["status"] != "invalid") & (both["status_ref"] != "invalid")]
        ax.scatter(both["sparc_ref"], both["sparc"], s=10, alpha=0.7, color=CLUSTER_COLORS[0])
        lims = [
            min(both["sparc_ref"].min(), both["sparc"].min()),
            max(both["sparc_ref"].max(), both["sparc"].max()),
        ]
        ax.plot(lims, lims, color="0.4", lw=1, ls=":")
        rho = both["sparc"].corr(both["sparc_ref"], method="spearman")
        ax.set_title(f"{label}: {len(both)} trials, rank correlation {rho:.2f}", fontsize=9)
        ax.set_xlabel(xlabel)
    for ax in axes[:, 0]:
        ax.set_ylabel(ylabel)
    return fig
