"""One trial from a TRC file (OpenSim's marker format): a marker's path, no contact signal.

A TRC file is text, tab-separated as OpenSim writes it::

    PathFileType  4  (X/Y/Z)  trial.trc
    DataRate  CameraRate  NumFrames  NumMarkers  Units  OrigDataRate  OrigDataStartFrame  OrigNumFrames
    100       100         250        2           mm     100           1                   250
    Frame#    Time        tip                     wrist
                          X1     Y1     Z1        X2     Y2     Z2
    1         0.000       ...

(an empty line may follow the ``X1`` row). :func:`read_trc` reads the header lines itself and the data
block with :func:`pandas.read_csv`. ``kineticstoolkit`` (0.17) and ``pyomeca`` read TRC too, but each
brings a large dependency tree (kineticstoolkit requires PyQt5, requests and requests-cache among others
and returns its own TimeSeries type; pyomeca builds on xarray) for what is a page of pandas here;
the small ``trc-data-reader`` turns a cell that is not a number into a silent NaN (here: an error
naming the line) and imports ``c3d``.

**What is read** (the variants other writers produce):

* the separator, tab or comma (pyomeca writes commas), from the header names (line 2); it holds for every
  line, and a message that lists columns or markers says how the line was split ("split at tabs");
* header lines 2 and 3 (names, values) with repeated separators and spaces around the cells (OpenSim's
  MATLAB writers put ``\\t\\t`` and ``%7d`` there); a value is matched to its name by position once empty
  cells are dropped (or, when that does not pair them, with empty cells kept);
* the marker names (line 4) after the ``Frame#`` and ``Time`` labels, each over its three columns (name
  in the first, two empty) or repeated in each of them; spaces and repeated separators around them;
* the ``X1 Y1 Z1`` line (line 5; when it is missing the data start on line 5, with a note), blank lines
  (also lines of separators only, as pyomeca writes) and Windows line ends anywhere;
* columns of the data rows: the labels of line 4 (``Frame#``, ``Time``, either may be missing), then
  three per marker in the order of the names; a row cut short after its last sample has empty cells.

**Rules**: the marker by name (the only one by default; several without a name, an unknown name, or a
name given twice raise an error listing them); ``Units`` (``mm``, ``cm``, ``m``) from the header
converted to m (the ``units`` argument overrides it, and is needed when the header states none);
``NumMarkers`` must be a whole number equal to the names listed; ``t`` is the file's ``Time`` column
(s), believed over ``DataRate`` (without a ``Time`` column: ``(Frame# - first Frame#) / DataRate``, or
the row number over ``DataRate``); an empty cell or a sample at exactly ``(0, 0, 0)`` is a gap (NaN,
so :mod:`skilllib.recordings` marks the trial invalid); ``contact`` is all NaN: TRC has no contact
signal, the height rule gives it (:func:`skilllib.recordings.map_frame` with ``contact_height``).

**Notes, not errors** (the data present are believed), in ``frame.attrs["notes"]`` (a list of text):
``NumFrames`` different from the data rows ("header announces 652 frames, file has 93"), ``DataRate``
more than 1 % from the rate of the ``Time`` column, a ``DataRate`` or ``NumFrames`` that is not a number
while the data do not need it, no ``Time`` column, no ``X1 Y1 Z1`` line. ``frame.attrs["units"]`` is
the unit the header states (``"mm"``, ``"m"``, ``"cm"``, as written when unknown) or None.

Every refusal is a :class:`~skilllib.recordings.DataFormatError` naming the file and, where it
applies, the line, the marker and what to do.
"""

from __future__ import annotations

import csv
import io
import math
import re
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pandas as pd

from ._errors import DataFormatError, check_file, quote
from ._mapping import unit_factor

HEADER_LINES = 5  #: PathFileType, header names, header values, marker names, X1/Y1/Z1
SEPARATORS = {"\t": "tabs", ",": "commas"}  #: the separators a TRC file may use, and how a message names them
RATE_TOLERANCE = 0.01  #: relative difference of DataRate and the Time column's rate above which a note says so
_COORDINATE = re.compile(r"[XYZ]\d+", re.IGNORECASE)


class _Layout(NamedTuple):
    """What the header lines say: separator, header, markers, the columns before them, where data start."""

    sep: str
    header: dict[str, str]
    names: list[str]
    lead: list[str]  # "frame" and/or "time", in the order of the columns before the markers
    first: int  # 0-based index of the first line after the header (the X1/Y1/Z1 line when there is one)


def _lines(path: Path) -> list[str]:
    check_file(path, "TRC")
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError:
        raise DataFormatError(f"{path}: not a text (UTF-8) TRC file") from None
    lines = text.splitlines()
    if not lines or not lines[0].lstrip().startswith("PathFileType"):
        raise DataFormatError(f"{path}, line 1: not a TRC file (the first line must start with 'PathFileType')")
    if len(lines) < HEADER_LINES:
        raise DataFormatError(f"{path}: TRC header cut short ({len(lines)} lines, need {HEADER_LINES})")
    return lines


def _separator(lines: list[str], path: Path) -> str:
    """Tab or comma: the one of them that separates the header names (line 2)."""
    counts = {sep: lines[1].count(sep) for sep in SEPARATORS}
    sep = max(counts, key=lambda s: counts[s])
    if counts[sep] == 0:
        raise DataFormatError(
            f"{path}, line 2: the header names are separated neither by tabs nor by commas ({quote(lines[1])}); "
            "write DataRate, NumMarkers, Units, ... as tab-separated cells"
        )
    return sep


def _cells(line: str, sep: str) -> list[str]:
    return [c.strip() for c in line.split(sep)]


def _is_blank(line: str, sep: str) -> bool:
    return not line.replace(sep, "").strip()


def _header(lines: list[str], path: Path, sep: str) -> dict[str, str]:
    """Header names (line 2) to values (line 3), empty cells dropped (or kept, when only that pairs them)."""
    how = SEPARATORS[sep]
    names, values = _cells(lines[1], sep), _cells(lines[2], sep)
    full_names, full_values = [c for c in names if c], [c for c in values if c]
    if len(full_names) != len(full_values):  # an empty value: pair the cells by position, empty ones kept
        while names and not names[-1]:
            names.pop()
        while values and not values[-1]:
            values.pop()
        if len(names) != len(values):
            raise DataFormatError(
                f"{path}, line 3: {len(full_values)} header values ({', '.join(full_values)}) for "
                f"{len(full_names)} header names on line 2 ({', '.join(full_names)}), both split at {how}: "
                "give each name one value"
            )
        full_names, full_values = names, values
    header = {n: v for n, v in zip(full_names, full_values) if n}
    if "NumMarkers" not in header:
        raise DataFormatError(
            f"{path}, line 2: TRC header has no 'NumMarkers' (header names, split at {how}: "
            f"{', '.join(header) or 'none'}); add it with the number of markers on line 3"
        )
    return header


def _whole(text: str) -> int | None:
    """``text`` as a whole number >= 0, or None when it is not one (``inf``, ``2.5``, ``abc``, ``-1``)."""
    try:
        value = float(text)
    except ValueError:
        return None
    if not math.isfinite(value) or value < 0 or value != int(value):
        return None
    return int(value)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _rate(text: str | None) -> float | None:
    """``DataRate`` as a positive finite rate (Hz), or None when absent or not one."""
    try:
        value = float(text) if text is not None else math.nan
    except ValueError:
        return None
    return value if math.isfinite(value) and value > 0 else None


def _layout(lines: list[str], path: Path) -> _Layout:
    sep = _separator(lines, path)
    how = SEPARATORS[sep]
    header = _header(lines, path, sep)
    n_markers = _whole(header["NumMarkers"])
    if n_markers is None:
        raise DataFormatError(
            f"{path}, line 3: NumMarkers {quote(header['NumMarkers'])} is not a whole number of markers "
            f"(line split at {how}); write the number of markers listed on line 4"
        )
    cells = [c for c in _cells(lines[3], sep) if c]
    lead: list[str] = []
    for c in cells[:2]:
        label = "frame" if c.lower().startswith("frame") else "time" if c.lower().startswith("time") else None
        if label is None or label in lead:
            break
        lead.append(label)
    names = cells[len(lead) :]
    if n_markers and len(names) == 3 * n_markers and names[0::3] == names[1::3] == names[2::3]:
        names = names[0::3]  # each name repeated over its X, Y, Z columns
    if len(names) != n_markers:
        raise DataFormatError(
            f"{path}, line 4: {len(names)} marker names ({', '.join(names)}) but NumMarkers is {n_markers} "
            f"(line split at {how}); make them agree: each marker named once, in the first of its three columns"
        )
    coordinates = [c for c in _cells(lines[4], sep) if c]
    first = 4 if coordinates and _COORDINATE.fullmatch(coordinates[0]) is None and _is_number(coordinates[0]) else 5
    return _Layout(sep, header, names, lead, first)


def _marker_index(layout: _Layout, marker: str | None, path: Path) -> int:
    names, how = layout.names, SEPARATORS[layout.sep]
    listed = ", ".join(names) or "none"
    if marker is None:
        if len(names) != 1:
            raise DataFormatError(
                f"{path}: {len(names)} markers ({listed}): choose one with --marker NAME (line 4 split at {how})"
            )
        return 0
    if marker.strip() not in names:
        raise DataFormatError(
            f"{path}, line 4: no marker {marker!r} (markers: {listed}; line split at {how}): "
            "choose one of them with --marker NAME"
        )
    if names.count(marker.strip()) > 1:
        raise DataFormatError(
            f"{path}, line 4: marker {marker!r} is named {names.count(marker.strip())} times (markers: {listed}; "
            f"line split at {how}): rename the copies in the file"
        )
    return names.index(marker.strip())


def _columns(
    lines: list[str], rows: list[int], cols: dict[str, int], layout: _Layout, path: Path
) -> dict[str, np.ndarray]:
    """The numbers of columns ``cols`` (name -> 0-based column) of data lines ``rows``; NaN where empty."""
    sep, how = layout.sep, SEPARATORS[layout.sep]
    expected = len(layout.lead) + 3 * len(layout.names)
    widths = [len(lines[i].rstrip(sep + " ").split(sep)) for i in rows]
    width = max(lines[i].count(sep) for i in rows) + 1
    if max(widths) > expected:
        i = rows[int(np.argmax(np.asarray(widths) > expected))]
        labels = " and ".join(c.capitalize() for c in layout.lead) or "no Frame#/Time"
        raise DataFormatError(
            f"{path}, line {i + 1}: {max(widths)} columns, but the header describes {expected} ({labels}, then 3 "
            f"for each of {len(layout.names)} markers; split at {how}): check NumMarkers and the names on line 4"
        )
    for name, j in cols.items():
        if j >= width:
            raise DataFormatError(
                f"{path}, line {rows[0] + 1}: no column {j + 1} for {name!r} (the data rows have {width} columns, "
                f"split at {how})"
            )
    body = "\n".join(lines[i] for i in rows)
    try:
        table = pd.read_csv(
            io.StringIO(body),
            sep=sep,
            header=None,
            names=range(width),
            usecols=sorted(set(cols.values())),
            dtype=str,
            keep_default_na=False,
            quoting=csv.QUOTE_NONE,
            skip_blank_lines=False,
        )
    except (pd.errors.ParserError, ValueError) as e:
        raise DataFormatError(
            f"{path}: data rows are not a regular table split at {how} ({e}; the data start on line {rows[0] + 1})"
        ) from None
    out = {}
    for name, j in cols.items():
        text = table[j].fillna("").str.strip()
        num = pd.to_numeric(text, errors="coerce")
        bad = (num.isna() & (text != "")).to_numpy()
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise DataFormatError(
                f"{path}, line {rows[i] + 1}, column {j + 1} ({name}): {quote(text.iloc[i])} is not a number"
            )
        out[name] = num.to_numpy(dtype=float, na_value=np.nan)
    return out


def _time(data: dict[str, np.ndarray], header: dict[str, str], n: int, path: Path, notes: list[str]) -> np.ndarray:
    """``t`` (s): the Time column, believed over DataRate; without it, Frame# (or the row) over DataRate."""
    rate = _rate(header.get("DataRate"))
    stated = f"DataRate {quote(header['DataRate'])}" if "DataRate" in header else "no DataRate"
    if "time" in data:
        t = data["time"]
        steps = np.diff(t[np.isfinite(t)])
        step = float(np.median(steps)) if len(steps) else math.nan
        if rate is None:
            notes.append(f"header has {stated} (not a rate in Hz): the Time column is used")
        elif step > 0 and abs(1 / step / rate - 1) > RATE_TOLERANCE:
            notes.append(
                f"header DataRate is {rate:g} Hz, the Time column steps {step:g} s ({1 / step:g} Hz): "
                "the Time column is used"
            )
        return t
    if rate is None:
        raise DataFormatError(
            f"{path}, line 3: {stated}, not a rate in Hz, and no Time column to take the times from: "
            "write the sampling rate (Hz) as DataRate"
        )
    if "frame" in data and np.isfinite(data["frame"]).all():
        notes.append(f"no Time column: t from Frame# and DataRate ({rate:g} Hz)")
        return (data["frame"] - data["frame"][0]) / rate
    notes.append(f"no Time column: t from the row number and DataRate ({rate:g} Hz)")
    return np.arange(n) / rate


def read_trc(path: str | Path, *, marker: str | None = None, units: str | None = None) -> pd.DataFrame:
    """One marker of a TRC file as one trial: columns ``t`` (s), ``x, y, z`` (m, the file's axes), ``contact`` (NaN).

    Rules, the variants read and the notes in the module docstring.

    Parameters
    ----------
    path : str or pathlib.Path
        The TRC file (text, tab- or comma-separated).
    marker : str or None
        Name of the marker to read (text); None: the file's only marker.
    units : str or None
        Unit of the file's positions (text: ``"m"``, ``"cm"`` or ``"mm"``), overriding a missing or wrong
        header; None: the file's own.

    Returns
    -------
    pandas.DataFrame
        ``t`` (s), ``x, y, z`` (m, the file's axes), ``contact`` (NaN); ``attrs["notes"]``: what the reader
        noticed but did not refuse (list of text, empty when nothing), ``attrs["units"]``: the unit the header
        states (text, ``"mm"``, ``"m"``, ``"cm"``) or None.

    Raises
    ------
    DataFormatError
        One line naming the file (and the line, marker and what to do, where they apply), when the file is
        missing, is not a TRC file, is split neither at tabs nor at commas, has header values that do not
        pair with its names, lacks ``NumMarkers`` or has one that is not a whole number, lists another number
        of markers than ``NumMarkers``, has several markers and no ``marker`` or no marker ``marker``
        (listing them), has no unit (header or ``units``) or an unknown one, has data rows wider than the
        header describes, has no ``Time`` column and no ``DataRate``, or has a cell that is not a number in
        the chosen marker's or the time column.
    """
    path = Path(path)
    lines = _lines(path)
    layout = _layout(lines, path)
    k = _marker_index(layout, marker, path)
    header, notes = layout.header, []
    stated = header.get("Units") or None
    if stated is not None and stated.strip().lower() in ("m", "cm", "mm"):
        stated = stated.strip().lower()
    if units is not None:
        factor = unit_factor(units, str(path))
    elif stated is None:
        raise DataFormatError(
            f"{path}, line 3: the TRC header states no Units: give the unit of the positions with --units (m, cm, mm)"
        )
    else:
        try:
            factor = unit_factor(stated, f"{path}, line 3: Units")
        except DataFormatError as e:
            raise DataFormatError(f"{e}; give the unit of the positions with --units") from None
    if layout.first == 4:
        notes.append("no X1/Y1/Z1 line: the data start on line 5")
    rows = [i for i in range(layout.first, len(lines)) if not _is_blank(lines[i], layout.sep)]
    if not rows:
        raise DataFormatError(f"{path}: no data rows after the TRC header (line {layout.first + 1} on)")
    n_lead = len(layout.lead)
    cols = {label: j for j, label in enumerate(layout.lead)}
    cols.update({"x": n_lead + 3 * k, "y": n_lead + 3 * k + 1, "z": n_lead + 3 * k + 2})
    data = _columns(lines, rows, cols, layout, path)
    if "NumFrames" in header:
        n_frames = _whole(header["NumFrames"])
        if n_frames is None:
            notes.append(f"header NumFrames {quote(header['NumFrames'])} is not a whole number (ignored)")
        elif n_frames != len(rows):
            notes.append(f"header announces {n_frames} frames, file has {len(rows)}")
    t = _time(data, header, len(rows), path, notes)
    xyz = np.column_stack([data["x"], data["y"], data["z"]])
    xyz[np.all(xyz == 0, axis=1)] = np.nan
    xyz *= factor
    frame = pd.DataFrame({"t": t, "x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2], "contact": np.full(len(xyz), np.nan)})
    frame.attrs["notes"] = notes
    frame.attrs["units"] = stated
    return frame


def write_trc(path: str | Path, markers: dict[str, np.ndarray], t: np.ndarray, *, units: str = "mm") -> Path:
    """Write marker paths as a TRC file (the layout :func:`read_trc` reads, OpenSim's).

    A NaN position is written as an empty cell (a gap). Creates the folder.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write (text).
    markers : dict of str to numpy.ndarray
        Marker name (text) -> (N, 3) positions (m).
    t : numpy.ndarray, shape (N,)
        The time stamps (s), uniform (DataRate is 1 / their mean interval).
    units : str
        The unit the positions are written in (text: ``mm``, ``cm`` or ``m``), to 0.001 of the unit.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    factor = unit_factor(units, str(path))
    t = np.asarray(t, dtype=float)
    n = len(t)
    rate = (n - 1) / (t[-1] - t[0]) if n > 1 else 0.0
    names = list(markers)
    head = [
        f"PathFileType\t4\t(X/Y/Z)\t{path.name}",
        "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames",
        f"{rate:g}\t{rate:g}\t{n}\t{len(names)}\t{units}\t{rate:g}\t1\t{n}",
        "Frame#\tTime\t" + "\t".join(f"{m}\t\t" for m in names),
        "\t\t" + "\t".join(f"X{i}\tY{i}\tZ{i}" for i in range(1, len(names) + 1)),
        "",
    ]
    cols = [np.asarray(markers[m], dtype=float) / factor for m in names]
    rows = []
    for i in range(n):
        cells = [str(i + 1), f"{t[i]:.6f}"]
        for c in cols:
            cells += ["" if not np.isfinite(v) else f"{v:.3f}" for v in c[i]]
        rows.append("\t".join(cells))
    path.write_text("\n".join(head + rows) + "\n")
    return path
