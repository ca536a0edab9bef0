"""Events of C3D files kept in the recordings (issue 24, item 2), and a contact channel in contact below its
threshold (item 8).

Fixtures are written at test time with ezc3d (the reader's library), as in ``test_c3d.py``; the real Vicon
file in ``data/real`` (pyomeca's ``markers_analogs.c3d``) checks ``contact_below`` on a load cell.
"""

from __future__ import annotations

import struct
from pathlib import Path

import ezc3d
import numpy as np
import pandas as pd
import pytest

from skilllib.recordings import (
    EVENT_COLUMNS,
    DataFormatError,
    c3d_events,
    events_frame,
    load_recordings,
    read_c3d,
)

FS = 100.0
REAL = Path(__file__).resolve().parents[2] / "data" / "real"


def path_mm(n: int = 120) -> np.ndarray:
    """(n, 3) positions in mm: rest, a minimum-jerk move of 150 mm in x, rest (y up, constant)."""
    t = np.arange(n) / FS
    tau = np.clip((t - 0.2) / 0.6, 0, 1)
    s = tau**3 * (10 - 15 * tau + 6 * tau**2)
    return np.column_stack([100 + 150 * s, 300 + 0 * s, 50 + 0 * s])


def write_ez(
    path: Path,
    pos: np.ndarray,
    *,
    events: list[tuple[str, float]] = (),
    contexts: list[str] | None = None,
    analogs: dict[str, np.ndarray] | None = None,
    first_frame: int = 1,
) -> Path:
    """A C3D file by ezc3d: one marker ``tip`` (mm), events ``(label, time in s)`` with optional
    ``EVENT:CONTEXTS``, analog channels (``m`` samples per frame) and a first frame number."""
    n = len(pos)
    c = ezc3d.c3d()
    c["parameters"]["POINT"]["RATE"]["value"] = [FS]
    c["parameters"]["POINT"]["LABELS"]["value"] = ("tip",)
    c["parameters"]["POINT"]["UNITS"]["value"] = ["mm"]
    pts = np.ones((4, 1, n))
    pts[:3, 0] = np.asarray(pos, dtype=float).T
    c["data"]["points"] = pts
    if analogs:
        m = len(next(iter(analogs.values()))) // n
        c["parameters"]["ANALOG"]["RATE"]["value"] = [FS * m]
        c["parameters"]["ANALOG"]["LABELS"]["value"] = tuple(analogs)
        c["data"]["analogs"] = np.stack([np.asarray(a, dtype=float) for a in analogs.values()])[np.newaxis]
    if events:
        c.add_parameter("EVENT", "LABELS", [lab for lab, _ in events])
        c.add_parameter("EVENT", "TIMES", np.array([[0.0 for _ in events], [tm for _, tm in events]]))
        if contexts is not None:
            c.add_parameter("EVENT", "CONTEXTS", list(contexts))
    c.write(str(path))
    if first_frame != 1:
        raw = bytearray(path.read_bytes())
        raw[6:10] = struct.pack("<HH", first_frame, first_frame + n - 1)
        path.write_bytes(bytes(raw))
    return path


def test_c3d_events_kept_with_labels_as_written_and_combined_with_their_context(tmp_path):
    events = [("Foot Strike", 0.55), ("Foot Off", 0.3), ("Foot Strike", 0.25), ("touch", 0.8)]
    path = write_ez(tmp_path / "P1_3.c3d", path_mm(), events=events, contexts=["Left", "Right", "Right", ""])
    df = read_c3d(path)
    got = df.attrs["events"]
    assert [lab for lab, _ in got] == [
        "Foot Strike",
        "Right Foot Strike",
        "Foot Off",
        "Right Foot Off",
        "Foot Strike",
        "Left Foot Strike",
        "touch",
    ]
    np.testing.assert_allclose([t for _, t in got], [0.25, 0.25, 0.3, 0.3, 0.55, 0.55, 0.8], atol=1e-6)
    rec = load_recordings(path, contact_height=-1.0)
    assert list(rec.events.columns) == list(EVENT_COLUMNS)
    ev = rec.trial_events("P1", "3")
    assert set(ev) == {"Foot Strike", "Left Foot Strike", "Right Foot Strike", "Foot Off", "Right Foot Off", "touch"}
    np.testing.assert_allclose(ev["Foot Strike"], [0.25, 0.55], atol=1e-6)  # sorted, both contexts
    np.testing.assert_allclose(ev["Left Foot Strike"], [0.55], atol=1e-6)
    np.testing.assert_allclose(ev["touch"], [0.8], atol=1e-6)
    assert set(rec.trial_events("P1", 3)) == set(ev)  # a number is looked up as its text; an unknown trial raises
    with pytest.raises(KeyError):
        rec.trial_events("P1", "4")


def test_event_times_share_the_clock_of_t_in_a_cropped_trial(tmp_path):
    """A trial cropped to start at capture frame 101 keeps the capture clock: an event at 1.4 s is at the
    sample whose t is 1.4 s (the 41st sample of the file)."""
    path = write_ez(tmp_path / "P1_1.c3d", path_mm(), events=[("go", 1.4)], first_frame=101)
    rec = load_recordings(path, contact_height=-1.0)
    tr = rec.trial("P1", "1")
    assert tr.t[0] == pytest.approx(1.0)
    (go,) = rec.trial_events("P1", "1")["go"]
    assert int(np.searchsorted(tr.t, go - 1e-6)) == 40


def test_contact_from_an_event_still_works_and_by_its_combined_label(tmp_path):
    pos = path_mm()
    path = write_ez(tmp_path / "a.c3d", pos, events=[("contact", 0.5)])
    df = read_c3d(path)
    assert np.flatnonzero(df["contact"].to_numpy() == 1)[0] == 50
    path = write_ez(
        tmp_path / "b.c3d", pos, events=[("Foot Strike", 0.31), ("Foot Strike", 0.62)], contexts=["Right", "Left"]
    )
    df = read_c3d(path, contact_channel="Left Foot Strike")
    assert np.flatnonzero(df["contact"].to_numpy() == 1)[0] == 62
    with pytest.raises(DataFormatError, match=r"events: Foot Strike, Left Foot Strike, Right Foot Strike\)"):
        read_c3d(path, contact_channel="touch")


def test_events_through_a_folder_and_none_for_formats_without_events(tmp_path):
    root = tmp_path / "data"
    (root / "P1").mkdir(parents=True)
    write_ez(root / "P1" / "1.c3d", path_mm(), events=[("touch", 0.9), ("go", 0.2)])
    write_ez(root / "P1" / "2.c3d", path_mm())  # no events
    rec = load_recordings(root, contact_height=-1.0)
    assert rec.keys() == [("P1", "1"), ("P1", "2")]
    assert rec.events[["participant", "trial", "label"]].values.tolist() == [["P1", "1", "go"], ["P1", "1", "touch"]]
    assert rec.trial_events("P1", "2") == {}
    np.testing.assert_allclose(rec.trial_events("P1", "1")["touch"], [0.9], atol=1e-6)
    csv = tmp_path / "r.csv"
    tr = rec.trial("P1", "1")
    pd.DataFrame(
        {
            "participant": "P1",
            "trial": "1",
            "t": tr.t,
            "x": tr.pos[:, 0],
            "y": tr.pos[:, 1],
            "z": tr.pos[:, 2],
            "contact": 0,
        }
    ).to_csv(csv, index=False)
    plain = load_recordings(csv)
    assert plain.events is None and plain.trial_events("P1", "1") == {}
    assert events_frame([]) is None


def test_c3d_events_without_a_label_are_left_out_and_used_limits_them():
    params = {"EVENT": {"LABELS": ["a", "", "b"], "TIMES": np.array([[0, 0, 1], [0.5, 0.6, 0.1]]), "USED": [3]}}
    events, unlabelled = c3d_events(params)
    assert events == [("a", 0.5), ("b", 60.1)] and unlabelled == 1
    params["EVENT"]["USED"] = [1]
    assert c3d_events(params) == ([("a", 0.5)], 0)
    assert c3d_events({}) == ([], 0)


def test_contact_below_the_threshold_for_a_load_cell_going_negative(tmp_path):
    n, m = 120, 4
    pos = path_mm(n)
    load = np.zeros(n * m)
    load[70 * m + 2 :] = -3.0  # loaded from the 3rd analog sample of frame 70 on
    path = write_ez(tmp_path / "a.c3d", pos, analogs={"Fz": load})
    above = read_c3d(path, contact_channel="Fz")["contact"].to_numpy()
    below = read_c3d(path, contact_channel="Fz", contact_below=True)["contact"].to_numpy()
    assert np.flatnonzero(below == 1)[0] == 70 and below[70:].all() and not below[:70].any()
    assert above[:70].all() and not above[71:].any()  # the default rule: "in contact" at rest, the wrong way round
    assert above[70] == 1  # frame 70 has samples on both sides: "any sample" is true either way
    given = read_c3d(path, contact_channel="Fz", contact_threshold=-1.0, contact_below=True)["contact"].to_numpy()
    np.testing.assert_array_equal(given, below)
    rec = load_recordings(path, contact_channel="Fz", contact_below=True)
    assert np.flatnonzero(rec.trial("a", "a").contact)[0] == 70


def test_contact_below_refused_for_parquet_input(tmp_path):
    df = pd.DataFrame(
        {"participant": "P1", "trial": "1", "t": np.arange(10) / FS, "x": 0.0, "y": 0.0, "z": 0.0, "contact": 0}
    )
    path = tmp_path / "r.parquet"
    df.to_parquet(path)
    with pytest.raises(DataFormatError, match="--contact-below does not apply to Parquet"):
        load_recordings(path, contact_below=True)


def test_real_vicon_load_cell_voltage_2_negative_while_the_box_is_held():
    """pyomeca's Vicon file: Voltage.2 of the box's load cell is flat at rest and goes negative while the box
    is held. Below the midpoint: contact from 1.64 s (the index finger has slowed to < 0.1 m/s at the box)
    to 3.71 s (release), 35 % of the frames; the default rule (above) gives the complement."""
    path = REAL / "pyomeca_markers_analogs.c3d"
    below = read_c3d(path, marker="INDEX", contact_channel="Voltage.2", contact_below=True)
    above = read_c3d(path, marker="INDEX", contact_channel="Voltage.2")
    c = below["contact"].to_numpy()
    t = below["t"].to_numpy()
    on = np.flatnonzero(np.diff(c) != 0) + 1
    assert t[on[0]] == pytest.approx(1.64, abs=0.015) and t[on[-1]] == pytest.approx(3.71, abs=0.015)
    assert c[0] == 0 and c[-1] == 0 and c.mean() == pytest.approx(0.35, abs=0.01)
    a = above["contact"].to_numpy()
    assert ((a == 1) | (c == 1)).all() and (a == c).sum() <= 5  # the complement but for frames crossing it
    pos = below[["x", "y", "z"]].to_numpy()
    speed = np.linalg.norm(np.gradient(pos, 1 / 100, axis=0), axis=1)
    assert speed[on[0] - 3 : on[0] + 3].max() < 0.3  # the hand has arrived at the box when the load begins
    rec = load_recordings(path, marker="INDEX", contact_channel="Voltage.2", contact_below=True, up_axis="z")
    assert rec.events is None  # the file has no events
    assert np.flatnonzero(rec.trial(*rec.keys()[0]).contact)[0] == on[0]
