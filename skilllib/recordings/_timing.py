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
* **jitter and dropped frames.** VR and game-engine logs stamp each sample with the frame time, which
  varies by a few ms, and drop frames now and then. A trial whose intervals all lie within
  :data:`JITTER_TOLERANCE` of ``dt`` is regular and used as recorded. Otherwise, as long as no interval
  exceeds :data:`MAX_GAP_INTERVALS` x ``dt``, the trial is **resampled** onto the uniform grid
  ``t0 + k dt`` (:func:`resample_uniform`): positions by a cubic interpolating spline
  (``scipy.interpolate.make_interp_spline``, k = 3, not-a-knot ends) fitted separately to the approach
  (samples before the first contact sample) and to the samples in contact, so that the impact's velocity
  step does not ring into the approach; contact from the first grid time at or after the first contact
  sample's time stamp. This assumes, as the loggers do, that each time stamp is the time its sample was
  taken. A longer gap (more than two frames missing in a row) cannot be bridged honestly and makes the
  trial ``invalid`` with the reason.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import make_interp_spline

RATE_TOLERANCE = 0.10  #: a trial's median interval may differ this much (relative) from the file's
MIXED_FRACTION = 0.05  #: more trials than this fraction at another rate: the file mixes rates (error)
JITTER_TOLERANCE = 0.02  #: intervals within (1 +- this) x dt are regular (0.1 ms rounding at 60 Hz is 0.6 %)
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
    """

    max_jitter: float
    dropped: int
    max_interval: float
    at: int
    dt: float
    frame_jitter: float

    @property
    def regular(self) -> bool:
        return self.max_jitter <= JITTER_TOLERANCE

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
    return Irregularity(float(rel.max()), dropped, float(d[k]), k + 1, float(dt), frame_jitter)


def resample_uniform(
    t: np.ndarray, pos: np.ndarray, contact: np.ndarray, dt: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Resample one trial onto the uniform grid ``t[0] + k dt`` (k = 0 .. floor((t[-1] - t[0]) / dt)).

    Positions: cubic interpolating splines, one through the approach samples (before the first contact
    sample) and one through the samples in contact (a part with fewer than 4 samples is interpolated
    linearly); a grid time between the last approach sample and the first contact sample is extrapolated
    from the approach spline. Contact: True from the first grid time at or after the first contact
    sample's time stamp.

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
    tc = t[c] if hits.size else np.inf
    out = np.empty((n, pos.shape[1]))
    before = grid < tc
    for part, where in ((slice(0, c), before), (slice(c, len(t)), ~before)):
        tp, pp = t[part], pos[part]
        if not where.any():
            continue
        if len(tp) >= 4:
            out[where] = make_interp_spline(tp, pp, k=3)(grid[where])
        elif len(tp) >= 2:
            out[where] = np.column_stack([np.interp(grid[where], tp, pp[:, j]) for j in range(pp.shape[1])])
        else:
            out[where] = pp[0]
    return grid, out, grid >= tc
