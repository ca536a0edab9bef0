"""One trial's approach: velocity by a Savitzky-Golay derivative, onset and contact, the segment.

The per-trial definitions of :mod:`skilllib.features` (its docstring gives the method and the reasons
for it): :func:`velocity`, :func:`segment_arrays` and the texts of the reasons why a trial cannot be
segmented. :mod:`skilllib.features` computes the same for many trials at once and is tested against these.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.signal import savgol_filter

from ._filtering import Lowpass

ONSET_SPEED = 0.05  #: m/s, movement onset threshold (the paper)
CONTACT_WINDOW = (0.3, 0.7)  #: m/s, selected contact speeds, inclusive (the paper)
MIN_SEGMENT_SAMPLES = 5  #: fewer samples from onset to contact: too short to analyse
DIFF_SPAN_S = 2 / 60  #: s, span of the differentiating window (3 samples at the experiment's 60 Hz)
MIN_DIFF_WINDOW = 3  #: samples: the smallest differentiating window (a quadratic needs three points)
MIN_APPROACH_SAMPLES = 2  #: fewer samples before contact leave nothing to differentiate


@dataclass(frozen=True)
class Segment:
    """The approach of one trial from onset to the last sample before contact.

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
        Indices (samples) in the trial of the onset sample and of the first contact sample.
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
        """Onset to contact in s (``N / fs``)."""
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


def segment_arrays(
    t: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray,
    fs: float,
    *,
    onset_speed: float = ONSET_SPEED,
    min_samples: int = MIN_SEGMENT_SAMPLES,
    participant: Any = None,
    trial: Any = None,
    lowpass: Lowpass | None = None,
) -> Segment | str:
    """Segment one trial's samples; returns the :class:`Segment` or the reason it cannot be segmented.

    ``lowpass``: the filter applied to the approach's positions before they are differentiated
    (:mod:`skilllib.features`; None: none); the segment's ``pos`` are then the filtered positions.

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
    onset_speed : float
        The speed above which the movement has begun (m/s).
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
        The segment (times in s, positions in m, speeds in m/s), or the reason (text) why the trial cannot
        be segmented.
    """
    hits = np.flatnonzero(contact)
    if hits.size == 0:
        return NO_CONTACT
    c = int(hits[0])
    if c < MIN_APPROACH_SAMPLES:
        return in_contact_reason(c)
    if lowpass is not None and lowpass.cutoff_hz is not None:
        pos = np.concatenate([lowpass.apply(pos[:c], fs), pos[c:]])
    vel = velocity(pos[:c], fs)
    speed = np.linalg.norm(vel, axis=1)
    moving = np.flatnonzero(speed > onset_speed)
    if moving.size == 0:
        return no_onset_reason(onset_speed, speed.max())
    o = int(moving[0])
    if o == 0:
        return no_rest_reason(onset_speed, speed[0])
    n = c - o
    if n < min_samples:
        return too_short_reason(n, min_samples)
    return Segment(
        participant,
        trial,
        np.asarray(t[o:c], dtype=float),
        np.asarray(pos[o:c], dtype=float),
        vel[o:],
        speed[o:],
        float(fs),
        o,
        c,
    )


#: The reasons a trial cannot be segmented (:func:`segment_arrays`, :mod:`skilllib.features`).
NO_CONTACT = "no contact: the contact flag is never 1"


def in_contact_reason(c: int) -> str:
    return f"in contact from sample {c + 1}: no approach recorded before contact"


def no_onset_reason(onset_speed: float, max_speed: float) -> str:
    return f"no onset: speed stays below {onset_speed:g} m/s before contact (max {max_speed:.3f} m/s)"


def no_rest_reason(onset_speed: float, first_speed: float) -> str:
    return (
        f"no rest before onset: speed {first_speed:.2f} m/s > {onset_speed:g} m/s at the first sample "
        f"(the movement started before the recording)"
    )


def too_short_reason(n: int, min_samples: int) -> str:
    return f"too short: {n} samples from onset to contact (need at least {min_samples})"
