"""skilllib/recordings/_defects.py: real-data defects found, repaired, counted and said, per trial."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import skilllib as sk
from skilllib.datasets import cohort_path
from skilllib.recordings import frozen_samples, jump_samples, recordings_from_frame, repair_trial, stale_leading

KINESIS = Path(__file__).resolve().parents[2] / "data" / "real" / "kinesis_rtgData.txt"
FS = 100.0


def reach(seed: int = 0, noise: float = 1e-4, fs: float = FS) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A minimum-jerk reach of 0.3 m in 0.8 s after 1 s of rest, then 0.5 s of hold in contact; t (s), pos
    (m) with Gaussian noise of ``noise`` m, contact (bool)."""
    rng = np.random.default_rng(seed)
    t = np.arange(0, 2.3, 1 / fs)
    s = np.clip((t - 1.0) / 0.8, 0, 1)
    x = 0.3 * (10 * s**3 - 15 * s**4 + 6 * s**5)
    pos = np.column_stack([x, 0.1 * x, np.zeros_like(x)]) + rng.normal(0, noise, (len(t), 3))
    return t, pos, t >= 1.8


def frame_of(t, pos, contact, trial="1") -> pd.DataFrame:
    return pd.DataFrame(
        {
            "participant": "P1",
            "trial": trial,
            "t": t,
            "x": pos[:, 0],
            "y": pos[:, 1],
            "z": pos[:, 2],
            "contact": contact.astype(int),
        }
    )


# --- clean trials are never touched --------------------------------------------------------------------


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**31), noise=st.sampled_from([0.0, 1e-5, 1e-4, 5e-4]), fs=st.sampled_from([60.0, 100.0, 250.0])
)
def test_a_clean_smooth_trial_with_noise_is_never_repaired(seed, noise, fs):
    t, pos, c = reach(seed, noise, fs)
    pos = np.round(pos, 5)  # written to 0.01 mm, as the writer does: exact repeats at rest
    r = repair_trial(t, pos, c)
    assert not r.changed and r.describe() == ""
    assert np.array_equal(r.pos, pos) and np.array_equal(r.t, t)


def test_no_rule_fires_on_the_synthetic_cohort():
    rec = sk.load_recordings(cohort_path())
    assert (rec.trials["repairs"] == "").all() and (rec.trials["n_repaired"] == 0).all()
    assert (rec.trials["n_dropped"] == 0).all() and not rec._repaired


# --- single-frame jumps ----------------------------------------------------------------------------------


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**31),
    k=st.integers(5, 224),
    size=st.floats(0.012, 0.2),  # at 100 Hz, 200 m/s^2 is a deviation of 10 mm
    direction=st.sampled_from([(1, 0, 0), (0, 1, 0), (0, 0, 1), (0.6, 0.8, 0)]),
)
def test_a_planted_jump_beyond_the_acceleration_limit_is_found_and_replaced_within_noise(seed, k, size, direction):
    t, truth, c = reach(seed, noise=0.0)
    pos = truth + np.random.default_rng(seed).normal(0, 1e-4, truth.shape)
    pos[k] += size * np.asarray(direction)
    assert jump_samples(t, pos).tolist() == [i == k for i in range(len(t))]
    r = repair_trial(t, pos, c)
    assert r.n_jumps == 1 and r.repaired.sum() == 1 and r.repaired[k]
    assert np.linalg.norm(r.pos[k] - truth[k]) < 1e-3  # within noise (0.1 mm) of the truth
    assert "1 jump replaced by interpolation" in r.describe()


def test_a_jump_inflates_pv_until_repaired():
    t, pos, c = reach(3)
    k = 130  # at peak speed, 1.3 s
    bad = pos.copy()
    bad[k, 0] += 0.02
    for p, expect_repair in ((pos, False), (bad, True)):
        rec = recordings_from_frame(frame_of(t, p, c))
        assert bool(rec.trials["repairs"][0]) == expect_repair
        f = sk.trial_features(rec, lowpass="none")
        assert f["pv"][0] == pytest.approx(0.3 * 1.875 / 0.8, rel=0.03)  # min-jerk peak speed, x and 0.1 x
    assert (
        sk.trial_features(recordings_from_frame(frame_of(t, bad, c), max_gap_s=0.0), lowpass="none")["status"][0]
        == "invalid"
    )  # with no filling, the jump is a gap in the analysed part


# --- frozen positions ------------------------------------------------------------------------------------


def test_frozen_positions_while_moving_are_replaced_and_at_rest_left():
    t, pos, c = reach(1)
    pos[120:125] = pos[119]  # frozen for 5 samples during the reach
    pos[30:33] = pos[29]  # exact repeats at rest: a quantised tracker may do that
    frozen = frozen_samples(t, pos)
    assert np.flatnonzero(frozen).tolist() == [120, 121, 122, 123, 124]
    r = repair_trial(t, pos, c)
    assert r.n_frozen == 5 and np.flatnonzero(r.repaired).tolist() == [120, 121, 122, 123, 124]
    truth = reach(1, noise=0.0)[1]
    assert np.abs(r.pos[120:125] - truth[120:125]).max() < 1e-3
    assert r.describe() == "5 frozen samples replaced by interpolation"


def test_a_long_frozen_run_before_contact_invalidates_and_after_contact_cuts():
    t, pos, c = reach(2)
    long_ = pos.copy()
    long_[110:130] = long_[109]  # 0.2 s frozen in the reach
    r = repair_trial(t, long_, c)
    assert r.reason.startswith("positions frozen (exactly repeated) at sample 111: a gap of 20 samples (0.200 s)")
    moved = pos.copy()
    moved[200:215] = moved[199] + np.array([0.01, 0, 0])  # frozen in the hold, after a step: the hand moved
    moved[200] = moved[199] + np.array([0.005, 0, 0])
    r = repair_trial(t, moved, c)


# --- stale leading frames -------------------------------------------------------------------------------


def test_a_stale_first_frame_and_its_duplicate_are_dropped():
    t, pos, c = reach(4)
    pos[0] += np.array([0.03, -0.04, 0.0])  # 50 mm away
    pos[1] = pos[2]  # the second repeats the third
    assert stale_leading(t, pos) == (1, 1)
    r = repair_trial(t, pos, c)
    assert r.n_stale == 1 and r.n_duplicate == 1 and len(r.t) == len(t) - 2 and r.t[0] == t[2]
    assert r.describe() == "1 stale leading frame and 1 duplicated leading frame dropped"
    f = sk.trial_features(recordings_from_frame(frame_of(t, pos, c)), lowpass="none")
    assert f["status"][0] == "selected" or "started before the recording" not in f["reason"][0]


def test_a_trial_that_starts_moving_keeps_its_first_frame():
    t, pos, c = reach(5)
    t, pos, c = t[105:], pos[105:], c[105:]  # starts during the reach
    assert stale_leading(t, pos) == (0, 0)


# --- NaN gaps -----------------------------------------------------------------------------------------


def test_gaps_short_filled_long_before_contact_invalid_after_contact_cut_ends_trimmed():
    t, truth, c = reach(6, noise=0.0)
    pos = truth.copy()
    pos[125:129] = np.nan  # 4 samples: filled
    pos[:3] = np.nan  # leading: trimmed
    pos[-2:] = np.nan  # trailing: trimmed
    r = repair_trial(t, pos, c)
    assert r.n_missing == 4 and r.n_trimmed == 5 and not r.reason
    assert np.abs(r.pos[122:126] - truth[125:129]).max() < 2e-4  # cubic through a smooth reach
    assert r.describe() == (
        "5 samples without a position trimmed at the ends; 4 missing samples replaced by interpolation; "
        "gap of 4 samples filled at 1.250 s (sample 126)"
    )
    lin = repair_trial(t, pos, c, fill="linear")
    assert np.abs(lin.pos[122:126] - truth[125:129]).max() > np.abs(r.pos[122:126] - truth[125:129]).max()
    long_before = truth.copy()
    long_before[120:140, 1] = np.nan
    r = repair_trial(t, long_before, c)
    assert r.reason.startswith("y is missing (NaN) at sample 121: a gap of 20 samples (0.200 s) before contact")
    assert repair_trial(t, long_before, c, max_gap_s=0.25).reason == ""
    after = truth.copy()
    after[200:220] = np.nan  # in the hold, after contact at 1.8 s
    r = repair_trial(t, after, c)
    assert not r.reason and len(r.t) == 200 and r.n_cut == 30
    assert r.describe() == "30 samples from a long gap after contact on cut off"
    rest = truth.copy()
    rest[20:40] = np.nan  # during the rest before the movement: the trial starts after it
    r = repair_trial(t, rest, c)
    assert not r.reason and r.n_rest_dropped == 40 and r.t[0] == t[40]


def test_recordings_report_repairs_and_the_mask_is_aligned():
    t, pos, c = reach(7)
    bad = pos.copy()
    bad[0] += 0.05
    bad[125:128] = np.nan
    df = pd.concat([frame_of(t, pos, c, "1"), frame_of(t, bad, c, "2")], ignore_index=True)
    rec = recordings_from_frame(df)
    tr = rec.trials.set_index("trial")
    assert tr.loc["1", "repairs"] == "" and tr.loc["2", "status"] == "ok"
    assert tr.loc["2", "repairs"] == (
        "1 stale leading frame dropped; 3 missing samples replaced by interpolation; "
        "gap of 3 samples filled at 1.250 s (row 355)"
    )
    assert tr.loc["2", "n_repaired"] == 3 and tr.loc["2", "n_dropped"] == 1
    mask = rec.repaired_mask("P1", "2")
    assert mask.shape == rec.trial("P1", "2").t.shape and np.flatnonzero(mask).tolist() == [124, 125, 126]
    assert not rec.repaired_mask("P1", "1").any() and not rec.is_repaired("P1", "1") and rec.is_repaired("P1", "2")
    assert np.isfinite(rec.trial("P1", "2").pos).all()
    f = sk.trial_features(rec, lowpass="none")
    assert f["repairs"].tolist() == ["", tr.loc["2", "repairs"]] and f["n_repaired"].tolist() == [0, 3]


# --- the real file ------------------------------------------------------------------------------------


def kinesis(contact: bool = True) -> pd.DataFrame:
    """The kinesis Optotrak export (tab-separated, ms and mm) as the book's long table; contact (the file
    has none) from the hold: the samples within 5 mm of the trial's 90th percentile height and above."""
    d = pd.read_csv(KINESIS, sep="\t")
    out = pd.DataFrame(
        {
            "participant": d["subjName"].astype(str),
            "trial": d["trialN"].astype(str),
            "t": d["globalTime"] / 1000,  # `time` is not monotonic within a trial; globalTime is (README)
            "x": d["indexXraw"] / 1000,
            "y": d["indexYraw"] / 1000,
            "z": d["indexZraw"] / 1000,
            "contact": 0,
        }
    )
    if contact:
        top = out.groupby("trial", sort=False)["y"].transform(lambda y: np.percentile(y, 90))
        out["contact"] = (out["y"] >= top - 0.005).astype(int)
    return out


@pytest.mark.skipif(not KINESIS.exists(), reason="real fixture missing")
def test_kinesis_stale_first_frames_found_and_no_longer_lost_for_them():
    rec = recordings_from_frame(kinesis())
    stale = rec.trials["repairs"].str.contains("stale leading frame")
    assert len(rec) == 45 and stale.sum() == 44  # trial 42's first step (5 mm, slow) is within its drift
    t, pos, contact = rec.arrays()
    started = "started before the recording"
    before = after = 0
    for (p, tr), r in zip(rec.keys(), [rec._rows[k] for k in rec.keys()]):
        raw = sk.segment_arrays(t[r], pos[r], contact[r], rec.fs)  # the samples as recorded
        d = rec.trial(p, tr)
        fixed = sk.segment_arrays(d.t, d.pos, d.contact, rec.fs)
        before += isinstance(raw, str) and started in raw
        after += isinstance(fixed, str) and started in fixed
    # as recorded all 45 start "moving"; after, 11 remain: a slow start (trials 19, 21, 42) or unfiltered noise of
    # 0.05-0.06 m/s at the first sample (not a stale frame)
    assert before == 45 and after <= 12, (before, after)


def test_a_spike_between_still_samples_is_a_jump_not_a_freeze():
    """A noise-free hand at rest (exact repeats) with one sample 1 m off: the spike is the jump; the still
    samples around it are not frozen (the speed across them is measured without the spike; catches the
    frozen rule reading the spike as motion and invalidating a sound trial)."""
    t = np.arange(60) / 60.0
    pos = np.zeros((60, 3))
    pos[30, 1] = 1.0
    r = repair_trial(t, pos, np.zeros(60, bool))
    assert r.reason == "" and r.n_jumps == 1 and r.n_frozen == 0
    assert np.flatnonzero(r.repaired).tolist() == [30] and np.allclose(r.pos, 0.0)


def test_a_whole_body_recording_of_known_unit_is_repaired_and_kept():
    """An overground walk spanning 4 m in metres with one missing sample: with the unit stated
    (``--units m``) the gap is filled and the trial kept; with nothing stating the unit the span reads as
    'not metres' and nothing is repaired (catches the 2 m plausibility limit applied to a known unit)."""
    t = np.arange(300) / 100.0
    x = 1.3 * t + 0.02 * np.sin(2 * np.pi * t)  # 1.3 m/s: 3.9 m in 3 s
    pos = np.column_stack([x, 0.9 + 0.03 * np.sin(4 * np.pi * t), 0.1 * np.ones_like(t)])
    pos[150, 0] = np.nan
    df = frame_of(t, pos, t >= 2.5, "walk")
    known = sk.load_recordings(df, units="m")
    assert known.trials.status.iloc[0] == "ok" and known.trials.n_repaired.iloc[0] == 1
    unknown = recordings_from_frame(df)
    assert unknown.trials.status.iloc[0] == "invalid" and unknown.trials.repairs.iloc[0] == ""


def test_a_marker_frozen_at_rest_that_jumps_when_it_comes_back_is_frozen():
    """The Optotrak pattern (kinesis): the marker freezes while the hand is still, the hand moves off, and
    the tracker catches up with a jump; the repeats are frozen (the hand did not move into the run, but
    the step out of it is a jump far faster than the steps after it). A still hand whose samples repeat
    and then start moving smoothly is not (catches both the old rule and a rule without the jump)."""
    t, pos, c = reach(3)
    onset = int(np.searchsorted(t, 1.0))
    frozen = pos.copy()
    frozen[onset - 5 : onset + 25] = frozen[onset - 5]  # frozen from rest well into the movement
    assert np.flatnonzero(frozen_samples(t, frozen)).tolist() == list(range(onset - 4, onset + 25))
    still = pos.copy()
    still[: onset - 2] = still[0]  # a noise-free still hand, then the movement starts smoothly
    assert not frozen_samples(t, still).any()
