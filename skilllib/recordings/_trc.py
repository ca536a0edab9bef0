"""One trial from a TRC file (OpenSim's marker format): a marker's path, no contact signal.

A TRC file is tab-separated text::

    PathFileType  4  (X/Y/Z)  trial.trc
    DataRate  CameraRate  NumFrames  NumMarkers  Units  OrigDataRate  OrigDataStartFrame  OrigNumFrames
    100       100         250        2           mm     100           1                   250
    Frame#    Time        tip                     wrist
                          X1     Y1     Z1        X2     Y2     Z2
    1         0.000       ...

(an empty line may follow the ``X1`` row). :func:`read_trc` reads the header lines itself and the data
block with :func:`pandas.read_csv`. ``kineticstoolkit`` (0.17) and ``pyomeca`` read TRC too, but each
brings a large dependency tree (kineticstoolkit requires PyQt5, requests and requests-cache among others
and returns its own TimeSeries type; pyomeca builds on xarray) for what is 40 lines of pandas here;
the small ``trc-data-reader`` turns a cell that is not a number into a silent NaN (here: an error
naming the line) and imports ``c3d``.

Rules: the marker by name in the names row (the only one by default; several without a name, or an
unknown name, raise an error listing them); ``Units`` (``mm``, ``cm``, ``m``) from the header converted
to m (the ``units`` argument overrides it); ``t`` is the file's ``Time`` column (s); an empty cell or a
sample at exactly ``(0, 0, 0)`` is a gap (NaN, so :mod:`skilllib.recordings` marks the trial invalid);
``contact`` is all NaN: TRC has no contact signal, the height rule gives it
(:func:`skilllib.recordings.map_frame` with ``contact_height``).
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pandas as pd

from ._errors import DataFormatError, check_file, quote
from ._mapping import unit_factor

HEADER_LINES = 5  #: PathFileType, header names, header values, marker names, X1/Y1/Z1


def _lines(path: Path) -> list[str]:
    check_file(path, "TRC")
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError:
        raise DataFormatError(f"{path}: not a text (UTF-8) TRC file") from None
    lines = text.splitlines()
    if not lines or not lines[0].startswith("PathFileType"):
        raise DataFormatError(f"{path}, line 1: not a TRC file (the first line must start with 'PathFileType')")
    if len(lines) < HEADER_LINES:
        raise DataFormatError(f"{path}: TRC header cut short ({len(lines)} lines, need {HEADER_LINES})")
    return lines


def _header(lines: list[str], path: Path) -> dict[str, str]:
    """Header names (line 2) to values (line 3)."""
    names = [s.strip() for s in lines[1].split("\t")]
    values = [s.strip() for s in lines[2].split("\t")]
    header = {n: v for n, v in zip(names, values) if n}
    for key in ("DataRate", "NumMarkers", "Units"):
        if key not in header:
            raise DataFormatError(f"{path}, line 2: TRC header has no {key!r} (has: {', '.join(header)})")
    return header


def read_trc(path: str | Path, *, marker: str | None = None, units: str | None = None) -> pd.DataFrame:
    """One marker of a TRC file as one trial: columns ``t`` (s), ``x, y, z`` (m, the file's axes), ``contact`` (NaN).

    Rules in the module docstring.

    Parameters
    ----------
    path : str or pathlib.Path
        The TRC file (text).
    marker : str or None
        Name of the marker to read (text); None: the file's only marker.
    units : str or None
        Unit of the file's positions (text: ``"m"``, ``"cm"`` or ``"mm"``), overriding a missing or wrong
        header; None: the file's own.

    Returns
    -------
    pandas.DataFrame
        ``t`` (s), ``x, y, z`` (m, the file's axes), ``contact`` (NaN).

    Raises
    ------
    DataFormatError
        One line naming the file and line, when the file is missing, is not a TRC file, lacks
        ``DataRate``, ``NumMarkers`` or ``Units``, lists another number of markers than ``NumMarkers``, has
        several markers and no ``marker`` or no marker ``marker`` (listing them), has an unknown unit, or
        has a cell that is not a number in the chosen marker's or the time column.
    """
    path = Path(path)
    lines = _lines(path)
    header = _header(lines, path)
    names = [s.strip() for s in lines[3].split("\t")[2:] if s.strip()]
    try:
        n_markers = int(float(header["NumMarkers"]))
    except ValueError:
        raise DataFormatError(f"{path}, line 3: NumMarkers {header['NumMarkers']!r} is not a number") from None
    if len(names) != n_markers:
        raise DataFormatError(
            f"{path}, line 4: {len(names)} marker names ({', '.join(names)}) but NumMarkers is {n_markers}"
        )
    listed = ", ".join(names)
    if marker is None:
        if len(names) != 1:
            raise DataFormatError(f"{path}: {len(names)} markers ({listed or 'none'}): choose one with --marker NAME")
        k = 0
    elif marker.strip() in names:
        k = names.index(marker.strip())
    else:
        raise DataFormatError(f"{path}: no marker {marker!r} (markers: {listed})")
    factor = unit_factor(
        units if units is not None else header["Units"], str(path) if units is not None else f"{path}, line 3: Units"
    )
    data_lines = [i for i in range(HEADER_LINES, len(lines)) if lines[i].strip()]  # 0-based line numbers
    if not data_lines:
        raise DataFormatError(f"{path}: no data rows after the TRC header")
    body = "\n".join(lines[i] for i in data_lines)
    try:
        table = pd.read_csv(io.StringIO(body), sep="\t", header=None, dtype=str, keep_default_na=False)
    except pd.errors.ParserError as e:  # e.g. "Expected 8 fields in line 12, saw 9" (line of the data block)
        msg = str(e).replace("Error tokenizing data. C error: ", "").strip()
        raise DataFormatError(
            f"{path}: data rows are not a regular tab-separated table ({msg}; the data "
            f"start on line {data_lines[0] + 1})"
        ) from None
    cols = {"t": 1, "x": 2 + 3 * k, "y": 3 + 3 * k, "z": 4 + 3 * k}
    out = {}
    for name, j in cols.items():
        if j >= table.shape[1]:
            raise DataFormatError(
                f"{path}, line {data_lines[0] + 1}: no column {j + 1} for {name!r} "
                f"(the data rows have {table.shape[1]} columns)"
            )
        text = table[j].fillna("").str.strip()
        num = pd.to_numeric(text, errors="coerce")
        bad = (num.isna() & (text != "")).to_numpy()
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise DataFormatError(
                f"{path}, line {data_lines[i] + 1}, column {j + 1} ({name}): {quote(text.iloc[i])} is not a number"
            )
        out[name] = num.to_numpy(dtype=float, na_value=np.nan)
    xyz = np.column_stack([out["x"], out["y"], out["z"]])
    xyz[np.all(xyz == 0, axis=1)] = np.nan
    xyz *= factor
    return pd.DataFrame(
        {"t": out["t"], "x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2], "contact": np.full(len(xyz), np.nan)}
    )


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
