"""Vicon Nexus CSV exports ("Trajectories"): recognised by content (plain or compressed), read like a C3D
file (marker with or without the subject prefix, a list of markers, rate and units from the header, sub
frames, empty marker columns, further sections ignored), damaged files refused with one line naming the
file and line; a folder of them, and the real forward reaches of the UE-ADL database (MIT licence)."""

from __future__ import annotations

import gzip
import re
from pathlib import Path

import numpy as np
import pytest

from skilllib.recordings import (
    DataFormatError,
    is_nexus,
    load_recordings,
    read_any,
    read_folder,
    read_nexus,
)

RATE = 100.0
ADL = Path(__file__).resolve().parents[2] / "data" / "real" / "ue-adl-forward-reach"
ADL_ALL = Path("/work/shared/real-recordings/ue-adl-forward-reach")  # the 160 files (development set)


def path_of(n: int = 50, drop: float = 0.1, start: tuple[float, float, float] = (200.0, 300.0, 400.0)) -> np.ndarray:
    """(n, 3) mm: rest, then a minimum-jerk move of ``drop`` m down z (z up), with seeded 0.05 mm noise."""
    tau = np.clip((np.arange(n) - 10) / 30, 0, 1)
    s = tau**3 * (10 - 15 * tau + 6 * tau**2)
    p = np.tile(np.asarray(start, dtype=float), (n, 1))
    p[:, 1] += 50 * s
    p[:, 2] -= 1000 * drop * s
    return p + np.random.default_rng(n).normal(0, 0.05, p.shape)


def nexus_text(
    markers: dict[str, np.ndarray | None],
    *,
    rate: float | str = RATE,
    units: str = "mm",
    prefix: str | None = "S01",
    sub_frames: int = 1,
    devices: bool = False,
    first: str = "Trajectories",
) -> str:
    """A Nexus Trajectories export: ``markers`` name -> (n, 3) positions in ``units`` (None: never seen);
    ``sub_frames`` rows per frame; ``devices``: a Devices section at 1 kHz after it (and one before when
    ``first`` is "Devices")."""
    names = list(markers)
    n = next(len(v) for v in markers.values() if v is not None)
    head = [
        first,
        rate if isinstance(rate, str) else f"{rate:g}",
        ",," + ",".join(f"{prefix + ':' if prefix else ''}{m},," for m in names),  # Nexus: a trailing comma
        "Frame,Sub Frame" + ",X,Y,Z" * len(names),
        ",," + ",".join([units] * 3 * len(names)),
    ]
    rows = []
    for k in range(n):
        cells = [str(k // sub_frames + 1), str(k % sub_frames)]
        for m in names:
            v = markers[m]
            cells += ["", "", ""] if v is None or np.isnan(v[k]).any() else [f"{c:.6f}" for c in v[k]]
        rows.append(",".join(cells))
    text = "\n".join(head + rows) + "\n"
    dev = "Devices\n1000\n,,Force Plate\nFrame,Sub Frame,Fx\n,,N\n1,0,0.5\n1,1,0.6\n"
    if first == "Devices":
        return dev + "\nTrajectories\n" + text.split("\n", 1)[1]
    return text + ("\n" + dev if devices else "")


def write(path: Path, text: str) -> Path:
    if path.name.endswith(".gz"):
        path.write_bytes(gzip.compress(text.encode("utf-8-sig")))
    else:
        path.write_text("\ufeff" + text)  # Nexus writes a byte-order mark
    return path


def test_recognised_by_content_plain_or_compressed(tmp_path):
    text = nexus_text({"RFTP": path_of()})
    for name in ("t.csv", "t.csv.gz", "t.txt"):
        assert is_nexus(write(tmp_path / name, text))
    plain = tmp_path / "plain.csv"
    plain.write_text("participant,trial,t,x,y,z,contact\n")
    assert not is_nexus(plain) and not is_nexus(tmp_path / "missing.csv")


@pytest.mark.parametrize("prefix", ["S01", None], ids=["prefix", "no-prefix"])
@pytest.mark.parametrize("name", ["trial.csv", "trial.csv.gz"], ids=["plain", "gzip"])
def test_a_marker_with_or_without_the_subject_prefix_in_metres_at_the_header_rate(tmp_path, prefix, name):
    p = path_of()
    path = write(tmp_path / name, nexus_text({"RSHO": path_of(start=(0, 0, 1400)), "RFTP": p}, prefix=prefix))
    for marker in ("RFTP", f"{prefix}:RFTP" if prefix else "RFTP"):
        df = read_nexus(path, marker=marker)
        np.testing.assert_allclose(df[["x", "y", "z"]], np.round(p, 6) / 1000, atol=1e-12)
        np.testing.assert_allclose(df["t"], np.arange(len(p)) / RATE)
        assert df["contact"].isna().all()
        assert df.attrs["units"] == "mm" and df.attrs["marker"] == (f"{prefix}:RFTP" if prefix else "RFTP")


def test_units_from_the_header_or_the_option(tmp_path):
    p = path_of()
    path = write(tmp_path / "cm.csv", nexus_text({"RFTP": p / 10}, units="cm"))
    np.testing.assert_allclose(read_nexus(path)["x"], np.round(p[:, 0] / 10, 6) / 100)
    np.testing.assert_allclose(read_nexus(path, units="m")["x"], np.round(p[:, 0] / 10, 6))


def test_sub_frames_give_the_time_between_frames(tmp_path):
    """Two rows per frame at 200 Hz: t = ((Frame - 1) * 2 + Sub Frame) / 200."""
    p = path_of(60)
    df = read_nexus(write(tmp_path / "s.csv", nexus_text({"RFTP": p}, rate=200, sub_frames=2)))
    np.testing.assert_allclose(df["t"], np.arange(60) / 200)


def test_empty_marker_columns_are_allowed_and_gaps_are_nan(tmp_path):
    """A marker never seen (its columns empty throughout) is no problem; a gap of the read marker is NaN,
    which the recordings layer reports or repairs (not the reader's business)."""
    p = path_of()
    p[20:23] = np.nan
    df = read_nexus(write(tmp_path / "g.csv", nexus_text({"LTHUM": None, "RFTP": p})), marker="RFTP")
    assert df[["x", "y", "z"]].iloc[20:23].isna().all().all()
    assert df[["x", "y", "z"]].drop(index=[20, 21, 22]).notna().all().all()


def test_other_sections_are_ignored_but_trajectories_must_exist(tmp_path):
    p = path_of()
    after = read_nexus(write(tmp_path / "a.csv", nexus_text({"RFTP": p}, devices=True)))
    before = read_nexus(write(tmp_path / "b.csv", nexus_text({"RFTP": p}, first="Devices")))
    assert len(after) == len(before) == len(p)
    np.testing.assert_allclose(after[["t", "x"]], before[["t", "x"]])
    only = write(tmp_path / "devices.csv", "Devices\n1000\n,,Force Plate\nFrame,Sub Frame,Fx\n,,N\n1,0,0.5\n")
    assert is_nexus(only)
    with pytest.raises(DataFormatError, match=r"devices\.csv: no Trajectories section .*\(sections: Devices\)"):
        read_nexus(only)


def test_marker_choice_errors_list_the_markers(tmp_path):
    path = write(tmp_path / "m.csv", nexus_text({"RFTP": path_of(), "LFTP": path_of(start=(0, 0, 0))}))
    with pytest.raises(DataFormatError, match=r"m\.csv: 2 markers \(S01:RFTP, S01:LFTP\): choose one"):
        read_nexus(path)
    with pytest.raises(DataFormatError, match=r"m\.csv: no marker 'WRIST' \(markers: S01:RFTP, S01:LFTP\)"):
        read_nexus(path, marker="WRIST")
    text = nexus_text({"RFTP": path_of()}).replace(",,S01:RFTP,,", ",,S01:RFTP,,,S02:RFTP,,")
    text = text.replace("Frame,Sub Frame,X,Y,Z", "Frame,Sub Frame,X,Y,Z,X,Y,Z").replace(
        ",,mm,mm,mm", ",,mm,mm,mm,mm,mm,mm"
    )
    text = re.sub(r"^(\d+,\d+,[^\n]*)$", r"\1,1,2,3", text, flags=re.M)
    two = write(tmp_path / "two.csv", text)
    with pytest.raises(DataFormatError, match=r"two\.csv: marker 'RFTP' is ambiguous: S01:RFTP, S02:RFTP"):
        read_nexus(two, marker="RFTP")
    assert read_nexus(two, marker="S02:RFTP")["x"].iloc[0] == pytest.approx(0.001)


def test_a_marker_list_takes_the_one_that_moves_most(tmp_path):
    """--marker RFTP,LFTP: the moving fingertip, whichever hand; names not in the file are skipped."""
    moving, still = path_of(), path_of(drop=0.0)
    right = write(tmp_path / "R.csv", nexus_text({"RFTP": moving, "LFTP": still}))
    left = write(tmp_path / "L.csv", nexus_text({"RFTP": still, "LFTP": moving}))
    assert read_nexus(right, marker="RFTP,LFTP").attrs["marker"] == "S01:RFTP"
    assert read_nexus(left, marker="RFTP,LFTP").attrs["marker"] == "S01:LFTP"
    assert read_nexus(left, marker="WRIST,LFTP").attrs["marker"] == "S01:LFTP"


@pytest.mark.parametrize(
    "edit, where",
    [
        (lambda t: t.replace(",,mm,mm,mm\n", "", 1), r"line 5: no units row"),
        (lambda t: t.replace("\n100\n", "\nfast\n", 1), r"line 2: rate 'fast' is not a positive number"),
        (lambda t: t.replace("\n3,0,", "\n3,0,1,", 1), r"line 8: 6 fields, the column-name row \(line 4\) has 5"),
        (lambda t: t.replace("\n4,0,", "\n4,0,abc", 1), r"line 9, column 3 \(S01:RFTP X\): 'abc\d*\.\d+' is not"),
        (lambda t: t.replace("Frame,Sub Frame", "Frame,Subframe", 1), r"line 4: expected the column names"),
        (lambda t: t.replace(",,mm,mm,mm", ",,inch,inch,inch", 1), r"line 5, column 3: unknown length unit 'inch'"),
        (lambda t: t.split("Frame,")[0], r"Trajectories section cut short"),
        (lambda t: "\n".join(t.split("\n")[:5]) + "\n", r"no frames in the Trajectories section"),
        (lambda t: t.replace("\n5,0,", "\n,0,", 1), r"line 10: Frame is empty"),
    ],
    ids=["no-units", "rate", "ragged", "not-a-number", "column-names", "unit", "cut-short", "no-frames", "frame"],
)
@pytest.mark.parametrize("name", ["bad.csv", "bad.csv.gz"], ids=["plain", "gzip"])
def test_a_damaged_file_is_one_line_naming_file_and_line(tmp_path, edit, where, name):
    path = write(tmp_path / name, edit(nexus_text({"RFTP": path_of()})))
    with pytest.raises(DataFormatError) as e:
        load_recordings(path, contact_height=0.0)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(str(path))
    assert re.search(where, msg), msg


def test_a_single_file_is_one_trial_named_like_a_c3d_file(tmp_path):
    path = write(tmp_path / "P07_reach2.csv.gz", nexus_text({"RFTP": path_of()}))
    frame, problems = read_any(path, up_axis="z", contact_height=0.3)
    assert problems == [] and frame.attrs["units"] == "mm"
    rec = load_recordings(path, up_axis="z", contact_height=0.3)
    assert rec.keys() == [("P07", "reach2")] and rec.fs == pytest.approx(RATE)


def test_a_whole_body_trial_is_believed_in_the_header_unit(tmp_path):
    """A 5 m walk in mm: the header states the unit, so it is not refused as "not metres"."""
    n = 400
    walk = np.column_stack([np.linspace(0, 5000, n), np.full(n, 1000.0), np.linspace(0, 100, n)])
    walk += np.random.default_rng(1).normal(0, 0.05, walk.shape)
    path = write(tmp_path / "W_1.csv", nexus_text({"SACR": walk}))
    rec = load_recordings(path, up_axis="z", contact_height=-1.0)
    assert rec.trials.status.tolist() == ["ok"]


def test_a_folder_of_nexus_files_and_of_ordinary_csvs(tmp_path):
    """A folder of Nexus exports reads like a folder of C3D files (the marker list per file); a folder of
    ordinary per-trial CSVs keeps working."""
    root = tmp_path / "nexus"
    root.mkdir()
    for k, hand in enumerate("RL"):
        markers = {"RFTP": path_of(drop=0.1 if hand == "R" else 0), "LFTP": path_of(drop=0.1 if hand == "L" else 0)}
        write(root / f"P1_{hand}{k}.csv.gz", nexus_text(markers))
    frame, problems = read_folder(root, marker="RFTP,LFTP", up_axis="z", contact_height=0.3)
    assert problems == [] and frame.attrs["units"] == "mm"
    assert sorted(set(frame.trial)) == ["L1", "R0"]
    plain = tmp_path / "plain"
    plain.mkdir()
    (plain / "P1_1.csv").write_text("t,x,y,z,contact\n" + "".join(f"{k / 100},0,{k / 1e4},0,0\n" for k in range(20)))
    frame, problems = read_folder(plain)
    assert problems == [] and len(frame) == 20 and frame.attrs["units"] is None


# --- the real exports: UE-ADL forward reaches (Vicon Nexus 2.10, 100 Hz, mm) --------------------------

ADL_FILES = ["ADL001FL1", "ADL001FR1", "ADL002FR2", "ADL005FR3"]


def _raw_first(path: Path, marker: str) -> np.ndarray:
    """The marker's first-frame x, y, z (mm) straight from the file's text."""
    lines = gzip.open(path, "rt", encoding="utf-8-sig").read().split("\n")
    j = next(i for i, n in enumerate(lines[2].split(",")) if n.endswith(":" + marker))
    return np.array([float(c) for c in lines[5].split(",")[j : j + 3]])


@pytest.mark.parametrize("stem", ADL_FILES)
def test_real_adl_exports_read_in_metres_at_100_hz(stem):
    path = ADL / f"{stem}.csv.gz"
    assert is_nexus(path)
    hand = stem[-2]
    df = read_nexus(path, marker="RFTP,LFTP")
    assert df.attrs["marker"].endswith(f"{hand}FTP") and df.attrs["units"] == "mm"
    assert np.diff(df["t"]).mean() == pytest.approx(1 / 100)
    raw = _raw_first(path, f"{hand}FTP")
    np.testing.assert_allclose(df[["x", "y", "z"]].iloc[0], raw / 1000, rtol=1e-12)
    rec = load_recordings(path, marker=f"{hand}FTP", up_axis="z", contact_height=-1.0)
    assert rec.fs == pytest.approx(100.0) and rec.keys() == [(stem, stem)]


def test_real_adl_folder_reads_every_file_with_one_command():
    rec = load_recordings(
        ADL,
        marker="RFTP,LFTP",
        up_axis="z",
        contact_height=-1.0,
        name_pattern=r"(?P<participant>ADL\d+)(?P<trial>F[LR]\d)",
    )
    assert len(rec) == 160 and rec.trials.participant.nunique() == 16  # the compact copy of the 160 exports
    assert rec.keys()[:3] == [("ADL001", "FL1"), ("ADL001", "FL2"), ("ADL001", "FL3")]
    assert (rec.trials.status == "ok").all()
    assert rec.fs == pytest.approx(100.0)
    assert "no contact" not in " ".join(rec.trials.reason)  # contact is judged by the features, not here


@pytest.mark.slow
@pytest.mark.skipif(not ADL_ALL.is_dir(), reason="the development set of real recordings is not here")
def test_the_compact_copy_reads_as_the_original_exports():
    """data/real holds only Frame, Sub Frame and the two fingertips of each export
    (scripts/derive_real_data.py): read, they are the originals' samples bit for bit."""
    options = dict(marker="RFTP,LFTP", up_axis="z", contact_height=-1.0)
    pattern = r"(?P<participant>ADL\d+)(?P<trial>F[LR]\d)"
    full = load_recordings(ADL_ALL, name_pattern=pattern, **options)
    compact = load_recordings(ADL, name_pattern=pattern, **options)
    assert full.keys() == compact.keys() and len(full) == 160
    for a, b in zip(full.arrays(), compact.arrays(), strict=True):
        np.testing.assert_array_equal(a, b)
