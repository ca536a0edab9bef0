"""Figures of the SPARC chapter: speed profiles, normalised spectra and SPARC bands."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np

from ..smoothness import SPARC_PARAMS, SparcBands, SparcSpectrum, sparc_spectrum
from ._common import CLUSTER_COLORS
from ._style import SINGLE, WIDE, book_figure


@book_figure
def plot_sparc_spectra(
    spectra: Mapping[str, SparcSpectrum], ax: plt.Axes | None = None, fmax: float | None = None
) -> plt.Figure:
    """Normalised Fourier magnitude spectra ``|V(f)| / V(0)`` against frequency (Hz).

    The band whose arc length SPARC measures drawn thick, the rest thin; the amplitude threshold (dashed),
    the maximum cut-off fc (dotted) and each adaptive cut-off (dot). Labels carry the SPARC values.

    Parameters
    ----------
    spectra : mapping of str to SparcSpectrum
        Label (text) -> the :func:`skilllib.smoothness.sparc_spectrum` of a profile (frequencies in Hz).
    ax : matplotlib.axes.Axes or None
        The axes to draw into; None: a new figure.
    fmax : float or None
        Highest frequency shown (Hz); None: 1.5 times the largest of fc and the cut-offs.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; magnitude (dimensionless) against frequency (Hz).
    """
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(SINGLE, 3.6))
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


@book_figure
def plot_speeds_and_spectra(
    speeds: Mapping[str, np.ndarray], fs: float, fmax: float | None = None, **sparc_params: float
) -> plt.Figure:
    r"""Speed profiles beside their normalised spectra and SPARC bands (:func:`plot_sparc_spectra`).

    Speeds in m/s against time in s, sampled at ``fs`` Hz; ``sparc_params`` default to ``SPARC_PARAMS``.

    Parameters
    ----------
    speeds : mapping of str to numpy.ndarray
        Label (text) -> speed profile (m/s).
    fs : float
        The sampling rate (Hz).
    fmax : float or None
        Highest frequency shown (Hz); None: as :func:`plot_sparc_spectra`.
    \*\*sparc_params : float
        SPARC's parameters ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; speed (m/s) against time (s), and the spectra against frequency (Hz).
    """
    params = {**SPARC_PARAMS, **sparc_params}
    fig, (ax_v, ax_f) = plt.subplots(1, 2, figsize=(WIDE, 3.4), layout="constrained")
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


@book_figure
def plot_sparc_against(
    x: Sequence[float],
    curves: Mapping[str, Sequence[float]],
    xlabel: str,
    ylabel: str = "SPARC",
    ax: plt.Axes | None = None,
) -> plt.Figure:
    """One or more smoothness values against a parameter of the movement (e.g. delay, noise level).

    Parameters
    ----------
    x : sequence of float
        The parameter's values (in the unit ``xlabel`` names, e.g. s).
    curves : mapping of str to sequence of float
        Label (text) -> the smoothness value at each ``x`` (dimensionless, e.g. SPARC).
    xlabel : str
        The x axis label, with its unit (text).
    ylabel : str
        The y axis label (text).
    ax : matplotlib.axes.Axes or None
        The axes to draw into; None: a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; the curves against ``x``.
    """
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(SINGLE, 3.6))
    for i, (label, y) in enumerate(curves.items()):
        ax.plot(x, y, "o-", ms=3, color=CLUSTER_COLORS[i % 10], label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if len(curves) > 1:
        ax.legend(fontsize="small", frameon=False)
    return fig


@book_figure
def plot_padded_spectra(
    speed: np.ndarray, fs: float, padlevels: Sequence[int] = (0, 2, 4), fmax: float = 3.0
) -> plt.Figure:
    """The normalised spectrum of one speed profile on the FFT grids of several zero paddings.

    Parameters
    ----------
    speed : numpy.ndarray
        Speed samples (m/s).
    fs : float
        Sampling rate (Hz).
    padlevels : sequence of int
        Zero paddings, ``nfft = 2**(ceil(log2 N) + padlevel)`` (dimensionless).
    fmax : float
        Highest frequency shown (Hz).

    Returns
    -------
    matplotlib.figure.Figure
        The band of each grid as the polygon through its bins (normalised magnitude against frequency in
        Hz), labelled with its nfft and SPARC.
    """
    fig, ax = plt.subplots(figsize=(SINGLE, 3.4))
    for p in padlevels:
        s = sparc_spectrum(speed, fs, padlevel=p)
        label = f"padlevel {p}: nfft {s.nfft}, SPARC {s.sparc:.3f}"
        ax.plot(s.f_sel, s.Mf_sel, ".-", ms=4, lw=1, label=label)
    ax.set_xlim(0, fmax)
    ax.set_xlabel("frequency f (Hz)")
    ax.set_ylabel(r"normalised magnitude $|V(f)|\,/\,V(0)$")
    ax.legend(frameon=False)
    return fig


@book_figure
def plot_short_segments(
    n: Sequence[int], bands: Mapping[tuple[float, float], SparcBands], amp_th: float = SPARC_PARAMS["amp_th"]
) -> plt.Figure:
    """SPARC and the end of its band against the length of segments of one shape.

    Parameters
    ----------
    n : sequence of int
        Segment lengths (samples at 60 Hz).
    bands : mapping
        ``{(contact_ratio, fc): SparcBands}``, the :func:`skilllib.sparc_bands` of the segments at each
        ``n``, for a contact at ``contact_ratio`` of the peak speed (a fraction) and a maximum cut-off
        ``fc`` (Hz). One colour per ratio; the highest fc solid, the next dashed, dash-dotted, dotted.
    amp_th : float
        The amplitude threshold the bands used, a fraction of the peak magnitude (dimensionless), for
        the bound of :func:`threshold_bound` (dotted).

    Returns
    -------
    matplotlib.figure.Figure
        Left, SPARC (dimensionless) against n; right, the band's last frequency (Hz). Filled markers where
        the threshold ended the band, open markers where fc did.
    """
    from .experiment import threshold_bound  # the bound the cohort's figure draws too

    n = np.asarray(n)
    ratios = list(dict.fromkeys(r for r, _ in bands))
    fcs = sorted({fc for _, fc in bands}, reverse=True)
    styles = ["-", "--", "-.", ":"]
    fig, (ax, ax_end) = plt.subplots(1, 2, figsize=(WIDE, 4.2), layout="constrained")
    for (r, fc), b in bands.items():
        color, ls = f"C{ratios.index(r) % 10}", styles[fcs.index(fc) % len(styles)]
        for a, y in ((ax, np.asarray(b.sparc)), (ax_end, np.asarray(b.band_end_hz))):
            capped = np.asarray(b.capped, dtype=bool)
            a.plot(n, y, ls, color=color, lw=1, label=f"cut at {r:.0%}, fc = {fc:g} Hz")
            a.scatter(n[~capped], y[~capped], s=9, color=color)
            a.scatter(n[capped], y[capped], s=12, facecolor="white", edgecolor=color, zorder=3)
    ax.axhline(threshold_bound(amp_th), color="0.3", ls=":", lw=1)
    ax.set_xlabel("segment length n (samples at 60 Hz)")
    ax.set_ylabel("SPARC")
    ax_end.set_xlabel("segment length n (samples at 60 Hz)")
    ax_end.set_ylabel("band end (Hz)")
    handles, labels = ax_end.get_legend_handles_labels()  # below the panels: inside, it would hide lines
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize="small", frameon=False)
    return fig


@book_figure
def plot_speed_profiles(speeds: Mapping[str, np.ndarray], fs: float, ax: plt.Axes | None = None) -> plt.Figure:
    """Speed profiles against time, one line of dots per profile (one dot per sample).

    Parameters
    ----------
    speeds : mapping of str to numpy.ndarray
        Label (text) -> speed profile (m/s).
    fs : float
        The sampling rate (Hz).
    ax : matplotlib.axes.Axes or None
        The axes to draw into; None: a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; speed (m/s, from 0 to 1.15 times the highest peak) against time (s).
    """
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(SINGLE, 3.4), layout="constrained")
    top = 0.0
    for label, v in speeds.items():
        v = np.asarray(v, dtype=float)
        ax.plot(np.arange(v.size) / fs, v, ".-", ms=3, label=label)
        top = max(top, float(np.nanmax(v)))
    ax.set(xlabel="time t (s)", ylabel="speed v (m/s)", ylim=(0, 1.15 * top))
    ax.legend(frameon=False, loc="upper right")
    return fig


@book_figure
def plot_spectra_side_by_side(spectra: Mapping[str, SparcSpectrum], fmax: float | None = None) -> plt.Figure:
    """Each spectrum in its own panel, side by side on a shared magnitude axis (:func:`plot_sparc_spectra`).

    Parameters
    ----------
    spectra : mapping of str to SparcSpectrum
        Label (text) -> the :func:`skilllib.smoothness.sparc_spectrum` of a profile (frequencies in Hz).
    fmax : float or None
        Highest frequency shown (Hz); None: as :func:`plot_sparc_spectra`.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per spectrum, magnitude (dimensionless) against frequency (Hz).
    """
    fig, axes = plt.subplots(1, len(spectra), figsize=(WIDE, 3.4), sharey=True, layout="constrained", squeeze=False)
    for ax, (label, s) in zip(axes.flat, spectra.items()):
        plot_sparc_spectra({label: s}, ax=ax, fmax=fmax)
    for ax in axes.flat[1:]:
        ax.set_ylabel("")
    return fig
