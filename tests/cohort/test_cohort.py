"""Tests of skilllib.cohort: the seeded generator of the synthetic cohort and the committed data file."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from skilllib.cohort import _calibration as calibration
from skilllib.cohort import _model as cohort
from skilllib.features import CONTACT_WINDOW, trial_features
from skilllib.recordings import COLUMNS, format_recordings, read_recordings, recordings_from_frame

ROOT = Path(__file__).resolve().parents[2]
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
        "data/cohort.csv differs from generate_cohort(SEED): regenerate it with skilllib.cohort.write_cohort"
    )


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
    b = b[b.trial.astype(int) <= SMALL.n_trials].reset_index(drop=True)
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
        assert np.ptp(y[ci + 3 :]) < 0.003  # resting on the surface


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


def _survey(seeds: list[int]) -> pd.DataFrame:
    return calibration.seed_survey(seeds)


@pytest.mark.slow
def test_the_seed_rule_is_recomputed_from_scratch():
    """The committed survey holds seeds 0..SEED; every row is recomputed here (generator, CSV rounding,
    features, silhouette sweep: about 4 s a seed, two processes), and the rule picks SEED: the first seed
    whose cohort meets every calibration target. Slow (~25 s), but the claim rests on it."""
    from concurrent.futures import ProcessPoolExecutor

    committed = pd.read_csv(calibration.SURVEY_CSV, index_col="seed")
    seeds = list(range(cohort.SEED + 1))
    assert list(committed.index) == seeds, "the survey must hold exactly the seeds 0..SEED the rule looks at"
    with ProcessPoolExecutor(max_workers=2) as pool:
        again = pd.concat(pool.map(_survey, [seeds[0::2], seeds[1::2]])).sort_index()
    pd.testing.assert_frame_equal(again, committed, check_dtype=False)
    assert again["all"].tolist() == [False] * cohort.SEED + [True]  # SEED is the first seed meeting all
    summary = calibration.survey_summary(committed)
    assert summary["all targets"] == 1 and summary["seeds"] == cohort.SEED + 1


def test_the_committed_cohort_is_the_row_of_seed(committed_features, committed_sweep):
    row = pd.read_csv(calibration.SURVEY_CSV, index_col="seed").loc[cohort.SEED]
    v = calibration.calibration_values(committed_features, committed_sweep)
    assert row.selected == v["n_selected"] and row.valid_k == len(v["valid_ks"])
    assert row.silhouette_k6 == round(v["silhouette_k6"], 3) and row.centre_gap == round(v["centre_gap"], 3)
    assert row.participant_ratio == round(min(v["participant_ratio"].values()), 2)


# --- properties of the generator that do not depend on the seed ----------------------------------------

#: Seeds of the statistical tests: not the committed seed, not chosen for anything.
STAT_SEEDS = (100, 101, 102, 103, 104)
MEDIUM = replace(cohort.CohortModel(), n_participants=6, n_trials=40)


@pytest.fixture(scope="module")
def medium():
    return {s: cohort.generate_cohort(s, MEDIUM) for s in STAT_SEEDS}


def test_every_seed_keeps_the_models_bounds(medium):
    m = MEDIUM
    half = m.start_box / 2
    for c in medium.values():
        tr = c.truth
        assert tr.t_onset.between(*m.rest_before).all()  # rest before onset, s
        assert tr.travel.between(m.travel[0] - half, m.travel[1] + half).all()  # m, start box included
        assert tr.rtpv.between(0.35, 0.7).all()  # relative time to peak speed, clipped
        assert tr.contact_aim.between(m.aim_soft_min[1], m.aim_soft_max[1]).all()  # m/s, soft limits
        assert set(tr.n_corrections) <= {0, 1} and tr.n_corrections.any()  # second_correction = 0
        after = tr.t_contact - tr.t_onset
        assert (after > 0).all()


def test_the_selected_share_is_a_property_of_the_model_not_of_the_seed(medium):
    """About 45 % of the trials touch at 0.3-0.7 m/s (the paper: 650 of 1500, 43 %); each 240-trial
    cohort within 0.33-0.50 (binomial SD about 0.03), the 1,200 together within 0.37-0.47."""
    lo, hi = CONTACT_WINDOW
    shares = {s: c.truth.contact_speed.between(lo, hi).mean() for s, c in medium.items()}
    assert all(0.33 <= v <= 0.50 for v in shares.values()), shares
    pooled = pd.concat([c.truth for c in medium.values()]).contact_speed.between(lo, hi).mean()
    assert 0.37 <= pooled <= 0.47


def test_the_position_noise_is_the_device_resolution(medium):
    """White noise of SD noise_sd on every axis (then rounded to 0.01 mm by the writer, not here): the
    second differences of the samples at rest have SD sqrt(6) noise_sd; within 10 % in every cohort."""
    for c in medium.values():
        onset = c.truth.set_index(["participant", "trial"]).t_onset
        est = []
        for (p, tr), g in c.frame.groupby(["participant", "trial"]):
            rest = g[g.t < onset[(p, tr)] - 0.1][["x", "y", "z"]].to_numpy()
            if len(rest) >= 8:
                est.append(np.diff(rest, 2, axis=0).std(axis=0).mean() / np.sqrt(6))
        assert np.median(est) == pytest.approx(MEDIUM.noise_sd, rel=0.1)


def test_faster_movements_are_corrected_more_often(medium):
    """Corrections grow with the primary's peak speed (Meyer et al. 1988): pooled over the seeds, the
    fastest third of the trials is corrected more often than the slowest third by at least 0.1."""
    tr = pd.concat([c.truth for c in medium.values()])
    corrected = tr.n_corrections > 0
    fast, slow = tr.pv > tr.pv.quantile(2 / 3), tr.pv < tr.pv.quantile(1 / 3)
    assert corrected[fast].mean() - corrected[slow].mean() > 0.1


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(2, 12))
def test_participant_traits_fall_one_per_stratum(seed, n):
    """Latin-hypercube traits: for every trait, the n participants' values fall one in each of n
    equally probable strata of its distribution, whatever the seed."""
    from scipy.special import ndtr

    m = replace(cohort.CohortModel(), n_participants=n)
    parts = pd.DataFrame(cohort._participants(np.random.default_rng(seed), m))
    uniform = {
        "travel": m.travel,
        "surface_y": m.surface_y,
        "dur_within": m.dur_within,
        "aim_within": m.aim_within,
        "rtpv": m.rtpv,
        "correction_rate": m.correction_rate,
    }
    for col, (lo, hi) in uniform.items():
        strata = np.floor((parts[col] - lo) / (hi - lo) * n).astype(int)
        assert sorted(strata) == list(range(n)), col
    for col, median, sd in (("dur_pref", m.dur_median, m.dur_between), ("contact_aim", m.aim_median, m.aim_between)):
        u = ndtr(np.log(parts[col] / median) / sd)
        assert sorted(np.floor(u * n).astype(int)) == list(range(n)), col


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
    f = trial_features(c.recordings)
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
