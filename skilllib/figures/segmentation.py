"""The segmentation of every trial, page by page: what the analysis saw of each recording.

:func:`plot_segmentation_pages` draws small multiples (24 trials a page): the speed of the whole recording
with the run's onset threshold (absolute, or computed from each trial's peak), the onset, the end sample
(contact, offset, event or height, as the run's end rule says, labelled so) and the analysed segment
marked, repaired samples, resampling and the trial's status and reason. :func:`segmentation_keys` chooses
the trials a run draws (every invalid one first).
"""

from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import MaxNLocator

from ..features import (
    PAPER_END,
    PAPER_START,
    EndRule,
    Lowpass,
    StartRule,
    segmentation_detail,
    trial_events,
    velocity,
)
from ..recordings import Recordings, gap_runs, natural_key
from ._style import MIN_FONT, WIDE, book_figure
from .experiment import _plabel

#: Panels of a page: rows x columns (trials); four columns fit the book's page width.
PAGE_ROWS, PAGE_COLS = 6, 4
#: Pages a run writes at most (72 trials): every invalid trial first, then an even sample of the valid ones.
MAX_SEGMENTATION_PAGES = 3
#: Trials a run draws at most.
MAX_SEGMENTATION_TRIALS = MAX_SEGMENTATION_PAGES * PAGE_ROWS * PAGE_COLS
#: Colour of each status: the title, and the frame of an invalid trial's panel.
STATUS_COLORS = {"selected": "#1a7f37", "excluded": "0.2", "invalid": "#c62828"}
#: Background of an invalid trial's panel.
INVALID_FACE = "#fdecec"
#: Characters of a title line, and lines of the reason (the full reason is in results.json).
LINE_CHARS, REASON_LINES = 36, 2
ONSET_COLOR, CONTACT_COLOR, SEGMENT_COLOR, REPAIRED_COLOR = "tab:blue", "tab:purple", "tab:blue", "tab:orange"
FONT = MIN_FONT  #: pt, the panels' text (titles, ticks, labels, marks) at the saved size
#: A panel's share of the page (in), and the page's margins above and below the panels (in).
PANEL_W, PANEL_H, TOP_IN, BOTTOM_IN = 2.25, 2.0, 0.5, 0.55
#: The narrowest page (in), the height of a line of the header or of the legend (in), the width of a
#: legend entry (in), the header's font (pt).
MIN_WIDTH, LINE_IN, LEGEND_ENTRY_W, HEAD_FONT = 4.5, 0.17, 1.9, 8.5
#: Resolution of a written page (dots per inch): 8 pt text is 12 pixels high.
PAGE_DPI = 110


def _short(reason: str, width: int = LINE_CHARS, lines: int = REASON_LINES) -> str:
    """``reason`` wrapped into at most ``lines`` lines of ``width`` characters, an ellipsis when cut."""
    out = textwrap.wrap(reason, width, max_lines=lines, placeholder=" …")
    return "\n".join(out)


def segmentation_keys(features: pd.DataFrame, most: int | None = None) -> tuple[list[tuple[str, str]], str]:
    """The trials the segmentation pages show, in natural order of participant and trial, and a note.

    All trials when they are ``most`` or fewer; otherwise every invalid trial (natural order; the first
    ``most`` when there are more), the room left filled with valid trials evenly spaced over the natural
    order (so every participant appears), and the whole set put back in natural order.

    Parameters
    ----------
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (``participant``, ``trial``,
        ``status``).
    most : int or None
        The most trials shown (dimensionless); None: all.

    Returns
    -------
    keys : list of tuple
        The ``(participant, trial)`` ids (text) shown.
    note : str
        What was left out, or "" when every trial is shown (text).
    """
    ids = list(zip(features["participant"], features["trial"], features["status"]))
    ids.sort(key=lambda k: (natural_key(k[0]), natural_key(k[1])))
    if most is None or len(ids) <= most:
        return [(p, t) for p, t, _ in ids], ""
    invalid = [k for k in ids if k[2] == "invalid"]
    valid = [k for k in ids if k[2] != "invalid"]
    chosen = invalid[:most]
    room = most - len(chosen)
    if room > 0:
        picks = np.unique(np.linspace(0, len(valid) - 1, room).round().astype(int))
        chosen += [valid[i] for i in picks]
    chosen.sort(key=lambda k: (natural_key(k[0]), natural_key(k[1])))
    n_inv = sum(k[2] == "invalid" for k in chosen)
    what = f"all {len(invalid)} invalid" if n_inv == len(invalid) else f"the first {n_inv} of {len(invalid)} invalid"
    note = (
        f"the segmentation of {len(chosen)} of {len(ids)} trials: {what} and "
        f"{len(chosen) - n_inv} of {len(valid)} valid ones evenly spaced by participant and trial"
    )
    return [(p, t) for p, t, _ in chosen], note


def _speeds(t: np.ndarray, pos: np.ndarray, c: int, fs: float, lowpass: Lowpass | None) -> tuple:
    """The speed (m/s) of the whole recording and the analysis' speed of the approach (the first ``c``
    samples), the approach's positions filtered by ``lowpass`` first, as :func:`skilllib.features.segment`."""
    pos = np.asarray(pos, dtype=float)
    if not np.isfinite(fs):
        return np.full(len(pos), np.nan), np.full(c, np.nan)
    if lowpass is not None and lowpass.cutoff_hz is not None and c >= 2 and np.isfinite(pos[:c]).all():
        pos = np.concatenate([lowpass.apply(pos[:c], fs), pos[c:]])
    return _run_speed(pos, fs), _run_speed(pos[:c], fs)


def _run_speed(pos: np.ndarray, fs: float) -> np.ndarray:
    """The speed (m/s) of ``pos`` (m), differentiated over each run of samples with a position (an invalid
    trial can keep a gap too long to fill); NaN at the missing samples and in runs of fewer than 2."""
    out = np.full(len(pos), np.nan)
    have = np.isfinite(pos).all(axis=1) if len(pos) else np.zeros(0, dtype=bool)
    for a, b in gap_runs(have):
        if b - a >= 2:
            out[a:b] = np.linalg.norm(velocity(pos[a:b], fs), axis=1)
    return out


def _detail(recordings: Recordings, p: Any, tr: Any, d: Any, fs: float, lowpass, start, end):
    """:func:`skilllib.features.segmentation_detail` of the trial, or None when its samples cannot be
    analysed (missing positions, no rate)."""
    pos = np.asarray(d.pos, dtype=float)
    if not np.isfinite(fs) or len(pos) < 2 or not np.isfinite(pos).all():
        return None
    events = trial_events(recordings, p, tr) if "event" in (start.kind, end.kind) else None
    return segmentation_detail(d.t, pos, d.contact, fs, start=start, end=end, events=events, lowpass=lowpass)


def _draw_trial(
    ax: plt.Axes,
    recordings: Recordings,
    row: Any,
    lowpass: Lowpass | None,
    start: StartRule = PAPER_START,
    end: EndRule = PAPER_END,
) -> dict[str, bool]:
    """One panel; returns which of the legend's elements it drew."""
    p, tr, status = row.participant, row.trial, row.status
    d = recordings.trial(p, tr)
    t = np.asarray(d.t, dtype=float)
    fs = float(recordings.fs)
    if not np.isfinite(fs):  # no usable trial gave the rate: this trial's own median interval, if any
        dt = np.diff(t)
        dt = dt[np.isfinite(dt) & (dt > 0)]
        fs = 1.0 / float(np.median(dt)) if dt.size else np.nan
    detail = _detail(recordings, p, tr, d, fs, lowpass, start, end)
    if end.kind == "contact":  # the paper: the speed before contact as analysed, the rest as recorded
        hits = np.flatnonzero(d.contact)
        c = int(hits[0]) if hits.size else len(t)
        whole, approach = _speeds(t, d.pos, c, fs, lowpass)
    else:  # the end is where the rule found it (the table's t_contact, or what the analysis got to)
        c = -1
        if pd.notna(row.t_contact):
            c = int(np.searchsorted(t, float(row.t_contact)))
        elif detail is not None and detail.end >= 0:
            c = detail.end
        whole_pos = np.asarray(d.pos, dtype=float)
        if end.kind == "offset" and lowpass is not None and lowpass.cutoff_hz is not None and detail is not None:
            whole_pos = lowpass.apply(whole_pos, fs)  # offset: the whole trial filtered as analysed
        whole = _run_speed(whole_pos, fs) if np.isfinite(fs) else np.full(len(t), np.nan)
        approach = detail.speed if detail is not None else np.zeros(0)
    drew = {"repaired": False, "onset": False, "contact": False, "segment": False, "offset_threshold": False}
    ax.plot(t, whole, color="0.65", lw=0.7)
    ax.plot(t[: len(approach)], approach, color="k", lw=0.9)
    on_th = detail.start_threshold if detail is not None else np.nan
    if not np.isfinite(on_th) and start.kind == "speed" and start.threshold.fraction is None:
        on_th = float(start.threshold.speed)
    if np.isfinite(on_th):
        ax.axhline(on_th, color="0.45", lw=0.6, ls=":")
    off_th = detail.end_threshold if detail is not None else np.nan
    if np.isfinite(off_th) and not (np.isfinite(on_th) and np.isclose(off_th, on_th, rtol=1e-9, atol=0)):
        ax.axhline(off_th, color="0.45", lw=0.6, ls="-.")
        drew["offset_threshold"] = True
    t_on = float(row.t_onset) if pd.notna(row.t_onset) else np.nan
    if not np.isfinite(t_on) and detail is not None and detail.onset > 0:  # an invalid trial: the analysis' onset
        if end.kind != "contact" or c < len(t):
            t_on = float(t[detail.onset])
    if np.isfinite(t_on):
        ax.axvline(t_on, color=ONSET_COLOR, lw=1.0, ls="--")
        drew["onset"] = True
        if status != "invalid" and 0 < c <= len(t):
            ax.axvspan(t_on, t[c - 1], color=SEGMENT_COLOR, alpha=0.13, lw=0)
            drew["segment"] = True
    if 0 <= c < len(t):
        t_c = float(row.t_contact) if pd.notna(row.t_contact) else float(t[c])
        ax.axvline(t_c, color=CONTACT_COLOR, lw=1.0)
        ax.text(
            t_c,
            0.97,
            _END_MARKS[end.kind] + " ",
            transform=ax.get_xaxis_transform(),
            rotation=90,
            ha="right",
            va="top",
            fontsize=FONT,
            color=CONTACT_COLOR,
        )
        drew["contact"] = True
    repaired_mask = getattr(recordings, "repaired_mask", None)
    if callable(repaired_mask):
        mask = np.asarray(repaired_mask(p, tr), dtype=bool)
        if mask.shape == t.shape and mask.any():
            ax.plot(t[mask], whole[mask], "x", color=REPAIRED_COLOR, ms=3.5, mew=0.9, ls="none")
            drew["repaired"] = True
    if len(t) > 1 and np.isfinite(t[[0, -1]]).all() and t[-1] > t[0]:
        ax.set_xlim(t[0], t[-1])
    ax.set_ylim(0, None)
    ax.tick_params(labelsize=FONT, length=2, pad=1.5)
    ax.xaxis.set_major_locator(MaxNLocator(4))
    ax.yaxis.set_major_locator(MaxNLocator(3))
    head = f"{_label(p, tr)} · {status}" + (" · resampled" if bool(row.resampled) else "")
    reason = str(row.reason) if isinstance(row.reason, str) and row.reason else ""
    if status == "selected" and end.kind == "contact" and pd.notna(row.contact_speed):
        reason = f"contact speed {row.contact_speed:.3f} m/s"
    elif status == "selected" and pd.notna(row.duration) and pd.notna(row.pv):
        reason = f"duration {row.duration:.2f} s · PV {row.pv:.3f} m/s"
    lines = [_short(head, LINE_CHARS, 1), *(_short(reason).split("\n") if reason else [])]
    color = STATUS_COLORS.get(status, "k")
    ax.set_title("\n".join(lines), fontsize=FONT, color=color, loc="left", pad=2, linespacing=1.15)
    if status == "invalid":
        ax.set_facecolor(INVALID_FACE)
        for s in ax.spines.values():
            s.set_edgecolor(color)
            s.set_linewidth(1.2)
    return drew


def _label(p: Any, tr: Any) -> str:
    """ "P3 T12" for ids of digits; ids of other text as they are ("anna run2")."""
    s = str(tr)
    return f"{_plabel(p)} {'T' + s if s.isdigit() and not s.startswith('0') else s}"


@book_figure
def plot_segmentation_pages(
    recordings: Recordings,
    features: pd.DataFrame,
    *,
    keys: list[tuple] | None = None,
    lowpass: Lowpass | None = None,
    rows: int = PAGE_ROWS,
    cols: int = PAGE_COLS,
    max_pages: int | None = None,
    start: StartRule | None = None,
    end: EndRule | None = None,
) -> list[plt.Figure]:
    """The segmentation of every trial (or of ``keys``): pages of small multiples, one panel per trial.

    Each panel: the speed (m/s) against time (s) over the whole recording (grey; black: the speed as the
    analysis differentiated it, after the run's low-pass filter: up to contact for the paper's end, up to
    the end sample for an event or height end, the whole trial for an offset end), the run's onset
    threshold (dotted; for a relative threshold, computed from the trial's peak), the offset threshold
    when it differs (dash-dot), the onset (dashed) and the end sample (solid, labelled by what ended it:
    contact, offset, event or height) as vertical lines, the analysed segment (onset to the last sample
    before the end) shaded, repaired samples crossed (when the recordings have ``repaired_mask``), and in
    the title the ids, the status (selected, excluded, invalid: red and framed), "resampled" for a trial
    resampled onto the uniform grid, and the reason, shortened (the full reason is in the feature table and
    results.json). Trials in natural order of participant and trial; one legend a page.

    Parameters
    ----------
    recordings : Recordings
        The recordings (t in s, positions in m).
    features : pandas.DataFrame
        The per-trial table of :func:`skilllib.features.trial_features` (``status``, ``reason``,
        ``contact_speed`` in m/s, ``t_onset`` and ``t_contact`` in s, ``resampled``).
    keys : list of tuple or None
        The ``(participant, trial)`` ids (text) to draw, e.g. :func:`segmentation_keys`; None: every trial
        of ``features``.
    lowpass : Lowpass or None
        The positions' filter of the run (cut-off in Hz); None: ``features.attrs["lowpass"]`` when there,
        else none.
    rows, cols : int
        Panels of a page (dimensionless).
    max_pages : int or None
        The most pages drawn (dimensionless); None: all.
    start : StartRule or None
        The run's start rule (speeds in m/s); None: ``features.attrs["start"]`` when there, else the
        paper's (0.05 m/s).
    end : EndRule or None
        The run's end rule (speeds in m/s, heights in m); None: ``features.attrs["end"]`` when there, else
        the paper's (contact).

    Returns
    -------
    list of matplotlib.figure.Figure
        One figure a page; panels of speed (m/s) against time (s).
    """
    if lowpass is None:
        lowpass = features.attrs.get("lowpass")
    start = start if start is not None else features.attrs.get("start", PAPER_START)
    end = end if end is not None else features.attrs.get("end", PAPER_END)
    rules = "" if start == PAPER_START and end.kind == "contact" else f" Rules: start {start.text()}, end {end.text()}."
    table = features.assign(participant=features["participant"].astype(str), trial=features["trial"].astype(str))
    table = table.set_index(["participant", "trial"], drop=False)
    if keys is None:
        keys = sorted(table.index, key=lambda k: (natural_key(k[0]), natural_key(k[1])))
    keys = [(str(p), str(t)) for p, t in keys]
    per_page = rows * cols
    n_pages = -(-len(keys) // per_page)
    if n_pages == 1:  # all on one page: no empty rows or columns
        cols = min(cols, len(keys))
        rows = -(-len(keys) // cols)
        per_page = rows * cols
    if max_pages is not None:
        n_pages = min(n_pages, max_pages)
    width = min(WIDE, max(PANEL_W * cols, MIN_WIDTH))
    legend_cols = max(1, min(8, int(width // LEGEND_ENTRY_W)))
    figs = []
    for page in range(n_pages):
        chunk = keys[page * per_page : (page + 1) * per_page]
        head = textwrap.wrap(
            f"Segmentation, page {page + 1} of {n_pages}: {_label(*chunk[0])}"
            + (f" to {_label(*chunk[-1])} ({len(chunk)} trials)" if len(chunk) > 1 else "")
            + "."
            + rules
            + " Titles: ids, status (selected green, excluded black, invalid red and framed), reason (shortened;"
            " in full in results.json).",
            int(width * 72 / (HEAD_FONT * 0.55)),
        )
        handles = [None] * 8  # the most entries a legend has: the room kept for it
        top = 0.08 + LINE_IN * (len(head) + -(-len(handles) // legend_cols)) + TOP_IN
        height = PANEL_H * rows + top + BOTTOM_IN
        fig, axs = plt.subplots(rows, cols, figsize=(width, height), squeeze=False)
        fig.subplots_adjust(
            left=0.5 / width,
            right=1 - 0.4 / width,
            bottom=BOTTOM_IN / height,
            top=1 - top / height,
            wspace=0.3,
            hspace=0.62,
        )
        drew: dict[str, bool] = {}
        for i, ax in enumerate(axs.flat):
            if i >= len(chunk):
                ax.axis("off")
                continue
            for k, v in _draw_trial(ax, recordings, table.loc[chunk[i]], lowpass, start, end).items():
                drew[k] = drew.get(k, False) or v
        last = {j: max(i for i in range(len(chunk)) if i % cols == j) for j in range(min(cols, len(chunk)))}
        for i, ax in enumerate(axs.flat[: len(chunk)]):
            if i == last[i % cols]:
                ax.set_xlabel("time (s)", fontsize=FONT, labelpad=1)
            if i % cols == 0:
                ax.set_ylabel("speed (m/s)", fontsize=FONT, labelpad=1)
        fig.text(0.08 / width, 1 - 0.06 / height, "\n".join(head), fontsize=HEAD_FONT, ha="left", va="top")
        fig.legend(
            handles=_legend(drew, start, end),
            loc="upper left",
            bbox_to_anchor=(0.04 / width, 1 - (0.1 + LINE_IN * len(head)) / height),
            ncol=legend_cols,
            frameon=False,
            fontsize=FONT,
            handlelength=1.8,
            columnspacing=1.2,
            borderaxespad=0,
            borderpad=0,
        )
        figs.append(fig)
    return figs


#: The end sample's label in a panel, by end rule.
_END_MARKS = {
    "contact": "contact",
    "offset": "offset",
    "event": "event",
    "height-above": "height",
    "height-below": "height",
}


def _end_label(end: EndRule) -> str:
    """The legend's name of the end sample."""
    if end.kind == "contact":
        return "first contact sample"
    if end.kind == "offset":
        return "offset (end)"
    if end.kind == "event":
        return f"event {end.label} (end)"
    return f"height {'above' if end.kind == 'height-above' else 'below'} {end.height:g} m (end)"


def _threshold_label(th: Any, what: str) -> str:
    if th.fraction is None:
        return f"{what} threshold {th.speed:g} m/s"
    return f"{what} threshold {th.text()} of the peak"


def _legend(drew: dict[str, bool], start: StartRule = PAPER_START, end: EndRule = PAPER_END) -> list:
    """The legend's entries of a page: the lines every panel has, and what some panel drew."""
    analysed = {"contact": "speed before contact", "offset": "speed"}.get(end.kind, "speed before the end")
    handles = [
        Line2D([], [], color="k", lw=0.9, label=f"{analysed} (as analysed)"),
        Line2D([], [], color="0.65", lw=0.7, label="speed, whole recording"),
    ]
    if start.kind == "speed":
        label = _threshold_label(start.threshold, "onset")
        if end.kind == "offset" and end.offset_threshold(start) == start.threshold:
            label = label.replace("onset threshold", "onset and offset threshold")
        handles.append(Line2D([], [], color="0.45", lw=0.6, ls=":", label=label))
    if drew.get("offset_threshold"):
        th = end.offset_threshold(start)
        handles.append(Line2D([], [], color="0.45", lw=0.6, ls="-.", label=_threshold_label(th, "offset")))
    if drew.get("onset"):
        handles.append(Line2D([], [], color=ONSET_COLOR, lw=1.0, ls="--", label="onset"))
    if drew.get("contact"):
        handles.append(Line2D([], [], color=CONTACT_COLOR, lw=1.0, label=_end_label(end)))
    if drew.get("segment"):
        handles.append(Patch(color=SEGMENT_COLOR, alpha=0.13, lw=0, label="analysed segment"))
    if drew.get("repaired"):
        handles.append(Line2D([], [], color=REPAIRED_COLOR, marker="x", ms=4, ls="none", label="repaired sample"))
    return handles


def save_page(fig: plt.Figure, out_dir: str | Path, name: str, dpi: int = PAGE_DPI) -> list[Path]:
    """Write one page as ``out_dir/name.png`` (PNG only, the page's own size: no tight bounding box).

    A run writes a few pages of 24 panels each: a PNG at a modest resolution keeps that to about a second
    a page, where :func:`skilllib.figures.save` (PNG and SVG, tight) would take three.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The page.
    out_dir : str or pathlib.Path
        The folder (text), created when missing.
    name : str
        The file name without extension (text).
    dpi : int
        Resolution of the PNG (dots per inch).

    Returns
    -------
    list of pathlib.Path
        The PNG written.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{name}.png"
    fig.savefig(path, dpi=dpi)
    return [path]
