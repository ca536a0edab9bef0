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
  noise of 1-3 % of the peak speed leaves SPARC unchanged). The noise is measured where the protocol
  has the hand at rest, the first :data:`REST_S` of every trial (:func:`rest_noise`: from the median
  absolute fourth difference, which white noise has and a still, swaying or even smoothly moving hand
  has not; the median over trials). Winter's intercept is not used for this decision: a recording without
  noise but with an
  abrupt start (a kink) has broadband content that his line reads as noise. The book's 60 Hz cohort (0.03 mm, about
  2 mm/s) is therefore not filtered, and its results are those of the paper's procedure. A number
  filters at that cut-off; ``"none"`` never filters.

Only the samples before contact are filtered (the approach; the impact is a velocity step that a filter
would smear into it), each end extended by odd reflection about a straight line fitted to the samples
there (:func:`_extend`), not about the raw end sample as scipy's default does, whose noise the filter
would otherwise keep as a step at the first sample.
What filtering does to SPARC is shown in chapter 13: it removes spectrum above the cut-off, and a band
that SPARC reads beyond the cut-off is partly the filter's (the pipeline counts those trials).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.signal import butter, freqz, savgol_coeffs, sosfiltfilt, sosfreqz

ORDER = 2  #: Butterworth order of one pass (two passes: order 4, zero lag)
PASSES = 2  #: forwards and backwards
SPEED_NOISE_LIMIT = 0.005  #: m/s, 3-D speed noise (RMS) above which "auto" filters
NOISE_FIT_RANGE = (0.5, 0.9)  #: fractions of the Nyquist frequency where the residual is fitted as noise
MIN_CUTOFF_HZ = 2.0  #: the lowest cut-off the residual analysis proposes (Hz)
RESIDUAL_TRIALS = 100  #: trials the residual analysis looks at (evenly spaced over the file, deterministic)
START_FIT_S = 0.2  #: s, samples at the start a straight line is fitted to, to extend the signal (:func:`_extend`)
END_FIT_S = 0.05  #: s, samples at the end a straight line is fitted to
N_CUTOFFS = 60  #: cut-offs the residual analysis scans
REST_S = 0.1  #: s, the start of each trial where the hand rests and the noise is measured
REST_MIN_SAMPLES = 16  #: samples of that start at least (at low rates; 0.27 s at 60 Hz)
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


def _extend(x: np.ndarray, n_pad: int, n_fit_start: int, n_fit_end: int) -> np.ndarray:
    """``x`` (N, m) with ``n_pad`` samples added at each end by odd reflection about the value, at that end,
    of a straight line fitted to the samples there (``n_fit_start`` at the start, ``n_fit_end`` at the
    end). Reflecting about the raw end sample (scipy's ``padtype="odd"``) would pin the filtered signal to
    that sample's noise: a step at the first sample of a noisy recording that the derivative turns into a
    false movement onset. The fitted line keeps the end's slope (the approach still moves at contact, and a
    recording that starts in motion still does) with much less of its noise."""
    n = len(x)
    k0, k1 = max(2, min(n_fit_start, n)), max(2, min(n_fit_end, n))
    a0 = np.polyfit(np.arange(k0, dtype=float), x[:k0], 1)  # (2, m): slope, intercept
    a1 = np.polyfit(np.arange(k1, dtype=float), x[n - k1 :], 1)
    first = a0[1]
    last = a1[0] * (k1 - 1) + a1[1]
    head = 2 * first - x[n_pad:0:-1]
    tail = 2 * last - x[n - 2 : n - 2 - n_pad : -1]
    return np.concatenate([head, x, tail])


def butterworth_lowpass(pos: np.ndarray, fs: float, cutoff_hz: float, order: int = ORDER) -> np.ndarray:
    """Positions (N, ...) low-pass filtered along axis 0 with a zero-lag Butterworth filter whose
    forward-backward -3 dB frequency is ``cutoff_hz`` (Hz; the design frequency below ``fs / 2``).

    The ends are extended by :func:`_extend` over about two periods of the design frequency (at most
    N - 1 samples), with lines fitted to :data:`START_FIT_S` of samples at the start (where a trial's hand
    rests: a long line, little noise) and :data:`END_FIT_S` at the end (where the approach still moves and
    decelerates: a short one), so that the filter's start-up transient falls outside the recording."""
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
        _extend(x, n_pad, max(3, int(round(START_FIT_S * fs))), max(3, int(round(END_FIT_S * fs)))),
        axis=0,
        padtype=None,
    )
    return y[n_pad : n_pad + len(x)].reshape(shape)


def speed_noise(
    position_noise_m: float, fs: float, window: int, cutoff_hz: float | None = None, order: int = ORDER
) -> float:
    """3-D speed noise (RMS, m/s) that white position noise (RMS ``position_noise_m`` m per axis) has after
    the zero-lag low-pass at ``cutoff_hz`` (None: no filter) and the Savitzky-Golay derivative (quadratic,
    ``window`` samples) at ``fs`` Hz: sqrt(3) x the per-axis SD, from the combined gain by Parseval's
    theorem, ``var = noise**2 x mean over 0..fs/2 of |D(f)|**2 |H(f)|**(2 passes)``."""
    f = np.linspace(0, fs / 2, 4097)
    _, d = freqz(savgol_coeffs(window, 2, deriv=1, delta=1.0 / fs, use="dot"), worN=f, fs=fs)
    gain = np.abs(d) ** 2
    if cutoff_hz is not None:
        _, h = sosfreqz(butter(order, design_frequency(cutoff_hz, order, fs=fs), fs=fs, output="sos"), worN=f, fs=fs)
        gain = gain * np.abs(h) ** (2 * PASSES)
    return float(np.sqrt(3) * position_noise_m * np.sqrt(np.trapezoid(gain, f) / (fs / 2)))


def max_cutoff(fs: float, order: int = ORDER) -> float:
    """The highest cut-off (Hz) the zero-lag filter can have at ``fs`` (design frequency just below Nyquist)."""
    return fs / 2 * (2 ** (1 / PASSES) - 1) ** (1 / (2 * order)) * 0.99


#: Median absolute fourth difference of white Gaussian noise of SD 1 (see :func:`rest_noise`).
REST_NOISE_SCALE = 0.6745 * np.sqrt(70)


def rest_samples(fs: float) -> int:
    """Samples at the start of a trial that :func:`rest_noise` reads: :data:`REST_S` s, at least
    :data:`REST_MIN_SAMPLES`."""
    return max(REST_MIN_SAMPLES, int(round(REST_S * fs)))


def rest_noise(approaches: Sequence[np.ndarray], fs: float) -> float:
    """White position noise (m, SD per axis) at the start of the trials: over the first :data:`REST_S` s of
    every trial (at least :data:`REST_MIN_SAMPLES`), the median absolute fourth difference over samples and
    axes, divided by 0.6745 sqrt(70) (white Gaussian noise of SD s has fourth differences, coefficients
    1, -4, 6, -4, 1, of SD s sqrt(70), whose median absolute value is 0.6745 times that); the median over
    trials. Fourth differences of a smooth movement are tiny (its fourth derivative times dt**4), so a
    recording that starts in motion does not read as noisy, as it would with second differences (its
    acceleration times dt**2); the median ignores the few differences an abrupt start changes. 0 when no
    trial is long enough."""
    n = max(REST_MIN_SAMPLES, int(round(REST_S * fs)))
    scale = 0.6745 * np.sqrt(70)
    est = [
        float(np.median(np.abs(np.diff(np.asarray(a[:n], dtype=float), 4, axis=0))) / scale)
        for a in approaches
        if len(a) >= n
    ]
    return float(np.median(est)) if est else 0.0


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
    (m/s), when estimated.

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
    """

    cutoff_hz: float | None
    chosen_by: str
    order: int = ORDER
    noise_m: float | None = None
    speed_noise: float | None = None
    fs: float | None = None  #: Hz, the recordings' sampling rate (for the exact design frequency)

    def apply(self, pos: np.ndarray, fs: float) -> np.ndarray:
        """``pos`` filtered (or as it is, when no filter applies)."""
        if self.cutoff_hz is None or len(pos) < 4:
            return np.asarray(pos, dtype=float)
        return butterworth_lowpass(pos, fs, self.cutoff_hz, self.order)

    def to_dict(self) -> dict[str, Any]:
        """results.json ``filter``: kind, order, passes, cutoff_hz, design_hz, chosen_by, noise estimates."""
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
    noise: float | None = None,
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
    noise : float or None
        The :func:`rest_noise` of ``approaches`` (m) when the caller computed it (then ``approaches`` must
        hold only approaches of at least 4 samples and may be a lazy sequence: only the residual analysis
        reads it); None: estimated here.

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
    noise = rest_noise(pick, fs) if noise is None else noise
    sn = speed_noise(noise, fs, window)
    if sn <= SPEED_NOISE_LIMIT:
        return Lowpass(None, "auto: not needed", noise_m=noise, speed_noise=sn)
    ra = residual_analysis([pick[i] for i in residual_trials(len(pick))], fs)
    if ra.cutoff_hz is None:  # the residual never falls to the noise line: filter at the highest cut-off scanned
        return Lowpass(
            float(ra.cutoffs[-1]),
            "winter residual analysis (no crossing: highest cut-off)",
            noise_m=noise,
            speed_noise=sn,
            fs=fs,
        )
    return Lowpass(ra.cutoff_hz, "winter residual analysis", noise_m=noise, speed_noise=sn, fs=fs)
