"""The contact speed estimated at the contact instant (skilllib.features._contact): analytic approaches into
a wall with a known contact instant and speed, the feature table's last-sample value, the errors' summary."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import skilllib as sk
from skilllib.features import (
    CONTACT_ESTIMATORS,
    contact_speed_at,
    contact_speed_estimates,
    estimate_errors,
    trial_features,
)

FS = 60.0
DIRECTION = np.array([0.05, -1.0, 0.08]) / np.linalg.norm([0.05, -1.0, 0.08])  # down, tilted a little


def into_wall(drop, tc: float, t_end: float = 1.0, fs: float = FS):
    """Samples (t, pos, first contact index) of an approach ``drop(t)`` (m along DIRECTION) that stops at
    the wall at ``tc`` s and rests there."""
    t = np.arange(int(t_end * fs) + 1) / fs
    s = np.where(t < tc, drop(np.minimum(t, tc)), drop(tc))
    pos = np.array([0.01, 0.2, -0.03]) + s[:, None] * DIRECTION
    return t, pos, int(np.searchsorted(t, tc))


def constant_deceleration(v0: float = 1.2, a: float = 2.0):
    """Drop (m) and speed (m/s) of an approach starting at v0 m/s and decelerating at a m/s^2."""
    return (lambda t: v0 * t - a * t**2 / 2), (lambda t: v0 - a * t)


@pytest.mark.parametrize("tc", [0.3011, 0.3083, 0.3161])  # early, mid and late in a sampling interval
def test_a_constant_deceleration_into_a_wall_is_exact_and_beats_the_last_sample(tc):
    drop, speed = constant_deceleration()
    t, pos, end = into_wall(drop, tc)
    last = contact_speed_at(t, pos, end, method="last-sample", degree=2, n_fit=3)
    assert last.speed == pytest.approx(speed(t[end - 1]), abs=1e-9)  # exact, but at the last sample
    assert last.speed - speed(tc) == pytest.approx(2.0 * (tc - t[end - 1]), abs=1e-9)  # high by a * gap
    for degree, n_fit in [(2, 3), (3, 4)]:  # a quadratic motion: exact for a fit of degree 2 or more
        new = contact_speed_at(t, pos, end, method="crossing", degree=degree, n_fit=n_fit)
        assert new.t_contact == pytest.approx(tc, abs=1e-9)
        assert new.speed == pytest.approx(speed(tc), abs=1e-9)
        assert abs(new.speed - speed(tc)) < abs(last.speed - speed(tc)) - 0.002


def test_a_cubic_motion_is_exact_for_the_cubic_fit_at_the_crossing_and_at_the_midpoint():
    j = -30.0  # m/s^3
    tc = 0.2937
    t, pos, end = into_wall(lambda t: 1.0 * t + 1.5 * t**2 + j * t**3 / 6, tc)
    speed = lambda t: 1.0 + 3.0 * t + j * t**2 / 2  # noqa: E731
    got = contact_speed_at(t, pos, end, method="crossing")  # defaults: cubic, 4 samples
    assert got.t_contact == pytest.approx(tc, abs=1e-9) and got.speed == pytest.approx(speed(tc), abs=1e-9)
    mid = contact_speed_at(t, pos, end, method="midpoint")
    t_mid = (t[end - 1] + t[end]) / 2
    assert mid.t_contact == pytest.approx(t_mid) and mid.speed == pytest.approx(speed(t_mid), abs=1e-9)
    quad = contact_speed_at(t, pos, end, method="crossing", degree=2, n_fit=3)  # the wrong degree is not
    assert abs(quad.speed - speed(tc)) > 1e-3


def test_on_a_minimum_jerk_flank_sampled_at_every_phase_the_crossing_beats_the_last_sample():
    dur, amp = 0.4, 0.12  # s, m; contact on the falling flank, at 75 % of the duration plus a phase

    def drop(t):
        x = np.clip(t / dur, 0, 1)
        return amp * x**3 * (10 - 15 * x + 6 * x**2)

    def speed(t):
        x = t / dur
        return amp / dur * 30 * x**2 * (1 - x) ** 2

    err = {m: [] for m in CONTACT_ESTIMATORS}
    for phase in np.linspace(0.0005, 1 / FS - 0.0005, 25):
        tc = 0.3 + phase
        t, pos, end = into_wall(drop, tc)
        for m in CONTACT_ESTIMATORS:
            kw = {"degree": 2, "n_fit": 3} if m == "last-sample" else {}
            err[m].append(contact_speed_at(t, pos, end, method=m, **kw).speed - speed(tc))
    rmse = {m: float(np.sqrt(np.mean(np.square(e)))) for m, e in err.items()}
    assert rmse["crossing"] < rmse["last-sample"] / 3
    assert rmse["midpoint"] < rmse["last-sample"] / 1.5
    assert np.mean(err["last-sample"]) > 0.02  # decelerating: the last sample reads high


def test_too_few_samples_or_no_contact_sample_give_nan_with_the_reason():
    drop, _ = constant_deceleration()
    t, pos, end = into_wall(drop, 0.3011)
    got = contact_speed_at(t[end - 3 :], pos[end - 3 :], 3)  # 3 samples before contact, the cubic needs 4
    assert np.isnan(got.speed) and np.isnan(got.t_contact) and "the fit needs 4" in got.reason
    none_after = contact_speed_at(t[:end], pos[:end], end, method="crossing")
    assert np.isnan(none_after.speed) and "no sample in contact" in none_after.reason
    ok = contact_speed_at(t[:end], pos[:end], end, method="last-sample")  # needs no sample in contact
    assert np.isfinite(ok.speed) and ok.reason == ""


@pytest.mark.parametrize(
    ("kw", "words"),
    [
        ({"method": "spline"}, "unknown contact estimator"),
        ({"degree": 0, "n_fit": 3}, "degree must be at least 1"),
        ({"degree": 3, "n_fit": 3}, "cannot fit a polynomial of degree 3"),
    ],
)
def test_bad_settings_raise_with_the_problem(kw, words):
    drop, _ = constant_deceleration()
    t, pos, end = into_wall(drop, 0.3011)
    with pytest.raises(ValueError, match=words):
        contact_speed_at(t, pos, end, **kw)


def test_estimate_errors_summarises_and_counts_the_flips_of_the_window():
    got = estimate_errors(np.array([0.35, 0.69, 0.8, np.nan]), np.array([0.25, 0.71, 0.8, 0.5]))
    assert got["trials"] == 3  # the NaN estimate left out
    assert got["bias"] == pytest.approx((0.1 - 0.02) / 3)
    assert got["RMSE"] == pytest.approx(np.sqrt((0.01 + 0.0004) / 3))
    assert got["max |error|"] == pytest.approx(0.1)
    assert got["flips"] == 2  # 0.35 in / 0.25 out, 0.69 in / 0.71 out; 0.8 out by both
    assert "flips" not in estimate_errors([0.4], [0.5], window=None)
    with pytest.raises(ValueError, match="differ in shape"):
        estimate_errors([0.4, 0.5], [0.5])


@pytest.fixture(scope="module")
def small_cohort():
    return sk.generate_cohort(3, sk.CohortModel(n_participants=2, n_trials=15))


@pytest.mark.parametrize("written", [False, True])  # True: through the CSV writer (t rounded to 0.1 ms)
def test_last_sample_with_the_quadratic_is_the_feature_tables_contact_speed(small_cohort, written, tmp_path):
    rec = small_cohort.recordings
    if written:
        rec = sk.read_recordings(sk.write_recordings(small_cohort.frame, tmp_path / "cohort.csv"))
    f = trial_features(rec)
    got = contact_speed_estimates(rec, f, method="last-sample", degree=2, n_fit=3)
    assert got[["participant", "trial"]].equals(f[["participant", "trial"]])
    np.testing.assert_allclose(got["contact_speed"], f["contact_speed"], rtol=1e-9)
    assert (got["t_contact"] < f["t_contact"]).all()  # the last sample, before the first contact sample


def test_the_crossing_lands_in_the_last_interval_and_nearer_the_truth_on_a_cohort(small_cohort):
    rec = small_cohort.recordings
    f = trial_features(rec)
    got = contact_speed_estimates(rec, f)
    dt = 1 / rec.fs
    assert ((got["t_contact"] >= f["t_contact"] - dt - 1e-9) & (got["t_contact"] <= f["t_contact"] + 1e-9)).all()
    truth = small_cohort.truth
    t_err = np.abs(got["t_contact"].to_numpy() - truth["t_contact"].to_numpy())
    assert np.median(t_err) < dt / 4  # the instant, to well inside the interval
    old = estimate_errors(f["contact_speed"], truth["contact_speed"])
    new = estimate_errors(got["contact_speed"], truth["contact_speed"])
    assert new["RMSE"] < old["RMSE"] and abs(new["bias"]) < abs(old["bias"])


def test_trial_features_uses_the_estimator_only_when_asked(small_cohort):
    rec = small_cohort.recordings
    default = trial_features(rec)
    assert default.attrs["contact_estimator"] == "last-sample"
    crossing = trial_features(rec, contact_estimator="crossing", window=(0.3, 0.7))
    est = contact_speed_estimates(rec, default, method="crossing")
    np.testing.assert_allclose(crossing["contact_speed"], est["contact_speed"], rtol=1e-12)
    inside = crossing["contact_speed"].between(0.3, 0.7)
    assert ((crossing["status"] == "selected") == inside).all()
    assert crossing.attrs["contact_estimator"] == "crossing"
    pd.testing.assert_frame_equal(
        crossing.drop(columns=["contact_speed", "status", "reason"]),
        default.drop(columns=["contact_speed", "status", "reason"]),
    )  # only the contact speed and what it decides change
    with pytest.raises(ValueError, match="unknown contact_estimator"):
        trial_features(rec, contact_estimator="spline")


@pytest.mark.parametrize(("method", "degree", "n_fit", "gain"), [("last-sample", 2, 3, 2.55), ("midpoint", 3, 4, 7.69)])
def test_position_noise_reaches_the_speed_as_the_module_docstring_says(method, degree, n_fit, gain):
    sigma, rng = 1e-5, np.random.default_rng(0)  # m; seeded
    t = np.arange(10) / FS
    clean = np.column_stack([np.zeros(10), 0.2 - 0.5 * t, np.zeros(10)])  # 0.5 m/s down, contact at t[6]
    speeds = [
        contact_speed_at(
            t, clean + rng.normal(0, sigma, clean.shape), 6, fs=FS, method=method, degree=degree, n_fit=n_fit
        ).speed
        for _ in range(4000)
    ]
    assert np.mean(speeds) == pytest.approx(0.5, abs=1e-3)
    assert np.std(speeds) / (sigma * FS) == pytest.approx(gain, rel=0.05)


def test_a_trial_the_estimator_cannot_estimate_becomes_invalid_with_the_reason(small_cohort, monkeypatch):
    import skilllib.features._table as table

    real = table.contact_speed_estimates

    def one_fails(*args, **kwargs):  # the first trial cannot be estimated (as "no motion" would say)
        out = real(*args, **kwargs)
        out.loc[0, ["contact_speed", "t_contact", "reason"]] = [np.nan, np.nan, "no motion at the last sample"]
        return out

    monkeypatch.setattr(table, "contact_speed_estimates", one_fails)
    rec = small_cohort.recordings
    got = trial_features(rec, window=None, contact_estimator="crossing")
    assert got.loc[0, "status"] == "invalid" and got.loc[0, "reason"] == "contact speed: no motion at the last sample"
    assert got.loc[0, ["pv", "contact_speed", "sparc", "t_contact"]].isna().all()
    assert pd.isna(got.loc[0, "n"]) and pd.isna(got.loc[0, "sparc_capped"])
    assert (got.loc[1:, "status"] == "selected").all()  # the others untouched
