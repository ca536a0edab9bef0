"""Tests of skilllib.recordings: C3D, TRC, CSV mapping (columns, units, up axis, contact height), folders.

Every file is written by the test: C3D files with test_c3d.write_c3d (the C3D tests are in test_c3d.py), TRC
files as text.
Values are checked against the written ones (positions after unit conversion, time stamps, the contact
sample), and every error message against the names it must list.
"""

from __future__ import annotations

import gzip
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_c3d import write_c3d  # the C3D tests and their writer live in test_c3d.py

from skilllib.features import trial_features
from skilllib.recordings import (
    UNIT_FACTORS,
    UP_AXIS_ROTATIONS,
    DataFormatError,
    FileProblem,
    contact_from_height,
    map_frame,
    parse_columns,
    read_any,
    read_csv_table,
    read_folder,
    recordings_from_frame,
    up_axis_rotation,
)

FS = 100.0


def approach(n: int = 80, fs: float = FS, drop: float = 0.12) -> np.ndarray:
    """(n, 3) book-frame path in m: 0.2 s rest, then a minimum-jerk descent of ``drop`` m in y that is cut
    at 80 % of its duration (still moving, as when the tip meets the surface), then at rest below."""
    t = np.arange(n) / fs
    tau = np.clip((t - 0.2) / 0.6, 0, 0.8)
    s = tau**3 * (10 - 15 * tau + 6 * tau**2)
    return np.column_stack([0.02 + 0.01 * s, 0.30 - drop * s, -0.05 + 0.03 * s])


def write_trc(
    path: Path,
    markers: dict[str, np.ndarray],
    *,
    rate: float = FS,
    units: str = "mm",
    t0: float = 0.0,
    blank_line: bool = True,
    cells: dict[tuple[int, int], str] | None = None,
) -> Path:
    """A TRC file (OpenSim layout, tabs); ``cells`` overrides data cells by (row, column) with text."""
    n = len(next(iter(markers.values())))
    lines = [
        f"PathFileType\t4\t(X/Y/Z)\t{path.name}",
        "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames",
        f"{rate:g}\t{rate:g}\t{n}\t{len(markers)}\t{units}\t{rate:g}\t1\t{n}",
        "Frame#\tTime\t" + "\t".join(f"{m}\t\t" for m in markers),
        "\t\t" + "\t".join(f"X{i}\tY{i}\tZ{i}" for i in range(1, len(markers) + 1)),
    ]
    if blank_line:
        lines.append("")
    for i in range(n):
        row = [str(i + 1), f"{t0 + i / rate:.6f}"] + [f"{v:.6f}" for m in markers.values() for v in m[i]]
        for (r, col), text in (cells or {}).items():
            if r == i:
                row[col] = text
        lines.append("\t".join(row))
    path.write_text("\n".join(lines) + "\n")
    return path


# --- TRC -----------------------------------------------------------------------------------------


# The TRC tests are in tests/recordings/test_trc.py.


# --- mapping -------------------------------------------------------------------------------------


@pytest.mark.parametrize("axis", sorted(UP_AXIS_ROTATIONS))
def test_every_up_axis_is_a_proper_rotation_sending_up_to_plus_y(axis):
    r = up_axis_rotation(axis)
    assert np.linalg.det(r) == pytest.approx(1.0)
    np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-12)
    up = np.zeros(3)
    up["xyz".index(axis[-1])] = -1.0 if axis.startswith("-") else 1.0
    np.testing.assert_allclose(r @ up, [0, 1, 0], atol=1e-12)


def test_z_up_matrix_as_documented_and_applied_to_a_table():
    df = pd.DataFrame({"t": [0.0], "x": [1.0], "y": [2.0], "z": [3.0], "contact": [0]})
    out = map_frame(df, up_axis="z")
    assert out[["x", "y", "z"]].iloc[0].tolist() == [1.0, 3.0, -2.0]  # (x, z, -y)_lab
    assert map_frame(df, up_axis="+Z")[["x", "y", "z"]].iloc[0].tolist() == [1.0, 3.0, -2.0]
    assert map_frame(df, up_axis="-x")[["x", "y", "z"]].iloc[0].tolist() == [2.0, -1.0, 3.0]


@settings(max_examples=40, deadline=None)
@given(
    axis=st.sampled_from(sorted(UP_AXIS_ROTATIONS)),
    unit=st.sampled_from(sorted(UNIT_FACTORS)),
    pts=st.lists(st.tuples(*[st.floats(-2e3, 2e3, allow_nan=False)] * 3), min_size=2, max_size=6),
)
def test_mapping_keeps_distances_up_to_the_unit_factor(axis, unit, pts):
    lab = np.array(pts)
    df = pd.DataFrame({"t": np.arange(len(lab)) * 0.01, "x": lab[:, 0], "y": lab[:, 1], "z": lab[:, 2], "contact": 0})
    book = map_frame(df, units=unit, up_axis=axis)[["x", "y", "z"]].to_numpy()
    d_lab = np.linalg.norm(lab[:, None] - lab[None], axis=-1)
    d_book = np.linalg.norm(book[:, None] - book[None], axis=-1)
    np.testing.assert_allclose(d_book, d_lab * UNIT_FACTORS[unit], rtol=1e-9, atol=1e-9)
    # units round trip: scaling back by the factor gives the written numbers
    np.testing.assert_allclose(book @ up_axis_rotation(axis) / UNIT_FACTORS[unit], lab, rtol=1e-9, atol=1e-6)


def test_unknown_unit_or_axis_is_an_error_naming_the_known_ones():
    df = pd.DataFrame({"t": [0.0], "x": [1.0], "y": [2.0], "z": [3.0], "contact": [0]})
    with pytest.raises(DataFormatError, match=r"unknown length unit 'inch' \(known: m, cm, mm\)"):
        map_frame(df, units="inch")
    with pytest.raises(DataFormatError, match=r"unknown up axis 'w' \(known: y, -y, z, -z, x, -x\)"):
        map_frame(df, up_axis="w")


def test_column_mapping_renames_and_reports_unknown_or_clashing_columns():
    df = pd.DataFrame(
        {"subject": ["01"], "rep": ["1"], "time": [0.0], "px": [1.0], "py": [2.0], "pz": [3.0], "touch": [0]}
    )
    cols = parse_columns("subject=participant, rep=trial,time=t,px=x,py=y,pz=z,touch=contact")
    out = map_frame(df, columns=cols)
    assert list(out.columns) == ["participant", "trial", "t", "x", "y", "z", "contact"]
    assert out["participant"].iloc[0] == "01"
    with pytest.raises(
        DataFormatError,
        match=r"--columns names column 'pos_x', which the table does not have "
        r"\(columns: subject, rep, time, px, py, pz, touch\)",
    ):
        map_frame(df, columns={"pos_x": "x"})
    with pytest.raises(DataFormatError, match=r"column 'x' would appear twice"):
        map_frame(df.assign(x=0.0), columns={"px": "x"})
    with pytest.raises(DataFormatError, match=r"--columns: 'time' is not old=new"):
        parse_columns("time,px=x")


def test_contact_from_height_per_trial_at_the_first_sample_at_or_below_it():
    y1 = np.array([0.30, 0.20, 0.101, 0.10, 0.12, 0.05])  # at 0.10 on sample 3, then back up: stays 1
    y2 = np.array([0.30, 0.25, 0.09, 0.08, 0.07, 0.06])
    y3 = np.full(6, 0.5)  # never low: no contact
    df = pd.DataFrame(
        {
            "participant": ["a"] * 6 + ["b"] * 6 + ["b"] * 6,
            "trial": ["1"] * 6 + ["1"] * 6 + ["2"] * 6,
            "t": np.tile(np.arange(6) / FS, 3),
            "x": 0.0,
            "y": np.concatenate([y1, y2, y3]),
            "z": 0.0,
        }
    )
    c = map_frame(df, contact_height=0.10)["contact"].to_numpy()
    assert c.tolist() == [0, 0, 0, 1, 1, 1] + [0, 0, 1, 1, 1, 1] + [0] * 6
    assert contact_from_height(np.array([np.nan, 0.0]), 0.1).tolist() == [0.0, 1.0]
    # the rule uses the height after units and axes: z up in mm, surface 100 mm up = 0.1 m
    lab = pd.DataFrame({"t": np.arange(6) / FS, "x": 0.0, "y": 0.0, "z": y1 * 1000})
    assert map_frame(lab, units="mm", up_axis="z", contact_height=0.10)["contact"].tolist() == [0, 0, 0, 1, 1, 1]


def test_a_measured_contact_flag_is_kept_and_no_contact_without_height_is_an_error():
    df = pd.DataFrame(
        {
            "participant": ["a"] * 4 + ["b"] * 4,
            "trial": "1",
            "t": np.tile(np.arange(4) / FS, 2),
            "x": 0.0,
            "y": 0.0,
            "z": 0.0,
            "contact": [0, 0, 0, 1] + [np.nan] * 4,
        }
    )
    out = map_frame(df, contact_height=0.5)  # y = 0 is below 0.5 m: trial b in contact from its first sample
    assert out["contact"].tolist() == [0, 0, 0, 1] + [1] * 4
    with pytest.raises(
        DataFormatError,
        match=r"t\.csv: no contact flag in 1 trial\(s\) and no contact height: "
        r"give the height.*--contact-height",
    ):
        map_frame(df, source="t.csv")
    with pytest.raises(DataFormatError, match=r"no 'contact' column and no contact height"):
        map_frame(df.drop(columns="contact"))


# --- CSV tables ----------------------------------------------------------------------------------

ID_TEXT = ["01", "1", "NA", "12345678901234567", "12345678901234568", "1e20"]


@pytest.mark.parametrize("name", ["rec.csv", "rec.csv.gz"])
def test_csv_identifiers_are_text_exactly_as_written(tmp_path, name):
    rows = ["participant,trial,t,x,y,z,contact"]
    for k, pid in enumerate(ID_TEXT):
        rows += [f"{pid},{ID_TEXT[-1 - k]},{i / FS:.2f},0.0,{0.3 - 0.01 * i:.2f},0.0,{int(i >= 4)}" for i in range(6)]
    text = "\n".join(rows) + "\n"
    path = tmp_path / name
    path.write_bytes(gzip.compress(text.encode()) if name.endswith(".gz") else text.encode())
    df = read_csv_table(path)
    assert df["participant"].drop_duplicates().tolist() == ID_TEXT
    assert df["trial"].drop_duplicates().tolist() == ID_TEXT[::-1]
    assert all(type(v) is str for v in df["participant"]) and df["y"].dtype == float
    frame, problems = read_any(path)
    assert problems == [] and frame["participant"].nunique() == len(ID_TEXT)


def test_csv_with_other_names_units_and_z_up_through_read_any(tmp_path):
    path = tmp_path / "vr.csv"
    path.write_text(
        "subject,rep,time,px,py,pz\n" + "".join(f"S01,007,{i / FS},{10 * i},{-5.0},{300 - 40 * i}\n" for i in range(6))
    )
    frame, _ = read_any(
        path,
        columns="subject=participant,rep=trial,time=t,px=x,py=y,pz=z",
        units="mm",
        up_axis="z",
        contact_height=0.15,
    )
    assert frame[["participant", "trial"]].iloc[0].tolist() == ["S01", "007"]
    np.testing.assert_allclose(frame["y"], (300 - 40 * np.arange(6)) / 1000)  # z_lab in m
    np.testing.assert_allclose(frame["z"], 0.005)  # -y_lab
    assert frame["contact"].tolist() == [0, 0, 0, 0, 1, 1]  # 0.14 m at sample 4
    path.write_text("subject,rep,time,px,py,pz\nS01,1,0,1,2,3\nS01,1,0.01,abc,2,3\n")
    with pytest.raises(DataFormatError, match=r"vr\.csv, line 3, column 'x': 'abc' is not a number"):
        read_any(path, columns="subject=participant,rep=trial,time=t,px=x,py=y,pz=z", units="mm", contact_height=0.1)


def test_csv_blank_line_keeps_line_numbers_and_is_not_a_trial(tmp_path):
    path = tmp_path / "r.csv"
    path.write_text("participant,trial,t,x,y,z,contact\nA,1,0,0,0,0,0\n\nA,1,0.01,0,0,0,1\n")
    df = read_csv_table(path)
    assert len(df) == 3 and df.iloc[1].isna().all()
    assert map_frame(df)["contact"].iloc[[0, 2]].tolist() == [0, 1]  # the blank row asks for no height


# --- folders -------------------------------------------------------------------------------------


def test_folder_rule_ids_are_text_and_trials_in_natural_order(tmp_path):
    pos = approach(80)
    for sub, stem in [("01", "3"), ("1", "3"), ("1", "10"), ("1", "2")]:
        (tmp_path / sub).mkdir(exist_ok=True)
        write_c3d(tmp_path / sub / f"{stem}.c3d", {"tip": pos * 1000}, events=[("contact", 0.1)])
    write_trc(tmp_path / "P_10_05.trc", {"tip": pos * 1000})
    write_trc(tmp_path / "P_2_1.trc", {"tip": pos * 1000})
    frame, problems = read_folder(tmp_path, contact_height=0.25)
    assert problems == []
    keys = frame[["participant", "trial"]].drop_duplicates().apply(tuple, axis=1).tolist()
    assert keys == [("01", "3"), ("1", "2"), ("1", "3"), ("1", "10"), ("P_2", "1"), ("P_10", "05")]
    assert all(type(v) is str for v in frame["trial"])
    c3d_rows = frame[(frame.participant == "01")]
    assert np.flatnonzero(c3d_rows["contact"].to_numpy())[0] == 10  # the event, not the height rule
    trc_rows = frame[(frame.participant == "P_2")]
    assert np.flatnonzero(trc_rows["contact"].to_numpy())[0] == np.flatnonzero(pos[:, 1] <= 0.25)[0]


def test_folder_name_pattern(tmp_path):
    write_trc(tmp_path / "sub-07_run-2.trc", {"tip": approach(10)}, units="m")
    write_trc(tmp_path / "notes.trc", {"tip": approach(10)}, units="m")
    frame, problems = read_folder(
        tmp_path, name_pattern=r"sub-(?P<participant>\w+)_run-(?P<trial>\d+)", contact_height=0.2
    )
    assert frame[["participant", "trial"]].iloc[0].tolist() == ["07", "2"]
    assert problems == []  # a name without ids is no trial: skipped, with its reason (issue 23)
    assert [q.path for q in frame.attrs["skipped"]] == ["notes.trc"]
    assert "does not match the name pattern" in frame.attrs["skipped"][0].reason
    with pytest.raises(DataFormatError, match=r"has no \(\?P<trial>...\) group"):
        read_folder(tmp_path, name_pattern=r"(?P<participant>.*)")


def test_a_broken_file_is_reported_while_the_others_are_read(tmp_path):
    pos = approach(20) * 1000
    (tmp_path / "A").mkdir()
    write_c3d(tmp_path / "A" / "1.c3d", {"tip": pos}, events=[("contact", 0.1)])
    (tmp_path / "A" / "2.c3d").write_bytes(b"\x00" * 100)
    write_c3d(tmp_path / "A" / "3.c3d", {"tip": pos, "wrist": pos}, events=[("contact", 0.1)])
    write_c3d(tmp_path / "A" / "4.c3d", {"tip": pos}, events=[("contact", 0.1)])
    write_trc(tmp_path / "A" / "4.trc", {"tip": pos})  # the same participant and trial again
    (tmp_path / "A" / "deep").mkdir()
    write_trc(tmp_path / "A" / "deep" / "5.trc", {"tip": pos})
    write_trc(tmp_path / "nounderscore.trc", {"tip": pos})
    frame, problems = read_folder(tmp_path, contact_height=0.2)
    assert frame[["participant", "trial"]].drop_duplicates().values.tolist() == [["A", "1"], ["A", "4"]]
    assert all(isinstance(p, FileProblem) for p in problems)
    got = {(Path(p.path).name, p.participant, p.trial): p.reason for p in problems}
    skipped = dict(frame.attrs["skipped"])  # no ids or too deep: not trials, skipped with a reason (issue 23)
    assert list(skipped) == ["A/deep/5.trc", "nounderscore.trc"]
    assert skipped["A/deep/5.trc"].startswith("in a sub-sub-folder")
    assert "PARTICIPANT_TRIAL" in skipped["nounderscore.trc"]
    assert set(got) == {
        ("2.c3d", "A", "2"),
        ("3.c3d", "A", "3"),
        ("4.trc", "A", "4"),
    }
    assert got["2.c3d", "A", "2"].startswith("not a readable C3D file")
    assert got["3.c3d", "A", "3"] == "2 markers (tip, wrist): choose one with --marker NAME"
    assert "also" in got["4.trc", "A", "4"] and "4.c3d" in got["4.trc", "A", "4"]


def test_folder_errors(tmp_path):
    with pytest.raises(DataFormatError, match=r"no \.c3d, \.trc or \.csv files"):
        read_folder(tmp_path)
    (tmp_path / "a_1.c3d").write_bytes(b"junk")
    with pytest.raises(DataFormatError, match=r"none of the 1 files could be read \(first: .*a_1\.c3d: not a readable"):
        read_folder(tmp_path)
    with pytest.raises(DataFormatError, match=r"unknown up axis"):
        read_folder(tmp_path, up_axis="up")


def test_folder_of_per_trial_csv_logs(tmp_path):
    (tmp_path / "P1").mkdir()
    (tmp_path / "P1" / "1.csv.gz").write_bytes(
        gzip.compress(b"time,px,py,pz\n" + b"".join(f"{i / FS},0,{5 - i},100\n".encode() for i in range(6)))
    )
    (tmp_path / "P1" / "2.csv").write_text("participant,trial,t,x,y,z\n")
    frame, problems = read_folder(
        tmp_path, columns={"time": "t", "px": "x", "py": "y", "pz": "z"}, units="cm", up_axis="-z", contact_height=0.03
    )
    np.testing.assert_allclose(frame["y"], -1.0)  # -z_lab = -100 cm
    np.testing.assert_allclose(frame["z"], (5 - np.arange(6)) / 100)  # y_lab
    assert frame["contact"].tolist() == [1.0] * 6
    assert [(p.trial, "participant/trial columns" in p.reason) for p in problems] == [("2", True)]
    again, _ = read_any(tmp_path, columns="time=t,px=x,py=y,pz=z", units="cm", up_axis="-z", contact_height=0.03)
    pd.testing.assert_frame_equal(again, frame)


# --- end to end ------------------------------------------------------------------------------------


def test_a_z_up_c3d_in_mm_with_a_contact_event_runs_through_validation_and_features(tmp_path):
    pos = approach(100)
    first_low = int(np.flatnonzero(pos[:, 1] <= pos[-1, 1] + 1e-9)[0])  # where the descent was cut (sample 68)
    lab = np.column_stack([pos[:, 0], -pos[:, 2], pos[:, 1]]) * 1000  # book (x, y, z) = lab (x, z, -y)
    path = write_c3d(tmp_path / "S1_7.c3d", {"tip": lab}, events=[("contact", first_low / FS)])
    frame, problems = read_any(path, up_axis="z")
    np.testing.assert_allclose(frame[["x", "y", "z"]].to_numpy(), pos, atol=1e-6)
    assert frame[["participant", "trial"]].iloc[0].tolist() == ["S1", "7"] and problems == []
    rec = recordings_from_frame(frame, str(path))
    assert rec.fs == pytest.approx(FS) and rec.trials.status.tolist() == ["ok"]
    feats = trial_features(rec)
    assert feats.status[0] in ("selected", "excluded")
    assert feats.t_contact[0] == pytest.approx(first_low / FS)
