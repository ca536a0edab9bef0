"""Time stamps: the file's sampling rate, trials at another rate, and irregular sampling.

The sampling rate is read from the time stamps, never given: every usable trial's intervals are looked
at, and

* the file's interval ``dt`` (s) is the median over on-rate trials of each trial's mean *regular*
  interval (its intervals within :data:`TRIM` of its median, a symmetric trim that leaves out dropped
  frames without biasing jittered intervals; the median of a trial's intervals alone is biased by time
  stamps rounded to 0.1 ms). For jitter up to about a quarter of the interval the intervals telescope and
  the rate is exact to a fraction of a per mille; jitter of half an interval (0 to 2 intervals) flattens
  their distribution and a trial tells its rate only to a few per cent, so the median over many trials
  is what makes it precise;
* a trial whose median interval differs from the file's by more than :data:`RATE_TOLERANCE` was sampled
  at another rate: it is ``invalid`` (several such trials, more than :data:`MIXED_FRACTION`, mean the
  file mixes rates: an error);
* **jitter, rounding and dropped frames.** A trial whose intervals all lie within
  :data:`JITTER_TOLERANCE` of ``dt`` is regular and used as recorded. Otherwise its time stamps are
  compared with the regular grid they scatter around (:func:`grid_jitter`: the largest distance of a
  stamp from the straight line fitted to the stamps against their frame numbers): stamps within
  :data:`REGULAR_JITTER` of an interval of that grid, or within the resolution they are written with
  (:func:`time_quantum`: OpenSim writes 60 Hz stamps rounded to the millisecond, 0.017, 0.033, ...,
  whose intervals of 16 and 17 ms are 4 % off), are a regular recording whose clock was logged
  imprecisely: the trial is used as recorded (its ``timing`` says so). Only really irregular stamps
  (VR and game-engine logs stamp each sample with the frame time and drop frames now and then) are
  **resampled** onto the uniform grid ``t0 + k dt`` (:func:`resample_uniform`), as long as no interval
  exceeds :data:`MAX_GAP_INTERVALS` x ``dt``: positions by a cubic interpolating spline
  (``scipy.interpolate.make_interp_spline``, k = 3, not-a-knot ends) fitted separately to the approach
  (samples before the first contact sample) and to the samples in contact, so that the impact's velocity
  step does not ring into the approach. **No grid sample is extrapolated**: grid samples within the
  recorded approach come from its spline, those between the last approach sample and the first contact
  sample from the straight line between the two, and contact begins at the midpoint between them (its
  best estimate). The contact speed (read at the last approach grid sample) therefore comes from
  interpolation between recorded samples, never from a spline carried past its data. This assumes, as
  the loggers do, that each time stamp is the time its sample was taken. A longer gap (more than two
  frames missing in a row) cannot be bridged honestly: after the first contact sample, where the
  analysis never looks, the trial is cut at the gap (its ``timing`` says how many samples were left);
  before it, the trial is ``invalid`` with the reason.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import make_interp_spline

RATE_TOLERANCE = 0.10  #: a trial's median interval may differ this much (relative) from the file's
MIXED_FRACTION = 0.05  #: more trials than this fraction at another rate: the file mixes rates (error)
JITTER_TOLERANCE = 0.02  #: intervals within (1 +- this) x dt are regular (0.1 ms rounding at 60 Hz is 0.6 %)
REGULAR_JITTER = 0.05  #: stamps within this fraction of dt of a regular grid are that grid (Optotrak: 0.3 ms at 85 Hz)
QUANTA = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)  #: s, the resolutions time stamps are commonly rounded to
MAX_GAP_INTERVALS = 3.5  #: an interval above this many dt (more than two frames missing): the trial is invalid
TRIM = 0.5  #: intervals further than this fraction from a trial's median are left out of its rate (dropped frames)
MIN_RATE_HZ = 10.0  #: a sampling rate below this, read from t in s, means t is in another unit (error)
MAX_RATE_HZ = 100_000.0  #: the fastest rate a unit suggestion considers plausible (Hz)


def regular_mean_interval(t: np.ndarray) -> float:
    """The typical interval of time stamps ``t``.

    The mean of the intervals within +-:data:`TRIM` of a centre, the centre moved to that mean until it
    stays (a flat-kernel mean shift from the median, at most 20 steps): the mode of the intervals, which
    jitter does not bias and dropped frames (2 x the interval) do not reach. For regular time stamps every
    interval is in the window and this is their mean.

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s), increasing.

    Returns
    -------
    float
        The typical interval (s).
    """
    d = np.diff(np.asarray(t, dtype=float))
    c = float(np.median(d))
    for _ in range(20):
        new = float(d[np.abs(d - c) <= TRIM * c].mean())
        if new == c:
            break
        c = new
    return c


def time_unit_advice(step: float) -> str:
    """What a median time step too long for seconds says about the unit.

    The unit (milliseconds or microseconds) whose rate is plausible, and the division that fixes it.

    Parameters
    ----------
    step : float
        The median time step between samples, in the file's unit (s if it were seconds; ms or us as
        suspected).

    Returns
    -------
    str
        The advice for the message (text).
    """
    head = (
        f"median time step {step:g} between samples: {1 / step:.3g} Hz if t were in seconds, below {MIN_RATE_HZ:g} Hz"
    )
    for unit, factor in (("milliseconds", 1e3), ("microseconds", 1e6)):
        if MIN_RATE_HZ <= factor / step <= MAX_RATE_HZ:
            return (
                f"time stamps look like {unit} ({head}; {factor / step:.4g} Hz in {unit}); t must be in "
                f"seconds: divide t by {factor:.0f}"
            )
    return f"time stamps are not in seconds ({head}); t must be in seconds"


@dataclass(frozen=True)
class Irregularity:
    """How a trial's intervals deviate from the file's ``dt``.

    The largest relative deviation of an interval from dt (``max_jitter``, e.g. 0.5 for an interval of
    1.5 dt or 0.5 dt; a dropped frame counts here), the number of dropped frames (``dropped``: sum over
    intervals of round(d / dt) - 1), the longest interval (``max_interval`` in s, ``at``: index of the
    sample after it), against the interval ``dt`` (s), and the jitter apart from dropped frames
    (``frame_jitter``: the largest deviation of an interval from its nearest whole number of frames, at
    least one, relative to dt).

    Attributes
    ----------
    max_jitter : float
        Largest deviation of an interval from ``dt``, relative to ``dt`` (dimensionless).
    dropped : int
        Number of dropped frames (samples).
    max_interval : float
        The longest interval (s).
    at : int
        Index of the sample after the longest interval (samples).
    dt : float
        The interval judged against (s).
    frame_jitter : float
        Largest deviation of an interval from its nearest whole number of frames, relative to ``dt``
        (dimensionless).
    grid_jitter : float
        Largest distance of a stamp from the regular grid fitted to the stamps (:func:`grid_jitter`),
        relative to ``dt`` (dimensionless).
    quantum : float
        The resolution the stamps are written with (:func:`time_quantum`; s), 0 when none of
        :data:`QUANTA`.
    """

    max_jitter: float
    dropped: int
    max_interval: float
    at: int
    dt: float
    frame_jitter: float
    grid_jitter: float = 0.0
    quantum: float = 0.0

    @property
    def regular(self) -> bool:
        """Used as recorded: intervals within :data:`JITTER_TOLERANCE` of dt, or no dropped frame and every
        stamp within :data:`REGULAR_JITTER` x dt (or the stamps' resolution) of the regular grid."""
        if self.max_jitter <= JITTER_TOLERANCE:
            return True
        return self.dropped == 0 and self.grid_jitter * self.dt <= max(REGULAR_JITTER * self.dt, self.quantum)

    def describe_regular(self) -> str:
        """``"stamps within 0.31 ms of a regular 85 Hz grid (rounded to 1 ms): used as recorded"``."""
        text = f"stamps within {1e3 * self.grid_jitter * self.dt:.2g} ms of a regular {1 / self.dt:.4g} Hz grid"
        if self.quantum:
            text += f" (written to {self.quantum * 1e3:g} ms)"
        return text + ": used as recorded"

    @property
    def gap(self) -> bool:
        """An interval too long to bridge (more than :data:`MAX_GAP_INTERVALS` x dt)."""
        return self.max_interval > MAX_GAP_INTERVALS * self.dt

    def describe(self) -> str:
        """``"jitter up to 1.9 ms, 2 dropped frames"``: what resampling bridged (the jitter apart from
        the dropped frames, ``frame_jitter``)."""
        parts = [f"jitter up to {1e3 * self.frame_jitter * self.dt:.2g} ms"]
        if self.dropped:
            parts.append(f"{self.dropped} dropped frame{'s' if self.dropped > 1 else ''}")
        return ", ".join(parts)


def irregularity(t: np.ndarray, dt: float) -> Irregularity:
    """The :class:`Irregularity` of time stamps ``t`` against the interval ``dt``.

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s), increasing.
    dt : float
        The file's sampling interval (s).

    Returns
    -------
    Irregularity
        How the intervals of ``t`` deviate from ``dt`` (s and dimensionless ratios).
    """
    d = np.diff(np.asarray(t, dtype=float))
    rel = np.abs(d / dt - 1)
    k = int(np.argmax(d))
    frames = np.maximum(np.round(d / dt), 1)
    dropped = int((frames - 1).sum())
    frame_jitter = float(np.abs(d / dt - frames).max())
    return Irregularity(
        float(rel.max()), dropped, float(d[k]), k + 1, float(dt), frame_jitter, grid_jitter(t, dt), time_quantum(t)
    )


def grid_jitter(t: np.ndarray, dt: float) -> float:
    """How far time stamps ``t`` stray from the regular grid they scatter around, relative to ``dt``.

    Each stamp's frame number is ``k = round((t - t[0]) / dt)`` counted along the intervals (an interval
    of about two dt is a dropped frame); a straight line ``a + b k`` is fitted to ``t`` by least squares
    (``b`` absorbs a clock a little off the file's rate), and the largest ``|t - a - b k|`` is returned in
    units of ``dt``. Stamps rounded to a resolution ``q`` give at most about ``q / 2``; jitter of +-j gives
    about j.

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s), increasing.
    dt : float
        The file's sampling interval (s).

    Returns
    -------
    float
        The largest distance of a stamp from the fitted grid, relative to ``dt`` (dimensionless).
    """
    t = np.asarray(t, dtype=float)
    if len(t) < 3:
        return 0.0
    k = np.concatenate([[0.0], np.cumsum(np.maximum(np.round(np.diff(t) / dt), 1))])
    km, tm = k.mean(), t.mean()
    b = float(((k - km) * (t - tm)).sum() / ((k - km) ** 2).sum())
    return float(np.abs(t - tm - b * (k - km)).max() / dt)


def time_quantum(t: np.ndarray) -> float:
    """The coarsest of :data:`QUANTA` (s) that every time stamp is a whole multiple of, 0 when none.

    OpenSim and many loggers write stamps rounded to the millisecond; such stamps scatter around the
    true, regular, sample times by up to half that resolution, which says nothing about irregular
    sampling. A stamp is a multiple of ``q`` when ``t / q`` is within 1e-6 of a whole number (the decimal
    text read into binary floats is not exact).

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s).

    Returns
    -------
    float
        The resolution the stamps are written with (s), or 0.
    """
    t = np.asarray(t, dtype=float)
    for q in QUANTA:
        x = t / q
        if np.all(np.abs(x - np.round(x)) <= 1e-6):
            return q
    return 0.0


def gap_after_contact(t: np.ndarray, contact: np.ndarray, dt: float) -> int | None:
    """Where to cut a trial whose only long gaps in the time stamps come after its first contact sample.

    The analysis reads the approach (up to the first contact sample); an interval longer than
    :data:`MAX_GAP_INTERVALS` x ``dt`` later in the recording does not touch it. Returns the index of the
    sample after the first such gap (keep ``t[:cut]``), or None when a long gap lies at or before the
    first contact sample, or the trial has no contact.

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s), increasing.
    contact : numpy.ndarray of bool, shape (N,)
        The contact flag of each sample (dimensionless).
    dt : float
        The file's sampling interval (s).

    Returns
    -------
    int or None
        The index of the first sample not kept (samples), or None.
    """
    hits = np.flatnonzero(np.asarray(contact, dtype=bool))
    if not hits.size:
        return None
    after = np.flatnonzero(np.diff(np.asarray(t, dtype=float)) > MAX_GAP_INTERVALS * dt) + 1  # sample after
    if not after.size or after[0] <= hits[0]:
        return None
    return int(after[0])


def resample_uniform(
    t: np.ndarray, pos: np.ndarray, contact: np.ndarray, dt: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Resample one trial onto the uniform grid ``t[0] + k dt`` (k = 0 .. floor((t[-1] - t[0]) / dt)),
    interpolating only, never extrapolating.

    With ``c`` the first contact sample: grid times up to the last approach sample ``t[c - 1]`` are
    interpolated by a cubic spline through the approach samples ``0 .. c - 1``; grid times between
    ``t[c - 1]`` and ``t[c]`` linearly between those two samples; from ``t[c]`` on by a cubic spline through
    the contact samples. (The approach spline is not carried past its last recorded sample, where an
    extrapolated spline can land millimetres off the path, exactly where the contact speed is read.)
    Contact began somewhere between ``t[c - 1]`` and ``t[c]``; its best estimate is the midpoint, so a grid
    time before the midpoint is approach and one at or after it is in contact (on regular stamps this is
    the first sample at or after the first contact sample, as recorded). A part with 2 or 3
    samples is interpolated linearly, a part of one sample is that sample; a trial without contact is
    one spline, one in contact from its first sample another.

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s), increasing.
    pos : numpy.ndarray, shape (N, 3)
        The positions (m).
    contact : numpy.ndarray of bool, shape (N,)
        The contact flag of each sample (dimensionless).
    dt : float
        The grid's interval (s).

    Returns
    -------
    t_grid : numpy.ndarray, shape (M,)
        The uniform time stamps (s).
    pos_grid : numpy.ndarray, shape (M, 3)
        The resampled positions (m).
    contact_grid : numpy.ndarray of bool, shape (M,)
        The resampled contact flag (dimensionless).
    """
    t = np.asarray(t, dtype=float)
    pos = np.asarray(pos, dtype=float)
    contact = np.asarray(contact, dtype=bool)
    n = int(np.floor((t[-1] - t[0]) / dt * (1 + 1e-9))) + 1
    grid = t[0] + dt * np.arange(n)
    hits = np.flatnonzero(contact)
    c = int(hits[0]) if hits.size else len(t)
    out = np.empty((n, pos.shape[1]))
    between = np.zeros(n, dtype=bool)  # grid times after the last approach sample, before the first contact one
    if 0 < c < len(t):
        between = (grid > t[c - 1]) & (grid < t[c])
    approach = grid <= t[c - 1] if c > 0 else np.zeros(n, dtype=bool)
    held = ~approach & ~between
    for part, where in ((slice(0, c), approach), (slice(c, len(t)), held)):
        if where.any():
            out[where] = _interpolate(t[part], pos[part], grid[where])
    if between.any():
        out[between] = _interpolate(t[c - 1 : c + 1], pos[c - 1 : c + 1], grid[between])
        approach |= between & (grid < 0.5 * (t[c - 1] + t[c]))  # contact began at about the midpoint
    return grid, out, ~approach


def _interpolate(tp: np.ndarray, pp: np.ndarray, at: np.ndarray) -> np.ndarray:
    """``pp`` (m) sampled at ``tp`` (s) interpolated at ``at`` (s, within ``tp``'s range): a cubic spline
    from 4 samples, linear from 2 or 3, the sample itself from one."""
    if len(tp) >= 4:
        return make_interp_spline(tp, pp, k=3)(at)
    if len(tp) >= 2:
        return np.column_stack([np.interp(at, tp, pp[:, j]) for j in range(pp.shape[1])])
    return np.broadcast_to(pp[0], (len(at), pp.shape[1]))
