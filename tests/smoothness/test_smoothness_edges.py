"""skilllib.smoothness at the edges its docstrings name: a one-bin band, the capped flag at fc = Nyquist
and at the threshold itself, LDLJ's independence of fs, short and empty inputs of ``ldlj_many``, the
reference profiles' defaults and argument checks.

Each test says which wrong behaviour it catches; expected values come from the definitions (by hand,
numpy's FFT) or from the SPARC authors' package monalysa, never from skilllib's own output.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from monalysa.quality.smoothness import log_dimensionless_jerk as ldlj_authors
from monalysa.quality.smoothness import sparc as sparc_authors

from skilllib.smoothness import (
    ldlj,
    ldlj_many,
    minimum_jerk_segment,
    minimum_jerk_speed,
    sparc,
    sparc_bands,
    sparc_many,
    sparc_spectrum,
)

FS = 60.0  # Hz
NYQUIST = FS / 2


def capped_by_definition(v: np.ndarray, fs: float, fc: float, amp_th: float, padlevel: int = 4) -> bool:
    """The docstring's definition, from numpy's FFT: some bin above fc and at or below the Nyquist
    frequency has a normalised magnitude at or above amp_th."""
    n_fft = int(2 ** (np.ceil(np.log2(v.size)) + padlevel))
    Mf = np.abs(np.fft.fft(v, n_fft))
    Mf = Mf / Mf.max()
    f = np.arange(n_fft) * fs / n_fft
    return bool(np.any(Mf[(f > fc) & (f <= fs / 2)] >= amp_th))


# --- SPARC: a one-bin band, the capped flag -------------------------------------------------------


def test_a_one_bin_band_gives_plus_zero_as_the_authors():
    """A band of a single bin has an empty arc: SPARC 0, the authors' value (an empty sum). Catches a
    negative zero, which results.json and every table would print as "-0.0"."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        theirs = sparc_authors(np.array([0.3]), 1000.0, fc=20.0)[0]
    assert theirs == 0 and not np.signbit(theirs)
    values = [
        sparc([0.3], 1000.0),
        sparc_spectrum([0.3], 1000.0).sparc,
        sparc_many([[0.3]], 1000.0)[0],
        sparc_bands([[0.3]], 1000.0).sparc[0],
    ]
    assert [repr(float(x)) for x in values] == ["0.0"] * 4


def test_fc_at_nyquist_never_caps_even_a_flat_spectrum():
    """No bin lies above fc = fs / 2 and at or below it, so nothing can cap the band. A single sample
    has a flat spectrum (1 at every bin, mirror image included): catches a capped test that reads one
    bin past Nyquist, into the mirror image of the bins just below it."""
    v = np.array([0.7])
    for fc in (NYQUIST, NYQUIST - 1.0):
        assert capped_by_definition(v, FS, fc, 0.05) is (fc < NYQUIST)
        assert sparc_spectrum(v, FS, fc=fc).capped is (fc < NYQUIST)
        assert bool(sparc_bands([v], FS, fc=fc).capped[0]) is (fc < NYQUIST)


@pytest.mark.parametrize("fc", [10.0, 25.0, NYQUIST - FS / 64, NYQUIST])
def test_capped_is_the_definition_on_varied_profiles(fc):
    """capped == some bin in (fc, fs / 2] reaches amp_th, on noisy, bell and truncated profiles, fc up to
    Nyquist and one grid step (fs / nfft for 4 samples, padlevel 4) below it. Catches a capped flag
    that counts bins beyond Nyquist or misses the last one."""
    rng = np.random.default_rng(11)
    bell = minimum_jerk_speed(np.arange(0, 1, 1 / FS))
    vs = [np.abs(rng.normal(size=4)) + 0.1, np.abs(rng.normal(size=50)) + 0.1, bell, bell[:40], rng.normal(size=33)]
    for amp_th in (0.05, 0.2):
        expected = [capped_by_definition(v, FS, fc, amp_th) for v in vs]
        assert [sparc_spectrum(v, FS, fc=fc, amp_th=amp_th).capped for v in vs] == expected
        assert sparc_bands(vs, FS, fc=fc, amp_th=amp_th).capped.tolist() == expected
    if fc < NYQUIST:  # both outcomes occur, so neither a constant True nor a constant False passes
        assert 0 < sum(capped_by_definition(v, FS, fc, 0.05) for v in vs) < len(vs)


def test_a_bin_exactly_at_amp_th_above_fc_caps_the_band():
    """ "Reaches amp_th" is >=, as the authors' band (Mf >= amp_th): a single sample's spectrum is exactly
    1 at every bin, so with amp_th = 1 every bin above fc reaches it. Catches a strict comparison."""
    v = np.array([1.0])
    assert capped_by_definition(v, FS, 10.0, 1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        their_end = sparc_authors(v, FS, fc=NYQUIST, amp_th=1.0, padlevel=4)[2][0][-1]
    assert their_end == NYQUIST > 10.0  # with fc at Nyquist their band runs past our fc
    assert sparc_spectrum(v, FS, fc=10.0, amp_th=1.0).capped
    assert sparc_bands([v], FS, fc=10.0, amp_th=1.0).capped.tolist() == [True]


def test_spectrum_records_its_parameters():
    """SparcSpectrum carries fs, fc, amp_th and nfft as used (the figures label their axes with them).
    Catches a field left empty or swapped."""
    v = minimum_jerk_speed(np.arange(0, 0.8, 1 / FS))  # 48 samples: nfft = 2**(6 + 3) with padlevel 3
    s = sparc_spectrum(v, FS, fc=12.5, amp_th=0.1, padlevel=3)
    assert (s.fs, s.fc, s.amp_th, s.nfft) == (60.0, 12.5, 0.1, 512)
    assert s.f[1] == FS / 512 and s.f_sel[-1] == s.cutoff <= 12.5


# --- LDLJ ------------------------------------------------------------------------------------------


def by_hand_ldlj(v: np.ndarray) -> float:
    """-ln(N**3 sum (second difference of v / v_peak)**2): the authors' -ln |DLJ| with duration N dt,
    jerk (second difference) / dt**2 and the integral a sum times dt; the powers of dt cancel."""
    d2 = np.diff(np.asarray(v, dtype=float) / np.max(np.abs(v)), 2)
    return float(-np.log(v.size**3 * np.sum(d2**2)))


def test_ldlj_does_not_depend_on_fs_and_never_overflows():
    """LDLJ is dimensionless: the same samples give the same value at any fs. Catches a wrong sampling
    interval (1/fs is needed nowhere once the powers cancel) and the inf/NaN that powers of dt gave at
    extreme (if accepted) rates such as 1e-100 or 1e200 Hz."""
    v = minimum_jerk_speed(np.arange(0, 1, 1 / FS), 0, 1.0, 0.3) + 0.01 * np.sin(np.arange(60))
    with np.errstate(all="ignore"):
        assert ldlj_authors(v, FS) == pytest.approx(by_hand_ldlj(v), rel=1e-12)  # the identity holds
    for fs in (1e-200, 1e-100, 1e-3, 7.0, FS, 1e4, 1e100, 1e200):
        assert ldlj(v, fs) == pytest.approx(by_hand_ldlj(v), rel=1e-12)
        np.testing.assert_allclose(ldlj_many([v[:30], v], fs), [by_hand_ldlj(v[:30]), by_hand_ldlj(v)], rtol=1e-12)


def test_ldlj_many_of_a_very_long_profile():
    """2.2 million samples (37 min at 1 kHz): N**3 exceeds the int64 range. Catches a cube taken in
    integers (wrapping around to a wrong or negative value) rather than in floats."""
    t = np.arange(2_200_000) / 1000.0
    v = 1.5 + np.sin(t)
    assert 2_200_000**3 > np.iinfo(np.int64).max
    assert ldlj_many([v], 1000.0)[0] == pytest.approx(by_hand_ldlj(v), rel=1e-9)
    assert ldlj(v, 1000.0) == pytest.approx(by_hand_ldlj(v), rel=1e-9)


def test_constant_speed_gives_plus_inf_without_a_warning():
    """Constant speed has no jerk: +inf, as documented, silently (log of 0 is the expected case, not a
    numerical accident). Catches a RuntimeWarning 'divide by zero' reaching the user."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert ldlj(np.full(7, 0.4), FS) == np.inf
        assert ldlj_many([np.full(7, 0.4), np.full(3, 2.0)], FS).tolist() == [np.inf, np.inf]


@pytest.mark.parametrize("where", [0, 1, 2])
@pytest.mark.parametrize("short", [[0.1], [0.1, 0.2]])
def test_ldlj_many_names_a_profile_too_short_for_second_differences(short, where):
    """A profile of 1 or 2 samples has no second difference: ValueError naming it, as ldlj does,
    wherever it stands. Catches a value computed from differences straddling two profiles."""
    good = minimum_jerk_speed(np.arange(0, 1, 1 / FS))
    vs = [good, good]
    vs.insert(where, short)
    with pytest.raises(ValueError, match=rf"speeds\[{where}\] has {len(short)} samples; at least 3 needed"):
        ldlj_many(vs, FS)
    with pytest.raises(ValueError, match=f"speed has {len(short)} samples; at least 3 needed"):
        ldlj(short, FS)


def test_many_of_no_profiles_is_empty():
    """No profiles, no values: an empty float array, as sparc_many. Catches an error or a stray value."""
    for fn in (ldlj_many, sparc_many):
        out = fn([], FS)
        assert out.shape == (0,) and out.dtype == float


# --- reference profiles ----------------------------------------------------------------------------


def test_minimum_jerk_speed_defaults_are_one_metre_in_one_second():
    """Defaults D = 1 m, T = 1 s, t0 = 0: v = 30 tau**2 (1 - tau)**2, peak 1.875 m/s at 0.5 s and
    30 (1/16)(9/16) = 1.0546875 m/s at 0.25 s (Flash & Hogan 1985). Catches another default amplitude
    or duration."""
    v = minimum_jerk_speed([0.25, 0.5, 0.75, 1.5])
    assert v.tolist() == [1.0546875, 1.875, 1.0546875, 0.0]


def test_minimum_jerk_speed_takes_time_stamps_in_double_precision():
    """Times stored as float32 (as some recording formats keep them) or integers are evaluated in
    float64: the same values as the same instants given as float64. Catches arithmetic done in the
    input's float32, which is off by about 1e-7 relative."""
    t32 = np.arange(0, 1.4, 1 / 97, dtype=np.float32)
    v = minimum_jerk_speed(t32, 0.1, 1.1, 0.3)
    assert v.dtype == np.float64
    np.testing.assert_array_equal(v, minimum_jerk_speed(t32.astype(np.float64), 0.1, 1.1, 0.3))
    np.testing.assert_array_equal(minimum_jerk_speed(np.arange(5), 0, 4), minimum_jerk_speed(np.arange(5.0), 0, 4))


@pytest.mark.parametrize(
    "n, contact, onset",
    [
        (0, 0.5, 0.05),
        (-3, 0.5, 0.05),  # no samples
        (10, 0.5, 0.0),
        (10, 0.5, 1.0),
        (10, 0.5, 1.5),
        (10, 0.5, -0.1),  # onset ratio outside (0, 1)
        (10, 0.0, 0.05),
        (10, 1.0, 0.05),
        (10, 1.5, 0.05),
        (10, -0.2, 0.05),  # contact ratio outside (0, 1)
    ],
)
def test_minimum_jerk_segment_refuses_what_has_no_onset_or_contact(n, contact, onset):
    """Ratios of the peak must lie strictly inside (0, 1) (0 has no onset time, 1 is the peak itself,
    above 1 never happens) and n >= 1. Catches a bound taken inclusively or an 'or' read as 'and'."""
    with pytest.raises(
        ValueError,
        match=rf"need n >= 1 and ratios in \(0, 1\); got n = {n}, "
        rf"onset_ratio = {onset}, contact_ratio = {contact}$",
    ):
        minimum_jerk_segment(n, contact, FS, onset_ratio=onset)


def test_minimum_jerk_segment_of_one_sample_is_the_onset():
    """n = 1 is allowed: the single sample is the onset, at onset_ratio of the peak. Catches n = 1
    refused."""
    assert minimum_jerk_segment(1, 0.5, FS).tolist() == [pytest.approx(0.05, abs=1e-15)]
    assert minimum_jerk_segment(1, 0.5, FS, onset_ratio=0.2).tolist() == [pytest.approx(0.2, abs=1e-15)]


@pytest.mark.parametrize("amp_th", [0.0, -0.1])
def test_a_threshold_at_or_below_zero_keeps_the_whole_band_as_the_authors(amp_th):
    """amp_th <= 0: every bin up to fc is above the threshold, so the band runs to fc, as in the
    authors' code (their ``Mf >= amp_th``). Catches a negative threshold squared into a positive one
    or turned into one no bin reaches."""
    v = minimum_jerk_speed(np.linspace(0, 1, 61)) * (1 + 0.3 * np.sin(np.linspace(0, 9, 61)))
    theirs = sparc_authors(v, FS, padlevel=4, fc=10.0, amp_th=amp_th)[0]
    assert sparc(v, FS, fc=10.0, amp_th=amp_th) == pytest.approx(theirs, abs=1e-9)
    assert sparc_many([v], FS, fc=10.0, amp_th=amp_th)[0] == pytest.approx(theirs, abs=1e-9)
    df = FS / 2**10  # Hz: the bin spacing, n_fft = 2 ** (ceil(log2(61)) + 4) = 1024
    assert 10.0 - df < sparc_bands([v], FS, fc=10.0, amp_th=amp_th).band_end_hz[0] <= 10.0  # the last bin up to fc


def test_profiles_of_text_are_refused_with_the_message_not_a_numpy_error():
    """Speeds given as text (e.g. read from a file without conversion): a ValueError saying what speeds
    must be, from sparc_many and ldlj_many alike, never numpy's TypeError from comparing strings."""
    text = np.array(["0.1", "0.4", "0.2", "0.1"])
    for many in (sparc_many, ldlj_many):
        with pytest.raises(ValueError, match=r"^speeds must be a sequence of 1-D speed profiles \(m/s\)$"):
            many([text], FS)


def test_single_threaded_limits_the_pools_and_restores_them():
    """``single_threaded`` (context manager and decorator) holds the chosen thread pools at one thread
    and restores them on leaving, also after an exception. Catches limits left behind or not applied."""
    from threadpoolctl import threadpool_info

    from skilllib.smoothness import single_threaded

    def threads(api=None):
        return [i["num_threads"] for i in threadpool_info() if api in (None, i["user_api"])]

    before = [(i["filepath"], i["num_threads"]) for i in threadpool_info()]
    with single_threaded("blas"):
        assert threads("blas") and set(threads("blas")) == {1}
    assert single_threaded()(threads)() and set(single_threaded()(threads)()) == {1}
    with pytest.raises(RuntimeError), single_threaded():
        raise RuntimeError
    assert [(i["filepath"], i["num_threads"]) for i in threadpool_info()] == before


def test_single_threaded_sees_pools_loaded_after_its_first_use():
    """A pool loaded after the first use (scikit-learn's OpenMP, imported later) is limited too: the
    controller is not frozen at the first call. Catches K-means left on all threads because SPARC ran
    first. Runs in a fresh interpreter, where scikit-learn is not yet imported."""
    import subprocess
    import sys

    code = (
        "from threadpoolctl import threadpool_info\n"
        "from skilllib.smoothness import single_threaded\n"
        "with single_threaded():\n    pass\n"
        "import sklearn.cluster\n"
        "with single_threaded():\n"
        "    inside = {i['user_api']: i['num_threads'] for i in threadpool_info()}\n"
        "print(sorted(inside.items()))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "('openmp', 1)" in out and "('blas', 1)" in out
