"""The segmentation of every trial, page by page: what the analysis saw of each recording.

:func:`plot_segmentation_pages` draws small multiples (24 trials a page): the speed of the whole recording
with the onset, the contact and the analysed segment marked, repaired samples, resampling and the trial's
status and reason. :func:`segmentation_keys` chooses the trials a run draws (every invalid one first).
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

from ..features import ONSET_SPEED, Lowpass, velocity
from ..recordings import Recordings, gap_runs, natural_key
from .experiment import _plabel

#: Panels of a page: rows x columns (trials).
PAGE_ROWS, PAGE_COLS = 4, 6
#: Pages a run writes at most (72 trials): every invalid trial first, then an even sample of the valid ones.
MAX_SEGMENTATION_PAGES = 3
#: Trials a run draws at most.
MAX_SEGMENTATION_TRIALS = MAX_SEGMENTATION_PAGES * PAGE_ROWS * PAGE_COLS
#: Colour of each status: the title, and the frame of an invalid trial's panel.
STATUS_COLORS = {"selected": "#1a7f37", "excluded": "0.2", "invalid": "#c62828"}
#: Background of an invalid trial's panel.
INVALID_FACE = "#fdecec"
#: Characters of a title line, and lines of the reason (the full reason is in results.json).
LINE_CHARS, REASON_LINES = 38, 2
ONSET_COLOR, CONTACT_COLOR, SEGMENT_COLOR, REPAIRED_COLOR = "tab:blue", "tab:purple", "tab:blue", "tab:orange"
FONT = 7.5  #: pt, the panels' text (titles, ticks, labels) at the saved size
#: A panel's share of the page (in), and the page's margins above and below the panels (in).
PANEL_W, PANEL_H, TOP_IN, BOTTOM_IN = 2.25, 1.9, 0.5, 0.55
#: The narrowest page (in), the height of a line of the header or of the legend (in), the width of a
#: legend entry (in), the header's font (pt).
MIN_WIDTH, LINE_IN, LEGEND_ENTRY_W, HEAD_FONT = 4.5, 0.17, 1.9, 8.5
#: Resolution of a written page (dots per inch): 7.5 pt text is 11 pixels high.
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


def _draw_trial(ax: plt.Axes, recordings: Recordings, row: Any, lowpass: Lowpass | None) -> dict[str, bool]:
    """One panel; returns which of the legend's elements it drew."""
    p, tr, status = row.participant, row.trial, row.status
    d = recordings.trial(p, tr)
    t = np.asarray(d.t, dtype=float)
    hits = np.flatnonzero(d.contact)
    c = int(hits[0]) if hits.size else len(t)
    fs = float(recordings.fs)
    if not np.isfinite(fs):  # no usable trial gave the rate: this trial's own median interval, if any
        dt = np.diff(t)
        dt = dt[np.isfinite(dt) & (dt > 0)]
        fs = 1.0 / float(np.median(dt)) if dt.size else np.nan
    whole, approach = _speeds(t, d.pos, c, fs, lowpass)
    drew = {"repaired": False, "onset": False, "contact": False, "segment": False}
    ax.plot(t, whole, color="0.65", lw=0.7)
    ax.plot(t[:c], approach, color="k", lw=0.9)
    ax.axhline(ONSET_SPEED, color="0.45", lw=0.6, ls=":")
    t_on = float(row.t_onset) if pd.notna(row.t_onset) else np.nan
    if not np.isfinite(t_on) and c < len(t) and len(approach):  # an invalid trial: the analysis' crossing, if any
        moving = np.flatnonzero(approach > ONSET_SPEED)
        t_on = float(t[moving[0]]) if moving.size and moving[0] > 0 else np.nan
    if np.isfinite(t_on):
        ax.axvline(t_on, color=ONSET_COLOR, lw=1.0, ls="--")
        drew["onset"] = True
        if status != "invalid":
            ax.axvspan(t_on, t[c - 1], color=SEGMENT_COLOR, alpha=0.13, lw=0)
            drew["segment"] = True
    if c < len(t):
        t_c = float(row.t_contact) if pd.notna(row.t_contact) else float(t[c])
        ax.axvline(t_c, color=CONTACT_COLOR, lw=1.0)
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
    if status == "selected" and pd.notna(row.contact_speed):
        reason = f"contact speed {row.contact_speed:.3f} m/s"
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


def plot_segmentation_pages(
    recordings: Recordings,
    features: pd.DataFrame,
    *,
    keys: list[tuple] | None = None,
    lowpass: Lowpass | None = None,
    rows: int = PAGE_ROWS,
    cols: int = PAGE_COLS,
    max_pages: int | None = None,
) -> list[plt.Figure]:
    """The segmentation of every trial (or of ``keys``): pages of small multiples, one panel per trial.

    Each panel: the speed (m/s) against time (s) over the whole recording (grey; black up to contact: the
    approach as the analysis differentiated it, after the run's low-pass filter), the onset threshold
    (dotted), the onset (dashed) and the first contact sample (solid) as vertical lines, the analysed
    segment (onset to the last sample before contact) shaded, repaired samples crossed (when the recordings
    have ``repaired_mask``), and in the title the ids, the status (selected, excluded, invalid: red and
    framed), "resampled" for a trial resampled onto the uniform grid, and the reason, shortened (the full
    reason is in the feature table and results.json). Trials in natural order of participant and trial;
    one legend a page.

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

    Returns
    -------
    list of matplotlib.figure.Figure
        One figure a page; panels of speed (m/s) against time (s).
    """
    if lowpass is None:
        lowpass = features.attrs.get("lowpass")
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
    width = max(PANEL_W * cols, MIN_WIDTH)
    legend_cols = max(1, min(8, int(width // LEGEND_ENTRY_W)))
    figs = []
    for page in range(n_pages):
        chunk = keys[page * per_page : (page + 1) * per_page]
        head = textwrap.wrap(
            f"Segmentation, page {page + 1} of {n_pages}: {_label(*chunk[0])}"
            + (f" to {_label(*chunk[-1])} ({len(chunk)} trials)" if len(chunk) > 1 else "")
            + ". Titles: ids, status (selected green, excluded black, invalid red and framed), reason (shortened;"
            " in full in results.json).",
            int(width * 72 / (HEAD_FONT * 0.55)),
        )
        handles = [None] * 7  # the most entries a legend has: the room kept for it
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
            for k, v in _draw_trial(ax, recordings, table.loc[chunk[i]], lowpass).items():
                drew[k] = drew.get(k, False) or v
        last = {j: max(i for i in range(len(chunk)) if i % cols == j) for j in range(min(cols, len(chunk)))}
        for i, ax in enumerate(axs.flat[: len(chunk)]):
            if i == last[i % cols]:
                ax.set_xlabel("time (s)", fontsize=FONT, labelpad=1)
            if i % cols == 0:
                ax.set_ylabel("speed (m/s)", fontsize=FONT, labelpad=1)
        fig.text(0.08 / width, 1 - 0.06 / height, "\n".join(head), fontsize=HEAD_FONT, ha="left", va="top")
        fig.legend(
            handles=_legend(drew),
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


def _legend(drew: dict[str, bool]) -> list:
    """The legend's entries of a page: the lines every panel has, and what some panel drew."""
    handles = [
        Line2D([], [], color="k", lw=0.9, label="speed before contact (as analysed)"),
        Line2D([], [], color="0.65", lw=0.7, label="speed, whole recording"),
        Line2D([], [], color="0.45", lw=0.6, ls=":", label=f"onset threshold {ONSET_SPEED:g} m/s"),
    ]
    if drew.get("onset"):
        handles.append(Line2D([], [], color=ONSET_COLOR, lw=1.0, ls="--", label="onset"))
    if drew.get("contact"):
        handles.append(Line2D([], [], color=CONTACT_COLOR, lw=1.0, label="first contact sample"))
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
