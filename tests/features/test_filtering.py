"""The positions' low-pass filter (skilllib.features) and what it does for noisy recordings (issue 12)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.signal import butter, sosfreqz

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.features import _filtering as flt
from skilllib.features import approaches, diff_window, run_lowpass, trial_features
from skilllib.recordings import recordings_from_frame


def test_the_cut_off_is_the_minus_3_db_point_of_the_forward_backward_filter():
    """Two passes square the gain: the single pass is designed above the cut-off so that the whole filter
    has |H|^2 = 1/2 there (Winter's correction 0.802 for order 2; exact with the bilinear warping)."""
    assert flt.design_frequency(6.0) == pytest.approx(6.0 / 0.8022, rel=1e-4)
    for fs, fc in ((250.0, 6.0), (60.0, 12.0), (1000.0, 3.0)):
        sos = butter(flt.ORDER, flt.design_frequency(fc, fs=fs), fs=fs, output="sos")
        _, h = sosfreqz(sos, worN=[fc], fs=fs)
        assert abs(h[0]) ** (2 * flt.PASSES) == pytest.approx(0.5, rel=1e-9)


def test_the_filter_has_no_lag_and_passes_slow_movements():
    """A bell well below the cut-off keeps its peak time and height (zero phase; the ends extended)."""
    fs = 200.0
    t = np.arange(300) / fs
    y = np.exp(-(((t - 0.7) / 0.15) ** 2))[:, None] * np.array([0.0, 0.1, 0.02])
    out = flt.butterworth_lowpass(y, fs, 10.0)
    assert np.argmax(out[:, 1]) == np.argmax(y[:, 1])
    assert np.abs(out - y).max() < 1e-3 * 0.1


def test_the_ends_are_not_pinned_to_the_noise_of_the_end_samples():
    """scipy's odd extension keeps the first sample's noise in the filtered signal (a step that reads as a
    movement onset); the line fitted to the start keeps far less of it."""
    from scipy.signal import sosfiltfilt

    rng = np.random.default_rng(1)
    fs, sd = 250.0, 0.001
    x = rng.normal(0, sd, (200, 3))
    x[0] = 5 * sd  # a bad first sample
    out = flt.butterworth_lowpass(x, fs, 5.0)
    scipy_out = sosfiltfilt(butter(2, flt.design_frequency(5.0, fs=fs), fs=fs, output="sos"), x, axis=0)
    assert np.abs(scipy_out[0] - x[0]).max() < 0.2 * sd  # held near the bad sample (5 sd)
    assert np.abs(out[0]).max() < 0.25 * np.abs(scipy_out[0]).max()


@settings(max_examples=20, deadline=None)
@given(sd=st.floats(1e-5, 2e-3), fs=st.sampled_from([60.0, 100.0, 120.0, 250.0, 500.0]))
def test_rest_noise_recovers_white_noise(sd, fs):
    rng = np.random.default_rng(int(sd * 1e7) + int(fs))
    trials = [np.array([0.01, 0.2, -0.03]) + rng.normal(0, sd, (int(0.5 * fs), 3)) for _ in range(60)]
    assert flt.rest_noise(trials, fs) == pytest.approx(sd, rel=0.1)


def test_speed_noise_matches_a_monte_carlo_derivative():
    """The Parseval formula against white noise filtered and differentiated by skilllib itself."""
    from skilllib.features import velocity

    rng = np.random.default_rng(2)
    fs, sd = 250.0, 0.0005
    x = rng.normal(0, sd, (20000, 3))
    for cut in (None, 8.0):
        y = x if cut is None else flt.butterworth_lowpass(x, fs, cut)
        v = velocity(y, fs)[100:-100]
        measured = np.sqrt(np.mean(np.sum(v**2, axis=1)))
        assert flt.speed_noise(sd, fs, diff_window(fs), cut) == pytest.approx(measured, rel=0.05)


def test_residual_analysis_finds_the_noise_of_a_smooth_movement():
    fs, sd = 250.0, 0.0005
    rng = np.random.default_rng(3)
    t = np.arange(int(1.2 * fs)) / fs
    s = np.clip((t - 0.3) / 0.6, 0, 1)
    path = np.column_stack([0.01 * s, -0.15 * (10 * s**3 - 15 * s**4 + 6 * s**5), 0 * s])
    ra = flt.residual_analysis([path + rng.normal(0, sd, path.shape) for _ in range(30)], fs)
    assert sd < ra.noise_m < 1.5 * sd  # Winter's intercept overestimates the noise a little
    assert 3.0 < ra.cutoff_hz < 10.0 and ra.residual[0] > ra.residual[-1]


@pytest.mark.parametrize("spec, want", [("none", None), ("NONE", None), (" auto ", "auto"), ("12.5", 12.5), (8, 8.0)])
def test_parse_lowpass(spec, want):
    got = flt.parse_lowpass(spec)
    assert got == ("none" if want is None else want)


@pytest.mark.parametrize("bad", ["fast", "0", "-3", "nan", "inf"])
def test_parse_lowpass_rejects(bad):
    with pytest.raises(ValueError):
        flt.parse_lowpass(bad)


def test_a_cut_off_above_what_the_rate_allows_is_refused():
    with pytest.raises(ValueError, match="too high"):
        flt.choose_lowpass(50.0, [], 60.0, 3)


def test_auto_leaves_the_books_cohort_unfiltered_and_unchanged():
    rec = recordings_from_frame(generate_cohort(9, CohortModel(n_participants=3, n_trials=20)).frame)
    lp = run_lowpass(rec, "auto")
    assert lp.cutoff_hz is None and lp.chosen_by == "auto: not needed"
    assert lp.speed_noise < flt.SPEED_NOISE_LIMIT and lp.noise_m == pytest.approx(CohortModel().noise_sd, rel=0.3)
    a, b = trial_features(rec, lowpass="auto"), trial_features(rec, lowpass="none")
    assert a.drop(columns=[]).equals(b)


def test_auto_does_not_read_an_abrupt_noise_free_start_as_noise():
    """A noise-free ramp that starts with a kink: Winter's intercept would see noise; the rest noise is 0."""
    fs = 60.0
    n = 40
    y = -np.maximum(np.arange(n) - 9, 0) * 0.5 / fs
    pos = np.column_stack([np.zeros(n), y, np.zeros(n)])
    lp = flt.choose_lowpass("auto", [pos] * 5, fs, diff_window(fs))
    assert lp.cutoff_hz is None and lp.noise_m == 0.0


NOISY = [(100.0, 0.0001), (120.0, 0.0005), (250.0, 0.0002), (250.0, 0.001)]


@pytest.mark.parametrize("fs, sd", NOISY, ids=[f"{f:g}Hz-{s * 1e3:g}mm" for f, s in NOISY])
def test_every_sound_trial_of_a_noisy_recording_is_kept(fs, sd):
    """Tracker noise of 0.1-1 mm at 100-250 Hz with +-1 ms frame jitter: every trial valid without the noise
    is valid with it (the default filter), while without a filter most are lost at the higher noise."""
    model = CohortModel(n_participants=3, n_trials=15, fs=fs)
    clean = trial_features(generate_cohort(21, replace(model, noise_sd=0.0)).recordings, lowpass="none")
    frame = generate_cohort(21, replace(model, noise_sd=sd)).frame
    rng = np.random.default_rng(21)
    frame = frame.assign(t=frame.t + rng.uniform(-0.001, 0.001, len(frame)))
    rec = recordings_from_frame(frame)
    f = trial_features(rec)
    sound = clean.status != "invalid"
    assert sound.all() and (f.status[sound] != "invalid").all(), f.reason[f.status == "invalid"].tolist()
    assert f.attrs["lowpass"].cutoff_hz is not None
    if sd >= 0.0005:
        assert (trial_features(rec, lowpass="none").status == "invalid").mean() > 0.5


def test_winters_cut_off_is_used_when_the_noise_needs_a_filter():
    model = CohortModel(n_participants=3, n_trials=15, fs=250.0, noise_sd=0.0005)
    rec = recordings_from_frame(generate_cohort(22, model).frame)
    lp = run_lowpass(rec, "auto")
    ra = flt.residual_analysis(approaches(rec), rec.fs)
    assert lp.chosen_by == "winter residual analysis" and lp.cutoff_hz == pytest.approx(ra.cutoff_hz)
    assert lp.noise_m == pytest.approx(0.0005, rel=0.15) and lp.speed_noise > flt.SPEED_NOISE_LIMIT
    d = lp.to_dict()
    assert d["cutoff_hz"] == lp.cutoff_hz and d["design_hz"] == pytest.approx(
        flt.design_frequency(lp.cutoff_hz, fs=rec.fs)
    )
    assert (d["order"], d["passes"]) == (2, 2)
