"""Tests of skilllib/recordings/_trc.py: TRC files as OpenSim, its MATLAB scripts and pyomeca write them.

Every file is written by the test as text (:func:`trc_lines` builds the lines of each variant): tabs or
commas, repeated separators and padded cells in the header, a marker's name over its three columns or
repeated in each, Windows line ends, trailing blank lines, empty cells. Values are checked against the
written ones, notes and units against ``frame.attrs``, and every error message against what it must name.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import skilllib
from skilllib.recordings import UNIT_FACTORS, DataFormatError, read_trc
from skilllib.recordings import write_trc as library_write_trc

FS = 100.0
HEADER_NAMES = ["DataRate", "CameraRate", "NumFrames", "NumMarkers", "Units", "OrigDataRate", "OrigDataStartFrame"]


def approach(n: int = 80, fs: float = FS, drop: float = 0.12) -> np.ndarray:
    """(n, 3) path in m: 0.2 s rest, then a minimum-jerk descent of ``drop`` m in y cut at 80 %, then rest."""
    t = np.arange(n) / fs
    tau = np.clip((t - 0.2) / 0.6, 0, 0.8)
    s = tau**3 * (10 - 15 * tau + 6 * tau**2)
    return np.column_stack([0.02 + 0.01 * s, 0.30 - drop * s, -0.05 + 0.03 * s])


def trc_lines(
    markers: dict[str, np.ndarray],
    *,
    rate: float = FS,
    units: str | None = "mm",
    t0: float = 0.0,
    sep: str = "\t",
    padded: bool = False,
    repeated_names: bool = False,
    lead: tuple[str, ...] = ("Frame#", "Time"),
    times: np.ndarray | None = None,
    num_frames: str | None = None,
    num_markers: str | None = None,
    coordinates: bool = True,
    blank_line: bool = True,
    trailing_sep: bool = False,
    cells: dict[tuple[int, int], str] | None = None,
) -> list[str]:
    """The lines of a TRC file (OpenSim's layout). ``padded``: header and name lines as OpenSim's MATLAB
    scripts write them (``%7d`` cells, doubled separators, leading spaces); ``cells`` overrides data cells
    by (row, column) with text; ``times`` (s) replaces the Time column's ``t0 + i / rate``."""
    n = len(next(iter(markers.values())))
    gap = sep * 2 if padded else sep
    names = HEADER_NAMES + ["OrigNumFrames"]
    values = [f"{rate:g}", f"{rate:g}", num_frames or str(n), num_markers or str(len(markers))]
    values += [units or "", f"{rate:g}", "1", str(n)]
    if units is None:
        del names[4], values[4]
    if padded:
        values = [f"{v:>7}" for v in values]
    marker_cells = [sep.join([m] * 3) if repeated_names else m + sep * 2 for m in markers]
    lines = [
        f"PathFileType{sep}4{sep}(X/Y/Z){sep}file.trc",
        sep.join(names),
        gap.join(values),
        ("  " if padded else "") + gap.join(lead) + gap + gap.join(marker_cells),
    ]
    if coordinates:
        lines.append(sep * len(lead) + sep.join(f"X{i}{sep}Y{i}{sep}Z{i}" for i in range(1, len(markers) + 1)))
    if blank_line:
        lines.append(sep * (len(lead) + 3 * len(markers)) if sep == "," else "")  # pyomeca: a line of commas
    for i in range(n):
        t = times[i] if times is not None else t0 + i / rate
        row = {"Frame#": str(i + 1), "Time": f"{t:.6f}"}
        cells_i = [row[c] for c in lead] + [f"{v:.6f}" for m in markers.values() for v in m[i]]
        for (r, col), text in (cells or {}).items():
            if r == i:
                cells_i[col] = text
        lines.append(sep.join(cells_i) + (sep if trailing_sep else ""))
    return lines


def write(path: Path, lines: list[str], *, newline: str = "\n", trailing_blank: int = 0) -> Path:
    path.write_bytes((newline.join(lines) + newline * (1 + trailing_blank)).encode())
    return path


def xyz(df) -> np.ndarray:
    return df[["x", "y", "z"]].to_numpy()


# --- the layout OpenSim writes (moved from test_formats.py) -----------------------------------------


@pytest.mark.parametrize("units,blank", [("mm", True), ("m", False)])
def test_trc_positions_in_metres_time_from_the_file_and_marker_choice(tmp_path, units, blank):
    a, b = approach(30), approach(30) + 0.25
    markers = {"tip": a / UNIT_FACTORS[units], "wrist": b / UNIT_FACTORS[units]}
    path = write(tmp_path / "a.trc", trc_lines(markers, units=units, t0=1.5, blank_line=blank))
    df = read_trc(path, marker="wrist")
    np.testing.assert_allclose(xyz(df), b, atol=1e-6 * UNIT_FACTORS[units])
    np.testing.assert_allclose(df["t"], 1.5 + np.arange(30) / FS, atol=1e-6)
    assert df["contact"].isna().all()
    assert df.attrs == {"notes": [], "units": units}
    with pytest.raises(DataFormatError, match=r"a\.trc: 2 markers \(tip, wrist\): choose one with --marker"):
        read_trc(path)
    with pytest.raises(DataFormatError, match=r"a\.trc, line 4: no marker 'elbow' \(markers: tip, wrist; line split"):
        read_trc(path, marker="elbow")


def test_trc_empty_cell_is_a_gap_and_text_is_an_error_naming_the_line(tmp_path):
    pos = approach(10) * 1000
    df = read_trc(write(tmp_path / "a.trc", trc_lines({"tip": pos}, cells={(3, 3): ""})))
    assert df["y"].isna().tolist() == [False] * 3 + [True] + [False] * 6
    bad = write(tmp_path / "b.trc", trc_lines({"tip": pos}, cells={(4, 2): "1,5"}))  # 5 header lines + blank: line 11
    with pytest.raises(DataFormatError, match=r"b\.trc, line 11, column 3 \(x\): '1,5' is not a number"):
        read_trc(bad)


def test_trc_header_checks(tmp_path):
    text = trc_lines({"tip": approach(5)})
    path = write(tmp_path / "b.trc", ["Frame#\tTime"] + text[1:])
    with pytest.raises(DataFormatError, match=r"b\.trc, line 1: not a TRC file"):
        read_trc(path)
    path = write(tmp_path / "c.trc", trc_lines({"tip": approach(5)}, num_markers="2"))
    with pytest.raises(
        DataFormatError, match=r"c\.trc, line 4: 1 marker names \(tip\) but NumMarkers is 2 \(line split at tabs\)"
    ):
        read_trc(path)


@pytest.mark.parametrize("units", ["mm", "cm", "m"])
def test_the_library_trc_writer_round_trips_through_the_reader(tmp_path, units):
    pos = approach(40)
    pos[7, 1] = np.nan  # a gap: an empty cell
    t = 0.25 + np.arange(len(pos)) / FS
    path = library_write_trc(tmp_path / "P1_3.trc", {"tip": pos}, t, units=units)
    df = read_trc(path)
    assert np.isnan(df["y"].iloc[7]) and np.isnan(df["y"].to_numpy()).sum() == 1
    ok = ~np.isnan(pos).any(axis=1)
    np.testing.assert_allclose(xyz(df)[ok], pos[ok], atol=0.0005 * UNIT_FACTORS[units])
    np.testing.assert_allclose(df["t"].to_numpy(), t, atol=1e-6)
    assert df.attrs["units"] == units and df.attrs["notes"] == []


# --- the variants other writers produce -------------------------------------------------------------


def test_opensim_matlab_header_with_double_tabs_and_leading_spaces(tmp_path):
    """OpenSim's MATLAB writers: ``%7.1f\\t\\t%7.1f\\t\\t%7d...`` on line 3, ``  Frame#\\t\\tTime`` on line 4,
    a CRLF file with blank lines at its end."""
    a, b = approach(20), approach(20) + 0.1
    lines = trc_lines({"R.ASIS": a * 1000, "L.ASIS": b * 1000}, padded=True, trailing_sep=True)
    assert lines[2].startswith("    100\t\t    100\t\t     20") and lines[3].startswith("  Frame#\t\tTime\t\tR.ASIS")
    path = write(tmp_path / "subject01_walk1.trc", lines, newline="\r\n", trailing_blank=3)
    df = read_trc(path, marker="L.ASIS")
    np.testing.assert_allclose(xyz(df), b, atol=1e-9)
    np.testing.assert_allclose(df["t"], np.arange(20) / FS, atol=1e-9)
    assert df.attrs == {"notes": [], "units": "mm"}


def test_pyomeca_comma_separated_trc_with_a_frame_count_note(tmp_path):
    """pyomeca's tests/data/markers.trc: commas, every header line padded with commas, a line of commas
    after X1/Y1/Z1, NumFrames 652 over 93 rows, OrigDataStartFrame 0."""
    names = ["ASISl", "ASISr", "STER"]
    markers = {m: (approach(93) + 0.1 * j) * 1000 for j, m in enumerate(names)}
    lines = trc_lines(markers, sep=",", num_frames="652")
    pad = "," * 12
    lines[0] += pad
    lines[1] += pad
    lines[2] = lines[2].replace(",1,93", ",0,652") + pad
    assert lines[3] == "Frame#,Time,ASISl,,,ASISr,,,STER,," and set(lines[5]) == {","}
    df = read_trc(write(tmp_path / "markers.trc", lines), marker="ASISr")
    np.testing.assert_allclose(xyz(df), approach(93) + 0.1, atol=1e-9)
    assert df.attrs == {"notes": ["header announces 652 frames, file has 93"], "units": "mm"}
    with pytest.raises(
        DataFormatError, match=r"markers\.trc, line 4: no marker 'WRIST' \(markers: ASISl, ASISr, STER; "
    ):
        read_trc(tmp_path / "markers.trc", marker="WRIST")
    with pytest.raises(DataFormatError, match=r"3 markers \(ASISl, ASISr, STER\): .* \(line 4 split at commas\)"):
        read_trc(tmp_path / "markers.trc")


def test_a_name_repeated_in_each_of_its_columns(tmp_path):
    a, b = approach(10), approach(10) - 0.05
    df = read_trc(
        write(tmp_path / "r.trc", trc_lines({"tip": a, "wrist": b}, units="m", repeated_names=True)), marker="wrist"
    )
    np.testing.assert_allclose(xyz(df), b, atol=1e-9)


@pytest.mark.parametrize("units", ["mm", "cm", "m", "MM"])
def test_units_from_the_header_in_metres_and_in_attrs(tmp_path, units):
    pos = approach(10)
    df = read_trc(write(tmp_path / "u.trc", trc_lines({"tip": pos / UNIT_FACTORS[units.lower()]}, units=units)))
    np.testing.assert_allclose(xyz(df), pos, atol=1e-9)
    assert df.attrs["units"] == units.lower()


def test_a_header_without_units_needs_the_units_argument(tmp_path):
    path = write(tmp_path / "n.trc", trc_lines({"tip": approach(10) * 100}, units=None))
    with pytest.raises(DataFormatError, match=r"n\.trc, line 3: the TRC header states no Units: give .* with --units"):
        read_trc(path)
    df = read_trc(path, units="cm")
    np.testing.assert_allclose(xyz(df), approach(10), atol=1e-9)
    assert df.attrs["units"] is None
    bad = write(tmp_path / "in.trc", trc_lines({"tip": approach(10)}, units="in"))
    with pytest.raises(DataFormatError, match=r"in\.trc, line 3: Units: unknown length unit 'in' .*--units"):
        read_trc(bad)
    assert read_trc(bad, units="m").attrs["units"] == "in"  # the unit the header states, overridden


def test_missing_samples_are_nan_also_in_a_row_cut_short(tmp_path):
    pos = approach(8) * 1000
    lines = trc_lines({"tip": pos, "wrist": pos}, cells={(2, 3): "", (2, 4): ""})
    lines[-1] = "\t".join(lines[-1].split("\t")[:5])  # the last row ends after the first marker
    df = read_trc(write(tmp_path / "g.trc", lines), marker="wrist")
    assert np.isnan(xyz(df)).any(axis=1).tolist() == [False] * 7 + [True]
    df = read_trc(tmp_path / "g.trc", marker="tip")
    assert np.isnan(df["y"]).tolist() == [False, False, True] + [False] * 5


@pytest.mark.parametrize("value", ["inf", "nan", "two", "2.5", "-1", ""])
def test_num_markers_not_a_whole_number_is_a_clear_error(tmp_path, value):
    lines = trc_lines({"tip": approach(5)})
    cells = lines[2].split("\t")
    cells[3] = value
    lines[2] = "\t".join(cells)
    with pytest.raises(DataFormatError, match=r"h\.trc, line 3: NumMarkers .*(not a whole number|values)"):
        read_trc(write(tmp_path / "h.trc", lines))


def test_header_garbage_is_an_error_naming_the_line(tmp_path):
    lines = trc_lines({"tip": approach(5)})
    path = write(tmp_path / "s.trc", lines[:1] + [" ".join(HEADER_NAMES)] + lines[2:])
    with pytest.raises(DataFormatError, match=r"s\.trc, line 2: the header names are separated neither by tabs"):
        read_trc(path)
    path = write(tmp_path / "v.trc", lines[:2] + ["100\t100\t5\t1 mm"] + lines[3:])
    with pytest.raises(DataFormatError, match=r"v\.trc, line 3: 4 header values .* split at tabs: give each name one"):
        read_trc(path)
    path = write(tmp_path / "k.trc", lines[:1] + ["DataRate\tUnits"] + ["100\tmm"] + lines[3:])
    with pytest.raises(DataFormatError, match=r"k\.trc, line 2: TRC header has no 'NumMarkers' .*: DataRate, Units\)"):
        read_trc(path)
    wide = trc_lines({"tip": approach(5)}, cells={})
    wide[7] += "\t1.0\t2.0"
    with pytest.raises(DataFormatError, match=r"w\.trc, line 8: 7 columns, but the header describes 5"):
        read_trc(write(tmp_path / "w.trc", wide))
    path = write(tmp_path / "d.trc", trc_lines({"tip": approach(5), "tip ": approach(5)}))
    with pytest.raises(DataFormatError, match=r"d\.trc, line 4: marker 'tip' is named 2 times"):
        read_trc(path, marker="tip")
    path = write(tmp_path / "e.trc", trc_lines({"tip": approach(5)})[:6])
    with pytest.raises(DataFormatError, match=r"e\.trc: no data rows after the TRC header"):
        read_trc(path)


def test_the_time_column_is_believed_over_data_rate(tmp_path):
    pos = approach(30)
    slow = read_trc(write(tmp_path / "a.trc", trc_lines({"tip": pos}, times=np.arange(30) / 50)))
    np.testing.assert_allclose(slow["t"], np.arange(30) / 50, atol=1e-9)
    assert slow.attrs["notes"] == [
        "header DataRate is 100 Hz, the Time column steps 0.02 s (50 Hz): the Time column is used"
    ]
    close = read_trc(write(tmp_path / "b.trc", trc_lines({"tip": pos}, times=np.arange(30) / 100.5)))
    assert close.attrs["notes"] == []  # 0.5 % apart: nothing to say
    lines = trc_lines({"tip": pos})
    lines[2] = lines[2].replace("100\t100\t30", "fast\t100\t30")
    assert read_trc(write(tmp_path / "c.trc", lines)).attrs["notes"] == [
        "header has DataRate 'fast' (not a rate in Hz): the Time column is used"
    ]


def test_without_a_time_column_the_data_rate_gives_t(tmp_path):
    pos = approach(12) * 1000
    df = read_trc(write(tmp_path / "f.trc", trc_lines({"tip": pos}, rate=60, lead=("Frame#",))))
    np.testing.assert_allclose(df["t"], np.arange(12) / 60, atol=1e-12)
    np.testing.assert_allclose(xyz(df), pos / 1000, atol=1e-9)
    assert df.attrs["notes"] == ["no Time column: t from Frame# and DataRate (60 Hz)"]
    lines = trc_lines({"tip": pos}, lead=("Frame#",))
    lines[2] = lines[2].replace("100\t100", "\t100", 1)
    with pytest.raises(DataFormatError, match=r"g\.trc, line 3: DataRate '', not a rate in Hz, and no Time column"):
        read_trc(write(tmp_path / "g.trc", lines))


def test_a_file_without_the_coordinate_line(tmp_path):
    pos = approach(6)
    df = read_trc(write(tmp_path / "c.trc", trc_lines({"tip": pos}, units="m", coordinates=False, blank_line=False)))
    np.testing.assert_allclose(xyz(df), pos, atol=1e-9)
    assert df.attrs["notes"] == ["no X1/Y1/Z1 line: the data start on line 5"]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    sep=st.sampled_from(["\t", ","]),
    padded=st.booleans(),
    repeated_names=st.booleans(),
    newline=st.sampled_from(["\n", "\r\n"]),
    trailing_blank=st.integers(0, 3),
    trailing_sep=st.booleans(),
    blank_line=st.booleans(),
    marker=st.sampled_from(["tip", "wrist"]),
)
def test_separators_and_spacing_do_not_change_the_values(
    tmp_path, sep, padded, repeated_names, newline, trailing_blank, trailing_sep, blank_line, marker
):
    markers = {"tip": approach(15) * 1000, "wrist": approach(15) * 1000 - 40}
    plain = read_trc(write(tmp_path / "plain.trc", trc_lines(markers)), marker=marker)
    lines = trc_lines(
        markers,
        sep=sep,
        padded=padded,
        repeated_names=repeated_names,
        trailing_sep=trailing_sep,
        blank_line=blank_line,
    )
    df = read_trc(write(tmp_path / "variant.trc", lines, newline=newline, trailing_blank=trailing_blank), marker=marker)
    np.testing.assert_array_equal(df.to_numpy(), plain.to_numpy())
    assert df.attrs == plain.attrs == {"notes": [], "units": "mm"}


# --- a folder of TRC files through the front door ----------------------------------------------------


def test_a_folder_of_two_trc_files_through_load_recordings(tmp_path):
    pos = approach(80)
    markers = {"tip": pos * 1000, "wrist": pos * 1000 + 50}
    write(tmp_path / "P1_1.trc", trc_lines(markers, padded=True))
    write(tmp_path / "P1_2.trc", trc_lines(markers, sep=",", num_frames="652"), newline="\r\n")
    rec = skilllib.load_recordings(tmp_path, marker="tip", contact_height=0.25)
    assert rec.keys() == [("P1", "1"), ("P1", "2")]
    assert rec.trials.status.tolist() == ["ok", "ok"]
    with pytest.raises(DataFormatError, match=r"P1_1\.trc, line 4: no marker 'elbow' \(markers: tip, wrist; "):
        skilllib.load_recordings(tmp_path / "P1_1.trc", marker="elbow", contact_height=0.25)


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    sep=st.sampled_from(["\t", ","]),
    edits=st.lists(
        st.tuples(st.floats(0, 1), st.integers(0, 3), st.text(alphabet="\t,\n\r 0159.-+eEinfNa#XYZ\x00é", max_size=4)),
        min_size=1,
        max_size=4,
    ),
    marker=st.sampled_from([None, "tip", "elbow"]),
)
def test_a_damaged_file_is_read_or_refused_with_a_data_format_error_never_another_exception(
    tmp_path, sep, edits, marker
):
    text = "\n".join(trc_lines({"tip": approach(6) * 1000, "wrist": approach(6)}, sep=sep)) + "\n"
    for where, cut, insert in edits:  # replace `cut` characters at a relative position by `insert`
        i = int(where * len(text))
        text = text[:i] + insert + text[i + cut :]
    path = tmp_path / "damaged.trc"
    path.write_bytes(text.encode())
    try:
        df = read_trc(path, marker=marker)
    except DataFormatError as e:
        assert str(e).startswith(str(path)) and "\n" not in str(e)
    else:
        assert list(df.columns) == ["t", "x", "y", "z", "contact"] and isinstance(df.attrs["notes"], list)
