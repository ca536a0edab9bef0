"""skilllib.smoothness: published values, the SPARC authors' own code as oracle, invariances, errors.

The oracle is monalysa 0.2.1 (Balasubramanian's package): ``sparc`` must agree with it to 1e-9 on every
input it accepts and raise ValueError where it fails; ``sparc_many`` must give ``sparc``'s values.
"""

from __future__ import annotations

import inspect
import warnings
import zlib

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from monalysa.quality.smoothness import log_dimensionless_jerk as ldlj_authors
from monalysa.quality.smoothness import sparc as sparc_authors

import skilllib
from skilllib.smoothness import (
    SPARC_PARAMS,
    _spectral,
    ldlj,
    ldlj_many,
    minimum_jerk_speed,
    nfft,
    sparc,
    sparc_bands,
    sparc_many,
    sparc_spectrum,
)
from skilllib.smoothness import _measures as smoothness

TOL = 1e-9
FAST = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def authors(v, fs, **kw) -> float:
    """The authors' SPARC with the book's parameters where ``kw`` gives none (their Python default fc
    is 10 Hz, the book's 20 Hz: the comparison is of the computation, at equal parameters)."""
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        return float(sparc_authors(np.asarray(v, dtype=float), fs, **{**SPARC_PARAMS, **kw})[0])


def well_conditioned(v, fs, fc=smoothness.DEFAULT_FC, amp_th=0.05, padlevel=4) -> bool:
    """No bin <= fc lies within 1e-9 of the threshold: the band does not hinge on rounding, so two
    different (correct) ways of computing the spectrum must select the same band."""
    s = sparc_spectrum(v, fs, fc, amp_th, padlevel)
    return bool(np.all(np.abs(s.Mf[: np.searchsorted(s.f, fc, "right")] - amp_th) > 1e-9))


# --- profiles of every kind the oracle must agree on ---------------------------------------------


def profile(kind: str, rng: np.random.Generator, fs: float) -> np.ndarray:
    """A speed profile (m/s) at ``fs`` Hz: bell, overlapping submovements, noisy, cut at contact,
    single sample."""
    T = rng.uniform(0.3, 1.5)
    t = np.arange(0, T, 1 / fs)
    if kind == "single":
        return np.array([rng.uniform(0.01, 2)])
    if kind == "bell":
        return minimum_jerk_speed(t, 0, T, rng.uniform(0.05, 0.5))
    if kind == "submovements":  # two or three, overlapping
        n = rng.integers(2, 4)
        t0 = np.sort(rng.uniform(0, T / 2, n))
        return minimum_jerk_speed(t[:, None], t0, T / 2, rng.uniform(0.05, 0.3, n)).sum(axis=1)
    v = minimum_jerk_speed(t, 0, T, 0.3)
    if kind == "noisy":
        return np.abs(v + rng.normal(0, rng.uniform(0.001, 0.1), v.size))
    if kind == "truncated":  # contact during the deceleration, speed still 25-90 % of its peak
        cut = np.flatnonzero((t > T / 2) & (v < rng.uniform(0.25, 0.9) * v.max()))
        return v[: max(cut[0], 1)] if cut.size else v
    raise ValueError(kind)


KINDS = ["bell", "submovements", "noisy", "truncated", "single"]
PARAMS = [
    {},
    {"fc": 20.0},
    {"fc": 5.0, "amp_th": 0.1},
    {"amp_th": 0.01},
    {"padlevel": 2},
    {"padlevel": 6, "fc": 3.0},
    {"padlevel": 0},
]


@pytest.mark.parametrize("fs", [60.0, 100.0, 250.0, 13.7])
@pytest.mark.parametrize("kw", PARAMS, ids=str)
@pytest.mark.parametrize("kind", KINDS)
def test_agrees_with_the_authors_code(kind, kw, fs):
    rng = np.random.default_rng(zlib.crc32(f"{kind} {kw} {fs}".encode()))  # hash() varies per process
    vs = [profile(kind, rng, fs) for _ in range(8)]
    if {**SPARC_PARAMS, **kw}["fc"] > fs / 2:  # the authors' code would read the mirror image
        for fn in (lambda: sparc(vs[0], fs, **kw), lambda: sparc_many(vs, fs, **kw)):
            with pytest.raises(ValueError, match="Nyquist"):
                fn()
        return
    ref = np.array([authors(v, fs, **kw) for v in vs])
    assert np.max(np.abs([sparc(v, fs, **kw) for v in vs] - ref)) < TOL
    assert np.max(np.abs(sparc_many(vs, fs, **kw) - ref)) < TOL


speeds = hnp.arrays(np.float64, st.integers(1, 300), elements=st.floats(0, 100, allow_subnormal=False))
signed = hnp.arrays(np.float64, st.integers(1, 300), elements=st.floats(-100, 100, allow_subnormal=False))
any_fs = st.floats(1.0, 2000.0)
nonneg = hnp.arrays(np.float64, st.integers(2, 200), elements=st.floats(0, 10, allow_subnormal=False))


@FAST
@given(
    v=st.one_of(speeds, signed),
    fs=any_fs,
    fc=st.floats(0.0, 100.0),
    amp_th=st.floats(-0.1, 1.2),
    padlevel=st.integers(-2, 7),
)
def test_agrees_with_the_authors_code_or_raises_valueerror(v, fs, fc, amp_th, padlevel):
    kw = {"fc": fc, "amp_th": amp_th, "padlevel": padlevel}
    if fc > fs / 2:  # refused (as is a bad profile): the authors' code would read the mirror image
        with pytest.raises(ValueError):
            sparc(v, fs, **kw)
        return
    try:
        ref = authors(v, fs, **kw)
    except (IndexError, ValueError, ZeroDivisionError):
        with pytest.raises(ValueError):
            sparc(v, fs, **kw)
        return
    assume(np.isfinite(ref))  # the authors' code returns NaN for an all-zero cropped profile
    assert abs(sparc(v, fs, **kw) - ref) < TOL


@FAST
@given(
    vs=st.lists(st.one_of(speeds, signed), min_size=1, max_size=12),
    fs=any_fs,
    fc=st.floats(0.5, 60.0),
    amp_th=st.floats(0.005, 0.6),
    padlevel=st.integers(0, 6),
)
def test_sparc_many_equals_sparc(vs, fs, fc, amp_th, padlevel):
    kw = {"fc": fc, "amp_th": amp_th, "padlevel": padlevel}
    assume(all(np.any(v) for v in vs))
    try:
        one = [sparc(v, fs, **kw) for v in vs]
    except ValueError:
        with pytest.raises(ValueError):
            sparc_many(vs, fs, **kw)
        return
    assume(all(well_conditioned(v, fs, **kw) for v in vs))
    assert np.max(np.abs(sparc_many(vs, fs, **kw) - one)) < TOL


def test_sparc_many_on_long_profiles_and_wide_bands_both_paths():
    """Long profiles take the batched-FFT path, short ones the direct DFT; fc at Nyquist takes the whole
    one-sided spectrum. A 2-D array is a valid sequence of equal-length profiles."""
    rng = np.random.default_rng(3)
    vs = [np.abs(rng.normal(size=n)) + 0.5 for n in (1, 2, 3, 31, 64, 65, 257, 700, 2000, 5000)]
    vs += [rng.normal(size=n) for n in (5, 90, 700)]  # signed
    for fs, fc in [(60.0, 10.0), (60.0, 30.0), (100.0, 50.0)]:
        assert np.max(np.abs(sparc_many(vs, fs, fc=fc) - [sparc(v, fs, fc=fc) for v in vs])) < TOL
    block = np.abs(rng.normal(size=(7, 40)))
    assert np.max(np.abs(sparc_many(block, 60.0) - [sparc(v, 60.0) for v in block])) < TOL
    assert sparc_many([], 60.0).shape == (0,)


def test_direct_dft_and_fft_give_the_same_power(monkeypatch):
    rng = np.random.default_rng(4)
    P = np.abs(rng.normal(size=(9, 75)))
    P[3] -= 1.0  # one signed row: its peak needs the whole spectrum
    signed_rows = (P < 0).any(axis=1)
    monkeypatch.setattr(_spectral, "_DFT_FACTOR", np.inf)
    a2, p2 = _spectral._power(P, 2048, 342, signed_rows)
    monkeypatch.setattr(_spectral, "_DFT_FACTOR", 0.0)
    b2, q2 = _spectral._power(P, 2048, 342, signed_rows)
    assert np.allclose(a2, b2, rtol=1e-12, atol=1e-12 * p2.max())
    assert np.allclose(p2, q2, rtol=1e-12)


# --- how the band ended: sparc_bands and the capped flag -------------------------------------------


def authors_band_end(v, fs, **kw) -> float:
    """Last frequency (Hz) of the band in the authors' code (``sparc(...)[2][0][-1]``)."""
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        return float(sparc_authors(np.asarray(v, dtype=float), fs, **{**SPARC_PARAMS, **kw})[2][0][-1])


@FAST
@given(
    vs=st.lists(speeds, min_size=1, max_size=8),
    fs=st.floats(20.0, 500.0),
    fc_share=st.floats(0.02, 0.98),
    amp_th=st.floats(0.01, 0.5),
    padlevel=st.integers(2, 6),
)
def test_capped_means_a_higher_fc_would_lengthen_the_band(vs, fs, fc_share, amp_th, padlevel):
    """``capped`` is checked against the authors' code run with fc at the Nyquist frequency: their band
    then ends above our fc exactly when ours was capped. ``band_end_hz`` is their band end at our fc."""
    fc = fc_share * fs / 2
    kw = {"fc": fc, "amp_th": amp_th, "padlevel": padlevel}
    assume(all(np.any(v) for v in vs))
    assume(all(well_conditioned(v, fs, fs / 2, amp_th, padlevel) for v in vs))
    b = sparc_bands(vs, fs, **kw)
    assert b.capped.dtype == bool and b.sparc.shape == b.band_end_hz.shape == b.capped.shape == (len(vs),)
    for i, v in enumerate(vs):
        assert b.capped[i] == (authors_band_end(v, fs, fc=fs / 2, amp_th=amp_th, padlevel=padlevel) > fc)
        assert b.band_end_hz[i] == pytest.approx(authors_band_end(v, fs, **kw), abs=1e-9)
        one = sparc_spectrum(v, fs, **kw)
        assert (one.capped, one.cutoff) == (b.capped[i], pytest.approx(b.band_end_hz[i], abs=1e-12))
        assert abs(one.sparc - b.sparc[i]) < TOL
    assert np.max(np.abs(b.sparc - sparc_many(vs, fs, **kw))) < TOL  # more bins may take the FFT path


def test_a_short_truncated_profile_is_capped_at_10_hz_and_a_whole_bell_is_not():
    t = np.arange(0, 1, 1 / 60)
    bell = minimum_jerk_speed(t, 0, 1.0, 0.2)  # its spectrum falls below 5 % near 1.6 Hz
    short = minimum_jerk_speed(np.arange(12) / 60, 0, 12 / 60 / 0.75, 0.2)  # cut at 74 % of its peak
    b10, b20 = (sparc_bands([bell, short], 60.0, fc=fc) for fc in (10.0, 20.0))
    assert b10.capped.tolist() == [False, True] and b20.capped.tolist() == [False, True]
    assert b10.band_end_hz[0] == b20.band_end_hz[0] < 2.0  # the threshold ends the bell's band
    assert 9.5 < b10.band_end_hz[1] <= 10.0 and 19.5 < b20.band_end_hz[1] <= 20.0  # fc ends the other
    assert b10.sparc[1] > b20.sparc[1] + 0.1  # the lower cap cuts a longer arc short: 'smoother'


def test_fc_at_nyquist_never_caps_and_above_it_is_refused():
    v = np.abs(np.random.default_rng(5).normal(size=50)) + 0.1  # noise: the spectrum stays high
    assert sparc_bands([v], 60.0, fc=29.0).capped[0]
    assert not sparc_bands([v], 60.0, fc=30.0).capped[0] and not sparc_spectrum(v, 60.0, fc=30.0).capped
    for fn in (
        sparc,
        sparc_spectrum,
        lambda v, fs, fc: sparc_many([v], fs, fc=fc),
        lambda v, fs, fc: sparc_bands([v], fs, fc=fc),
    ):
        with pytest.raises(ValueError, match=r"fc = 30.5 Hz lies above the Nyquist frequency 30 Hz"):
            fn(v, 60.0, fc=30.5)
    with pytest.raises(ValueError, match="Nyquist frequency 15 Hz"):
        sparc(v, 30.0)  # the book's default fc = 20 Hz needs samples at 40 Hz or more


@FAST
@given(v=nonneg, fs=st.floats(10.0, 500.0), amp_th=st.floats(0.01, 0.5), padlevel=st.integers(0, 6))
def test_sparc_is_at_most_minus_the_straight_line_across_its_band(v, fs, amp_th, padlevel):
    """The polygon is at least as long as the chord from (0, 1) to (1, V^ at the band end): an
    uncapped band ends near amp_th, so SPARC <= about -sqrt(1 + (1 - amp_th)**2); only a cap (or a
    coarse grid) lets the band end higher and the value rise above that."""
    assume(np.any(v))
    s = sparc_spectrum(v, fs, fc=min(smoothness.DEFAULT_FC, fs / 2), amp_th=amp_th, padlevel=padlevel)
    assume(s.f_sel.size > 1)
    assert s.sparc <= -np.hypot(1.0, s.Mf_sel[0] - s.Mf_sel[-1]) + 1e-12
    assert s.Mf_sel[0] == pytest.approx(1.0, abs=1e-12)  # v >= 0: the band starts at DC, the maximum


# --- published values ----------------------------------------------------------------------------


def test_published_values():
    t = np.arange(-1, 1, 0.01)
    gauss = np.exp(-5 * t**2)
    assert round(sparc(gauss, fs=100.0), 5) == -1.41403
    assert round(ldlj(gauss, fs=100.0), 5) == -5.81636
    assert round(np.exp(-ldlj(gauss, fs=100.0)), 5) == 335.74684  # |DLJ|
    mj = minimum_jerk_speed(np.arange(0, 1, 0.01))
    assert abs(sparc(mj, fs=100.0) - (-1.4058293244214655)) < 1e-12


# --- invariances ---------------------------------------------------------------------------------


@FAST
@given(v=nonneg, scale=st.floats(1e-3, 1e3), j=st.integers(-20, 20))
def test_amplitude_invariance(v, scale, j):
    assume(np.any(v))
    s = sparc(v, 60.0)
    assert sparc(v * 2.0**j, 60.0) == s  # exact: scaling by 2**j commutes with rounding
    assume(well_conditioned(v, 60.0))
    assert abs(sparc(v * scale, 60.0) - s) < TOL


@FAST
@given(
    v=st.one_of(speeds, signed),
    fs=any_fs,
    fc=st.floats(0.5, 50),
    amp_th=st.floats(0.001, 0.9),
    padlevel=st.integers(0, 7),
)
def test_sparc_is_at_most_minus_one_or_zero_for_a_one_bin_band(v, fs, fc, amp_th, padlevel):
    """Inputs outside SPARC's domain (fc above Nyquist, a profile at rest: both tested in
    test_bad_*) are assumed away, not silently passed; a signed profile whose spectrum stays below
    amp_th up to fc must raise. The band runs from the first to the last bin up to fc at or above
    amp_th (numpy's FFT here); a band of one bin has SPARC 0, any longer one at most -1."""
    assume(fc <= fs / 2 and np.any(v))
    n_fft = nfft(v.size, padlevel)
    Mf = np.abs(np.fft.fft(v, n_fft))
    Mf = Mf[np.arange(n_fft) * (fs / n_fft) <= fc] / Mf.max()  # the bins up to fc, normalised
    assume(np.all(np.abs(Mf - amp_th) > 1e-9 * amp_th))  # no bin on the threshold: unambiguous
    if not np.any(Mf >= amp_th):
        with pytest.raises(ValueError, match="no spectral magnitude at or above amp_th"):
            sparc_spectrum(v, fs, fc, amp_th, padlevel)
        return
    s = sparc_spectrum(v, fs, fc, amp_th, padlevel)
    above = np.flatnonzero(Mf >= amp_th)
    assert s.f_sel.size == above[-1] - above[0] + 1  # the band: first to last bin at or above amp_th
    if s.f_sel.size == 1:
        assert s.sparc == 0.0  # empty arc, as the authors' code
    else:
        assert s.sparc <= -1 + 1e-12


@FAST
@given(v=nonneg, fs=st.floats(1.0, 500.0), amp_th=st.floats(0.001, 0.7), padlevel=st.integers(3, 7))
def test_speeds_sampled_finely_enough_give_at_most_minus_one(v, fs, amp_th, padlevel):
    """For v >= 0 with padlevel >= 3 the band holds at least two bins once fs / nfft <= fc."""
    fc = min(smoothness.DEFAULT_FC, fs / 2)
    assume(np.any(v) and fs / nfft(v.size, padlevel) <= fc)
    assert sparc(v, fs, fc=fc, amp_th=amp_th, padlevel=padlevel) <= -1 + 1e-12


def test_extreme_amplitudes_neither_overflow_nor_underflow():
    v = minimum_jerk_speed(np.arange(0, 1, 1 / 60))
    for scale in (1e305, 1e-310):  # the FFT of v * 1e305 overflows in the authors' code (NaN)
        assert abs(sparc(v * scale, 60.0) - sparc(v, 60.0)) < TOL
        assert abs(sparc_many([v * scale], 60.0)[0] - sparc(v, 60.0)) < TOL


def test_single_sample_gives_minus_one_and_a_one_bin_band_gives_zero():
    assert abs(sparc([0.3], 60.0) + 1) < 1e-12
    # grid step fs / nfft = 1000 / 16 Hz > fc: the band is the DC bin alone, as in the authors' code
    assert sparc([0.3], 1000.0) == 0.0 == authors([0.3], 1000.0)


@FAST
@given(v=nonneg, fs=st.floats(10.0, 500.0), j=st.integers(-6, 6))
def test_time_stretching_exact(v, fs, j):
    """Stretching time by 2**j (the same samples at fs / 2**j, cut-off fc / 2**j) changes nothing."""
    assume(np.any(v))
    c = 2.0**j
    fc = fs / 4  # below the Nyquist frequency at both rates
    assert sparc(v, fs / c, fc=fc / c) == sparc(v, fs, fc=fc)


@pytest.mark.parametrize("fs", [60.0, 100.0])
@pytest.mark.parametrize("T", [0.5, 0.8, 1.3])
def test_time_stretching_resampled(T, fs):
    """The same movement 2 or 4 times longer at the same fs (N and nfft scale together): equal up to
    the sampling of the profile (< 1e-4), not exactly: the samples are different."""
    s = [sparc(minimum_jerk_speed(np.arange(0, c * T, 1 / fs), 0, c * T), fs) for c in (1, 2, 4)]
    assert abs(s[1] - s[0]) < 1e-4 and abs(s[2] - s[0]) < 1e-4


@FAST
@given(fs=st.floats(40.0, 500.0), n=st.integers(1, 3), j=st.integers(1, 2), data=st.data())
def test_time_stretching_resampled_property(fs, n, j, data):
    """Any movement of 1-3 minimum-jerk submovements, stretched by c = 2**j and sampled at the same fs:
    N and nfft both scale by c and the grids line up. The samples differ, so SPARC is not equal
    bit for bit (that holds for the same samples, test above) but to the sampling, < 1e-3, unless a
    bin lies within 1e-3 of the threshold (the band may then take in one more bin)."""
    T = np.array(data.draw(st.lists(st.floats(0.2, 1.0), min_size=n, max_size=n)))
    t0 = np.r_[0.0, data.draw(st.lists(st.floats(0.0, 0.8), min_size=n - 1, max_size=n - 1))]
    D = np.array(data.draw(st.lists(st.floats(0.05, 0.5), min_size=n, max_size=n)))
    c = 2.0**j
    assume(T.min() * fs >= 20)  # each submovement resolved by at least 20 samples

    def sampled(c):
        t = np.arange(0, c * (t0 + T).max(), 1 / fs)
        return minimum_jerk_speed(t[:, None], c * t0, c * T, D).sum(axis=1)

    v, w = sampled(1.0), sampled(c)
    assume(nfft(w.size) == c * nfft(v.size))
    s = sparc_spectrum(v, fs)
    assume(np.all(np.abs(s.Mf[: np.searchsorted(s.f, smoothness.DEFAULT_FC, "right")] - 0.05) > 1e-3))
    assert abs(sparc(w, fs) - s.sparc) < 1e-3


def test_sparc_many_is_batched(monkeypatch):
    """No per-trial work on the hot path: 3,000 trials of 30-90 samples at 60 Hz take about one batched
    spectral evaluation per distinct length (profiles are batched by nfft and length, so that a value
    does not depend on the other profiles of the batch), and never the one-profile functions."""
    rng = np.random.default_rng(7)
    vs = [minimum_jerk_speed(np.arange(n) / 60.0, 0, n / 60.0 / 0.8) for n in rng.integers(30, 91, 3000)]
    expected = np.array([sparc(v, 60.0) for v in vs])
    calls = []
    power = _spectral._power
    monkeypatch.setattr(_spectral, "_power", lambda P, *a: calls.append(len(P)) or power(P, *a))
    for name in ("sparc", "sparc_spectrum"):
        monkeypatch.setattr(smoothness, name, None)
    monkeypatch.setattr(_spectral, "_as_speed", None)
    assert np.max(np.abs(sparc_many(vs, 60.0) - expected)) < TOL
    assert sum(calls) == len(vs) and len(calls) <= 2 * len({len(v) for v in vs}) < len(vs) / 20


def test_submovements_drifting_apart_lower_sparc():
    t = np.arange(0, 3, 1 / 60)
    s = [sparc(minimum_jerk_speed(t[:, None], [0, d], 0.6, 0.2).sum(axis=1), 60.0) for d in (0.0, 0.2, 0.4, 0.6, 0.8)]
    assert np.all(np.diff(s) < 0)


# --- the spectrum companion ----------------------------------------------------------------------


def test_spectrum_companion():
    v = minimum_jerk_speed(np.arange(0, 0.8, 1 / 60), 0, 1.0)  # cut at contact, 80 % of the way
    s = sparc_spectrum(v, 60.0)
    assert abs(s.sparc - authors(v, 60.0)) < TOL and s.sparc == sparc(v, 60.0)
    assert s.nfft == 2 ** (int(np.ceil(np.log2(v.size))) + 4) == s.f.size == s.Mf.size  # padlevel 4
    np.testing.assert_allclose(s.f, np.arange(s.nfft) * 60.0 / s.nfft, rtol=1e-12)
    Mf = np.abs(np.fft.fft(v, s.nfft))
    np.testing.assert_allclose(s.Mf, Mf / Mf.max(), rtol=0, atol=1e-12)
    assert s.f_sel[0] == 0.0 and s.cutoff == pytest.approx(authors_band_end(v, 60.0), abs=1e-12)
    assert s.cutoff <= s.fc and s.Mf_sel[-1] >= s.amp_th
    beyond = (s.f > s.cutoff) & (s.f <= s.fc)
    assert np.all(s.Mf[beyond] < s.amp_th)
    assert np.array_equal(s.Mf_sel, s.Mf[: s.Mf_sel.size])


def test_nfft_is_the_authors_formula():
    for p in (-2, 0, 4, 4.5, 7):
        for n in range(1, 3000):
            theirs = int(pow(2, np.ceil(np.log2(n)) + p))
            if theirs < 1:  # np.fft.fft(v, 0) fails in their code
                with pytest.raises(ValueError, match="nfft"):
                    nfft(n, p)
            else:
                assert nfft(n, p) == theirs


def test_book_parameters_are_the_defaults():
    defaults = {k: p.default for k, p in inspect.signature(sparc).parameters.items() if k in SPARC_PARAMS}
    # fc: the KI 2020 paper's "0 to 20 Hz" (the authors' MATLAB default), chosen in chapters 2 and 4
    assert defaults == dict(SPARC_PARAMS) == {"fc": 20.0, "amp_th": 0.05, "padlevel": 4}
    assert skilllib.sparc is sparc


def test_minimum_jerk_speed():
    t = np.linspace(-0.5, 2.5, 30001)
    v = minimum_jerk_speed(t, t0=0.5, T=1.5, D=0.3)
    assert abs(v.max() - 1.875 * 0.3 / 1.5) < 1e-6
    assert abs(t[v.argmax()] - 1.25) < 1e-3
    assert abs(np.sum(v) * (t[1] - t[0]) - 0.3) < 1e-6  # travels D
    assert np.all(v[(t < 0.5) | (t > 2.0)] == 0)


# --- LDLJ ----------------------------------------------------------------------------------------


@FAST
@given(v=hnp.arrays(np.float64, st.integers(3, 300), elements=st.floats(0, 10, allow_subnormal=False)), fs=any_fs)
def test_ldlj_agrees_with_the_authors_code(v, fs):
    assume(np.any(v) and np.any(np.diff(v, 2)))
    with np.errstate(all="ignore"):
        ref = ldlj_authors(v, fs)
    assume(np.isfinite(ref))  # their code under- or overflows for extreme values (we scale by v_peak)
    assert abs(ldlj(v, fs) - ref) < TOL * max(1, abs(ref))
    assert abs(ldlj_many([v, v[::-1]], fs)[0] - ref) < TOL * max(1, abs(ref))


def test_ldlj_many_equals_ldlj_and_constant_speed_is_infinitely_smooth():
    rng = np.random.default_rng(5)
    vs = [np.abs(rng.normal(size=n)) for n in rng.integers(3, 200, 50)] + [np.ones(7)]
    many = ldlj_many(vs, 60.0)
    assert np.allclose(many, [ldlj(v, 60.0) for v in vs], rtol=1e-12, atol=0)
    assert many[-1] == np.inf == ldlj(np.ones(7), 60.0)


def test_ldlj_collapses_with_noise_sparc_does_not():
    rng = np.random.default_rng(6)
    v = minimum_jerk_speed(np.arange(0, 1, 1 / 60), 0, 1, 0.3)
    noisy = np.abs(v + rng.normal(0, 0.01 * v.max(), v.size))  # 1 % of peak speed
    assert abs(sparc(noisy, 60.0) - sparc(v, 60.0)) < 0.05
    assert ldlj(noisy, 60.0) - ldlj(v, 60.0) < -1.0


# --- bad input -----------------------------------------------------------------------------------

BAD = [
    ([], "empty"),
    ([0.1, np.nan], "NaN"),
    ([0.1, np.inf], "infinite"),
    (np.ones((3, 2)), "1-D"),
    (np.zeros(5), "zero everywhere"),
    (["a", "b"], "numbers"),
]


@pytest.mark.parametrize("v, words", BAD)
@pytest.mark.parametrize("fn", [sparc, sparc_spectrum, ldlj])
def test_bad_speed_is_named(fn, v, words):
    with pytest.raises(ValueError, match=words):
        fn(v, 60.0)


@pytest.mark.parametrize("fs", [0.0, -60.0, np.nan, np.inf])
@pytest.mark.parametrize("fn", [sparc, ldlj, sparc_many, ldlj_many])
def test_bad_fs(fn, fs):
    v = minimum_jerk_speed(np.linspace(0, 1, 40))
    with pytest.raises(ValueError, match="fs must be"):
        fn([v] if fn in (sparc_many, ldlj_many) else v, fs)


def test_bad_parameters_and_no_band():
    v = minimum_jerk_speed(np.linspace(0, 1, 40))
    with pytest.raises(ValueError, match="fc must be"):
        sparc(v, 60.0, fc=-1.0)
    with pytest.raises(ValueError, match="amp_th must be"):
        sparc(v, 60.0, amp_th=np.nan)
    with pytest.raises(ValueError, match="no spectral magnitude at or above amp_th"):
        sparc(v, 60.0, amp_th=1.5)
    with pytest.raises(ValueError, match="at least 3"):
        ldlj([0.1, 0.2], 60.0)


@pytest.mark.parametrize("v, words", BAD[:-1] + [([[0.1], [0.2]], "1-D"), (0.3, "1-D")])
def test_sparc_many_names_the_bad_profile(v, words, monkeypatch):
    monkeypatch.setattr(_spectral, "_CHUNK", 4)  # the index must count across blocks
    good = minimum_jerk_speed(np.linspace(0, 1, 40))
    vs = [good] * 9 + [v] + [good] * 3
    for fn in (sparc_many, ldlj_many):
        with pytest.raises(ValueError, match=rf"speeds\[9\].*{words}"):
            fn(vs, 60.0)
    with pytest.raises(ValueError, match=r"speeds\[2\].*no spectral magnitude"):
        sparc_many([good, good, -np.ones(4) * (np.arange(4) % 2 - 0.5)], 60.0, fc=1.0, amp_th=0.9)
    cropped = [0.0, 0.0, 0.0, 0.0, 1.0]  # padlevel -1: nfft = 4 < N, np.fft.fft keeps the zeros only
    with pytest.raises(ValueError, match="zero"):
        sparc(cropped, 60.0, padlevel=-1)
    with pytest.raises(ValueError, match=r"speeds\[1\] is zero over its first nfft = 4"):
        sparc_many([good[:5], cropped], 60.0, padlevel=-1)


@pytest.mark.parametrize("n, ratio", [(8, 0.3), (20, 0.5), (200, 0.7)])
def test_minimum_jerk_segment_runs_from_onset_to_contact_in_n_samples(n, ratio):
    v = smoothness.minimum_jerk_segment(n, ratio, 60.0)
    assert v.size == n and v[0] == pytest.approx(0.05) and v.max() <= 1.0
    T = n / 60.0 / (((1 + np.sqrt(1 - np.sqrt(ratio))) - (1 - np.sqrt(1 - np.sqrt(0.05)))) / 2)
    full = minimum_jerk_speed(
        np.arange(-1, n + 1) / 60.0 + (1 - np.sqrt(1 - np.sqrt(0.05))) / 2 * T, 0, T, 1 / 1.875 * T
    )
    np.testing.assert_allclose(v, full[1:-1], atol=1e-12)  # the same bell, peak 1
    assert full[0] < 0.05 and full[-1] == pytest.approx(ratio) and v[-1] > ratio  # onset and contact samples
    if n >= 100:
        assert v.max() == pytest.approx(1.0, abs=1e-3)


def test_a_profiles_sparc_does_not_depend_on_the_other_profiles_of_the_batch():
    """The partitions of a Dask run see other batches than the in-memory path: each profile's SPARC,
    band end and capped flag must be the same bits whatever profiles are computed with it (alone, in a
    random subset, all). Catches a batch padded to its longest profile or a BLAS product whose rounding
    depends on the number of rows."""
    rng = np.random.default_rng(3)
    vs = [
        minimum_jerk_speed(np.arange(n) / 60.0, 0, n / 60.0 / 0.8) * (1 + 0.05 * rng.random(n))
        for n in rng.integers(12, 140, 400)
    ]
    full = sparc_bands(vs, 60.0)
    idx = np.sort(rng.choice(len(vs), 60, replace=False))
    part = sparc_bands([vs[i] for i in idx], 60.0)
    alone = np.array([sparc_bands([vs[i]], 60.0).sparc[0] for i in idx[:20]])
    np.testing.assert_array_equal(part.sparc, full.sparc[idx])
    np.testing.assert_array_equal(part.band_end_hz, full.band_end_hz[idx])
    np.testing.assert_array_equal(alone, full.sparc[idx[:20]])
