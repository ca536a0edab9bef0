"""Edge cases of reading and validating recordings (skilllib.recordings, skilllib.recordings) that the main tests
of tests/test_data.py leave open: files without a final line end, a byte-order mark, folders and damaged
archives, physical line numbers, and the values the validation gives back (rates, reasons, resampled
trials). Expected values come from the definitions in the module docstrings or from the csv module.
"""

from __future__ import annotations

import csv
import gzip
import io
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from skilllib.recordings import (
    COLUMNS,
    MAX_TYPICAL_SPEED,
    MIN_RATE_HZ,
    DataFormatError,
    read_recordings,
    read_table,
    record_lines,
    recordings_from_frame,
)

FS = 64.0  # Hz: the interval 1/64 s is exact in binary
DT = 1 / FS


def trial_frame(participant="1", trial="1", n=40, contact_at=30, t0=0.0) -> pd.DataFrame:
    """A plausible trial at FS: rest, a 0.1 m downward minimum-jerk approach, contact from ``contact_at``."""
    tau = np.clip((np.arange(n) - 8) / (contact_at - 6), 0, 1)
    y = 0.1 * (1 - tau**3 * (10 - 15 * tau + 6 * tau**2))
    return pd.DataFrame(
        {
            "participant": participant,
            "trial": trial,
            "t": t0 + np.arange(n) * DT,
            "x": 0.01,
            "y": y,
            "z": -0.02,
            "contact": (np.arange(n) >= contact_at).astype(int),
        }
    )


def cohort_frame(n_part=2, n_trials=3, **kw) -> pd.DataFrame:
    return pd.concat(
        [trial_frame(str(p), str(tr), **kw) for p in range(1, n_part + 1) for tr in range(1, n_trials + 1)],
        ignore_index=True,
    )


def status(rec, participant, trial) -> tuple[str, str]:
    row = rec.trials.set_index(["participant", "trial"]).loc[(str(participant), str(trial))]
    return row.status, row.reason


# --- csvtable: physical lines --------------------------------------------------------------------


def csv_module_lines(text: str) -> list[int]:
    """The first physical line of each record after the header, counted by the csv module."""
    reader = csv.reader(io.StringIO(text))
    starts, end = [], 0
    for _ in reader:
        starts.append(end + 1)
        end = reader.line_num
    return starts[1:]


@pytest.mark.parametrize("final_newline", [True, False], ids=["ends-with-newline", "no-final-newline"])
def test_record_lines_one_per_line_with_or_without_a_final_line_end(final_newline):
    """Header on line 1, records on lines 2 to 4, a blank line 3 included: [2, 3, 4] whether or not the
    file ends with a line end (catches a record too many or too few at the end)."""
    text = "a,b\n1,2\n\n3,4" + ("\n" if final_newline else "")
    assert record_lines(text).tolist() == [2, 3, 4]


@settings(max_examples=60, deadline=None)
@given(rows=st.lists(st.sampled_from(["1,2", "", "x,y", " ,3"]), min_size=1, max_size=12), final_newline=st.booleans())
def test_record_lines_without_quotes_agree_with_the_csv_module(rows, final_newline):
    """The fast path for text without quotes counts the records the csv module counts (blank lines are
    records), at the lines where they start."""
    text = "\n".join(["a,b", *rows]) + ("\n" if final_newline else "")
    expected = csv_module_lines(text)
    assert record_lines(text).tolist() == expected


def test_a_bad_cell_on_the_last_line_of_a_file_without_a_final_line_end(tmp_path):
    """The last record of a file that does not end with a line end still has its line: the message names
    it (a record count one short would misalign or lose it)."""
    df = cohort_frame(1, 2).astype({"x": object})
    last = len(df) - 1
    df.loc[last, "x"] = "oops"
    p = tmp_path / "rec.csv"
    p.write_text(df.to_csv(index=False, lineterminator="\n").rstrip("\n"))
    with pytest.raises(DataFormatError, match=rf"rec\.csv, line {last + 2}, column 'x': 'oops' is not a number"):
        read_recordings(p)


def test_read_table_gives_the_physical_line_of_every_row(tmp_path):
    """read_table: one text row per record and its physical line (blank lines kept as rows)."""
    p = tmp_path / "t.csv"
    p.write_text("participant,trial\n01,a\n\nNA,b")
    df, lines = read_table(p)
    assert df.participant.tolist() == ["01", "", "NA"] and lines.tolist() == [2, 3, 4]


def test_too_many_fields_after_a_multi_line_cell_name_the_physical_line(tmp_path):
    """A quoted cell over lines 2-4, then a row of 4 fields on line 6 (the parser's record 4): the whole
    message, with the physical line (catches the parser's record number left as it is, or shifted)."""
    p = tmp_path / "q.csv"
    p.write_text('a,b,note\n1,2,"x\ny\nz"\n3,4,5\n5,6,7,8\n7,8,9\n')
    with pytest.raises(DataFormatError) as e:
        read_table(p)
    assert str(e.value) == f"{p}: not a valid CSV table: Expected 3 fields in line 6, saw 4"


def test_too_many_fields_in_a_file_without_quotes(tmp_path):
    """Without quotes the parser's line is the physical line: the message in full, without pandas' prefix."""
    p = tmp_path / "f.csv"
    p.write_text("a,b,note\n1,2,3\n5,6,7,8\n")
    with pytest.raises(DataFormatError) as e:
        read_table(p)
    assert str(e.value) == f"{p}: not a valid CSV table: Expected 3 fields in line 3, saw 4"


def test_a_quoted_cell_after_a_space_is_one_cell(tmp_path):
    """``1, 2, "x, y"``: spaces after the separators are skipped, so the quotes still hold the comma."""
    p = tmp_path / "s.csv"
    p.write_text('a,b,note\n1, 2, "x, y"\n')
    df, lines = read_table(p)
    assert df.iloc[0].tolist() == ["1", "2", "x, y"] and lines.tolist() == [2]


def test_record_lines_of_a_quoted_header_alone_are_an_empty_list_of_integers():
    assert record_lines('"a",b\n').dtype.kind == "i" and len(record_lines('"a",b\n')) == 0


# --- csvtable: opening the file ------------------------------------------------------------------


def test_blank_lines_before_the_header_raise_an_error_naming_the_file(tmp_path):
    """Blank lines before the header leave pandas no columns: a DataFormatError naming the file and
    saying where the header must be (not a pandas exception, not "file is empty" for a file with data)."""
    p = tmp_path / "blank_first.csv"
    p.write_text("\n\n" + ",".join(COLUMNS) + "\n1,1,0,0,0,0,0\n")
    with pytest.raises(DataFormatError, match=rf"^{re.escape(str(p))}: no column names on line 1") as e:
        read_recordings(p)
    assert "empty" not in str(e.value)


def test_a_byte_order_mark_is_not_part_of_the_first_column_name(tmp_path):
    """Spreadsheets write UTF-8 with a byte-order mark: the first column is still 'participant'."""
    df = cohort_frame()
    p = tmp_path / "bom.csv"
    p.write_bytes(b"\xef\xbb\xbf" + df.to_csv(index=False).encode("utf-8"))
    rec = read_recordings(p)
    assert len(rec) == len(df.groupby(["participant", "trial"])) and (rec.trials.status == "ok").all()


def test_a_folder_is_not_a_csv_file(tmp_path):
    with pytest.raises(DataFormatError, match=rf"^{tmp_path}: is a directory, not a CSV file$"):
        read_recordings(tmp_path)


@pytest.mark.parametrize("damage", ["not-gzip", "cut-short"])
def test_a_damaged_archive_cannot_be_decompressed(tmp_path, damage):
    """A .gz that is not gzip, or is cut short, raises a one-line error naming the file and the cause."""
    data = gzip.compress(cohort_frame().to_csv(index=False).encode())
    p = tmp_path / "rec.csv.gz"
    p.write_bytes(b"plain text, not gzip" * 5 if damage == "not-gzip" else data[: len(data) // 2])
    with pytest.raises(DataFormatError, match=r"rec\.csv\.gz: cannot be decompressed: \S"):
        read_recordings(p)


# --- data: what validation gives back --------------------------------------------------------------


def test_a_table_that_is_not_a_dataframe_is_named_by_its_type():
    with pytest.raises(DataFormatError, match=r"^<DataFrame>: expected a pandas DataFrame, got dict$"):
        recordings_from_frame({c: [] for c in COLUMNS})


N = 40  # samples per trial
JITTER = 0.25  # of DT: one late sample of trial A/2
GAP_AT = 20  # sample of trial A/3 after which 3 frames are missing (an interval of 4 DT)
GAP_INTERVALS = 4


def mixed_file(tmp_path) -> Path:
    """A/1 regular; A/2 one sample JITTER x DT late (resampled); A/3 a gap of GAP_INTERVALS x DT
    (invalid); B/1 three samples (invalid); B/2 like A/2 (after an invalid trial). Written by pandas with
    every digit (the library's writer rounds t to 0.1 ms), so that the time stamps are exact multiples of DT."""
    a2 = trial_frame("A", "2")
    a2.loc[10, "t"] += JITTER * DT
    a3 = trial_frame("A", "3")
    a3.loc[GAP_AT:, "t"] += (GAP_INTERVALS - 1) * DT
    b2 = trial_frame("B", "2")
    b2.loc[5, "t"] -= JITTER * DT
    df = pd.concat([trial_frame("A", "1"), a2, a3, trial_frame("B", "1", n=3, contact_at=2), b2], ignore_index=True)
    p = tmp_path / "mixed.csv"
    df.to_csv(p, index=False)
    return p


def test_the_trial_table_states_every_trial_as_the_file_has_it(tmp_path):
    """Counts, first physical lines, statuses, reasons and timing of each trial, by hand from the layout
    (header on line 1, trials of 40, 40, 40, 3 and 40 rows); a trial after an invalid one is still checked
    and resampled."""
    rec = read_recordings(mixed_file(tmp_path))
    tr = rec.trials
    assert tr.columns.tolist() == [
        "participant",
        "trial",
        "n_samples",
        "first_line",
        "status",
        "reason",
        "timing",
        "repairs",
        "n_repaired",
        "n_dropped",
    ]
    assert list(zip(tr.participant, tr.trial)) == [("A", "1"), ("A", "2"), ("A", "3"), ("B", "1"), ("B", "2")]
    assert tr.n_samples.tolist() == [N, N, N, 3, N]
    assert tr.first_line.tolist() == [2, 2 + N, 2 + 2 * N, 2 + 3 * N, 2 + 3 * N + 3]
    assert tr.status.tolist() == ["ok", "ok", "invalid", "invalid", "ok"]
    gap_line = 2 + 2 * N + GAP_AT
    assert tr.reason[2] == (
        f"gap in the time stamps: {GAP_INTERVALS * DT:.4f} s before line {gap_line}, "
        f"{GAP_INTERVALS:.1f} sampling intervals (the file samples every {DT:.4f} s; "
        f"at most 3.5 are bridged by resampling)"
    )
    assert tr.reason[3] == "too few samples (3; need at least 5)"
    assert tr.reason[[0, 1, 4]].tolist() == ["", "", ""]
    resampled = f"resampled: jitter up to {1e3 * JITTER * DT:.2g} ms"
    assert tr.timing.tolist() == ["", resampled, "", "", resampled]
    assert rec.fs == FS and rec.source == str(tmp_path / "mixed.csv") and len(rec) == 5


def test_a_resampled_trial_is_given_on_the_grid_and_the_others_as_recorded(tmp_path):
    """rec.trial: A/2 on the grid k DT (k = 0 .. N-1) with the positions the samples had where they sat on
    the grid and contact from the first contact sample; A/1 and the invalid A/3 as recorded."""
    rec = read_recordings(mixed_file(tmp_path))
    a2 = rec.trial("A", "2")
    grid = np.arange(N) * DT
    np.testing.assert_array_equal(a2.t, grid)
    want = trial_frame("A", "2")
    on = np.arange(N) != 10  # every sample but the late one sits on the grid
    np.testing.assert_allclose(a2.pos[on], want[["x", "y", "z"]].to_numpy()[on], atol=1e-5)
    np.testing.assert_array_equal(a2.contact, want.contact.to_numpy() == 1)
    assert (a2.participant, a2.trial) == ("A", "2")
    a3 = rec.trial("A", "3")
    assert len(a3.t) == N and a3.t[GAP_AT] - a3.t[GAP_AT - 1] == pytest.approx(GAP_INTERVALS * DT, abs=1e-4)
    a1 = rec.trial("A", "1")
    np.testing.assert_allclose(a1.t, grid, atol=1e-4)
    assert a1.contact.dtype == bool and a1.contact.sum() == N - 30


def test_the_frame_keeps_every_sample_with_text_ids_and_numbers(tmp_path):
    """rec.frame: all 163 samples in file order, ids as text, t/x/y/z/contact as floats, 0-based index."""
    rec = read_recordings(mixed_file(tmp_path))
    f = rec.frame
    assert f.columns.tolist() == list(COLUMNS) and len(f) == 4 * N + 3
    assert f.index.tolist() == list(range(len(f)))
    assert f.participant.tolist() == ["A"] * 3 * N + ["B"] * (N + 3)
    assert all(isinstance(v, str) for v in f.trial) and f.trial.iloc[3 * N] == "1"
    assert f.t.dtype == float and f.contact.dtype == float
    assert rec.keys() == [("A", "1"), ("A", "2"), ("A", "3"), ("B", "1"), ("B", "2")]


def test_a_file_whose_trials_are_all_invalid_is_read_with_no_rate():
    """Every trial too short: no rate can be read (fs is NaN), no error, every trial invalid."""
    df = cohort_frame(2, 2, n=4, contact_at=2)
    rec = recordings_from_frame(df)
    assert np.isnan(rec.fs) and (rec.trials.status == "invalid").all() and len(rec) == 4
    assert (rec.trials.timing == "").all()


def test_an_unknown_trial_is_a_key_error_naming_it():
    rec = recordings_from_frame(cohort_frame(1, 1))
    with pytest.raises(KeyError, match=r"no trial '9' of participant '1' in <DataFrame>"):
        rec.trial(1, 9)


def test_extra_columns_named_like_a_pandas_index_are_ignored():
    """A frame reset twice by pandas carries columns 'level_0' and 'index': other columns are ignored,
    these too (the validation must not add an index column of its own, which would clash with them)."""
    df = cohort_frame(1, 2).reset_index().reset_index()
    assert {"level_0", "index"} <= set(df.columns)
    rec = recordings_from_frame(df)
    assert rec.frame.columns.tolist() == list(COLUMNS) and (rec.trials.status == "ok").all()


def spoil(df: pd.DataFrame, column: str, row: int, value) -> pd.DataFrame:
    df = df.astype({column: object})
    df.loc[row, column] = value
    return df


@pytest.mark.parametrize(
    "column, value, what",
    [
        ("participant", " ", "participant is empty"),
        ("trial", "", "trial is empty"),
        ("contact", 2, "contact must be 0 or 1, got 2"),
        ("t", "1.2.3", "'1.2.3' is not a number"),
    ],
)
def test_a_bad_cell_is_named_by_file_line_and_column(tmp_path, column, value, what):
    """The whole place of a bad cell: the file, the physical line (data row 7 is line 9) and the column,
    in that order, then what is wrong (catches the file left out of the message)."""
    p = tmp_path / "bad.csv"
    spoil(cohort_frame(), column, 7, value).to_csv(p, index=False)
    with pytest.raises(DataFormatError) as e:
        read_recordings(p)
    assert str(e.value) == f"{p}, line 9, column '{column}': {what}"


def test_a_bad_cell_of_a_dataframe_is_named_by_its_row():
    with pytest.raises(DataFormatError) as e:
        recordings_from_frame(spoil(cohort_frame(), "participant", 5, ""), source="mine")
    assert str(e.value) == "mine, row 5, column 'participant': participant is empty"


def test_places_name_where_each_row_came_from():
    """With ``places`` (one text per row, as for tables read from several files), reasons and errors
    name the place of the row."""
    df = cohort_frame(1, 2).astype({"x": object, "y": object})
    df.loc[N + 3, "y"] = np.nan
    places = np.array([f"{'ab'[i // N]}.c3d, frame {i % N}" for i in range(len(df))])
    rec = recordings_from_frame(df, "folder", places=places)
    assert status(rec, 1, 2) == ("ok", "") and rec.trials.repairs.iloc[1].endswith("(b.c3d, frame 3)")
    rec = recordings_from_frame(df, "folder", places=places, max_gap_s=0.0)  # not filled: at rest, cut before
    assert (
        status(rec, 1, 2) == ("ok", "") and rec.trials.repairs.iloc[1] == "4 samples before a long gap at rest dropped"
    )
    df.loc[N + 5, "x"] = "?"
    with pytest.raises(DataFormatError, match=r"^folder, b\.c3d, frame 5, column 'x': '\?' is not a number$"):
        recordings_from_frame(df, "folder", places=places)


@pytest.mark.parametrize(
    "problem, what",
    [
        ("ms", "time stamps look like milliseconds"),
        ("mixed", "mixed sampling rates (6 trials at 64 Hz, 6 trials at 32 Hz)"),
        ("mm", "positions look like millimetres or centimetres"),
    ],
)
def test_a_file_level_problem_names_the_file_first(tmp_path, problem, what):
    """Time in milliseconds, mixed rates, positions in millimetres: the message starts with the file."""
    df = cohort_frame(2, 6)
    if problem == "ms":
        df["t"] *= 1e3
    elif problem == "mixed":
        df.loc[df.participant == "2", "t"] *= 2
    else:
        df[["x", "y", "z"]] *= 1e3
    p = tmp_path / "f.csv"
    df.to_csv(p, index=False)
    with pytest.raises(DataFormatError) as e:
        read_recordings(p)
    assert str(e.value).startswith(f"{p}: {what}")


# --- data: reasons of invalid trials name the right lines -------------------------------------------


def read_spoiled(tmp_path, edit, trial="2") -> tuple[str, str]:
    """2 x 10 trials written with every digit; ``edit(df)`` spoils participant 1 trial 2 (file lines
    2 + N .. 1 + 2N); returns the status and reason of participant 1 ``trial`` after checking that the
    trials of participant 2 are ok."""
    df = edit(cohort_frame(2, 10))
    p = tmp_path / "s.csv"
    df.to_csv(p, index=False)
    rec = read_recordings(p)
    assert (rec.trials[rec.trials.participant == "2"].status == "ok").all()
    return status(rec, 1, trial)


FIRST = 2 + N  # file line of the first sample of participant 1 trial 2


def test_rows_of_a_trial_split_by_a_single_row_name_both_parts(tmp_path):
    """Trial 1/2 with its first 10 samples, one row of trial 1/3, then its other 30 samples: the message
    names the first line, the last line before the foreign row and the first line after it (a single
    foreign row is a step of 2 in the row numbers: catches ``> 2`` for ``> 1``)."""

    def edit(df):
        rows = df.index[(df.participant == "1") & (df.trial == "2")]
        other = df.index[(df.participant == "1") & (df.trial == "3")][0]
        order = [*df.index[: rows[10]], other, *[i for i in df.index[rows[10] :] if i != other]]
        return df.loc[order].reset_index(drop=True)

    assert read_spoiled(tmp_path, edit) == (
        "invalid",
        f"rows not contiguous: line {FIRST} to {FIRST + 9} and from line {FIRST + 11} on belong to it, "
        f"with other rows between",
    )
    # trial 1/3: its first row moved up to line FIRST + 10, the others after the 41 lines of trial 1/2
    assert read_spoiled(tmp_path, edit, "3") == (
        "invalid",
        f"rows not contiguous: line {FIRST + 10} to "
        f"{FIRST + 10} and from line {FIRST + 41} on belong "
        f"to it, with other rows between",
    )


def test_a_missing_time_stamp_names_its_first_line(tmp_path):
    """Time stamps missing at samples 6 and 9 of trial 1/2: the reason names sample 6's line."""

    def edit(df):
        rows = df.index[(df.participant == "1") & (df.trial == "2")]
        df.loc[rows[[6, 9]], "t"] = np.nan
        return df

    assert read_spoiled(tmp_path, edit) == ("invalid", f"time stamp missing at line {FIRST + 6}")


def test_time_going_backwards_names_the_sample_and_both_time_stamps(tmp_path):
    """A repeated time stamp at sample 5 and a step back at sample 12: going backwards is the reason (it
    is checked first), at sample 12's line, with its time stamp and the one before it (catches a repeat
    taken for a step back and the wrong neighbour in the message)."""

    def edit(df):
        rows = df.index[(df.participant == "1") & (df.trial == "2")]
        df.loc[rows[5], "t"] = df.loc[rows[4], "t"]
        df.loc[rows[12], "t"] = 0.125  # sample 11 is at 11/64 = 0.171875 s
        return df

    assert read_spoiled(tmp_path, edit) == (
        "invalid",
        f"time goes backwards at line {FIRST + 12} (t = 0.125 s after 0.171875 s)",
    )


# --- data: rates ------------------------------------------------------------------------------------


def test_a_trial_at_another_rate_states_both_rates_and_intervals(tmp_path):
    """Trial 1/2 at half the rate: its rate and interval against the file's, in full."""

    def edit(df):
        rows = df.index[(df.participant == "1") & (df.trial == "2")]
        df.loc[rows, "t"] = np.arange(len(rows)) * 2 * DT
        return df

    assert read_spoiled(tmp_path, edit) == (
        "invalid",
        f"sampled at {FS / 2:.1f} Hz, the file at {FS:.1f} Hz (mean interval {2 * DT:.4f} s vs {DT:.4f} s)",
    )


def test_mixed_rates_name_the_four_most_common_rates_by_count():
    """5 trials at 64 Hz, 4 at 32, 3 at 128, 2 at 59.94 (NTSC video) and 1 at 48: the message lists the
    four most common with their counts, most common first, rates to 0.1 Hz (catches another number of
    rates listed and rates rounded otherwise)."""
    counts = {64.0: 5, 32.0: 4, 128.0: 3, 59.94: 2, 48.0: 1}
    parts, k = [], 0
    for fs, n in counts.items():
        for _ in range(n):
            k += 1
            tr = trial_frame("1", str(k))
            tr["t"] = np.arange(len(tr)) / fs
            parts.append(tr)
    with pytest.raises(DataFormatError) as e:
        recordings_from_frame(pd.concat(parts, ignore_index=True))
    assert str(e.value) == (
        "<DataFrame>: mixed sampling rates (5 trials at 64 Hz, 4 trials at 32 Hz, 3 trials at "
        "128 Hz, 2 trials at 59.9 Hz); split the file by rate or resample every trial to one rate"
    )


def test_time_stamps_exactly_at_the_slowest_rate_are_seconds():
    """Trials sampled every 1 / MIN_RATE_HZ = 0.1 s exactly (time stamps -0.2, -0.1, 0, 0.1, 0.2, whose
    differences are all the float 0.1): read as seconds at MIN_RATE_HZ (catches ``>=`` for ``>``)."""
    t = np.array([-0.2, -0.1, 0.0, 0.1, 0.2])
    assert (np.diff(t) == 1 / MIN_RATE_HZ).all()
    df = pd.concat(
        [
            pd.DataFrame(
                {
                    "participant": "1",
                    "trial": str(k),
                    "t": t,
                    "x": 0.0,
                    "y": 0.01 * np.arange(5),
                    "z": 0.0,
                    "contact": [0, 0, 0, 1, 1],
                }
            )
            for k in range(3)
        ],
        ignore_index=True,
    )
    rec = recordings_from_frame(df)
    assert rec.fs == MIN_RATE_HZ and (rec.trials.status == "ok").all()


def test_the_typical_speed_is_the_95th_percentile_of_the_sample_speeds():
    """Trials at rest but for one sample STEP = 3 x MAX_TYPICAL_SPEED x DT away (two steps of 39): the
    95th percentile (linear, at 36.1 of 38) is 0.3 x the limit, the 96th (at 36.48) 1.44 x: metres, no
    error (catches another percentile)."""
    step = 3 * MAX_TYPICAL_SPEED * DT
    y = np.zeros(N)
    y[N // 2] = step
    assert np.percentile(np.abs(np.diff(y)), 95) / DT < MAX_TYPICAL_SPEED < np.percentile(np.abs(np.diff(y)), 96) / DT
    df = pd.concat([trial_frame("1", str(k)).assign(x=0.0, y=y, z=0.0) for k in range(6)], ignore_index=True)
    rec = recordings_from_frame(df)
    assert (rec.trials.status == "ok").all() and rec.fs == FS


def test_an_unterminated_quote_is_a_csv_error_naming_the_file(tmp_path):
    """A quote never closed: pandas' message has no line to translate; a DataFormatError with it."""
    p = tmp_path / "open_quote.csv"
    p.write_text(",".join(COLUMNS) + '\n1,1,0,0,0,0,"0\n1,1,0.1,0,0,0,0\n')
    with pytest.raises(DataFormatError, match=rf"^{p}: not a valid CSV table: \S"):
        read_recordings(p)


@pytest.mark.parametrize("missing", [None, pd.NA, float("nan")])
def test_a_missing_id_in_a_dataframe_is_empty_not_the_text_none(missing):
    """A DataFrame given through the API may hold None, pd.NA or NaN in a text id column: each is an
    empty id (an error naming its row), never the participant "None", "<NA>" or "nan"."""
    with pytest.raises(DataFormatError, match=r"^mine, row 5, column 'participant': participant is empty$"):
        recordings_from_frame(spoil(cohort_frame(), "participant", 5, missing), source="mine")


def test_a_capitalised_column_name_is_reported_with_the_columns_found_and_the_case_hint():
    """'Participant' instead of 'participant': the message names the missing column, lists the columns
    found and expected, and says that names are lower case (not the --columns mapping hint)."""
    f = cohort_frame().rename(columns={"participant": "Participant"})
    found = ", ".join(f.columns)
    with pytest.raises(DataFormatError) as e:
        recordings_from_frame(f, source="mine")
    assert str(e.value) == (
        f"mine: required column 'participant' missing (found: {found}; expected: "
        f"{', '.join(COLUMNS)}); column names are lower case"
    )
