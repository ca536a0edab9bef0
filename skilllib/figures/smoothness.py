"""Figures of the SPARC chapter: speed profiles, normalised spectra and SPARC bands."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np

from ..smoothness import SPARC_PARAMS, SparcSpectrum, sparc_spectrum
from ._common import CLUSTER_COLORS


def plot_sparc_spectra(
    spectra: Mapping[str, SparcSpectrum], ax: plt.Axes | None = None, fmax: float | None = None
) -> plt.Figure:
    """Normalised Fourier magnitude spectra ``|V(f)| / V(0)`` against frequency (Hz): the band whose arc length
    SPARC measures drawn thick, the rest thin; the amplitude threshold (dashed), the maximum cut-off fc
    (dotted) and each adaptive cut-off (dot). Labels carry the SPARC values."""
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(5.5, 3.4))
    first = next(iter(spectra.values()))
    fmax = fmax if fmax is not None else 1.5 * max(first.fc, max(s.cutoff for s in spectra.values()))
    for i, (label, s) in enumerate(spectra.items()):
        color = CLUSTER_COLORS[i % len(CLUSTER_COLORS)]
        shown = s.f <= fmax
        ax.plot(s.f[shown], s.Mf[shown], color=color, lw=0.8, alpha=0.5)
        ax.plot(s.f_sel, s.Mf_sel, color=color, lw=2, label=f"{label}: SPARC {s.sparc:.3f}")
        ax.plot(s.cutoff, s.Mf_sel[-1], "o", color=color, ms=4)
    ax.axhline(first.amp_th, color="0.3", ls="--", lw=0.8)
    ax.text(fmax, first.amp_th, f"amp_th = {first.amp_th:g}", ha="right", va="bottom", fontsize="small")
    if first.fc <= fmax:
        ax.axvline(first.fc, color="0.3", ls=":", lw=1)
        ax.text(first.fc, 1.02, f"fc = {first.fc:g} Hz", ha="center", va="bottom", fontsize="small")
    ax.set_xlim(0, fmax)
    ax.set_ylim(0, 1.1)
    ax.set_xlabel("frequency f (Hz)")
    ax.set_ylabel(r"normalised magnitude $|V(f)|\,/\,V(0)$")
    ax.legend(
        fontsize="small",
        loc="upper right",
        bbox_to_anchor=(1, 0.93),
        facecolor="white",
        edgecolor="none",
        framealpha=0.9,
    )  # the box hides the fc line behind the labels
    return fig


def plot_speeds_and_spectra(
    speeds: Mapping[str, np.ndarray], fs: float, fmax: float | None = None, **sparc_params: float
) -> plt.Figure:
    """Speed profiles (m/s against s, sampled at ``fs`` Hz) beside their normalised spectra and SPARC
    bands (:func:`plot_sparc_spectra`); ``sparc_params`` default to ``SPARC_PARAMS``."""
    params = {**SPARC_PARAMS, **sparc_params}
    fig, (ax_v, ax_f) = plt.subplots(1, 2, figsize=(10, 3.4), layout="constrained")
    spectra = {}
    for i, (label, v) in enumerate(speeds.items()):
        v = np.asarray(v, dtype=float)
        ax_v.plot(np.arange(v.size) / fs, v, ".-", ms=2.5, lw=1, color=CLUSTER_COLORS[i % 10], label=label)
        spectra[label] = sparc_spectrum(v, fs, **params)
    ax_v.set_xlabel("time t (s)")
    ax_v.set_ylabel("speed v (m/s)")
    ax_v.set_ylim(bottom=0)
    plot_sparc_spectra(spectra, ax=ax_f, fmax=fmax)
    return fig


def plot_sparc_against(
    x: Sequence[float],
    curves: Mapping[str, Sequence[float]],
    xlabel: str,
    ylabel: str = "SPARC",
    ax: plt.Axes | None = None,
) -> plt.Figure:
    """One or more smoothness values against a parameter of the movement (e.g. delay, noise level)."""
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(5.5, 3.4))
    for i, (label, y) in enumerate(curves.items()):
        ax.plot(x, y, "o-", ms=3, color=CLUSTER_COLORS[i % 10], label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if len(curves) > 1:
        ax.legend(fontsize="small", frameon=False)
    return fig
