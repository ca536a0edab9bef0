"""Tables whose rows do not line up with their header are refused, never shifted (issue 23, item 3).

A data row with more or fewer fields than the header is a DataFormatError naming the file, the physical
line and both counts, on the pyarrow fast path and the pandas path alike (a ``.gz`` file takes the
latter). A trailing comma on every line, the header included, lines up and reads as the file without it;
on the data rows only, it is refused with a message that says to remove it.
"""

from __future__ import annotations

import gzip
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from skilllib.recordings import DataFormatError, read_recordings, read_table

FS = 64.0  # Hz: the interval 1/64 s is exact in binary
HEADER = "participant,trial,t,x,y,z,contact"


def cohort_text(n_part: int = 2, n_trials: int = 2, n: int = 40) -> str:
    """The CSV text of plausible trials at FS: rest, a 0.1 m minimum-jerk approach, contact from sample 30."""
    tau = np.clip((np.arange(n) - 8) / 24, 0, 1)
    y = 0.1 * (1 - tau**3 * (10 - 15 * tau + 6 * tau**2))
    rows = [
        f"{p},{tr},{k / FS},0.01,{y[k]:.6f},-0.02,{int(k >= 30)}"
        for p in range(1, n_part + 1)
        for tr in range(1, n_trials + 1)
        for k in range(n)
    ]
    return "\n".join([HEADER, *rows]) + "\n"


def write(path: Path, text: str) -> Path:
    if path.suffix == ".gz":
        path.write_bytes(gzip.compress(text.encode()))
    else:
        path.write_text(text)
    return path


def with_trailing_comma(text: str, header: bool) -> str:
    lines = text.splitlines()
    start = 0 if header else 1
    return "\n".join(lines[:start] + [line + "," for line in lines[start:]]) + "\n"


def trial_keys(rec) -> list[tuple[str, str]]:
    return sorted(zip(rec.trials.participant, rec.trials.trial, strict=True))


@pytest.mark.parametrize("name", ["data.csv", "data.csv.gz"], ids=["plain", "gzip"])
def test_an_empty_trailing_field_on_every_data_row_is_ignored_and_said(tmp_path, name):
    """8 fields under a 7-name header, the 8th empty on every row (an exporter's trailing comma): the rows
    line up once it is dropped, so the file is read as the same recordings, never shifted by one column,
    and a note names the file (issue 23: ignored and said so); plain or compressed alike."""
    path = write(tmp_path / name, with_trailing_comma(cohort_text(), header=False))
    rec = read_recordings(path)
    ref = read_recordings(write(tmp_path / f"ref-{name}", cohort_text()))
    assert trial_keys(rec) == trial_keys(ref)
    for c in ("t", "x", "y", "z", "contact"):
        np.testing.assert_array_equal(rec.frame[c].to_numpy(), ref.frame[c].to_numpy())
    assert rec.notes == (f"{path}: every data row ends with a comma the header lacks: the empty last field is ignored",)


def test_a_trailing_field_not_empty_on_every_row_is_refused_naming_line_2(tmp_path):
    """The same file with one trailing field holding a value: the extra field is data, so the rows do not
    line up: refused at line 2 (the first data row) with both counts, never read shifted."""
    lines = with_trailing_comma(cohort_text(), header=False).splitlines()
    lines[9] += "0.5"
    path = write(tmp_path / "data.csv", "\n".join(lines) + "\n")
    with pytest.raises(DataFormatError) as info:
        read_recordings(path)
    msg = str(info.value)
    assert "\n" not in msg and str(path) in msg
    assert "Expected 7 fields in line 2, saw 8" in msg


@pytest.mark.parametrize("fields", [5, 8], ids=["short", "long"])
@pytest.mark.parametrize("name", ["data.csv", "data.csv.gz"], ids=["plain", "gzip"])
def test_one_row_of_another_width_in_the_middle_is_refused_naming_its_line(tmp_path, name, fields):
    """Line 50 (record 49) with 5 or 8 fields, the others 7: refused at line 50 with both counts."""
    lines = cohort_text().splitlines()
    cells = lines[49].split(",")
    lines[49] = ",".join(cells[:fields] if fields < len(cells) else [*cells, "0"])
    path = write(tmp_path / name, "\n".join(lines) + "\n")
    with pytest.raises(DataFormatError) as info:
        read_recordings(path)
    msg = str(info.value)
    assert "\n" not in msg
    assert str(path) in msg
    assert re.search(r"\bline 50\b", msg) and not re.search(r"\bline (2|49|51)\b", msg)
    assert f"Expected 7 fields in line 50, saw {fields}" in msg


def test_a_short_row_is_refused_by_read_table(tmp_path):
    """read_table itself refuses the short row (it would otherwise read its missing cells as empty)."""
    lines = cohort_text().splitlines()
    lines[9] = ",".join(lines[9].split(",")[:6])
    path = write(tmp_path / "data.csv", "\n".join(lines) + "\n")
    with pytest.raises(DataFormatError, match=r"Expected 7 fields in line 10, saw 6$"):
        read_table(path)


@pytest.mark.parametrize("name", ["data.csv", "data.csv.gz"], ids=["plain", "gzip"])
def test_trailing_comma_on_every_line_reads_as_the_file_without_it(tmp_path, name):
    """Header and rows all end with a comma: they line up; the same trials, times and positions as without."""
    text = cohort_text()
    want = read_recordings(write(tmp_path / ("ref" + name), text))
    got = read_recordings(write(tmp_path / name, with_trailing_comma(text, header=True)))
    assert trial_keys(got) == trial_keys(want) == [(p, t) for p in "12" for t in "12"]
    assert list(got.trials.status) == list(want.trials.status) == ["ok"] * 4
    a, b = got.frame, want.frame
    assert list(a.participant) == list(b.participant) and list(a.trial) == list(b.trial)
    for c in ("t", "x", "y", "z", "contact"):
        np.testing.assert_array_equal(np.asarray(a[c], dtype=float), np.asarray(b[c], dtype=float))


def test_trailing_comma_on_the_header_only_is_refused(tmp_path):
    """An empty 8th name over 7-field rows: refused at line 2 with the fix for line 1."""
    lines = cohort_text().splitlines()
    path = write(tmp_path / "data.csv", "\n".join([lines[0] + ","] + lines[1:]) + "\n")
    with pytest.raises(DataFormatError) as info:
        read_recordings(path)
    msg = str(info.value)
    assert "Expected 8 fields in line 2, saw 7" in msg
    assert "remove the trailing comma" in msg


def test_blank_lines_are_not_rows_of_another_width(tmp_path):
    """A blank line is not a short row: read_table keeps it as an empty row, as before."""
    lines = cohort_text().splitlines()
    path = write(tmp_path / "data.csv", "\n".join([*lines[:5], "", *lines[5:]]) + "\n")
    table, where = read_table(path)
    assert isinstance(table, pd.DataFrame) and len(table) == len(lines)
    assert list(where[:6]) == [2, 3, 4, 5, 6, 7]
