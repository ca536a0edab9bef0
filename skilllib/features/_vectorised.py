"""Segmentation and features of many trials at once: the in-memory path at the speed of its core.

:func:`segment_many` does for every trial what :func:`skilllib.features.segment_arrays` does for one
(velocity by the Savitzky-Golay derivative over the approach, onset, contact, segment, the same reasons
for a trial that cannot be segmented) and adds the per-trial features of :mod:`skilllib.features` (PV,
contact speed, duration, LDLJ, peak acceleration, path length, time stamps of onset and contact); SPARC
then runs over the segments with :func:`skilllib.smoothness.sparc_bands`, which was already batched.

The batched core is the paper's rules (start: speed above an absolute threshold; end: first contact).
Any other rule of :mod:`skilllib.features._rules` (a relative onset, an event, the offset, a height)
segments every trial through :func:`skilllib.features.segment_arrays`, one by one: a Python loop, fast
enough for hundreds of trials. The features of the segments are computed in blocks of equal length
either way.

No Python loop per trial on the common path: trials are runs of rows of flat arrays
(:class:`skilllib.recordings.Runs`), gathered into blocks of equal approach length (for the derivative) and
of equal segment length (for LDLJ), so every value has the same bits as the per-trial functions
(:mod:`skilllib.recordings` explains why). Three cases go through the per-trial function instead, one trial
at a time: an approach shorter than the differentiating window (a few samples; the window shrinks for
it), a run with a low-pass filter (the filter runs per trial), and segments of fewer than 3 samples
(LDLJ raises there, as it does per trial). ``scipy.signal.savgol_filter`` fits the first and last
samples of windows of 9 or more samples (rates of 240 Hz and above) with a least-squares solve whose
last bits depend on how many profiles are solved together: there the edge velocities agree with the
per-trial ones to about 1e-15 relative, not bit for bit.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.signal import savgol_filter

from .. import smoothness
from ..recordings import Runs, first_true
from ._filtering import Lowpass
from ._rules import PAPER_END, PAPER_START, EndRule, StartRule
from ._segmentation import (
    MIN_APPROACH_SAMPLES,
    MIN_SEGMENT_SAMPLES,
    NO_CONTACT,
    diff_window,
    in_contact_reason,
    no_onset_reason,
    no_rest_reason,
    path_length,
    peak_acceleration,
    segment_arrays,
    start_rule,
    too_short_reason,
)


@dataclass(frozen=True, eq=False)
class SegmentedTrials:
    """Per trial (aligned with the runs): ``reason`` ("" when segmented), ``onset`` and ``contact``
    (indices within the trial of the onset and of the end sample: contact, offset, event or height; -1
    when unknown), ``n`` (segment samples, 0 when not segmented), ``pv`` and ``contact_speed`` (m/s; the
    speed at the last sample before the end), ``duration`` (s), ``ldlj``, ``peak_acc`` (m/s^2, the largest
    ``|d speed / dt|`` over the segment, NaN below 2 samples), ``path_length`` (m, the trapezoidal integral of the
    speed), ``t_onset`` and ``t_contact`` (s, time stamps of the onset and the end sample; NaN when not
    segmented); ``speeds``: the segments' speed profiles (m/s) of the segmented trials, in trial order."""

    reason: np.ndarray
    onset: np.ndarray
    contact: np.ndarray
    n: np.ndarray
    pv: np.ndarray
    contact_speed: np.ndarray
    duration: np.ndarray
    ldlj: np.ndarray
    peak_acc: np.ndarray
    path_length: np.ndarray
    t_onset: np.ndarray
    t_contact: np.ndarray
    speeds: list[np.ndarray]

    @property
    def segmented(self) -> np.ndarray:
        """Bool per trial: it was segmented (its features are set)."""
        return self.n > 0


def _blank(n_trials: int) -> dict[str, np.ndarray]:
    nan = np.full(n_trials, np.nan)
    return {
        "reason": np.full(n_trials, "", dtype=object),
        "onset": np.full(n_trials, -1, np.int64),
        "contact": np.full(n_trials, -1, np.int64),
        "n": np.zeros(n_trials, np.int64),
        "pv": nan.copy(),
        "contact_speed": nan.copy(),
        "duration": nan.copy(),
        "ldlj": nan.copy(),
        "peak_acc": nan.copy(),
        "path_length": nan.copy(),
        "t_onset": nan.copy(),
        "t_contact": nan,
    }


def segment_many(
    t: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray,
    runs: Runs,
    fs: float,
    *,
    which: np.ndarray | None = None,
    separate: Mapping[int, Any] | None = None,
    start: StartRule = PAPER_START,
    end: EndRule = PAPER_END,
    events: Mapping[int, Mapping[str, np.ndarray] | None] | None = None,
    onset_speed: float | None = None,
    min_samples: int = MIN_SEGMENT_SAMPLES,
    lowpass: Lowpass | None = None,
) -> SegmentedTrials:
    """Segment every trial of ``runs`` as :func:`skilllib.features.segment_arrays` does one by one, and
    compute its features.

    The paper's rules (an absolute onset speed, the end at contact) run batched; any other rule runs
    :func:`skilllib.features.segment_arrays` trial by trial.

    Parameters
    ----------
    t : numpy.ndarray, shape (R,)
        The time stamps of all trials' rows (s).
    pos : numpy.ndarray, shape (R, 3)
        The positions (m).
    contact : numpy.ndarray of bool, shape (R,)
        The contact flag (dimensionless).
    runs : Runs
        The trials' runs of rows (samples).
    fs : float
        The sampling rate (Hz).
    which : numpy.ndarray of bool or None
        The trials to segment (others keep an empty reason and no features: the caller's invalid trials);
        None: all.
    separate : mapping of int to object or None
        Trials whose samples are given apart from the flat arrays (objects with ``t`` in s, ``pos`` in m,
        ``contact``: resampled trials), segmented one by one.
    start : StartRule
        Where a movement starts (speeds in m/s).
    end : EndRule
        Where it ends (speeds in m/s, heights in m, hold in s).
    events : mapping of int to mapping or None
        Trial index -> that trial's events (label, text -> sorted times in s), or None; None: no events.
    onset_speed : float or None
        Kept for older callers: an absolute onset threshold (m/s) instead of ``start``.
    min_samples : int
        The fewest samples a segment may have (samples).
    lowpass : Lowpass or None
        As in segment_arrays (cut-off in Hz).

    Returns
    -------
    SegmentedTrials
        Per trial: reason (text), onset and end (samples), features (m/s, s, m/s^2, m).
    """
    start = start_rule(start, onset_speed)
    paper = start.kind == "speed" and start.threshold.fraction is None and end.kind == "contact"
    events = events or {}
    n_trials = len(runs)
    out = _blank(n_trials)
    todo = np.ones(n_trials, bool) if which is None else np.asarray(which, bool).copy()
    separate = dict(separate or {})
    todo[list(separate)] = False  # their rows in the flat arrays are not the samples to use
    seg_speed: dict[int, np.ndarray] = {}
    if paper:
        c = first_true(np.asarray(contact, bool), runs)
        none = todo & (c == runs.length)
        out["reason"][none] = NO_CONTACT
        early = todo & ~none & (c < MIN_APPROACH_SAMPLES)
        for i in np.flatnonzero(early):
            out["reason"][i] = in_contact_reason(int(c[i]))
        rest = todo & ~none & ~early
        filtered = lowpass is not None and lowpass.cutoff_hz is not None
        w = diff_window(fs) if np.isfinite(fs) else 0  # fs is unknown only when no trial is usable
        fast = rest & (c >= w) & (not filtered)
        onset_speed = float(start.threshold.speed)
        for trials, rows in runs.blocks(fast, length=c):
            _segment_block(out, seg_speed, trials, rows, t, pos, fs, w, onset_speed, min_samples)
    else:  # every trial one by one, its end as its rule says (the contact flag is read by "contact" only)
        rest, fast = todo, np.zeros(n_trials, bool)
    one_by_one = [(int(i), None) for i in np.flatnonzero(rest & ~fast) if int(i) not in separate]
    for i, samples in [*one_by_one, *separate.items()]:  # short approaches, filtered runs, resampled trials
        r = slice(runs.start[i], runs.start[i] + runs.length[i])
        ti, pi, ci = (t[r], pos[r], contact[r]) if samples is None else (samples.t, samples.pos, samples.contact)
        seg = segment_arrays(
            ti, pi, ci, fs, start=start, end=end, events=events.get(i), min_samples=min_samples, lowpass=lowpass
        )
        if isinstance(seg, str):
            out["reason"][i] = seg
            continue
        v = seg.speed
        out["onset"][i], out["contact"][i], out["n"][i] = seg.onset, seg.contact, len(v)
        out["pv"][i], out["contact_speed"][i], out["duration"][i] = v.max(), v[-1], seg.duration
        out["t_onset"][i], out["t_contact"][i] = ti[seg.onset], ti[seg.contact]
        seg_speed[int(i)] = v
    _features_by_length(out, seg_speed, fs)
    order = sorted(seg_speed)
    return SegmentedTrials(**out, speeds=[seg_speed[i] for i in order])


def _segment_block(
    out: dict[str, np.ndarray],
    seg_speed: dict[int, np.ndarray],
    trials: np.ndarray,
    rows: np.ndarray,
    t: np.ndarray,
    pos: np.ndarray,
    fs: float,
    w: int,
    onset_speed: float,
    min_samples: int,
) -> None:
    """Trials whose approaches have the same length c (``rows``: (K, c) rows of the approaches)."""
    c = rows.shape[1]
    vel = savgol_filter(pos[rows], w, polyorder=2, deriv=1, delta=1.0 / fs, axis=1, mode="interp")
    speed = np.linalg.norm(vel, axis=2)  # (K, c) m/s
    moving = speed > onset_speed
    has = moving.any(axis=1)
    o = np.where(has, moving.argmax(axis=1), -1)
    n = c - o
    for k in np.flatnonzero(~has):
        out["reason"][trials[k]] = no_onset_reason(onset_speed, speed[k].max())
    for k in np.flatnonzero(has & (o == 0)):
        out["reason"][trials[k]] = no_rest_reason(onset_speed, speed[k, 0])
    for k in np.flatnonzero(has & (o > 0) & (n < min_samples)):
        out["reason"][trials[k]] = too_short_reason(int(n[k]), min_samples)
    ok = np.flatnonzero(has & (o > 0) & (n >= min_samples))
    if ok.size == 0:
        return
    i, o, n = trials[ok], o[ok], n[ok]
    sp = speed[ok]
    in_seg = np.arange(c)[None, :] >= o[:, None]
    out["onset"][i], out["contact"][i], out["n"][i] = o, c, n
    out["pv"][i] = np.where(in_seg, sp, -np.inf).max(axis=1)
    out["contact_speed"][i] = sp[:, -1]
    out["duration"][i] = n / float(fs)
    out["t_onset"][i] = t[rows[ok, 0] + o]
    out["t_contact"][i] = t[rows[ok, 0] + c]
    for k, trial in enumerate(i):
        seg_speed[int(trial)] = sp[k, o[k] :]


def _features_by_length(out: dict[str, np.ndarray], seg_speed: dict[int, np.ndarray], fs: float) -> None:
    """LDLJ, peak acceleration and path length of every segment, in blocks of equal length
    (:func:`skilllib.smoothness.ldlj`, :func:`skilllib.features.peak_acceleration` and
    :func:`skilllib.features.path_length` row by row, with the same bits); segments of fewer than 3 samples
    go to the per-segment functions (ldlj says why it cannot compute them)."""
    by_n: dict[int, list[int]] = {}
    for i, v in seg_speed.items():
        by_n.setdefault(len(v), []).append(i)
    dt = 1.0 / fs
    for n, trials in by_n.items():
        if n < 3:
            for i in trials:
                out["ldlj"][i] = smoothness.ldlj(seg_speed[i], fs)
                out["peak_acc"][i] = peak_acceleration(seg_speed[i], fs)
                out["path_length"][i] = path_length(seg_speed[i], fs)
            continue
        block = np.stack([seg_speed[i] for i in trials])
        out["ldlj"][trials] = smoothness.ldlj_rows(block, fs)
        out["peak_acc"][trials] = np.abs(np.gradient(block, dt, axis=1)).max(axis=1)
        out["path_length"][trials] = np.trapezoid(block, dx=dt, axis=1)
