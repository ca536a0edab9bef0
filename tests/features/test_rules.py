"""The task's start and end rules in segmentation (skilllib/features/_rules.py, _segmentation.py): each rule
on small synthetic trials whose answer is known, every reason a rule gives when it cannot apply, the
paper's rules unchanged through trial_features, and the real forward reaches (UE-ADL) and reach-to-grasp
trials (kinesis) under a relative onset and offset.

The synthetic reach is a minimum-jerk movement (Flash & Hogan 1985) along the up axis at 100 Hz with rest
before and after: its speed ``v(tau) = A / D * 30 tau^2 (1 - tau)^2`` is known in closed form, so the
sample where it crosses a fraction of its peak is known.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import skilllib
from skilllib.datasets import cohort_path
from skilllib.features import (
    PAPER_END,
    PAPER_START,
    EndRule,
    SpeedThreshold,
    StartRule,
    parse_end,
    parse_start,
    path_length,
    peak_acceleration,
    segment,
    segment_arrays,
    segmentation_detail,
    trial_features,
)
from skilllib.features import _vectorised as batch
from skilllib.recordings import recordings_from_frame

FS = 100.0
REAL = Path(__file__).resolve().parents[2] / "data" / "real"
ADL = REAL / "ue-adl-forward-reach"


def min_jerk(
    amp: float = 0.3, dur: float = 1.0, rest_before: float = 1.0, rest_after: float = 1.0, y0: float = 0.5
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A minimum-jerk reach up the y axis (m) at FS: t (s), pos (N, 3) m, contact (all 0)."""
    n = int(round((rest_before + dur + rest_after) * FS)) + 1
    t = np.arange(n) / FS
    tau = np.clip((t - rest_before) / dur, 0, 1)
    y = y0 + amp * (10 * tau**3 - 15 * tau**4 + 6 * tau**5)
    pos = np.column_stack([np.full(n, 0.1), y, np.full(n, -0.2)])
    return t, pos, np.zeros(n, bool)


def analytic_speed(t: np.ndarray, amp: float = 0.3, dur: float = 1.0, rest_before: float = 1.0) -> np.ndarray:
    tau = np.clip((t - rest_before) / dur, 0, 1)
    return amp / dur * 30 * tau**2 * (1 - tau) ** 2


# --- speed start and offset end on the minimum-jerk reach ---------------------------------------------


@pytest.mark.parametrize("pct", [3, 5, 10])
def test_relative_onset_and_offset_land_where_the_analytic_speed_crosses(pct):
    """``speed:P%`` and ``offset:P%``: onset and end within one sample of the samples where the analytic
    speed first exceeds, and after the peak first falls to, P % of the peak."""
    t, pos, contact = min_jerk()
    seg = segment_arrays(t, pos, contact, FS, start=parse_start(f"speed:{pct}%"), end=parse_end(f"offset:{pct}%"))
    v = analytic_speed(t)
    thr = pct / 100 * v.max()
    want_on = int(np.flatnonzero(v > thr)[0])
    k = int(np.argmax(v))
    want_off = k + 1 + int(np.flatnonzero(v[k + 1 :] <= thr)[0])
    assert abs(seg.onset - want_on) <= 1 and abs(seg.contact - want_off) <= 1
    assert (
        seg.speed[-1]
        > seg.speed.max() * pct / 100
        >= np.linalg.norm(np.gradient(pos, 1 / FS, axis=0), axis=1)[seg.contact + 2]
    )  # the last sample of the segment is still above, the rest after the end below
    assert seg.duration == pytest.approx((seg.contact - seg.onset) / FS)
    assert seg.contact - seg.onset == len(seg.speed) == len(seg.t) == len(seg.pos)


def test_offset_without_a_threshold_takes_the_starts():
    t, pos, contact = min_jerk()
    for start in (parse_start("speed:0.05"), parse_start("speed:4%")):
        a = segment_arrays(t, pos, contact, FS, start=start, end=parse_end("offset"))
        b = segment_arrays(
            t, pos, contact, FS, start=start, end=EndRule("offset", threshold=start.threshold, hold_s=0.1)
        )
        assert (a.onset, a.contact) == (b.onset, b.contact)
        v = np.linalg.norm(np.gradient(pos, 1 / FS, axis=0), axis=1)
        assert a.contact > np.argmax(v)


def test_absolute_offset_threshold_in_m_per_s():
    t, pos, contact = min_jerk()
    seg = segment_arrays(t, pos, contact, FS, start=parse_start("speed:0.05"), end=parse_end("offset:0.2"))
    v = analytic_speed(t)
    k = int(np.argmax(v))
    assert abs(seg.contact - (k + 1 + int(np.flatnonzero(v[k + 1 :] <= 0.2)[0]))) <= 1


def two_reaches(pause_s: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Two minimum-jerk reaches of 0.6 s up the y axis with a pause of ``pause_s`` s between them."""
    t1, p1, _ = min_jerk(amp=0.2, dur=0.6, rest_before=0.5, rest_after=pause_s)
    _, p2, _ = min_jerk(amp=0.1, dur=0.6, rest_before=0.0, rest_after=0.5, y0=p1[-1, 1])
    pos = np.concatenate([p1, p2[1:]])
    t = np.arange(len(pos)) / FS
    return t, pos, np.zeros(len(t), bool)


def test_the_hold_decides_whether_a_pause_ends_the_movement():
    """A pause of 0.3 s between two reaches: a hold of 0.1 s ends at the pause; a hold of 0.5 s (longer
    than the pause) ends after the second reach; a hold of 0 at the first sample at or below."""
    t, pos, contact = two_reaches(0.3)
    start = parse_start("speed:0.05")
    first = segment_arrays(t, pos, contact, FS, start=start, end=parse_end("offset", hold_s=0.1))
    whole = segment_arrays(t, pos, contact, FS, start=start, end=parse_end("offset", hold_s=0.5))
    zero = segment_arrays(t, pos, contact, FS, start=start, end=parse_end("offset", hold_s=0.0))
    assert 0.5 * FS < first.contact < (0.5 + 0.6 + 0.3) * FS
    assert whole.contact > (0.5 + 0.6 + 0.3 + 0.3) * FS
    assert zero.contact == first.contact  # the pause holds for 0.1 s right away
    v = np.linalg.norm(np.gradient(pos, 1 / FS, axis=0), axis=1)
    assert (v[first.contact : first.contact + 11] <= 0.05 + 1e-9).all()


def test_a_stay_cut_short_by_the_recordings_end_ends_the_movement():
    """The speed falls below the threshold a few samples before the recording ends (hold 0.1 s = 10
    samples): the offset is there all the same."""
    t, pos, contact = min_jerk(rest_after=0.0)
    v = np.linalg.norm(np.gradient(pos, 1 / FS, axis=0), axis=1)
    seg = segment_arrays(t, pos, contact, FS, start=parse_start("speed:0.05"), end=parse_end("offset:0.01"))
    assert not isinstance(seg, str) and len(t) - seg.contact < 10
    assert seg.contact > np.argmax(v)


@settings(max_examples=40, deadline=None)
@given(
    amp=st.floats(0.05, 0.5),
    dur=st.floats(0.4, 1.5),
    rest_after=st.floats(0.3, 1.0),
    extra=st.integers(1, 200),
    pct=st.sampled_from([3, 5, 10]),
)
def test_the_offset_does_not_move_when_rest_is_appended(amp, dur, rest_after, extra, pct):
    """Rest samples appended after the end change neither onset nor end (nor the segment's speed)."""
    t, pos, contact = min_jerk(amp=amp, dur=dur, rest_before=0.5, rest_after=rest_after)
    rules = dict(start=parse_start(f"speed:{pct}%"), end=parse_end(f"offset:{pct}%"))
    a = segment_arrays(t, pos, contact, FS, **rules)
    more = np.concatenate([pos, np.repeat(pos[-1:], extra, axis=0)])
    b = segment_arrays(np.arange(len(more)) / FS, more, np.zeros(len(more), bool), FS, **rules)
    assert (a.onset, a.contact) == (b.onset, b.contact)
    np.testing.assert_allclose(a.speed, b.speed, rtol=0, atol=1e-12)


@settings(max_examples=30, deadline=None)
@given(amp=st.floats(0.05, 0.5), dur=st.floats(0.4, 1.5), shift=st.integers(1, 100))
def test_onset_and_end_shift_with_rest_prepended(amp, dur, shift):
    t, pos, contact = min_jerk(amp=amp, dur=dur, rest_before=0.5, rest_after=0.5)
    rules = dict(start=parse_start("speed:5%"), end=parse_end("offset:5%"))
    a = segment_arrays(t, pos, contact, FS, **rules)
    more = np.concatenate([np.repeat(pos[:1], shift, axis=0), pos])
    b = segment_arrays(np.arange(len(more)) / FS, more, np.zeros(len(more), bool), FS, **rules)
    assert (b.onset, b.contact) == (a.onset + shift, a.contact + shift)


# --- height ends ----------------------------------------------------------------------------------------


def _crossing(y: np.ndarray, m: float, after: int, up: bool) -> int:
    on = y >= m if up else y <= m
    return after + 1 + int(np.flatnonzero(on[after + 1 :] & ~on[after:-1])[0])


def test_height_above_ends_at_the_upward_crossing_and_segments_like_contact_there():
    t, pos, contact = min_jerk(y0=0.5, amp=0.4)  # 0.5 m up to 0.9 m
    seg = segment_arrays(t, pos, contact, FS, end=parse_end("height-above:0.8"))
    want = _crossing(pos[:, 1], 0.8, seg.onset, True)
    assert seg.contact == want and pos[want, 1] >= 0.8 > pos[want - 1, 1]
    flag = np.arange(len(t)) >= want  # the same trial with its contact flag at the crossing
    ref = segment_arrays(t, pos, flag, FS)
    assert (ref.onset, ref.contact) == (seg.onset, seg.contact)
    np.testing.assert_array_equal(ref.speed, seg.speed)


def test_height_below_ends_at_the_downward_crossing():
    t, pos, contact = min_jerk(y0=0.9, amp=-0.4)  # 0.9 m down to 0.5 m
    seg = segment_arrays(t, pos, contact, FS, start=parse_start("speed:5%"), end=parse_end("height-below:0.6"))
    want = _crossing(pos[:, 1], 0.6, seg.onset, False)
    assert seg.contact == want and pos[want, 1] <= 0.6 < pos[want - 1, 1]


def test_height_reached_only_by_crossing():
    """Starting above the height (0.85 m, height-above:0.8) the first sample is not a crossing: the end is
    where the hand comes back up through 0.8 m after dipping below it."""
    t1, p1, _ = min_jerk(y0=0.85, amp=-0.15, dur=0.6, rest_before=0.5, rest_after=0.2)
    _, p2, _ = min_jerk(y0=0.7, amp=0.2, dur=0.6, rest_before=0.0, rest_after=0.5)
    pos = np.concatenate([p1, p2[1:]])
    t = np.arange(len(pos)) / FS
    seg = segment_arrays(t, pos, np.zeros(len(t), bool), FS, end=parse_end("height-above:0.8"))
    assert seg.contact > len(p1) and pos[seg.contact, 1] >= 0.8 > pos[seg.contact - 1, 1]


def test_height_reasons_name_what_the_recording_reaches():
    t, pos, contact = min_jerk(y0=0.5, amp=0.21)
    assert segment_arrays(t, pos, contact, FS, end=parse_end("height-above:0.8")) == (
        "the up-axis position never rises to 0.8 m after onset (max 0.71 m)"
    )
    assert segment_arrays(t, pos, contact, FS, end=parse_end("height-below:0.3")) == (
        "the up-axis position never falls to 0.3 m after onset (min 0.502 m)"
    )
    assert segment_arrays(t, pos, contact, FS, end=parse_end("height-below:0.6")) == (
        "the up-axis position never falls to 0.6 m after onset: it is already below it at onset (0.502 m) "
        "and does not cross it again"
    )


# --- event starts and ends ------------------------------------------------------------------------------


def test_event_start_and_end_are_the_first_frames_at_or_after_the_events():
    t, pos, contact = min_jerk()
    dt = 1 / FS
    events = {"Go": np.array([t[90] + 0.005 * dt]), "Grasp": np.array([0.2, t[210] + 0.02 * dt, 2.9])}
    seg = segment_arrays(
        t, pos, contact, FS, start=parse_start("event:Go"), end=parse_end("event:Grasp"), events=events
    )
    assert seg.onset == 90  # 0.5 % of a frame interval after frame 90: counts as at it
    assert seg.contact == 211  # 2 % after frame 210: the next frame; the event at 0.2 s lies before the onset
    np.testing.assert_array_equal(seg.t, t[90:211])


def test_event_end_with_a_speed_start_segments_like_contact_at_that_frame():
    t, pos, contact = min_jerk()
    seg = segment_arrays(t, pos, contact, FS, end=parse_end("event:Touch"), events={"Touch": np.array([t[180]])})
    ref = segment_arrays(t, pos, np.arange(len(t)) >= 180, FS)
    assert (seg.onset, seg.contact) == (ref.onset, ref.contact) == (ref.onset, 180)
    np.testing.assert_array_equal(seg.speed, ref.speed)


def test_event_start_with_offset_and_contact_ends():
    t, pos, contact = min_jerk()
    ev = {"Go": np.array([0.8])}
    off = segment_arrays(t, pos, contact, FS, start=parse_start("event:Go"), end=parse_end("offset:0.05"), events=ev)
    assert off.onset == 80 and off.contact > 150
    con = segment_arrays(t, pos, np.arange(len(t)) >= 170, FS, start=parse_start("event:Go"), events=ev)
    assert (con.onset, con.contact) == (80, 170)


def test_event_reasons_name_the_events_the_trial_has():
    t, pos, contact = min_jerk()
    go = parse_start("event:Foot Strike")
    ev = {"Foot Off": np.array([1.0]), "General": np.array([0.5])}
    assert segment_arrays(t, pos, contact, FS, start=go, end=parse_end("offset:0.05"), events=ev) == (
        "no event 'Foot Strike' in this trial (events: Foot Off, General)"
    )
    assert segment_arrays(t, pos, contact, FS, start=go, end=parse_end("offset:0.05")) == (
        "no event 'Foot Strike' in this trial (it has no events)"
    )
    end = parse_end("event:Foot Off")
    assert segment_arrays(t, pos, contact, FS, end=end, events={"Foot Off": np.array([0.2, 0.4])}) == (
        "no event 'Foot Off' after the onset at 1.090 s (its events at 0.200, 0.400 s)"
    )
    late = {"Foot Off": np.array([5.0])}
    assert segment_arrays(t, pos, contact, FS, end=end, events=late) == (
        "no end: the event 'Foot Off' at 5.000 s is after the recording ends (last frame at 3.000 s)"
    )
    off = parse_end("offset:0.05")
    assert segment_arrays(t, pos, contact, FS, start=parse_start("event:Go"), end=off, events={"Go": [9.0]}) == (
        "no onset: the event 'Go' at 9.000 s is after the recording ends (last frame at 3.000 s)"
    )
    flag = np.arange(len(t)) >= 100
    assert segment_arrays(t, pos, flag, FS, start=parse_start("event:Go"), events={"Go": np.array([1.5])}) == (
        "no onset: the event 'Go' at 1.500 s is not before contact at 1.000 s"
    )


# --- reasons of the speed rules -------------------------------------------------------------------------


def test_speed_and_offset_reasons():
    t, pos, contact = min_jerk()
    cut = int(1.5 * FS)  # the recording stops at the peak
    assert segment_arrays(t[:cut], pos[:cut], contact[:cut], FS, end=parse_end("offset:3%")) == (
        "no offset: speed stays above 0.0169 m/s (3% of the peak 0.563 m/s) after the onset until the recording ends"
    )
    assert segment_arrays(t, pos, contact, FS, start=parse_start("speed:2"), end=parse_end("offset")) == (
        "no onset: speed stays below 2 m/s in the recording (max 0.562 m/s)"
    )
    moving = slice(120, None)  # starts in motion
    assert segment_arrays(t[moving], pos[moving], contact[moving], FS, start=parse_start("speed:3%")) == (
        "no contact: the contact flag is never 1"
    )
    got = segment_arrays(
        t[moving], pos[moving], contact[moving], FS, start=parse_start("speed:3%"), end=parse_end("offset")
    )
    assert got.startswith("no rest before onset: speed 0.23 m/s > 0.0169 m/s (3% of the peak 0.562 m/s) at the first")
    got = segment_arrays(t, pos, contact, FS, end=parse_end("offset:0.05"), min_samples=500)
    assert got.startswith("too short: ") and got.endswith(" samples from onset to offset (need at least 500)")


def test_an_offset_that_dips_but_never_holds():
    """The speed dips below the threshold between two reaches for less than the hold (about 0.14 s of
    0.2 s), and the recording ends during the second."""
    t, pos, contact = two_reaches(0.05)
    cut = int((0.5 + 0.6 + 0.05 + 0.3) * FS)
    got = segment_arrays(
        t[:cut], pos[:cut], contact[:cut], FS, start=parse_start("speed:0.05"), end=parse_end("offset", hold_s=0.2)
    )
    assert got == (
        "no offset: after the onset the speed never stays at or below 0.05 m/s for 0.2 s before the recording ends"
    )


def test_onset_speed_is_the_absolute_speed_start():
    t, pos, _ = min_jerk()
    flag = np.arange(len(t)) >= 180
    a = segment_arrays(t, pos, flag, FS, onset_speed=0.2)
    b = segment_arrays(t, pos, flag, FS, start=StartRule("speed", SpeedThreshold(0.2)))
    assert (a.onset, a.contact) == (b.onset, b.contact)
    with pytest.raises(TypeError, match="not both"):
        segment_arrays(t, pos, flag, FS, start=parse_start("speed:5%"), onset_speed=0.2)


def test_segmentation_detail_gives_the_thresholds_the_rules_used():
    t, pos, contact = min_jerk()
    d = segmentation_detail(t, pos, contact, FS, start=parse_start("speed:5%"), end=parse_end("offset:0.02"))
    assert d.reason == "" and len(d.speed) == len(t)
    assert d.start_threshold == pytest.approx(0.05 * d.speed.max()) and d.end_threshold == 0.02
    seg = segment_arrays(t, pos, contact, FS, start=parse_start("speed:5%"), end=parse_end("offset:0.02"))
    assert (d.onset, d.end) == (seg.onset, seg.contact)
    bad = segmentation_detail(t, pos, contact, FS)  # the paper's end: no contact
    assert bad.reason == "no contact: the contact flag is never 1" and bad.end == -1


# --- the two new features ---------------------------------------------------------------------------------


def test_peak_acc_and_path_length_of_the_minimum_jerk_reach():
    """Path length: the distance travelled (0.3 m); peak acceleration: the analytic max |a| of the
    minimum-jerk profile, 10 sqrt(3) / 3 * A / D^2 = 1.732 m/s^2 (within the derivatives' discretisation)."""
    t, pos, contact = min_jerk()
    seg = segment_arrays(t, pos, contact, FS, start=parse_start("speed:0.001"), end=parse_end("offset:0.001"))
    assert path_length(seg.speed, FS) == pytest.approx(0.3, abs=2e-3)
    assert peak_acceleration(seg.speed, FS) == pytest.approx(10 * np.sqrt(3) / 3 * 0.3, rel=0.02)
    assert np.isnan(peak_acceleration(np.array([0.1]), FS)) and path_length(np.array([0.1]), FS) == 0.0


# --- the paper's rules through trial_features -----------------------------------------------------------


@pytest.fixture(scope="module")
def cohort():
    return skilllib.load_recordings(cohort_path())


def test_paper_rules_default_explicit_and_onset_speed_give_the_same_table(cohort):
    a = trial_features(cohort)
    b = trial_features(cohort, start=PAPER_START, end=PAPER_END)
    c = trial_features(cohort, onset_speed=0.05, end=parse_end("contact"))
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    pd.testing.assert_frame_equal(a, c, check_exact=True)
    cols = list(a.columns)
    assert cols[cols.index("ldlj") + 1 : cols.index("ldlj") + 3] == ["peak_acc", "path_length"]
    assert a.attrs["start"] == PAPER_START and a.attrs["end"] == PAPER_END


def test_new_features_equal_the_per_segment_functions(cohort):
    f = trial_features(cohort).set_index(["participant", "trial"])
    for p, tr in cohort.keys()[::97]:
        seg = segment(cohort, p, tr)
        assert f.loc[(p, tr), "peak_acc"] == peak_acceleration(seg.speed, cohort.fs)
        assert f.loc[(p, tr), "path_length"] == path_length(seg.speed, cohort.fs)


def test_other_rules_go_trial_by_trial_and_agree_with_segment_arrays(cohort):
    """speed:5% with contact (not batched) and offset: the table's onset and end are segment_arrays'."""
    for start, end in [(parse_start("speed:5%"), PAPER_END), (PAPER_START, parse_end("offset:0.05"))]:
        f = trial_features(cohort, start=start, end=end).set_index(["participant", "trial"])
        for p, tr in cohort.keys()[::150]:
            d = cohort.trial(p, tr)
            seg = segment_arrays(d.t, d.pos, d.contact, cohort.fs, start=start, end=end)
            row = f.loc[(p, tr)]
            if isinstance(seg, str):
                assert row["status"] == "invalid" and row["reason"] == seg
            else:
                assert (row["t_onset"], row["t_contact"], row["n"]) == (
                    d.t[seg.onset],
                    d.t[seg.contact],
                    len(seg.speed),
                )
                assert row["pv"] == seg.speed.max() and row["contact_speed"] == seg.speed[-1]
        assert f.attrs["start"] == start and f.attrs["end"] == end


def test_segment_many_keeps_the_batched_path_for_the_paper(cohort, monkeypatch):
    """The paper's rules never call segment_arrays for a plain trial; another rule calls it per trial."""
    calls = []
    real = batch.segment_arrays
    monkeypatch.setattr(batch, "segment_arrays", lambda *a, **k: calls.append(1) or real(*a, **k))
    t, pos, contact = cohort.arrays()
    ok = (cohort.trials["status"] == "ok").to_numpy()
    batch.segment_many(t, pos, contact, cohort.runs(), cohort.fs, which=ok)
    assert calls == []
    batch.segment_many(t, pos, contact, cohort.runs(), cohort.fs, which=ok, start=parse_start("speed:5%"))
    assert len(calls) == ok.sum()


def _with_events(rec, rows):
    events = pd.DataFrame(rows, columns=["participant", "trial", "label", "t"])
    return dataclasses.replace(rec, events=events, _cache={})


def test_trial_features_reads_events_from_the_recordings():
    """Events from Recordings.trial_events; a trial without the event says so."""
    frames = []
    for tr in ("1", "2"):
        t, pos, contact = min_jerk()
        frames.append(
            pd.DataFrame(
                {"participant": "P1", "trial": tr, "t": t, "x": pos[:, 0], "y": pos[:, 1], "z": pos[:, 2]}
            ).assign(contact=0)
        )
    rec = recordings_from_frame(pd.concat(frames, ignore_index=True))
    if not callable(getattr(rec, "trial_events", None)):
        pytest.skip("Recordings.trial_events is not there yet")
    rec = _with_events(rec, [("P1", "1", "Grasp", 1.8)])
    f = trial_features(rec, end=parse_end("event:Grasp")).set_index("trial")
    assert f.loc["1", "t_contact"] == pytest.approx(1.8) and f.loc["1", "status"] != "invalid"
    assert f.loc["2", "reason"] == "no event 'Grasp' in this trial (it has no events)"
    seg = segment(rec, "P1", "1", end=parse_end("event:Grasp"))
    assert seg.t[-1] == pytest.approx(1.79)


# --- real recordings ------------------------------------------------------------------------------------

ADL_NAMED = [("ADL001", "FL1"), ("ADL001", "FR1"), ("ADL002", "FR2"), ("ADL005", "FR3")]
#: Trials of the UE-ADL copy whose first frames hold a 1-2 mm single-frame jump of the fingertip marker:
#: the speed at the first sample is then 0.04-0.13 m/s, above 3 % of the peak, for a sample or two.
ADL_FLICKER = [("ADL003", "FR5"), ("ADL013", "FL4"), ("ADL013", "FR1"), ("ADL013", "FR5"), ("ADL016", "FL1")]


@pytest.fixture(scope="module")
def adl():
    rec = skilllib.load_recordings(
        ADL,
        marker="RFTP,LFTP",
        up_axis="z",
        contact_height=-1.0,  # never: these reaches touch nothing; the offset ends them
        name_pattern=r"(?P<participant>ADL\d+)(?P<trial>F[LR]\d)",
    )
    return rec, trial_features(rec, start=parse_start("speed:3%"), end=parse_end("offset:3%"))


def test_real_forward_reaches_segment_with_relative_onset_and_offset(adl):
    """UE-ADL forward reaches (Vicon, 100 Hz): with speed:3% and offset:3% all 160 trials segment after a
    rest, lasting 0.4-2.5 s; a marker that flickers in the first frames does not start the movement (the
    relative onset is held), so those trials start where the hand moves, as the others."""
    rec, f = adl
    f = f.set_index(["participant", "trial"])
    assert len(f) == 160 and (f["status"] != "invalid").all()
    assert f["duration"].between(0.4, 2.5).all()
    first = f.index.map(lambda k: rec.trial(*k).t[0]).to_numpy()
    assert (f["t_onset"].to_numpy() - first >= 0.05).all()  # at least 5 samples of rest before the onset
    for k in ADL_NAMED + ADL_FLICKER:
        assert f.loc[k, "t_onset"] >= 0.5 and 0.4 <= f.loc[k, "duration"] <= 2.5
    assert f["path_length"].between(0.1, 0.6).all()  # a forward reach: tens of centimetres
    assert (f["contact_speed"] < 0.1 * f["pv"]).all()  # each ends near rest (the last sample above 3 %)


def test_a_flicker_at_the_first_frames_does_not_start_a_relative_onset():
    """A held onset: a 2-sample blip above the threshold at the start of the recording is skipped, a run that
    starts at the first sample and lasts is 'no rest before onset'."""
    t, pos, contact = min_jerk()
    pos = pos.copy()
    pos[0, 2] += 0.002  # a 2 mm jump of the first frame
    seg = segment_arrays(t, pos, contact, FS, start=parse_start("speed:3%"), end=parse_end("offset:3%"))
    ref = segment_arrays(t, min_jerk()[1], contact, FS, start=parse_start("speed:3%"), end=parse_end("offset:3%"))
    assert not isinstance(seg, str) and seg.onset == ref.onset and seg.contact == ref.contact
    paper_like = segment_arrays(t, pos, contact, FS, start=parse_start("speed:0.01"), end=parse_end("offset:3%"))
    assert isinstance(paper_like, str) and paper_like.startswith("no rest before onset")  # absolute: not held


def test_kinesis_reach_to_grasp_under_relative_rules():
    """kinesis (Optotrak, ~85 Hz, y up): 30 of 45 trials are usable; with speed:3% and offset:3% the usable
    trials that do not segment start in motion or never hold still after the peak (the recordings begin
    a few hundredths of a second before the movement and end before the hand comes to rest)."""
    rec = skilllib.load_recordings(
        REAL / "kinesis_rtgData.txt",
        sep="tab",
        time_unit="ms",
        units="mm",
        columns={
            "subjName": "participant",
            "trialN": "trial",
            "globalTime": "t",
            "indexXraw": "x",
            "indexYraw": "y",
            "indexZraw": "z",
        },
        contact_height=-10.0,
    )
    f = trial_features(rec, start=parse_start("speed:3%"), end=parse_end("offset:3%"))
    usable = (rec.trials["status"] == "ok").to_numpy()
    segmented = f["status"].to_numpy() != "invalid"
    assert usable.sum() == 30 and segmented.sum() >= 10
    why = f.loc[usable & ~segmented, "reason"]
    assert why.str.match(r"no rest before onset|no offset").all()
    assert f.loc[segmented, "duration"].between(0.4, 3.0).all()
