"""Tests of skilllib.recordings: the recordings CSV (reading, validating, writing).

Each bad-input case writes a small CSV in tmp_path and checks the error message or the trial's status.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from skilllib.recordings import (
    COLUMNS,
    JITTER_TOLERANCE,
    MAX_GAP_INTERVALS,
    MAX_RANGE_M,
    MAX_TYPICAL_SPEED,
    MIN_RATE_HZ,
    MIN_SAMPLES,
    MIXED_FRACTION,
    RATE_TOLERANCE,
    DataFormatError,
    format_recordings,
    read_recordings,
    recordings_from_frame,
    write_recordings,
)

FS = 60.0


def trial_frame(participant=1, trial=1, n=40, fs=FS, contact_at=30, t0=0.0, scale=1.0) -> pd.DataFrame:
    """A plausible small trial: rest, a 0.1 m downward minimum-jerk approach, contact from ``contact_at``."""
    t = t0 + np.arange(n) / fs
    tau = np.clip((np.arange(n) - 8) / (contact_at - 6), 0, 1)
    y = 0.1 * (1 - tau**3 * (10 - 15 * tau + 6 * tau**2))
    contact = (np.arange(n) >= contact_at).astype(int)
    return pd.DataFrame(
        {
            "participant": participant,
            "trial": trial,
            "t": t,
            "x": 0.01 * scale,
            "y": y * scale,
            "z": -0.02 * scale,
            "contact": contact,
        }
    )


def cohort_frame(n_part=2, n_trials=3, **kw) -> pd.DataFrame:
    return pd.concat(
        [trial_frame(p, tr, **kw) for p in range(1, n_part + 1) for tr in range(1, n_trials + 1)], ignore_index=True
    )


def write(tmp_path: Path, df: pd.DataFrame, name="rec.csv") -> Path:
    return write_recordings(df, tmp_path / name)


def status(rec, participant, trial) -> tuple[str, str]:
    row = rec.trials[(rec.trials.participant == str(participant)) & (rec.trials.trial == str(trial))].iloc[0]
    return row.status, row.reason


# --- a good file --------------------------------------------------------------------------------


def test_good_file_reads_with_all_trials_ok_and_60_hz(tmp_path):
    rec = read_recordings(write(tmp_path, cohort_frame()))
    assert len(rec) == 6 and (rec.trials.status == "ok").all()
    assert rec.fs == pytest.approx(60.0, rel=1e-3)
    assert rec.trials.first_line.tolist() == [2, 42, 82, 122, 162, 202]
    tr = rec.trial(2, 3)
    assert tr.pos.shape == (40, 3) and tr.contact.sum() == 10 and tr.t[0] == 0.0


def test_write_read_write_is_byte_identical(tmp_path):
    p1 = write(tmp_path, cohort_frame(), "a.csv")
    p2 = write(tmp_path, read_recordings(p1), "b.csv")
    assert p1.read_bytes() == p2.read_bytes()


def test_writer_rounds_and_has_no_negative_zero():
    df = trial_frame(n=6, contact_at=4)
    df.loc[0, "x"] = -1e-9
    text = format_recordings(df)
    assert text.splitlines()[0] == ",".join(COLUMNS)
    assert "-0.00000" not in text and ",0.00000," in text
    assert text.splitlines()[2].split(",")[2] == "0.0167"  # t to 0.1 ms


def test_string_participant_labels_are_kept(tmp_path):
    df = cohort_frame()
    df["participant"] = "P" + df["participant"].astype(str)
    rec = read_recordings(write(tmp_path, df))
    assert rec.keys()[0] == ("P1", "1") and (rec.trials.status == "ok").all()


def test_extra_columns_and_blank_lines_are_tolerated(tmp_path):
    df = cohort_frame(1, 2).assign(note=1.5)
    p = tmp_path / "r.csv"
    text = df.to_csv(index=False) + "\n\n"
    p.write_text(text)
    rec = read_recordings(p)
    assert len(rec) == 2 and list(rec.frame.columns) == list(COLUMNS)


# --- file-level problems raise -----------------------------------------------------------------


def test_missing_file(tmp_path):
    with pytest.raises(DataFormatError, match=r"nope\.csv: file not found"):
        read_recordings(tmp_path / "nope.csv")


def test_empty_file(tmp_path):
    (tmp_path / "e.csv").write_text("")
    with pytest.raises(DataFormatError, match="e.csv: file is empty"):
        read_recordings(tmp_path / "e.csv")


def test_header_only_is_empty(tmp_path):
    (tmp_path / "h.csv").write_text(",".join(COLUMNS) + "\n")
    with pytest.raises(DataFormatError, match="empty"):
        read_recordings(tmp_path / "h.csv")


def test_missing_column_is_named(tmp_path):
    p = tmp_path / "m.csv"
    cohort_frame().drop(columns="contact").to_csv(p, index=False)
    with pytest.raises(DataFormatError, match=r"m\.csv: required column 'contact' missing"):
        read_recordings(p)


def test_semicolon_separator_hint(tmp_path):
    """A semicolon file is read (the separator detected); forced to commas, the message says how the line
    was split and which separator the file seems to use (tests/recordings/test_tables.py has the rest)."""
    p = tmp_path / "s.csv"
    cohort_frame().to_csv(p, index=False, sep=";")
    assert len(read_recordings(p)) == len(read_recordings(write(tmp_path, cohort_frame())))
    with pytest.raises(DataFormatError, match="split at commas.*split at semicolons: give the separator with --sep"):
        read_recordings(p, sep=",")


def test_non_number_cell_names_line_and_column(tmp_path):
    p = write(tmp_path, cohort_frame())
    lines = p.read_text().splitlines()
    fields = lines[56].split(",")  # file line 57
    fields[4] = "abc"  # column y
    lines[56] = ",".join(fields)
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataFormatError, match=r"rec\.csv, line 57, column 'y': 'abc' is not a number"):
        read_recordings(p)


def test_line_numbers_count_blank_lines(tmp_path):
    p = write(tmp_path, cohort_frame())
    lines = p.read_text().splitlines()
    lines.insert(3, "")  # a blank line 4 shifts the data below it
    fields = lines[10].split(",")  # file line 11
    fields[2] = "1,5".replace(",", ";")
    lines[10] = ",".join(fields)
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataFormatError, match=r"line 11, column 't'"):
        read_recordings(p)


def test_wrong_number_of_fields(tmp_path):
    p = write(tmp_path, cohort_frame())
    lines = p.read_text().splitlines()
    lines[5] += ",9"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataFormatError, match=r"line 6"):
        read_recordings(p)


@pytest.mark.parametrize("column", ["participant", "trial"])
@pytest.mark.parametrize("empty", ["", "   "], ids=["empty", "spaces"])
def test_an_empty_id_names_its_line(tmp_path, column, empty):
    df = cohort_frame().astype({column: object})
    df.loc[7, column] = empty
    with pytest.raises(DataFormatError, match=rf"line 9, column '{column}': {column} is empty"):
        read_recordings(write(tmp_path, df, "p.csv"))


def test_contact_must_be_0_or_1(tmp_path):
    df = cohort_frame()
    df.loc[12, "contact"] = 2
    with pytest.raises(DataFormatError, match=r"line 14, column 'contact': contact must be 0 or 1, got 2"):
        read_recordings(write(tmp_path, df))


@pytest.mark.parametrize("factor", [1000.0, 100.0])
def test_positions_in_millimetres_or_centimetres(tmp_path, factor):
    df = cohort_frame()
    df[["x", "y", "z"]] *= factor
    with pytest.raises(DataFormatError, match="look like millimetres.*divide millimetres by 1000"):
        read_recordings(write(tmp_path, df))


def test_time_in_milliseconds(tmp_path):
    df = cohort_frame()
    df["t"] *= 1000
    with pytest.raises(DataFormatError, match="milliseconds.*divide t by 1000"):
        read_recordings(write(tmp_path, df))


def test_mixed_sampling_rates_in_one_file(tmp_path):
    df = pd.concat([cohort_frame(1, 4), cohort_frame(1, 4, fs=120.0).assign(participant=2)], ignore_index=True)
    with pytest.raises(DataFormatError, match=r"mixed sampling rates \(4 trials at 60 Hz, 4 trials at 120 Hz\)"):
        read_recordings(write(tmp_path, df))


# --- trial-level problems mark the trial invalid -------------------------------------------------


def bad_trial(tmp_path, edit) -> tuple[str, str, object]:
    """Cohort of 2 x 10 trials, ``edit(df)`` spoils participant 1 trial 2; returns its status and reason."""
    df = cohort_frame(2, 10)
    df = edit(df)
    rec = read_recordings(write(tmp_path, df))
    others = rec.trials[~((rec.trials.participant == "1") & (rec.trials.trial == "2"))]
    assert (others.status == "ok").all(), others[others.status != "ok"]
    assert len(rec) == 20
    return (*status(rec, 1, 2), rec)


def rows_of(df, p=1, tr=2):
    return df.index[(df.participant == p) & (df.trial == tr)]


def test_time_going_backwards(tmp_path):
    def edit(df):
        i = rows_of(df)[10]
        df.loc[i, "t"] = df.loc[i - 2, "t"]
        return df

    st_, reason, _ = bad_trial(tmp_path, edit)
    assert st_ == "invalid" and reason.startswith("time goes backwards at line 52")


def test_repeated_time_stamp(tmp_path):
    def edit(df):
        i = rows_of(df)[10]
        df.loc[i, "t"] = df.loc[i - 1, "t"]
        return df

    st_, reason, _ = bad_trial(tmp_path, edit)
    assert st_ == "invalid" and reason.startswith("time stamp repeated at line 52")


@pytest.mark.parametrize("value, word", [(np.nan, "missing"), (np.inf, "infinite")])
def test_nan_or_inf_position(tmp_path, value, word):
    def edit(df):
        df.loc[rows_of(df)[5], "z"] = value
        return df

    st_, reason, rec = bad_trial(tmp_path, edit)
    if word == "missing":  # a one-sample gap is filled, and the repair names its line (issue 22)
        assert (st_, reason) == ("ok", "")
        repairs = rec.trials.set_index(["participant", "trial"]).loc[("1", "2"), "repairs"]
        assert repairs.endswith("gap of 1 sample filled at 0.083 s (line 47)"), repairs
    else:
        assert (st_, reason) == ("invalid", "z is infinite at line 47")


def test_empty_position_cell_is_nan(tmp_path):
    p = write(tmp_path, cohort_frame(2, 10))
    lines = p.read_text().splitlines()
    f = lines[46].split(",")
    f[3] = ""
    lines[46] = ",".join(f)
    p.write_text("\n".join(lines) + "\n")
    rec = read_recordings(p)
    assert status(rec, 1, 2) == ("ok", "")
    assert rec.trials.repairs[rec.trials.trial == "2"].iloc[0].endswith("(line 47)")
    assert status(read_recordings(p, max_gap_s=0.0), 1, 2)[1].startswith("x is missing (NaN) at line 47: a gap")


@pytest.mark.parametrize("n", [MIN_SAMPLES - 1, MIN_SAMPLES])
def test_min_samples_at_both_sides_of_the_edge(tmp_path, n):
    """Exactly MIN_SAMPLES samples make a valid trial, one fewer an invalid one (catches ``<=`` for
    ``<`` and an off-by-one in the count)."""

    def edit(df):
        return df.drop(rows_of(df)[n:])

    st_, reason, rec = bad_trial(tmp_path, edit)
    assert len(rec.trial(1, 2).t) == n
    if n < MIN_SAMPLES:
        assert (st_, reason) == ("invalid", f"too few samples ({n}; need at least {MIN_SAMPLES})")
    else:
        assert (st_, reason) == ("ok", "")


def test_rows_not_contiguous(tmp_path):
    def edit(df):
        r = rows_of(df)
        moved = df.loc[r[30:]]
        return pd.concat([df.drop(r[30:]), moved], ignore_index=True)

    st_, reason, _ = bad_trial(tmp_path, edit)
    assert st_ == "invalid" and reason.startswith("rows not contiguous: line 42 to 71 and from line")


def test_trial_at_another_rate(tmp_path):
    def edit(df):
        r = rows_of(df)
        df.loc[r, "t"] = np.arange(len(r)) / 30.0
        return df

    st_, reason, _ = bad_trial(tmp_path, edit)
    assert st_ == "invalid" and reason.startswith("sampled at 30.0 Hz, the file at 60.0 Hz")


def test_gap_in_a_trial(tmp_path):
    def edit(df):
        r = rows_of(df)
        df.loc[r[20:], "t"] += 3 / 60  # three frames missing in a row: an interval of 4 dt
        return df

    st_, reason, _ = bad_trial(tmp_path, edit)
    assert st_ == "invalid" and reason.startswith("gap in the time stamps: 0.0666 s before line 62, 4.0 sampling")


def test_single_trial_with_huge_span(tmp_path):
    def edit(df):
        df.loc[rows_of(df)[12], "x"] = 5.0
        return df

    st_, reason, _ = bad_trial(tmp_path, edit)
    assert st_ == "invalid" and reason.startswith("positions span 4.99 m")


def test_missing_contact_flag(tmp_path):
    def edit(df):
        df["contact"] = df["contact"].astype(float)
        df.loc[rows_of(df)[33], "contact"] = np.nan
        return df

    st_, reason, _ = bad_trial(tmp_path, edit)
    assert (st_, reason) == ("invalid", "contact flag missing at line 75")


def test_frame_input_names_rows_not_lines():
    df = cohort_frame(1, 2)
    df.loc[3, "y"] = np.nan
    rec = recordings_from_frame(df)
    assert status(rec, 1, 1) == ("ok", "") and rec.trials.repairs.iloc[0].endswith("(row 3)")
    with pytest.raises(DataFormatError, match="<DataFrame>: required column 't' missing"):
        recordings_from_frame(df.drop(columns="t"))


@settings(max_examples=25, deadline=None)
@given(order=st.permutations(list(range(6))))
def test_trial_order_does_not_change_validation(order):
    """Shuffling whole trials (each kept contiguous) changes neither statuses nor the sampling rate."""
    trials = [trial_frame(p, tr) for p in (1, 2) for tr in (1, 2, 3)]
    trials[4].loc[trials[4].index[7], "t"] = 0.0  # one invalid trial
    base = recordings_from_frame(pd.concat(trials, ignore_index=True))
    shuffled = recordings_from_frame(pd.concat([trials[i] for i in order], ignore_index=True))
    key = ["participant", "trial"]
    a = base.trials.set_index(key)[["status"]].sort_index()
    b = shuffled.trials.set_index(key)[["status"]].sort_index()
    pd.testing.assert_frame_equal(a, b)
    assert shuffled.fs == base.fs


# --- every threshold at both sides of its edge -----------------------------------------------------
#
# These go through recordings_from_frame (no CSV rounding) at 64 Hz: the interval 1/64 s is a power of
# two, so time stamps k/64, the file's interval and products of it with the constants are exact and a
# value can sit exactly on a threshold. "Beyond" is then the next float (np.nextafter) or a margin of
# 1e-9 where the library's own arithmetic is not exact.

DT64 = 2.0**-6  # s: 64 Hz


def frame64(n_part=2, n_trials=10) -> pd.DataFrame:
    return cohort_frame(n_part, n_trials, fs=1 / DT64)


def check(df) -> tuple[str, str]:
    """Status and reason of participant 1 trial 2 (after checking that every other trial is ok)."""
    rec = recordings_from_frame(df)
    others = rec.trials[~((rec.trials.participant == "1") & (rec.trials.trial == "2"))]
    assert (others.status == "ok").all(), others[others.status != "ok"]
    return status(rec, 1, 2)


@pytest.mark.parametrize("sign", [1, -1], ids=["longer", "shorter"])
@pytest.mark.parametrize("beyond", [False, True], ids=["at", "beyond"])
def test_jitter_tolerance_at_both_sides_of_the_edge(sign, beyond):
    """One interval of (1 +- JITTER_TOLERANCE) x the file's is regular (trial used as recorded, nothing
    said); the next float further out is looked at closely: a step of 2 % of an interval in the stamps is
    far within REGULAR_JITTER of a regular grid, so the trial is still used as recorded, and its timing
    says so. Catches ``>=`` for ``>``, a dropped abs() (the shorter interval) and a tolerance other than
    the constant."""
    df = frame64()
    r = rows_of(df)
    t = np.arange(len(r)) * DT64

    def rel(t20):  # the relative deviation of the interval before t20, as skilllib.recordings computes it
        return abs((t20 - t[19]) / DT64 - 1)

    t20 = t[19] + DT64 * (1 + sign * JITTER_TOLERANCE)  # then the last float at or inside the edge
    while rel(t20) > JITTER_TOLERANCE:
        t20 = np.nextafter(t20, -sign * np.inf)
    while rel(np.nextafter(t20, sign * np.inf)) <= JITTER_TOLERANCE:
        t20 = np.nextafter(t20, sign * np.inf)
    if beyond:
        t20 = np.nextafter(t20, sign * np.inf)
    assert (rel(t20) > JITTER_TOLERANCE) == beyond and abs(rel(t20) - JITTER_TOLERANCE) < 1e-12
    t[20:] = t20 + np.arange(len(r) - 20) * DT64
    df.loc[r, "t"] = t
    rec = recordings_from_frame(df)
    assert (rec.trials.status == "ok").all()
    timing = rec.trials.set_index(["participant", "trial"]).loc[("1", "2"), "timing"]
    tr = rec.trial(1, 2)
    assert np.array_equal(tr.t, t)
    if beyond:
        assert timing.startswith("stamps within ") and timing.endswith(": used as recorded")
    else:
        assert timing == ""


@pytest.mark.parametrize("beyond", [False, True], ids=["at", "beyond"])
def test_gap_limit_at_both_sides_of_the_edge(beyond):
    """An interval of MAX_GAP_INTERVALS x dt is bridged by resampling; the next float beyond is a gap
    that makes the trial invalid with the line after it."""
    df = frame64()
    r = rows_of(df)
    t = np.arange(len(r)) * DT64
    t20 = t[19] + DT64 * MAX_GAP_INTERVALS
    if beyond:
        t20 = np.nextafter(t20, np.inf)
    t[20:] = t20 + np.arange(len(r) - 20) * DT64
    df.loc[r, "t"] = t
    st_, reason = check(df) if beyond else status(recordings_from_frame(df), 1, 2)
    if beyond:
        assert st_ == "invalid" and reason.startswith("gap in the time stamps:") and "before row 60" in reason
    else:
        assert (st_, reason) == ("ok", "")


@pytest.mark.parametrize("sign", [1, -1], ids=["slower", "faster"])
@pytest.mark.parametrize("beyond", [False, True], ids=["inside", "outside"])
def test_rate_tolerance_at_both_sides_of_the_edge(sign, beyond):
    """A trial whose interval is (1 +- RATE_TOLERANCE) x the file's, 1e-9 inside, is kept; 1e-9
    outside it is 'sampled at another rate'. Catches a tolerance other than the constant and a
    one-sided (no abs) comparison."""
    df = frame64()
    r = rows_of(df)
    ratio = 1 + sign * RATE_TOLERANCE * (1 + (1e-9 if beyond else -1e-9))
    df.loc[r, "t"] = np.arange(len(r)) * DT64 * ratio
    st_, reason = check(df)
    if beyond:
        assert st_ == "invalid" and reason.startswith(f"sampled at {ratio**-1 / DT64:.1f} Hz, the file at 64.0 Hz")
    else:
        assert (st_, reason) == ("ok", "")


@pytest.mark.parametrize("extra", [0, 1], ids=["at", "beyond"])
def test_mixed_fraction_at_both_sides_of_the_edge(extra):
    """With N trials, MIXED_FRACTION x N trials at half the rate are single off-rate trials (marked
    invalid); one more and the file mixes rates. Catches ``>=`` for ``>`` and a fraction taken over
    the on-rate trials only (2 > 0.05 x 38 would raise at the edge)."""
    n = round(2 / MIXED_FRACTION)
    limit = 2
    assert MIXED_FRACTION * n == limit  # the edge is an exact count
    df = cohort_frame(2, n // 2, fs=1 / DT64)
    slow = list(range(1, limit + extra + 1))  # trials 1.. of participant 1 at 32 Hz
    for tr in slow:
        r = rows_of(df, 1, tr)
        df.loc[r, "t"] = np.arange(len(r)) * 2 * DT64
    if extra:
        with pytest.raises(
            DataFormatError,
            match=rf"mixed sampling rates \({n - limit - 1} trials at 64 Hz, "
            rf"{limit + 1} trials at 32 Hz\)",
        ):
            recordings_from_frame(df)
        return
    rec = recordings_from_frame(df)
    assert rec.fs == 64.0
    bad = rec.trials[rec.trials.status != "ok"]
    assert bad.trial.tolist() == [str(v) for v in slow] and (bad.participant == "1").all()
    assert bad.reason.str.startswith("sampled at 32.0 Hz, the file at 64.0 Hz").all()


@pytest.mark.parametrize("beyond", [False, True], ids=["inside", "beyond"])
def test_slowest_rate_at_both_sides_of_the_edge(beyond):
    """A median step just under 1 / MIN_RATE_HZ s is read as seconds; just over it raises (catches another
    limit than the constant and a reversed comparison)."""
    step = (1 + (1e-6 if beyond else -1e-6)) / MIN_RATE_HZ
    df = cohort_frame(2, 3)
    for g in df.groupby(["participant", "trial"]).groups.values():
        df.loc[g, "t"] = np.arange(len(g)) * step
    if beyond:
        with pytest.raises(DataFormatError, match=r"below 10 Hz.*t must be in seconds"):
            recordings_from_frame(df)
    else:
        rec = recordings_from_frame(df)
        assert (rec.trials.status == "ok").all() and rec.fs == pytest.approx(1 / step)


@pytest.mark.parametrize(
    "fs, unit, factor",
    [
        (60.0, "milliseconds", 1e3),
        (2000.0, "milliseconds", 1e3),
        (5000.0, "milliseconds", 1e3),
        (60.0, "microseconds", 1e6),
        (250.0, "microseconds", 1e6),
    ],
)
def test_the_unit_of_the_time_stamps_is_named(fs, unit, factor):
    """Time in ms or us is recognised at any rate of motion capture (2 kHz in ms has steps of 0.5, which
    an earlier rule read as a 2 Hz file in seconds), and the advice names the unit and its factor."""
    df = cohort_frame(2, 3, fs=fs)
    df["t"] *= factor
    option = {"milliseconds": "ms", "microseconds": "us"}[unit]
    advice = rf"look like {unit} .*{fs:.4g} Hz in {unit}.*divide t by {factor:.0f}, or give the unit: "
    advice += rf"--time-unit {option}$"
    with pytest.raises(DataFormatError, match=advice):
        recordings_from_frame(df)


@pytest.mark.parametrize("beyond", [False, True], ids=["at", "beyond"])
def test_single_trial_span_at_both_sides_of_max_range(beyond):
    """A trial spanning exactly MAX_RANGE_M is kept; the next float is 'positions span' (catches
    ``>=`` for ``>`` and another limit than the constant)."""
    span = np.nextafter(MAX_RANGE_M, np.inf) if beyond else MAX_RANGE_M
    df = frame64()
    r = rows_of(df)
    df.loc[r, "x"] = 0.0
    df.loc[r[12], "x"] = span
    st_, reason = check(df)
    if beyond:
        assert st_ == "invalid" and reason.startswith(f"positions span {span:.3g} m (more than {MAX_RANGE_M:g} m)")
    else:
        assert (st_, reason) == ("ok", "")


def units_frame(y_of_trial) -> pd.DataFrame:
    """2 x 3 trials of 40 samples at 64 Hz, x = z = 0 and y = ``y_of_trial(n)``."""
    parts = []
    for p in (1, 2):
        for tr in (1, 2, 3):
            y = y_of_trial(40)
            parts.append(
                pd.DataFrame(
                    {
                        "participant": p,
                        "trial": tr,
                        "t": np.arange(40) * DT64,
                        "x": 0.0,
                        "y": y,
                        "z": 0.0,
                        "contact": (np.arange(40) >= 30).astype(int),
                    }
                )
            )
    return pd.concat(parts, ignore_index=True)


@pytest.mark.parametrize("beyond", [False, True], ids=["at", "beyond"])
def test_file_span_at_both_sides_of_max_range(beyond):
    """Trials that all span exactly MAX_RANGE_M (at 3 m/s, a plausible speed) are metres; the next
    float raises 'millimetres or centimetres' (catches ``>=`` for ``>`` in the file-level check)."""
    span = np.nextafter(MAX_RANGE_M, np.inf) if beyond else MAX_RANGE_M
    df = units_frame(lambda n: np.minimum(np.linspace(0.0, span, n), span))
    if beyond:
        with pytest.raises(DataFormatError, match="look like millimetres or centimetres"):
            recordings_from_frame(df)
    else:
        assert (recordings_from_frame(df).trials.status == "ok").all()


@pytest.mark.parametrize("beyond", [False, True], ids=["at", "beyond"])
def test_typical_speed_at_both_sides_of_max_typical_speed(beyond):
    """Trials moving back and forth by MAX_TYPICAL_SPEED x dt each sample (speed exactly
    MAX_TYPICAL_SPEED, span well under MAX_RANGE_M) are metres; a step one float longer raises.
    Catches ``>=`` for ``>`` and another limit than the constant."""
    step = MAX_TYPICAL_SPEED * DT64  # exact: DT64 is a power of two
    if beyond:
        step = np.nextafter(step, np.inf)
    assert step < MAX_RANGE_M
    df = units_frame(lambda n: np.where(np.arange(n) % 2 == 1, step, 0.0))
    if beyond:
        with pytest.raises(DataFormatError, match="look like millimetres or centimetres"):
            recordings_from_frame(df)
    else:
        assert (recordings_from_frame(df).trials.status == "ok").all()


# --- issue 12: identifiers are text, compressed files, physical line numbers, long cells, jitter ------------


def test_ids_are_text_as_written_and_never_merged(tmp_path):
    """'01' and '1', 'NA', a 17-digit id and '1e20' are five distinct participants (and trials); results
    keep them as written. Numbers would merge '01' with '1', read 'NA' as missing, round the 17-digit id
    and overflow 1e20."""
    ids = ["01", "1", "NA", "12345678901234567", "1e20"]
    df = pd.concat([trial_frame(p, tr) for p in ids for tr in ("007", "7")], ignore_index=True)
    rec = read_recordings(write(tmp_path, df))
    assert rec.keys() == [(p, tr) for p in ids for tr in ("007", "7")]
    assert (rec.trials.status == "ok").all() and len(rec) == 10
    assert rec.trial("12345678901234567", "007").participant == "12345678901234567"
    assert format_recordings(rec).splitlines()[1].startswith("01,007,")


def test_ids_from_a_dataframe_of_numbers_are_their_text():
    df = cohort_frame().astype({"participant": float})
    rec = recordings_from_frame(df)
    assert rec.keys()[:2] == [("1", "1"), ("1", "2")]


@pytest.mark.parametrize("suffix", [".csv.gz", ".csv.bz2", ".csv.xz", ".zip"])
def test_compressed_csv_is_read_as_pandas_reads_it(tmp_path, suffix):
    df = cohort_frame()
    plain = read_recordings(write(tmp_path, df))
    packed = tmp_path / f"rec{suffix}"
    df.to_csv(packed, index=False)  # pandas compresses by the extension
    rec = read_recordings(packed)
    assert rec.keys() == plain.keys() and rec.fs == pytest.approx(plain.fs)
    np.testing.assert_allclose(rec.trial(2, 3).pos, plain.trial(2, 3).pos, atol=1e-5)


def test_a_binary_file_is_not_text(tmp_path):
    p = tmp_path / "rec.csv"
    p.write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff\xfe" * 10)
    with pytest.raises(DataFormatError, match=r"rec\.csv: not a text \(UTF-8\) CSV file"):
        read_recordings(p)


def test_line_numbers_count_the_lines_of_a_quoted_multi_line_cell(tmp_path):
    """A note column with a quoted cell over three lines (file lines 3-5): a bad cell on data row 10 is on
    physical line 13, not 11."""
    df = cohort_frame().assign(note="").astype({"y": object})
    df.loc[1, "note"] = "first line\nsecond\nthird"
    df.loc[9, "y"] = "abc"
    p = tmp_path / "rec.csv"
    df.to_csv(p, index=False)
    text = p.read_text()
    assert text.splitlines()[12].split(",")[4] == "abc"  # physical line 13
    with pytest.raises(DataFormatError, match=r"rec\.csv, line 13, column 'y': 'abc' is not a number"):
        read_recordings(p)


def test_a_long_cell_is_quoted_cut_with_its_length(tmp_path):
    df = cohort_frame().astype({"x": object})
    df.loc[4, "x"] = "z" * 100_000
    p = tmp_path / "rec.csv"
    df.to_csv(p, index=False)
    with pytest.raises(DataFormatError) as e:
        read_recordings(p)
    msg = str(e.value)
    assert len(msg) < 200 and "'zzzz" in msg and "(100,000 characters)" in msg and "line 6, column 'x'" in msg


def _jittered_log(jitter: float, fs: float = 250.0, n: int = 200, n_trials: int = 8, drops: int = 3, seed: int = 4):
    """A log of smooth descents at ``fs`` whose frame times jitter uniformly by +-``jitter`` s and drop
    ``drops`` isolated frames per trial; contact from 0.7 s."""
    rng = np.random.default_rng(seed)
    frames = []
    for tr in range(1, n_trials + 1):
        t = np.arange(n) / fs + rng.uniform(-jitter, jitter, n) * (np.arange(n) > 0)
        keep = np.ones(n, bool)
        keep[rng.choice(np.arange(5, n - 5), drops, replace=False)] = False
        t = np.sort(t[keep])
        y = 0.1 * np.cos(np.pi * np.clip(t / 0.6, 0, 1))
        frames.append(
            pd.DataFrame(
                {
                    "participant": "P",
                    "trial": str(tr),
                    "t": t,
                    "x": 0.0,
                    "y": y,
                    "z": 0.0,
                    "contact": (t >= 0.7).astype(int),
                }
            )
        )
    return pd.concat(frames, ignore_index=True)


def test_jittered_time_stamps_with_dropped_frames_are_resampled_not_lost():
    """A 250 Hz log whose frame times jitter by up to 1 ms and that drops isolated frames: every trial is
    kept, resampled onto the 250 Hz grid, and the resampled positions match the movement at the grid times."""
    rec = recordings_from_frame(_jittered_log(0.001))
    assert (rec.trials.status == "ok").all() and rec.trials.timing.str.startswith("resampled: jitter up to").all()
    assert rec.trials.timing.str.endswith("3 dropped frames").all()
    assert rec.fs == pytest.approx(250.0, rel=1e-3)
    tr = rec.trial("P", "3")
    assert np.allclose(np.diff(tr.t), 1 / rec.fs)
    truth = 0.1 * np.cos(np.pi * np.clip(tr.t / 0.6, 0, 1))
    assert np.abs(tr.pos[:, 1] - truth).max() < 2e-5  # 0.02 mm
    first = np.flatnonzero(tr.contact)[0]
    assert tr.contact[first:].all() and tr.t[first] >= 0.7 - 0.001 and tr.t[first - 1] < 0.7 + 0.001


def test_jitter_of_half_an_interval_still_keeps_every_trial():
    """+-2 ms at 250 Hz (intervals from 0 to 8 ms), which the old rule marked invalid everywhere: every trial
    is kept; the rate is then only known to a few per cent from 8 trials (the mode of such intervals is
    flat), which the docstring of skilllib.recordings says."""
    rec = recordings_from_frame(_jittered_log(0.002))
    assert (rec.trials.status == "ok").all() and (rec.trials.timing != "").all()
    assert rec.fs == pytest.approx(250.0, rel=0.05)


def test_natural_key_orders_ids_and_file_names_as_people_do():
    """One key for ids, file names and Parquet parts: digit runs by value, other text ignoring case, the
    text itself last (a total, fixed order). Catches P10 before P2, all upper case before lower case, and
    01 / 1 or P1 / p1 left in input order."""
    from skilllib.recordings import natural_key, sort_ids

    assert sort_ids(["P10", "p2", "P1", "P2", 10, "2", "p1", "01", "1"]) == [
        "01", "1", "2", 10, "P1", "p1", "P2", "p2", "P10",
    ]  # fmt: skip
    assert sort_ids(["trial_10.csv", "Trial_9.csv", "trial_9b.csv"]) == ["Trial_9.csv", "trial_9b.csv", "trial_10.csv"]
    assert sort_ids(["a01b", "a1a"]) == ["a1a", "a01b"]  # leading zeros only break ties
    assert natural_key("P01") != natural_key("P1") and natural_key(7) == natural_key("7")
