"""One trial from a Vicon Nexus CSV export ("Trajectories"): a marker's path, no contact signal.

Nexus's *Export CSV* writes one section per kind of data, each starting with its name on a line of its
own (the first line of the file, or after a blank line)::

    Trajectories                         <- section name (NEXUS_SECTIONS)
    100                                  <- the section's rate (Hz)
    ,,ADL005:RFTP,,,ADL005:LFTP,,,       <- marker names, each over its three columns (subject prefix)
    Frame,Sub Frame,X,Y,Z,X,Y,Z          <- column names
    ,,mm,mm,mm,mm,mm,mm                  <- units
    1,0,123.3,-211.5,426.2,,,            <- one row per frame; empty cells where a marker is not seen

    Devices                              <- further sections (Model Outputs, Devices, Joints, Segments)
    1000                                    are skipped; only Trajectories is read
    ...

The file may be compressed (``.csv.gz``, ``.zip``, ...; as pandas infers from the name) and is recognised
by its content (:func:`is_nexus`: the first line is a section name), not its name.

Rules: the marker by name (:func:`choose_marker`): the full name (``ADL005:RFTP``) or the name after the
subject prefix (``RFTP``); a name two subjects share is ambiguous (an error listing the candidates); no
name: the file's only marker. A list ``"RFTP,LFTP"`` means *the one of these that moves most in this
file* (the largest range of x, y or z over the trial; markers not in the file, or never seen, are
skipped): the moving hand's fingertip when both are recorded. Units (``mm``, ``cm``, ``m``) from the
units row, converted to m (``units`` overrides them); ``t`` from ``Frame`` and ``Sub Frame``:
``t = ((Frame - 1) * n_sub + Sub Frame) / rate`` with ``n_sub`` sub frames per frame (1 when every
``Sub Frame`` is 0: ``t = (Frame - 1) / rate``). An empty cell is NaN, so :mod:`skilllib.recordings`
marks the trial invalid; ``contact`` is all NaN (Nexus trajectories carry no contact signal: the height
rule gives it). The frame's ``attrs["units"]`` is the units row's unit, as :func:`read_c3d` and
:func:`read_trc` set theirs.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from ._csv import COMPRESSED, _read_text, text_head
from ._errors import DataFormatError, check_file, quote
from ._mapping import unit_factor

#: The section names of a Nexus CSV export; a file whose first line is one of them is a Nexus file.
NEXUS_SECTIONS = ("Trajectories", "Model Outputs", "Devices", "Joints", "Segments")
NEXUS_SUFFIXES = (".csv", ".txt")  #: the names a Nexus export may have (before a compression suffix)


def _section_name(line: str) -> str | None:
    """The section a line names (``Trajectories``; trailing separators allowed), or None."""
    name = line.strip().strip(",").strip()
    return name if name in NEXUS_SECTIONS else None


def is_nexus(path: str | Path) -> bool:
    """Whether a file is a Vicon Nexus CSV export: a ``.csv`` or ``.txt`` (also compressed) whose first line
    names a section (:data:`NEXUS_SECTIONS`).

    Parameters
    ----------
    path : str or pathlib.Path
        The file (text).

    Returns
    -------
    bool
        True for a Nexus export (dimensionless).
    """
    path = Path(path)
    name = path.name.lower()
    for suffix in COMPRESSED:
        name = name.removesuffix(suffix)
    if not name.endswith(NEXUS_SUFFIXES) or not path.is_file():
        return False
    head = text_head(path, 256)
    return _section_name(head.split("\n", 1)[0]) is not None


def _lines(path: Path) -> list[str]:
    check_file(path, "Nexus CSV")
    return _read_text(path).replace("\r\n", "\n").replace("\r", "\n").split("\n")


def _sections(lines: list[str]) -> dict[str, int]:
    """Section name -> 0-based line of its name (the first line, or a line after a blank line)."""
    out: dict[str, int] = {}
    for i, line in enumerate(lines):
        if (i == 0 or not lines[i - 1].strip()) and (name := _section_name(line)) is not None:
            out.setdefault(name, i)
    return out


def choose_marker(names: list[str], marker: str, path: str | Path) -> str | None:
    """The one marker of ``names`` (text, ``SUBJECT:NAME`` or ``NAME``) that ``marker`` names.

    The full name, else the name after the subject prefix (the part after the last ``:``).

    Parameters
    ----------
    names : list of str
        The file's marker names (text).
    marker : str
        The name asked for (text).
    path : str or pathlib.Path
        The file, for the message (text).

    Returns
    -------
    str or None
        The marker's full name (text), or None when no marker has that name.

    Raises
    ------
    DataFormatError
        When the name after the prefix is that of several markers (listing them).
    """
    name = marker.strip()
    if name in names:
        return name
    tails = [n for n in names if n.rsplit(":", 1)[-1] == name]
    if len(tails) > 1:
        raise DataFormatError(f"{path}: marker {marker!r} is ambiguous: {', '.join(tails)}; give the full name")
    return tails[0] if tails else None


def _numbers(cells: list[list[str]], j: int, lines: list[int], path: Path, what: str) -> np.ndarray:
    """Column ``j`` of the data rows as floats (empty: NaN); a cell that is not a number raises."""
    out = np.full(len(cells), np.nan)
    for k, row in enumerate(cells):
        text = row[j].strip()
        if not text:
            continue
        try:
            out[k] = float(text)
        except ValueError:
            raise DataFormatError(
                f"{path}, line {lines[k]}, column {j + 1} ({what}): {quote(text)} is not a number"
            ) from None
    return out


def read_nexus(path: str | Path, *, marker: str | None = None, units: str | None = None) -> pd.DataFrame:
    """One marker of a Vicon Nexus CSV export as one trial: ``t`` (s), ``x, y, z`` (m, the file's axes),
    ``contact`` (NaN).

    The layout and the rules (marker names and lists, units, time from frames and sub frames) are in the
    module docstring.

    Parameters
    ----------
    path : str or pathlib.Path
        The Nexus CSV file, perhaps compressed (text).
    marker : str or None
        The marker's name, with or without the subject prefix, or several separated by commas (the one
        moving most; text); None: the file's only marker.
    units : str or None
        The unit of the positions (text: ``"m"``, ``"cm"``, ``"mm"``), replacing the units row's; None:
        the file's own.

    Returns
    -------
    pandas.DataFrame
        Columns ``t`` (s), ``x, y, z`` (m), ``contact`` (all NaN); ``attrs["units"]``: the units row's unit
        (text, None when the row has none), ``attrs["marker"]``: the marker read (text).

    Raises
    ------
    DataFormatError
        One line naming the file (and line): no Trajectories section, a rate that is not a positive number,
        a missing names, column-name or units row, an unknown unit, ragged rows, a cell that is not a
        number, no frames, no such marker (listing the markers), an ambiguous marker name.
    """
    path = Path(path)
    lines = _lines(path)
    sections = _sections(lines)
    if "Trajectories" not in sections:
        found = ", ".join(sections) or "none"
        raise DataFormatError(
            f"{path}: no Trajectories section in this Nexus export (sections: {found}); export the "
            f"trajectories (markers) from Nexus"
        )
    s = sections["Trajectories"]
    header = lines[s + 1 : s + 5]
    if len(header) < 4:
        raise DataFormatError(f"{path}: Trajectories section cut short after line {len(lines)} (no frames)")
    rate_text = header[0].split(",")[0].strip()
    try:
        rate = float(rate_text)
    except ValueError:
        rate = float("nan")
    if not np.isfinite(rate) or rate <= 0:
        raise DataFormatError(f"{path}, line {s + 2}: rate {quote(rate_text)} is not a positive number (Hz)")
    names_row = header[1].split(",")
    columns_row = [c.strip() for c in header[2].split(",")]
    units_row = [c.strip() for c in header[3].split(",")]
    if columns_row[:2] != ["Frame", "Sub Frame"]:
        raise DataFormatError(
            f"{path}, line {s + 4}: expected the column names 'Frame,Sub Frame,X,Y,Z,...', found {quote(header[2])}"
        )
    width = len(columns_row)
    if units_row[0] or len(units_row) < 3 or units_row[2][:1].isdigit():  # a frame number: a data row
        raise DataFormatError(
            f"{path}, line {s + 5}: no units row (expected ',,mm,mm,mm,...' after the X,Y,Z line, found "
            f"{quote(header[3])})"
        )
    markers = {n.strip(): j for j, n in enumerate(names_row) if j >= 2 and n.strip()}
    for name, j in markers.items():
        if j + 2 >= width or columns_row[j : j + 3] != ["X", "Y", "Z"]:
            raise DataFormatError(
                f"{path}, line {s + 4}: marker {name!r} (line {s + 3}, column {j + 1}) is not over X, Y, Z columns"
            )
    listed = ", ".join(markers) or "none"
    if marker is None:
        if len(markers) != 1:
            raise DataFormatError(f"{path}: {len(markers)} markers ({listed}): choose one with --marker NAME")
        wanted = list(markers)
    else:
        asked = [m for m in marker.split(",") if m.strip()]
        wanted = [n for m in asked if (n := choose_marker(list(markers), m, path)) is not None]
        if not wanted:
            raise DataFormatError(f"{path}: no marker {marker!r} (markers: {listed})")
    data_lines, cells = [], []
    for i in range(s + 5, len(lines)):
        if not lines[i].strip():  # the end of the section
            break
        row = lines[i].split(",")
        if len(row) != width:
            raise DataFormatError(
                f"{path}, line {i + 1}: {len(row)} fields, the column-name row (line {s + 4}) has {width}"
            )
        data_lines.append(i + 1)
        cells.append(row)
    if not cells:
        raise DataFormatError(f"{path}: no frames in the Trajectories section (line {s + 6} on)")
    frame = _numbers(cells, 0, data_lines, path, "Frame")
    sub = _numbers(cells, 1, data_lines, path, "Sub Frame")
    for what, v in (("Frame", frame), ("Sub Frame", sub)):
        if np.isnan(v).any():
            k = int(np.flatnonzero(np.isnan(v))[0])
            raise DataFormatError(f"{path}, line {data_lines[k]}: {what} is empty")
    n_sub = int(np.max(sub)) + 1
    t = ((frame - 1) * n_sub + sub) / rate
    best, best_span, best_xyz = wanted[0], -1.0, np.full((len(t), 3), np.nan)
    for name in wanted:
        j = markers[name]
        unit = units if units is not None else units_row[j] if j < len(units_row) else ""
        if not unit:
            raise DataFormatError(f"{path}, line {s + 5}, column {j + 1}: no unit for marker {name!r}")
        where = str(path) if units is not None else f"{path}, line {s + 5}, column {j + 1}"
        factor = unit_factor(unit, where)
        xyz = np.column_stack([_numbers(cells, j + a, data_lines, path, f"{name} {'XYZ'[a]}") for a in range(3)])
        seen = np.isfinite(xyz).all(axis=1)
        span = float(np.ptp(xyz[seen], axis=0).max()) * factor if seen.any() else -1.0
        if span > best_span:
            best, best_span, best_xyz = name, span, xyz * factor
    if best_span < 0 and len(wanted) > 1:
        raise DataFormatError(f"{path}: none of the markers {', '.join(wanted)} is seen in any frame")
    out = pd.DataFrame(
        {"t": t, "x": best_xyz[:, 0], "y": best_xyz[:, 1], "z": best_xyz[:, 2], "contact": np.full(len(t), np.nan)}
    )
    j = markers[best]
    out.attrs["units"] = (units_row[j] if j < len(units_row) else "") or None
    out.attrs["marker"] = best
    return out
