"""Tests of skilllib.features: speed, onset/contact segmentation, per-trial features, selection."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from monalysa.quality.smoothness import log_dimensionless_jerk as ldlj_authors
from monalysa.quality.smoothness import sparc as sparc_authors

from skilllib.features import (
    CONTACT_WINDOW,
    DIFF_SPAN_S,
    FEATURE_COLUMNS,
    MIN_SEGMENT_SAMPLES,
    ONSET_SPEED,
    SPARC_PARAMS,
    diff_window,
    participant_summary,
    segment,
    segment_arrays,
    select,
    status_counts,
    trial_features,
    velocity,
)
from skilllib.features import _segmentation as kinematics
from skilllib.recordings import recordings_from_frame

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
        parts.append(
            pd.DataFrame(
                {
                    "participant": p,
                    "trial": tr,
                    "t": t,
                    "x": pos[:, 0],
                    "y": pos[:, 1],
                    "z": pos[:, 2],
                    "contact": c.astype(int),
                }
            )
        )
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
    np.testing.assert_allclose(velocity(pos, FS), np.gradient(pos, 1 / FS, axis=0, edge_order=2), rtol=0, atol=1e-12)


@pytest.mark.parametrize("fs", [30.0, 120.0, 500.0, 1000.0])
def test_velocity_is_exact_for_quadratic_motion_at_any_rate(fs):
    t = np.arange(int(0.4 * fs)) / fs
    pos = np.column_stack([0.3 * t, -2.0 * t**2, 0 * t])
    np.testing.assert_allclose(velocity(pos, fs)[:, 1], -4.0 * t, atol=1e-9)


def nearest_odd_window(fs: float) -> int:
    """The odd window (at least 3 samples) whose span (w - 1) / fs is nearest DIFF_SPAN_S, by search."""
    ws = np.arange(1, 2001, 2)
    return max(3, int(ws[np.argmin(np.abs((ws - 1) / fs - DIFF_SPAN_S))]))


def window_edges() -> list[float]:
    """Rates at which the nearest odd window steps from 2k - 1 to 2k + 1 samples: (2k - 1) / DIFF_SPAN_S
    (k = 1: 30 Hz, where the minimum of 3 samples keeps it at 3)."""
    return [(2 * k - 1) / DIFF_SPAN_S for k in (1, 2, 3, 4, 17)]


def test_differentiating_window_spans_the_same_time_at_every_rate():
    assert diff_window(60.0) == 3  # the experiment's rate: the three-point difference
    for fs in (20.0, 60.0, 120.0, 250.0, 1000.0):
        assert diff_window(fs) == nearest_odd_window(fs), fs


@pytest.mark.parametrize("edge", window_edges())
def test_differentiating_window_at_both_sides_of_each_step(edge):
    """Just below a step the window is the smaller odd size, just above the next one (a minimum of 3
    at 30 Hz). Catches floor/ceil for round, a span other than DIFF_SPAN_S, a dropped minimum."""
    below, above = diff_window(edge * (1 - 1e-6)), diff_window(edge * (1 + 1e-6))
    assert (below, above) == (nearest_odd_window(edge * (1 - 1e-6)), nearest_odd_window(edge * (1 + 1e-6)))
    assert above == (3 if edge * DIFF_SPAN_S < 2 else below + 2)


@pytest.mark.parametrize("edge", window_edges()[1:3])
@pytest.mark.parametrize("side", [1 - 1e-6, 1 + 1e-6], ids=["below", "above"])
def test_velocity_uses_the_window_of_its_rate(edge, side):
    """The error of a quadratic Savitzky-Golay derivative of t**3 over 2m + 1 samples is
    h**2 sum(k**4) / sum(k**2) (h = 1/fs, k = -m..m): it tells the window velocity() really used.
    Catches velocity() ignoring diff_window (a fixed three-point difference)."""
    fs = edge * side
    t = np.arange(60) / fs
    pos = np.column_stack([0 * t, t**3, 0 * t])
    err = velocity(pos, fs)[30, 1] - 3 * t[30] ** 2
    k = np.arange(-(nearest_odd_window(fs) // 2), nearest_odd_window(fs) // 2 + 1)
    assert err == pytest.approx(np.sum(k**4) / np.sum(k**2) / fs**2, rel=1e-6)


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


@pytest.mark.parametrize(
    "make, reason",
    [
        (lambda: approach(amp=0.10, surface=0.2), "no contact"),
        (lambda: (lambda t, p, c: (t, p, np.ones_like(c)))(*approach()), "in contact from sample 1"),
        (lambda: approach(amp=0.15, surface=0.008), "too short: 3 samples"),
        (lambda: approach(amp=0.002, dur=1.0, surface=0.0019), "no onset"),
        (lambda: approach(rest=-0.2), "no rest before onset"),
    ],
)
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
    df.loc[df.index[(df.participant == 1) & (df.trial == 1)][-3:], "contact"] = 1  # ints here: a DataFrame
    bad = frame_of({(2, 1): approach()})
    bad.loc[5, "x"] = np.inf  # data-level invalid (a NaN would be a gap, filled)
    f = trial_features(recordings_from_frame(pd.concat([df, bad], ignore_index=True)))
    bad_row = len(df) + 5
    assert list(f.columns) == list(FEATURE_COLUMNS)
    assert f[["participant", "trial"]].apply(tuple, axis=1).tolist() == [
        ("1", "1"),
        ("1", "2"),
        ("1", "3"),
        ("1", "4"),
        ("2", "1"),
    ]
    assert f.status.tolist() == ["selected", "excluded", "excluded", "invalid", "invalid"]
    assert f.reason[0] == ""
    assert f.reason[1].startswith("contact speed") and "above 0.7 m/s" in f.reason[1]
    assert "below 0.3 m/s" in f.reason[2]
    assert f.reason[3].startswith("no contact") and f.reason[4] == f"x is infinite at row {bad_row}"
    num = ["pv", "contact_speed", "duration", "sparc", "ldlj"]
    assert f.loc[f.status != "invalid", num].notna().all().all()
    assert f.loc[f.status == "invalid", num].isna().all().all()
    assert len(select(f)) == 1 and (select(f).status == "selected").all()


def test_window_edges_are_inclusive_and_the_next_float_out_is_excluded():
    """A contact speed exactly on an edge is selected, the window one float narrower excludes it
    (catches ``<=``/``>=`` for ``<``/``>`` in the window test)."""
    df = frame_of({(1, 1): approach()})
    v = trial_features(recordings_from_frame(df)).contact_speed[0]
    lo, hi = CONTACT_WINDOW
    assert trial_features(recordings_from_frame(df), window=(v, hi)).status[0] == "selected"
    assert trial_features(recordings_from_frame(df), window=(lo, v)).status[0] == "selected"
    out = trial_features(recordings_from_frame(df), window=(np.nextafter(v, np.inf), hi))
    assert out.status[0] == "excluded" and out.reason[0].startswith(f"contact speed {v:.3f} m/s below")
    out = trial_features(recordings_from_frame(df), window=(lo, np.nextafter(v, -np.inf)))
    assert out.status[0] == "excluded" and out.reason[0].startswith(f"contact speed {v:.3f} m/s above")


def test_paper_and_documented_constants():
    """The paper's selection (0.3-0.7 m/s) and onset threshold (0.05 m/s), and the values the module
    docstring and chapter 3 state (a 2/60 s differentiating span, segments of at least 5 samples):
    the threshold tests use the constants, so only this catches a changed value."""
    assert CONTACT_WINDOW == (0.3, 0.7) and ONSET_SPEED == 0.05
    assert DIFF_SPAN_S == 2 / 60 and MIN_SEGMENT_SAMPLES == 5


@pytest.mark.parametrize("edge", [0, 1], ids=["lower", "upper"])
@pytest.mark.parametrize("inside", [True, False], ids=["inside", "outside"])
def test_default_window_is_contact_window(edge, inside):
    """With the default window, a trial whose contact speed lies 1e-6 inside an edge of CONTACT_WINDOW
    is selected and 1e-6 outside excluded: trial_features selects with the constant (positions scaled
    about the start scale the speed)."""
    t, pos, c = approach()
    v = trial_features(recordings_from_frame(frame_of({(1, 1): (t, pos, c)}))).contact_speed[0]
    inward = 1e-6 if edge == 0 else -1e-6
    target = CONTACT_WINDOW[edge] * (1 + (inward if inside else -inward))
    f = trial_features(recordings_from_frame(frame_of({(1, 1): (t, pos[0] + (pos - pos[0]) * (target / v), c)})))
    assert f.contact_speed[0] == pytest.approx(target, rel=1e-9)
    assert f.status[0] == ("selected" if inside else "excluded")


def test_features_match_an_independent_computation():
    """Every feature against values computed without skilllib: the speed by numpy's second-order
    difference over the samples before contact, onset by the paper's rule, SPARC and LDLJ by the
    authors' code (monalysa). ``segment`` gives the same segment."""
    t, pos, c = approach()
    rec = recordings_from_frame(frame_of({(3, 7): (t, pos, c)}))
    f = trial_features(rec).iloc[0]
    ci = int(np.flatnonzero(c)[0])
    speed = np.linalg.norm(np.gradient(pos[:ci], 1 / FS, axis=0, edge_order=2), axis=1)
    o = int(np.flatnonzero(speed > ONSET_SPEED)[0])
    v = speed[o:]
    assert (f.n, f.t_onset, f.t_contact) == (ci - o, t[o], t[ci])
    assert f.pv == pytest.approx(v.max(), rel=1e-9) and f.contact_speed == pytest.approx(v[-1], rel=1e-9)
    assert f.duration == pytest.approx((ci - o) / FS, rel=1e-9)
    p = SPARC_PARAMS
    assert f.sparc == pytest.approx(
        sparc_authors(v, FS, padlevel=p["padlevel"], fc=p["fc"], amp_th=p["amp_th"])[0], abs=1e-9
    )
    assert f.ldlj == pytest.approx(ldlj_authors(v, FS), abs=1e-9)
    seg = segment(rec, 3, 7)
    assert (seg.onset, seg.contact) == (o, ci)
    np.testing.assert_allclose(seg.speed, v, rtol=1e-9)


def test_peak_speed_of_a_minimum_jerk_approach():
    """Cut at 95 % of its amplitude, a 0.15 m / 0.5 s minimum-jerk drop peaks at 1.875 D / T."""
    f = trial_features(recordings_from_frame(frame_of({(1, 1): approach(amp=0.15, dur=0.5, surface=0.1425)}))).iloc[0]
    assert f.pv == pytest.approx(1.875 * 0.15 / 0.5, rel=0.01)


def test_segment_of_an_invalid_or_unknown_trial_raises():
    rec = recordings_from_frame(frame_of({(1, 1): approach(amp=0.10, surface=0.2)}))
    with pytest.raises(ValueError, match="cannot be segmented: no contact"):
        segment(rec, 1, 1)
    with pytest.raises(KeyError):
        segment(rec, 1, 2)


def test_summaries_count_every_trial():
    trials = {(p, tr): approach(amp=0.13 + 0.02 * tr) for p in (1, 2) for tr in range(1, 5)}
    f = trial_features(recordings_from_frame(frame_of(trials)))
    counts = status_counts(f)
    assert counts.loc["all", "total"] == 8 and counts.loc["1", "total"] == 4
    summ = participant_summary(f)
    assert summ["valid trials"].tolist() == [4, 4]
    assert summ["selected"].sum() == counts.loc["all", "selected"]


@settings(max_examples=30, deadline=None)
@given(
    shift=st.tuples(*[st.floats(-0.2, 0.2)] * 3),
    angle=st.floats(0, 2 * np.pi),
    t0=st.floats(0, 100),
    amp=st.floats(0.12, 0.3),
    dur=st.floats(0.3, 0.9),
)
def test_features_invariant_to_translation_rotation_and_time_origin(shift, angle, t0, amp, dur):
    """Speed-based features do not depend on the frame's origin, a rotation about the vertical or the
    time origin (only t_onset / t_contact move with it)."""
    t, pos, c = approach(amp=amp, dur=dur)
    rot = np.array([[np.cos(angle), 0, -np.sin(angle)], [0, 1, 0], [np.sin(angle), 0, np.cos(angle)]])
    a = trial_features(recordings_from_frame(frame_of({(1, 1): (t, pos, c)}))).iloc[0]
    b = trial_features(recordings_from_frame(frame_of({(1, 1): (t + t0, pos @ rot.T + np.array(shift), c)}))).iloc[0]
    assert a.status == b.status
    for col in ["pv", "contact_speed", "duration", "sparc", "ldlj"]:
        assert b[col] == pytest.approx(a[col], rel=1e-6, abs=1e-9), col
    assert b.t_onset - a.t_onset == pytest.approx(t0, abs=1e-6)


# --- segmentation thresholds at both sides of their edge -------------------------------------------


def ramp(n=30, start=10, u=0.5, fs=FS):
    """Rest at y = 0 up to sample ``start`` - 1, then y falls at ``u`` m/s: the second-order difference
    gives speed 0 before ``start`` - 1, u / 2 at ``start`` - 1 (central difference across the start),
    so with u / 2 > ONSET_SPEED the onset is sample ``start`` - 1."""
    t = np.arange(n) / fs
    y = -np.maximum(np.arange(n) - (start - 1), 0) * u / fs
    return t, np.column_stack([np.zeros(n), 0.2 + y, np.zeros(n)])


@pytest.mark.parametrize("n", [MIN_SEGMENT_SAMPLES - 1, MIN_SEGMENT_SAMPLES])
def test_min_segment_samples_at_both_sides_of_the_edge(n):
    """Exactly MIN_SEGMENT_SAMPLES samples from onset to contact is a segment, one fewer 'too short',
    in segment_arrays and trial_features (their defaults). Catches ``<=`` for ``<``, an off-by-one in
    n = contact - onset and a default other than the constant."""
    t, pos = ramp()
    onset = 9
    contact = np.arange(len(t)) >= onset + n
    seg = segment_arrays(t, pos, contact, FS)
    f = trial_features(recordings_from_frame(frame_of({(1, 1): (t, pos, contact)}))).iloc[0]
    if n < MIN_SEGMENT_SAMPLES:
        reason = f"too short: {n} samples from onset to contact (need at least {MIN_SEGMENT_SAMPLES})"
        assert seg == reason and (f.status, f.reason) == ("invalid", reason)
    else:
        assert (seg.onset, seg.contact, len(seg.speed)) == (onset, onset + n, n)
        assert f.status != "invalid" and f.n == n and f.t_onset == t[onset]


def test_onset_speed_exactly_at_the_threshold_does_not_start_the_movement(monkeypatch):
    """Onset is the first speed strictly above ONSET_SPEED: speeds equal to it (here at the first
    sample, too) neither start the movement nor count as 'no rest before onset'. velocity() is replaced
    by a profile of exact speeds, since a derivative never lands exactly on 0.05. Catches ``>=``."""
    above = np.nextafter(ONSET_SPEED, np.inf)
    speeds = np.array([ONSET_SPEED, 0.0, ONSET_SPEED, ONSET_SPEED, above, 0.2, 0.4, 0.5, 0.5, 0.45, 0.4, 0.4])
    monkeypatch.setattr(kinematics, "velocity", lambda p, fs: np.column_stack([0 * speeds, -speeds, 0 * speeds]))
    n = len(speeds)
    contact = np.arange(n + 3) >= n
    seg = segment_arrays(np.arange(n + 3) / FS, np.zeros((n + 3, 3)), contact, FS)
    assert not isinstance(seg, str), seg
    assert seg.onset == 4 and seg.speed[0] == above
    all_at = segment_arrays(
        np.arange(n + 3) / FS, np.zeros((n + 3, 3)), contact, FS, onset_speed=0.5
    )  # the maximum: nothing strictly above it
    assert all_at.startswith("no onset")


@pytest.mark.parametrize("inside", [False, True], ids=["below", "above"])
def test_onset_speed_with_the_real_derivative(inside):
    """End to end with the real velocity(): a speed 1e-6 below ONSET_SPEED at sample 9 leaves the onset
    at sample 10, 1e-6 above starts it at 9 (trial_features's default is the constant)."""
    t, pos = ramp()
    pos[10:, 1] += 0.5 / FS  # the ramp now starts at sample 10 ...
    a = ONSET_SPEED * (1 + (1e-6 if inside else -1e-6)) * 2 / FS  # ... after a first step of a
    pos[10:, 1] -= a  # central difference at sample 9: a * FS / 2
    contact = np.arange(len(t)) >= 25
    f = trial_features(recordings_from_frame(frame_of({(1, 1): (t, pos, contact)}))).iloc[0]
    assert f.t_onset == t[9 if inside else 10]


@pytest.mark.parametrize(
    "first_contact, reason",
    [
        (0, "in contact from sample 1: no approach recorded before contact"),
        (1, "in contact from sample 2: no approach recorded before contact"),
        (2, "no onset: speed stays below"),  # past the rule: two samples can be differentiated
    ],
)
def test_contact_from_the_first_or_second_sample(first_contact, reason):
    """Contact at sample index 0 or 1 leaves fewer than 2 samples to differentiate; at index 2 the
    approach is differentiated (at rest here: no onset). The 2 is a bare literal in segment_arrays.
    Catches ``c < 3`` (index 2 refused) and ``c < 1`` (velocity of one sample raises)."""
    n = 20
    contact = np.arange(n) >= first_contact
    out = segment_arrays(np.arange(n) / FS, np.zeros((n, 3)), contact, FS)
    assert isinstance(out, str) and out.startswith(reason), out


def test_tables_order_ids_naturally_and_keep_them_as_text():
    """'P2' before 'P10', '2' before '10'; '01' and '1' two participants (status_counts, participant_summary)."""
    trials = {(p, "1"): approach() for p in ("P10", "P2", "10", "2", "01", "1")}
    f = trial_features(recordings_from_frame(frame_of(trials)))
    assert status_counts(f).index.tolist() == ["01", "1", "2", "10", "P2", "P10", "all"]
    assert participant_summary(f).index.tolist() == ["01", "1", "2", "10", "P2", "P10"]
