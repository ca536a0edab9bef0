"""Delimited tables as labs write them: the separator detected (comma, tab, semicolon) or given (``--sep``),
time in ms or us (``--time-unit``), a table without participant/trial columns as one recording, and a
stated unit believed (a whole-body span is no longer "not metres"). Both paths are tested: the fast
reader (no option) and the mapping (``read_table`` + ``map_frame``); also the per-trial CSVs of a folder.
"""

from __future__ import annotations

import gzip
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from skilllib.pipeline import main
from skilllib.recordings import (
    MAX_KNOWN_RANGE_M,
    DataFormatError,
    detect_sep,
    file_ids,
    load_recordings,
    parse_sep,
    read_any,
    read_csv_table,
    read_folder,
    read_recordings,
    read_table,
)

FS = 64.0  # Hz: 1/64 s is exact in binary
REAL = Path(__file__).resolve().parents[2] / "data" / "real"
KINESIS = REAL / "kinesis_rtgData.txt"
SEPS = {",": "commas", "\t": "tabs", ";": "semicolons"}


def frame(n_part: int = 2, n_trials: int = 2, n: int = 40, scale: float = 1.0) -> pd.DataFrame:
    """Plausible trials at FS: rest (with 0.05 mm of seeded noise: no frozen samples), a 0.1 m (times
    ``scale``) approach, contact from sample 30."""
    tau = np.clip((np.arange(n) - 8) / 24, 0, 1)
    y = 0.1 * (1 - tau**3 * (10 - 15 * tau + 6 * tau**2))
    noise = np.random.default_rng(3).normal(0, 5e-5, (n, 3))
    rows = [
        {
            "participant": f"P{p}",
            "trial": str(tr),
            "t": k / FS,
            "x": (0.01 + noise[k, 0]) * scale,
            "y": (y[k] + noise[k, 1]) * scale,
            "z": (-0.02 + noise[k, 2]) * scale,
            "contact": int(k >= 30),
        }
        for p in range(1, n_part + 1)
        for tr in range(1, n_trials + 1)
        for k in range(n)
    ]
    return pd.DataFrame(rows)


def write(df: pd.DataFrame, path: Path, sep: str = ",") -> Path:
    text = df.to_csv(index=False, sep=sep, lineterminator="\n")
    if path.suffix == ".gz":
        path.write_bytes(gzip.compress(text.encode()))
    else:
        path.write_text(text)
    return path


def keys(rec) -> list[tuple[str, str]]:
    return list(zip(rec.trials.participant, rec.trials.trial, strict=True))


# --- the separator ------------------------------------------------------------------------------------


@pytest.mark.parametrize("sep", [",", "\t", ";"], ids=["comma", "tab", "semicolon"])
@pytest.mark.parametrize("name", ["rec.csv", "rec.csv.gz", "rec.txt"], ids=["plain", "gzip", "txt"])
def test_a_table_is_read_whatever_its_separator_on_both_paths(tmp_path, sep, name):
    """The same recordings written with commas, tabs or semicolons read alike: the fast reader (no
    option), the mapping path (an option given) and read_table, plain or compressed."""
    df = frame()
    path = write(df, tmp_path / name, sep)
    want = read_recordings(write(df, tmp_path / "ref.csv"))
    fast = read_recordings(path)
    mapped = load_recordings(path, units="m")
    table, lines = read_table(path)
    for rec in (fast, mapped):
        assert keys(rec) == keys(want)
        assert rec.trials.status.tolist() == ["ok"] * 4
        np.testing.assert_allclose(rec.frame[["t", "x", "y", "z"]], want.frame[["t", "x", "y", "z"]])
    assert list(table.columns) == list(df.columns) and lines[0] == 2 and table.attrs["sep"] == sep


def test_detection_reads_the_header_and_the_next_lines():
    assert detect_sep("a\tb\tc\n1\t2\t3\n") == "\t"
    assert detect_sep("a;b;c\n1,5;2,5;3\n") == ";"  # decimal commas do not fool it
    assert detect_sep("a,b,c\n1,2,3\n") == ","
    assert detect_sep("a,b;c\n1,2;3\n4,5;6\n") == ","  # both consistent: the one with more fields
    assert detect_sep("a,b,c\n1,2,3,\n") == ","  # none consistent: the header's (alignment then reports)
    assert detect_sep("abc\n1\n") == ","


@pytest.mark.parametrize("value, sep", [(",", ","), (";", ";"), ("tab", "\t"), ("\\t", "\t"), ("\t", "\t")])
def test_sep_values(value, sep):
    assert parse_sep(value) == sep


def test_an_unknown_sep_is_refused():
    with pytest.raises(DataFormatError, match="--sep: unknown separator '|'"):
        parse_sep("|")


def test_sep_given_overrides_detection(tmp_path):
    """A semicolon file whose cells hold commas: detection picks ';' (consistent), and ``sep=','``
    forced reads one column, with a message saying how the line was split and which separator it seems
    to use."""
    path = write(frame(), tmp_path / "semi.csv", ";")
    assert keys(read_recordings(path, sep=";")) == keys(read_recordings(path))
    with pytest.raises(DataFormatError) as e:
        read_recordings(path, sep=",")
    msg = str(e.value)
    assert "\n" not in msg
    assert "columns found (split at commas): participant;trial;t;x;y;z;contact" in msg
    assert "split at semicolons: give the separator with --sep" in msg


@pytest.mark.parametrize("options", [{}, {"units": "m"}], ids=["fast", "mapping"])
def test_a_missing_column_message_says_how_the_line_was_split(tmp_path, options):
    path = write(frame().drop(columns="z"), tmp_path / "tabs.tsv", "\t")
    with pytest.raises(DataFormatError) as e:
        load_recordings(path, **options)
    msg = str(e.value)
    assert re.search(r"tabs\.tsv: required column 'z' missing \(columns found \(split at tabs\): participant", msg)


def test_columns_option_naming_an_absent_column_says_how_the_line_was_split(tmp_path):
    path = write(frame(), tmp_path / "tabs.txt", "\t")
    with pytest.raises(DataFormatError, match=r"columns found \(split at tabs\): participant, trial, t"):
        load_recordings(path, columns="time=t")


@pytest.mark.parametrize("sep", ["\t", ";"], ids=["tab", "semicolon"])
def test_a_ragged_row_names_its_physical_line_and_the_separator(tmp_path, sep):
    lines = write(frame(), tmp_path / "x.csv", sep).read_text().splitlines()
    lines[9] += f"{sep}0"
    path = tmp_path / "ragged.csv"
    path.write_text("\n".join(lines) + "\n")
    for read in (read_recordings, lambda p: load_recordings(p, units="m"), read_csv_table):
        with pytest.raises(DataFormatError) as e:
            read(path)
        msg = str(e.value)
        assert "Expected 7 fields in line 10, saw 8" in msg and f"split at {SEPS[sep]}" in msg


def test_read_csv_table_detects_the_separator_and_keeps_ids_as_text(tmp_path):
    df = frame().assign(participant="01")
    table = read_csv_table(write(df, tmp_path / "t.csv", "\t"))
    assert table.attrs["sep"] == "\t"
    assert table["participant"].tolist()[0] == "01" and table["t"].dtype == float


def test_a_cell_that_is_not_a_number_names_line_and_column_in_a_tab_table(tmp_path):
    lines = write(frame(), tmp_path / "x.tsv", "\t").read_text().splitlines()
    cells = lines[14].split("\t")
    cells[4] = "abc"
    lines[14] = "\t".join(cells)
    path = tmp_path / "bad.tsv"
    path.write_text("\n".join(lines) + "\n")
    for options in ({}, {"units": "m"}):
        with pytest.raises(DataFormatError, match=r"bad\.tsv, line 15, column 'y': 'abc' is not a number"):
            load_recordings(path, **options)


# --- time units ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("unit, factor", [("s", 1.0), ("ms", 1e3), ("us", 1e6)])
def test_time_unit_divides_t_into_seconds(tmp_path, unit, factor):
    df = frame()
    path = write(df.assign(t=df["t"] * factor), tmp_path / "rec.csv", "\t")
    rec = load_recordings(path, time_unit=unit)
    assert rec.fs == pytest.approx(FS)
    np.testing.assert_allclose(rec.frame["t"], df["t"], rtol=1e-12)


def test_milliseconds_without_the_option_name_the_option(tmp_path):
    df = frame()
    path = write(df.assign(t=df["t"] * 1000), tmp_path / "ms.csv")
    with pytest.raises(DataFormatError, match=r"milliseconds.*divide t by 1000, or give the unit: --time-unit ms"):
        read_recordings(path)


def test_an_unknown_time_unit_is_refused(tmp_path):
    with pytest.raises(DataFormatError, match="unknown time unit 'min'"):
        load_recordings(write(frame(), tmp_path / "r.csv"), time_unit="min")


# --- a table of one recording -------------------------------------------------------------------------


@pytest.mark.parametrize(
    "name, ids", [("lab_walk3.csv", ("lab", "walk3")), ("walk.tsv.gz", ("walk", "walk")), ("P1_2.txt", ("P1", "2"))]
)
@pytest.mark.parametrize("options", [{}, {"units": "m"}], ids=["fast", "mapping"])
def test_a_table_without_ids_is_one_recording_named_after_the_file(tmp_path, name, ids, options):
    """No participant and no trial column: one recording, ids from the file's stem split at its last '_'
    (as a single C3D file); blank lines stay blank."""
    df = frame(1, 1).drop(columns=["participant", "trial"])
    path = write(df, tmp_path / name, "\t")
    rec = load_recordings(path, **options)
    assert keys(rec) == [ids] and rec.trials.status.tolist() == ["ok"]
    assert file_ids(path) == ids
    assert read_any(path)[0][["participant", "trial"]].drop_duplicates().values.tolist() == [list(ids)]


def test_one_recording_keeps_blank_lines_blank_and_names_lines(tmp_path):
    df = frame(1, 1).drop(columns=["participant", "trial"])
    lines = write(df, tmp_path / "x.csv").read_text().splitlines()
    lines.insert(5, "")
    cells = lines[20].split(",")
    cells[2] = "oops"
    lines[20] = ",".join(cells)
    path = tmp_path / "one_rec.csv"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataFormatError, match=r"one_rec\.csv, line 21, column 'y': 'oops' is not a number"):
        read_recordings(path)


def test_a_name_pattern_names_a_one_recording_table(tmp_path):
    df = frame(1, 1).drop(columns=["participant", "trial"])
    path = write(df, tmp_path / "S07-run2.csv")
    rec = load_recordings(path, name_pattern=r"(?P<participant>S\d+)-(?P<trial>.*)")
    assert keys(rec) == [("S07", "run2")]


def test_a_table_with_only_one_id_column_still_needs_the_other(tmp_path):
    path = write(frame().drop(columns="trial"), tmp_path / "p.csv")
    with pytest.raises(DataFormatError, match="required column 'trial' missing"):
        read_recordings(path)


# --- a folder of per-trial CSVs: the same separator logic and alignment check -----------------------


def test_a_folder_of_per_trial_tables_detects_each_separator_and_refuses_shifted_rows(tmp_path):
    root = tmp_path / "trials"
    root.mkdir()
    one = frame(1, 1).drop(columns=["participant", "trial"])
    write(one, root / "P1_1.csv", ",")
    write(one, root / "P1_2.tsv.csv", "\t")
    write(one, root / "P2_1.csv", ";")
    lines = write(one, root / "P2_2.csv").read_text().splitlines()
    lines[6] += ",9"
    (root / "P2_2.csv").write_text("\n".join(lines) + "\n")
    got, problems = read_folder(root)
    assert sorted(set(zip(got.participant, got.trial))) == [("P1", "1"), ("P1", "2.tsv"), ("P2", "1")]
    assert [(q.participant, q.trial) for q in problems] == [("P2", "2")]
    assert "Expected 5 fields in line 7, saw 6" in problems[0].reason
    ms = tmp_path / "ms"
    ms.mkdir()
    write(one.assign(t=one["t"] * 1000), ms / "P1_1.csv", "\t")
    write(one.assign(t=one["t"] * 1000), ms / "P1_2.csv", ";")
    rec = load_recordings(ms, time_unit="ms")  # every CSV of the folder in ms
    assert rec.fs == pytest.approx(FS) and rec.trials.status.tolist() == ["ok", "ok"]


# --- units: a stated unit is believed -----------------------------------------------------------------


def test_a_whole_body_span_is_read_when_the_unit_is_stated(tmp_path):
    """Trials spanning 4 m in mm: refused as "not metres" when nothing states the unit (the guess), read
    with --units mm (believed); a span beyond MAX_KNOWN_RANGE_M is still a glitch."""
    df = frame(scale=40.0)  # 4 m, in m
    mm = df.assign(**{c: df[c] * 1000 for c in ("x", "y", "z")})
    path = write(mm, tmp_path / "gait.csv")
    with pytest.raises(DataFormatError, match="millimetres or centimetres"):
        read_recordings(path)
    rec = load_recordings(path, units="mm")
    assert rec.trials.status.tolist() == ["ok"] * 4
    in_m = write(df, tmp_path / "gait_m.csv")
    with pytest.raises(DataFormatError, match="not metres"):
        load_recordings(in_m, time_unit="s")  # an option, but no unit: still guessed
    assert load_recordings(in_m, units="m").trials.status.tolist() == ["ok"] * 4
    glitch = df.copy()
    glitch.loc[5:20, "x"] = 1.5 * MAX_KNOWN_RANGE_M  # sustained: not a single-frame jump a repair would fix
    rec = load_recordings(write(glitch, tmp_path / "glitch.csv"), units="m")
    assert rec.trials.status.tolist() == ["invalid", "ok", "ok", "ok"]
    assert "more than 20 m, with the unit stated): a glitch" in rec.trials.reason[0]


# --- a real tab-separated export: kinesis (Optotrak, ms, mm) ----------------------------------------


def test_kinesis_tab_separated_export_reads_with_time_unit_ms():
    """The kinesis reach-to-grasp export (tabs, ms, mm, 45 trials): the separator detected, its own
    column names mapped, t in ms divided; ~85 Hz."""
    assert detect_sep(KINESIS.read_text()[:5000]) == "\t"
    rec = load_recordings(
        KINESIS,
        columns="subjName=participant,trialN=trial,globalTime=t,indexXraw=x,indexYraw=y,indexZraw=z",
        time_unit="ms",
        units="mm",
        contact_height=-10.0,
    )
    assert len(rec) == 45 and set(rec.trials.participant) == {"cc25"}
    assert 84 < rec.fs < 86
    assert rec.trials.first_line.iloc[0] == 2
    raw = pd.read_csv(KINESIS, sep="\t", nrows=1)
    assert rec.frame["x"].iloc[0] == pytest.approx(raw["indexXraw"].iloc[0] / 1000)
    assert rec.frame["t"].iloc[0] == pytest.approx(raw["globalTime"].iloc[0] / 1000)
    assert (rec.trials.status == "ok").sum() >= 30


def test_kinesis_without_options_lists_the_columns_split_at_tabs():
    with pytest.raises(DataFormatError) as e:
        read_recordings(KINESIS)
    msg = str(e.value)
    assert "required column 'participant' missing (columns found (split at tabs): subjName, IOD, trialN" in msg


def test_kinesis_through_the_command_line(tmp_path, capsys):
    code = main(
        [
            "run",
            "--quiet",
            "--no-figures",
            "--data",
            str(KINESIS),
            "--out",
            str(tmp_path / "o"),
            "--columns",
            "subjName=participant,trialN=trial,globalTime=t,indexXraw=x,indexYraw=y,indexZraw=z",
            "--time-unit",
            "ms",
            "--units",
            "mm",
            "--sep",
            "tab",
            "--contact-height=-10",
        ]
    )
    out = capsys.readouterr().out
    assert code in (0, 3), out  # 3: too few selected trials to cluster is a result, not a reading error
    assert "trials read: 45 from 1 participant(s)" in out
