"""Synthetic hand paths for the robot tests: a vertical minimum-jerk descent cut at contact."""

from __future__ import annotations

import numpy as np


def minimum_jerk_descent(
    amplitude: float = 0.2, peak_speed: float = 1.0, fs: float = 60.0, fraction: float = 0.7
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A synthetic prototype: a vertical downward minimum-jerk movement cut at contact.

    Minimum-jerk position s(tau) = A (10 tau^3 - 15 tau^4 + 6 tau^5), speed peak 1.875 A / T
    (Flash & Hogan 1985), so T = 1.875 A / ``peak_speed``; ``amplitude`` A in m, ``peak_speed`` in
    m/s. Sampled at ``fs`` Hz from t = 0 while s <= ``fraction`` A: the movement ends at contact
    with non-zero speed, like the experiment's trials. Returns t (s), positions (N, 3) m and
    velocities (N, 3) m/s in the experiment frame (moving along -y, starting at the origin).

    Parameters
    ----------
    amplitude : float
        The full minimum-jerk amplitude A (m).
    peak_speed : float
        The peak speed of the full movement (m/s).
    fs : float
        The sampling rate (Hz).
    fraction : float
        The fraction of A at which contact ends the movement, in (0, 1] (dimensionless).

    Returns
    -------
    t : numpy.ndarray, shape (N,)
        The time stamps from 0 (s).
    positions : numpy.ndarray, shape (N, 3)
        The positions in the experiment frame (m).
    velocities : numpy.ndarray, shape (N, 3)
        The velocities in the experiment frame (m/s).

    Raises
    ------
    ValueError
        When ``amplitude``, ``peak_speed`` or ``fs`` is not positive, or ``fraction`` not in (0, 1].
    """
    if amplitude <= 0 or peak_speed <= 0 or fs <= 0 or not 0 < fraction <= 1:
        raise ValueError("amplitude (m), peak_speed (m/s), fs (Hz) must be positive and 0 < fraction <= 1")
    T = 1.875 * amplitude / peak_speed
    t = np.arange(0.0, T + 0.5 / fs, 1.0 / fs)
    tau = np.clip(t / T, 0.0, 1.0)
    s = amplitude * (10 * tau**3 - 15 * tau**4 + 6 * tau**5)
    keep = s <= fraction * amplitude + 1e-12
    sd = amplitude / T * 30 * tau**2 * (1 - tau) ** 2
    pos = np.zeros((t.size, 3))
    vel = np.zeros((t.size, 3))
    pos[:, 1], vel[:, 1] = -s, -sd
    return t[keep], pos[keep], vel[keep]
