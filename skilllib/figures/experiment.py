"""Figures of the experiment and its data: trajectories, segmentation, per-participant features."""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.collections import LineCollection

from ..features import CONTACT_WINDOW, ONSET_SPEED, velocity
from ..recordings import Recordings, sort_ids
from ..smoothness import DEFAULT_AMP_TH
from ._style import SINGLE, WIDE, book_figure

#: Colours of the participants (in sorted participant order): tab10 with its grey replaced by black,
#: because grey marks excluded trials.
PARTICIPANT_COLORS = tuple((0.0, 0.0, 0.0) if i == 7 else c for i, c in enumerate(plt.get_cmap("tab10").colors))


def _plabel(p: Any) -> str:
    """Short label of participant ``p``: "P3" for an id of digits, the id itself otherwise ("P03", "anna",
    "007": a leading zero is kept as written)."""
    s = str(p)
    return f"P{s}" if s.isdigit() and not s.startswith("0") else s


def _pcolor(participants: list, p) -> tuple[float, float, float]:
    return PARTICIPANT_COLORS[list(participants).index(p) % len(PARTICIPANT_COLORS)]


def _approach(rec: Recordings, p, tr, t_end: float | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """t (s), y (m) of the whole trial, speed (m/s) before the end (as the features), the end's index: the
    first contact sample, or the sample at ``t_end`` (s; the feature table's ``t_contact``, the end of any
    rule) when given; the speed is then differentiated over the whole trial."""
    d = rec.trial(p, tr)
    if t_end is None or not np.isfinite(t_end):
        c = int(np.flatnonzero(d.contact)[0])
        return d.t, d.pos[:, 1], np.linalg.norm(velocity(d.pos[:c], rec.fs), axis=1), c
    c = int(np.argmin(np.abs(d.t - t_end)))
    return d.t, d.pos[:, 1], np.linalg.norm(velocity(d.pos, rec.fs), axis=1)[:c], c


#: Participants the per-participant figures of a run draw at most (one panel or box each).
MAX_FIGURE_PARTICIPANTS = 12


def few_participants(features: pd.DataFrame, most: int = MAX_FIGURE_PARTICIPANTS) -> tuple[pd.DataFrame, str]:
    """The rows of the first ``most`` participants (natural order of their ids) and a note saying so.

    The note is "" when all are kept: a corpus of a thousand participants would give a thousand panels.

    Parameters
    ----------
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (pv and contact_speed in m/s,
        duration in s, sparc dimensionless).
    most : int
        The most participants kept (dimensionless).

    Returns
    -------
    rows : pandas.DataFrame
        The rows of the kept participants (same columns and units).
    note : str
        What was left out, or "" (text).
    """
    parts = sort_ids(features["participant"].unique())
    if len(parts) <= most:
        return features, ""
    kept = features[features["participant"].isin(parts[:most])]
    return kept, f"the first {most} of {len(parts)} participants (by id)"


#: s, shown before the earliest onset by :func:`plot_trials_by_participant` (the rest before the movement)
ONSET_MARGIN_S = 0.2
#: s, shown after contact at most by :func:`plot_trials_by_participant` (the hand rests on the target)
AFTER_CONTACT_S = 0.3


def trials_window(
    recordings: Recordings, features: pd.DataFrame, margin: float = ONSET_MARGIN_S
) -> tuple[float, float]:
    """The span of time from contact that shows every valid trial's onset: the figure's default window.

    From the earliest onset over the valid trials of ``features`` less ``margin``, to the latest end of
    their recordings after contact, at most :data:`AFTER_CONTACT_S`.

    Parameters
    ----------
    recordings : Recordings
        The recordings (t in s).
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (``t_onset`` and ``t_contact`` in s).
    margin : float
        Time shown before the earliest onset (s).

    Returns
    -------
    tuple of float
        The window's start and end relative to contact (s); (-0.9, 0.3) when no trial is valid.
    """
    f = features[features["status"] != "invalid"]
    lead = (f["t_onset"].astype(float) - f["t_contact"].astype(float)).to_numpy()
    lead = lead[np.isfinite(lead)]
    if not lead.size:
        return (-0.9, AFTER_CONTACT_S)
    ends = [float(recordings.trial(p, tr).t[-1]) for p, tr in zip(f["participant"], f["trial"])]
    after = float(np.nanmax(np.asarray(ends) - f["t_contact"].astype(float).to_numpy()))
    return (float(lead.min()) - margin, float(np.clip(after, 0.0, AFTER_CONTACT_S)))


@book_figure
def plot_trials_by_participant(
    recordings: Recordings, features: pd.DataFrame, window: tuple[float, float] | None = None, *, end: str = "contact"
) -> plt.Figure:
    """The paper's Fig. 1b redrawn: height and speed of every valid trial against time from contact.

    Vertical position y (m) and speed (m/s, approach only) against time from contact (s), one column per
    participant (two rows of participants from three participants on, one row for one or two). Selected
    trials in the participant's colour, excluded ones in grey; each trial's onset a black dot on its speed.
    Every column has its time axis, whatever the number of participants.

    Parameters
    ----------
    recordings : Recordings
        The recordings (t in s, positions in m).
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (pv and contact_speed in m/s,
        duration in s, sparc dimensionless; ``t_onset``, ``t_contact`` in s).
    window : tuple of float or None
        The time span shown, relative to contact (s); None: :func:`trials_window`, from the earliest onset
        (less 0.2 s) to the end of the recordings (at most 0.3 s after contact).
    end : str
        What ends the segments (text): ``"contact"`` (the paper: speed differentiated before the first
        contact sample), or the word of another end rule (``"offset"``, ...): the time axis then counts
        from each trial's end sample (``t_contact``) and the speed is the whole trial's.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; y (m) and speed (m/s) against time (s).
    """
    f = features[features["status"] != "invalid"]
    if window is None:
        window = trials_window(recordings, f)
    parts = sort_ids(f["participant"].unique())
    prow = 1 if len(parts) <= 2 else 2  # rows of participants
    ncol = max(1, int(np.ceil(len(parts) / prow)))
    fig, axs = plt.subplots(
        2 * prow,
        ncol,
        figsize=(min(WIDE, max(1.8 * ncol, 3.2)), 3.6 * prow + 0.2),
        sharex=True,
        sharey="row",
        squeeze=False,
    )
    for i, p in enumerate(parts):
        ay, av = axs[2 * (i // ncol), i % ncol], axs[2 * (i // ncol) + 1, i % ncol]
        lines = {"y": {True: [], False: []}, "v": {True: [], False: []}}
        onsets = []
        g = f.loc[f["participant"] == p]
        for tr, status, t_on, t_end in g[["trial", "status", "t_onset", "t_contact"]].itertuples(index=False):
            t, y, v, c = _approach(recordings, p, tr, None if end == "contact" else float(t_end))
            tt = t - t[c]
            keep = (tt >= window[0]) & (tt <= window[1])
            sel = status == "selected"
            lines["y"][sel].append(np.column_stack([tt[keep], y[keep]]))
            kv = keep[:c]
            lines["v"][sel].append(np.column_stack([tt[:c][kv], v[kv]]))
            o = int(np.argmin(np.abs(t[:c] - t_on))) if pd.notna(t_on) else None
            if o is not None and window[0] <= tt[o] <= window[1]:
                onsets.append((tt[o], v[o]))
        color = _pcolor(parts, p)
        for ax, key in ((ay, "y"), (av, "v")):
            ax.add_collection(LineCollection(lines[key][False], colors="0.75", lw=0.4))
            ax.add_collection(LineCollection(lines[key][True], colors=[color], lw=0.5, alpha=0.6))
            ax.autoscale_view()
            ax.axvline(0, color="k", lw=0.5, ls=":")
        if onsets:
            av.plot(*np.array(onsets).T, "o", ms=1.5, color="k", alpha=0.5, ls="none", zorder=3, label="onset")
        ay.set_title(f"participant {p}", fontsize=9)
    for r in range(1, 2 * prow, 2):
        axs[r, 0].set_ylim(0, None)
    for r in range(2 * prow):
        axs[r, 0].set_ylabel("y (m)" if r % 2 == 0 else "speed (m/s)")
    axs[0, 0].set_xlim(*window)
    for i in range(len(parts), prow * ncol):  # a spare panel: hidden, the panel above gets the time axis
        axs[2 * (i // ncol), i % ncol].axis("off")
        axs[2 * (i // ncol) + 1, i % ncol].axis("off")
        axs[2 * (i // ncol) - 1, i % ncol].tick_params(labelbottom=True)
        axs[2 * (i // ncol) - 1, i % ncol].set_xlabel(f"time from {end} (s)")
    for ax in axs[-1, : len(parts) - (prow - 1) * ncol]:
        ax.set_xlabel(f"time from {end} (s)")
    fig.tight_layout()
    return fig


def segmentation_examples(features: pd.DataFrame, speeds: tuple[float, float] = (1.0, 0.2)) -> list[tuple]:
    """The four trials :func:`plot_segmentation` shows in the chapter on the experiment.

    Parameters
    ----------
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (``status``, ``sparc``,
        ``contact_speed`` in m/s).
    speeds : tuple of float
        Contact speeds (m/s) of the two excluded examples: the valid trials nearest them are taken.

    Returns
    -------
    list of tuple
        ``(participant, trial)`` pairs (ids as text): the selected trial with the median SPARC, the
        selected trial with the lowest SPARC (the least smooth), and the valid trials whose contact
        speeds lie nearest ``speeds``.
    """
    valid = features[features["status"] != "invalid"]
    sel = valid[valid["status"] == "selected"]
    rows = [
        (sel["sparc"] - sel["sparc"].median()).abs().idxmin(),
        sel["sparc"].idxmin(),
        *[(valid["contact_speed"] - v).abs().idxmin() for v in speeds],
    ]
    return [tuple(features.loc[r, ["participant", "trial"]]) for r in rows]


@book_figure
def plot_segmentation(recordings: Recordings, features: pd.DataFrame, keys: list[tuple]) -> plt.Figure:
    """Onset/contact segmentation of example trials: y and approach speed against time.

    y (m) and approach speed (m/s) against time (s); the onset threshold, the onset sample, the last sample
    before contact (the contact speed), the first contact sample and the segment (shaded). One legend for
    all panels; the contact speed in the titles.

    Parameters
    ----------
    recordings : Recordings
        The recordings (t in s, positions in m).
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (pv and contact_speed in m/s,
        duration in s, sparc dimensionless).
    keys : list of tuple
        The ``(participant, trial)`` ids of the examples (text), e.g. :func:`segmentation_examples`.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; one column per example: y (m) and speed (m/s) against time (s).
    """
    fig, axs = plt.subplots(2, len(keys), figsize=(min(WIDE, 2.3 * len(keys)), 5.0), sharex="col", squeeze=False)
    idx = features.set_index(["participant", "trial"])
    for j, (p, tr) in enumerate(keys):
        row = idx.loc[(p, tr)]
        t, y, v, c = _approach(recordings, p, tr)
        ay, av = axs[0, j], axs[1, j]
        ay.plot(t, y, ".-", ms=3, lw=0.8, color="0.3")
        av.plot(t[:c], v, ".-", ms=3, lw=0.8, color="0.3")
        av.axhline(ONSET_SPEED, color="tab:orange", lw=0.8, ls="--", label=f"onset threshold {ONSET_SPEED:g} m/s")
        title = f"{_plabel(p)} T{tr}: {row['status']}"
        if row["status"] != "invalid":
            o = round((row["t_onset"] - t[0]) * recordings.fs)
            for ax in (ay, av):
                ax.axvspan(t[o], t[c - 1], color="tab:blue", alpha=0.12, lw=0, label="segment" if ax is av else None)
            av.plot(t[o], v[o], "o", color="tab:orange", ms=5, label="onset")
            av.plot(t[c - 1], v[c - 1], "s", color="tab:red", ms=5, label="last sample before contact")
            title += f"\ncontact speed {row['contact_speed']:.2f} m/s"
        for ax in (ay, av):
            ax.axvline(t[c], color="tab:red", lw=0.8, ls=":", label="first contact sample" if ax is av else None)
        ay.set_title(title, fontsize=9)
        av.set_xlabel("time (s)")
    axs[0, 0].set_ylabel("y (m)")
    axs[1, 0].set_ylabel("speed (m/s)")
    handles, labels = axs[1, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 5), frameon=False, fontsize=8.5)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    return fig


@book_figure
def plot_participant_features(
    features: pd.DataFrame, *, window: tuple[float, float] | None = CONTACT_WINDOW, end: str = "contact"
) -> plt.Figure:
    """Per participant, peak speed, contact speed, duration and SPARC of every valid trial.

    Peak speed (m/s), contact speed (m/s, the selection window shaded), duration (s) and SPARC (box:
    quartiles; points: trials, selected in colour).

    Parameters
    ----------
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (pv and contact_speed in m/s,
        duration in s, sparc dimensionless).
    window : tuple of float or None
        The contact-speed window of the selection, shaded (m/s); None: none shown.
    end : str
        What ends the segments (text: ``"contact"``, ``"offset"``, ...), for the labels.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; four panels (m/s, m/s, s, dimensionless).
    """
    f = features[features["status"] != "invalid"]
    parts = sort_ids(f["participant"].unique())
    cols = [
        ("pv", "peak speed PV (m/s)"),
        ("contact_speed", f"{'contact' if end == 'contact' else 'end'} speed (m/s)"),
        ("duration", f"duration onset-{end} (s)"),
        ("sparc", "SPARC"),
    ]
    fig, axs = plt.subplots(len(cols), 1, figsize=(7.5, 8), sharex=True)
    rng = np.random.default_rng(0)  # horizontal jitter of the points only
    for ax, (c, label) in zip(axs, cols):
        data = [f.loc[f["participant"] == p, c].to_numpy() for p in parts]
        ax.boxplot(data, positions=range(len(parts)), widths=0.5, showfliers=False, medianprops={"color": "k"})
        for i, p in enumerate(parts):
            g = f[f["participant"] == p]
            x = i + rng.uniform(-0.18, 0.18, len(g))
            sel = (g["status"] == "selected").to_numpy()
            ax.scatter(x[~sel], g[c].to_numpy()[~sel], s=3, color="0.7", zorder=2)
            ax.scatter(x[sel], g[c].to_numpy()[sel], s=3, color=_pcolor(parts, p), zorder=3)
        ax.set_ylabel(label, fontsize=8)
        if c == "contact_speed" and window is not None:
            ax.axhspan(*window, color="tab:green", alpha=0.12, lw=0)
    axs[-1].set_xticks(range(len(parts)), [str(p) for p in parts])
    axs[-1].set_xlabel("participant")
    fig.tight_layout()
    return fig


@book_figure
def plot_contact_speeds(
    features: pd.DataFrame,
    bin_width: float = 0.05,
    ax: plt.Axes | None = None,
    *,
    window: tuple[float, float] | None = CONTACT_WINDOW,
    end: str = "contact",
) -> plt.Figure:
    """Histogram of contact speeds of the valid trials; the selection window shaded.

    Parameters
    ----------
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (pv and contact_speed in m/s,
        duration in s, sparc dimensionless).
    bin_width : float
        The width of a bin (m/s), with a window; without one the bins fit the speeds (numpy's "auto").
    ax : matplotlib.axes.Axes or None
        The axes to draw into; None: a new figure.
    window : tuple of float or None
        The contact-speed window of the selection, shaded (m/s); None: none (the selected trials are then
        counted in the title).
    end : str
        What ends the segments (text: ``"contact"``, ``"offset"``, ...), for the axis label.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; counts (dimensionless) against contact speed (m/s).
    """
    v = features.loc[features["status"] != "invalid", "contact_speed"].to_numpy()
    n_sel = int((features["status"] == "selected").sum())
    fig, ax = plt.subplots(figsize=(SINGLE, 3.4)) if ax is None else (ax.figure, ax)
    bins = np.arange(0, v.max() + bin_width, bin_width) if window is not None else "auto"  # no window: any scale
    ax.hist(v, bins=bins, color="0.55")
    if window is not None:
        ax.axvspan(
            *window,
            color="tab:green",
            alpha=0.15,
            lw=0,
            label=f"selected: {window[0]:g}-{window[1]:g} m/s ({n_sel} trials)",
        )
        ax.legend(frameon=False, fontsize=8)
    else:
        ax.set_title(f"{n_sel} of {len(v)} valid trials selected", fontsize=9)
    ax.set_xlabel(f"{'contact' if end == 'contact' else 'end'} speed (m/s)")
    ax.set_ylabel("trials")
    return fig


def threshold_bound(amp_th: float = DEFAULT_AMP_TH) -> float:
    """About the highest SPARC a band ended by the amplitude threshold can have.

    The chord from (0, 1) to (1, amp_th), -sqrt(1 + (1 - amp_th)**2) (chapter 2). Higher values come from
    bands capped by fc.

    Parameters
    ----------
    amp_th : float
        The amplitude threshold, a fraction of the peak magnitude (dimensionless).

    Returns
    -------
    float
        The bound on SPARC (dimensionless).
    """
    return -float(np.hypot(1.0, 1.0 - amp_th))


def _mark_capped(ax: plt.Axes, f: pd.DataFrame, x: str, amp_th: float) -> None:
    """Ring the trials whose SPARC band fc ended and draw the threshold-ended bound (dashed)."""
    if "sparc_capped" in f.columns:
        cap = f[f["sparc_capped"].fillna(False).astype(bool)]
        many = len(cap) > 2_000  # a corpus: faint rings, or they hide every point
        ax.scatter(
            cap[x],
            cap["sparc"],
            s=16,
            facecolor="none",
            edgecolor="k",
            lw=0.3 if many else 0.5,
            alpha=0.15 if many else 1.0,
            label=f"band ended by fc ({len(cap)})",
            zorder=4,
        )
    ax.axhline(
        threshold_bound(amp_th),
        color="0.3",
        ls="--",
        lw=0.8,
        label=f"highest SPARC of a band ended by amp_th = {amp_th:g}",
    )


@book_figure
def plot_feature_space(
    features: pd.DataFrame, ax: plt.Axes | None = None, amp_th: float = DEFAULT_AMP_TH
) -> plt.Figure:
    """Peak speed PV against SPARC: selected trials coloured by participant, excluded in grey.

    Trials whose SPARC band the maximum cut-off fc ended (``sparc_capped``) ringed, and the dashed line
    :func:`threshold_bound` above which only such trials can lie.

    Parameters
    ----------
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (pv and contact_speed in m/s,
        duration in s, sparc dimensionless).
    ax : matplotlib.axes.Axes or None
        The axes to draw into; None: a new figure.
    amp_th : float
        The amplitude threshold of the SPARC bands, a fraction of the peak magnitude (dimensionless), for
        the bound of :func:`threshold_bound`.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; PV (m/s) against SPARC (dimensionless).
    """
    f = features[features["status"] != "invalid"]
    parts = sort_ids(f["participant"].unique())
    fig, ax = plt.subplots(figsize=(7.2, 4.2), layout="constrained") if ax is None else (ax.figure, ax)
    ex = f[f["status"] == "excluded"]
    ax.scatter(ex["pv"], ex["sparc"], s=4, color="0.8", label="excluded")
    if len(parts) > MAX_FIGURE_PARTICIPANTS:  # a corpus: one colour, not a legend of every participant
        g = f[f["status"] == "selected"]
        ax.scatter(g["pv"], g["sparc"], s=3, color="tab:blue", label=f"selected ({len(parts)} participants)")
    for p in parts if len(parts) <= MAX_FIGURE_PARTICIPANTS else []:
        g = f[(f["participant"] == p) & (f["status"] == "selected")]
        ax.scatter(g["pv"], g["sparc"], s=6, color=_pcolor(parts, p), label=_plabel(p))
    _mark_capped(ax, f, "pv", amp_th)
    ax.set_xlabel("peak speed PV (m/s)")
    ax.set_ylabel("SPARC")
    ax.legend(fontsize="small", frameon=False, ncol=2, loc="upper left", bbox_to_anchor=(1.01, 1), markerscale=2)
    return fig


@book_figure
def plot_sparc_vs_length(features: pd.DataFrame, fs: float, amp_th: float = DEFAULT_AMP_TH) -> plt.Figure:
    """SPARC of every valid trial against its segment length, and the share of bands ended by fc.

    Left: SPARC against the segment length N in samples (top axis: the duration N / fs in s); selected
    trials blue, excluded grey, bands ended by fc ringed, the threshold-ended bound dashed. Right: the share
    of bands ended by fc at each N (bars; valid trials), with the number of trials at each N.

    Parameters
    ----------
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (pv and contact_speed in m/s,
        duration in s, sparc dimensionless).
    fs : float
        The sampling rate (Hz), for the duration axis.
    amp_th : float
        The amplitude threshold of the SPARC bands, a fraction of the peak magnitude (dimensionless), for
        the bound of :func:`threshold_bound`.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; SPARC (dimensionless) and the capped share against N (samples).
    """
    f = features[features["status"] != "invalid"]
    sel = (f["status"] == "selected").to_numpy()
    n = f["n"].astype(float).to_numpy()
    fig, (a, b) = plt.subplots(1, 2, figsize=(WIDE, 3.8), layout="constrained", width_ratios=(1, 1))
    g = f.assign(_x=n + np.random.default_rng(0).uniform(-0.25, 0.25, len(f)))  # jitter the integers
    a.scatter(g.loc[~sel, "_x"], g.loc[~sel, "sparc"], s=4, color="0.75", label="excluded")
    a.scatter(g.loc[sel, "_x"], g.loc[sel, "sparc"], s=5, color="C0", label="selected")
    _mark_capped(a, g, "_x", amp_th)
    a.set_xlabel(f"segment length N (samples at {fs:g} Hz, jittered)")
    a.set_ylabel("SPARC")
    top = a.secondary_xaxis("top", functions=(lambda x: x / fs, lambda d: d * fs))
    top.set_xlabel("duration N / fs (s)")
    a.legend(fontsize="small", frameon=False, loc="lower left")
    if "sparc_capped" in f.columns:
        share = f.assign(_c=f["sparc_capped"].astype(float)).groupby(n)["_c"].agg(["mean", "size"])
        b.bar(share.index, share["mean"], width=0.8, color="0.5")
        for x, (m, k) in share.iterrows():
            b.text(x, m + 0.02, str(int(k)), ha="center", va="bottom", fontsize=8, rotation=90)
        b.set_ylim(0, 1.15)
        b.set_xlabel("segment length N (samples)")
        b.set_ylabel("share of bands ended by fc")
    return fig


@book_figure
def plot_feature_overview(
    features: pd.DataFrame,
    amp_th: float = DEFAULT_AMP_TH,
    *,
    window: tuple[float, float] | None = CONTACT_WINDOW,
    end: str = "contact",
) -> plt.Figure:
    """The pipeline's features figure: contact-speed histogram and PV against SPARC.

    The contact-speed histogram with the selection window (m/s) and PV (m/s) against SPARC of the valid
    trials (:func:`plot_feature_space`).

    Parameters
    ----------
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (pv and contact_speed in m/s,
        duration in s, sparc dimensionless).
    amp_th : float
        The amplitude threshold of the SPARC bands, a fraction of the peak magnitude (dimensionless), for
        the bound of :func:`threshold_bound`.
    window : tuple of float or None
        The contact-speed window of the selection (m/s), as in :func:`plot_contact_speeds`.
    end : str
        What ends the segments (text), as in :func:`plot_contact_speeds`.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; two panels (m/s; m/s against SPARC).
    """
    fig, (a, b) = plt.subplots(1, 2, figsize=(WIDE, 4.6), layout="constrained")
    plot_contact_speeds(features, ax=a, window=window, end=end)
    plot_feature_space(features, ax=b, amp_th=amp_th)
    legend = b.get_legend()  # below both panels: beside the right one it would squeeze them
    handles, labels = legend.legend_handles, [text.get_text() for text in legend.get_texts()]
    legend.remove()
    fig.legend(handles, labels, loc="outside lower center", ncol=4, frameon=False, fontsize="small", markerscale=2)
    return fig


@book_figure
def plot_estimates_vs_truth(
    features: pd.DataFrame,
    truth: pd.DataFrame,
    contact_estimates: pd.DataFrame | None = None,
    *,
    label: str = "new estimate",
    window: tuple[float, float] | None = CONTACT_WINDOW,
) -> plt.Figure:
    """Features estimated from the 60 Hz samples against the generator's noise-free truth.

    Peak speed, contact speed (m/s) and duration (s); the identity line dashed. With ``contact_estimates``
    a second row compares them with the feature table's contact speed (the last sample before contact):
    both against the true contact speed, and the error of each against the true contact speed, with the
    selection window's bounds, where an error moves a trial across a bound.

    Parameters
    ----------
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (pv and contact_speed in m/s,
        duration in s, sparc dimensionless).
    truth : pandas.DataFrame
        The generator's ground truth per trial (:func:`skilllib.cohort.generate_cohort`: speeds in m/s,
        times in s).
    contact_estimates : pandas.DataFrame or None
        Other estimates of the contact speed (:func:`skilllib.features.contact_speed_estimates`: ids and
        ``contact_speed`` in m/s); None: the first row only.
    label : str
        The name of those estimates in the legend (text).
    window : tuple of float or None
        The selection window (m/s), its bounds drawn in the second row; None: none.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; three panels (m/s, m/s, s), and two more (m/s) with ``contact_estimates``.
    """
    m = features[features["status"] != "invalid"].merge(truth, on=["participant", "trial"], suffixes=("", "_true"))
    m = m.assign(duration_true=m["t_contact_true"] - m["t_onset_true"])
    rows = 1 if contact_estimates is None else 2
    fig, axs = plt.subplots(rows, 3, figsize=(WIDE, 3.2 * rows), squeeze=False)
    for ax, (c, name) in zip(
        axs[0], [("pv", "PV (m/s)"), ("contact_speed", "contact speed (m/s)"), ("duration", "duration (s)")]
    ):
        ax.scatter(m[f"{c}_true"], m[c], s=3, color="0.35")
        lim = [0, max(m[c].max(), m[f"{c}_true"].max()) * 1.05]
        ax.plot(lim, lim, "--", color="tab:red", lw=0.8)
        ax.set(xlim=lim, ylim=lim, xlabel=f"true {name}", ylabel=f"estimated {name}")
    if contact_estimates is not None:
        _contact_rows(axs[1], m, contact_estimates, label, window)
    fig.tight_layout()
    return fig


def _contact_rows(
    axs: np.ndarray, m: pd.DataFrame, est: pd.DataFrame, label: str, window: tuple[float, float] | None
) -> None:
    """The second row of :func:`plot_estimates_vs_truth`: both estimates against the truth, their errors."""
    e = m.merge(est[["participant", "trial", "contact_speed"]], on=["participant", "trial"], suffixes=("", "_new"))
    v = e["contact_speed_true"].to_numpy()
    old, new = e["contact_speed"].to_numpy(), e["contact_speed_new"].to_numpy()
    styles = [("last sample before contact", old, "0.6"), (label, new, "tab:blue")]
    a, b, c = axs
    lim = [0, max(np.nanmax(old), np.nanmax(new), v.max()) * 1.05]
    for name, x, col in styles:
        a.scatter(v, x, s=3, color=col, alpha=0.7, label=name)
        b.scatter(v, x - v, s=3, color=col, alpha=0.7)
    a.plot(lim, lim, "--", color="tab:red", lw=0.8)
    a.set(xlim=lim, ylim=lim, xlabel="true contact speed (m/s)", ylabel="estimated contact speed (m/s)")
    a.legend(fontsize="small", frameon=False, loc="upper left", markerscale=3)
    b.axhline(0, color="tab:red", lw=0.8, ls="--")
    b.set(xlim=lim, xlabel="true contact speed (m/s)", ylabel="estimate - truth (m/s)")
    for ax in (a, b) if window is not None else ():
        for bound in window:
            ax.axvline(bound, color="tab:green", lw=0.8, ls=":")
    bins = np.linspace(-0.5, 0.5, 51)
    for name, x, col in styles:
        rmse = np.sqrt(np.nanmean((x - v) ** 2))
        c.hist(
            np.clip(x - v, bins[0], bins[-1]), bins=bins, color=col, alpha=0.6, label=f"{name}\n(RMSE {rmse:.3f} m/s)"
        )
    c.set(xlabel="estimate - truth (m/s)", ylabel="trials", ylim=(0, c.get_ylim()[1] * 1.4))  # room for the legend
    c.legend(fontsize="small", frameon=False, loc="upper left")
