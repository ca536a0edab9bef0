"""Several movements in one recording: the recording cut into one trial per movement.

The paper's recordings hold one approach each; a lab's often hold several (a block of reaches, the pushes
of a wheelchair's hand rim, a task repeated without stopping the capture). :func:`split_movements` cuts
each such recording into pieces, one movement each, that the segmentation rules
(:mod:`skilllib.features._rules`) then treat as trials of their own.

**Rules** (speed from :func:`skilllib.features.velocity` of the whole trial's positions, as recorded or as
repaired and resampled):

* **Movements.** The maximal runs of samples faster than the start threshold (``StartRule.threshold``:
  absolute in m/s; a fraction of the recording's own peak speed), merged when the rest between two of
  them is shorter than ``min_rest_s`` (default ``hold_s``: a brief dip is not a rest). A run shorter than
  :data:`MIN_MOVEMENT_SAMPLES` samples, or whose peak speed is below :data:`NOISE_FACTOR` times the
  threshold, is noise, not a movement.
* **Cuts.** The recording is cut at the middle of every rest between two movements (the rest's middle
  sample starts the next piece), so each piece holds rest before and after its movement; the first piece
  starts at the first sample, the last ends at the last.
* **Events.** With a start rule ``event:LABEL`` the recording is cut at those events instead: piece
  ``k`` from the first sample at or after the ``k``-th event to the sample before the next one's (the
  samples before the first event are in no piece). With an end rule ``event:LABEL`` (and a speed start):
  piece ``k`` from the sample after the previous end event's sample (the first piece from the first
  sample) to the ``k``-th end event's sample, which it holds, so that the end rule finds its event (the
  samples after the last end event are in no piece). Labels are matched as written, else without case.
* **Names.** Every piece of a split recording is a trial ``f"{trial}-{k}"`` (``k`` = 1, 2, ... in time
  order) of the same participant, even when there is one piece; a recording in which no movement (no
  event) is found stays one trial with its own id, for its segmentation to say why. Invalid trials are
  kept as they are. Samples, repairs and events go with their pieces
  (:func:`skilllib.recordings.cut_trials`), and the recordings' ``notes`` gain one line saying how many
  recordings were split into how many movements.

The offset rule (``EndRule("offset")``) looks for ``hold_s`` of rest after the movement; a piece cut
from a rest shorter than twice ``hold_s`` holds less than that after its movement: give ``min_rest_s``
of at least ``2 * hold_s`` when the movements are separated by short rests.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..recordings import Recordings, cut_trials
from ._rules import DEFAULT_HOLD_S, PAPER_START, EndRule, StartRule
from ._segmentation import velocity

MIN_MOVEMENT_SAMPLES = 3  #: samples: a faster run shorter than this is noise
NOISE_FACTOR = 2.0  #: a run whose peak speed is below this times the threshold is noise
EVENT_TOLERANCE = 0.01  #: fraction of a sampling interval by which a sample may precede an event and count as at it


def find_movements(
    speed: np.ndarray, threshold: float, fs: float, *, min_rest_s: float = DEFAULT_HOLD_S
) -> list[tuple[int, int]]:
    """The movements of a speed trace (module docstring: Movements).

    Parameters
    ----------
    speed : numpy.ndarray, shape (N,)
        The speed (m/s).
    threshold : float
        The speed above which a sample moves (m/s).
    fs : float
        The sampling rate (Hz).
    min_rest_s : float
        The shortest rest between two movements (s); shorter rests are merged into the movement.

    Returns
    -------
    list of tuple of (int, int)
        ``(start, stop)`` per movement (samples): its first sample faster than the threshold and the
        sample after its last, in time order.
    """
    fast = np.asarray(speed, dtype=float) > threshold
    if not fast.any():
        return []
    edges = np.diff(np.concatenate([[False], fast, [False]]).astype(np.int8))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    runs = [[int(starts[0]), int(stops[0])]]
    for a, b in zip(starts[1:], stops[1:]):
        if (a - runs[-1][1]) / fs < min_rest_s:
            runs[-1][1] = int(b)
        else:
            runs.append([int(a), int(b)])
    speed = np.asarray(speed, dtype=float)
    return [
        (a, b) for a, b in runs if b - a >= MIN_MOVEMENT_SAMPLES and np.nanmax(speed[a:b]) >= NOISE_FACTOR * threshold
    ]


def movement_pieces(movements: list[tuple[int, int]], n: int) -> list[tuple[int, int]]:
    """The pieces a recording of ``n`` samples is cut into around its movements (module docstring: Cuts).

    Parameters
    ----------
    movements : list of tuple of (int, int)
        ``(start, stop)`` per movement (samples), in time order (:func:`find_movements`).
    n : int
        The recording's number of samples (samples).

    Returns
    -------
    list of tuple of (int, int)
        ``(start, stop)`` per piece (samples; ``stop`` excluded), covering ``0 .. n - 1``; empty when
        there is no movement.
    """
    if not movements:
        return []
    cuts = [(stop + nxt) // 2 for (_, stop), (nxt, _) in zip(movements[:-1], movements[1:])]
    bounds = [0, *cuts, n]
    return list(zip(bounds[:-1], bounds[1:]))


def _event_samples(times: np.ndarray, t: np.ndarray, fs: float) -> np.ndarray:
    """The first sample at or after each event (within the tolerance), distinct, inside the recording."""
    tol = EVENT_TOLERANCE / fs if np.isfinite(fs) and fs > 0 else 0.0
    at = np.searchsorted(t, np.asarray(times, dtype=float) - tol, side="left")
    return np.unique(at[at < len(t)])


def _label_times(events: dict[str, np.ndarray], label: str) -> np.ndarray:
    if label in events:
        return events[label]
    hits = [v for k, v in events.items() if k.strip().lower() == label.strip().lower()]
    return np.sort(np.concatenate(hits)) if hits else np.array([])


def event_pieces(samples: np.ndarray, n: int, *, at_start: bool) -> list[tuple[int, int]]:
    """The pieces cut at event samples (module docstring: Events).

    Parameters
    ----------
    samples : numpy.ndarray
        The events' samples (samples), increasing, each below ``n``.
    n : int
        The recording's number of samples (samples).
    at_start : bool
        True: start events (each piece starts at one); False: end events (each piece ends with one,
        dimensionless).

    Returns
    -------
    list of tuple of (int, int)
        ``(start, stop)`` per piece (samples; ``stop`` excluded); empty without events.
    """
    s = [int(v) for v in samples]
    if not s:
        return []
    if at_start:
        return list(zip(s, [*s[1:], n]))
    return list(zip([0, *(v + 1 for v in s[:-1])], [v + 1 for v in s]))


def split_movements(
    recordings: Recordings,
    start: StartRule = PAPER_START,
    end: EndRule = EndRule("offset"),  # noqa: B008 (a frozen dataclass: one shared value is safe)
    *,
    hold_s: float = DEFAULT_HOLD_S,
    min_rest_s: float | None = None,
) -> Recordings:
    """Each recording cut into one trial per movement (rules: module docstring).

    Parameters
    ----------
    recordings : Recordings
        The recordings (t in s, positions in m); only trials with status ``ok`` are split.
    start : StartRule
        The start rule: its speed threshold (m/s, or a fraction of each recording's peak speed, dimensionless)
        finds the movements; ``event:LABEL``: cut at those events.
    end : EndRule
        The end rule; ``event:LABEL`` (with a speed start): cut after those events. Its other kinds do not
        change the cuts.
    hold_s : float
        The offset hold (s): by default also the shortest rest between two movements.
    min_rest_s : float or None
        The shortest rest between two movements (s); shorter rests are merged into the movement; None:
        ``hold_s``.

    Returns
    -------
    Recordings
        The recordings with every split recording's movements as trials ``f"{trial}-{k}"`` (t in s,
        positions in m, fs in Hz); ``notes`` gain a line on the split.
    """
    rest = hold_s if min_rest_s is None else min_rest_s
    if not (np.isfinite(rest) and rest >= 0):
        raise ValueError(f"the shortest rest must be a time of at least 0 s, got {rest!r}")
    fs = recordings.fs
    pieces: dict[tuple[str, str], list[tuple[int, int]]] = {}
    ok = recordings.trials["status"].to_numpy() == "ok"
    n_ok = 0
    for key, usable in zip(recordings.keys(), ok):
        if not usable:
            continue
        n_ok += 1
        tr = recordings.trial(*key)
        n = len(tr.t)
        if start.kind == "event" or end.kind == "event":
            label = start.label if start.kind == "event" else end.label
            times = _label_times(recordings.trial_events(*key), label)
            cut = event_pieces(_event_samples(times, tr.t, fs), n, at_start=start.kind == "event")
        else:
            if n < 2:
                continue
            speed = np.linalg.norm(velocity(tr.pos, fs), axis=1)
            threshold = start.threshold.value(np.nanmax(speed))
            cut = movement_pieces(find_movements(speed, threshold, fs, min_rest_s=rest), n)
        if cut:
            pieces[key] = cut
    out = cut_trials(recordings, pieces)
    how = (
        f"at {start.text()} events"
        if start.kind == "event"
        else f"after {end.text()} events"
        if end.kind == "event"
        else f"at rests between runs faster than {start.threshold.text()}"
        f"{' m/s' if start.threshold.fraction is None else ' of the peak speed'} of at least {rest:g} s"
    )
    n_pieces = sum(len(v) for v in pieces.values())
    note = (
        f"split_movements: {len(pieces)} of {n_ok} usable recording(s) split into {n_pieces} movement(s), "
        f"cut {how}" + (f"; {n_ok - len(pieces)} with no movement found kept whole" if n_ok > len(pieces) else "")
    )
    return replace(out, notes=(*out.notes, note))
