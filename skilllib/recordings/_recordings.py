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
recordings; :mod:`skilllib.recordings` turns C3D and TRC files, folders of them, and tables with other
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
checked by :mod:`skilllib.recordings`.
"""

from __future__ import annotations

import io
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from . import _checks as checks
from . import _defects as defects
from . import _timing as timing
from ._checks import (
    _check_rates,
    _check_units,
)
from ._columns import COLUMNS, ID_COLUMNS, POSITION_COLUMNS
from ._csv import SEPARATORS, read_plain, read_table, split_words, with_file_ids
from ._errors import DataFormatError, quote
from ._parquet import is_parquet, read_parquet, release_arrow_memory, with_skipped
from ._runs import Runs

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

    Attributes
    ----------
    frame : pandas.DataFrame
        The samples: ``participant, trial`` (text), ``t`` (s), ``x, y, z`` (m), ``contact`` (0/1).
    trials : pandas.DataFrame
        One row per trial: ``participant, trial`` (text), ``n_samples`` (samples), ``first_line``,
        ``status``, ``reason``, ``timing`` (text).
    fs : float
        The sampling rate derived from the time stamps (Hz).
    source : str
        The file read, or ``<DataFrame>`` (text).
    notes : tuple of str
        What the readers noticed in the files but did not refuse (a TRC header announcing more frames than
        the file holds, C3D frame counts that disagree, ...), each naming its file (text).
    skipped : tuple of SkippedFile or None
        For a folder of trial files (:func:`skilllib.recordings.read_folder`), the entries it holds that are
        not read at all, each with its reason (hidden, a broken link, another format, ...; text); None for
        any other input.
    events : pandas.DataFrame or None
        The events read with the recordings (C3D ``EVENT`` parameters; :func:`skilllib.recordings.read_c3d`):
        one row per event, columns ``participant, trial, label`` (text) and ``t`` (s, on the clock of the
        trial's ``t``), ordered by trial, then time; None when nothing read carries events.
        :meth:`trial_events` gives one trial's.
    """

    frame: pd.DataFrame
    trials: pd.DataFrame
    fs: float
    source: str
    _rows: dict = field(repr=False)
    _resampled: dict = field(repr=False, default_factory=dict)  # key -> Trial: replaced (resampled, repaired)
    _repaired: dict = field(repr=False, default_factory=dict)  # key -> bool mask of the repaired samples
    _cache: dict = field(repr=False, default_factory=dict, compare=False)
    notes: tuple = ()
    skipped: tuple | None = None
    events: pd.DataFrame | None = None

    def trial_events(self, participant: Any, trial: Any) -> dict[str, np.ndarray]:
        """The events of one trial, by label.

        Parameters
        ----------
        participant, trial : Any
            The trial's ids (text; a number is looked up as its text).

        Returns
        -------
        dict of str to numpy.ndarray
            Label (text, as written; with a context also ``"CONTEXT LABEL"``) -> the event times, sorted (s,
            on the clock of :meth:`trial`'s ``t``); empty when the trial has no events.

        Raises
        ------
        KeyError
            When there is no such trial.
        """
        key = (_id(participant), _id(trial))
        if key not in self._rows:
            raise KeyError(f"no trial {key[1]!r} of participant {key[0]!r} in {self.source}")
        if self.events is None or self.events.empty:
            return {}
        if "events" not in self._cache:
            groups: dict[tuple[str, str], dict[str, np.ndarray]] = {}
            ev = self.events
            for (p, t, label), times in ev.groupby(["participant", "trial", "label"], sort=False)["t"]:
                groups.setdefault((p, t), {})[label] = np.sort(times.to_numpy(dtype=float))
            self._cache["events"] = groups
        return dict(self._cache["events"].get(key, {}))

    def trial(self, participant: Any, trial: Any) -> Trial:
        """The samples of one trial (whatever its status; resampled when its timing says so); KeyError if
        there is no such trial. Ids are text; a number given here is looked up as its text (``1`` -> ``"1"``)."""
        key = (_id(participant), _id(trial))
        if key not in self._rows:
            raise KeyError(f"no trial {key[1]!r} of participant {key[0]!r} in {self.source}")
        if key in self._resampled:
            return self._resampled[key]
        r = self._rows[key]
        t, pos, contact = self.arrays()
        return Trial(key[0], key[1], t[r], pos[r], contact[r])

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The samples of :attr:`frame` as flat arrays (kept after the first call): ``t`` (R,) s, ``pos``
        (R, 3) m, ``contact`` (R,) bool. Trial rows as :meth:`runs` gives them (resampled trials excepted)."""
        if "arrays" not in self._cache:
            f = self.frame
            self._cache["arrays"] = (
                f["t"].to_numpy(dtype=float),
                f[list(POSITION_COLUMNS)].to_numpy(dtype=float),
                f["contact"].to_numpy() == 1,
            )
        return self._cache["arrays"]

    def runs(self) -> Runs:
        """Trial ``i`` (order of :attr:`trials`) as rows ``start[i] .. start[i] + length[i] - 1`` of
        :meth:`arrays`; meaningful for trials whose rows are contiguous (every usable trial)."""
        if "runs" not in self._cache:
            rows = [self._rows[k] for k in self.keys()]
            start = np.array([r[0] if len(r) else 0 for r in rows], dtype=np.int64)
            length = np.array([len(r) for r in rows], dtype=np.int64)
            self._cache["runs"] = Runs(start, length)
        return self._cache["runs"]

    def is_resampled(self, participant: Any, trial: Any) -> bool:
        """Whether :meth:`trial` gives other samples than :attr:`frame`'s: resampled onto the uniform grid
        (``timing``) or repaired (``repairs``, :meth:`is_repaired`)."""
        return (_id(participant), _id(trial)) in self._resampled

    def is_repaired(self, participant: Any, trial: Any) -> bool:
        """Whether some of the trial's samples were repaired (``repairs`` of :attr:`trials`)."""
        return (_id(participant), _id(trial)) in self._repaired

    def repaired_mask(self, participant: Any, trial: Any) -> np.ndarray:
        """Which samples of :meth:`trial` were replaced by interpolation (frozen, jumps, gaps).

        Parameters
        ----------
        participant, trial : Any
            The trial's ids (text; a number is looked up as its text).

        Returns
        -------
        numpy.ndarray
            Bool, aligned with ``trial(participant, trial).t`` (all False for a trial without repairs).
        """
        key = (_id(participant), _id(trial))
        if key in self._repaired:
            return self._repaired[key]
        return np.zeros(len(self.trial(*key).t), dtype=bool)

    def keys(self) -> list[tuple[str, str]]:
        """(participant, trial) of every trial, in order of first appearance."""
        return list(self._rows)

    def __len__(self) -> int:
        return len(self._rows)


def natural_key(label: Any) -> tuple:
    """Sort key that orders ids and file names as people (and file managers) do.

    Digit runs by value (``P2`` < ``P10``, ``2`` < ``10``), other runs ignoring case (``p2`` between
    ``P1`` and ``P10``), then the text itself, so that ``01`` and ``1``, ``P1`` and ``p1`` keep a fixed
    order. The one key of the package: the folder reader orders files, Parquet parts and tables their ids
    with it.

    Parameters
    ----------
    label : Any
        An id or file name (text, or anything its ``str`` is taken of).

    Returns
    -------
    tuple
        The sort key.
    """
    s = str(label)
    return tuple((0, int(p), "") if p.isdigit() else (1, 0, p.casefold()) for p in re.split(r"(\d+)", s) if p), s


def sort_ids(labels: Iterable[Any]) -> list:
    """``labels`` sorted by :func:`natural_key`.

    Parameters
    ----------
    labels : iterable
        Ids or file names (text).

    Returns
    -------
    list
        The labels in natural order.
    """
    return sorted(labels, key=natural_key)


EVENT_COLUMNS = ("participant", "trial", "label", "t")  #: columns of :attr:`Recordings.events`


def events_frame(events: Iterable[tuple[Any, Any, str, float]]) -> pd.DataFrame | None:
    """The events table of :class:`Recordings` from ``(participant, trial, label, time)`` rows.

    Parameters
    ----------
    events : iterable of tuple
        ``(participant, trial, label, t)``: ids and label (text; numbers as their text), time (s).

    Returns
    -------
    pandas.DataFrame or None
        Columns ``participant, trial, label`` (text) and ``t`` (s), rows in the order given, ids as text;
        None when there are no events.
    """
    rows = [(_id(p), _id(tr), str(label), float(t)) for p, tr, label, t in events]
    if not rows:
        return None
    out = pd.DataFrame(rows, columns=list(EVENT_COLUMNS))
    out["t"] = out["t"].astype(float)
    return out


def _where(source: str, place: str, column: str) -> str:
    """ "file, line 12, column 'x'" (``place`` from the caller's ``loc``)."""
    return f"{source}, {place}, column '{column}'"


def _check_columns(df: pd.DataFrame, source: str) -> pd.DataFrame:
    sep = df.attrs.get("sep")  # a file's separator (skilllib.recordings.read_table), for the message
    df = df.rename(columns=lambda c: str(c).strip())
    missing = [c for c in COLUMNS if c not in df.columns]
    if missing:
        found = ", ".join(map(str, df.columns))
        hint = ""
        seps = [s for s in SEPARATORS if s != sep and s in found]
        if len(df.columns) == 1 and seps:
            hint = f"; the file seems to be split at {SEPARATORS[seps[0]]}: give the separator with --sep"
        elif any(str(c).lower() in COLUMNS for c in df.columns):
            hint = "; column names are lower case"
        else:
            hint = "; other names can be mapped with --columns old=new,... (skilllib.recordings.map_frame)"
        how = split_words(sep)
        head = f"columns found ({how})" if how else "found"
        raise DataFormatError(
            f"{source}: required column '{missing[0]}' missing ({head}: {quote(found)[1:-1]}; "
            f"expected: {', '.join(COLUMNS)}){hint}"
        )
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


def _id_text(v: Any) -> str:
    """One id cell as text: a string stripped; missing (None, NA, NaN) as ""; a number as :func:`_id`."""
    if isinstance(v, str):
        return v.strip()
    if v is None or v is pd.NA or (isinstance(v, float) and np.isnan(v)):
        return ""
    return _id(v)


def _factorize(col: pd.Series) -> tuple[np.ndarray, np.ndarray]:
    """``pd.factorize(col)`` (codes, -1 for missing; the distinct values in order of first appearance);
    an Arrow-backed column is encoded by pyarrow with 32-bit codes, without 64-bit temporaries."""
    if isinstance(col.dtype, pd.ArrowDtype):
        import pyarrow.compute as pc

        enc = pc.dictionary_encode(col.array._pa_array).combine_chunks()
        return enc.indices.fill_null(-1).to_numpy(), np.asarray(enc.dictionary.to_pylist(), dtype=object)
    return pd.factorize(col, use_na_sentinel=True)


def _ids(df: pd.DataFrame, source: str, loc: Callable[[int], str]) -> list[tuple[np.ndarray, np.ndarray]]:
    """Participant and trial ids as text: per column ``(codes, names)``, the row's code into the distinct
    names (object array of str, order of first appearance). Each distinct cell is converted once
    (:func:`_id_text`), not each row. DataFormatError at the first empty id."""
    out = []
    for name in ID_COLUMNS:
        raw_codes, uniques = _factorize(df[name])
        text = np.array([_id_text(u) for u in np.asarray(uniques, dtype=object)] + [""], dtype=object)
        merged, names = pd.factorize(text)  # "01" and " 01" are one id; NA (code -1: the last entry) is ""
        codes = merged.astype(np.int32)[raw_codes]
        del raw_codes
        names = np.asarray(names, dtype=object)
        empty = np.flatnonzero(names == "")
        if empty.size and (codes == empty[0]).any():
            i = int(np.argmax(codes == empty[0]))
            raise DataFormatError(f"{_where(source, loc(i), name)}: {name} is empty")
        out.append((codes, names))
    return out


def recordings_from_frame(
    df: pd.DataFrame,
    source: str = "<DataFrame>",
    *,
    lines: np.ndarray | range | None = None,
    places: np.ndarray | None = None,
    place: Callable[[int], str] | None = None,
    rate: tuple[float, float] | None = None,
    units_known: bool = False,
    max_gap_s: float = defects.MAX_GAP_S,
    fill: str = "cubic",
) -> Recordings:
    """Validate a long table into :class:`Recordings`; see :func:`read_recordings`.

    Messages name the physical file line (``lines``), a place text (``places``, ``place``), else the
    0-based row. The per-trial statistics are kept in ``_cache["stats"]``.

    Parameters
    ----------
    df : pandas.DataFrame
        The long table: ``participant, trial`` (text), ``t`` (s), ``x, y, z`` (m), ``contact`` (0/1).
    source : str
        The name of the table in messages (text).
    lines : numpy.ndarray, range or None
        The physical file line of each row (as :func:`read_table` gives; dimensionless), or None.
    places : numpy.ndarray or None
        A text per row naming where it came from (``"P01/3.c3d, frame 12"``, for tables read from
        several files; text), or None.
    place : callable or None
        The same as a function of the 0-based row (:func:`skilllib.recordings.read_parquet`; text), or None.
    rate : tuple of float or None
        ``(ref, dt)`` (s): the median of the trials' median intervals and the sampling interval of a whole
        corpus this table is a part of (:mod:`skilllib.features`); trials are judged against them, and the
        corpus-wide errors (mixed rates, units) are left to the caller. ``(nan, nan)``: no rate is decided
        (fs NaN). None: decided from this table.
    units_known : bool
        Whether the positions' unit is stated (a file header's, or given with ``--units``): then the "not
        metres" plausibility checks are skipped (:func:`skilllib.recordings.check_corpus_units`) and only a
        span beyond :data:`skilllib.recordings.MAX_KNOWN_RANGE_M` marks a trial invalid; False: guessed.
    max_gap_s : float
        The longest gap of missing (or frozen, or jumping) positions filled by interpolation (s); longer
        gaps before contact make a trial invalid, after contact cut it (:func:`repair_trial`).
    fill : str
        How short gaps are filled: ``"cubic"`` or ``"linear"`` (text).

    Returns
    -------
    Recordings
        The validated recordings (t in s, positions in m, fs in Hz).

    Raises
    ------
    DataFormatError
        For what makes the whole table unreadable, as :func:`read_recordings`.
    """
    if not isinstance(df, pd.DataFrame):
        raise DataFormatError(f"{source}: expected a pandas DataFrame, got {type(df).__name__}")
    df = _check_columns(df, source)
    blank = np.ones(len(df), dtype=bool)  # blank lines (kept for line numbers): every cell empty
    numeric = {c: pd.api.types.is_numeric_dtype(df[c]) for c in COLUMNS}
    for c in sorted(COLUMNS, key=lambda c: not numeric[c]):  # cheap columns first
        if blank.any():
            blank[blank] = _blank(df[c][blank])
    kept = np.flatnonzero(~blank) if blank.any() else range(len(df))  # a range: no memory per row
    if blank.any():
        df = df.loc[~blank].reset_index(drop=True)
    del blank
    if df.empty:
        raise DataFormatError(f"{source}: file is empty (a header but no data rows)")
    where = kept if lines is None else lines if isinstance(kept, range) else lines[kept]

    def line(r: int) -> int:  # the physical file line (or 0-based frame row) of kept row r
        return int(where[r])

    def loc(r: int) -> str:
        if place is not None:
            return place(int(kept[r]))
        if places is not None:
            return str(places[kept[r]])
        return f"line {line(r)}" if lines is not None else f"row {line(r)}"

    cols = {c: _numeric(df[c], c, source, loc) for c in ("t", "x", "y", "z", "contact")}
    (p_codes, p_names), (t_codes, t_names) = _ids(df, source, loc)
    c = cols["contact"]
    bad = np.isfinite(c) & (c != 0) & (c != 1) | np.isinf(c)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DataFormatError(f"{_where(source, loc(i), 'contact')}: contact must be 0 or 1, got {c[i]:g}")
    del df
    frame = pd.DataFrame(
        {
            "participant": pd.Categorical.from_codes(p_codes, categories=p_names),
            "trial": pd.Categorical.from_codes(t_codes, categories=t_names),
            **cols,
        },
        copy=False,
    )
    trial_of_row, keys = _trial_numbers(p_codes, t_codes, p_names, t_names)
    del p_codes, t_codes
    counts = np.bincount(trial_of_row, minlength=len(keys))
    order = np.argsort(trial_of_row, kind="stable").astype(np.int32 if len(trial_of_row) < 2**31 else np.int64)
    rows = np.split(order, np.cumsum(counts)[:-1])
    pos_all = _positions(*(cols[c] for c in POSITION_COLUMNS))
    t_all, c_all = cols["t"], cols["contact"]
    reasons = checks.trial_problems(t_all, pos_all, c_all, trial_of_row, rows, line, loc)
    repairs = defects.repair_trials(  # real-data defects: stale frames, frozen, jumps, gaps (counted, said)
        t_all, pos_all, c_all, trial_of_row, rows, ~np.array([bool(r) for r in reasons]),
        max_gap_s=max_gap_s, fill=fill, where=loc,
        max_span_m=checks.MAX_KNOWN_RANGE_M if units_known else defects.MAX_SPAN_M,
    )  # fmt: skip
    for i, rp in repairs.items():
        reasons[i] = rp.reason or (
            f"too few samples after repairs ({len(rp.t)}; need at least {checks.MIN_SAMPLES})"
            if len(rp.t) < checks.MIN_SAMPLES
            else ""
        )
    timings = [""] * len(keys)
    resampled: dict[tuple[str, str], Trial] = {}
    fs = np.nan
    usable = np.array([not r for r in reasons], dtype=bool)
    cache: dict = {"arrays": (t_all, pos_all, c_all == 1)}
    if usable.any():
        runs = Runs(np.array([r[0] for r in rows], dtype=np.int64), counts.astype(np.int64))
        with np.errstate(invalid="ignore"):  # NaN positions of trials repaired below
            stats = checks.trial_stats(t_all, pos_all, runs, usable)
        for i, rp in repairs.items():  # the rate is the recording's; span and steps of the repaired samples
            if usable[i]:
                one = checks.trial_stats(rp.t, rp.pos, Runs(np.array([0]), np.array([len(rp.t)])), np.array([True]))
                for name in ("span", "step95", "d_min", "d_max"):
                    getattr(stats, name)[i] = getattr(one, name)[0]
        cache["stats"] = stats
    if usable.any() and (rate is None or np.isfinite(rate[1])):
        dt = _check_rates(source, stats, reasons, rate)
        _check_units(source, stats, reasons, dt, corpus_checked=rate is not None, units_known=units_known)
        dev = np.maximum(np.abs(stats.d_min / dt - 1), np.abs(stats.d_max / dt - 1))  # NaN: not usable
        for i in np.flatnonzero(usable & ~(dev <= timing.JITTER_TOLERANCE)):
            if reasons[i] or i in repairs:  # repaired trials: their timing below, on the repaired samples
                continue
            r, key = rows[i], keys[i]
            irr = timing.irregularity(t_all[r], dt)
            note = ""
            if irr.gap:
                cut = timing.gap_after_contact(t_all[r], c_all[r] == 1, dt)
                if cut is None:
                    reasons[i] = (
                        f"gap in the time stamps: {irr.max_interval:.4f} s before {loc(r[irr.at])}, "
                        f"{irr.max_interval / dt:.1f} sampling intervals (the file samples every {dt:.4f} s; "
                        f"at most {timing.MAX_GAP_INTERVALS:g} are bridged by resampling)"
                    )
                    continue
                note = (
                    f"cut at a {t_all[r][cut] - t_all[r][cut - 1]:.4f} s gap in the time stamps after contact, "
                    f"before {loc(r[cut])} ({len(r) - cut} samples after it not used)"
                )
                r = r[:cut]
                irr = timing.irregularity(t_all[r], dt)
            if irr.regular:
                if note:
                    resampled[key] = Trial(key[0], key[1], t_all[r], pos_all[r], c_all[r] == 1)
                said = irr.describe_regular() if irr.max_jitter > timing.JITTER_TOLERANCE else ""
                timings[i] = "; ".join(x for x in (note, said) if x)
            else:
                t_u, pos_u, con_u = timing.resample_uniform(t_all[r], pos_all[r], c_all[r] == 1, dt)
                resampled[key] = Trial(key[0], key[1], t_u, pos_u, con_u)
                timings[i] = "; ".join(x for x in (note, f"resampled: {irr.describe()}") if x)
        fs = 1.0 / dt
    masks = _repaired_timing(repairs, keys, reasons, timings, resampled, fs, loc, rows)
    trials = pd.DataFrame(
        {
            "participant": [k[0] for k in keys],
            "trial": [k[1] for k in keys],
            "n_samples": counts,
            "first_line": [line(r[0]) for r in rows],
            "status": ["invalid" if r else "ok" for r in reasons],
            "reason": reasons,
            "timing": timings,
            "repairs": [repairs[i].describe() if i in repairs else "" for i in range(len(keys))],
            "n_repaired": [repairs[i].n_repaired if i in repairs else 0 for i in range(len(keys))],
            "n_dropped": [repairs[i].n_dropped if i in repairs else 0 for i in range(len(keys))],
        }
    )
    return Recordings(
        frame=frame,
        trials=trials,
        fs=fs,
        source=source,
        _rows=dict(zip(keys, rows)),
        _resampled=resampled,
        _repaired=masks,
        _cache=cache,
    )


def _repaired_timing(
    repairs: dict[int, defects.Repair],
    keys: list[tuple[str, str]],
    reasons: list[str],
    timings: list[str],
    resampled: dict,
    fs: float,
    loc: Callable[[int], str],
    rows: list[np.ndarray],
) -> dict[tuple[str, str], np.ndarray]:
    """The repaired trials' samples (into ``resampled``, onto the uniform grid when their time stamps are
    irregular, as for any trial) and their repaired masks; a gap in the time stamps makes one invalid."""
    masks = {}
    for i, rp in repairs.items():
        if reasons[i]:
            continue
        key = keys[i]
        t, pos, con, mask = rp.t, rp.pos, rp.contact, rp.repaired
        if np.isfinite(fs):
            dt = 1.0 / fs
            irr = timing.irregularity(t, dt)
            if irr.gap:
                reasons[i] = (
                    f"gap in the time stamps: {irr.max_interval:.4f} s before {loc(rows[i][rp.n_first + irr.at])}, "
                    f"{irr.max_interval / dt:.1f} sampling intervals (the file samples every {dt:.4f} s; "
                    f"at most {timing.MAX_GAP_INTERVALS:g} are bridged by resampling)"
                )
                continue
            if not irr.regular:
                t_u, pos, con = timing.resample_uniform(t, pos, con, dt)
                mask = np.interp(t_u, t, mask.astype(float)) > 0  # a grid sample from a repaired one
                t = t_u
                timings[i] = f"resampled: {irr.describe()}"
        resampled[key] = Trial(key[0], key[1], t, pos, con)
        masks[key] = mask
    return masks


def _trial_numbers(
    p_codes: np.ndarray, t_codes: np.ndarray, p_names: np.ndarray, t_names: np.ndarray
) -> tuple[np.ndarray, list[tuple[str, str]]]:
    """The trial number of each row (0, 1, ... in order of first appearance of its (participant, trial))
    and the trials' ids; computed over the runs of equal consecutive ids, not the rows."""
    change = np.flatnonzero((p_codes[1:] != p_codes[:-1]) | (t_codes[1:] != t_codes[:-1])) + 1
    start = np.concatenate([[0], change])
    run_of, pairs = pd.factorize(p_codes[start].astype(np.int64) * len(t_names) + t_codes[start])
    trial_of_row = np.repeat(run_of.astype(np.int32), np.diff(np.append(start, len(p_codes))))
    keys = [(p_names[k // len(t_names)], t_names[k % len(t_names)]) for k in pairs.tolist()]
    return trial_of_row, keys


def _positions(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """The (R, 3) positions: the array x, y and z are the columns of, when they are (as
    :func:`skilllib.recordings.read_plain` gives them: no copy), else a new one."""
    base = x
    while isinstance(base.base, np.ndarray):
        base = base.base
    if (
        base.shape == (len(x), 3)
        and base.dtype == float
        and all(
            np.shares_memory(v, base) and v.ctypes.data == base[:, j].ctypes.data and v.strides == base[:, j].strides
            for j, v in enumerate((x, y, z))
        )
    ):
        return base
    return np.column_stack([x, y, z])


def read_recordings(
    path: str | Path, sep: str | None = None, *, max_gap_s: float = defects.MAX_GAP_S, fill: str = "cubic"
) -> Recordings:
    """Read and validate a recordings CSV, or a Parquet file or folder of Parquet files.

    Format: module docstring (compressed CSV files as pandas infers); Parquet: :mod:`skilllib.recordings`.
    A plain CSV file (one record per line, no blank line, not compressed) is read by pyarrow's CSV reader,
    any other by pandas' (same result, tested; line numbers in messages count physical lines either way).
    The separator (comma, tab or semicolon) is ``sep`` or detected from the first lines
    (:func:`skilllib.recordings.detect_sep`); a table with neither a ``participant`` nor a ``trial``
    column is one recording named after the file (:func:`skilllib.recordings.file_ids`).

    Trial-level problems (time going backwards or repeated, a gap in the time stamps, NaN/inf positions,
    too few samples, rows not contiguous, a trial sampled at another rate) mark that trial ``invalid`` with
    a reason; contact and onset are checked by :func:`skilllib.features.trial_features`. For C3D and TRC
    files, folders and other column names see :func:`skilllib.recordings.load_recordings`.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file, Parquet file or folder of Parquet files (text).
    sep : str or None
        The CSV's separator (text: ``","``, ``"tab"`` or ``"\\t"``, ``";"``); None: detected.
    max_gap_s : float
        The longest gap of missing, frozen or jumping positions filled by interpolation (s; default
        0.1); longer ones before contact make a trial invalid, after contact cut it
        (:func:`skilllib.recordings.repair_trial`).
    fill : str
        How short gaps are filled: ``"cubic"`` or ``"linear"`` (text).

    Returns
    -------
    Recordings
        The validated recordings (t in s, positions in m, fs in Hz).

    Raises
    ------
    DataFormatError
        Naming the file (and line, column) when the file is missing or empty, a required column is
        missing, a cell is not a number, an id is empty, ``contact`` is not 0/1, positions look like
        millimetres, time stamps like milliseconds or microseconds, or trials mix sampling rates.
    """
    path = Path(path)
    if is_parquet(path):
        frame, where = read_parquet(path, COLUMNS, natural_key)
        rec = recordings_from_frame(frame, str(path), place=where, max_gap_s=max_gap_s, fill=fill)
        skipped = frame.attrs.get("skipped", ())  # a dataset's stray, hidden, metadata files: said
        del frame
        release_arrow_memory()
        return with_skipped(rec, skipped)
    fast = read_plain(path, ID_COLUMNS, ("t", *POSITION_COLUMNS, "contact"), NA_TEXT, sep=sep)
    if fast is not None:  # a plain file: pyarrow's reader; record k is line k + 2
        rec = recordings_from_frame(fast, str(path), lines=range(2, len(fast) + 2), max_gap_s=max_gap_s, fill=fill)
        del fast
        release_arrow_memory()
        return rec
    df, lines = read_table(path, sep)
    rec = recordings_from_frame(with_file_ids(df, path), str(path), lines=lines, max_gap_s=max_gap_s, fill=fill)
    notes = tuple(df.attrs.get("notes", ()))
    return replace(rec, notes=notes) if notes else rec


def _fmt(values: np.ndarray, decimals: int) -> list[str]:
    v = np.round(np.asarray(values, dtype=float), decimals) + 0.0  # + 0.0 turns -0.0 into 0.0
    return [f"{a:.{decimals}f}" for a in v]


def format_recordings(data: pd.DataFrame | Recordings) -> str:
    r"""The CSV text of ``data`` (rows in their order).

    Ids as text, t to 0.1 ms, positions to 0.01 mm, '\n' line ends. Deterministic: the same table always
    gives the same text (no locale, no -0.00000).

    Parameters
    ----------
    data : pandas.DataFrame or Recordings
        The recordings: ids (text), ``t`` (s), ``x, y, z`` (m), ``contact`` (0/1).

    Returns
    -------
    str
        The CSV text (text; t in s, positions in m).
    """
    df = data.frame if isinstance(data, Recordings) else data
    missing = [c for c in COLUMNS if c not in df.columns]
    if missing:
        raise ValueError(f"cannot write recordings: column(s) {missing} missing")
    out = pd.DataFrame(
        {
            "participant": [_id(v) for v in df["participant"]],
            "trial": [_id(v) for v in df["trial"]],
            "t": _fmt(df["t"], T_DECIMALS),
            **{c: _fmt(df[c], POS_DECIMALS) for c in POSITION_COLUMNS},
            "contact": [f"{c:.0f}" if np.isfinite(c) else "" for c in df["contact"].to_numpy(dtype=float)],
        }
    )
    buf = io.StringIO()
    out.to_csv(buf, index=False, lineterminator="\n")
    return buf.getvalue()


def write_recordings(data: pd.DataFrame | Recordings, path: str | Path) -> Path:
    """Write ``data`` as a recordings CSV (:func:`format_recordings`, UTF-8); returns the path.

    Parameters
    ----------
    data : pandas.DataFrame or Recordings
        The recordings: ids (text), ``t`` (s), ``x, y, z`` (m), ``contact`` (0/1).
    path : str or pathlib.Path
        The file to write (text).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    path = Path(path)
    path.write_bytes(format_recordings(data).encode("utf-8"))
    return path
