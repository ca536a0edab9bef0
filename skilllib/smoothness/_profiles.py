"""Generated speed profiles and the measurements the SPARC chapters (1 and 2) make on them.

Sums of minimum-jerk submovements (:func:`minimum_jerk_submovements`), a profile cut at contact
(:func:`cut_at_contact`), noisy copies (:func:`noisy_copies`), the dip between two peaks
(:func:`speed_dip`), the shortest segment length from which SPARC settles (:func:`stable_from`), and
the two literal readings of the squared integrand that the KI 2020 paper prints
(:func:`sparc_squared_integral`, :func:`sparc_squared_sum`), which are *not* SPARC.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from ._measures import DEFAULT_AMP_TH, DEFAULT_FC, DEFAULT_PADLEVEL, minimum_jerk_speed, sparc_spectrum


def minimum_jerk_submovements(onsets: Sequence[float], fs: float, T: float = 1.0, D: float = 1.0) -> np.ndarray:
    """Speed of a sum of identical minimum-jerk submovements, sampled from the first onset.

    Parameters
    ----------
    onsets : sequence of float
        Start time of each submovement (s), the first one at 0.
    fs : float
        Sampling rate (Hz).
    T : float
        Duration of each submovement (s).
    D : float
        Amplitude of each submovement (m).

    Returns
    -------
    numpy.ndarray
        Speed (m/s) at the times ``0, 1/fs, ...`` up to the end of the last submovement (exclusive),
        the sum of :func:`minimum_jerk_speed` over the onsets.
    """
    onsets = np.asarray(onsets, dtype=float)
    if onsets.ndim != 1 or onsets.size == 0 or not fs > 0 or not T > 0:
        raise ValueError(f"need a non-empty 1-D list of onsets, fs > 0 and T > 0; got {onsets}, {fs}, {T}")
    t = np.arange(0, onsets.max() + T, 1 / fs)
    return minimum_jerk_speed(t[:, None], onsets, T, D).sum(axis=1)


def cut_at_contact(speed: ArrayLike, ratio: float) -> np.ndarray:
    """A speed profile cut where a contact would end it, on the falling flank.

    Parameters
    ----------
    speed : array_like
        Speed samples (m/s) of one movement.
    ratio : float
        Speed at contact as a fraction of the peak speed (dimensionless), in (0, 1).

    Returns
    -------
    numpy.ndarray
        The samples before the first one after the peak whose speed is below ``ratio`` times the peak
        (m/s): the profile ends at non-zero speed, as the experiment's trials do.
    """
    v = np.asarray(speed, dtype=float)
    if not 0 < ratio < 1 or v.ndim != 1 or v.size == 0:
        raise ValueError(f"need a 1-D speed profile and a ratio in (0, 1), got ratio {ratio}")
    peak = int(np.argmax(v))
    below = np.flatnonzero(v[peak:] < ratio * v[peak])
    if below.size == 0:
        raise ValueError(f"the speed never falls below {ratio} of its peak after the peak")
    return v[: peak + below[0]]


def noisy_copies(
    speed: ArrayLike, level: float, n: int | None = None, rng: np.random.Generator | None = None
) -> np.ndarray:
    """Copies of a speed profile with Gaussian speed noise, made non-negative.

    Parameters
    ----------
    speed : array_like
        Speed samples (m/s).
    level : float
        Standard deviation of the noise as a fraction of the peak speed (dimensionless; 0.01 is 1 %).
    n : int or None
        Number of copies (dimensionless); None for one copy.
    rng : numpy.random.Generator or None
        Source of the noise (``numpy.random.default_rng()`` when None).

    Returns
    -------
    numpy.ndarray
        ``|v + noise|`` (m/s): shape ``(n, len(speed))``, or ``(len(speed),)`` when ``n`` is None. The
        copies draw their noise one after the other, as ``n`` separate calls would.
    """
    v = np.asarray(speed, dtype=float)
    rng = np.random.default_rng() if rng is None else rng
    shape = v.shape if n is None else (n, v.size)
    return np.abs(v + rng.normal(0, level * v.max(), shape))


def speed_dip(speed: ArrayLike) -> float:
    """Lowest speed between the first and the last local maximum of a profile.

    Parameters
    ----------
    speed : array_like
        Speed samples (m/s).

    Returns
    -------
    float
        The lowest speed (m/s) from the first to the last local maximum; the peak speed itself when the
        profile has a single maximum (no dip).
    """
    v = np.asarray(speed, dtype=float)
    peaks = np.flatnonzero((v[1:-1] > v[:-2]) & (v[1:-1] >= v[2:])) + 1
    if peaks.size == 0:
        return float(v.max())
    return float(v[peaks[0] : peaks[-1] + 1].min())


def stable_from(x: ArrayLike, values: ArrayLike, tol: float = 0.01) -> float:
    """The smallest ``x`` from which ``values`` stay within ``tol`` of their value at the last ``x``.

    Parameters
    ----------
    x : array_like
        Increasing parameter, e.g. the segment length (samples).
    values : array_like
        A measure at each ``x``, e.g. SPARC (dimensionless).
    tol : float
        Largest accepted distance from the last value, in the units of ``values`` (dimensionless
        for SPARC).

    Returns
    -------
    float
        ``x[i]`` for the smallest ``i`` with ``|values[j] - values[-1]| <= tol`` for every ``j >= i``.
    """
    x, values = np.asarray(x), np.asarray(values, dtype=float)
    if x.shape != values.shape or x.ndim != 1 or x.size == 0:
        raise ValueError(f"x and values need one and the same 1-D shape, got {x.shape} and {values.shape}")
    off = np.flatnonzero(np.abs(values - values[-1]) > tol)
    return x[off[-1] + 1].item() if off.size else x[0].item()


def sparc_squared_integral(
    speed: ArrayLike,
    fs: float,
    unit: str = "rad/s",
    fc: float = DEFAULT_FC,
    amp_th: float = DEFAULT_AMP_TH,
    padlevel: float = DEFAULT_PADLEVEL,
) -> float:
    """The integral the KI 2020 paper prints, squared integrand in place of SPARC's square root.

    ``-int_0^{omega_c} ((1/omega_c)**2 + (dV^/domega)**2)**2 domega`` as a Riemann sum over SPARC's band
    (:func:`sparc_spectrum`). Not SPARC: it has units (s^3 with omega in rad/s) and scales with the
    cube of the movement's duration; chapter 1 of the book shows why the square must be a slip.

    Parameters
    ----------
    speed : array_like
        Speed samples (m/s).
    fs : float
        Sampling rate (Hz).
    unit : {"rad/s", "Hz"}
        The unit of the frequency axis omega.
    fc, amp_th, padlevel : float
        SPARC's band parameters, as :func:`sparc`: the maximum cut-off (Hz), the amplitude
        threshold (dimensionless) and the zero-padding level (dimensionless).

    Returns
    -------
    float
        The value, in s^3 for ``"rad/s"`` (and in Hz^-3 for ``"Hz"``).
    """
    scale = {"rad/s": 2 * np.pi, "Hz": 1.0}.get(unit)
    if scale is None:
        raise ValueError(f'unit must be "rad/s" or "Hz", got {unit!r}')
    s = sparc_spectrum(speed, fs, fc, amp_th, padlevel)
    w = scale * s.f_sel
    dw = np.diff(w)
    return float(-np.sum(((1 / w[-1]) ** 2 + (np.diff(s.Mf_sel) / dw) ** 2) ** 2 * dw))


def sparc_squared_sum(
    speed: ArrayLike,
    fs: float,
    fc: float = DEFAULT_FC,
    amp_th: float = DEFAULT_AMP_TH,
    padlevel: float = DEFAULT_PADLEVEL,
) -> float:
    """SPARC's discrete sum with the printed square in place of the square root.

    ``-sum_k (1/K**2 + (V^_{k+1} - V^_k)**2)`` over the K intervals of SPARC's band. Not SPARC: each term
    is of the order of 1/K**2, so the value follows the FFT grid (padlevel, and the number of samples
    between two powers of two).

    Parameters
    ----------
    speed : array_like
        Speed samples (m/s).
    fs : float
        Sampling rate (Hz).
    fc, amp_th, padlevel : float
        SPARC's band parameters, as :func:`sparc`: the maximum cut-off (Hz), the amplitude
        threshold (dimensionless) and the zero-padding level (dimensionless).

    Returns
    -------
    float
        The sum (dimensionless); 0 for a band of one bin.
    """
    s = sparc_spectrum(speed, fs, fc, amp_th, padlevel)
    K = s.f_sel.size - 1
    if K == 0:
        return 0.0
    return float(-np.sum(1 / K**2 + np.diff(s.Mf_sel) ** 2))
