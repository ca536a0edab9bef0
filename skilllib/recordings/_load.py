"""Recordings in other formats: C3D, TRC, CSVs with other names, units and axes, folders of trials.

Everything ends as the book's long table (:mod:`skilllib.recordings`): ``participant, trial, t, x, y, z,
contact`` with identifiers as text, t in s, positions in m with y up, contact 0/1, which
:func:`skilllib.recordings.recordings_from_frame` then validates (:func:`load_recordings` does both, and is
what ``python -m skilllib run --data`` calls). :func:`read_any` dispatches on the path:

============================  =============================================================  ============
path                          read by                                                        trials
============================  =============================================================  ============
a folder                      :func:`~skilllib.recordings.read_folder`                   one per file
``*.c3d``                     :func:`~skilllib.recordings.read_c3d` (ezc3d, checked)        one
``*.trc``                     :func:`~skilllib.recordings.read_trc`                         one
a Vicon Nexus CSV export      :func:`~skilllib.recordings.read_nexus` (first line             one
(``.csv``, ``.csv.gz``, ...)  ``Trajectories``, ...; recognised by content)
anything else (``.csv``,      :func:`read_csv_table` (pandas; compression from the name:     many (one
``.csv.gz``, ``.txt``, ...)   gzip, zip, bz2, xz, zstd; separator detected or ``sep``)       without ids)
============================  =============================================================  ============

A table with neither a ``participant`` nor a ``trial`` column is one recording named after the file
(:func:`~skilllib.recordings.file_ids`: the stem split at its last ``_``, like a single C3D file).

Then :func:`~skilllib.recordings.map_frame` renames columns, converts units, rotates the vertical
axis to +y and fills contact from the surface height, as the options ask.

Options (the command line's flags in brackets): ``marker`` (``--marker NAME``; a list ``RFTP,LFTP``: the
one that moves most; a template ``{hand}FTP`` filled from each file's name:
:mod:`skilllib.recordings._folder`), ``contact_channel``
(``--contact-channel NAME``), ``contact_threshold`` (analog threshold in the channel's units),
``contact_below`` (an analog channel is in contact below the threshold, not above),
``contact_height`` (``--contact-height M``), ``units`` (``--units m|cm|mm``), ``up_axis``
(``--up-axis y|-y|z|-z|x|-x``), ``columns`` (``--columns old=new,...``, parsed by
:func:`~skilllib.recordings.parse_columns`), ``name_pattern`` (a regular expression for file names
in a folder), ``sep`` (``--sep , | ; | tab``), ``time_unit`` (``--time-unit s|ms|us``).

**Events.** The events of C3D files (``EVENT:LABELS``, ``CONTEXTS``, ``TIMES``;
:func:`~skilllib.recordings.read_c3d`) are kept: :attr:`Recordings.events` (one row per event:
participant, trial, label, t in s on the clock of the trial's ``t``) and
:meth:`Recordings.trial_events`. Other formats carry none (``events`` is None when nothing read has any).

**Units.** When the unit of the positions is stated (a C3D, TRC or Nexus header, or ``units``), it is
believed: the "not metres" guesses of :mod:`skilllib.recordings` are skipped and only a trial spanning
more than :data:`~skilllib.recordings.MAX_KNOWN_RANGE_M` is a glitch (``units_known`` of
:func:`~skilllib.recordings.recordings_from_frame`).
"""

from __future__ import annotations

import dataclasses
import io
import re
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd

from ._c3d import read_c3d
from ._columns import COLUMNS, ID_COLUMNS, POSITION_COLUMNS
from ._csv import (
    _read_text,
    check_alignment,
    detect_sep,
    drop_trailing_separators,
    file_stem_any,
    parse_sep,
    read_table,
    with_file_ids,
)
from ._defects import MAX_GAP_S
from ._errors import DataFormatError, check_file, quote
from ._folder import (
    FileProblem,
    SkippedFile,
    check_template,
    compile_pattern,
    file_groups,
    file_kind,
    fill_marker,
    read_folder,
    read_trial_file,
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
from ._parquet import is_parquet, read_parquet, with_skipped
from ._recordings import NA_TEXT, Recordings, events_frame, read_recordings, recordings_from_frame
from ._trc import read_trc

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
    if isinstance(e, DataFormatError):
        return e
    msg = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
    return DataFormatError(f"{path}: cannot be read as a (compressed) CSV file ({msg[:200]})")


def read_csv_table(
    path: str | Path, *, columns: Mapping[str, str] | None = None, sep: str | None = None
) -> pd.DataFrame:
    """A CSV table as pandas reads it (compression inferred from the name), identifiers as text.

    The columns that are, or that ``columns`` renames to, ``participant`` and ``trial`` are read as
    ``str`` exactly as written: ``01`` and ``1``, ``NA``, ``1e20`` and a 17-digit id stay distinct text;
    an empty id is ``''`` (and a blank line NaN in every column, as the validation expects). Other
    columns keep pandas' defaults (numbers; ``NA``, ``nan``, empty are missing). Column names are not
    renamed here (:func:`map_frame` does it); blank lines are kept so that row ``r`` is file line
    ``r + 2``. The separator is ``sep`` or detected (:func:`~skilllib.recordings.detect_sep`), kept in
    ``attrs["sep"]``; a row with more or fewer fields than the header is refused
    (``check_alignment``).

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file (text).
    columns : mapping of str to str or None
        Column renames ``{old: new}`` (text), to find the id columns; None: no renaming.
    sep : str or None
        The separator (text: ``","``, ``"tab"`` or ``"\\t"``, ``";"``); None: detected.

    Returns
    -------
    pandas.DataFrame
        The table as in the file (units as in the file), ids as text.

    Raises
    ------
    DataFormatError
        Naming the file when it is missing, a folder, empty, not text, not a regular CSV table or a broken
        archive.
    """
    path = Path(path)
    check_file(path, "CSV")
    opts = dict(skipinitialspace=True, skip_blank_lines=False)
    try:
        text = _read_text(path)
        if not text.strip():
            raise pd.errors.EmptyDataError("empty")
        sep = parse_sep(sep) or detect_sep(text)
        note = check_alignment(path, text, sep)
        if note:
            text = drop_trailing_separators(text, sep)
        names = [str(c) for c in pd.read_csv(io.StringIO(text), sep=sep, nrows=0, **opts).columns]
        ids = [c for c in names if (columns or {}).get(c.strip(), c.strip()) in ID_COLUMNS]
        df = pd.read_csv(
            io.StringIO(text),
            sep=sep,
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
    df.attrs["sep"] = sep
    df.attrs["notes"] = [f"{path}: {note}"] if note else []
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
    sep: str | None = None,
    time_unit: str | None = None,
    contact_below: bool = False,
) -> tuple[pd.DataFrame, list[FileProblem]]:
    """Read recordings from a folder, a ``.c3d``, ``.trc`` or Nexus file (one trial) or a CSV table (many).

    The dispatch table and the options are in the module docstring. A single C3D/TRC/Nexus file, and a
    table without ``participant`` and ``trial`` columns, is named like a file directly in a folder:
    ``PARTICIPANT_TRIAL`` split at the last ``_`` (or ``name_pattern``); a stem without ``_`` is
    participant and trial both. The frame's ``attrs["units"]`` is the unit stated (a header's, or
    ``units``), None when nothing states it; ``attrs["events"]`` the events of the C3D files read, as
    ``(participant, trial, label, time in s)``.

    Parameters
    ----------
    path : str or pathlib.Path
        The file or folder to read (text).
    marker : str or None
        Name of the marker to read (text), a list ``"RFTP,LFTP"`` (the one that moves most), or a template
        with ``{group}`` fields filled from the file name's groups (``"{hand}FTP"``); None: the file's only
        marker.
    contact_channel : str or None
        Name of the analog channel or event that gives contact in a C3D file (text); None: ``"contact"``
        when the file has it, else contact is left NaN for the height rule.
    contact_threshold : float or None
        Analog level above which a C3D frame is in contact, in the channel's own unit (V, N, ...; taken as
        dimensionless here); None: midway between the channel's minimum and maximum in the file.
    units : str or None
        Unit of the file's positions (text: ``"m"``, ``"cm"`` or ``"mm"``), overriding a missing or wrong
        header; None: the file's own.
    up_axis : str or None
        The lab's vertical axis with its sign (text: ``y``, ``-y``, ``z``, ``-z``, ``x``, ``-x``), rotated
        to the book's +y; None: already ``y``.
    contact_height : float or None
        Height of the touched surface in the book's frame (m): contact from the first sample at or below
        it, for trials without a contact signal; None: no height rule.
    columns : mapping of str to str, str or None
        Column renames ``{old: new}`` (text), or the ``"old=new,..."`` string of ``--columns``; None: no
        renaming.
    name_pattern : str, re.Pattern or None
        Regular expression for the file names of a folder (text), with named groups ``trial`` and,
        optionally, ``participant``; None: the naming rule of :func:`read_folder`.
    sep : str or None
        The separator of a CSV table (text: ``","``, ``"tab"`` or ``"\\t"``, ``";"``); None: detected.
    time_unit : str or None
        The unit of a CSV table's ``t`` (text: ``"s"``, ``"ms"``, ``"us"``); None: s.
    contact_below : bool
        Whether a C3D analog contact channel is in contact *below* its threshold (a load cell whose channel
        goes negative under load; dimensionless); False: above it.

    Returns
    -------
    frame : pandas.DataFrame
        The long table in the book's frame with identifiers as text, ``t`` (s), ``x, y, z`` (m), ``contact``
        (0/1), for :func:`skilllib.recordings.recordings_from_frame`.
    problems : list of FileProblem
        The files of a folder that could not be read (always empty for a single file, whose problems
        raise).

    Raises
    ------
    DataFormatError
        One line naming the file, when the path cannot be read as recordings: see :func:`read_folder`,
        :func:`read_c3d`, :func:`read_trc`, :func:`read_csv_table` and :func:`map_frame`.
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
            sep=sep,
            time_unit=time_unit,
            contact_below=contact_below,
        )
    kind = file_kind(path)
    if kind in ("c3d", "trc", "nexus"):
        check_file(path, {"nexus": "Nexus CSV"}.get(kind, kind.upper()))  # before the name is read
        groups = _single_file_groups(path, name_pattern)
        check_template(marker, compile_pattern(name_pattern))
        try:
            this_marker = fill_marker(marker, groups)
        except ValueError as e:
            raise DataFormatError(f"{path}: {e}") from None
        participant, trial = groups["participant"], groups["trial"]
        df = read_trial_file(
            path,
            marker=this_marker,
            contact_channel=contact_channel,
            contact_threshold=contact_threshold,
            contact_below=contact_below,
            units=units,
            up_axis=up_axis,
            contact_height=contact_height,
        )
        df.insert(0, "trial", trial)
        df.insert(0, "participant", participant)
        df[list(ID_COLUMNS)] = df[list(ID_COLUMNS)].astype(object)
        df.attrs["notes"] = [f"{path}: {note}" for note in df.attrs.get("notes", [])]
        df.attrs["events"] = [(participant, trial, label, t) for label, t in df.attrs.get("events", [])]
        return df, []
    table = read_csv_table(path, columns=cols, sep=sep)
    if cols:
        table = rename_columns(table, cols, str(path))
    table = _one_recording(table, path, name_pattern)
    out = map_frame(
        table,
        units=units,
        up_axis=up_axis,
        contact_height=contact_height,
        source=str(path),
        first_line=2,
        time_unit=time_unit,
    )
    out.attrs["units"] = units
    return out, []


def single_file_ids(path: str | Path, name_pattern: str | re.Pattern | None = None) -> tuple[str, str]:
    """(participant, trial) of a file read on its own as one recording (a C3D, TRC or Nexus file, a table
    without id columns): the stem split at its last ``_``, or ``name_pattern``; a stem without ``_`` is
    participant and trial both.

    Parameters
    ----------
    path : str or pathlib.Path
        The file (text).
    name_pattern : str, re.Pattern or None
        Regular expression with named groups ``trial`` and, optionally, ``participant`` (text); None: the
        rule above.

    Returns
    -------
    participant, trial : str
        The ids (text).

    Raises
    ------
    DataFormatError
        When the name does not match ``name_pattern``.
    """
    groups = _single_file_groups(path, name_pattern)
    return groups["participant"], groups["trial"]


def _single_file_groups(path: str | Path, name_pattern: str | re.Pattern | None) -> dict[str, str | None]:
    """The groups of a single file's name (:func:`single_file_ids`): participant, trial and the pattern's."""
    path = Path(path)
    stem = file_stem_any(path)
    try:
        return file_groups(stem, None, compile_pattern(name_pattern))
    except ValueError:
        if name_pattern is not None:
            raise DataFormatError(f"{path}: name {stem!r} does not match the name pattern") from None
        return {"participant": stem, "trial": stem}


def _one_recording(table: pd.DataFrame, path: Path, name_pattern: str | re.Pattern | None) -> pd.DataFrame:
    """``table`` with ids from the file's name when it has neither a participant nor a trial column."""
    out = with_file_ids(table, path)
    if out is not table:
        participant, trial = single_file_ids(path, name_pattern)
        have = out["participant"].notna().to_numpy()
        out.loc[have, "participant"] = participant
        out.loc[have, "trial"] = trial
    return out


def _mapped_parquet(
    path: Path,
    opts: dict,
    known: bool,
    repair: dict,
    *refused: object,
) -> Recordings:
    """A Parquet file or dataset read with the mapping options (``columns``, ``units``, ``up_axis``,
    ``contact_height``, ``time_unit``); the options of other formats (marker, contact channel and threshold,
    name pattern, separator) are refused naming the first given."""
    from ._recordings import natural_key

    flags = ("--marker", "--contact-channel", "--contact-threshold", "--name-pattern", "--sep", "--contact-below")
    given = [flag for flag, v in zip(flags, refused) if v is not None and v is not False]
    if given:
        raise DataFormatError(
            f"{path}: {given[0]} does not apply to Parquet input, which is read in the book's format "
            f"(--columns, --units, --up-axis, --contact-height and --time-unit apply; docs/inputs.md, Parquet)"
        )
    optional = ("contact",) if opts["contact_height"] is not None else ()
    frame, where = read_parquet(path, COLUMNS, natural_key, renames=opts["columns"], optional=optional)
    skipped = frame.attrs.get("skipped", ())
    mapped = map_frame(frame, **{k: v for k, v in opts.items() if k != "columns"}, source=str(path))
    del frame
    rec = recordings_from_frame(mapped, str(path), place=where, units_known=known, **repair)
    return with_skipped(rec, skipped)


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
    sep: str | None = None,
    time_unit: str | None = None,
    max_gap_s: float = MAX_GAP_S,
    fill: str = "cubic",
    contact_below: bool = False,
) -> Recordings:
    """Validated :class:`~skilllib.recordings.Recordings` from a path, a DataFrame or Recordings.

    A path is a folder, C3D, TRC, Nexus or CSV file (see :func:`read_any`), mapped by the options (module
    docstring). A stated unit (a header's, or ``units``) is believed (module docstring: Units). A CSV is
    read as text with its physical line numbers
    (:func:`skilllib.recordings.read_table`), so that messages name file lines; its columns are renamed
    before anything else, so ``--columns`` may name the file's own columns. Files of a folder that cannot
    be read are kept as ``invalid`` trials with their reason (file name and problem), never dropped;
    messages about a sample of a folder's file name the file and the sample. The events of C3D files are
    kept (:attr:`Recordings.events`, :meth:`Recordings.trial_events`; module docstring: Events).

    Parameters
    ----------
    data : str, pathlib.Path, pandas.DataFrame or Recordings
        The recordings: a path (text) or a long table (``t`` in s, positions in ``units``).
    columns : mapping of str to str, str or None
        Column renames ``{old: new}`` (text), or the ``"old=new,..."`` string of ``--columns``; None: no
        renaming.
    units : str or None
        Unit of the file's positions (text: ``"m"``, ``"cm"`` or ``"mm"``), overriding a missing or wrong
        header; None: the file's own.
    up_axis : str or None
        The lab's vertical axis with its sign (text: ``y``, ``-y``, ``z``, ``-z``, ``x``, ``-x``), rotated
        to the book's +y; None: already ``y``.
    marker : str or None
        Name of the marker to read (text), a list ``"RFTP,LFTP"`` (the one that moves most), or a template
        with ``{group}`` fields filled from each file's name (``"{hand}FTP"``); None: the file's only marker.
    contact_channel : str or None
        Name of the analog channel or event that gives contact in a C3D file (text); None: ``"contact"``
        when the file has it, else contact is left NaN for the height rule.
    contact_threshold : float or None
        Analog level above which a C3D frame is in contact, in the channel's own unit (V, N, ...; taken as
        dimensionless here); None: midway between the channel's minimum and maximum in the file.
    contact_height : float or None
        Height of the touched surface in the book's frame (m): contact from the first sample at or below
        it, for trials without a contact signal; None: no height rule.
    name_pattern : str, re.Pattern or None
        Regular expression for the file names of a folder (text), with named groups ``trial`` and,
        optionally, ``participant``; None: the naming rule of :func:`read_folder`.
    sep : str or None
        The separator of a CSV table (text: ``","``, ``"tab"`` or ``"\\t"``, ``";"``); None: detected.
    time_unit : str or None
        The unit of a table's ``t`` (text: ``"s"``, ``"ms"``, ``"us"``), divided into seconds; None: s.
    max_gap_s : float
        The longest gap of missing, frozen or jumping positions filled by interpolation (s; default
        0.1); longer ones before contact make a trial invalid, after contact cut it
        (:func:`skilllib.recordings.repair_trial`).
    fill : str
        How short gaps are filled: ``"cubic"`` or ``"linear"`` (text).
    contact_below : bool
        Whether a C3D analog contact channel is in contact *below* its threshold (a load cell whose channel
        goes negative under load; dimensionless); False: above it.

    Returns
    -------
    Recordings
        The validated recordings (t in s, positions in m with y up, fs in Hz).

    Raises
    ------
    DataFormatError
        For what cannot be read at all.
    """
    repair = dict(max_gap_s=max_gap_s, fill=fill)  # real-data defects (skilllib.recordings.repair_trial)
    given = (columns, units, up_axis, marker, contact_channel, contact_threshold, contact_height, name_pattern)
    given += (time_unit, contact_below or None)
    parse_sep(sep)  # a wrong --sep fails before anything is read
    if all(v is None for v in given):  # nothing to map: the book's format as it is
        if isinstance(data, Recordings):
            return data
        if isinstance(data, pd.DataFrame):
            return recordings_from_frame(data, **repair)
        path = Path(data)
        parquet = is_parquet(path)  # with --sep: refused below (a CSV option)
        csv_file = not parquet and not path.is_dir() and file_kind(path) not in ("c3d", "trc", "nexus")
        if parquet and sep is None or csv_file:
            return read_recordings(path, sep=sep, **repair)  # pyarrow's CSV reader; Parquet files, folders
    opts = dict(
        columns=parse_columns(columns) if isinstance(columns, str) else columns,
        units=units,
        up_axis=up_axis,
        contact_height=contact_height,
        time_unit=time_unit,
    )
    known = units is not None
    events = None
    if isinstance(data, Recordings):
        data, events = data.frame, data.events
    if isinstance(data, pd.DataFrame):
        rec = recordings_from_frame(map_frame(data, **opts), "<DataFrame>", units_known=known, **repair)
        return dataclasses.replace(rec, events=events) if events is not None else rec
    path = Path(data)
    if is_parquet(path):  # the book's columns: --columns, --units, --up-axis, --contact-height, --time-unit apply
        return _mapped_parquet(
            path, opts, known, repair, marker, contact_channel, contact_threshold, name_pattern, sep, contact_below
        )
    kind = None if path.is_dir() else file_kind(path)
    if not path.is_dir() and kind not in ("c3d", "trc", "nexus"):  # a CSV table, perhaps compressed
        table, lines = read_table(path, sep)
        if opts["columns"]:
            table = rename_columns(table, opts["columns"], str(path))
        table = _one_recording(table, path, name_pattern)
        table = _numeric_text(table, lines, str(path))
        mapped = map_frame(
            table,
            units=units,
            up_axis=up_axis,
            contact_height=contact_height,
            source=str(path),
            time_unit=time_unit,
        )
        rec = recordings_from_frame(mapped, str(path), lines=lines, units_known=known, **repair)
        notes = tuple(table.attrs.get("notes", ()))
        return dataclasses.replace(rec, notes=notes) if notes else rec
    frame, problems = read_any(
        path,
        marker=marker,
        contact_channel=contact_channel,
        contact_threshold=contact_threshold,
        name_pattern=name_pattern,
        sep=sep,
        contact_below=contact_below,
        **opts,
    )
    known = known or frame.attrs.get("units") is not None
    places = None
    if "file" in frame.columns:
        places = (frame["file"].astype(str) + ", sample " + frame["sample"].astype(str)).to_numpy()
    elif kind is not None:
        places = np.array([f"sample {i + 1}" for i in range(len(frame))], dtype=object)
    rec = recordings_from_frame(frame[list(COLUMNS)], str(path), places=places, units_known=known, **repair)
    extra = {"notes": tuple(frame.attrs.get("notes", ())), "events": events_frame(frame.attrs.get("events", ()))}
    if "skipped" in frame.attrs:  # a folder: what it holds besides its trials
        extra["skipped"] = tuple(frame.attrs["skipped"])
    return _with_problems(dataclasses.replace(rec, **extra), problems, path)


def _with_problems(rec: Recordings, problems: list[FileProblem], root: Path) -> Recordings:
    """``rec`` with one ``invalid`` trial per unreadable file (reason: the file and its problem); its
    ``notes`` and ``skipped`` kept."""
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
                "repairs": "",
                "n_repaired": 0,
                "n_dropped": 0,
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
        _repaired=rec._repaired,
        notes=rec.notes,
        skipped=rec.skipped,
        events=rec.events,
    )


__all__ = [
    "load_recordings",
    "read_any",
    "single_file_ids",
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
    "SkippedFile",
    "UNIT_FACTORS",
    "UP_AXIS_ROTATIONS",
    "DataFormatError",
]
