"""Defects that real exports have, found and repaired in one trial's samples, every change counted.

Pure functions on one trial's arrays: ``t`` (N,) in s, ``pos`` (N, 3) in m (NaN where the tracker gave
no position) and ``contact`` (N,) bool. :func:`repair_trial` applies the rules in this order and returns
a :class:`Repair` (the repaired samples, a per-sample ``repaired`` mask, the counts and their text):

1. **Missing ends.** Leading and trailing samples without a position (NaN) are trimmed (never
   extrapolated).
2. **Stale or duplicated leading frames** (:func:`stale_leading`). The first sample is *stale* when it
   is at least :data:`STALE_MIN_STEP_M` from the second and the speed that step implies is more than
   :data:`STALE_SPEED_RATIO` times the median speed of the next :data:`STALE_WINDOW` steps: a recording
   starts with the hand at rest or moving slowly, and a hand does not stop within one frame from several
   times the speed it has over the frames that follow. After a stale frame, a sample exactly equal to
   the next is a *duplicate* of the tracker's start-up (an exact repeat alone at the start is left: a
   tracker at rest whose positions are rounded, to 0.01 mm say, repeats them). Both are dropped, at most
   :data:`MAX_STALE_FRAMES` in all.
3. **Frozen positions** (:func:`frozen_samples`). A run of consecutive samples with exactly the same
   (x, y, z) while the hand moved (the positions before and after the run imply a speed above
   :data:`FROZEN_MIN_SPEED`, and either the hand moved into the run or the tracker caught up when it came
   back: a step out of the run of at least :data:`MIN_JUMP_M` and :data:`REACQUIRE_RATIO` times faster
   than the steps after it) is a frozen tracker (occlusion): the repeats (not the run's first sample, the
   last real position) are treated as missing. Exact repeats at rest are left as recorded (they change no
   position by more than the tracker's resolution), and so is a run the hand neither moved into nor
   jumped out of (a noise-free or coarsely quantised recording resting before its movement starts).
4. **Single-frame jumps** (:func:`jump_samples`). A sample whose deviation from the line through its two
   neighbours implies an acceleration above :data:`MAX_ACCELERATION` and that deviates by more than
   :data:`MIN_JUMP_M` and :data:`JUMP_NOISE_FACTOR` times the trial's own noise level is treated as
   missing.
5. **Gaps** (:func:`gap_runs`): runs of missing samples. A gap of at most ``max_gap_s`` (default
   :data:`MAX_GAP_S`) between recorded samples is filled from the recorded samples on both sides
   (:func:`fill_gap`: a cubic through up to :data:`FILL_NEIGHBOURS` samples each side, linear when a side
   has only one). A longer gap
   - after the first contact sample (a part the analysis never reads) cuts the trial: the samples before
     the gap are kept;
   - during the rest before the movement (every recorded sample before the gap and the first
     :data:`MIN_REST_S` after it move slower than :data:`REST_SPEED`) drops the samples up to the gap:
     the trial starts after it, still at rest;
   - anywhere else in the analysed part makes the trial invalid (``reason``).

Every sample changed is counted in :class:`Repair` and named in its :meth:`Repair.describe` text, which
:mod:`skilllib.recordings` keeps as the trial's ``repairs``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

MAX_GAP_S = 0.1  #: s; longer gaps of missing positions are not filled (6 frames at 60 Hz, 8 at 85 Hz)
FILL_METHODS = ("cubic", "linear")  #: how short gaps are filled (:func:`fill_gap`)
FILL_NEIGHBOURS = 3  #: recorded samples used on each side of a gap by the cubic fill (samples)
STALE_MIN_STEP_M = 0.001  #: m; a first step shorter than this is never called stale (tracker noise is ~0.1 mm)
STALE_SPEED_RATIO = 5.0  #: dimensionless; the first step's speed over the median speed of the next steps
STALE_WINDOW = 5  #: steps after the first that give the speed it is compared with (samples)
MAX_STALE_FRAMES = 3  #: at most this many leading frames are dropped as stale or duplicated (samples)
FROZEN_MIN_SPEED = 0.02  #: m/s; exact repeats while the hand moves faster than this are a frozen tracker
REACQUIRE_RATIO = 3.0  #: dimensionless; a step out of a run this much faster than the next steps: caught up
MAX_ACCELERATION = 200.0  #: m/s^2; no hand accelerates this much (reaching peaks at 5-20 m/s^2)
MIN_JUMP_M = 0.003  #: m; a jump deviates from its neighbours' line by more than this
JUMP_NOISE_FACTOR = 10.0  #: dimensionless; ... and by more than this many times the trial's noise level
MAX_JUMP_PASSES = 2  #: passes of the jump rule (a jump next to a jump shows after the first is replaced)
REST_SPEED = 0.05  #: m/s; slower is rest (the paper's onset speed, :mod:`skilllib.features`)
MIN_REST_S = 0.1  #: s of rest that must remain after a long gap in the rest before the movement
MAX_SPAN_M = 2.0  #: m; a trial spanning more is not in metres (or a glitch): not repaired (as MAX_RANGE_M)


@dataclass(frozen=True)
class Repair:
    """One trial's samples after :func:`repair_trial`, and what was changed.

    Attributes
    ----------
    t : numpy.ndarray
        Time stamps of the kept samples (s).
    pos : numpy.ndarray
        Positions (m), (N, 3), with the repaired samples interpolated.
    contact : numpy.ndarray
        Contact flags of the kept samples (bool, dimensionless).
    repaired : numpy.ndarray
        True where the position was replaced by interpolation (bool, dimensionless; aligned with ``t``).
    reason : str
        Why the trial is unusable after all ('' when it is usable; text).
    n_stale, n_duplicate : int
        Leading frames dropped as stale, and as duplicates of the next (samples).
    n_frozen, n_jumps, n_missing : int
        Samples replaced by interpolation: frozen repeats, single-frame jumps, NaN positions (samples).
    n_trimmed : int
        Leading and trailing samples without a position, trimmed (samples).
    n_cut : int
        Samples from a long gap after contact to the end, cut off (samples).
    n_rest_dropped : int
        Samples before a long gap in the rest before the movement, dropped (samples).
    gaps : list of tuple
        ``(n, t_start, filled, place)`` per gap: its samples, the time of its first sample (s), whether
        filled, where its first sample is (``"line 47"``; text).
    n_first : int
        The index of the first kept sample in the given arrays (samples).
    """

    t: np.ndarray
    pos: np.ndarray
    contact: np.ndarray
    repaired: np.ndarray
    reason: str = ""
    n_stale: int = 0
    n_duplicate: int = 0
    n_frozen: int = 0
    n_jumps: int = 0
    n_missing: int = 0
    n_trimmed: int = 0
    n_cut: int = 0
    n_rest_dropped: int = 0
    gaps: list = field(default_factory=list)
    n_first: int = 0

    @property
    def n_repaired(self) -> int:
        """Samples whose position was replaced by interpolation (samples)."""
        return int(self.repaired.sum())

    @property
    def n_dropped(self) -> int:
        """Samples removed: stale, duplicated, trimmed, cut or dropped before a gap (samples)."""
        return self.n_stale + self.n_duplicate + self.n_trimmed + self.n_cut + self.n_rest_dropped

    @property
    def changed(self) -> bool:
        """Whether any sample was changed or removed (dimensionless)."""
        return bool(self.n_repaired or self.n_dropped or self.reason)

    def describe(self) -> str:
        """The repairs as text ('' when none): ``"1 stale leading frame dropped; 3 frozen samples replaced
        by interpolation; gap of 4 samples filled at 1.23 s"``."""
        parts = []
        lead = [
            f"{n} {what} leading frame{'s' * (n != 1)}"
            for n, what in ((self.n_stale, "stale"), (self.n_duplicate, "duplicated"))
            if n
        ]
        if lead:
            parts.append(" and ".join(lead) + " dropped")
        if self.n_trimmed:
            parts.append(f"{_n(self.n_trimmed, 'sample')} without a position trimmed at the ends")
        repl = [
            _n(n, what)
            for n, what in (
                (self.n_frozen, "frozen sample"),
                (self.n_jumps, "jump"),
                (self.n_missing, "missing sample"),
            )
            if n
        ]
        if repl:
            parts.append(", ".join(repl) + " replaced by interpolation")
        for n, t0, filled, *place in self.gaps:
            if filled:
                at = f" ({place[0]})" if place else ""
                parts.append(f"gap of {_n(n, 'sample')} filled at {t0:.3f} s{at}")
        if self.n_rest_dropped:
            parts.append(f"{_n(self.n_rest_dropped, 'sample')} before a long gap at rest dropped")
        if self.n_cut:
            parts.append(f"{_n(self.n_cut, 'sample')} from a long gap after contact on cut off")
        return "; ".join(parts)


def _n(n: int, what: str) -> str:
    return f"{n} {what}{'s' * (n != 1)}"


def _speeds(t: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """Speed of each step between consecutive samples (m/s), (N - 1,)."""
    return np.linalg.norm(np.diff(pos, axis=0), axis=1) / np.diff(t)


def stale_leading(t: np.ndarray, pos: np.ndarray) -> tuple[int, int]:
    """How many leading frames are stale and how many duplicated (rule 2 of the module).

    Parameters
    ----------
    t : numpy.ndarray
        Time stamps (s), (N,), increasing.
    pos : numpy.ndarray
        Positions (m), (N, 3), without NaN at the start.

    Returns
    -------
    n_stale : int
        Leading frames to drop as stale (samples).
    n_duplicate : int
        Leading frames to drop as exact duplicates of the next, after a stale one (samples).
    """
    stale = dup = 0
    k = 0
    while stale + dup < MAX_STALE_FRAMES and len(t) - k > STALE_WINDOW + 2:
        p = pos[k : k + STALE_WINDOW + 2]
        if np.isnan(p).any():
            break
        if (p[0] == p[1]).all():
            if not stale:  # alone, a repeat at rest: a quantised tracker (0.01 mm) repeats positions
                break
            dup += 1
        else:
            v = _speeds(t[k : k + STALE_WINDOW + 2], p)
            step = float(np.linalg.norm(p[1] - p[0]))
            if dup or step < STALE_MIN_STEP_M or not v[0] > STALE_SPEED_RATIO * np.median(v[1:]):
                break
            stale += 1
        k += 1
    return stale, dup


def frozen_samples(t: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """The frozen repeats (rule 3 of the module): True for each repeat of a run of exactly equal positions
    across which the hand moved faster than :data:`FROZEN_MIN_SPEED`.

    Parameters
    ----------
    t : numpy.ndarray
        Time stamps (s), (N,), increasing.
    pos : numpy.ndarray
        Positions (m), (N, 3); NaN samples are never frozen, and the speed across a run is measured
        between the nearest recorded samples either side (a jump already set to NaN is skipped).

    Returns
    -------
    numpy.ndarray
        Bool (N,): the repeats (each run's first sample, the last real position, is False).
    """
    n = len(t)
    out = np.zeros(n, dtype=bool)
    same = np.zeros(n, dtype=bool)
    same[1:] = (pos[1:] == pos[:-1]).all(axis=1)
    if not same.any():
        return out
    have = np.flatnonzero(~np.isnan(pos).any(axis=1))
    for s, e in gap_runs(same):  # repeats s..e-1, run from s-1
        # the recorded samples either side of the run (or its first, at the start), skipping missing ones
        before, after = have[have <= s - 2], have[have >= e]
        i = int(before[-1]) if before.size else s - 1
        j = int(after[0]) if after.size else e - 1
        speed = 0.0
        if j > i:
            speed = float(np.linalg.norm(pos[j] - pos[i]) / (t[j] - t[i]))
        # the hand moved into the run: a still hand whose samples repeat exactly (a noise-free or coarsely
        # quantised recording at rest, a run from the first sample) is rest, not a frozen tracker
        moving_in = (
            s >= 1
            and before.size >= 1
            and float(np.linalg.norm(pos[s - 1] - pos[before[-1]]) / (t[s - 1] - t[before[-1]])) > FROZEN_MIN_SPEED
        )
        # or the tracker caught up when it came back: the step out of the run is a jump (at least
        # MIN_JUMP_M, and faster than REACQUIRE_RATIO x the steps that follow it), the hand having moved on
        caught_up = False
        if after.size >= 2 and e - 1 >= 0:
            k = int(after[0])
            out_step = float(np.linalg.norm(pos[k] - pos[e - 1]))
            nxt = after[1 : 1 + STALE_WINDOW]
            follow = np.linalg.norm(np.diff(pos[np.r_[k, nxt]], axis=0), axis=1) / np.diff(t[np.r_[k, nxt]])
            caught_up = out_step > MIN_JUMP_M and out_step / (t[k] - t[e - 1]) > REACQUIRE_RATIO * float(
                np.median(follow)
            )
        if speed > FROZEN_MIN_SPEED and (moving_in or caught_up):
            out[s:e] = True
    return out


def jump_samples(t: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """The single-frame jumps (rule 4 of the module) among the samples with a position.

    A sample k is a jump when its deviation ``d`` from the line through its recorded neighbours implies
    an acceleration ``2 d / (dt1 dt2)`` above :data:`MAX_ACCELERATION`, ``d`` exceeds :data:`MIN_JUMP_M`
    and :data:`JUMP_NOISE_FACTOR` times the trial's noise level (1.4826 times the median deviation), and
    ``d`` is the largest of it and its neighbours' (the neighbours of a jump deviate by half as much), and
    the positions come back after it (the neighbours' second differences point the other way, each at
    least a quarter as large: a step, as at an abrupt contact, is not a jump).

    Parameters
    ----------
    t : numpy.ndarray
        Time stamps (s), (N,), increasing.
    pos : numpy.ndarray
        Positions (m), (N, 3); NaN samples are skipped (the neighbours are the nearest recorded samples).

    Returns
    -------
    numpy.ndarray
        Bool (N,): True at the jumps.
    """
    out = np.zeros(len(t), dtype=bool)
    for _ in range(MAX_JUMP_PASSES):
        idx = np.flatnonzero(~np.isnan(pos).any(axis=1) & ~out)
        if len(idx) < 5:
            break
        tt, pp = t[idx], pos[idx]
        dt1, dt2 = tt[1:-1] - tt[:-2], tt[2:] - tt[1:-1]
        line = pp[:-2] + (pp[2:] - pp[:-2]) * (dt1 / (dt1 + dt2))[:, None]
        dev = np.linalg.norm(pp[1:-1] - line, axis=1)
        acc = 2 * dev / (dt1 * dt2)
        noise = 1.4826 * float(np.median(dev))
        big = (acc > MAX_ACCELERATION) & (dev > MIN_JUMP_M) & (dev > JUMP_NOISE_FACTOR * noise)
        padded = np.concatenate([[0.0], dev, [0.0]])
        big &= (dev >= padded[:-2]) & (dev >= padded[2:])
        # a spike leaves and comes back: its neighbours bend the other way, each by at least a quarter as
        # much (second differences 1, -2, 1); a step (a contact, a marker swapped for good) bends one way
        # and then back at the next sample only, and is no single-frame jump
        bend = pp[2:] - 2 * pp[1:-1] + pp[:-2]  # (M, 3), aligned with dev
        size = np.linalg.norm(bend, axis=1)
        back = np.zeros(len(dev), dtype=bool)
        if len(dev) >= 3:
            mid = bend[1:-1]
            prev_ok = ((bend[:-2] * mid).sum(axis=1) < 0) & (size[:-2] >= 0.25 * size[1:-1])
            next_ok = ((bend[2:] * mid).sum(axis=1) < 0) & (size[2:] >= 0.25 * size[1:-1])
            back[1:-1] = prev_ok & next_ok
        big &= back
        if not big.any():
            break
        out[idx[1:-1][big]] = True
    return out


def gap_runs(missing: np.ndarray) -> list[tuple[int, int]]:
    """The runs of True in ``missing`` as ``(start, stop)`` (stop exclusive; samples).

    Parameters
    ----------
    missing : numpy.ndarray
        Bool (N,): samples without a usable position.

    Returns
    -------
    list of tuple of int
        The runs, in order (samples).
    """
    edges = np.diff(np.concatenate([[0], missing.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1).tolist(), np.flatnonzero(edges == -1).tolist()))


def fill_gap(t: np.ndarray, pos: np.ndarray, missing: np.ndarray, start: int, stop: int, method: str = "cubic") -> None:
    """Fill ``pos[start:stop]`` in place from the recorded samples on both sides (never extrapolates).

    ``"cubic"``: a cubic spline (not-a-knot) in time through up to :data:`FILL_NEIGHBOURS` recorded
    samples on each side, when each side has at least two; else (or ``"linear"``) the line between the
    two nearest recorded samples.

    Parameters
    ----------
    t : numpy.ndarray
        Time stamps (s), (N,), increasing.
    pos : numpy.ndarray
        Positions (m), (N, 3); changed in place.
    missing : numpy.ndarray
        Bool (N,): samples without a usable position (the gap and any other).
    start, stop : int
        The gap, samples ``start .. stop - 1``, with recorded samples before and after (samples).
    method : str
        ``"cubic"`` or ``"linear"`` (text).
    """
    left = np.flatnonzero(~missing[:start])[-FILL_NEIGHBOURS:]
    right = stop + np.flatnonzero(~missing[stop:])[:FILL_NEIGHBOURS]
    if method == "cubic" and len(left) >= 2 and len(right) >= 2:
        from scipy.interpolate import CubicSpline

        k = np.concatenate([left, right])
        pos[start:stop] = CubicSpline(t[k], pos[k], axis=0)(t[start:stop])
        return
    a, b = int(left[-1]), int(right[0])
    w = ((t[start:stop] - t[a]) / (t[b] - t[a]))[:, None]
    pos[start:stop] = pos[a] + w * (pos[b] - pos[a])


def _at_rest(t: np.ndarray, pos: np.ndarray) -> bool:
    """Whether the recorded samples move slower than :data:`REST_SPEED` throughout (dimensionless)."""
    ok = ~np.isnan(pos).any(axis=1)
    if ok.sum() < 2:
        return ok.sum() == 1
    return bool((_speeds(t[ok], pos[ok]) < REST_SPEED).all())


def repair_trial(
    t: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray,
    *,
    max_gap_s: float = MAX_GAP_S,
    fill: str = "cubic",
    where: Callable[[int], str] | None = None,
) -> Repair:
    """Find and repair one trial's defects (the module's rules, in its order); every change counted.

    Parameters
    ----------
    t : numpy.ndarray
        Time stamps (s), (N,), increasing, no NaN.
    pos : numpy.ndarray
        Positions (m), (N, 3), NaN where missing (not changed).
    contact : numpy.ndarray
        Contact flags (bool, dimensionless), (N,).
    max_gap_s : float
        The longest gap filled (s), a gap's length being its missing samples times the trial's median
        interval (default :data:`MAX_GAP_S`: 6 samples at 60 Hz, 8 at 85 Hz).
    fill : str
        ``"cubic"`` or ``"linear"`` (text; :func:`fill_gap`).
    where : callable or None
        ``where(k)`` names sample k of the given arrays in a reason (``"line 47"``; text); None: ``"sample
        k + 1"``.

    Returns
    -------
    Repair
        The repaired samples (s, m, bool), the repaired mask and the counts.
    """
    if fill not in FILL_METHODS:
        raise ValueError(f"fill must be one of {', '.join(FILL_METHODS)}, got {fill!r}")
    t = np.asarray(t, dtype=float)
    pos = np.array(pos, dtype=float)
    contact = np.asarray(contact, dtype=bool)
    name = where or (lambda k: f"sample {k + 1}")
    raw = pos.copy()
    counts: dict = {}
    have = ~np.isnan(pos).any(axis=1)
    if not have.any():
        return Repair(t[:0], pos[:0], contact[:0], np.zeros(0, bool), "no sample has a position (x, y, z all NaN)")
    a, b = int(np.argmax(have)), len(have) - int(np.argmax(have[::-1]))
    counts["n_trimmed"] = a + len(t) - b
    t, pos, contact = t[a:b], pos[a:b], contact[a:b]
    stale, dup = stale_leading(t, pos)
    counts["n_stale"], counts["n_duplicate"] = stale, dup
    t, pos, contact = t[stale + dup :], pos[stale + dup :], contact[stale + dup :]
    nan = np.isnan(pos).any(axis=1)
    repeat = np.zeros(len(t), dtype=bool)
    repeat[1:] = (pos[1:] == pos[:-1]).all(axis=1)
    # a spike between still samples must not make them look frozen (a repeat is never the spike)
    first_jumps = jump_samples(t, pos) & ~repeat
    frozen = frozen_samples(t, np.where(first_jumps[:, None], np.nan, pos))
    pos[frozen] = np.nan
    jumps = jump_samples(t, pos)  # again, without the frozen runs (whose end can look like a jump)
    pos[jumps] = np.nan
    missing = frozen | nan | jumps
    dt = float(np.median(np.diff(t))) if len(t) > 1 else np.nan
    hits = np.flatnonzero(contact)
    first_contact = int(hits[0]) if hits.size else len(t)
    gaps: list[tuple[int, int]] = []
    reason = ""
    start, stop = 0, len(t)
    for s, e in gap_runs(missing):
        if e == len(t):  # frozen up to the end: trimmed like trailing NaN
            stop = s
            counts["n_trimmed"] += e - s
            break
        if (e - s) * dt <= max_gap_s:
            gaps.append((s, e))
            continue
        if s >= first_contact:
            stop = s
            counts["n_cut"] = len(t) - s
            break
        if _at_rest(t[start:s], pos[start:s]):
            after = np.flatnonzero((t >= t[e]) & (t <= t[e] + MIN_REST_S))
            if t[-1] - t[e] >= MIN_REST_S and not missing[after].any() and _at_rest(t[after], pos[after]):
                start, gaps = e, []
                continue
        k = a + stale + dup + s  # the gap's first sample in the given arrays
        nan_cols = [c for j, c in enumerate("xyz") if np.isnan(raw[k, j])]
        what = (
            f"{nan_cols[0]} is missing (NaN) at {name(k)}"
            if nan_cols
            else f"positions {'frozen (exactly repeated)' if frozen[s] else 'jump'} at {name(k)}"
        )
        part = "before contact" if hits.size else "in a trial without contact (all of it is analysed)"
        reason = (
            f"{what}: a gap of {e - s} samples ({(e - s) * dt:.3f} s) {part}, longer than the {max_gap_s:g} s "
            f"filled (--max-gap)"
        )
        break
    if reason:
        start, stop = 0, len(t)
    counts["n_rest_dropped"] = start
    repaired = np.zeros(len(t), dtype=bool)
    described = []
    if not reason:
        for s, e in gaps:
            fill_gap(t, pos, missing, s, e, fill)
            repaired[s:e] = True
            if nan[s:e].any():
                described.append((e - s, float(t[s]), True, name(a + stale + dup + s)))
    for key, flag in (("n_frozen", frozen), ("n_jumps", jumps), ("n_missing", nan)):
        counts[key] = int((flag & repaired).sum())
    keep = slice(start, stop)
    first = a + stale + dup + start
    return Repair(t[keep], pos[keep], contact[keep], repaired[keep], reason, gaps=described, n_first=first, **counts)


def repair_trials(
    t: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray,
    trial_of_row: np.ndarray,
    rows: list[np.ndarray],
    which: np.ndarray,
    *,
    max_gap_s: float = MAX_GAP_S,
    fill: str = "cubic",
    where: Callable[[int], str] | None = None,
    max_span_m: float = MAX_SPAN_M,
) -> dict[int, Repair]:
    """:func:`repair_trial` of the ``which`` trials that show a sign of a defect, over flat arrays.

    Flags over all rows at once find the suspects (a NaN position, an exact repeat, a step or a deviation
    that could be a jump, a first step of at least :data:`STALE_MIN_STEP_M`); only those are looked at one
    by one. The flags are a superset of what the rules find, so a trial not flagged needs no repair.

    Parameters
    ----------
    t : numpy.ndarray
        Time stamps (s), (R,).
    pos : numpy.ndarray
        Positions (m), (R, 3).
    contact : numpy.ndarray
        Contact flags (0/1 or bool), (R,).
    trial_of_row : numpy.ndarray
        The trial number of each row (dimensionless), (R,).
    rows : list of numpy.ndarray
        ``rows[i]``: the rows of trial i, ascending and contiguous for the ``which`` trials.
    which : numpy.ndarray
        Bool per trial: the trials to look at (usable so far).
    max_gap_s : float
        The longest gap filled (s).
    fill : str
        ``"cubic"`` or ``"linear"`` (text).
    where : callable or None
        ``where(r)`` names row r in a reason (text).
    max_span_m : float
        A trial spanning more than this is not repaired (m): :data:`MAX_SPAN_M` when nothing states the
        unit (such a trial is probably not in metres), larger when a header or ``--units`` states it.

    Returns
    -------
    dict of int to Repair
        The trials changed (or made invalid, ``reason``) by a repair, by trial number.
    """
    if fill not in FILL_METHODS:
        raise ValueError(f"fill must be one of {', '.join(FILL_METHODS)}, got {fill!r}")
    n = len(rows)
    if not len(t):
        return {}
    nan = np.isnan(pos).any(axis=1)
    same = np.zeros(len(t), dtype=bool)
    same[1:] = trial_of_row[1:] == trial_of_row[:-1]
    suspect = np.bincount(trial_of_row[nan], minlength=n) > 0
    repeat = same.copy()
    repeat[1:] &= (pos[1:] == pos[:-1]).all(axis=1)
    suspect |= np.bincount(trial_of_row[repeat], minlength=n) > 0
    inner = np.zeros(len(t), dtype=bool)
    inner[1:-1] = same[1:-1] & same[2:]
    k = np.flatnonzero(inner)
    if k.size:
        with np.errstate(invalid="ignore", divide="ignore"):
            dt1, dt2 = t[k] - t[k - 1], t[k + 1] - t[k]
            line = pos[k - 1] + (pos[k + 1] - pos[k - 1]) * (dt1 / (dt1 + dt2))[:, None]
            dev = np.linalg.norm(pos[k] - line, axis=1)
            jump = (dev > MIN_JUMP_M) & (2 * dev / (dt1 * dt2) > MAX_ACCELERATION)
        suspect |= np.bincount(trial_of_row[k[jump]], minlength=n) > 0
    first = np.array([r[0] if len(r) > 1 else -1 for r in rows], dtype=np.int64)
    has = first >= 0
    step = np.zeros(n)
    step[has] = np.linalg.norm(pos[first[has] + 1] - pos[first[has]], axis=1)
    suspect |= step >= STALE_MIN_STEP_M
    out = {}
    for i in np.flatnonzero(suspect & which):
        r = rows[i]
        rec = pos[r][~nan[r]]
        span = float((rec.max(axis=0) - rec.min(axis=0)).max()) if len(rec) else 0.0
        if not span <= max_span_m:  # not metres (or a glitch): the unit checks judge it, nothing is repaired
            bad = np.flatnonzero(nan[r])
            if bad.size:
                k = int(bad[0])
                col = "xyz"[int(np.flatnonzero(np.isnan(pos[r[k]]))[0])]
                at = where(int(r[k])) if where else f"sample {k + 1}"
                none = np.zeros(len(r), dtype=bool)
                out[int(i)] = Repair(t[r], pos[r], contact[r] == 1, none, f"{col} is missing (NaN) at {at}")
            continue
        name = None if where is None else (lambda j, r=r: where(int(r[j])))
        rep = repair_trial(t[r], pos[r], contact[r] == 1, max_gap_s=max_gap_s, fill=fill, where=name)
        if rep.changed:
            out[int(i)] = rep
    return out
