r"""A folder of one-trial files (C3D, TRC, Vicon Nexus CSV, per-trial CSV) as one long table, with the files it
could not read.

A ``.csv`` (also compressed) whose first line is a Nexus section name (``Trajectories``, ...) is a Nexus
export, read like a C3D file (:func:`skilllib.recordings.read_nexus`); any other is a per-trial table
(columns ``t, x, y, z`` and perhaps ``contact``; separator detected or ``sep``).

**Naming rule** (identifiers are text, exactly as in the file names: ``01`` and ``1`` are two ids):

* ``DIR/<participant>/<trial>.<ext>``: the sub-folder's name is the participant, the file's stem (name
  without ``.c3d``, ``.trc``, ``.csv``, ``.csv.gz``, ...) the trial;
* ``DIR/<participant>_<trial>.<ext>``: a file directly in ``DIR`` is split at the **last** ``_`` of its
  stem (``P_01_3.c3d``: participant ``P_01``, trial ``3``);
* ``name_pattern``: a regular expression with named groups ``trial`` and, optionally, ``participant``,
  matched against the whole stem of every file (``re.fullmatch``); its ``participant`` group, when it
  has one, replaces the sub-folder's name; a file directly in ``DIR`` needs it. Other named groups are
  allowed (for the marker template below); groups may nest, so that the trial keeps what tells two files
  apart: ``ADL(?P<participant>\d+)F(?P<trial>(?P<hand>[LR])\d)`` names ``ADL005FR3`` participant
  ``005``, trial ``R3``, hand ``R``.

**Marker template.** ``marker`` may hold ``{group}`` fields (Python's ``str.format`` syntax; ``{{`` for a
brace), filled for each file from its name: the groups of ``name_pattern``, and ``participant`` and
``trial`` as the naming rule gives them. With the pattern above, ``marker="{hand}FTP"`` reads ``RFTP``
in the ``R`` files and ``LFTP`` in the ``L`` files. A field the name does not give is an error naming
the field and the groups there are (before any file is read); a group that takes no part in one file's
match makes that file a problem (:class:`FileProblem`). A single file is named the same way
(:func:`skilllib.recordings.single_file_ids`).

Only ``DIR`` and its direct sub-folders are read (a sub-folder that is a link is followed). Trials come in
a fixed order: participants, then trials, in natural order (``P2`` before ``P10``; ids equal as numbers,
like ``01`` and ``1``, by their text).

**Every file is accounted for**: it is a trial, an unreadable file or a skipped one, never dropped
without a word. Files that cannot be read never stop the others: :func:`read_folder` returns them as
:class:`FileProblem` (file, participant, trial, reason) for the caller to list as invalid trials (a file
that cannot be opened, a damaged or empty one, a second file for the same ids). What is not read at all
is a :class:`SkippedFile` (path, reason) in the frame's ``attrs["skipped"]``: hidden files and folders
(``.name``, such as macOS's ``._name.c3d``), a sub-folder that cannot be listed, a broken link, a file
in a sub-sub-folder, a file of another format, a name that gives no ids (not matching ``name_pattern``,
or without ``_`` directly in ``DIR``), something that is not a regular file. :func:`read_folder` raises
only when the options are wrong, the folder cannot be listed, or no file at all can be read.
"""

from __future__ import annotations

import io
import os
import re
import string
from collections.abc import Mapping
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pandas as pd

from ._c3d import read_c3d
from ._columns import ID_COLUMNS
from ._csv import _read_text, check_alignment, columns_found, detect_sep, drop_trailing_separators, parse_sep
from ._errors import DataFormatError
from ._mapping import map_frame, rename_columns, time_unit_factor, unit_factor, up_axis_rotation
from ._nexus import is_nexus, read_nexus
from ._recordings import natural_key
from ._trc import read_trc

C3D_SUFFIXES = (".c3d",)
TRC_SUFFIXES = (".trc",)
CSV_SUFFIXES = (".csv", ".csv.gz", ".csv.zip", ".csv.bz2", ".csv.xz", ".csv.zst")  #: pandas infers compression
TRIAL_COLUMNS = ("t", "x", "y", "z", "contact")  #: columns of one trial's table (no ids)


class FileProblem(NamedTuple):
    """A file that could not be read: ``reason`` is one line; ``participant``/``trial`` as text or None.

    Parameters
    ----------
    path : str
        The file, relative to the folder (text).
    participant : str or None
        The participant its name gives (text), or None when the name gives none.
    trial : str or None
        The trial its name gives (text), or None when the name gives none.
    reason : str
        What is wrong with it, one line (text).
    """

    path: str
    participant: str | None
    trial: str | None
    reason: str


class SkippedFile(NamedTuple):
    """An entry of a folder that is not read at all, and why: ``reason`` is one line.

    Parameters
    ----------
    path : str
        The file, relative to the folder read, ``/`` between its parts; a folder skipped whole ends with
        ``/`` (text).
    reason : str
        Why it is not read, one line (text): ``"hidden file"``, ``"hidden folder"``, ``"cannot list the
        folder: Permission denied"``, ``"broken link to ..."``, ``"in a sub-sub-folder: ..."``, ``"not a
        C3D, TRC, Nexus or CSV file"``, a name that gives no ids, ...
    """

    path: str
    reason: str


#: The reason of a file of a folder whose format no reader takes.
OTHER_FORMAT = "not a C3D, TRC, Nexus or CSV file"


def file_kind(path: Path) -> str | None:
    """``'c3d'``, ``'trc'``, ``'nexus'``, ``'csv'`` (also compressed) or None: from the file name (case
    ignored), and for a ``.csv`` (or ``.txt``) from its first line (a Nexus section name: ``'nexus'``)."""
    name = path.name.lower()
    for kind, suffixes in (("c3d", C3D_SUFFIXES), ("trc", TRC_SUFFIXES), ("csv", CSV_SUFFIXES)):
        if name.endswith(suffixes):
            return "nexus" if kind == "csv" and is_nexus(path) else kind
    return "nexus" if is_nexus(path) else None


def file_stem(path: Path) -> str:
    """The name without the format's suffix(es): ``P01_3.csv.gz`` -> ``P01_3``."""
    name = path.name
    for suffix in sorted(C3D_SUFFIXES + TRC_SUFFIXES + CSV_SUFFIXES, key=len, reverse=True):
        if name.lower().endswith(suffix):
            return name[: -len(suffix)]
    return path.stem


def compile_pattern(name_pattern: str | re.Pattern | None) -> re.Pattern | None:
    """``name_pattern`` compiled; DataFormatError when it is not a regular expression or has no ``trial`` group."""
    if name_pattern is None:
        return None
    try:
        pat = re.compile(name_pattern)
    except re.error as e:
        raise DataFormatError(f"name pattern {str(name_pattern)!r} is not a regular expression: {e}") from None
    if "trial" not in pat.groupindex:
        raise DataFormatError(f"name pattern {pat.pattern!r} has no (?P<trial>...) group")
    return pat


def template_fields(marker: str | None) -> list[str]:
    """The ``{field}`` names of a marker template, in order (empty for a plain marker name).

    Parameters
    ----------
    marker : str or None
        The marker option (text), perhaps holding ``{group}`` fields; None: no marker.

    Returns
    -------
    list of str
        The fields it names (text).

    Raises
    ------
    DataFormatError
        When the template cannot be read (an unmatched brace, an empty or numbered field, a format spec).
    """
    if not marker or "{" not in marker and "}" not in marker:
        return []
    try:
        parsed = list(string.Formatter().parse(marker))
    except ValueError as e:
        raise DataFormatError(f"marker template {marker!r} cannot be read: {e} (write {{{{ for a brace)") from None
    fields = []
    for _, name, spec, conv in parsed:
        if name is None:
            continue
        if not name.isidentifier() or spec or conv:
            raise DataFormatError(
                f"marker template {marker!r}: {{{name}{'!' + conv if conv else ''}{':' + spec if spec else ''}}} "
                f"is not a group name (write {{group}} with a group of the name pattern)"
            )
        fields.append(name)
    return fields


def name_groups(pattern: re.Pattern | None) -> list[str]:
    """The groups a file's name gives for a marker template: ``participant``, ``trial`` and the named
    groups of ``pattern``."""
    return list(dict.fromkeys(["participant", "trial", *((pattern.groupindex) if pattern is not None else ())]))


def check_template(marker: str | None, pattern: re.Pattern | None) -> None:
    """DataFormatError when the marker template names a field the file names do not give (module docstring).

    Parameters
    ----------
    marker : str or None
        The marker option (text), perhaps a template with ``{group}`` fields.
    pattern : re.Pattern or None
        The compiled name pattern (text), or None for the naming rule.
    """
    have = name_groups(pattern)
    for name in template_fields(marker):
        if name not in have:
            source = f"the name pattern {pattern.pattern!r}" if pattern is not None else "the file naming rule"
            raise DataFormatError(
                f"marker template {marker!r} names the field {name!r}, which {source} does not give "
                f"(groups: {', '.join(have)}); add a (?P<{name}>...) group to the name pattern"
            )


def fill_marker(marker: str | None, groups: Mapping[str, str | None]) -> str | None:
    """The marker name for one file: the template's fields filled from the file name's groups.

    Parameters
    ----------
    marker : str or None
        The marker option (text), perhaps a template with ``{group}`` fields (checked by :func:`check_template`).
    groups : mapping of str to str or None
        The groups of the file's name (text; None for a group that took no part in the match).

    Returns
    -------
    str or None
        The marker name (text); ``marker`` itself when it has no field.

    Raises
    ------
    ValueError
        When a field's group took no part in this file's match (the file's problem).
    """
    fields = template_fields(marker)
    if not fields:
        return marker
    missing = [f for f in fields if groups.get(f) is None]
    if missing:
        raise ValueError(f"the name gives no {missing[0]!r} for the marker template {marker!r}")
    return marker.format_map({f: groups[f] for f in fields})


def file_groups(stem: str, folder: str | None, pattern: re.Pattern | None) -> dict[str, str | None]:
    """The groups of a file's name (:func:`name_groups`): ``participant`` and ``trial`` (:func:`trial_ids`)
    and the named groups of ``pattern``; ValueError as :func:`trial_ids`."""
    participant, trial = trial_ids(stem, folder, pattern)
    groups = dict(pattern.fullmatch(stem).groupdict()) if pattern is not None else {}
    groups.update(participant=participant, trial=trial)
    return groups


def trial_ids(stem: str, folder: str | None, pattern: re.Pattern | None) -> tuple[str, str]:
    """(participant, trial) as text for a file ``stem`` in sub-folder ``folder`` (None: directly in the
    folder read), by the naming rule of the module docstring; ValueError with the reason when the name
    does not give them."""
    if pattern is not None:
        m = pattern.fullmatch(stem)
        if m is None:
            raise ValueError(f"name {stem!r} does not match the name pattern {pattern.pattern!r}")
        participant = m.groupdict().get("participant") or folder
        if not participant:
            raise ValueError(
                f"name pattern {pattern.pattern!r} gives no participant for {stem!r} and the file "
                f"is not in a participant's sub-folder"
            )
        if not m.group("trial"):
            raise ValueError(f"name pattern {pattern.pattern!r} gives an empty trial for {stem!r}")
        return participant, m.group("trial")
    if folder is not None:
        return folder, stem
    participant, sep, trial = stem.rpartition("_")
    if not sep or not participant or not trial:
        raise ValueError(
            f"cannot tell participant and trial from the name {stem!r}: name it PARTICIPANT_TRIAL, "
            f"put it in a sub-folder named after the participant, or give a name pattern"
        )
    return participant, trial


def read_trial_csv(path: Path, *, columns: Mapping[str, str] | None = None, sep: str | None = None) -> pd.DataFrame:
    """One trial's CSV (compression inferred from the name): columns ``t`` (s), ``x, y, z`` and, when
    present, ``contact``, after renaming by ``columns`` (units and axes: :func:`map_frame`). The separator
    is ``sep`` or detected (:func:`skilllib.recordings.detect_sep`); a row with more or fewer fields than
    the header is refused (:func:`check_alignment`). A table with participant or trial
    columns holds several trials and is refused."""
    text = _read_text(path)
    if not text.strip():
        raise DataFormatError(f"{path}: file is empty")
    sep = parse_sep(sep) or detect_sep(text)
    if note := check_alignment(path, text, sep):
        text = drop_trailing_separators(text, sep)
    try:
        df = pd.read_csv(io.StringIO(text), sep=sep, skipinitialspace=True)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, ValueError) as e:
        msg = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        raise DataFormatError(f"{path}: not a readable CSV table ({msg[:200]})") from None
    df = df.rename(columns=lambda c: str(c).strip())
    df.attrs["sep"] = sep
    df.attrs["notes"] = [note] if note else []
    ids = [c for c in df.columns if (columns or {}).get(c, c) in ID_COLUMNS]
    if ids:
        raise DataFormatError(
            f"{path}: has participant/trial columns ({', '.join(ids)}); a folder holds one "
            f"trial per file (read a table of many trials as a CSV file, not as a folder)"
        )
    if columns:
        df = rename_columns(df, columns, str(path))
    missing = [c for c in TRIAL_COLUMNS[:4] if c not in df.columns]
    if missing:
        raise DataFormatError(
            f"{path}: required column {missing[0]!r} missing ({columns_found(df.columns, sep)}); "
            f"rename with --columns old=new"
        )
    return df[[c for c in TRIAL_COLUMNS if c in df.columns]]


def _largest_span(frames: list[pd.DataFrame]) -> pd.DataFrame:
    """Of one file's markers read as trials, the one whose positions span most (the moving one)."""

    def span(df: pd.DataFrame) -> float:
        p = df[["x", "y", "z"]].to_numpy(dtype=float)
        p = p[np.isfinite(p).all(axis=1)]
        return float(np.ptp(p, axis=0).max()) if len(p) else -1.0

    return max(frames, key=span)


def _read_markers(path: Path, kind: str, marker: str | None, **opts: object) -> pd.DataFrame:
    """A C3D or TRC file's marker; a list ``"A,B"``: the one of them (in the file) that moves most."""
    read = read_c3d if kind == "c3d" else read_trc
    names = [m for m in (marker or "").split(",") if m.strip()]
    if len(names) < 2:
        return read(path, marker=marker, **opts)
    frames, errors = [], []
    for name in names:
        try:
            frames.append(read(path, marker=name.strip(), **opts))
        except DataFormatError as e:
            errors.append(e)
    if not frames:
        raise errors[0]
    return _largest_span(frames)


def read_trial_file(
    path: str | Path,
    *,
    marker: str | None = None,
    contact_channel: str | None = None,
    contact_threshold: float | None = None,
    units: str | None = None,
    up_axis: str | None = None,
    contact_height: float | None = None,
    columns: Mapping[str, str] | None = None,
    sep: str | None = None,
    time_unit: str | None = None,
    contact_below: bool = False,
) -> pd.DataFrame:
    """One C3D, TRC, Nexus or per-trial CSV file as one trial in the book's frame (columns ``t, x, y, z,
    contact``; s, m, y up, 0/1 or NaN where the file's own contact flag is empty).

    C3D, TRC and Nexus files carry their unit in the header (``units`` replaces it); a CSV is in
    ``units`` (None: m), its ``t`` in ``time_unit`` (None: s), split at ``sep`` (None: detected) and
    renamed by ``columns``. ``marker`` may list several names (``"RFTP,LFTP"``): the one of them that
    moves most in the file (a template's fields must be filled before: :func:`fill_marker`). ``up_axis``
    and ``contact_height`` as in :func:`map_frame`; ``contact_below``: a C3D analog channel is in contact
    below its threshold (:func:`~skilllib.recordings.read_c3d`). The frame's ``attrs["units"]`` is the unit
    the file (or ``units``) states, None when nothing states it; ``attrs["events"]`` the file's events
    (``(label, time in s)``; a C3D file's, else empty). Raises :class:`~skilllib.recordings.DataFormatError`
    naming the file.
    """
    path = Path(path)
    kind = file_kind(path)
    if kind == "c3d":
        df = _read_markers(
            path,
            kind,
            marker,
            contact_channel=contact_channel,
            contact_threshold=contact_threshold,
            contact_below=contact_below,
            units=units,
        )
    elif kind == "trc":
        df = _read_markers(path, kind, marker, units=units)
    elif kind == "nexus":
        df = read_nexus(path, marker=marker, units=units)
    elif kind == "csv":
        df = read_trial_csv(path, columns=columns, sep=sep)
    else:
        raise DataFormatError(f"{path}: not a .c3d, .trc or .csv file")
    # a reader that does not set attrs["units"] refuses a file without a unit: its header states one
    stated = units if units is not None else None if kind == "csv" else df.attrs.get("units", "header")
    out = map_frame(
        df,
        units=units if kind == "csv" else None,
        up_axis=up_axis,
        contact_height=contact_height,
        source=str(path),
        time_unit=time_unit if kind == "csv" else None,
    )
    out.attrs["units"] = stated
    out.attrs["notes"] = list(df.attrs.get("notes", []))  # what the reader noticed but did not refuse
    out.attrs["events"] = list(df.attrs.get("events", []))  # (label, t in s): a C3D file's
    return out


def _reason(e: Exception, path: Path) -> str:
    """The error's message without the leading file name (the problem names the file)."""
    msg = str(e)
    head = str(path)
    return msg[len(head) :].lstrip(":, ") if msg.startswith(head) else msg


def _listing(folder: Path) -> list[os.DirEntry]:
    """The entries of ``folder`` sorted by name; OSError when it cannot be listed."""
    with os.scandir(folder) as it:
        return sorted(it, key=lambda e: e.name)


def _is_dir(entry: os.DirEntry) -> bool:
    """Whether the entry is a folder (a link to one too); False when that cannot be told."""
    try:
        return entry.is_dir()
    except OSError:
        return False


def _scan(root: Path) -> tuple[list[tuple[Path, str | None]], list[SkippedFile]]:
    """Every entry under ``root``, accounted for: the files to read as (path, sub-folder name or None), in
    order of their paths, and the entries skipped with their reason (:class:`SkippedFile`). ``root``'s
    direct sub-folders are participants (a link to a folder is followed there, not deeper); a file
    deeper down is skipped, each one named. OSError when ``root`` itself cannot be listed."""
    found: list[tuple[Path, str | None]] = []
    skipped: list[SkippedFile] = []

    def visit(folder: Path, parts: tuple[str, ...], entries: list[os.DirEntry]) -> None:
        for e in entries:
            rel = "/".join((*parts, e.name))
            is_dir = _is_dir(e)
            if e.name.startswith("."):
                skipped.append(SkippedFile(rel + "/", "hidden folder") if is_dir else SkippedFile(rel, "hidden file"))
            elif e.is_symlink() and not os.path.exists(e.path):
                try:
                    target = os.readlink(e.path)
                except OSError:
                    target = "a missing file"
                skipped.append(SkippedFile(rel, f"broken link to {target}"))
            elif is_dir and parts and e.is_symlink():  # below a participant's folder: a link could loop
                skipped.append(
                    SkippedFile(
                        rel + "/", f"link to a folder inside a sub-folder: only {root}/<participant>/<file> is read"
                    )
                )
            elif is_dir:
                try:
                    inner = _listing(Path(e.path))
                except OSError as err:
                    skipped.append(SkippedFile(rel + "/", f"cannot list the folder: {err.strerror or err}"))
                    continue
                visit(Path(e.path), (*parts, e.name), inner)
            elif not e.is_file():
                skipped.append(SkippedFile(rel, "not a regular file (a device, pipe or socket)"))
            elif len(parts) > 1:
                skipped.append(SkippedFile(rel, f"in a sub-sub-folder: only {root}/<participant>/<file> is read"))
            elif file_kind(Path(e.path)) is None:
                skipped.append(SkippedFile(rel, OTHER_FORMAT))
            else:
                found.append((Path(e.path), parts[0] if parts else None))

    visit(root, (), _listing(root))
    return found, skipped


def _check_readable(path: Path) -> None:
    """OSError (Permission denied, ...) when the file cannot be opened for reading."""
    with path.open("rb"):
        pass


def read_folder(
    path: str | Path,
    *,
    marker: str | None = None,
    contact_channel: str | None = None,
    contact_threshold: float | None = None,
    units: str | None = None,
    up_axis: str | None = None,
    contact_height: float | None = None,
    columns: Mapping[str, str] | None = None,
    name_pattern: str | re.Pattern | None = None,
    sep: str | None = None,
    time_unit: str | None = None,
    contact_below: bool = False,
) -> tuple[pd.DataFrame, list[FileProblem]]:
    """Every ``.c3d``, ``.trc`` and ``.csv`` (also compressed; Vicon Nexus exports among them) file of
    ``path`` as one trial each, and every other entry accounted for.

    Returns ``(frame, problems)``: ``frame`` is the long table ``participant, trial, t, x, y, z,
    contact`` and ``file``, ``sample`` (the file, relative to ``path``, and the 1-based sample in it) (ids as
    ``str``; s; m in the book's frame; 0/1, or NaN where a file's own flag is empty),
    trials in the natural order of the module docstring, each file's rows contiguous; ``problems`` lists
    the files that could not be read (:class:`FileProblem`: cannot be opened, damaged, no samples, a
    second file for the same ids), in the same order, for the caller to mark those trials invalid. The
    entries not read at all (hidden, unlistable sub-folders, broken links, too deep, another format, a
    name that gives no ids) are the frame's ``attrs["skipped"]``, a list of :class:`SkippedFile` in order
    of their paths (module docstring): every entry of the folder is a trial, a problem or skipped. The
    options are those of
    :func:`read_trial_file`; the naming rule (sub-folder or ``PARTICIPANT_TRIAL`` name, or
    ``name_pattern``) is in the module docstring. Two files giving one (participant, trial) are a
    problem for the second. The frame's ``attrs["units"]`` is the unit stated for every file read (the
    headers' or ``units``; ``"mixed"`` when they differ), None when some file states none. Its
    ``attrs["events"]`` lists the events of the files read, ``(participant, trial, label, time in s)``.

    Parameters
    ----------
    path : str or pathlib.Path
        The folder (text).
    marker : str or None
        Name of the marker to read (text), a list ``"RFTP,LFTP"`` (the one that moves most), or a template
        with ``{group}`` fields filled from each file's name (``"{hand}FTP"``; module docstring); None: the
        file's only marker.
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
    columns : mapping of str to str or None
        Column renames ``{old: new}`` for the CSV files (text); None: no renaming.
    name_pattern : str, re.Pattern or None
        Regular expression for the file names of a folder (text), with named groups ``trial`` and,
        optionally, ``participant``; None: the naming rule of :func:`read_folder`.
    sep : str or None
        The separator of the per-trial CSV files (text: ``","``, ``"tab"``, ``";"``); None: detected.
    time_unit : str or None
        The unit of the per-trial CSV files' ``t`` (text: ``"s"``, ``"ms"``, ``"us"``); None: s.
    contact_below : bool
        Whether a C3D analog contact channel is in contact *below* its threshold (dimensionless); False:
        above it.

    Returns
    -------
    frame : pandas.DataFrame
        The long table: ids (text), ``t`` (s), ``x, y, z`` (m, the book's frame), ``contact`` (0/1 or NaN),
        ``file`` (text) and ``sample`` (1-based, samples).
    problems : list of FileProblem
        The files that could not be read.

    Raises
    ------
    DataFormatError
        When ``path`` is not a folder or cannot be listed, an option is wrong (unit, axis, pattern), the
        folder has no such file, or none of its files can be read.
    """
    root = Path(path)
    if not root.is_dir():
        raise DataFormatError(f"{root}: not a folder" if root.exists() else f"{root}: folder not found")
    pattern = compile_pattern(name_pattern)
    check_template(marker, pattern)
    if units is not None:
        unit_factor(units, str(root))
    if up_axis is not None:
        up_axis_rotation(up_axis)
    if time_unit is not None:
        time_unit_factor(time_unit, str(root))
    parse_sep(sep)
    try:
        found, skipped = _scan(root)
    except OSError as e:
        raise DataFormatError(f"{root}: cannot list the folder: {e.strerror or e}") from None
    if not found:
        first = f" ({len(skipped)} skipped; first: {skipped[0].path}: {skipped[0].reason})" if skipped else ""
        raise DataFormatError(f"{root}: no .c3d, .trc or .csv files in the folder or its sub-folders{first}")
    opts = dict(
        contact_channel=contact_channel,
        contact_threshold=contact_threshold,
        contact_below=contact_below,
        units=units,
        up_axis=up_axis,
        contact_height=contact_height,
        columns=columns,
        sep=sep,
        time_unit=time_unit,
    )
    named, problems, unnamed = [], [], []
    for p, folder in found:
        try:
            groups = file_groups(file_stem(p), folder, pattern)
        except ValueError as e:  # no ids: not a trial
            unnamed.append(SkippedFile(p.relative_to(root).as_posix(), str(e)))
            continue
        named.append((groups["participant"], groups["trial"], p, groups))
    named.sort(key=lambda r: (natural_key(r[0]), natural_key(r[1]), str(r[2])))
    frames, seen, stated, notes, events = [], {}, set(), [], []
    for participant, trial, p, groups in named:
        if (participant, trial) in seen:
            problems.append(
                FileProblem(
                    str(p),
                    participant,
                    trial,
                    f"participant {participant!r} trial {trial!r} is also {seen[participant, trial]}",
                )
            )
            continue
        seen[participant, trial] = p
        try:
            this_marker = fill_marker(marker, groups)
        except ValueError as e:  # a group of the template took no part in this name's match
            problems.append(FileProblem(str(p), participant, trial, str(e)))
            continue
        try:
            _check_readable(p)
            df = read_trial_file(p, marker=this_marker, **opts)
        except DataFormatError as e:
            problems.append(FileProblem(str(p), participant, trial, _reason(e, p)))
            continue
        except OSError as e:  # Permission denied, an I/O error: that file, not the run
            problems.append(FileProblem(str(p), participant, trial, f"cannot be read: {e.strerror or e}"))
            continue
        if not len(df):
            problems.append(FileProblem(str(p), participant, trial, "no samples"))
            continue
        stated.add(df.attrs.get("units"))
        notes += [f"{p.relative_to(root)}: {note}" for note in df.attrs.get("notes", [])]
        events += [(participant, trial, label, t) for label, t in df.attrs.get("events", [])]
        df = df.reindex(columns=list(TRIAL_COLUMNS))
        df.insert(0, "trial", trial)
        df.insert(0, "participant", participant)
        df["file"] = str(p.relative_to(root))  # where each sample came from, for messages
        df["sample"] = np.arange(1, len(df) + 1)
        frames.append(df)
    if not frames:
        first = [(q.path, q.reason) for q in problems] + [(str(root / q.path), q.reason) for q in unnamed]
        raise DataFormatError(
            f"{root}: none of the {len(found)} files could be read (first: {first[0][0]}: {first[0][1]})"
        )
    problems.sort(key=lambda q: (natural_key(q.participant or ""), natural_key(q.trial or ""), q.path))
    frame = pd.concat(frames, ignore_index=True)
    frame["participant"] = frame["participant"].astype(object)
    frame["trial"] = frame["trial"].astype(object)
    frame.attrs["units"] = None if None in stated else stated.pop() if len(stated) == 1 else "mixed"
    frame.attrs["notes"] = notes
    frame.attrs["events"] = events
    frame.attrs["skipped"] = sorted(skipped + unnamed, key=lambda q: natural_key(q.path))
    return frame, problems
