"""Recordings in other formats: C3D, TRC, CSVs with other names, units and axes, folders of trials.

Everything ends as the book's long table (:mod:`skilllib.recordings`): ``participant, trial, t, x, y, z,
contact`` with identifiers as text, t in s, positions in m with y up, contact 0/1, which
:func:`skilllib.recordings.recordings_from_frame` then validates (:func:`load_recordings` does both, and is
what ``python -m skilllib run --data`` calls). :func:`read_any` dispatches on the path:

============================  =============================================================  ============
path                          read by                                                        trials
============================  =============================================================  ============
a folder                      :func:`~skilllib.recordings.read_folder`                   one per file
``*.c3d``                     :func:`~skilllib.recordings.read_c3d` (c3d)                   one
``*.trc``                     :func:`~skilllib.recordings.read_trc`                         one
anything else (``.csv``,      :func:`read_csv_table` (pandas; compression from the name:     many
``.csv.gz``, ``.zip``, ...)   gzip, zip, bz2, xz, zstd)
============================  =============================================================  ============

Then :func:`~skilllib.recordings.map_frame` renames columns, converts units, rotates the vertical
axis to +y and fills contact from the surface height, as the options ask.

Options (the command line's flags in brackets): ``marker`` (``--marker NAME``), ``contact_channel``
(``--contact-channel NAME``), ``contact_threshold`` (analog threshold in the channel's units),
``contact_height`` (``--contact-height M``), ``units`` (``--units m|cm|mm``), ``up_axis``
(``--up-axis y|-y|z|-z|x|-x``), ``columns`` (``--columns old=new,...``, parsed by
:func:`~skilllib.recordings.parse_columns`), ``name_pattern`` (a regular expression for file names
in a folder).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd

from ._c3d import read_c3d
from ._csv import read_table
from ._errors import DataFormatError, quote
from ._folder import (
    FileProblem,
    compile_pattern,
    file_kind,
    file_stem,
    read_folder,
    read_trial_file,
    trial_ids,
)
from ._mapping import (
    UNIT_FACTORS,
    UP_AXIS_ROTATIONS,
    contact_from_height,
    map_frame,
    parse_columns,
    rename_columns,
    up_axis_rotation,
)
from ._recordings import COLUMNS, NA_TEXT, POSITION_COLUMNS, Recordings, recordings_from_frame
from ._trc import read_trc

ID_COLUMNS = ("participant", "trial")
#: the cells pandas reads as missing by default (pandas.read_csv ``na_values``); kept for every column but the ids
DEFAULT_NA = (
    "",
    "#N/A",
    "#N/A N/A",
    "#NA",
    "-1.#IND",
    "-1.#QNAN",
    "-NaN",
    "-nan",
    "1.#IND",
    "1.#QNAN",
    "<NA>",
    "N/A",
    "NA",
    "NULL",
    "NaN",
    "None",
    "n/a",
    "nan",
    "null",
)


def _csv_error(path: Path, e: Exception) -> DataFormatError:
    if isinstance(e, pd.errors.ParserError):  # e.g. "Expected 7 fields in line 12, saw 8"
        return DataFormatError(
            f"{path}: not a valid CSV table: {str(e).replace('Error tokenizing data. C error: ', '').strip()}"
        )
    if isinstance(e, pd.errors.EmptyDataError):
        return DataFormatError(f"{path}: file is empty")
    if isinstance(e, UnicodeDecodeError):
        return DataFormatError(f"{path}: not a text (UTF-8) CSV file")
    msg = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
    return DataFormatError(f"{path}: cannot be read as a (compressed) CSV file ({msg[:200]})")


def read_csv_table(path: str | Path, *, columns: Mapping[str, str] | None = None) -> pd.DataFrame:
    """A CSV table as pandas reads it (compression inferred from the name), identifiers as text.

    The columns that are, or that ``columns`` renames to, ``participant`` and ``trial`` are read as
    ``str`` exactly as written: ``01`` and ``1``, ``NA``, ``1e20`` and a 17-digit id stay distinct text;
    an empty id is ``''`` (and a blank line NaN in every column, as the validation expects). Other
    columns keep pandas' defaults (numbers; ``NA``, ``nan``, empty are missing). Column names are not
    renamed here (:func:`map_frame` does it); blank lines are kept so that row ``r`` is file line
    ``r + 2``. Raises :class:`~skilllib.recordings.DataFormatError` naming the file when it is missing, a
    folder, empty, not text, not a regular CSV table or a broken archive.
    """
    path = Path(path)
    if not path.exists():
        raise DataFormatError(f"{path}: file not found")
    if path.is_dir():
        raise DataFormatError(f"{path}: is a directory, not a CSV file")
    opts = dict(skipinitialspace=True, skip_blank_lines=False)
    try:
        names = [str(c) for c in pd.read_csv(path, nrows=0, **opts).columns]
        ids = [c for c in names if (columns or {}).get(c.strip(), c.strip()) in ID_COLUMNS]
        df = pd.read_csv(
            path,
            dtype={c: str for c in ids},
            keep_default_na=False,
            na_values={c: list(DEFAULT_NA) for c in names if c not in ids},
            **opts,
        )
    except (
        pd.errors.ParserError,
        pd.errors.EmptyDataError,
        UnicodeDecodeError,
        OSError,
        ValueError,
        EOFError,
        ImportError,
    ) as e:  # a broken gzip, a zip of several files, .zst without zstandard, ...
        raise _csv_error(path, e) from None
    if ids and len(df):
        others = [c for c in df.columns if c not in ids]
        blank = df[others].isna().all(axis=1).to_numpy() & (df[ids] == "").all(axis=1).to_numpy()
        for c in ids:
            col = df[c].astype(object)
            col[blank] = np.nan
            df[c] = col
    return df


def read_any(
    path: str | Path,
    *,
    marker: str | None = None,
    contact_channel: str | None = None,
    contact_threshold: float | None = None,
    units: str | None = None,
    up_axis: str | None = None,
    contact_height: float | None = None,
    columns: Mapping[str, str] | str | None = None,
    name_pattern: str | re.Pattern | None = None,
) -> tuple[pd.DataFrame, list[FileProblem]]:
    """Read recordings from a folder, a ``.c3d`` or ``.trc`` file (one trial) or a CSV table (many).

    Returns ``(frame, problems)``: the long table in the book's frame with identifiers as text (for
    :func:`skilllib.recordings.recordings_from_frame`) and the files of a folder that could not be read
    (:class:`FileProblem`; always empty for a single file, whose problems raise). The dispatch table and
    the options are in the module docstring; ``columns`` may be a ``"old=new,..."`` string.

    A single C3D/TRC file is named like a file directly in a folder: ``PARTICIPANT_TRIAL`` split at the
    last ``_`` (or ``name_pattern``); a stem without ``_`` is participant and trial both.

    Raises :class:`~skilllib.recordings.DataFormatError` (one line naming the file) when the path cannot be
    read as recordings: see :func:`read_folder`, :func:`read_c3d`, :func:`read_trc`,
    :func:`read_csv_table` and :func:`map_frame`.
    """
    path = Path(path)
    cols = parse_columns(columns) if isinstance(columns, str) else columns
    if path.is_dir():
        return read_folder(
            path,
            marker=marker,
            contact_channel=contact_channel,
            contact_threshold=contact_threshold,
            units=units,
            up_axis=up_axis,
            contact_height=contact_height,
            columns=cols,
            name_pattern=name_pattern,
        )
    kind = file_kind(path)
    if kind in ("c3d", "trc"):
        if not path.exists():
            raise DataFormatError(f"{path}: file not found")
        stem = file_stem(path)
        try:
            participant, trial = trial_ids(stem, None, compile_pattern(name_pattern))
        except ValueError:
            if name_pattern is not None:
                raise DataFormatError(f"{path}: name {stem!r} does not match the name pattern") from None
            participant, trial = stem, stem
        df = read_trial_file(
            path,
            marker=marker,
            contact_channel=contact_channel,
            contact_threshold=contact_threshold,
            units=units,
            up_axis=up_axis,
            contact_height=contact_height,
        )
        df.insert(0, "trial", trial)
        df.insert(0, "participant", participant)
        df[list(ID_COLUMNS)] = df[list(ID_COLUMNS)].astype(object)
        return df, []
    table = read_csv_table(path, columns=cols)
    return map_frame(
        table, columns=cols, units=units, up_axis=up_axis, contact_height=contact_height, source=str(path), first_line=2
    ), []


def _numeric_text(df: pd.DataFrame, lines: np.ndarray, source: str) -> pd.DataFrame:
    """The t, x, y, z and contact columns of a text table (:func:`skilllib.recordings.read_table`) as numbers,
    :data:`skilllib.recordings.NA_TEXT` as NaN; a cell that is not a number raises naming its physical line.
    Ids stay text; the id cells of blank lines become NaN, as the mapping expects of a blank line."""
    out = df.copy()
    blank = np.ones(len(df), dtype=bool)
    for c in df.columns:
        text = df[c].astype("string").str.strip()
        blank &= (text.isna() | (text == "")).to_numpy(dtype=bool)
    for c in [c for c in ("t", *POSITION_COLUMNS, "contact") if c in df.columns]:
        text = df[c].astype("string").str.strip()
        missing = (text.isna() | text.isin(NA_TEXT)).to_numpy(dtype=bool)
        num = pd.to_numeric(text.mask(missing), errors="coerce")
        bad = num.isna().to_numpy() & ~missing
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise DataFormatError(f"{source}, line {lines[i]}, column '{c}': {quote(text.iloc[i])} is not a number")
        out[c] = num.to_numpy(dtype=float, na_value=np.nan)
    for c in [c for c in ID_COLUMNS if c in df.columns]:
        col = out[c].astype(object)
        col[blank] = np.nan
        out[c] = col
    return out


def load_recordings(
    data: str | Path | pd.DataFrame | Recordings,
    *,
    columns: Mapping[str, str] | str | None = None,
    units: str | None = None,
    up_axis: str | None = None,
    marker: str | None = None,
    contact_channel: str | None = None,
    contact_threshold: float | None = None,
    contact_height: float | None = None,
    name_pattern: str | re.Pattern | None = None,
) -> Recordings:
    """Validated :class:`~skilllib.recordings.Recordings` from a path (folder, C3D, TRC or CSV, see
    :func:`read_any`), a DataFrame or Recordings, mapped by the options (module docstring).

    A CSV is read as text with its physical line numbers (:func:`skilllib.recordings.read_table`), so that
    messages name file lines; its columns are renamed before anything else, so ``--columns`` may name the
    file's own columns. Files of a folder that cannot be read are kept as ``invalid`` trials with their
    reason (file name and problem), never dropped; messages about a sample of a folder's file name the
    file and the sample. Raises :class:`~skilllib.recordings.DataFormatError` for what cannot be read at all.
    """
    opts = dict(
        columns=parse_columns(columns) if isinstance(columns, str) else columns,
        units=units,
        up_axis=up_axis,
        contact_height=contact_height,
    )
    if isinstance(data, Recordings):
        data = data.frame
    if isinstance(data, pd.DataFrame):
        return recordings_from_frame(map_frame(data, **opts), "<DataFrame>")
    path = Path(data)
    kind = None if path.is_dir() else file_kind(path)
    if not path.is_dir() and kind not in ("c3d", "trc"):  # a CSV table, perhaps compressed
        table, lines = read_table(path)
        if opts["columns"]:
            table = rename_columns(table, opts["columns"], str(path))
        table = _numeric_text(table, lines, str(path))
        mapped = map_frame(table, units=units, up_axis=up_axis, contact_height=contact_height, source=str(path))
        return recordings_from_frame(mapped, str(path), lines=lines)
    frame, problems = read_any(
        path,
        marker=marker,
        contact_channel=contact_channel,
        contact_threshold=contact_threshold,
        name_pattern=name_pattern,
        **opts,
    )
    places = None
    if "file" in frame.columns:
        places = (frame["file"].astype(str) + ", sample " + frame["sample"].astype(str)).to_numpy()
    elif kind is not None:
        places = np.array([f"sample {i + 1}" for i in range(len(frame))], dtype=object)
    rec = recordings_from_frame(frame[list(COLUMNS)], str(path), places=places)
    return _with_problems(rec, problems, path)


def _with_problems(rec: Recordings, problems: list[FileProblem], root: Path) -> Recordings:
    """``rec`` with one ``invalid`` trial per unreadable file (reason: the file and its problem)."""
    if not problems:
        return rec
    rows, extra = [], {}
    for q in problems:
        rel = Path(q.path).relative_to(root) if Path(q.path).is_relative_to(root) else Path(q.path)
        key = (q.participant or "(no id)", q.trial or str(rel))
        while key in rec._rows or key in extra:  # a duplicate's second file: its own entry
            key = (key[0], f"{key[1]} ({rel})")
        extra[key] = np.array([], dtype=np.int64)
        rows.append(
            {
                "participant": key[0],
                "trial": key[1],
                "n_samples": 0,
                "first_line": 0,
                "status": "invalid",
                "reason": f"file {rel}: {q.reason}",
                "timing": "",
            }
        )
    trials = pd.concat([rec.trials, pd.DataFrame(rows)], ignore_index=True)
    return Recordings(
        frame=rec.frame,
        trials=trials,
        fs=rec.fs,
        source=rec.source,
        _rows={**rec._rows, **extra},
        _resampled=rec._resampled,
    )


__all__ = [
    "load_recordings",
    "read_any",
    "read_folder",
    "read_c3d",
    "read_trc",
    "read_csv_table",
    "read_trial_file",
    "map_frame",
    "parse_columns",
    "contact_from_height",
    "up_axis_rotation",
    "FileProblem",
    "UNIT_FACTORS",
    "UP_AXIS_ROTATIONS",
    "DataFormatError",
]
