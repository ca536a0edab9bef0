"""One trial's movement: velocity by a Savitzky-Golay derivative, onset and end, the segment.

The per-trial definitions of :mod:`skilllib.features` (its docstring gives the method and the reasons
for it): :func:`velocity`, :func:`segment_arrays` under the task's start and end rules
(:mod:`skilllib.features._rules`: the paper's speed onset and first contact by default; also a relative
onset, an event, the speed's offset, a height crossed), :func:`segmentation_detail` (what the rules saw,
for the figures), the two kinematic features :func:`peak_acceleration` (``peak_acc``, m/s^2: the
largest ``|d speed / dt|`` over the segment) and :func:`path_length` (``path_length``, m: the
trapezoidal integral of the speed), and the texts of the reasons why a trial cannot be segmented.
:mod:`skilllib.features` computes the same for many trials at once and is tested against these.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.signal import savgol_filter

from ._filtering import Lowpass
from ._rules import PAPER_END, PAPER_START, EndRule, SpeedThreshold, StartRule

ONSET_SPEED = 0.05  #: m/s, movement onset threshold (the paper)
CONTACT_WINDOW = (0.3, 0.7)  #: m/s, selected contact speeds, inclusive (the paper)
MIN_SEGMENT_SAMPLES = 5  #: fewer samples from onset to contact: too short to analyse
DIFF_SPAN_S = 2 / 60  #: s, span of the differentiating window (3 samples at the experiment's 60 Hz)
MIN_DIFF_WINDOW = 3  #: samples: the smallest differentiating window (a quadratic needs three points)
MIN_APPROACH_SAMPLES = 2  #: fewer samples before contact leave nothing to differentiate


@dataclass(frozen=True)
class Segment:
    """The movement of one trial from onset to the last sample before its end (the paper: before contact).

    What the robot needs of a prototype: :func:`skilllib.robot.transfer` takes a Segment as it is.

    Attributes
    ----------
    participant, trial : str
        The trial's ids (text, as written in the recordings).
    t : numpy.ndarray
        Time stamps as recorded, (N,) s (:attr:`time` counts from the onset).
    pos : numpy.ndarray
        Tool-tip positions, (N, 3) m, in the book's frame (x mediolateral, y up, z anteroposterior).
    vel : numpy.ndarray
        Velocities, (N, 3) m/s (the positions differentiated).
    speed : numpy.ndarray
        Speed, (N,) m/s.
    fs : float
        Sampling rate, Hz.
    onset, contact : int
        Indices (samples) in the trial of the onset sample and of the end sample, the first sample after
        the segment: contact (the paper), offset, event or height, as the task's end rule says (the field
        keeps its name).
    """

    participant: str
    trial: str
    t: np.ndarray
    pos: np.ndarray
    vel: np.ndarray
    speed: np.ndarray
    fs: float
    onset: int
    contact: int

    @property
    def duration(self) -> float:
        """Onset to the end sample (contact) in s (``N / fs``)."""
        return len(self.speed) / self.fs

    @property
    def time(self) -> np.ndarray:
        """The time stamps from the onset sample, (N,) s (``t - t[0]``): the time axis a prototype is
        plotted and executed on."""
        return self.t - self.t[0]


def diff_window(fs: float, span_s: float = DIFF_SPAN_S) -> int:
    """Samples (odd, at least 3) of the differentiating window that spans ``span_s`` s at ``fs`` Hz.

    Parameters
    ----------
    fs : float
        The sampling rate (Hz).
    span_s : float
        The time the window spans (s).

    Returns
    -------
    int
        The window's length (samples), odd and at least 3.
    """
    return max(MIN_DIFF_WINDOW, 2 * int(round(span_s * fs / 2)) + 1)


def velocity(pos: np.ndarray, fs: float, span_s: float = DIFF_SPAN_S) -> np.ndarray:
    """Velocity of positions sampled at ``fs`` Hz.

    Savitzky-Golay derivative of a quadratic fitted over :func:`diff_window` samples (``span_s`` s;
    quadratic fits to the first/last window at the ends). At 60 Hz the window has 3 samples and this is
    ``numpy.gradient(pos, 1/fs, edge_order=2)``. Shorter inputs use the largest odd window that fits;
    2 samples give their difference quotient. Needs N >= 2.

    Parameters
    ----------
    pos : numpy.ndarray, shape (N, 3)
        The positions (m), N >= 2.
    fs : float
        The sampling rate (Hz).
    span_s : float
        The time the differentiating window spans (s).

    Returns
    -------
    numpy.ndarray, shape (N, 3)
        The velocity (m/s).
    """
    pos = np.asarray(pos, dtype=float)
    if len(pos) < 2:
        raise ValueError(f"need at least 2 samples to differentiate, got {len(pos)}")
    if len(pos) == 2:
        return np.repeat((pos[1:] - pos[:1]) * fs, 2, axis=0)
    window = min(diff_window(fs, span_s), len(pos) - (1 - len(pos) % 2))
    return savgol_filter(pos, window, polyorder=2, deriv=1, delta=1.0 / fs, axis=0, mode="interp")


@dataclass(frozen=True)
class SegmentationDetail:
    """What the segmentation of one trial saw: the speed it analysed, its thresholds, onset and end.

    :func:`segmentation_detail` gives it for a trial that cannot be segmented too (as far as it got), so a
    figure can draw what the rules saw (:mod:`skilllib.figures.segmentation`).

    Attributes
    ----------
    speed : numpy.ndarray, shape (M,)
        The analysed speed (m/s) of the trial's first M samples: the samples before the end (contact,
        event, height) or the whole trial (offset); empty when the analysis did not get that far.
    start_threshold : float
        The onset threshold (m/s; a fraction of the peak already multiplied out); NaN for an event start
        or when unknown.
    end_threshold : float
        The offset threshold (m/s); NaN for any other end or when unknown.
    onset, end : int
        The onset sample and the end sample (indices in the trial, samples); -1 when unknown.
    reason : str
        Why the trial cannot be segmented; "" when it can (text).
    """

    speed: np.ndarray
    start_threshold: float = np.nan
    end_threshold: float = np.nan
    onset: int = -1
    end: int = -1
    reason: str = ""


def segment_arrays(
    t: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray,
    fs: float,
    *,
    start: StartRule = PAPER_START,
    end: EndRule = PAPER_END,
    events: Mapping[str, np.ndarray] | None = None,
    onset_speed: float | None = None,
    min_samples: int = MIN_SEGMENT_SAMPLES,
    participant: Any = None,
    trial: Any = None,
    lowpass: Lowpass | None = None,
) -> Segment | str:
    """Segment one trial's samples; returns the :class:`Segment` or the reason it cannot be segmented.

    The rules (:mod:`skilllib.features._rules`; the paper's by default):

    * **end** ``contact``: the first sample in contact; the velocity is the derivative of the samples
      before it only (the paper, :mod:`skilllib.features`).
    * **end** ``offset``: the velocity of the whole trial (its positions filtered as a whole when
      ``lowpass`` has a cut-off); the end is the first sample after the onset at or below the offset
      threshold (absolute, or a fraction of the peak speed from the onset on; the start's threshold when
      the rule states none) from which the speed stays at or below it for ``hold_s`` s, i.e. at that
      sample and the next ``round(hold_s * fs)`` ones: the first rest after the movement's peak (a later,
      faster movement, such as the return of a reach-to-grasp, is not part of it); a stay cut short by the
      end of the recording also ends the movement. The contact flag is not read.
    * **end** ``event:LABEL``: the first frame at or after the first event ``LABEL`` whose frame lies
      after the onset (a frame up to 1 % of a frame interval before the event counts as at it).
    * **end** ``height-above:M`` / ``height-below:M``: the first sample after the onset at or above (at
      or below) M m on the up axis (``pos[:, 1]``, the recorded positions, not filtered) whose previous
      sample is on the other side (reached by crossing).

      For these two the end depends on the onset and, for a speed start, the onset on the velocity before
      the end; so a provisional onset is found first, by the start rule on the speed of the whole trial
      (filtered as a whole; a fraction of the whole trial's peak), the end is found after it, and then the
      trial is segmented as for contact: velocity of the samples before the end only, the onset found
      again on it. (The two onsets differ only when the derivative's edge window at the end reaches the
      onset, or when a later, faster movement made the provisional fraction threshold higher; then the
      end found is still the first after the provisional onset.)
    * **start** ``speed``: absolute (m/s; the paper): the first sample faster than the threshold. A
      fraction of the peak speed (the maximum over the analysed samples: before the end; the whole trial
      for ``offset``): the first sample of a run faster than the threshold that lasts more than
      ``round(hold_s * fs)`` samples (the end rule's hold), so that a blip in the rest (a marker jump at
      the first frames, a twitch) does not start the movement. "No rest before onset" when that run
      begins at the first sample.
    * **start** ``event:LABEL``: the first frame at or after the first event ``LABEL``.

    Every rule that cannot apply gives its reason (text) naming what the recording has; bad data raise
    nothing. ``lowpass``: the filter applied to the analysed positions before they are differentiated
    (the samples before the end, or the whole trial for ``offset``; None: none); the segment's ``pos``
    are then the filtered positions.

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s), increasing.
    pos : numpy.ndarray, shape (N, 3)
        The positions (m); ``pos[:, 1]`` is the up axis.
    contact : numpy.ndarray of bool, shape (N,)
        The contact flag (dimensionless); read by the ``contact`` end only.
    fs : float
        The sampling rate (Hz).
    start : StartRule
        Where the movement starts (:func:`skilllib.features.parse_start`; speeds in m/s).
    end : EndRule
        Where it ends (:func:`skilllib.features.parse_end`; speeds in m/s, heights in m, hold in s).
    events : mapping of str to numpy.ndarray or None
        The trial's events: label (text) -> sorted event times (s, on the clock of ``t``); None: none.
    onset_speed : float or None
        Kept for older callers: the start rule ``speed`` with this absolute threshold (m/s); None: ``start``.
    min_samples : int
        The fewest samples a segment may have (samples).
    participant : Any
        The participant's id, kept in the segment (text).
    trial : Any
        The trial's id, kept in the segment (text).
    lowpass : Lowpass or None
        The positions' filter (cut-off in Hz); None: none.

    Returns
    -------
    Segment or str
        The segment (times in s, positions in m, speeds in m/s; ``contact`` holds the end sample), or the
        reason (text) why the trial cannot be segmented.
    """
    start = start_rule(start, onset_speed)
    got = _analyse(t, pos, contact, fs, start, end, events, min_samples, lowpass)
    if isinstance(got, str):
        return got
    detail, p, vel = got
    o, c = detail.onset, detail.end
    return Segment(
        participant,
        trial,
        np.asarray(t[o:c], dtype=float),
        np.asarray(p[o:c], dtype=float),
        vel[o:c],
        detail.speed[o:c],
        float(fs),
        o,
        c,
    )


def segmentation_detail(
    t: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray,
    fs: float,
    *,
    start: StartRule = PAPER_START,
    end: EndRule = PAPER_END,
    events: Mapping[str, np.ndarray] | None = None,
    min_samples: int = MIN_SEGMENT_SAMPLES,
    lowpass: Lowpass | None = None,
) -> SegmentationDetail:
    """What :func:`segment_arrays` saw of one trial: the analysed speed, the thresholds, onset and end.

    For a trial that cannot be segmented, as much as the analysis found before it stopped, and its reason.

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s).
    pos : numpy.ndarray, shape (N, 3)
        The positions (m).
    contact : numpy.ndarray of bool, shape (N,)
        The contact flag (dimensionless).
    fs : float
        The sampling rate (Hz).
    start : StartRule
        Where the movement starts (speeds in m/s).
    end : EndRule
        Where it ends (speeds in m/s, heights in m, hold in s).
    events : mapping of str to numpy.ndarray or None
        The trial's events: label (text) -> sorted times (s); None: none.
    min_samples : int
        The fewest samples a segment may have (samples).
    lowpass : Lowpass or None
        The positions' filter (cut-off in Hz); None: none.

    Returns
    -------
    SegmentationDetail
        The analysed speed (m/s), thresholds (m/s), onset and end (samples), reason (text).
    """
    trace: dict[str, Any] = {}
    got = _analyse(t, pos, contact, fs, start, end, events, min_samples, lowpass, trace)
    if isinstance(got, str):
        return SegmentationDetail(
            np.asarray(trace.get("speed", np.zeros(0))),
            float(trace.get("start_threshold", np.nan)),
            float(trace.get("end_threshold", np.nan)),
            int(trace.get("onset", -1)),
            int(trace.get("end", -1)),
            got,
        )
    return got[0]


def start_rule(start: StartRule = PAPER_START, onset_speed: float | None = None) -> StartRule:
    """The start rule a call means: ``start``, or (older callers) the absolute ``onset_speed`` (m/s).

    Parameters
    ----------
    start : StartRule
        The start rule (speeds in m/s).
    onset_speed : float or None
        An absolute onset threshold (m/s) given the old way; None: ``start``.

    Returns
    -------
    StartRule
        The rule.

    Raises
    ------
    TypeError
        When both a start rule other than the paper's and ``onset_speed`` are given.
    """
    if onset_speed is None:
        return start
    if start != PAPER_START:
        raise TypeError(
            f"give the start rule or onset_speed, not both (start {start.text()}, onset_speed {onset_speed})"
        )
    return StartRule("speed", SpeedThreshold(float(onset_speed)))


def frame_at(t: np.ndarray, time: float, fs: float) -> int:
    """The first frame at or after ``time`` (s): index into ``t`` (s), ``len(t)`` when after the last.

    A frame up to 1 % of a frame interval (``1 / fs``) before ``time`` counts as at it (event times
    written with fewer digits than the frames' time stamps).

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s), increasing.
    time : float
        The time (s).
    fs : float
        The sampling rate (Hz).

    Returns
    -------
    int
        The frame's index (samples).
    """
    return int(np.searchsorted(np.asarray(t, dtype=float), time - 0.01 / fs, side="left"))


def peak_acceleration(speed: np.ndarray, fs: float) -> float:
    """The peak magnitude of the tangential acceleration: the largest ``|d speed / dt|`` (m/s^2) over a segment.

    ``numpy.gradient(speed, 1 / fs)`` (central differences inside, one-sided at the ends); NaN for fewer
    than 2 samples.

    Parameters
    ----------
    speed : numpy.ndarray, shape (N,)
        The segment's speed (m/s).
    fs : float
        The sampling rate (Hz).

    Returns
    -------
    float
        The peak acceleration (m/s^2).
    """
    speed = np.asarray(speed, dtype=float)
    if len(speed) < 2:
        return np.nan
    return float(np.abs(np.gradient(speed, 1.0 / fs)).max())


def path_length(speed: np.ndarray, fs: float) -> float:
    """The distance travelled over a segment (m): the trapezoidal integral of its speed.

    ``numpy.trapezoid(speed, dx=1 / fs)``: from the first to the last sample of the segment (0 for one
    sample).

    Parameters
    ----------
    speed : numpy.ndarray, shape (N,)
        The segment's speed (m/s).
    fs : float
        The sampling rate (Hz).

    Returns
    -------
    float
        The path length (m).
    """
    return float(np.trapezoid(np.asarray(speed, dtype=float), dx=1.0 / fs))


def _speed(pos: np.ndarray, fs: float) -> tuple[np.ndarray, np.ndarray]:
    vel = velocity(pos, fs)
    return vel, np.linalg.norm(vel, axis=1)


def _filtered(pos: np.ndarray, n: int, fs: float, lowpass: Lowpass | None) -> np.ndarray:
    """``pos`` with its first ``n`` samples filtered by ``lowpass`` (when it has a cut-off)."""
    if lowpass is None or lowpass.cutoff_hz is None:
        return pos
    return np.concatenate([lowpass.apply(pos[:n], fs), pos[n:]])


def _analyse(
    t: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray,
    fs: float,
    start: StartRule,
    end: EndRule,
    events: Mapping[str, np.ndarray] | None,
    min_samples: int,
    lowpass: Lowpass | None,
    trace: dict[str, Any] | None = None,
) -> tuple[SegmentationDetail, np.ndarray, np.ndarray] | str:
    """The segmentation of one trial: (detail, analysed positions, velocity) or the reason. ``trace``
    collects what was found on the way (for :func:`segmentation_detail`)."""
    trace = {} if trace is None else trace
    n_all = len(pos)
    if end.kind == "contact":
        hits = np.flatnonzero(contact)
        if hits.size == 0:
            return NO_CONTACT
        c = int(hits[0])
        if c < MIN_APPROACH_SAMPLES:
            return in_contact_reason(c)
        return _before_end(t, pos, fs, c, start, end, events, min_samples, lowpass, trace)
    if end.kind == "offset":
        return _offset(t, pos, fs, start, end, events, min_samples, lowpass, trace)
    if end.kind not in ("event", "height-above", "height-below"):
        raise ValueError(f"unknown end rule {end.kind!r}")
    # event and height: a provisional onset on the whole trial, the end after it, then as for contact
    if start.kind == "event":
        o = _event_onset(t, fs, start, events, n_all)
        if isinstance(o, str):
            return o
    else:
        if n_all < MIN_APPROACH_SAMPLES:
            return short_recording_reason(n_all)
        _, speed = _speed(_filtered(pos, n_all, fs, lowpass), fs)
        o = _speed_onset(speed, start.threshold, "in the recording", int(round(end.hold_s * fs)))
        if isinstance(o, str):
            return o
        o = o[0]
    c = _event_end(t, fs, end, events, o) if end.kind == "event" else _height_end(pos, end, o)
    if isinstance(c, str):
        return c
    trace["end"] = c
    if c < MIN_APPROACH_SAMPLES:
        return too_short_reason(c, min_samples, _END_WORDS[end.kind])
    return _before_end(t, pos, fs, c, start, end, events, min_samples, lowpass, trace)


_END_WORDS = {
    "contact": "contact",
    "offset": "offset",
    "event": "the end event",
    "height-above": "the height crossing",
    "height-below": "the height crossing",
}


def _before_end(t, pos, fs, c, start, end, events, min_samples, lowpass, trace):
    """Segment with the end sample ``c`` known: the velocity of the samples before it only."""
    trace["end"] = c
    pos = _filtered(pos, c, fs, lowpass)
    vel, speed = _speed(pos[:c], fs)
    trace["speed"] = speed
    where = "before contact" if end.kind == "contact" else f"before {_END_WORDS[end.kind]}"
    if start.kind == "event":
        o = _event_onset(t, fs, start, events, c, end)
        if isinstance(o, str):
            return o
        thr = np.nan
    else:
        got = _speed_onset(speed, start.threshold, where, int(round(end.hold_s * fs)))
        if isinstance(got, str):
            trace["start_threshold"] = start.threshold.value(speed.max())
            return got
        o, thr = got
    trace["onset"], trace["start_threshold"] = o, thr
    n = c - o
    if n < min_samples:
        return too_short_reason(n, min_samples, _END_WORDS[end.kind])
    return SegmentationDetail(speed, float(thr), np.nan, o, c), pos, vel


def _offset(t, pos, fs, start, end, events, min_samples, lowpass, trace):
    """Segment with the ``offset`` end: velocity of the whole trial, onset, peak, the first held offset."""
    n_all = len(pos)
    if n_all < MIN_APPROACH_SAMPLES:
        return short_recording_reason(n_all)
    pos = _filtered(pos, n_all, fs, lowpass)
    vel, speed = _speed(pos, fs)
    trace["speed"] = speed
    if start.kind == "event":
        o = _event_onset(t, fs, start, events, n_all)
        if isinstance(o, str):
            return o
        thr = np.nan
    else:
        got = _speed_onset(speed, start.threshold, "in the recording", int(round(end.hold_s * fs)))
        if isinstance(got, str):
            trace["start_threshold"] = start.threshold.value(speed.max())
            return got
        o, thr = got
    trace["onset"], trace["start_threshold"] = o, thr
    peak = float(speed[o:].max())  # a fraction's reference: the fastest speed from the onset on
    rule = end.offset_threshold(start)
    off = rule.value(peak)
    trace["end_threshold"] = off
    hold = int(round(end.hold_s * fs))
    fast = np.flatnonzero(speed[o:] > off)  # an event may start the segment before the hand moves
    m = o + (int(fast[0]) if fast.size else 0)
    below = (speed[m + 1 :] <= off).astype(np.int8)
    edges = np.diff(np.concatenate([[0], below, [0]]))
    runs_from, runs_to = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)  # runs [from, to) at or below
    held = (runs_to - runs_from >= hold + 1) | (runs_to == len(below))
    if not held.any():
        return no_offset_reason(_threshold_text(off, rule, peak), end.hold_s, runs_from.size > 0)
    c = m + 1 + int(runs_from[held][0])  # the first held rest once moving: after this movement's peak
    trace["end"] = c
    n = c - o
    if n < min_samples:
        return too_short_reason(n, min_samples, "offset")
    return SegmentationDetail(speed, float(thr), float(off), o, c), pos, vel


def _speed_onset(speed: np.ndarray, rule: SpeedThreshold, where: str, hold: int = 0) -> tuple[int, float] | str:
    """The first sample faster than the threshold (absolute, or ``rule.fraction`` of ``speed.max()``)
    and the threshold (m/s), or the reason. A fraction's onset is **held**: the first sample of a run
    faster than the threshold for more than ``hold`` samples (or up to the end of ``speed``), so that a
    blip in the rest (a marker jump at the first frames, a twitch) does not start the movement; an
    absolute threshold is the paper's rule, the first faster sample."""
    peak = speed.max()
    thr = rule.value(peak)
    moving = np.flatnonzero(speed > thr)
    if moving.size and rule.fraction is not None and hold > 0:
        above = np.concatenate([[0], (speed > thr).astype(np.int8), [0]])
        edges = np.diff(above)
        run_from, run_to = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
        held = (run_to - run_from > hold) | (run_to == len(speed))
        moving = run_from[held]
    if moving.size == 0:
        if rule.fraction is None and where == "before contact":
            return no_onset_reason(thr, peak)  # the paper's text
        return no_onset_reason(thr, peak, where, _threshold_text(thr, rule, peak))
    o = int(moving[0])
    if o == 0:
        if rule.fraction is None:
            return no_rest_reason(thr, speed[0])
        return no_rest_reason(thr, speed[0], _threshold_text(thr, rule, peak))
    return o, thr


def _events_of(events: Mapping[str, np.ndarray] | None, label: str) -> np.ndarray | str:
    """The times (s) of the events ``label``, or the reason naming the labels the trial has."""
    events = events or {}
    times = np.asarray(events.get(label, []), dtype=float)
    if times.size:
        return np.sort(times)
    have = [str(k) for k, v in events.items() if np.size(v)]
    listed = f"events: {', '.join(have)}" if have else "it has no events"
    return f"no event {label!r} in this trial ({listed})"


def _event_onset(t, fs, start: StartRule, events, n: int, end: EndRule | None = None) -> int | str:
    """The onset of an ``event`` start: the first frame at or after the first event, before sample ``n``."""
    times = _events_of(events, start.label)
    if isinstance(times, str):
        return times
    o = frame_at(t, times[0], fs)
    if o >= len(t):
        return (
            f"no onset: the event {start.label!r} at {times[0]:.3f} s is after the recording ends "
            f"(last frame at {t[-1]:.3f} s)"
        )
    if o >= n:
        return (
            f"no onset: the event {start.label!r} at {times[0]:.3f} s is not before {_END_WORDS[end.kind]} "
            f"at {t[n]:.3f} s"
        )
    return o


def _event_end(t, fs, end: EndRule, events, o: int) -> int | str:
    """The end of an ``event`` end: the first frame at or after the first event whose frame is after ``o``."""
    times = _events_of(events, end.label)
    if isinstance(times, str):
        return times
    frames = np.array([frame_at(t, x, fs) for x in times])
    after = np.flatnonzero(frames > o)
    if after.size == 0:
        at = ", ".join(f"{x:.3f}" for x in times[:5]) + (", ..." if len(times) > 5 else "")
        return f"no event {end.label!r} after the onset at {t[o]:.3f} s (its events at {at} s)"
    c = int(frames[after[0]])
    if c >= len(t):
        return (
            f"no end: the event {end.label!r} at {times[after[0]]:.3f} s is after the recording ends "
            f"(last frame at {t[-1]:.3f} s)"
        )
    return c


def _height_end(pos: np.ndarray, end: EndRule, o: int) -> int | str:
    """The end of a ``height-above`` / ``height-below`` end: the first crossing after the onset ``o``."""
    y = np.asarray(pos, dtype=float)[o:, 1]
    m = float(end.height)
    up = end.kind == "height-above"
    on = y >= m if up else y <= m
    crossed = np.flatnonzero(on[1:] & ~on[:-1])
    if crossed.size:
        return o + 1 + int(crossed[0])
    verb, bound, extreme = ("rises", "max", np.nanmax(y)) if up else ("falls", "min", np.nanmin(y))
    if not on[0]:
        return f"the up-axis position never {verb} to {m:g} m after onset ({bound} {extreme:.3g} m)"
    side = "above" if up else "below"
    return (
        f"the up-axis position never {verb} to {m:g} m after onset: it is already {side} it at onset "
        f"({y[0]:.3g} m) and does not cross it again"
    )


def _threshold_text(value: float, rule: SpeedThreshold, peak: float) -> str:
    """``0.05 m/s``, or ``0.017 m/s (3% of the peak 0.566 m/s)`` for a relative threshold."""
    if rule.fraction is None:
        return f"{value:g} m/s"
    return f"{value:.3g} m/s ({rule.text()} of the peak {peak:.3f} m/s)"


#: The reasons a trial cannot be segmented (:func:`segment_arrays`, :mod:`skilllib.features`).
NO_CONTACT = "no contact: the contact flag is never 1"


def in_contact_reason(c: int) -> str:
    return f"in contact from sample {c + 1}: no approach recorded before contact"


def no_onset_reason(onset_speed: float, max_speed: float, where: str = "before contact", text: str = "") -> str:
    return f"no onset: speed stays below {text or f'{onset_speed:g} m/s'} {where} (max {max_speed:.3f} m/s)"


def no_rest_reason(onset_speed: float, first_speed: float, text: str = "") -> str:
    return (
        f"no rest before onset: speed {first_speed:.2f} m/s > {text or f'{onset_speed:g} m/s'} at the first sample "
        f"(the movement started before the recording)"
    )


def no_offset_reason(threshold: str, hold_s: float, dips: bool) -> str:
    if not dips:
        return f"no offset: speed stays above {threshold} after the onset until the recording ends"
    return (
        f"no offset: after the onset the speed never stays at or below {threshold} for {hold_s:g} s "
        f"before the recording ends"
    )


def short_recording_reason(n: int) -> str:
    return f"too short: {n} samples in the recording (need at least {MIN_APPROACH_SAMPLES} to differentiate)"


def too_short_reason(n: int, min_samples: int, end: str = "contact") -> str:
    return f"too short: {n} samples from onset to {end} (need at least {min_samples})"
