"""Movement smoothness: SPARC and LDLJ (Balasubramanian et al. 2015, J NeuroEng Rehab 12:112).

SPARC is computed exactly as its authors' code does (``monalysa.quality.smoothness.sparc``, the test
oracle): ``nfft = 2**(ceil(log2 N) + padlevel)``, the frequency grid ``arange(0, fs, fs/nfft)``, the FFT
magnitude normalised by its maximum, the bins ``f <= fc``, the band from the first to the last of them at
or above ``amp_th``, and the arc length of the normalised spectrum over that band with the frequency axis
divided by the band's width. Chapter 1 of the book derives the discrete sum from the integral. One
deliberate difference: ``fc`` above the Nyquist frequency ``fs / 2`` raises ValueError, where the
authors' code lets the band run on into the mirror image of the spectrum (bins between fs / 2 and fs).

:func:`sparc_spectrum` and :func:`sparc` use ``numpy.fft.fft`` like the authors. :func:`sparc_many`
evaluates only the bins it needs, for many profiles at once: a direct DFT by matrix product for short
profiles, batched FFTs for long ones; both paths share the band and arc-length helpers.
:func:`sparc_bands` adds how each band ended: at its adaptive cut-off (the spectrum fell below
``amp_th``) or *capped* by ``fc`` (the spectrum still reaches ``amp_th`` somewhere between ``fc`` and the
Nyquist frequency). A capped band is cut short by the parameter, not by the movement; chapter 2 shows
why such values are not comparable with the others.

The book's maximum cut-off is 20 Hz, the KI 2020 paper's "0 to 20 Hz" and the default of the SPARC
authors' MATLAB code (``SpectralArcLength``, parameters [0.05, 20, 4]); their Python code defaults to
10 Hz. On the book's short segments (a few tens of samples at 60 Hz) 10 Hz caps most bands (chapter 6
measures it), which is why the book uses 20 Hz; pass ``fc=10.0`` for the Python authors' setting.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ._spectral import (
    _arc_length,
    _as_speed,
    _band,
    _blocks,
    _check_fs,
    _check_params,
    _n_kept,
    _nffts,
    _pack,
    _sparc_block,
    frequencies,
    single_threaded,
)

#: Maximum cut-off frequency f_c (Hz) of the band: the paper's "0 to 20 Hz" (the authors' MATLAB default).
DEFAULT_FC = 20.0
#: Amplitude threshold V-bar of the adaptive cut-off (fraction of the peak magnitude).
DEFAULT_AMP_TH = 0.05
#: Zero padding: nfft = 2**(ceil(log2 N) + padlevel).
DEFAULT_PADLEVEL = 4
#: The SPARC parameters of the book and the pipeline: ``sparc(v, fs, **SPARC_PARAMS)``.
SPARC_PARAMS = MappingProxyType({"fc": DEFAULT_FC, "amp_th": DEFAULT_AMP_TH, "padlevel": DEFAULT_PADLEVEL})


# --- the frequency grid --------------------------------------------------------------------------


def nfft(n: int, padlevel: float = DEFAULT_PADLEVEL) -> int:
    """FFT length for ``n`` samples: ``2**(ceil(log2 n) + padlevel)``, as the authors' code.

    Parameters
    ----------
    n : int
        Number of samples of the profile (samples).
    padlevel : float
        Zero-padding level: powers of two added to ``ceil(log2 n)`` (dimensionless).

    Returns
    -------
    int
        The FFT length nfft (samples).
    """
    return int(_nffts(np.asarray(n), padlevel))


# --- one profile -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class SparcSpectrum:
    """The spectrum behind one SPARC value, for plots and for the step-by-step derivation.

    f, Mf: the whole FFT grid (Hz, 0 to fs) and the magnitude normalised by its maximum;
    f_sel, Mf_sel: the band the arc length runs over; cutoff: its last frequency omega_c / 2 pi (Hz);
    capped: True when fc, not the amplitude threshold, ended the band (Mf >= amp_th at some bin above fc
    and at or below the Nyquist frequency fs / 2).

    Attributes
    ----------
    sparc : float
        The SPARC value (dimensionless, <= 0).
    f : numpy.ndarray, shape (nfft,)
        The FFT frequency grid from 0 to fs (Hz).
    Mf : numpy.ndarray, shape (nfft,)
        The FFT magnitude normalised by its maximum (dimensionless).
    f_sel : numpy.ndarray
        The frequencies of the band the arc length runs over (Hz).
    Mf_sel : numpy.ndarray
        The normalised magnitude over that band (dimensionless).
    cutoff : float
        The last frequency of the band, the adaptive cut-off omega_c / 2 pi (Hz).
    nfft : int
        The FFT length (samples).
    fs : float
        The sampling rate of the profile (Hz).
    fc : float
        The maximum cut-off frequency the band was capped at (Hz).
    amp_th : float
        The amplitude threshold of the adaptive cut-off, a fraction of the peak magnitude (dimensionless).
    capped : bool
        True when ``fc``, not ``amp_th``, ended the band (dimensionless).
    """

    sparc: float
    f: np.ndarray
    Mf: np.ndarray
    f_sel: np.ndarray
    Mf_sel: np.ndarray
    cutoff: float
    nfft: int
    fs: float
    fc: float
    amp_th: float
    capped: bool = False


def sparc_spectrum(
    speed: ArrayLike,
    fs: float,
    fc: float = DEFAULT_FC,
    amp_th: float = DEFAULT_AMP_TH,
    padlevel: float = DEFAULT_PADLEVEL,
) -> SparcSpectrum:
    """SPARC of one speed profile with the spectrum it is computed from.

    SPARC = -int_0^{omega_c} sqrt((1/omega_c)**2 + (dV^/domega)**2) domega, V^ = V / V(0), with the
    adaptive cut-off omega_c = min{omega_c_max, min{omega : V^(r) < amp_th for all r > omega}}
    (Balasubramanian et al. 2015, definition of SPARC; book chapter 1, eqs. eq-sparc and eq-cutoff),
    evaluated as the authors' code does.

    Parameters
    ----------
    speed : array_like, shape (N,)
        The speed profile (m/s), finite and not all zero.
    fs : float
        Its sampling rate (Hz), finite and > 0.
    fc : float
        Maximum cut-off frequency of the band (Hz), at most the Nyquist frequency fs / 2.
    amp_th : float
        Amplitude threshold of the adaptive cut-off, a fraction of the peak magnitude (dimensionless).
    padlevel : float
        Zero-padding level of the FFT, see :func:`nfft` (dimensionless).

    Returns
    -------
    SparcSpectrum
        The SPARC value (dimensionless) with the frequency grid (Hz), the normalised magnitude and the band.

    Raises
    ------
    ValueError
        On a speed that is empty, not finite or all zero, a bad ``fs``, ``fc`` above fs / 2, or when no bin up
        to ``fc`` reaches ``amp_th``.
    """
    v = _as_speed(speed)
    fs = _check_fs(fs)
    _check_params(fc, amp_th, padlevel, fs)
    n_fft = nfft(v.size, padlevel)
    f = frequencies(n_fft, fs)
    k = _n_kept(f, fc)
    Mf = np.abs(np.fft.fft(v / np.abs(v).max(), n_fft))  # amplitude invariant; no overflow, as sparc_many
    peak = Mf.max()
    if not peak > 0:  # padlevel < 0: np.fft.fft(v, nfft) keeps only the first nfft samples
        raise ValueError(f"speed is zero over its first nfft = {n_fft} samples: no spectrum to normalise")
    Mf = Mf / peak
    first, last, ok = _band(Mf[None, :k] >= amp_th)
    if not ok[0]:
        raise ValueError(f"no spectral magnitude at or above amp_th = {amp_th} up to fc = {fc} Hz")
    value = -_arc_length(Mf[None, :k], np.ones(1), first, last)[0] + 0.0
    band = slice(int(first[0]), int(last[0]) + 1)
    capped = bool(np.any(Mf[k : n_fft // 2 + 1] >= amp_th))  # bins above fc up to Nyquist
    return SparcSpectrum(
        float(value), f[:n_fft], Mf, f[band], Mf[band], float(f[band][-1]), n_fft, fs, float(fc), float(amp_th), capped
    )


def sparc(
    speed: ArrayLike,
    fs: float,
    fc: float = DEFAULT_FC,
    amp_th: float = DEFAULT_AMP_TH,
    padlevel: float = DEFAULT_PADLEVEL,
) -> float:
    """Spectral arc length SPARC of a speed profile; dimensionless, <= -1.

    Balasubramanian et al. 2015 (definition of SPARC, with the adaptive cut-off), computed as the
    authors' code ``monalysa.quality.smoothness.sparc``. ``fc`` (Hz, at most fs / 2) caps the band,
    ``amp_th`` sets the adaptive cut-off, ``padlevel`` the zero padding. Closer to -1 is smoother. A band of
    a single bin (grid step fs/nfft > fc) gives 0, as in the authors' code. See :func:`sparc_spectrum`.

    Parameters
    ----------
    speed : array_like, shape (N,)
        The speed profile (m/s), finite and not all zero.
    fs : float
        Its sampling rate (Hz), finite and > 0.
    fc : float
        Maximum cut-off frequency of the band (Hz), at most the Nyquist frequency fs / 2.
    amp_th : float
        Amplitude threshold of the adaptive cut-off, a fraction of the peak magnitude (dimensionless).
    padlevel : float
        Zero-padding level of the FFT, see :func:`nfft` (dimensionless).

    Returns
    -------
    float
        The SPARC value (dimensionless).

    Raises
    ------
    ValueError
        As :func:`sparc_spectrum`: a bad speed profile, ``fs`` or parameter.
    """
    return sparc_spectrum(speed, fs, fc, amp_th, padlevel).sparc


def _sparc_blocks(
    speeds: Sequence[ArrayLike] | np.ndarray, fs: float, fc: float, amp_th: float, padlevel: float, bands: bool
) -> np.ndarray:
    fs = _check_fs(fs)
    _check_params(fc, amp_th, padlevel, fs)
    with single_threaded("blas"):  # the batches' matrix products are small
        parts = [
            _sparc_block(*_pack(block, start), start, fs, fc, amp_th, padlevel, bands)
            for start, block in _blocks(speeds)
        ]
    return np.concatenate(parts) if parts else np.empty((0, 3))


def sparc_many(
    speeds: Sequence[ArrayLike] | np.ndarray,
    fs: float,
    fc: float = DEFAULT_FC,
    amp_th: float = DEFAULT_AMP_TH,
    padlevel: float = DEFAULT_PADLEVEL,
) -> np.ndarray:
    """SPARC of each of many speed profiles (a ragged sequence of 1-D arrays, all at ``fs`` Hz).

    Same values as :func:`sparc` one by one (to rounding, about 1e-15), computed in batches of
    profiles with the same nfft: only the bins up to ``fc`` are evaluated. ValueError names the index
    of a bad profile.

    Parameters
    ----------
    speeds : sequence of array_like or numpy.ndarray
        The speed profiles (m/s), each 1-D, of any lengths; a 2-D array is one profile per row.
    fs : float
        Their sampling rate (Hz), finite and > 0.
    fc : float
        Maximum cut-off frequency of the band (Hz), at most fs / 2.
    amp_th : float
        Amplitude threshold of the adaptive cut-off, a fraction of the peak magnitude (dimensionless).
    padlevel : float
        Zero-padding level of the FFT, see :func:`nfft` (dimensionless).

    Returns
    -------
    numpy.ndarray, shape (K,)
        The SPARC value of each profile (dimensionless).

    Raises
    ------
    ValueError
        On a bad profile (named by its index), a bad ``fs`` or parameter.
    """
    return _sparc_blocks(speeds, fs, fc, amp_th, padlevel, bands=False)[:, 0]


class SparcBands(NamedTuple):
    """What :func:`sparc_bands` returns for K profiles: each one's SPARC and how its band ended.

    Per profile its SPARC, the last frequency of its band (the adaptive cut-off omega_c / 2 pi, Hz) and
    whether ``fc`` rather than the amplitude threshold ended the band.

    Parameters
    ----------
    sparc : numpy.ndarray, shape (K,)
        The SPARC value of each profile (dimensionless).
    band_end_hz : numpy.ndarray, shape (K,)
        The last frequency of each band, the adaptive cut-off omega_c / 2 pi (Hz).
    capped : numpy.ndarray of bool, shape (K,)
        True where ``fc``, not the amplitude threshold, ended the band (dimensionless).
    """

    sparc: np.ndarray
    band_end_hz: np.ndarray
    capped: np.ndarray


def sparc_bands(
    speeds: Sequence[ArrayLike] | np.ndarray,
    fs: float,
    fc: float = DEFAULT_FC,
    amp_th: float = DEFAULT_AMP_TH,
    padlevel: float = DEFAULT_PADLEVEL,
) -> SparcBands:
    """:func:`sparc_many` with how each band ended.

    Returns a ``SparcBands`` (the same as :func:`sparc_spectrum`'s ``cutoff`` and ``capped`` one by one).
    ``capped`` is True when the normalised spectrum reaches ``amp_th`` at some bin above ``fc`` (and at or
    below the Nyquist frequency fs / 2): raising ``fc`` would lengthen the band. Evaluates the bins up to
    Nyquist, so it costs more than sparc_many.

    Parameters
    ----------
    speeds : sequence of array_like or numpy.ndarray
        The speed profiles (m/s), each 1-D, of any lengths; a 2-D array is one profile per row.
    fs : float
        Their sampling rate (Hz), finite and > 0.
    fc : float
        Maximum cut-off frequency of the band (Hz), at most fs / 2.
    amp_th : float
        Amplitude threshold of the adaptive cut-off, a fraction of the peak magnitude (dimensionless).
    padlevel : float
        Zero-padding level of the FFT, see :func:`nfft` (dimensionless).

    Returns
    -------
    SparcBands
        Named tuple of arrays of shape (K,): ``sparc`` (dimensionless), ``band_end_hz``, the last frequency of
        each band (Hz), and ``capped`` (bool).

    Raises
    ------
    ValueError
        On a bad profile (named by its index), a bad ``fs`` or parameter.
    """
    out = _sparc_blocks(speeds, fs, fc, amp_th, padlevel, bands=True)
    return SparcBands(out[:, 0], out[:, 1], out[:, 2] == 1.0)


# --- log dimensionless jerk ------------------------------------------------------------------------


def _ldlj(n: np.ndarray, d2_cost: np.ndarray) -> np.ndarray:
    """LDLJ = -ln(n**3 * d2_cost), d2_cost = sum of the squared second differences of v / v_peak over
    the n samples: ``-ln |DLJ|``, DLJ = -(duration**3 / v_peak**2) int (d2v/dt2)**2 dt, with time in
    samples. The sampling interval dt cancels: duration = n dt, d2v/dt2 = (second difference) / dt**2
    and the integral a sum times dt give duration**3 int (d2v/dt2)**2 dt = n**3 d2_cost, so no power
    of dt can under- or overflow. Constant speed (d2_cost 0) gives +inf without a warning."""
    with np.errstate(divide="ignore"):
        return -np.log(np.asarray(n, dtype=float) ** 3 * d2_cost)


def ldlj(speed: ArrayLike, fs: float) -> float:
    """Log dimensionless jerk LDLJ of a speed profile (at least 3 samples).

    LDLJ = ``-ln |DLJ|``, DLJ = -((t2 - t1)**3 / v_peak**2) int_{t1}^{t2} (d2v/dt2)**2 dt
    (Balasubramanian et al. 2015, definition of LDLJ; chapter 2, eq-ldlj), as the authors' code
    ``log_dimensionless_jerk``: duration N/fs, jerk by second differences, the integral as a sum times
    1/fs; v / v_peak is differentiated (same value, no under- or overflow). The powers of 1/fs cancel
    (the measure is dimensionless), so the value depends on the samples only; ``fs`` is checked, and
    any finite fs > 0 gives the same finite value. More negative is less smooth; a profile of constant
    speed has no jerk and gives +inf.

    Parameters
    ----------
    speed : array_like, shape (N,)
        The speed profile (m/s), N >= 3, finite and not all zero.
    fs : float
        Its sampling rate (Hz), finite and > 0.

    Returns
    -------
    float
        The LDLJ value (dimensionless); +inf for constant speed.

    Raises
    ------
    ValueError
        On fewer than 3 samples, a speed not finite or all zero, or a bad ``fs``.
    """
    v = _as_speed(speed, min_len=3)
    _check_fs(fs)
    d2 = np.diff(v / np.abs(v).max(), 2)
    return float(_ldlj(v.size, np.sum(d2**2)))


def ldlj_rows(speeds: ArrayLike, fs: float) -> np.ndarray:
    """LDLJ of each row of a (K, N) block of speed profiles.

    :func:`ldlj` row by row, with the same bits (the same operations along the rows; used by
    :mod:`skilllib.features`).

    Parameters
    ----------
    speeds : array_like, shape (K, N)
        The speed profiles (m/s), one per row, N >= 3.
    fs : float
        Their sampling rate (Hz), finite and > 0.

    Returns
    -------
    numpy.ndarray, shape (K,)
        The LDLJ value of each row (dimensionless).

    Raises
    ------
    ValueError
        When ``speeds`` is not a (K, N) block with N >= 3, a row is not finite or all zero, or ``fs`` is bad.
    """
    v = np.asarray(speeds, dtype=float)
    if v.ndim != 2 or v.shape[1] < 3:
        raise ValueError(f"speeds must be a (K, N) block with N >= 3 samples; got shape {v.shape}")
    _check_fs(fs)
    bad = ~np.isfinite(v).all(axis=1) | ~v.any(axis=1)
    if bad.any():
        _as_speed(v[np.flatnonzero(bad)[0]], f"speeds[{np.flatnonzero(bad)[0]}]")
    d2 = np.diff(v / np.abs(v).max(axis=1, keepdims=True), 2, axis=1)
    return _ldlj(v.shape[1], np.sum(d2**2, axis=1))


def _ldlj_block(flat: np.ndarray, lengths: np.ndarray, start: int, block: Sequence[ArrayLike]) -> np.ndarray:
    """LDLJ of each profile of one packed block: second differences of the concatenated samples,
    those straddling two profiles set to zero, summed per profile."""
    flat = flat[:-1]  # without _pack's trailing zero
    offsets = np.cumsum(lengths) - lengths
    v_peak = np.maximum.reduceat(np.abs(flat), offsets)
    zero = np.flatnonzero(v_peak == 0)
    if zero.size:
        _as_speed(block[zero[0]], f"speeds[{start + zero[0]}]")
    d2sq = np.diff(flat / np.repeat(v_peak, lengths), 2) ** 2
    ends = (offsets + lengths)[:-1]
    d2sq[np.concatenate([ends - 2, ends - 1])] = 0.0  # differences across two profiles
    return _ldlj(lengths, np.add.reduceat(d2sq, offsets))


def ldlj_many(speeds: Sequence[ArrayLike] | np.ndarray, fs: float) -> np.ndarray:
    """LDLJ of each of many speed profiles (ragged, all at ``fs`` Hz).

    :func:`ldlj` one by one, vectorised over the concatenated samples. ValueError names the index of a
    bad profile.

    Parameters
    ----------
    speeds : sequence of array_like or numpy.ndarray
        The speed profiles (m/s), each 1-D with at least 3 samples.
    fs : float
        Their sampling rate (Hz), finite and > 0 (the values do not depend on it).

    Returns
    -------
    numpy.ndarray, shape (K,)
        The LDLJ value of each profile (dimensionless).

    Raises
    ------
    ValueError
        On a bad profile (named by its index) or a bad ``fs``.
    """
    _check_fs(fs)  # LDLJ does not depend on fs (see ldlj)
    parts = [_ldlj_block(*_pack(block, start, min_len=3), start, block) for start, block in _blocks(speeds)]
    return np.concatenate(parts) if parts else np.empty(0)


# --- reference profiles ----------------------------------------------------------------------------


def minimum_jerk_speed(t: ArrayLike, t0: ArrayLike = 0.0, T: ArrayLike = 1.0, D: ArrayLike = 1.0) -> np.ndarray:
    """Speed of a minimum-jerk submovement at times ``t``.

    A submovement of amplitude D (m) and duration T (s) starting at t0 (s):
    v = (D/T) 30 tau**2 (1 - tau)**2, tau = (t - t0)/T in [0, 1], else 0; peak 1.875 D/T at tau = 0.5
    (Flash & Hogan 1985). Broadcasts, so submovements sum along an axis.

    Parameters
    ----------
    t : array_like
        The times (s).
    t0 : array_like
        The start time of the submovement (s).
    T : array_like
        Its duration (s), > 0.
    D : array_like
        Its amplitude, the distance travelled (m).

    Returns
    -------
    numpy.ndarray
        The speed at each time (m/s), broadcast over ``t``, ``t0``, ``T`` and ``D``.
    """
    tau = (np.asarray(t, dtype=float) - t0) / T
    inside = (tau >= 0) & (tau <= 1)
    return np.where(inside, np.asarray(D) / T * 30 * tau**2 * (1 - tau) ** 2, 0.0)


def minimum_jerk_segment(n: int, contact_ratio: float, fs: float, onset_ratio: float = 0.05) -> np.ndarray:
    """Speed samples of one minimum-jerk movement segmented as the experiment's trials are.

    From the onset, where the speed reaches ``onset_ratio`` of the peak (sample 0), to the last sample
    before the contact, where it has fallen to ``contact_ratio`` of the peak on the falling flank (sample n
    would lie there); the movement's duration is chosen so that this takes exactly ``n`` samples at ``fs``
    Hz (duration n / fs). The same shape at every n: SPARC should not depend on n.

    With v / v_peak = 16 tau**2 (1 - tau)**2 (Flash & Hogan 1985), onset and contact fall at
    tau = (1 -+ sqrt(1 - sqrt(ratio))) / 2.

    Parameters
    ----------
    n : int
        Number of samples of the segment (samples), >= 1.
    contact_ratio : float
        Speed at the contact as a fraction of the peak speed (dimensionless), in (0, 1).
    fs : float
        The sampling rate (Hz).
    onset_ratio : float
        Speed at the onset as a fraction of the peak speed (dimensionless), in (0, 1).

    Returns
    -------
    numpy.ndarray, shape (n,)
        The speed samples in units of the peak speed (dimensionless).

    Raises
    ------
    ValueError
        When ``n < 1`` or a ratio is outside (0, 1).
    """
    if not (0 < onset_ratio < 1 and 0 < contact_ratio < 1) or n < 1:
        raise ValueError(
            f"need n >= 1 and ratios in (0, 1); got n = {n}, onset_ratio = {onset_ratio}, "
            f"contact_ratio = {contact_ratio}"
        )
    tau0 = (1 - np.sqrt(1 - np.sqrt(onset_ratio))) / 2
    tau_c = (1 + np.sqrt(1 - np.sqrt(contact_ratio))) / 2
    T = n / fs / (tau_c - tau0)  # s: the whole movement's duration
    tau = tau0 + np.arange(n) / fs / T
    return 16 * tau**2 * (1 - tau) ** 2
