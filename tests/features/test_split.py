"""Several movements per recording (issue 24, item 2): :func:`skilllib.features.split_movements` and the
recordings helper behind it, :func:`skilllib.recordings.cut_trials`.

Synthetic recordings of minimum-jerk reaches separated by rests check the rules exactly (pieces, names,
samples, repairs, resampling, events, the recordings' invariants); the real wheelchair-propulsion file of
kineticstoolkit (``data/real/ktk_sample_propulsion.c3d``) is cut into its pushes.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.signal import find_peaks

from skilllib.features import (
    EndRule,
    SpeedThreshold,
    StartRule,
    find_movements,
    movement_pieces,
    split_movements,
    velocity,
)
from skilllib.recordings import (
    cut_trials,
    events_frame,
    format_recordings,
    load_recordings,
    read_recordings,
    recordings_from_frame,
)

FS = 100.0
REAL = Path(__file__).resolve().parents[2] / "data" / "real"
AMPLITUDE = 0.2  #: m, each reach's distance
REACH_S = 0.8  #: s, each reach's duration
STARTS = (0.5, 2.0, 3.6)  #: s, the reaches' starts (rests of 0.7 and 0.8 s between them, 0.5 s at the ends)
DURATION = 4.9  #: s


def min_jerk(t: np.ndarray, t0: float, dur: float) -> np.ndarray:
    tau = np.clip((t - t0) / dur, 0, 1)
    return tau**3 * (10 - 15 * tau + 6 * tau**2)


def reaches(fs: float = FS, *, blip: bool = False, dip: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(t, pos): three reaches of 0.2 m in x, out and back and out again, with rests between them. ``blip``:
    a small bump in the first rest (peak speed about 0.06 m/s: noise); ``dip``: the second reach stops for an
    instant half way (below 0.05 m/s for 0.06 s: a brief dip, not a rest)."""
    t = np.arange(round(DURATION * fs)) / fs
    x = np.zeros_like(t)
    for k, t0 in enumerate(STARTS):
        sign = 1 if k % 2 == 0 else -1
        if dip and k == 1:
            x += sign * AMPLITUDE / 2 * (min_jerk(t, t0, REACH_S / 2) + min_jerk(t, t0 + REACH_S / 2, REACH_S / 2))
        else:
            x += sign * AMPLITUDE * min_jerk(t, t0, REACH_S)
    y = 0.3 + 0.0 * t
    if blip:
        y = y + 0.002 * np.exp(-0.5 * ((t - 1.45) / 0.02) ** 2)
    return t, np.column_stack([x, y, np.zeros_like(t)])


def frame(trials: dict[tuple[str, str], tuple[np.ndarray, np.ndarray]]) -> pd.DataFrame:
    parts = [
        pd.DataFrame(
            {"participant": p, "trial": tr, "t": t, "x": pos[:, 0], "y": pos[:, 1], "z": pos[:, 2], "contact": 0}
        )
        for (p, tr), (t, pos) in trials.items()
    ]
    return pd.concat(parts, ignore_index=True)


def speed_of(pos: np.ndarray, fs: float = FS) -> np.ndarray:
    return np.linalg.norm(velocity(pos, fs), axis=1)


def check_invariants(rec) -> None:
    """What every Recordings holds: rows, runs, arrays and trials agree; the CSV round trip keeps the trials."""
    t_all, pos_all, c_all = rec.arrays()
    runs = rec.runs()
    assert len(rec.trials) == len(rec) == len(runs.start)
    assert list(zip(rec.trials["participant"], rec.trials["trial"])) == rec.keys()
    assert rec.trials["n_samples"].sum() == len(rec.frame)
    for i, key in enumerate(rec.keys()):
        rows = slice(runs.start[i], runs.start[i] + runs.length[i])
        assert runs.length[i] == rec.trials["n_samples"].iloc[i]
        assert (rec.frame["trial"].iloc[rows] == key[1]).all()
        if not rec.is_resampled(*key):
            tr = rec.trial(*key)
            np.testing.assert_array_equal(tr.t, t_all[rows])
            np.testing.assert_array_equal(tr.pos, pos_all[rows])
    if rec.events is not None:
        keys = set(rec.keys())
        assert all(k in keys for k in zip(rec.events["participant"], rec.events["trial"]))


def test_three_reaches_give_three_pieces_each_with_one_full_movement(tmp_path):
    t, pos = reaches(blip=True, dip=True)
    rec = recordings_from_frame(frame({("P1", "block"): (t, pos)}))
    out = split_movements(rec)
    assert out.keys() == [("P1", "block-1"), ("P1", "block-2"), ("P1", "block-3")]
    assert (out.trials["status"] == "ok").all()
    x0 = 0.0
    for k, key in enumerate(out.keys()):
        tr = out.trial(*key)
        s = speed_of(tr.pos)
        assert s[0] < 0.05 and s[-1] < 0.05  # rest before and after the movement
        assert len(find_movements(s, 0.05, FS)) == 1  # one movement (the dip of reach 2 is not a rest)
        x1 = x0 + (AMPLITUDE if k % 2 == 0 else -AMPLITUDE)
        assert tr.pos[0, 0] == pytest.approx(x0, abs=1e-6) and tr.pos[-1, 0] == pytest.approx(x1, abs=1e-6)
        assert tr.t[0] < STARTS[k] and tr.t[-1] > STARTS[k] + REACH_S  # the whole reach, with margins
        x0 = x1
    np.testing.assert_array_equal(np.concatenate([out.trial(*k).t for k in out.keys()]), t)  # nothing lost
    cuts = [out.trial(*k).t[0] for k in out.keys()[1:]]
    assert cuts == pytest.approx(
        [(STARTS[0] + REACH_S + STARTS[1]) / 2, (STARTS[1] + REACH_S + STARTS[2]) / 2], abs=0.03
    )
    assert out.notes[-1].startswith("split_movements: 1 of 1 usable recording(s) split into 3 movement(s)")
    check_invariants(out)
    # the pieces are trials of their own in the book's format
    (tmp_path / "r.csv").write_text(format_recordings(out))
    back = read_recordings(tmp_path / "r.csv")
    assert back.keys() == out.keys() and back.trials["n_samples"].tolist() == out.trials["n_samples"].tolist()


def test_a_brief_dip_is_merged_noise_is_not_a_movement_and_a_long_dip_splits():
    t, pos = reaches(blip=True, dip=True)
    s = speed_of(pos)
    moves = find_movements(s, 0.05, FS)
    assert len(moves) == 3
    assert len(find_movements(s, 0.05, FS, min_rest_s=0.01)) == 4  # the 0.06 s dip as a rest
    assert len(find_movements(s, 0.01, FS)) == 4  # the blip (0.06 m/s) is noise at 0.05 m/s, not at 0.01
    assert (moves[0][1] + moves[1][0]) // 2 == movement_pieces(moves, len(s))[1][0]
    assert movement_pieces([], 10) == []


def test_recordings_without_movement_stay_whole_and_invalid_trials_are_kept():
    t, pos = reaches()
    still = np.column_stack([np.zeros_like(t), 0.3 + 0 * t, np.zeros_like(t)])
    data = frame({("P1", "1"): (t, pos), ("P1", "2"): (t, still), ("P2", "1"): (t, pos)})
    data.loc[data.index[(data["participant"] == "P2").to_numpy()][5], "t"] = 0.0  # time going back: invalid
    rec = recordings_from_frame(data)
    assert rec.trials["status"].tolist() == ["ok", "ok", "invalid"]
    out = split_movements(rec)
    assert out.keys() == [("P1", "1-1"), ("P1", "1-2"), ("P1", "1-3"), ("P1", "2"), ("P2", "1")]
    assert out.trials.set_index("trial").loc["1", "reason"] == rec.trials["reason"].iloc[2]
    assert "; 1 with no movement found kept whole" in out.notes[-1]
    check_invariants(out)
    one = split_movements(recordings_from_frame(frame({("P1", "r"): (t[:150], pos[:150])})))
    assert one.keys() == [("P1", "r-1")]  # one movement: still named -1


def test_a_relative_threshold_is_a_fraction_of_the_recordings_own_peak():
    t, pos = reaches()
    rec = recordings_from_frame(frame({("P1", "a"): (t, pos), ("P1", "b"): (t, pos * 0.2)}))
    out = split_movements(rec, StartRule("speed", SpeedThreshold(speed=None, fraction=0.05)))
    assert [k[1] for k in out.keys()] == ["a-1", "a-2", "a-3", "b-1", "b-2", "b-3"]
    absolute = split_movements(rec, StartRule("speed", SpeedThreshold(0.05)))
    assert [k[1] for k in absolute.keys()] == ["a-1", "a-2", "a-3", "b"]  # b's peak 0.075 m/s < 2 x 0.05


def test_repaired_samples_are_counted_per_piece():
    t, pos = reaches()
    pos = pos.copy()
    pos[[215, 216, 217]] = np.nan  # a gap of 3 samples during reach 2
    rec = recordings_from_frame(frame({("P1", "1"): (t, pos)}))
    assert rec.trials["n_repaired"].iloc[0] == 3
    out = split_movements(rec)
    assert out.trials["n_repaired"].tolist() == [0, 3, 0]
    assert out.trials["repairs"].tolist()[0] == "" and out.trials["repairs"].tolist()[2] == ""
    assert out.trials["repairs"].iloc[1].startswith("3 of the 3 repaired samples of recording 1 in this piece")
    assert out.is_repaired("P1", "1-2") and not out.is_repaired("P1", "1-1")
    assert out.repaired_mask("P1", "1-2").sum() == 3
    assert np.isfinite(out.trial("P1", "1-2").pos).all()
    check_invariants(out)


def test_a_resampled_trial_is_cut_in_its_resampled_samples():
    t, pos = reaches()
    keep = np.ones(len(t), dtype=bool)
    keep[[100, 300]] = False  # two dropped frames: resampled onto the uniform grid
    rec = recordings_from_frame(frame({("P1", "1"): (t[keep], pos[keep])}))
    assert rec.is_resampled("P1", "1") and "resampled" in rec.trials["timing"].iloc[0]
    out = split_movements(rec)
    assert len(out) == 3 and all(out.is_resampled(*k) for k in out.keys())
    assert all(out.trials["timing"] == rec.trials["timing"].iloc[0])
    np.testing.assert_allclose(np.concatenate([out.trial(*k).t for k in out.keys()]), rec.trial("P1", "1").t)
    assert out.trials["n_samples"].sum() == keep.sum()
    check_invariants(out)


def test_cut_at_start_events_or_after_end_events_and_events_go_with_their_pieces():
    t, pos = reaches()
    rec = recordings_from_frame(frame({("P1", "1"): (t, pos)}))
    ev = [("P1", "1", "go", t0 - 0.1) for t0 in STARTS] + [("P1", "1", "stop", t0 + REACH_S + 0.1) for t0 in STARTS]
    rec = dataclasses.replace(rec, events=events_frame(ev))
    out = split_movements(rec, StartRule("event", label="go"))
    assert [k[1] for k in out.keys()] == ["1-1", "1-2", "1-3"]
    for k, key in enumerate(out.keys()):
        tr = out.trial(*key)
        assert tr.t[0] == pytest.approx(STARTS[k] - 0.1)
        got = out.trial_events(*key)
        np.testing.assert_allclose(got["go"], [STARTS[k] - 0.1])
        np.testing.assert_allclose(got["stop"], [STARTS[k] + REACH_S + 0.1])
    assert out.trials["n_samples"].sum() == len(t) - round((STARTS[0] - 0.1) * FS)  # before the first: in no piece
    check_invariants(out)
    ends = split_movements(rec, PAPER_SPEED, EndRule("event", label="STOP"))  # labels matched without case
    assert len(ends) == 3
    for k, key in enumerate(ends.keys()):
        tr = ends.trial(*key)
        assert tr.t[-1] == pytest.approx(STARTS[k] + REACH_S + 0.1)  # the end event's sample is the last
    assert ends.trial("P1", "1-1").t[0] == 0.0
    assert ends.trial("P1", "1-2").t[0] == pytest.approx(STARTS[0] + REACH_S + 0.1 + 1 / FS)
    check_invariants(ends)
    none = split_movements(rec, StartRule("event", label="absent"))
    assert none.keys() == [("P1", "1")]


PAPER_SPEED = StartRule()


def test_cut_trials_refuses_bad_ranges_and_names_taken():
    t, pos = reaches()
    rec = recordings_from_frame(frame({("P1", "1"): (t, pos), ("P1", "1-1"): (t, pos)}))
    with pytest.raises(ValueError, match="exists"):
        cut_trials(rec, {("P1", "1"): [(0, 100), (100, 200)]})
    with pytest.raises(ValueError, match="non-overlapping"):
        cut_trials(rec, {("P1", "1-1"): [(0, 100), (50, 200)]})
    with pytest.raises(KeyError):
        cut_trials(rec, {("P9", "1"): [(0, 10)]})
    short = cut_trials(rec, {("P1", "1-1"): [(0, 2), (2, 490)]})
    assert short.trials.set_index("trial").loc["1-1-1", "status"] == "invalid"
    assert cut_trials(rec, {}) is rec
    check_invariants(short)


def test_real_wheelchair_propulsion_cut_into_its_pushes():
    """kineticstoolkit's propulsion recording (70 Hz, 10 s, m): the right hand's glove marker never rests
    (its speed stays above about 1 m/s), but its speed dips to 1.2-2 m/s once a cycle, when the hand is at
    the top of the hand rim (the highest point of its path, y up), where a push begins. With a start speed
    of 2.5 m/s and rests of at least 0.05 s, 19 pieces: 18 cuts, each within 0.02 s of one of the 18 highest
    points the hand reaches, and every piece but the last (cut by the end of the recording) holds one
    push down and one recovery up: one lowest point. Checked by eye on a plot of the speed with the cuts
    and the height (see the report of issue 24)."""
    rec = load_recordings(REAL / "ktk_sample_propulsion.c3d", marker="GloveR2", contact_height=-100.0)
    tr = rec.trial(*rec.keys()[0])
    assert rec.fs == pytest.approx(69.99, abs=0.01) and len(tr.t) == 700
    out = split_movements(rec, StartRule("speed", SpeedThreshold(2.5)), min_rest_s=0.05)
    assert len(out) == 19 and out.keys()[0] == ("ktk_sample", "propulsion-1")
    top, _ = find_peaks(tr.pos[:, 1], prominence=0.3)
    bottom, _ = find_peaks(-tr.pos[:, 1], prominence=0.3)
    cuts = np.array([out.trial(*k).t[0] for k in out.keys()[1:]])
    assert len(top) == 18 and np.abs(cuts - tr.t[top]).max() <= 0.02
    for key in out.keys()[:-1]:
        p = out.trial(*key)
        assert ((tr.t[bottom] >= p.t[0]) & (tr.t[bottom] <= p.t[-1])).sum() == 1
    check_invariants(out)
    whole = split_movements(rec)  # at 0.05 m/s the hand never rests: one movement
    assert whole.keys() == [("ktk_sample", "propulsion-1")]
