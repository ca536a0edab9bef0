"""Trials cut into pieces: several movements recorded in one trial become one trial each.

:func:`cut_trials` slices chosen trials of a :class:`~skilllib.recordings.Recordings` by sample ranges into
new trials and keeps every invariant of the class, so that the pieces are analysed like any trial
(:func:`skilllib.features.split_movements` chooses the ranges). Rules:

* **Names.** Piece ``k`` (1, 2, ... in the order given) of trial ``T`` is trial ``f"{T}-{k}"`` of the
  same participant, in the place of ``T`` in :attr:`~skilllib.recordings.Recordings.trials`; a name that
  another trial already has is an error. Trials not cut keep their rows, samples and ids.
* **Samples.** The ranges are ``(start, stop)`` sample indices (``stop`` excluded) into the samples of
  :meth:`~skilllib.recordings.Recordings.trial`: the resampled or repaired samples of a trial that has
  them, which its pieces keep (:meth:`~skilllib.recordings.Recordings.is_resampled`, the repaired mask).
* **Rows.** :attr:`~skilllib.recordings.Recordings.frame` keeps the rows as read, each relabelled with its
  piece: rows ``start .. stop - 1`` of the trial; for a resampled or repaired trial, the rows whose time
  is from the piece's first sample to before the next piece's (the first piece from the trial's first
  row, the last to its last). Rows in no piece (before the first range, between ranges that leave a
  gap, after the last) are left out. The frame is re-indexed ``0 .. R - 1``. ``n_samples`` counts a
  piece's rows; ``first_line`` is the trial's first line plus the offset of the piece's first row in the
  trial (the file line when the trial has no blank line inside).
* **Status and timing.** A piece is ``ok`` with the trial's ``timing`` text, or ``invalid`` when it has
  fewer than :data:`~skilllib.recordings.MIN_SAMPLES` samples (the reason says so).
* **Repairs.** ``n_repaired`` counts the piece's repaired samples; ``repairs`` says them and the trial's
  own text (``""`` for a piece without repaired samples, except the first piece of a trial with dropped
  samples); the trial's ``n_dropped`` goes to its first piece.
* **Events.** An event belongs to the piece that holds the first sample at or after it (within 1 % of a
  sampling interval, as the C3D reader's contact rule); events after the trial's last sample to its last
  piece when that one ends there; events in no piece are left out.
* ``fs``, ``source``, ``notes`` and ``skipped`` are kept.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd

from ._checks import MIN_SAMPLES
from ._recordings import EVENT_COLUMNS, Recordings, Trial, _id

EVENT_TOLERANCE = 0.01  #: fraction of a sampling interval by which a sample may precede an event and hold it


def piece_name(trial: str, k: int) -> str:
    """The id of piece ``k`` (from 1) of trial ``trial``: ``f"{trial}-{k}"``.

    Parameters
    ----------
    trial : str
        The trial's id (text).
    k : int
        The piece's number, 1, 2, ... in time order (dimensionless).

    Returns
    -------
    str
        The piece's trial id (text).
    """
    return f"{trial}-{k}"


def _check_ranges(key: tuple[str, str], ranges: Sequence[tuple[int, int]], n: int) -> list[tuple[int, int]]:
    out = [(int(a), int(b)) for a, b in ranges]
    if not out:
        raise ValueError(f"trial {key[1]!r} of participant {key[0]!r}: no piece to cut")
    last = 0
    for a, b in out:
        if not (last <= a < b <= n):
            raise ValueError(
                f"trial {key[1]!r} of participant {key[0]!r}: pieces must be increasing, non-empty, "
                f"non-overlapping sample ranges within its {n} samples, got {out}"
            )
        last = b
    return out


def _row_pieces(
    rows: np.ndarray, t_rows: np.ndarray, tr: Trial, ranges: list[tuple[int, int]], resampled: bool
) -> list[np.ndarray]:
    """The rows of the frame that each piece holds (module docstring: Rows)."""
    if not resampled:
        return [rows[a:b] for a, b in ranges]
    n = len(tr.t)
    out = []
    for a, b in ranges:
        lo = -np.inf if a == 0 else tr.t[a]
        hi = np.inf if b == n else tr.t[b]
        out.append(rows[(t_rows >= lo) & (t_rows < hi)])
    return out


def _repairs_text(n_piece: int, n_all: int, trial: str, text: str, first: bool, n_dropped: int) -> str:
    if not n_piece and not (first and n_dropped):
        return ""
    return f"{n_piece} of the {n_all} repaired samples of recording {trial} in this piece (recording: {text})"


def _piece_events(events: pd.DataFrame, key: tuple[str, str], tr: Trial, ranges: list[tuple[int, int]], fs: float):
    """The trial's events relabelled with their pieces (module docstring: Events)."""
    mine = events[(events["participant"] == key[0]) & (events["trial"] == key[1])]
    if mine.empty:
        return mine
    tol = EVENT_TOLERANCE / fs if np.isfinite(fs) and fs > 0 else 0.0
    at = np.searchsorted(tr.t, mine["t"].to_numpy(dtype=float) - tol, side="left")  # first sample at/after
    n = len(tr.t)
    piece = np.full(len(mine), -1)
    for k, (a, b) in enumerate(ranges):
        inside = (at >= a) & (at < b) | ((at >= n) & (b == n))
        piece[inside] = k
    out = mine[piece >= 0].copy()
    out["trial"] = [piece_name(key[1], k + 1) for k in piece[piece >= 0]]
    return out


def cut_trials(recordings: Recordings, pieces: Mapping[tuple[Any, Any], Sequence[tuple[int, int]]]) -> Recordings:
    """Recordings with chosen trials cut into pieces, each piece a trial (rules: module docstring).

    Parameters
    ----------
    recordings : Recordings
        The recordings (t in s, positions in m).
    pieces : mapping of (participant, trial) to sequence of (int, int)
        For each trial to cut (ids as text; a number as its text), its pieces as ``(start, stop)`` sample
        ranges (samples; ``stop`` excluded) into the samples of ``recordings.trial(participant, trial)``,
        increasing and not overlapping. Trials not named are kept as they are.

    Returns
    -------
    Recordings
        The recordings with piece ``k`` of trial ``T`` as trial ``f"{T}-{k}"`` (same participant, same
        ``fs`` in Hz, t in s, positions in m).

    Raises
    ------
    KeyError
        When a trial named is not in ``recordings``.
    ValueError
        When a trial's ranges are empty, overlap, are not increasing or leave its samples, or a piece's
        name is already a trial's.
    """
    cuts: dict[tuple[str, str], list[tuple[int, int]]] = {}
    for key, ranges in pieces.items():
        k = (_id(key[0]), _id(key[1]))
        cuts[k] = _check_ranges(k, ranges, len(recordings.trial(*k).t))
    if not cuts:
        return recordings
    keys = recordings.keys()
    existing = set(keys)
    t_all = recordings.frame["t"].to_numpy(dtype=float)
    trials = recordings.trials.set_index(["participant", "trial"], drop=False)
    row_blocks: list[np.ndarray] = []
    labels: list[str] = []
    table: list[dict] = []
    new_rows: dict[tuple[str, str], np.ndarray] = {}
    resampled: dict[tuple[str, str], Trial] = {}
    repaired: dict[tuple[str, str], np.ndarray] = {}
    events = [] if recordings.events is None else [recordings.events.iloc[:0]]
    at = 0

    def add(key: tuple[str, str], rows: np.ndarray, row: dict) -> None:
        nonlocal at
        rows = np.asarray(rows, dtype=np.int64)
        row_blocks.append(rows)
        labels.extend([key[1]] * len(rows))
        new_rows[key] = np.arange(at, at + len(rows), dtype=np.int64)
        at += len(rows)
        table.append(row)

    for key in keys:
        info = trials.loc[key].to_dict() if key in trials.index else {}
        rows = recordings._rows[key]
        if key not in cuts:
            add(key, rows, info)
            if key in recordings._resampled:
                resampled[key] = recordings._resampled[key]
            if key in recordings._repaired:
                repaired[key] = recordings._repaired[key]
            if recordings.events is not None:
                ev = recordings.events
                events.append(ev[(ev["participant"] == key[0]) & (ev["trial"] == key[1])])
            continue
        ranges = cuts[key]
        tr = recordings.trial(*key)
        is_res = recordings.is_resampled(*key)
        mask = recordings.repaired_mask(*key)
        by_piece = _row_pieces(rows, t_all[rows], tr, ranges, is_res)
        offsets = {int(r): i for i, r in enumerate(rows)}
        for k, ((a, b), prow) in enumerate(zip(ranges, by_piece), start=1):
            new = (key[0], piece_name(key[1], k))
            if new in existing:
                raise ValueError(f"cannot cut trial {key[1]!r} of participant {key[0]!r}: trial {new[1]!r} exists")
            n_rep = int(mask[a:b].sum())
            first_off = offsets[int(prow[0])] if len(prow) else 0
            short = b - a < MIN_SAMPLES
            add(
                new,
                prow,
                {
                    **info,
                    "trial": new[1],
                    "n_samples": len(prow),
                    "first_line": int(info.get("first_line", 0)) + first_off,
                    "status": "invalid" if short else info.get("status", "ok"),
                    "reason": (
                        f"too few samples in this piece ({b - a}; need at least {MIN_SAMPLES})"
                        if short
                        else info.get("reason", "")
                    ),
                    "repairs": _repairs_text(
                        n_rep,
                        int(mask.sum()),
                        key[1],
                        str(info.get("repairs", "")),
                        k == 1,
                        int(info.get("n_dropped", 0)),
                    ),
                    "n_repaired": n_rep,
                    "n_dropped": int(info.get("n_dropped", 0)) if k == 1 else 0,
                },
            )
            if is_res:
                resampled[new] = Trial(new[0], new[1], tr.t[a:b], tr.pos[a:b], tr.contact[a:b])
            if n_rep:
                repaired[new] = mask[a:b].copy()
        if recordings.events is not None:
            events.append(_piece_events(recordings.events, key, tr, ranges, recordings.fs))
        existing.update((key[0], piece_name(key[1], k)) for k in range(1, len(ranges) + 1))

    order = np.concatenate(row_blocks) if row_blocks else np.array([], dtype=np.int64)
    frame = recordings.frame.take(order).reset_index(drop=True)
    names = list(dict.fromkeys(labels))
    frame["trial"] = pd.Categorical(labels, categories=names)
    if isinstance(frame["participant"].dtype, pd.CategoricalDtype):
        frame["participant"] = frame["participant"].cat.remove_unused_categories()
    trials_out = pd.DataFrame(table, columns=list(recordings.trials.columns)).reset_index(drop=True)
    for c in recordings.trials.columns:
        if c in ("n_samples", "first_line", "n_repaired", "n_dropped"):
            trials_out[c] = trials_out[c].fillna(0).astype(np.int64)
    ev_out = None
    if recordings.events is not None:
        ev_out = pd.concat(events, ignore_index=True)[list(EVENT_COLUMNS)]
    return Recordings(
        frame=frame,
        trials=trials_out,
        fs=recordings.fs,
        source=recordings.source,
        _rows=new_rows,
        _resampled=resampled,
        _repaired=repaired,
        notes=recordings.notes,
        skipped=recordings.skipped,
        events=ev_out,
    )
