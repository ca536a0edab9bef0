"""The open recordings format: one CSV, read, validated and written.

A long table, one row per sample, columns ``participant, trial, t, x, y, z, contact``:

=============  =====  ===================================================================
column         unit   meaning
=============  =====  ===================================================================
participant    --     participant id (integer, or a label such as ``P01``)
trial          --     trial number within the participant (integer)
t              s      time stamp of the sample (any origin; increasing within a trial)
x, y, z        m      tool-tip position: x mediolateral, y vertical (up), z anteroposterior
contact        0/1    1 when the tip touches the contact surface
=============  =====  ===================================================================

The rows of one trial are contiguous and time-ordered; other columns are ignored. This is the format
of the book's synthetic cohort (``data/cohort.csv``, :mod:`skilllib.cohort`) and of a user's own
recordings.

Problems with the *file* raise :class:`DataFormatError` (a ``ValueError``) with one line naming the file
and, where it applies, the line and column. Problems with a *trial* never raise: the trial is kept,
marked ``invalid`` in :attr:`Recordings.trials` with the reason, and the rest is analysed.
The sampling rate is derived from the time stamps: the median over regular trials of each trial's mean
interval (the per-trial median interval, used to detect trials at another rate, is biased by rounding).
"""
from __future__ import annotations

import io
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

COLUMNS = ("participant", "trial", "t", "x", "y", "z", "contact")
POSITION_COLUMNS = ("x", "y", "z")
MIN_SAMPLES = 5  #: fewer samples than this make a trial invalid
MAX_RANGE_M = 2.0  #: a trial spanning more than this (m) has wrong units or a glitch (device: 0.38 m)
MAX_TYPICAL_SPEED = 20.0  #: m/s; a typical (median over trials of the 95th percentile) speed above it: wrong units
RATE_TOLERANCE = 0.10  #: a trial's median interval may differ this much (relative) from the file's
INTERVAL_TOLERANCE = 0.5  #: any single interval outside (1 +- this) x the file's is irregular sampling
MIXED_FRACTION = 0.05  #: more trials than this fraction at another rate: the file mixes rates (error)
MIN_RATE_HZ = 10.0  #: a sampling rate below this, read from t in s, means t is in another unit (error)
MAX_RATE_HZ = 100_000.0  #: the fastest rate a unit suggestion considers plausible (Hz)
T_DECIMALS, POS_DECIMALS = 4, 5  #: writer's rounding: 0.1 ms and 0.01 mm


class DataFormatError(ValueError):
    """The file cannot be read as recordings; the message names the file, line and column."""


@dataclass(frozen=True)
class Trial:
    """The samples of one trial: ``t`` (N,) in s, ``pos`` (N, 3) in m (x, y, z), ``contact`` (N,) bool."""

    participant: Any
    trial: int
    t: np.ndarray
    pos: np.ndarray
    contact: np.ndarray


@dataclass(frozen=True, eq=False)
class Recordings:
    """Validated recordings.

    ``frame``: the samples (columns :data:`COLUMNS`, input order, index = 0-based data row);
    ``trials``: one row per trial in order of first appearance, columns ``participant, trial, n_samples,
    first_line, status`` (``ok`` or ``invalid``) and ``reason`` (empty when ok); ``fs``: sampling rate
    in Hz derived from the time stamps; ``source``: the file (or ``<DataFrame>``).
    """

    frame: pd.DataFrame
    trials: pd.DataFrame
    fs: float
    source: str
    _rows: dict = field(repr=False)

    def trial(self, participant: Any, trial: int) -> Trial:
        """The samples of one trial (whatever its status); KeyError if there is no such trial."""
        key = (participant, trial)
        if key not in self._rows:
            raise KeyError(f"no trial {trial} of participant {participant!r} in {self.source}")
        r = self._rows[key]
        f = self.frame
        return Trial(participant, trial, f["t"].to_numpy()[r], f[list(POSITION_COLUMNS)].to_numpy()[r],
                     f["contact"].to_numpy()[r] == 1)

    def keys(self) -> list[tuple[Any, int]]:
        """(participant, trial) of every trial, in order of first appearance."""
        return list(self._rows)

    def __len__(self) -> int:
        return len(self._rows)


def _where(source: str, place: str, column: str) -> str:
    """"file, line 12, column 'x'" (``place`` from the caller's ``loc``)."""
    return f"{source}, {place}, column '{column}'"


def _read_table(path: Path) -> pd.DataFrame:
    if not path.exists():
        raise DataFormatError(f"{path}: file not found")
    if path.is_dir():
        raise DataFormatError(f"{path}: is a directory, not a CSV file")
    raw = path.read_bytes()
    if not raw.strip():
        raise DataFormatError(f"{path}: file is empty")
    try:
        return pd.read_csv(io.BytesIO(raw), skip_blank_lines=False, skipinitialspace=True)
    except pd.errors.ParserError as e:  # e.g. "Expected 7 fields in line 12, saw 8"
        msg = str(e).replace("Error tokenizing data. C error: ", "").strip()
        raise DataFormatError(f"{path}: not a valid CSV table: {msg}") from None
    except UnicodeDecodeError:
        raise DataFormatError(f"{path}: not a text (UTF-8) CSV file") from None


def _check_columns(df: pd.DataFrame, source: str) -> pd.DataFrame:
    df = df.rename(columns=lambda c: str(c).strip())
    missing = [c for c in COLUMNS if c not in df.columns]
    if missing:
        found = ", ".join(map(str, df.columns))
        hint = ""
        if len(df.columns) == 1 and any(s in found for s in ";\t"):
            hint = "; the file seems to use ';' or tabs: separate columns with commas"
        elif any(str(c).lower() in COLUMNS for c in df.columns):
            hint = "; column names are lower case"
        raise DataFormatError(f"{source}: required column '{missing[0]}' missing (found: {found}; "
                              f"expected: {', '.join(COLUMNS)}){hint}")
    return df


def _numeric(col: pd.Series, name: str, source: str, loc) -> np.ndarray:
    """Column as float; DataFormatError at the first cell that is not a number (empty cells are NaN)."""
    if pd.api.types.is_numeric_dtype(col) and not pd.api.types.is_bool_dtype(col):
        return col.to_numpy(dtype=float)
    text = col.astype("string").str.strip()
    num = pd.to_numeric(text, errors="coerce")
    bad = num.isna() & text.notna() & (text != "")
    if bad.any():
        i = int(np.flatnonzero(bad.to_numpy())[0])
        raise DataFormatError(f"{_where(source, loc(i), name)}: {text.iloc[i]!r} is not a number")
    return num.to_numpy(dtype=float, na_value=np.nan)


def _ids(df: pd.DataFrame, source: str, loc) -> tuple[pd.Series, np.ndarray]:
    """Participant labels (int when all integer) and integer trial numbers; error at an empty id."""
    p = df["participant"]
    if pd.api.types.is_numeric_dtype(p):
        pv = p.to_numpy(dtype=float)
        if np.isnan(pv).any():
            i = int(np.flatnonzero(np.isnan(pv))[0])
            raise DataFormatError(f"{_where(source, loc(i), 'participant')}: participant is empty")
        part = pd.Series(pv.astype(np.int64), index=df.index) if np.all(pv == np.round(pv)) else pd.Series(pv)
    else:
        text = p.astype("string").str.strip()
        empty = (text.isna() | (text == "")).to_numpy()
        if empty.any():
            i = int(np.flatnonzero(empty)[0])
            raise DataFormatError(f"{_where(source, loc(i), 'participant')}: participant is empty")
        num = pd.to_numeric(text, errors="coerce")
        ok = num.notna().all() and np.all(num.to_numpy(dtype=float) % 1 == 0)
        part = num.astype(np.int64) if ok else text.astype(object)
    tr = _numeric(df["trial"], "trial", source, loc)
    bad = ~np.isfinite(tr) | (tr != np.round(tr))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        what = "empty" if np.isnan(tr[i]) else f"{tr[i]:g}, not an integer"
        raise DataFormatError(f"{_where(source, loc(i), 'trial')}: trial is {what}")
    return part.reset_index(drop=True), tr.astype(np.int64)


def _trial_problem(t: np.ndarray, pos: np.ndarray, contact: np.ndarray, rows: np.ndarray,
                   line, loc) -> str:
    """Reason why one trial's samples are unusable ('' when fine); time/units checks come later."""
    n = len(rows)
    if rows[-1] - rows[0] + 1 != n:
        gap = int(np.flatnonzero(np.diff(rows) > 1)[0])
        return (f"rows not contiguous: {loc(rows[0])} to {line(rows[gap])} and from {loc(rows[gap + 1])} "
                f"on belong to it, with other rows between")
    if n < MIN_SAMPLES:
        return f"too few samples ({n}; need at least {MIN_SAMPLES})"
    if np.isnan(t).any():
        return f"time stamp missing at {loc(rows[np.flatnonzero(np.isnan(t))[0]])}"
    for j, name in enumerate(POSITION_COLUMNS):
        bad = ~np.isfinite(pos[:, j])
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            what = "missing (NaN)" if np.isnan(pos[k, j]) else "infinite"
            return f"{name} is {what} at {loc(rows[k])}"
    if np.isnan(contact).any():
        return f"contact flag missing at {loc(rows[np.flatnonzero(np.isnan(contact))[0]])}"
    d = np.diff(t)
    if (d < 0).any():
        k = int(np.flatnonzero(d < 0)[0]) + 1
        return f"time goes backwards at {loc(rows[k])} (t = {t[k]:g} s after {t[k - 1]:g} s)"
    if (d == 0).any():
        k = int(np.flatnonzero(d == 0)[0]) + 1
        return f"time stamp repeated at {loc(rows[k])} (t = {t[k]:g} s)"
    return ""


def recordings_from_frame(df: pd.DataFrame, source: str = "<DataFrame>", *, _is_file: bool = False) -> Recordings:
    """Validate a long table (as read from a CSV) into :class:`Recordings`; see :func:`read_recordings`."""
    if not isinstance(df, pd.DataFrame):
        raise DataFormatError(f"{source}: expected a pandas DataFrame, got {type(df).__name__}")
    df = _check_columns(df, source)
    blank = df.isna().all(axis=1).to_numpy()  # blank lines (kept by skip_blank_lines=False for line numbers)
    df = df.loc[~blank]
    if df.empty:
        raise DataFormatError(f"{source}: file is empty (a header but no data rows)")
    rows_in_file = np.flatnonzero(~blank)  # data-row number of each kept row
    df = df.reset_index(drop=True)

    def line(r: int) -> int:  # 1-based file line (header = line 1), or 0-based frame row, of kept row r
        return int(rows_in_file[r]) + 2 if _is_file else int(rows_in_file[r])

    def loc(r: int) -> str:
        return f"line {line(r)}" if _is_file else f"row {line(r)}"

    cols = {c: _numeric(df[c], c, source, loc) for c in ("t", "x", "y", "z", "contact")}
    part, tr = _ids(df, source, loc)
    c = cols["contact"]
    bad = np.isfinite(c) & (c != 0) & (c != 1) | np.isinf(c)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DataFormatError(f"{_where(source, loc(i), 'contact')}: contact must be 0 or 1, got {c[i]:g}")
    frame = pd.DataFrame({"participant": part, "trial": tr, **cols})
    frame.index = pd.RangeIndex(len(frame))
    groups = frame.groupby(["participant", "trial"], sort=False).indices
    pos_all = frame[list(POSITION_COLUMNS)].to_numpy()
    t_all, c_all = cols["t"], cols["contact"]
    keys, reasons, med_dt, mean_dt = list(groups), [], [], []
    for key in keys:
        r = np.asarray(groups[key])
        reason = _trial_problem(t_all[r], pos_all[r], c_all[r], r, line, loc)
        reasons.append(reason)
        med_dt.append(float(np.median(np.diff(t_all[r]))) if not reason else np.nan)
        mean_dt.append(float((t_all[r[-1]] - t_all[r[0]]) / (len(r) - 1)) if not reason else np.nan)
    med_dt, mean_dt = np.array(med_dt), np.array(mean_dt)
    ok = ~np.isnan(med_dt)
    dt = _check_rates(source, keys, groups, med_dt, mean_dt, t_all, reasons, loc) if ok.any() else np.nan
    if ok.any():
        _check_units(source, keys, groups, pos_all, reasons, dt)
    trials = pd.DataFrame({
        "participant": [k[0] for k in keys], "trial": [int(k[1]) for k in keys],
        "n_samples": [len(groups[k]) for k in keys], "first_line": [line(groups[k][0]) for k in keys],
        "status": ["invalid" if r else "ok" for r in reasons], "reason": reasons})
    rows = {(k[0], int(k[1])): np.asarray(groups[k]) for k in keys}
    return Recordings(frame=frame, trials=trials, fs=1.0 / dt if dt > 0 else np.nan, source=source, _rows=rows)


def _time_unit_advice(step: float) -> str:
    """What a median time step too long for seconds (``step`` in the file's unit) says about the unit."""
    head = (f"median time step {step:g} between samples: {1 / step:.3g} Hz if t were in seconds, below "
            f"{MIN_RATE_HZ:g} Hz")
    for unit, factor in (("milliseconds", 1e3), ("microseconds", 1e6)):
        if MIN_RATE_HZ <= factor / step <= MAX_RATE_HZ:
            return (f"time stamps look like {unit} ({head}; {factor / step:.4g} Hz in {unit}); t must be in "
                    f"seconds: divide t by {factor:.0f}")
    return f"time stamps are not in seconds ({head}); t must be in seconds"


def _check_rates(source, keys, groups, med_dt, mean_dt, t_all, reasons, loc) -> float:
    """Time units and mixed rates (errors), single off-rate or irregular trials (invalid); returns the
    file's sampling interval in s: the median over on-rate trials of each trial's mean interval (robust
    to time stamps rounded to 0.1 ms, unlike the median interval used to find off-rate trials)."""
    ok = ~np.isnan(med_dt)
    ref = float(np.median(med_dt[ok]))
    if ref > 1 / MIN_RATE_HZ:
        raise DataFormatError(f"{source}: {_time_unit_advice(ref)}")
    off = np.abs(med_dt / ref - 1) > RATE_TOLERANCE  # NaN compares False
    if off.sum() > MIXED_FRACTION * ok.sum():
        rates = pd.Series(np.round(1 / mean_dt[ok], 1)).value_counts()
        desc = ", ".join(f"{n} trials at {hz:g} Hz" for hz, n in rates.head(4).items())
        raise DataFormatError(f"{source}: mixed sampling rates ({desc}); split the file by rate or "
                              f"resample every trial to one rate")
    dt = float(np.median(mean_dt[ok & ~off]))
    for i, key in enumerate(keys):
        if reasons[i]:
            continue
        r = np.asarray(groups[key])
        if off[i]:
            reasons[i] = (f"sampled at {1 / mean_dt[i]:.1f} Hz, the file at {1 / dt:.1f} Hz "
                          f"(mean interval {mean_dt[i]:.4f} s vs {dt:.4f} s)")
            continue
        d = np.diff(t_all[r])
        irregular = np.abs(d / dt - 1) > INTERVAL_TOLERANCE
        if irregular.any():
            k = int(np.flatnonzero(irregular)[0]) + 1
            reasons[i] = (f"irregular sampling: interval of {d[k - 1]:.4f} s before {loc(r[k])} "
                          f"(the file samples every {dt:.4f} s; missing samples?)")
    return dt


def _check_units(source, keys, groups, pos_all, reasons, dt) -> None:
    """Positions in millimetres (or centimetres) raise; a single trial with a huge span is invalid."""
    idx = [i for i in range(len(keys)) if not reasons[i]]
    if not idx:
        return
    span = np.array([np.ptp(pos_all[groups[keys[i]]], axis=0).max() for i in idx])
    speed95 = np.array([np.percentile(np.linalg.norm(np.diff(pos_all[groups[keys[i]]], axis=0), axis=1), 95)
                        for i in idx]) / dt
    if np.median(span) > MAX_RANGE_M or np.median(speed95) > MAX_TYPICAL_SPEED:
        raise DataFormatError(
            f"{source}: positions look like millimetres or centimetres, not metres (a typical trial spans "
            f"{np.median(span):.3g} and moves at up to {np.median(speed95):.3g} per s; a hand-held device spans "
            f"well under {MAX_RANGE_M:g} m): write x, y, z in metres (divide millimetres by 1000, centimetres by 100)")
    for j, i in enumerate(idx):
        if span[j] > MAX_RANGE_M:
            reasons[i] = f"positions span {span[j]:.3g} m (more than {MAX_RANGE_M:g} m): a glitch or wrong units"


def read_recordings(path: str | Path) -> Recordings:
    """Read and validate a recordings CSV (format: module docstring).

    Raises :class:`DataFormatError` naming the file (and line, column) when the file is missing or
    empty, a required column is missing, a cell is not a number, an id is empty, ``contact`` is not 0/1,
    positions look like millimetres, time stamps like milliseconds, or trials mix sampling rates.
    Trial-level problems (time going backwards or repeated, NaN/inf positions, too few samples, rows not
    contiguous, a trial sampled at another rate or irregularly) mark that trial ``invalid`` with a reason;
    contact and onset are checked by :func:`skilllib.features.trial_features`.
    """
    path = Path(path)
    return recordings_from_frame(_read_table(path), str(path), _is_file=True)


def _fmt(values: np.ndarray, decimals: int) -> list[str]:
    v = np.round(np.asarray(values, dtype=float), decimals) + 0.0  # + 0.0 turns -0.0 into 0.0
    return [f"{a:.{decimals}f}" for a in v]


def format_recordings(data: pd.DataFrame | Recordings) -> str:
    """The CSV text of ``data`` (rows in their order): t to 0.1 ms, positions to 0.01 mm, '\\n' line ends.

    Deterministic: the same table always gives the same text (no locale, no -0.00000).
    """
    df = data.frame if isinstance(data, Recordings) else data
    missing = [c for c in COLUMNS if c not in df.columns]
    if missing:
        raise ValueError(f"cannot write recordings: column(s) {missing} missing")
    out = pd.DataFrame({
        "participant": df["participant"].astype(str).to_numpy(),
        "trial": df["trial"].astype(np.int64).astype(str).to_numpy(),
        "t": _fmt(df["t"], T_DECIMALS),
        **{c: _fmt(df[c], POS_DECIMALS) for c in POSITION_COLUMNS},
        "contact": [f"{c:.0f}" if np.isfinite(c) else "" for c in df["contact"].to_numpy(dtype=float)],
    })
    buf = io.StringIO()
    out.to_csv(buf, index=False, lineterminator="\n")
    return buf.getvalue()


def write_recordings(data: pd.DataFrame | Recordings, path: str | Path) -> Path:
    """Write ``data`` as a recordings CSV (:func:`format_recordings`, UTF-8); returns the path."""
    path = Path(path)
    path.write_bytes(format_recordings(data).encode("utf-8"))
    return path
