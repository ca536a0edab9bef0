"""Tests of skilllib.features: speed, onset/contact segmentation, per-trial features, selection."""
from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from skilllib import smoothness
from skilllib.data import recordings_from_frame
from skilllib.features import (
    CONTACT_WINDOW, FEATURE_COLUMNS, ONSET_SPEED, SPARC_PARAMS, participant_summary, segment, segment_arrays,
    select, status_counts, trial_features, velocity, diff_window,
)

FS = 60.0


def approach(amp=0.15, dur=0.5, surface=0.12, rest=0.4, after=0.3, fs=FS, t0=0.0):
    """Rest, a minimum-jerk drop of ``amp`` m in ``dur`` s cut by a surface ``surface`` m below the start
    (the tip then rests there), sampled at ``fs``; returns t, pos (N, 3), contact (bool)."""
    t = np.arange(int((rest + dur + after) * fs)) / fs
    tau = np.clip((t - rest) / dur, 0, 1)
    drop = amp * tau**3 * (10 - 15 * tau + 6 * tau**2)
    contact = drop >= surface
    contact = np.cumsum(contact) > 0
    y = 0.2 - np.minimum(drop, surface)
    pos = np.column_stack([np.full_like(t, 0.01), y, np.full_like(t, -0.03)])
    return t0 + t, pos, contact


def frame_of(trials: dict) -> pd.DataFrame:
    """Long table from {(participant, trial): (t, pos, contact)}."""
    parts = []
    for (p, tr), (t, pos, c) in trials.items():
        parts.append(pd.DataFrame({"participant": p, "trial": tr, "t": t, "x": pos[:, 0], "y": pos[:, 1],
                                   "z": pos[:, 2], "contact": c.astype(int)}))
    return pd.concat(parts, ignore_index=True)


def test_velocity_is_exact_for_quadratic_motion():
    t = np.arange(20) / FS
    pos = np.column_stack([0.3 * t, -2.0 * t**2, 0 * t])
    v = velocity(pos, FS)
    np.testing.assert_allclose(v[:, 0], 0.3, atol=1e-12)
    np.testing.assert_allclose(v[:, 1], -4.0 * t, atol=1e-12)  # second order, ends included


@pytest.mark.parametrize("n", [3, 4, 7, 90])
def test_velocity_at_60_hz_is_the_second_order_finite_difference(n):
    pos = np.random.default_rng(n).normal(size=(n, 3)).cumsum(axis=0) * 1e-3
    np.testing.assert_allclose(velocity(pos, FS), np.gradient(pos, 1 / FS, axis=0, edge_order=2),
                               rtol=0, atol=1e-12)


@pytest.mark.parametrize("fs", [30.0, 120.0, 500.0, 1000.0])
def test_velocity_is_exact_for_quadratic_motion_at_any_rate(fs):
    t = np.arange(int(0.4 * fs)) / fs
    pos = np.column_stack([0.3 * t, -2.0 * t**2, 0 * t])
    np.testing.assert_allclose(velocity(pos, fs)[:, 1], -4.0 * t, atol=1e-9)


def test_differentiating_window_spans_the_same_time_at_every_rate():
    assert diff_window(60.0) == 3
    for fs in (120.0, 250.0, 1000.0):
        w = diff_window(fs)
        assert w % 2 == 1 and abs((w - 1) / fs - 2 / 60) <= 1 / fs


def test_speed_noise_does_not_grow_with_the_sampling_rate():
    """The same 0.03 mm position noise at rest gives about the same speed noise at 60 Hz and 1 kHz."""
    noise = {}
    for fs in (60.0, 1000.0):
        pos = np.random.default_rng(0).normal(0, 0.03e-3, size=(int(2 * fs), 3))
        noise[fs] = np.std(np.linalg.norm(velocity(pos, fs), axis=1))
    assert noise[1000.0] < 1.5 * noise[60.0]
    assert noise[1000.0] < ONSET_SPEED / 10


def test_a_1_khz_recording_is_segmented_like_the_60_hz_one():
    feats = {}
    for fs in (60.0, 1000.0):
        t, pos, contact = approach(fs=fs)
        pos = pos + np.random.default_rng(1).normal(0, 0.03e-3, pos.shape)
        seg = segment_arrays(t, pos, contact, fs)
        assert not isinstance(seg, str), seg
        feats[fs] = seg.speed.max()
    assert feats[1000.0] == pytest.approx(feats[60.0], rel=0.02)


def test_velocity_of_two_samples_is_their_difference_quotient():
    v = velocity(np.array([[0.0, 0.0, 0.0], [0.01, 0.0, 0.0]]), 100.0)
    np.testing.assert_allclose(v, [[1.0, 0, 0], [1.0, 0, 0]])


def test_velocity_needs_two_samples():
    with pytest.raises(ValueError, match="at least 2 samples"):
        velocity(np.zeros((1, 3)), FS)


def test_segment_runs_from_onset_to_the_last_sample_before_contact():
    t, pos, c = approach()
    seg = segment_arrays(t, pos, c, FS)
    cidx = int(np.flatnonzero(c)[0])
    speed = np.linalg.norm(np.gradient(pos[:cidx], 1 / FS, axis=0, edge_order=2), axis=1)
    onset = int(np.flatnonzero(speed > ONSET_SPEED)[0])
    assert (seg.onset, seg.contact) == (onset, cidx)
    assert len(seg.speed) == cidx - onset and seg.duration == pytest.approx((cidx - onset) / FS)
    np.testing.assert_allclose(seg.speed, speed[onset:])
    assert seg.pos.shape == seg.vel.shape == (cidx - onset, 3)
    assert seg.speed[-1] > 0.3  # contact with non-zero speed: the approach is cut, not ended


@pytest.mark.parametrize("make, reason", [
    (lambda: approach(amp=0.10, surface=0.2), "no contact"),
    (lambda: (lambda t, p, c: (t, p, np.ones_like(c)))(*approach()), "in contact from sample 1"),
    (lambda: approach(amp=0.15, surface=0.008), "too short: 3 samples"),
    (lambda: approach(amp=0.002, dur=1.0, surface=0.0019), "no onset"),
    (lambda: approach(rest=-0.2), "no rest before onset"),
])
def test_trials_that_cannot_be_segmented_give_a_reason(make, reason):
    out = segment_arrays(*make(), FS)
    assert isinstance(out, str) and out.startswith(reason), out


def test_every_trial_is_kept_with_status_and_reason():
    trials = {
        (1, 1): approach(),  # selected
        (1, 2): approach(amp=0.30, dur=0.3),  # fast: excluded above
        (1, 3): approach(amp=0.121, dur=0.8),  # slow contact: excluded below
        (1, 4): approach(amp=0.10, surface=0.2),  # no contact: invalid
    }
    df = frame_of(trials)
    df.loc[df.index[(df.participant == 1) & (df.trial == 1)][-3:], "contact"] = 1
    bad = frame_of({(2, 1): approach()})
    bad.loc[5, "x"] = np.nan  # data-level invalid
    f = trial_features(pd.concat([df, bad], ignore_index=True))
    bad_row = len(df) + 5
    assert list(f.columns) == list(FEATURE_COLUMNS)
    assert f[["participant", "trial"]].apply(tuple, axis=1).tolist() == [(1, 1), (1, 2), (1, 3), (1, 4), (2, 1)]
    assert f.status.tolist() == ["selected", "excluded", "excluded", "invalid", "invalid"]
    assert f.reason[0] == ""
    assert f.reason[1].startswith("contact speed") and "above 0.7 m/s" in f.reason[1]
    assert "below 0.3 m/s" in f.reason[2]
    assert f.reason[3].startswith("no contact") and f.reason[4] == f"x is missing (NaN) at row {bad_row}"
    num = ["pv", "contact_speed", "duration", "sparc", "ldlj"]
    assert f.loc[f.status != "invalid", num].notna().all().all()
    assert f.loc[f.status == "invalid", num].isna().all().all()
    assert len(select(f)) == 1 and (select(f).status == "selected").all()


def test_window_edges_are_inclusive():
    t, pos, c = approach()
    f = trial_features(frame_of({(1, 1): (t, pos, c)}))
    v = f.contact_speed[0]
    assert trial_features(frame_of({(1, 1): (t, pos, c)}), window=(v, 0.9)).status[0] == "selected"
    assert trial_features(frame_of({(1, 1): (t, pos, c)}), window=(0.1, v)).status[0] == "selected"
    assert CONTACT_WINDOW == (0.3, 0.7)


def test_features_match_the_smoothness_module_on_the_segment():
    t, pos, c = approach()
    rec = recordings_from_frame(frame_of({(3, 7): (t, pos, c)}))
    f = trial_features(rec).iloc[0]
    seg = segment(rec, 3, 7)
    assert f.pv == seg.speed.max() and f.contact_speed == seg.speed[-1]
    assert f.sparc == pytest.approx(smoothness.sparc(seg.speed, FS, **SPARC_PARAMS), abs=1e-9)
    assert f.ldlj == pytest.approx(smoothness.ldlj(seg.speed, FS), abs=1e-9)
    assert f.t_onset == t[seg.onset] and f.t_contact == t[seg.contact] and f.n == len(seg.speed)
    assert f.duration == pytest.approx(f.t_contact - f.t_onset)


def test_peak_speed_of_a_minimum_jerk_approach():
    """Cut at 95 % of its amplitude, a 0.15 m / 0.5 s minimum-jerk drop peaks at 1.875 D / T."""
    f = trial_features(frame_of({(1, 1): approach(amp=0.15, dur=0.5, surface=0.1425)})).iloc[0]
    assert f.pv == pytest.approx(1.875 * 0.15 / 0.5, rel=0.01)


def test_segment_of_an_invalid_or_unknown_trial_raises():
    rec = recordings_from_frame(frame_of({(1, 1): approach(amp=0.10, surface=0.2)}))
    with pytest.raises(ValueError, match="cannot be segmented: no contact"):
        segment(rec, 1, 1)
    with pytest.raises(KeyError):
        segment(rec, 1, 2)


def test_summaries_count_every_trial():
    trials = {(p, tr): approach(amp=0.13 + 0.02 * tr) for p in (1, 2) for tr in range(1, 5)}
    f = trial_features(frame_of(trials))
    counts = status_counts(f)
    assert counts.loc["all", "total"] == 8 and counts.loc[1, "total"] == 4
    summ = participant_summary(f)
    assert summ["valid trials"].tolist() == [4, 4]
    assert summ["selected"].sum() == counts.loc["all", "selected"]


@settings(max_examples=30, deadline=None)
@given(shift=st.tuples(*[st.floats(-0.2, 0.2)] * 3), angle=st.floats(0, 2 * np.pi),
       t0=st.floats(0, 100), amp=st.floats(0.12, 0.3), dur=st.floats(0.3, 0.9))
def test_features_invariant_to_translation_rotation_and_time_origin(shift, angle, t0, amp, dur):
    """Speed-based features do not depend on the frame's origin, a rotation about the vertical or the
    time origin (only t_onset / t_contact move with it)."""
    t, pos, c = approach(amp=amp, dur=dur)
    rot = np.array([[np.cos(angle), 0, -np.sin(angle)], [0, 1, 0], [np.sin(angle), 0, np.cos(angle)]])
    a = trial_features(frame_of({(1, 1): (t, pos, c)})).iloc[0]
    b = trial_features(frame_of({(1, 1): (t + t0, pos @ rot.T + np.array(shift), c)})).iloc[0]
    assert a.status == b.status
    for col in ["pv", "contact_speed", "duration", "sparc", "ldlj"]:
        assert b[col] == pytest.approx(a[col], rel=1e-6, abs=1e-9), col
    assert b.t_onset - a.t_onset == pytest.approx(t0, abs=1e-6)
