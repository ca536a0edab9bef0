"""The open recordings format: one long table, read, validated and written.

A long table, one row per sample, columns ``participant, trial, t, x, y, z, contact``:

=============  =====  ===================================================================
column         unit   meaning
=============  =====  ===================================================================
participant    --     participant id: text, read exactly as written (``01``, ``1`` and ``NA`` differ)
trial          --     trial id within the participant: text, read exactly as written
t              s      time stamp of the sample (any origin; increasing within a trial)
x, y, z        m      tool-tip position: x mediolateral, y vertical (up), z anteroposterior
contact        0/1    1 when the tip touches the contact surface
=============  =====  ===================================================================

The rows of one trial are contiguous and time-ordered; other columns are ignored. This is the format
of the book's synthetic cohort (:mod:`skilllib.datasets`, :mod:`skilllib.cohort`) and of a user's own
recordings; :mod:`skilllib.formats` turns C3D and TRC files, folders of them, and tables with other
column names, units or axes into it.

**Identifiers are text.** They are never converted to numbers: ``01`` and ``1`` are two participants,
``NA`` is a participant, a 17-digit id keeps every digit. Surrounding spaces are removed; an empty id is
an error. A DataFrame given through the API may hold numbers: they are written as text (``str``, and an
integer-valued float without its ``.0``). Tables and figures order ids naturally (:func:`natural_key`:
``P2`` before ``P10``).

**Files.** A CSV, optionally compressed (``.gz``, ``.bz2``, ``.zip``, ``.xz``, ``.zst``: read as pandas
does, inferred from the extension); UTF-8 with or without a byte-order mark. Line numbers in messages
count physical lines of the file (a quoted cell spanning lines counts all of them).

Problems with the *file* raise :class:`DataFormatError` (a ``ValueError``) with one line naming the file
and, where it applies, the line and column. Problems with a *trial* never raise: the trial is kept,
marked ``invalid`` in :attr:`Recordings.trials` with the reason, and the rest is analysed. Time stamps
(sampling rate, trials at another rate, jitter and dropped frames, resampled onto a uniform grid) are
checked by :mod:`skilllib.timing`.
"""
from __future__ import annotations

import io
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from . import timing
from .csvtable import MAX_QUOTE, DataFormatError, quote, read_table, record_lines  # noqa: F401  (re-exported)
from .timing import MIN_RATE_HZ, MIXED_FRACTION, RATE_TOLERANCE  # noqa: F401  (re-exported)

COLUMNS = ("participant", "trial", "t", "x", "y", "z", "contact")
ID_COLUMNS = ("participant", "trial")
POSITION_COLUMNS = ("x", "y", "z")
MIN_SAMPLES = 5  #: fewer samples than this make a trial invalid
MAX_RANGE_M = 2.0  #: a trial spanning more than this (m) has wrong units or a glitch (device: 0.38 m)
MAX_TYPICAL_SPEED = 20.0  #: m/s; a typical (median over trials of the 95th percentile) speed above it: wrong units
T_DECIMALS, POS_DECIMALS = 4, 5  #: writer's rounding: 0.1 ms and 0.01 mm
#: Cells of the numeric columns read as missing (NaN), as pandas reads them by default.
NA_TEXT = frozenset({"", "NA", "N/A", "n/a", "NaN", "nan", "-nan", "-NaN", "NULL", "null", "None", "#N/A"})


@dataclass(frozen=True)
class Trial:
    """The samples of one trial: ``t`` (N,) in s, ``pos`` (N, 3) in m (x, y, z), ``contact`` (N,) bool
    (resampled onto a uniform grid when the trial's time stamps were irregular)."""

    participant: str
    trial: str
    t: np.ndarray
    pos: np.ndarray
    contact: np.ndarray


def _id(v: Any) -> str:
    """An id given through the API as text: str as it is; an integer-valued number without ``.0``."""
    if isinstance(v, str):
        return v
    if isinstance(v, (float, np.floating)) and float(v).is_integer():
        return str(int(v))
    return str(v)


@dataclass(frozen=True, eq=False)
class Recordings:
    """Validated recordings.

    ``frame``: the samples as read (columns :data:`COLUMNS`, input order, ids as text, index = 0-based
    data row); ``trials``: one row per trial in order of first appearance, columns ``participant, trial,
    n_samples, first_line, status`` (``ok`` or ``invalid``), ``reason`` (empty when ok) and ``timing``
    (empty, or what resampling onto the uniform grid bridged: ``"resampled: jitter up to 1.9 ms, 1
    dropped frame"``); ``fs``: sampling rate in Hz derived from the time stamps; ``source``: the file
    (or ``<DataFrame>``).
    """

    frame: pd.DataFrame
    trials: pd.DataFrame
    fs: float
    source: str
    _rows: dict = field(repr=False)
    _resampled: dict = field(repr=False, default_factory=dict)

    def trial(self, participant: Any, trial: Any) -> Trial:
        """The samples of one trial (whatever its status; resampled when its timing says so); KeyError if
        there is no such trial. Ids are text; a number given here is looked up as its text (``1`` -> ``"1"``)."""
        key = (_id(participant), _id(trial))
        if key not in self._rows:
            raise KeyError(f"no trial {key[1]!r} of participant {key[0]!r} in {self.source}")
        if key in self._resampled:
            return self._resampled[key]
        r = self._rows[key]
        f = self.frame
        return Trial(key[0], key[1], f["t"].to_numpy()[r], f[list(POSITION_COLUMNS)].to_numpy()[r],
                     f["contact"].to_numpy()[r] == 1)

    def keys(self) -> list[tuple[str, str]]:
        """(participant, trial) of every trial, in order of first appearance."""
        return list(self._rows)

    def __len__(self) -> int:
        return len(self._rows)


def natural_key(label: Any) -> tuple:
    """Sort key that orders ids as people do: digit runs by value (``P2`` < ``P10``, ``2`` < ``10``),
    then the text itself, so that ``01`` and ``1`` keep a fixed order."""
    s = str(label)
    return tuple((0, int(p), p) if p.isdigit() else (1, 0, p) for p in re.split(r"(\d+)", s) if p), s


def sort_ids(labels: Iterable[Any]) -> list:
    """``labels`` sorted by :func:`natural_key`."""
    return sorted(labels, key=natural_key)


def _where(source: str, place: str, column: str) -> str:
    """"file, line 12, column 'x'" (``place`` from the caller's ``loc``)."""
    return f"{source}, {place}, column '{column}'"


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
        else:
            hint = "; other names can be mapped with --columns old=new,... (skilllib.formats.map_frame)"
        raise DataFormatError(f"{source}: required column '{missing[0]}' missing (found: {quote(found)[1:-1]}; "
                              f"expected: {', '.join(COLUMNS)}){hint}")
    return df


def _blank(col: pd.Series) -> np.ndarray:
    """Cells that are empty: NaN/None, or text of spaces only."""
    empty = col.isna().to_numpy().copy()
    if col.dtype == object or pd.api.types.is_string_dtype(col):
        empty |= (col.astype("string").str.strip() == "").fillna(True).to_numpy(dtype=bool)
    return empty


def _numeric(col: pd.Series, name: str, source: str, loc: Callable[[int], str]) -> np.ndarray:
    """Column as float; DataFormatError at the first cell that is not a number (:data:`NA_TEXT` is NaN)."""
    if pd.api.types.is_numeric_dtype(col) and not pd.api.types.is_bool_dtype(col):
        return col.to_numpy(dtype=float)
    text = col.astype("string").str.strip()
    missing = (text.isna() | text.isin(NA_TEXT)).to_numpy()
    num = pd.to_numeric(text.mask(missing), errors="coerce")
    bad = num.isna().to_numpy() & ~missing
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DataFormatError(f"{_where(source, loc(i), name)}: {quote(text.iloc[i])} is not a number")
    return num.to_numpy(dtype=float, na_value=np.nan)


def _ids(df: pd.DataFrame, source: str, loc: Callable[[int], str]) -> tuple[np.ndarray, np.ndarray]:
    """Participant and trial ids as text (object arrays of str); error at an empty id."""
    out = []
    for name in ID_COLUMNS:
        col = df[name]
        if col.dtype == object or pd.api.types.is_string_dtype(col):
            text = np.array([v.strip() if isinstance(v, str) else ("" if v is None or v is pd.NA or
                             (isinstance(v, float) and np.isnan(v)) else _id(v)) for v in col], dtype=object)
        else:  # numbers given through the API
            values = col.to_numpy()
            text = np.array(["" if isinstance(v, float) and np.isnan(v) else _id(v) for v in values], dtype=object)
        empty = text == ""
        if empty.any():
            i = int(np.flatnonzero(empty)[0])
            raise DataFormatError(f"{_where(source, loc(i), name)}: {name} is empty")
        out.append(text)
    return out[0], out[1]


def _trial_problem(t: np.ndarray, pos: np.ndarray, contact: np.ndarray, rows: np.ndarray,
                   line: Callable[[int], int], loc: Callable[[int], str]) -> str:
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


def recordings_from_frame(df: pd.DataFrame, source: str = "<DataFrame>", *, lines: np.ndarray | None = None,
                          places: np.ndarray | None = None) -> Recordings:
    """Validate a long table into :class:`Recordings`; see :func:`read_recordings`. ``lines``: the
    physical file line of each row (as :func:`read_table` gives); ``places``: a text per row naming where
    it came from (``"P01/3.c3d, frame 12"``, for tables read from several files); else messages name
    0-based rows."""
    if not isinstance(df, pd.DataFrame):
        raise DataFormatError(f"{source}: expected a pandas DataFrame, got {type(df).__name__}")
    df = _check_columns(df, source)
    blank = np.logical_and.reduce([_blank(df[c]) for c in COLUMNS])  # blank lines (kept for line numbers)
    kept = np.flatnonzero(~blank)
    df = df.loc[~blank].reset_index(drop=True)
    if df.empty:
        raise DataFormatError(f"{source}: file is empty (a header but no data rows)")
    where = lines[kept] if lines is not None else kept

    def line(r: int) -> int:  # the physical file line (or 0-based frame row) of kept row r
        return int(where[r])

    def loc(r: int) -> str:
        if places is not None:
            return str(places[kept[r]])
        return f"line {line(r)}" if lines is not None else f"row {line(r)}"

    cols = {c: _numeric(df[c], c, source, loc) for c in ("t", "x", "y", "z", "contact")}
    part, tr = _ids(df, source, loc)
    c = cols["contact"]
    bad = np.isfinite(c) & (c != 0) & (c != 1) | np.isinf(c)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DataFormatError(f"{_where(source, loc(i), 'contact')}: contact must be 0 or 1, got {c[i]:g}")
    frame = pd.DataFrame({"participant": part, "trial": tr, **cols})
    groups = frame.groupby(["participant", "trial"], sort=False).indices
    pos_all = frame[list(POSITION_COLUMNS)].to_numpy()
    t_all, c_all = cols["t"], cols["contact"]
    keys = list(groups)
    reasons = [_trial_problem(t_all[groups[k]], pos_all[groups[k]], c_all[groups[k]], np.asarray(groups[k]),
                              line, loc) for k in keys]
    timings = [""] * len(keys)
    resampled: dict[tuple[str, str], Trial] = {}
    fs = np.nan
    if any(not r for r in reasons):
        dt = _check_rates(source, keys, groups, t_all, reasons)
        _check_units(source, keys, groups, pos_all, reasons, dt)
        for i, key in enumerate(keys):
            if reasons[i]:
                continue
            r = np.asarray(groups[key])
            irr = timing.irregularity(t_all[r], dt)
            if irr.gap:
                reasons[i] = (f"gap in the time stamps: {irr.max_interval:.4f} s before {loc(r[irr.at])}, "
                              f"{irr.max_interval / dt:.1f} sampling intervals (the file samples every {dt:.4f} s; "
                              f"at most {timing.MAX_GAP_INTERVALS:g} are bridged by resampling)")
            elif not irr.regular:
                t_u, pos_u, con_u = timing.resample_uniform(t_all[r], pos_all[r], c_all[r] == 1, dt)
                resampled[key] = Trial(key[0], key[1], t_u, pos_u, con_u)
                timings[i] = f"resampled: {irr.describe()}"
        fs = 1.0 / dt
    trials = pd.DataFrame({
        "participant": [k[0] for k in keys], "trial": [k[1] for k in keys],
        "n_samples": [len(groups[k]) for k in keys], "first_line": [line(groups[k][0]) for k in keys],
        "status": ["invalid" if r else "ok" for r in reasons], "reason": reasons, "timing": timings})
    rows = {k: np.asarray(groups[k]) for k in keys}
    return Recordings(frame=frame, trials=trials, fs=fs, source=source, _rows=rows, _resampled=resampled)


def _check_rates(source, keys, groups, t_all, reasons) -> float:
    """Time units and mixed rates (errors), single off-rate trials (invalid); returns the file's
    sampling interval in s (see :mod:`skilllib.timing`)."""
    usable = [i for i in range(len(keys)) if not reasons[i]]
    med_dt = np.full(len(keys), np.nan)
    mean_dt = np.full(len(keys), np.nan)
    for i in usable:
        t = t_all[groups[keys[i]]]
        med_dt[i] = float(np.median(np.diff(t)))
        mean_dt[i] = timing.regular_mean_interval(t)
    ok = ~np.isnan(med_dt)
    ref = float(np.median(med_dt[ok]))
    if ref > 1 / MIN_RATE_HZ:
        raise DataFormatError(f"{source}: {timing.time_unit_advice(ref)}")
    off = np.abs(med_dt / ref - 1) > RATE_TOLERANCE  # NaN compares False
    if off.sum() > MIXED_FRACTION * ok.sum():
        rates = pd.Series(np.round(1 / mean_dt[ok], 1)).value_counts()
        desc = ", ".join(f"{n} trials at {hz:g} Hz" for hz, n in rates.head(4).items())
        raise DataFormatError(f"{source}: mixed sampling rates ({desc}); split the file by rate or "
                              f"resample every trial to one rate")
    dt = float(np.median(mean_dt[ok & ~off]))
    for i in np.flatnonzero(off):
        reasons[i] = (f"sampled at {1 / mean_dt[i]:.1f} Hz, the file at {1 / dt:.1f} Hz "
                      f"(mean interval {mean_dt[i]:.4f} s vs {dt:.4f} s)")
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
            f"well under {MAX_RANGE_M:g} m): write x, y, z in metres (divide millimetres by 1000, centimetres by "
            f"100), or give the unit: --units mm")
    for j, i in enumerate(idx):
        if span[j] > MAX_RANGE_M:
            reasons[i] = f"positions span {span[j]:.3g} m (more than {MAX_RANGE_M:g} m): a glitch or wrong units"


def read_recordings(path: str | Path) -> Recordings:
    """Read and validate a recordings CSV (format: module docstring; compressed files as pandas infers).

    Raises :class:`DataFormatError` naming the file (and line, column) when the file is missing or
    empty, a required column is missing, a cell is not a number, an id is empty, ``contact`` is not 0/1,
    positions look like millimetres, time stamps like milliseconds or microseconds, or trials mix sampling
    rates. Trial-level problems (time going backwards or repeated, a gap in the time stamps, NaN/inf
    positions, too few samples, rows not contiguous, a trial sampled at another rate) mark that trial
    ``invalid`` with a reason; contact and onset are checked by :func:`skilllib.features.trial_features`.
    For C3D and TRC files, folders and other column names see :func:`skilllib.formats.load_recordings`.
    """
    path = Path(path)
    df, lines = read_table(path)
    return recordings_from_frame(df, str(path), lines=lines)


def _fmt(values: np.ndarray, decimals: int) -> list[str]:
    v = np.round(np.asarray(values, dtype=float), decimals) + 0.0  # + 0.0 turns -0.0 into 0.0
    return [f"{a:.{decimals}f}" for a in v]


def format_recordings(data: pd.DataFrame | Recordings) -> str:
    """The CSV text of ``data`` (rows in their order): ids as text, t to 0.1 ms, positions to 0.01 mm,
    '\\n' line ends. Deterministic: the same table always gives the same text (no locale, no -0.00000).
    """
    df = data.frame if isinstance(data, Recordings) else data
    missing = [c for c in COLUMNS if c not in df.columns]
    if missing:
        raise ValueError(f"cannot write recordings: column(s) {missing} missing")
    out = pd.DataFrame({
        "participant": [_id(v) for v in df["participant"]],
        "trial": [_id(v) for v in df["trial"]],
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
