"""Low-pass filtering of positions before they are differentiated: zero-lag Butterworth, Winter's rule.

Tracker noise is white in position; differentiating it multiplies it by the frequency, so a speed taken
from raw positions of optical or VR trackers (0.1-1 mm RMS at 100-250 Hz) is noisy enough to cross the
paper's 0.05 m/s onset threshold at rest. Biomechanics therefore low-pass filters positions first
(Winter 2009, *Biomechanics and Motor Control of Human Movement*, 4th ed., sec. 2.2.4):

* **The filter.** A Butterworth low-pass of order :data:`ORDER` (2), run forwards and backwards
  (``scipy.signal.butter(..., output="sos")`` and ``sosfiltfilt``): no phase lag, and order 4 in effect.
  Running it twice squares its gain, so its -3 dB point moves down. **The cut-off this module names is the
  -3 dB frequency of the whole forward-backward filter**; the single pass is designed at
  ``cutoff / C`` with Winter's correction ``C = (2**(1/passes) - 1)**(1/(2 order))`` (0.802 for order 2,
  two passes), made exact for the digital filter by the bilinear transform's warping,
  :func:`design_frequency`.
* **Winter's residual analysis** chooses the cut-off from the data (:func:`residual_analysis`): the RMS
  residual between raw and filtered positions, R(f), falls as the cut-off f rises; above the movement's
  band it is noise only and falls linearly to 0 at the Nyquist frequency. The straight line fitted to
  that part (cut-offs from :data:`NOISE_FIT_RANGE` of the Nyquist frequency) meets f = 0 at the noise's
  RMS amplitude a; the cut-off is the lowest f with R(f) <= a, where the signal distortion left equals the
  noise let through.
* **When to filter.** ``"auto"`` (the default) filters only when it is needed: when the position noise,
  differentiated over the pipeline's window, gives a 3-D speed noise (RMS) above
  :data:`SPEED_NOISE_LIMIT` (5 mm/s, a tenth of the onset threshold; the SPARC chapter shows that speed
  noise of 1-3 % of the peak speed leaves SPARC unchanged). The noise is measured **per axis**
  (:func:`measure_rest_noise`), from the median absolute fourth difference, which white noise has and a
  still, swaying or even smoothly moving hand has not; the median over trials. Trackers are rarely equally
  noisy on every axis (a camera's depth axis is the noisiest), and a median pooled over the axes reads
  noise on one axis only as none at all; the speed noise therefore adds the three axes' variances through
  the derivative's gain (:func:`speed_noise`). When the three axes agree within :data:`ISOTROPY_RATIO`
  the noise is isotropic and its common SD is estimated from the axes pooled (three times the samples in
  one median). Winter's intercept is not used for this decision: a recording without noise but with an
  abrupt start (a kink) has broadband content that his line reads as noise. The book's 60 Hz cohort
  (0.03 mm, about 2 mm/s) is therefore not filtered, and its results are those of the paper's procedure. A
  number filters at that cut-off; ``"none"`` never filters.
* **Where the hand rests.** The noise is read in each trial's **rest window** (:func:`rest_window`), not
  assumed in its first samples: :func:`rest_samples` samples (:data:`REST_S`, at least
  :data:`REST_MIN_SAMPLES`), the earliest window of the approach in which the hand is still, the speed of
  the straight line fitted to it below :data:`REST_SPEED`; when no window is that still (a trial that
  starts in motion), the window whose line is slowest.
* **Borderline decisions.** A speed noise within :data:`BORDERLINE_FRACTION` (20 %) of the limit is a
  decision that a few samples more or less can flip: the :class:`Lowpass` says so (``borderline``, and
  :func:`skilllib.features.trial_features` writes in its ``note`` what the other choice would change:
  trials whose status changes, the median change of SPARC), and the pipeline reports the note.

Only the samples before contact are filtered (the approach; the impact is a velocity step that a filter
would smear into it). Each end is extended before filtering, so that the filter's start-up transient falls
outside the recording, not by scipy's odd reflection about the raw end sample, whose noise the filter
would keep as a step at the first sample (:func:`_extend`). **The start** is extended by a quadratic or a
line fitted to its first samples, the residuals reflected evenly about it: a hand at rest stays at rest, one
already moving keeps its speed and acceleration. Which polynomial, fitted to how many samples, is chosen
per axis by Lepski's rule (Lepski & Spokoiny 1997, Ann. Stat. 25:2512): windows from
:data:`EDGE_MIN_PERIODS` of a period of the cut-off (at least :data:`EDGE_MIN_SAMPLES`) up to one period,
each :data:`EDGE_GROWTH` times the last, a quadratic and a line over each; ordered by their slope's
standard error, the last whose value and slope at the first sample agree, within :data:`EDGE_KAPPA`
standard errors (from that axis's own noise), with those of every noisier one. A long
rest gives a long line and little noise; a short rest or a start in motion, where a long fit would be
bent by the movement, a short one. **The end** is extended by odd reflection about a straight line fitted
to its last :data:`END_FIT_S` (the approach decelerating towards contact).
What filtering does to SPARC is shown in chapter 13: it removes spectrum above the cut-off, and a band
that SPARC reads beyond the cut-off is partly the filter's (the pipeline counts those trials).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.signal import butter, freqz, savgol_coeffs, sosfiltfilt, sosfreqz

ORDER = 2  #: Butterworth order of one pass (two passes: order 4, zero lag)
PASSES = 2  #: forwards and backwards
SPEED_NOISE_LIMIT = 0.005  #: m/s, 3-D speed noise (RMS) above which "auto" filters
NOISE_FIT_RANGE = (0.5, 0.9)  #: fractions of the Nyquist frequency where the residual is fitted as noise
MIN_CUTOFF_HZ = 2.0  #: the lowest cut-off the residual analysis proposes (Hz)
RESIDUAL_TRIALS = 100  #: trials the residual analysis looks at (evenly spaced over the file, deterministic)
EDGE_MIN_SAMPLES = 5  #: samples, the shortest window the start's quadratic is fitted to (:func:`_extend`)
EDGE_MIN_PERIODS = 0.25  #: periods of the cut-off the shortest window spans (at least EDGE_MIN_SAMPLES)
EDGE_GROWTH = 1.25  #: each window of Lepski's rule this factor longer than the one before
EDGE_KAPPA = 5.0  #: standard errors two fits at the start may differ by (Lepski's rule; high: the comparisons are many)
EDGE_NOISE_FLOOR_M = 1e-6  #: m, the least noise SD Lepski's rule assumes (noise-free recordings)
END_FIT_S = 0.05  #: s, samples at the end a straight line is fitted to
N_CUTOFFS = 60  #: cut-offs the residual analysis scans
REST_S = 0.1  #: s, the length of the rest window where the noise is measured (:func:`rest_window`)
REST_MIN_SAMPLES = 16  #: samples of that start at least (at low rates; 0.27 s at 60 Hz)
REST_SPEED = 0.025  #: m/s, a rest window's fitted line is slower than this (half the onset speed)
ISOTROPY_RATIO = 1.5  #: the largest axis's noise within this factor of the smallest: isotropic, pooled
BORDERLINE_FRACTION = 0.2  #: an auto decision within this fraction of the limit is borderline
LOWPASS_CHOICES = ("auto", "none")


def design_frequency(cutoff_hz: float, order: int = ORDER, passes: int = PASSES, fs: float | None = None) -> float:
    """The single-pass Butterworth design frequency (Hz) whose ``passes``-fold application has its -3 dB
    point at ``cutoff_hz``: ``cutoff / C``, ``C = (2**(1/passes) - 1)**(1/(2 order))`` (Winter 2009), for an
    analog filter. With ``fs`` (Hz) it is exact for the digital filter scipy designs (bilinear transform,
    prewarped at the design frequency): ``tan(pi fd / fs) = tan(pi cutoff / fs) / C``."""
    c = (2 ** (1 / passes) - 1) ** (1 / (2 * order))
    if fs is None:
        return cutoff_hz / c
    return float(fs / np.pi * np.arctan(np.tan(np.pi * cutoff_hz / fs) / c))


def _fit_weights(k: int, degree: int) -> np.ndarray:
    """(3, k): least-squares weights giving a polynomial's (degree 1 or 2) value, slope and half curvature per
    sample at sample 0 from ``k`` samples 0..k-1 (the curvature row 0 for a line)."""
    w = np.linalg.pinv(np.vander(np.arange(k, dtype=float), degree + 1, increasing=True))
    return np.vstack([w, np.zeros((2 - degree, k))])


def _start_quadratic(x: np.ndarray, k_max: int, k_min: int = EDGE_MIN_SAMPLES) -> np.ndarray:
    """(3, m): per column of ``x`` (N, m), the coefficients (in samples) of the low-order polynomial fitted to
    its first samples that Lepski's rule chooses (module docstring): the candidates, a quadratic and a line
    over each window of ``k_min`` (at least :data:`EDGE_MIN_SAMPLES`) .. ``k_max`` samples (growing by
    :data:`EDGE_GROWTH`), ordered by their slope's standard error, largest first; the last whose value and
    slope at sample 0 lie within :data:`EDGE_KAPPA` standard errors of those of every candidate before it.
    The standard errors from the column's white-noise SD (median absolute fourth difference over the
    column, at least :data:`EDGE_NOISE_FLOOR_M`)."""
    n, m = x.shape
    k_min = min(max(EDGE_MIN_SAMPLES, k_min), n)
    if k_min < 3:  # too short for a quadratic: the mean, flat
        return np.vstack([x.mean(axis=0), np.zeros((2, m))])
    sd = np.full(m, EDGE_NOISE_FLOOR_M)
    if n >= 5:
        sd = np.maximum(np.median(np.abs(np.diff(x, 4, axis=0)), axis=0) / REST_NOISE_SCALE, EDGE_NOISE_FLOOR_M)
    top = max(k_min, min(k_max, n))  # windows growing geometrically: few comparisons, each a real step
    ks = sorted(
        {min(top, int(round(k_min * EDGE_GROWTH**i))) for i in range(64) if k_min * EDGE_GROWTH ** (i - 1) < top}
    )
    weights = [_fit_weights(k, d) for k in ks for d in (2, 1)]
    unit_se = np.stack([np.sqrt(np.sum(w[:2] ** 2, axis=1)) for w in weights])  # (K, 2) per unit noise SD
    order = np.argsort(-unit_se[:, 1], kind="stable")
    weights = [weights[i] for i in order]
    coef = np.stack([w @ x[: w.shape[1]] for w in weights])  # (K, 3, m)
    se = unit_se[order][:, :, None] * sd  # (K, 2, m)
    out = np.empty((3, m))
    for j in range(m):
        best = 0
        for i in range(1, len(weights)):
            if np.any(np.abs(coef[i, :2, j] - coef[:i, :2, j]) > EDGE_KAPPA * se[:i, :, j]):
                break
            best = i
        out[:, j] = coef[best, :, j]
    return out


def _extend(x: np.ndarray, n_pad: int, k_start: int, n_fit_end: int, k_min: int = EDGE_MIN_SAMPLES) -> np.ndarray:
    """``x`` (N, m) with ``n_pad`` samples added at each end (module docstring).

    The start: the quadratic q of :func:`_start_quadratic` (windows of at most ``k_start`` samples),
    continued before sample 0, plus the residuals reflected evenly, ``x[-j] = q(-j) + x[j] - q(j)``: a hand
    at rest stays at rest and one in motion keeps its speed and acceleration, while the first sample's noise
    is not pinned as a step (as scipy's odd reflection about it would). The end: odd reflection about the
    value, at the end, of a straight line fitted to the last ``n_fit_end`` samples (the approach still moves
    at contact: the line keeps the end's slope with less of its noise)."""
    n = len(x)
    c = _start_quadratic(x, k_start, k_min)
    j = np.arange(n_pad, 0, -1, dtype=float)[:, None]
    head = c[0] - c[1] * j + c[2] * j**2 + x[n_pad:0:-1] - (c[0] + c[1] * j + c[2] * j**2)
    k1 = max(2, min(n_fit_end, n))
    a1 = np.polyfit(np.arange(k1, dtype=float), x[n - k1 :], 1)
    last = a1[0] * (k1 - 1) + a1[1]
    tail = 2 * last - x[n - 2 : n - 2 - n_pad : -1]
    return np.concatenate([head, x, tail])


def butterworth_lowpass(pos: np.ndarray, fs: float, cutoff_hz: float, order: int = ORDER) -> np.ndarray:
    """Positions (N, ...) low-pass filtered along axis 0 with a zero-lag Butterworth filter whose
    forward-backward -3 dB frequency is ``cutoff_hz`` (Hz; the design frequency below ``fs / 2``).

    The ends are extended by :func:`_extend` over about two periods of the design frequency (at most
    N - 1 samples): the start by a local quadratic fitted to at most one period of the cut-off (fewer
    samples when the hand moves: Lepski's rule), the end by odd reflection about a line fitted to
    :data:`END_FIT_S`, so that the filter's start-up transient falls outside the recording and the first
    sample's speed is not changed by it (module docstring).

    Parameters
    ----------
    pos : numpy.ndarray, shape (N, ...)
        The positions (m), N >= 2.
    fs : float
        The sampling rate (Hz).
    cutoff_hz : float
        The -3 dB frequency of the forward-backward filter (Hz).
    order : int
        The Butterworth order of one pass (dimensionless).

    Returns
    -------
    numpy.ndarray
        The filtered positions (m), the shape of ``pos``.

    Raises
    ------
    ValueError
        When the design frequency is not below ``fs / 2``.
    """
    fd = design_frequency(cutoff_hz, order, fs=fs)
    if not 0 < cutoff_hz < fs / 2:
        raise ValueError(
            f"a low-pass cut-off of {cutoff_hz:g} Hz (designed at {fd:.3g} Hz) needs a sampling rate "
            f"above {2 * fd:.3g} Hz; these recordings are sampled at {fs:g} Hz"
        )
    sos = butter(order, fd, btype="low", fs=fs, output="sos")
    pos = np.asarray(pos, dtype=float)
    shape = pos.shape
    x = pos.reshape(len(pos), -1)
    n_pad = min(len(x) - 1, int(np.ceil(2 * fs / fd)))
    y = sosfiltfilt(
        sos,
        _extend(
            x,
            n_pad,
            max(EDGE_MIN_SAMPLES, int(round(fs / cutoff_hz))),
            max(3, int(round(END_FIT_S * fs))),
            int(round(EDGE_MIN_PERIODS * fs / cutoff_hz)),
        ),
        axis=0,
        padtype=None,
    )
    return y[n_pad : n_pad + len(x)].reshape(shape)


def speed_noise(
    position_noise_m: float | Sequence[float] | np.ndarray,
    fs: float,
    window: int,
    cutoff_hz: float | None = None,
    order: int = ORDER,
) -> float:
    """3-D speed noise (RMS, m/s) of white position noise after the zero-lag low-pass and the derivative.

    By Parseval's theorem each axis's speed variance is its position variance times the mean over
    0..fs/2 of ``|D(f)|**2 |H(f)|**(2 passes)`` (D the Savitzky-Golay derivative, quadratic over ``window``
    samples; H the low-pass at ``cutoff_hz``); the 3-D speed noise adds the three axes' variances.

    Parameters
    ----------
    position_noise_m : float or array_like of 3 floats
        The white position noise's SD (m): one value, the same on every axis, or one per axis (x, y, z).
    fs : float
        The sampling rate (Hz).
    window : int
        The differentiating window (samples).
    cutoff_hz : float or None
        The low-pass cut-off (Hz); None: no filter.
    order : int
        The Butterworth order of one pass (dimensionless).

    Returns
    -------
    float
        The 3-D speed noise, RMS (m/s).
    """
    f = np.linspace(0, fs / 2, 4097)
    _, d = freqz(savgol_coeffs(window, 2, deriv=1, delta=1.0 / fs, use="dot"), worN=f, fs=fs)
    gain = np.abs(d) ** 2
    if cutoff_hz is not None:
        _, h = sosfreqz(butter(order, design_frequency(cutoff_hz, order, fs=fs), fs=fs, output="sos"), worN=f, fs=fs)
        gain = gain * np.abs(h) ** (2 * PASSES)
    g = np.sqrt(np.trapezoid(gain, f) / (fs / 2))
    if np.ndim(position_noise_m) == 0:
        return float(np.sqrt(3) * float(position_noise_m) * g)
    return float(np.sqrt(np.sum(np.square(np.asarray(position_noise_m, dtype=float)))) * g)


def max_cutoff(fs: float, order: int = ORDER) -> float:
    """The highest cut-off (Hz) the zero-lag filter can have at ``fs`` (design frequency just below Nyquist)."""
    return fs / 2 * (2 ** (1 / PASSES) - 1) ** (1 / (2 * order)) * 0.99


#: Median absolute fourth difference of white Gaussian noise of SD 1 (see :func:`rest_noise`).
REST_NOISE_SCALE = 0.6745 * np.sqrt(70)


def rest_samples(fs: float) -> int:
    """Samples of the rest window :func:`rest_noise` reads: :data:`REST_S` s, at least :data:`REST_MIN_SAMPLES`.

    Parameters
    ----------
    fs : float
        The sampling rate (Hz).

    Returns
    -------
    int
        The window's length (samples).
    """
    return max(REST_MIN_SAMPLES, int(round(REST_S * fs)))


def _line_speed(windows: np.ndarray, fs: float) -> np.ndarray:
    """(W,): the 3-D speed (m/s) of the straight line fitted to each window of ``windows`` (W, n, 3)."""
    k = np.arange(windows.shape[1], dtype=float)
    k -= k.mean()
    return np.linalg.norm(np.einsum("wnd,n->wd", windows, k) / np.sum(k**2) * fs, axis=1)


def rest_window(approach: np.ndarray, fs: float) -> int:
    """The first sample of the approach's rest window, where its noise is measured (module docstring).

    The window has :func:`rest_samples` samples: the earliest in which the hand is still (the straight
    line fitted to it slower than :data:`REST_SPEED`), else the one whose fitted line is slowest.

    Parameters
    ----------
    approach : numpy.ndarray, shape (N, 3)
        The positions before contact (m), N >= :func:`rest_samples`.
    fs : float
        The sampling rate (Hz).

    Returns
    -------
    int
        The window's first sample (index in the approach, samples).
    """
    a = np.asarray(approach, dtype=float)
    n = rest_samples(fs)
    speed = _line_speed(np.lib.stride_tricks.sliding_window_view(a, n, axis=0).transpose(0, 2, 1), fs)
    still = np.flatnonzero(speed < REST_SPEED)
    return int(still[0]) if still.size else int(np.argmin(speed))


@dataclass(frozen=True)
class RestNoise:
    """White position noise at rest, per axis, and the 3-D speed noise it gives (:func:`measure_rest_noise`).

    Attributes
    ----------
    per_axis : numpy.ndarray
        (3,) the noise's SD on each axis x, y, z (m): the median over trials of each trial's estimate.
    position : float
        The noise as one SD per axis (m): the RMS over the axes, or, when they agree within
        :data:`ISOTROPY_RATIO` (isotropic), the common SD estimated from the three axes pooled.
    speed : float
        The 3-D speed noise (RMS, m/s) without a filter, over the derivative's window: the three axes'
        variances added (:func:`speed_noise`); NaN when no window was given.
    isotropic : bool
        Whether the axes agree within :data:`ISOTROPY_RATIO`.
    n_trials : int
        The trials measured (dimensionless).
    """

    per_axis: np.ndarray
    position: float
    speed: float
    isotropic: bool
    n_trials: int


def measure_rest_noise(approaches: Sequence[np.ndarray], fs: float, window: int | None = None) -> RestNoise:
    """White position noise per axis in the trials' rest windows, and the speed noise it gives.

    In each trial's :func:`rest_window`, the median absolute fourth difference of each axis divided by
    0.6745 sqrt(70) (white Gaussian noise of SD s has fourth differences, coefficients 1, -4, 6, -4, 1, of SD
    s sqrt(70), whose median absolute value is 0.6745 times that); per axis the median over trials. Fourth
    differences of a smooth movement are tiny (its fourth derivative times dt**4), so a recording that
    starts in motion does not read as noisy; the median ignores the few differences an abrupt start
    changes. When the axes agree within :data:`ISOTROPY_RATIO`, the common SD is estimated with the three
    axes' differences pooled in each trial's median (module docstring). Trials shorter than the window are
    left out; none left: zero noise.

    Parameters
    ----------
    approaches : sequence of numpy.ndarray
        The trials' approach positions, each (N, 3) (m).
    fs : float
        The sampling rate (Hz).
    window : int or None
        The differentiating window (samples) for the speed noise; None: speed NaN.

    Returns
    -------
    RestNoise
        The noise per axis and as one SD (m), the speed noise (m/s).
    """
    return combine_rest_noise(rest_noise_rows(approaches, fs), fs, window)


def rest_noise_rows(approaches: Sequence[np.ndarray], fs: float) -> np.ndarray:
    """Each trial's rest-noise estimates, the part of :func:`measure_rest_noise` done trial by trial.

    Row i: the median absolute fourth difference of x, y and z, and of the three pooled, in trial i's
    rest window (:func:`rest_window`; the first :func:`rest_samples` samples when the hand rests there),
    divided by 0.6745 sqrt(70). Trials shorter than the window have no row. A corpus split into parts
    (a Dask cluster) gives the same result from its parts' rows stacked (:func:`combine_rest_noise`).

    Parameters
    ----------
    approaches : sequence of numpy.ndarray
        The trials' approach positions, each (N, 3) (m).
    fs : float
        The sampling rate (Hz).

    Returns
    -------
    numpy.ndarray
        (T, 4) the estimates of the noise's SD on x, y, z and pooled (m), one row per trial long enough.
    """
    n = rest_samples(fs)
    use = [np.asarray(a, dtype=float) for a in approaches if len(a) >= n]
    if not use:
        return np.empty((0, 4))
    windows = np.stack([a[:n] for a in use])  # (T, n, 3): most trials rest at their start
    moving = np.flatnonzero(_line_speed(windows, fs) >= REST_SPEED)
    for i in moving:
        s = rest_window(use[i], fs)
        windows[i] = use[i][s : s + n]
    d = np.abs(np.diff(windows, 4, axis=1))  # (T, n - 4, 3)
    return np.column_stack([np.median(d, axis=1), np.median(d.reshape(len(d), -1), axis=1)]) / REST_NOISE_SCALE


def combine_rest_noise(rows: np.ndarray, fs: float, window: int | None = None) -> RestNoise:
    """The :class:`RestNoise` of trials from their :func:`rest_noise_rows` (stacked over a corpus's parts).

    Per axis the median over trials; when the axes agree within :data:`ISOTROPY_RATIO`, the common SD is
    the median of the pooled estimates, else the RMS over the axes.

    Parameters
    ----------
    rows : numpy.ndarray
        (T, 4) the trials' estimates on x, y, z and pooled (m).
    fs : float
        The sampling rate (Hz).
    window : int or None
        The differentiating window (samples) for the speed noise; None: speed NaN.

    Returns
    -------
    RestNoise
        The noise per axis and as one SD (m), the speed noise (m/s).
    """
    rows = np.asarray(rows, dtype=float).reshape(-1, 4)
    if not len(rows):
        zero = np.zeros(3)
        return RestNoise(zero, 0.0, 0.0 if window is None else speed_noise(0.0, fs, window), True, 0)
    per_axis = np.median(rows[:, :3], axis=0)
    isotropic = bool(per_axis.max() <= ISOTROPY_RATIO * per_axis.min() or per_axis.max() < EDGE_NOISE_FLOOR_M**2)
    position = float(np.median(rows[:, 3])) if isotropic else float(np.sqrt(np.mean(per_axis**2)))
    sn = np.nan if window is None else speed_noise(position, fs, window)
    return RestNoise(per_axis, position, sn, isotropic, len(rows))


def rest_noise(approaches: Sequence[np.ndarray], fs: float) -> float:
    """White position noise at rest as one SD per axis (m): :attr:`RestNoise.position` of
    :func:`measure_rest_noise` (the RMS over the axes of their noise, or the pooled SD when isotropic).

    Parameters
    ----------
    approaches : sequence of numpy.ndarray
        The trials' approach positions, each (N, 3) (m).
    fs : float
        The sampling rate (Hz).

    Returns
    -------
    float
        The noise's SD per axis (m); 0 when no trial is long enough.
    """
    return measure_rest_noise(approaches, fs).position


@dataclass(frozen=True)
class ResidualAnalysis:
    """Winter's residual analysis: the residual of every cut-off scanned, the noise line and the cut-off.

    Attributes
    ----------
    cutoffs : numpy.ndarray
        The cut-offs scanned (Hz).
    residual : numpy.ndarray
        The RMS residual between raw and filtered positions at each cut-off (m).
    noise_m : float
        The fitted noise line's value at 0 Hz: the noise's RMS amplitude (m).
    slope : float
        The fitted noise line's slope (m per Hz).
    cutoff_hz : float or None
        The lowest cut-off with residual <= noise (Hz); None when the residual never falls that low.
    """

    cutoffs: np.ndarray
    residual: np.ndarray
    noise_m: float
    slope: float
    cutoff_hz: float | None


def residual_analysis(approaches: Sequence[np.ndarray], fs: float) -> ResidualAnalysis:
    """Winter's residual analysis over some trials' positions (each (N, 3), m) sampled at ``fs`` Hz.

    Scans :data:`N_CUTOFFS` cut-offs evenly from :data:`MIN_CUTOFF_HZ` to just below the highest the
    zero-lag filter allows at ``fs``; the residual at each is the RMS over samples, axes and trials of raw
    minus filtered positions. The trials are filtered together: each is cut to the same length (the
    median length of those given, its last samples, the movement's end; shorter trials are left out).
    The noise line is fitted by least squares over :data:`NOISE_FIT_RANGE` of the Nyquist frequency.

    Parameters
    ----------
    approaches : sequence of numpy.ndarray
        The trials' approach positions, each (N, 3) (m), as :func:`skilllib.features.approaches` gives them.
    fs : float
        The sampling rate (Hz).

    Returns
    -------
    ResidualAnalysis
        The residual of every cut-off (Hz, m), the noise line (m, m/Hz) and the cut-off chosen (Hz).

    Raises
    ------
    ValueError
        When no trial has 4 samples or the rate is too low for the scan.
    """
    usable = [np.asarray(a, dtype=float) for a in approaches if len(a) >= 4]
    if not usable:
        raise ValueError("residual analysis needs at least one trial with 4 or more samples")
    length = int(np.median([len(a) for a in usable]))
    x = np.column_stack([a[len(a) - length :] for a in usable if len(a) >= length])
    top = max_cutoff(fs)
    if top <= 2 * MIN_CUTOFF_HZ:
        raise ValueError(f"a sampling rate of {fs:g} Hz is too low for a residual analysis")
    cutoffs = np.linspace(MIN_CUTOFF_HZ, top, N_CUTOFFS)
    residual = np.array([np.sqrt(np.mean((x - butterworth_lowpass(x, fs, f)) ** 2)) for f in cutoffs])
    lo, hi = (r * fs / 2 for r in NOISE_FIT_RANGE)
    tail = (cutoffs >= lo) & (cutoffs <= hi)
    slope, noise = np.polyfit(cutoffs[tail], residual[tail], 1)
    noise = float(max(noise, 0.0))
    below = np.flatnonzero(residual <= noise)
    return ResidualAnalysis(cutoffs, residual, noise, float(slope), float(cutoffs[below[0]]) if below.size else None)


@dataclass(frozen=True)
class Lowpass:
    """The low-pass filter a run applies to the positions before differentiating them.

    ``cutoff_hz``: the -3 dB frequency of the forward-backward filter (Hz), None when no filter is applied;
    ``chosen_by``: ``"given"`` (a number), ``"winter residual analysis"`` (``auto``, noise above the
    limit), ``"auto: not needed"`` (``auto``, noise below it) or ``"none"``; ``noise_m``: the position
    noise at rest (m, :func:`rest_noise`) and ``speed_noise``: the 3-D speed noise it gives without a filter
    (m/s), when estimated; ``noise_axes``: that noise per axis (m); ``borderline``: the ``auto`` decision
    lay within :data:`BORDERLINE_FRACTION` of :data:`SPEED_NOISE_LIMIT`; ``alternative_hz``: then the
    cut-off the other choice would filter at (Hz; None: not filtering); ``note``: what the other choice
    would change (text, written by :func:`skilllib.features.trial_features`). ``noise_axes`` and ``note``
    are not compared (two runs that choose the same filter are equal).

    Attributes
    ----------
    cutoff_hz : float or None
        The -3 dB frequency of the forward-backward filter (Hz); None: no filter.
    chosen_by : str
        How the cut-off was chosen (text).
    order : int
        The Butterworth filter's order (dimensionless).
    noise_m : float or None
        The position noise at rest (m), when estimated.
    speed_noise : float or None
        The 3-D speed noise that position noise gives without a filter (m/s), when estimated.
    fs : float or None
        The recordings' sampling rate (Hz), for the exact design frequency.
    noise_axes : tuple of float or None
        The position noise at rest on each axis x, y, z (m), when estimated per axis.
    borderline : bool
        Whether the ``auto`` decision's speed noise lay within :data:`BORDERLINE_FRACTION` of the limit.
    alternative_hz : float or None
        For a borderline decision, the cut-off of the other choice (Hz); None: the other choice is no filter.
    note : str
        For a borderline decision, what the other choice would change (text; empty until measured).
    """

    cutoff_hz: float | None
    chosen_by: str
    order: int = ORDER
    noise_m: float | None = None
    speed_noise: float | None = None
    fs: float | None = None  #: Hz, the recordings' sampling rate (for the exact design frequency)
    noise_axes: tuple[float, ...] | None = field(default=None, compare=False)
    borderline: bool = False
    alternative_hz: float | None = None
    note: str = field(default="", compare=False)

    def apply(self, pos: np.ndarray, fs: float) -> np.ndarray:
        """``pos`` filtered (or as it is, when no filter applies)."""
        if self.cutoff_hz is None or len(pos) < 4:
            return np.asarray(pos, dtype=float)
        return butterworth_lowpass(pos, fs, self.cutoff_hz, self.order)

    def to_dict(self) -> dict[str, Any]:
        """results.json ``filter``: kind, order, passes, cutoff_hz, design_hz, chosen_by, noise estimates (one
        SD and per axis), whether the decision was borderline and the cut-off the other choice would use."""
        on = self.cutoff_hz is not None
        return {
            "kind": "butterworth low-pass, forward-backward (zero lag)" if on else None,
            "order": self.order if on else None,
            "passes": PASSES if on else None,
            "cutoff_hz": self.cutoff_hz,
            "design_hz": design_frequency(self.cutoff_hz, self.order, fs=self.fs) if on else None,
            "chosen_by": self.chosen_by,
            "position_noise_m": self.noise_m,
            "speed_noise_m_s": self.speed_noise,
            "speed_noise_limit_m_s": SPEED_NOISE_LIMIT if self.chosen_by.startswith(("auto", "winter")) else None,
            "position_noise_axes_m": list(self.noise_axes) if self.noise_axes is not None else None,
            "borderline": bool(self.borderline),
            "alternative_cutoff_hz": self.alternative_hz,
        }


NO_FILTER = Lowpass(None, "none")


def parse_lowpass(value: str | float | None) -> str | float:
    """``"auto"``, ``"none"`` or a cut-off in Hz (> 0) from an option value.

    Parameters
    ----------
    value : str, float or None
        The option's value: ``"auto"``, ``"none"`` (text) or a cut-off frequency (Hz); None is ``"none"``.

    Returns
    -------
    str or float
        ``"auto"``, ``"none"`` (text) or the cut-off frequency (Hz).

    Raises
    ------
    ValueError
        For any other value.
    """
    if value is None:
        return "none"
    if isinstance(value, str):
        v = value.strip().lower()
        if v in LOWPASS_CHOICES:
            return v
        try:
            value = float(v)
        except ValueError:
            raise ValueError(f"lowpass must be 'auto', 'none' or a cut-off in Hz, got {value!r}") from None
    value = float(value)
    if not (np.isfinite(value) and value > 0):
        raise ValueError(f"a low-pass cut-off must be a frequency > 0 Hz, got {value:g}")
    return value


def residual_trials(n: int) -> range:
    """Which of ``n`` approaches the residual analysis of ``"auto"`` reads: at most :data:`RESIDUAL_TRIALS`,
    evenly spaced from the first (deterministic).

    Parameters
    ----------
    n : int
        The number of approaches (dimensionless).

    Returns
    -------
    range
        The indices (dimensionless) of the approaches read.
    """
    return range(0, n, max(1, n // RESIDUAL_TRIALS))[:RESIDUAL_TRIALS]


def choose_lowpass(
    spec: str | float | Lowpass | None,
    approaches: Sequence[np.ndarray],
    fs: float,
    window: int,
    *,
    noise: RestNoise | float | None = None,
) -> Lowpass:
    """The :class:`Lowpass` for a run.

    ``spec`` is ``"none"``, a cut-off in Hz, a :class:`Lowpass` (used as it is), or ``"auto"``: Winter's
    residual analysis over (at most :data:`RESIDUAL_TRIALS` of) the trials' approach positions, filtering
    at its cut-off only when the noise it finds, differentiated over ``window`` samples, exceeds
    :data:`SPEED_NOISE_LIMIT` (module docstring).

    Parameters
    ----------
    spec : str, float, Lowpass or None
        ``"auto"``, ``"none"`` (text), a cut-off frequency (Hz) or a :class:`Lowpass`.
    approaches : sequence of numpy.ndarray
        The trials' approach positions, each (N, 3) (m).
    fs : float
        The sampling rate (Hz).
    window : int
        The differentiating window (samples), as :func:`diff_window`.
    noise : RestNoise, float or None
        The noise at rest of ``approaches`` when the caller measured it: a :class:`RestNoise` (per axis, m)
        or one SD for every axis (m, :func:`rest_noise`); then ``approaches`` must hold only approaches of at
        least 4 samples and may be a lazy sequence: only the residual analysis reads it. None: measured
        here (:func:`measure_rest_noise`).

    Returns
    -------
    Lowpass
        The filter (cut-off in Hz, noise in m and m/s).

    Raises
    ------
    ValueError
        For a ``spec`` that is none of these.
    """
    if isinstance(spec, Lowpass):
        return spec
    spec = parse_lowpass(spec)
    if spec == "none":
        return NO_FILTER
    if spec != "auto":
        if np.isfinite(fs) and float(spec) > max_cutoff(fs):
            raise ValueError(
                f"a low-pass cut-off of {spec:g} Hz is too high for recordings sampled at {fs:g} Hz "
                f"(at most {max_cutoff(fs):.3g} Hz for the zero-lag filter)"
            )
        return Lowpass(float(spec), "given", fs=fs if np.isfinite(fs) else None)
    pick = [a for a in approaches if len(a) >= 4] if noise is None else approaches
    if not len(pick) or not np.isfinite(fs):
        return Lowpass(None, "auto: not needed (no trial to estimate the noise from)")
    noise = measure_rest_noise(pick, fs) if noise is None else noise
    if isinstance(noise, RestNoise):
        axes: tuple[float, ...] | None = tuple(float(v) for v in noise.per_axis)
        noise = noise.position
    else:  # one SD for every axis (a caller that measured the noise pooled)
        axes = None
    sn = speed_noise(noise, fs, window)
    borderline = abs(sn - SPEED_NOISE_LIMIT) <= BORDERLINE_FRACTION * SPEED_NOISE_LIMIT
    common = dict(noise_m=noise, speed_noise=sn, noise_axes=axes, borderline=borderline)

    def winter() -> Lowpass:
        ra = residual_analysis([pick[i] for i in residual_trials(len(pick))], fs)
        if ra.cutoff_hz is None:  # the residual never falls to the noise line: filter at the highest cut-off
            return Lowpass(float(ra.cutoffs[-1]), "winter residual analysis (no crossing: highest cut-off)", fs=fs)
        return Lowpass(ra.cutoff_hz, "winter residual analysis", fs=fs)

    if sn <= SPEED_NOISE_LIMIT:
        alternative = None
        if borderline:  # the cut-off filtering would have used (the approaches may be only partly at hand)
            try:
                alternative = winter().cutoff_hz
            except (KeyError, IndexError, ValueError):
                alternative = None
        return Lowpass(None, "auto: not needed", alternative_hz=alternative, **common)
    w = winter()
    return Lowpass(w.cutoff_hz, w.chosen_by, fs=fs, alternative_hz=None, **common)
