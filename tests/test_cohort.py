"""Tests of skilllib.cohort: the seeded generator of the synthetic cohort and the committed data file."""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from skilllib import calibration, cohort
from skilllib.data import COLUMNS, format_recordings, read_recordings, recordings_from_frame
from skilllib.features import trial_features

ROOT = Path(__file__).resolve().parents[1]
COHORT_CSV = ROOT / "data" / "cohort.csv"
SMALL = replace(cohort.CohortModel(), n_participants=3, n_trials=6)
WORKSPACE = np.array([0.381, 0.267, 0.191])  # m, Phantom Premium 1.5 (x, y, z), centred on the origin


@pytest.fixture(scope="module")
def full():
    return cohort.generate_cohort()


@pytest.fixture(scope="module")
def committed_features():
    return trial_features(read_recordings(COHORT_CSV))


def test_committed_file_is_what_the_seeded_generator_writes(full):
    assert COHORT_CSV.exists(), "data/cohort.csv is missing: run skilllib.cohort.write_cohort('data/cohort.csv')"
    assert format_recordings(full.frame).encode("utf-8") == COHORT_CSV.read_bytes(), (
        "data/cohort.csv differs from generate_cohort(SEED): regenerate it with skilllib.cohort.write_cohort")


def test_the_paper_design_10_by_150_at_60_hz(full):
    f = full.frame
    assert list(f.columns) == list(COLUMNS)
    assert f.groupby("participant")["trial"].nunique().tolist() == [150] * 10
    rec = recordings_from_frame(f)
    assert len(rec) == 1500 and (rec.trials.status == "ok").all()
    assert rec.fs == pytest.approx(60.0, rel=1e-9)


def test_same_seed_same_cohort_other_seed_other_cohort():
    a, b, c = (cohort.generate_cohort(s, SMALL).frame for s in (5, 5, 6))
    assert a.equals(b)
    assert not a[["x", "y", "z"]].equals(c[["x", "y", "z"]])


def test_more_trials_leave_the_earlier_trials_unchanged():
    a = cohort.generate_cohort(3, SMALL).frame
    b = cohort.generate_cohort(3, replace(SMALL, n_trials=9)).frame
    b = b[b.trial <= SMALL.n_trials].reset_index(drop=True)
    assert a.equals(b)


def test_trials_rest_then_touch_and_stay_in_the_workspace(full):
    f, truth = full.frame, full.truth.set_index(["participant", "trial"])
    pos = f[["x", "y", "z"]].to_numpy()
    assert (np.abs(pos) < WORKSPACE / 2).all()
    for (p, tr), g in list(f.groupby(["participant", "trial"]))[::37]:
        t, c = g.t.to_numpy(), g.contact.to_numpy()
        assert t[0] == 0 and np.allclose(np.diff(t), 1 / 60)
        ci = int(np.argmax(c))
        assert (c[:ci] == 0).all() and (c[ci:] == 1).all() and ci > 0
        true = truth.loc[(p, tr)]
        assert t[ci - 1] < true.t_contact <= t[ci] + 1e-12  # flagged at the first sample after the touch
        assert true.t_onset > 0.25  # rest before onset
        y = g.y.to_numpy()
        travel = y[0] - y[ci:].max()
        assert 0.06 < travel < 0.23  # vertical travel of the start box (0.08-0.2 m, start box 2 cm)
        assert np.ptp(y[ci + 3:]) < 0.003  # resting on the surface


def test_every_generated_trial_is_segmentable_and_estimates_match_truth(full, committed_features):
    f = committed_features
    assert (f.status != "invalid").all()
    m = f.merge(full.truth, on=["participant", "trial"], suffixes=("", "_true"))
    assert np.median(np.abs(m.pv / m.pv_true - 1)) < 0.03  # 60 Hz peak speed within a few per cent
    assert np.median(np.abs(m.contact_speed - m.contact_speed_true)) < 0.06  # m/s
    lag = m.t_contact - m.t_contact_true  # first contact sample after the touch; t rounded to 0.1 ms
    assert (lag >= -1e-4).all() and (lag < 1 / 60 + 1e-4).all()


@pytest.fixture(scope="module")
def committed_sweep(committed_features):
    from skilllib.prototypes import silhouette_sweep

    return silhouette_sweep(committed_features[committed_features.status == "selected"], 2, 16, scaling="raw")


def test_calibration_targets_are_met(committed_features, committed_sweep):
    table = calibration.calibration_table(committed_features, committed_sweep)
    assert table["met"].all(), table[~table["met"]]


def test_committed_seed_survey_matches_the_committed_cohort_and_the_seed_rule(committed_features, committed_sweep):
    survey = pd.read_csv(calibration.SURVEY_CSV, index_col="seed")
    assert list(survey.index) == list(range(20))
    v = calibration.calibration_values(committed_features, committed_sweep)
    row = survey.loc[cohort.SEED]
    assert row.selected == v["n_selected"] and row.valid_k == len(v["valid_ks"])
    assert row.silhouette_k6 == pytest.approx(v["silhouette_k6"], abs=5e-4)
    assert row.centre_gap == pytest.approx(v["centre_gap"], abs=5e-4)
    assert row.participant_ratio == pytest.approx(min(v["participant_ratio"].values()), abs=5e-3)
    assert survey["all"].idxmax() == cohort.SEED and survey["all"].any()  # the first seed meeting every target
    summary = calibration.survey_summary(survey)
    assert summary["all targets"] == survey["all"].sum() <= summary.drop(["seeds", "all targets"]).min()


def test_intended_contact_speeds_have_a_smooth_tail_not_a_clip_spike(full):
    aim, m = full.truth.contact_aim.to_numpy(), cohort.CohortModel()
    assert m.aim_soft_min[1] < aim.min() and aim.max() < m.aim_soft_max[1]
    tails = aim[(aim < m.aim_soft_min[0]) | (aim > m.aim_soft_max[0])]
    assert tails.size > 100 and np.unique(tails).size == tails.size  # np.clip piled them up at the limits


@settings(max_examples=60, deadline=None)
@given(v=st.floats(0.01, 100.0))
def test_soft_max_is_identity_below_the_knee_and_bounded_and_monotone_above(v):
    knee, ceiling = 1.0, 1.8
    out = cohort._soft_max(v, knee, ceiling)
    if v <= knee:
        assert out == v
    else:
        assert knee < out < ceiling and out <= v
        assert cohort._soft_max(v * 1.01, knee, ceiling) >= out
    eps = 1e-6  # slope 1 at the knee: no kink where compression starts
    assert (cohort._soft_max(knee + eps, knee, ceiling) - knee) / eps == pytest.approx(1.0, rel=1e-4)


@settings(max_examples=8, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_any_seed_gives_valid_segmentable_trials(seed):
    c = cohort.generate_cohort(seed, SMALL)
    f = trial_features(c.frame)
    assert len(f) == SMALL.n_participants * SMALL.n_trials
    assert (f.status != "invalid").all(), f[f.status == "invalid"].reason.tolist()


@settings(max_examples=40, deadline=None)
@given(amp=st.floats(0.01, 0.3), dur=st.floats(0.1, 1.0), k=st.floats(0.35, 0.7), onset=st.floats(0, 1))
def test_submovement_is_an_asymmetric_minimum_jerk_bell(amp, dur, k, onset):
    """Displacement 0 -> amp, peak speed 1.875 amp / dur at onset + k dur, speed = d(displacement)/dt."""
    t = np.linspace(onset - 0.1, onset + dur + 0.1, 4001)
    s, v = cohort.submovement(t, onset, amp, dur, k)
    assert s[0] == 0 and s[-1] == pytest.approx(amp)
    assert v.max() == pytest.approx(1.875 * amp / dur, rel=1e-4)
    assert t[np.argmax(v)] == pytest.approx(onset + k * dur, abs=2 * (t[1] - t[0]))
    np.testing.assert_allclose(np.gradient(s, t), v, atol=2e-3 * v.max())
    assert (np.diff(s) >= -1e-15).all()


def test_model_table_gives_every_parameter_a_value_unit_and_meaning():
    t = cohort.model_table()
    assert list(t.index) == list(cohort.CohortModel.__dataclass_fields__)
    assert t["meaning"].str.len().min() > 5
    assert t.loc["fs", "unit"] == "Hz" and t.loc["noise_sd", "unit"] == "m" and t.loc["travel", "unit"] == "m"
    assert t.loc["noise_sd", "value"] == str(cohort.CohortModel().noise_sd)
