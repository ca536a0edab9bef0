"""Measures of corrective submovements (issue 25): speed peaks with a prominence threshold, the deepest
dip, and the per-trial table on a small synthetic cohort measured against the generator's truth."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.features import (
    CORRECTION_MEASURES,
    PEAK_NOISE_FACTOR,
    correction_measures,
    dip_depth,
    select,
    speed_peaks,
    trial_features,
)
from skilllib.smoothness import minimum_jerk_submovements

FS = 60.0


def test_one_minimum_jerk_bell_has_one_peak_at_its_maximum():
    v = minimum_jerk_submovements([0.0], FS, T=0.6, D=0.3)
    peaks = speed_peaks(v, 0.0)
    assert peaks.tolist() == [int(np.argmax(v))]
    assert dip_depth(v) == 0.0


def test_two_overlapping_submovements_with_a_clear_dip_have_two_peaks():
    v = minimum_jerk_submovements([0.0, 0.8], FS, T=1.0, D=0.4)
    peaks = speed_peaks(v, 0.01 * v.max())
    assert len(peaks) == 2
    # each peak near the middle of its submovement (0.5 s and 1.3 s)
    assert np.allclose(peaks / FS, [0.5, 1.3], atol=0.1)
    low = v[peaks[0] : peaks[1] + 1].min()
    assert dip_depth(v) == pytest.approx((min(v[peaks]) - low) / v.max())
    assert 0.3 < dip_depth(v) < 1


def _two(gap: float, second: float) -> np.ndarray:
    """Speed (m/s) of a bell of 1 s and a second one ``gap`` s later, ``second`` times as high."""
    v = minimum_jerk_submovements([0.0], FS, T=1.0, D=0.3)
    w = np.zeros(int((gap + 1.0) * FS) + 1)
    w[: v.size] += v
    w[int(gap * FS) : int(gap * FS) + v.size] += second * v[: w.size - int(gap * FS)]
    return w


def test_a_dip_shallower_than_the_prominence_is_not_a_peak():
    v = _two(0.8, 0.7)  # unequal peaks: equal ones would each keep the full height as prominence
    peaks = speed_peaks(v, 0.0)
    depth = min(v[peaks]) - v[peaks[0] : peaks[1] + 1].min()  # (m/s)
    assert len(speed_peaks(v, 0.99 * depth)) == 2
    assert len(speed_peaks(v, 1.01 * depth)) == 1


def test_a_profile_still_rising_at_its_end_counts_its_last_sample():
    v = minimum_jerk_submovements([0.0, 0.8], FS, T=1.0, D=0.4)
    cut = v[: int(1.1 * FS)]  # cut during the second submovement's acceleration
    assert np.all(np.diff(cut[-5:]) > 0)
    peaks = speed_peaks(cut, 0.01 * v.max())
    assert peaks.tolist() == [int(np.argmax(v[: int(0.8 * FS)])), cut.size - 1]
    assert dip_depth(cut) > 0.3


def test_two_separate_movements_have_a_dip_of_depth_one():
    v = np.r_[minimum_jerk_submovements([0.0], FS), np.zeros(5), minimum_jerk_submovements([0.0], FS)]
    assert dip_depth(v) == pytest.approx(1.0)
    assert len(speed_peaks(v, 0.5 * v.max())) == 2


def test_noise_below_the_prominence_adds_no_peak():
    rng = np.random.default_rng(3)
    v = minimum_jerk_submovements([0.0], 240.0, T=1.0, D=0.3)
    a = 0.01 * v.max()
    noisy = np.abs(v + rng.uniform(-a, a, v.size))
    assert len(speed_peaks(noisy, 0.0)) > 3  # the noise does make local maxima
    assert len(speed_peaks(noisy, 2 * a + 1e-12)) == 1  # a noise maximum's prominence is at most 2a


@settings(max_examples=60, deadline=None)
@given(
    gap=st.floats(0.2, 1.2),
    second=st.floats(0.1, 2.0),
    scale=st.floats(1e-3, 1e3),
    rel=st.floats(0.0, 0.3),
)
def test_scaling_the_amplitude_with_the_threshold_leaves_the_count(gap, second, scale, rel):
    w = _two(gap, second)
    p = rel * w.max()
    assert len(speed_peaks(scale * w, scale * p)) == len(speed_peaks(w, p))
    assert dip_depth(scale * w) == pytest.approx(dip_depth(w), abs=1e-12)


@pytest.mark.parametrize("bad", [[], [[0.1, 0.2]], [0.1, np.nan], [0.1, -0.2]])
def test_bad_speeds_are_refused(bad):
    with pytest.raises(ValueError):
        speed_peaks(np.asarray(bad, dtype=float), 0.01)
    with pytest.raises(ValueError):
        dip_depth(np.asarray(bad, dtype=float))


def test_a_bad_prominence_or_an_all_zero_profile_is_refused():
    with pytest.raises(ValueError, match="prominence"):
        speed_peaks(np.ones(5), -0.01)
    with pytest.raises(ValueError, match="zero"):
        dip_depth(np.zeros(5))


@pytest.fixture(scope="module")
def small():
    """A small synthetic cohort: recordings, features, the generator's corrections."""
    cohort = generate_cohort(5, CohortModel(n_participants=3, n_trials=40))
    rec = cohort.recordings
    feats = trial_features(rec)
    return rec, feats, cohort.truth


def test_the_table_has_a_row_per_trial_given_and_the_noise_rule(small):
    rec, feats, _ = small
    sel = select(feats)
    m = correction_measures(rec, sel)
    assert list(m.columns) == ["participant", "trial", *CORRECTION_MEASURES, "n_after"]
    assert m[["participant", "trial"]].equals(sel[["participant", "trial"]].reset_index(drop=True))
    assert np.allclose(m["ldlj"], sel["ldlj"].astype(float))
    noise = feats.attrs["lowpass"].speed_noise
    assert m.attrs["prominence"] == pytest.approx(PEAK_NOISE_FACTOR * np.sqrt(2) * noise)
    assert (m["n_peaks"] >= 1).all() and m["dip_depth"].between(0, 1).all()
    assert (m["n_after"] >= 1).all()  # the whole movement goes past contact
    assert m["sparc_whole"].lt(0).all()
    # a threshold above every peak speed leaves no peak; a stated one is used as given
    assert (correction_measures(rec, sel, prominence=10.0)["n_peaks"] == 0).all()


def test_the_noise_rule_is_measured_when_the_table_does_not_carry_it(small):
    rec, feats, _ = small
    sel = select(feats).head(5)
    bare = pd.DataFrame(sel)
    bare.attrs = {}
    assert correction_measures(rec, bare).attrs["prominence"] == pytest.approx(
        correction_measures(rec, sel).attrs["prominence"], rel=0.05
    )


def test_a_second_peak_marks_a_corrected_trial(small):
    rec, feats, truth = small
    m = correction_measures(rec, feats).merge(truth, on=["participant", "trial"])
    corrected = m["n_corrections"] > 0
    assert corrected.any() and (~corrected).any()
    assert (m.loc[~corrected, "n_peaks"] == 1).all()  # the noise rule flags no uncorrected trial
    assert (m.loc[corrected, "n_peaks"] == 2).mean() > 0.3
    assert m.loc[corrected, "dip_depth"].mean() > m.loc[~corrected, "dip_depth"].mean() + 0.05
