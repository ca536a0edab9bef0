"""From a lab's table to the book's frame: column names, units, the vertical axis, contact from height.

The book's frame (:mod:`skilllib.recordings`): positions in m, ``x`` mediolateral, ``y`` vertical **up**,
``z`` anteroposterior; ``contact`` 0/1. :func:`map_frame` turns a long table with other column names,
another length unit or another vertical axis into it, in this order:

1. **columns**: ``{old: new}`` renames (``--columns old=new,...``, parsed by :func:`parse_columns`).
2. **units**: ``x, y, z`` multiplied by :data:`UNIT_FACTORS` (``m`` 1, ``cm`` 0.01, ``mm`` 0.001); ``t``
   by :data:`TIME_UNIT_FACTORS` (``--time-unit s|ms|us``: 1, 0.001, 0.000001).
3. **vertical axis**: ``p_book = R p_lab`` with the proper rotation (``det R = +1``, no mirroring)
   :data:`UP_AXIS_ROTATIONS` that sends the lab's up axis to the book's ``+y``. In
   ``(x, y, z)_book`` terms:

   =========  =====================  =================================================
   up axis    ``(x, y, z)_book``     rotation
   =========  =====================  =================================================
   ``y``      ``( x,  y,  z)``       identity
   ``-y``     ``( x, -y, -z)``       180 deg about x
   ``z``      ``( x,  z, -y)``       -90 deg about x (the usual motion-capture lab: z up)
   ``-z``     ``( x, -z,  y)``       +90 deg about x
   ``x``      ``(-y,  x,  z)``       +90 deg about z
   ``-x``     ``( y, -x,  z)``       -90 deg about z
   =========  =====================  =================================================

   A rotation keeps every distance, so speeds, SPARC and LDLJ do not change; only the height used by
   the contact rule and the figures' vertical axis do.
4. **contact from height** (:func:`contact_from_height`), for a trial with no contact signal (no
   ``contact`` column, or the trial's ``contact`` all empty): ``contact = 1`` from the first sample whose
   vertical position ``y`` (after steps 2-3, in m) is at or below ``contact_height`` (m) on, 0 before;
   the flag stays 1 once set (the pipeline uses the first contact sample only). A trial that never gets
   that low has no contact sample, which :mod:`skilllib.features` reports ("no contact"). A trial with a
   contact signal keeps it: the height rule never overrides a measured flag.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd

from ._columns import POSITION_COLUMNS
from ._csv import columns_found
from ._errors import DataFormatError, quote

UNIT_FACTORS: dict[str, float] = {"m": 1.0, "cm": 0.01, "mm": 0.001}  #: metres per unit
TIME_UNIT_FACTORS: dict[str, float] = {"s": 1.0, "ms": 1e-3, "us": 1e-6}  #: seconds per time unit

#: ``R`` per up axis: ``p_book = R @ p_lab`` (column vectors ``(x, y, z)``); each is proper (det +1)
UP_AXIS_ROTATIONS: dict[str, np.ndarray] = {
    "y": np.eye(3),
    "-y": np.array([[1.0, 0, 0], [0, -1, 0], [0, 0, -1]]),
    "z": np.array([[1.0, 0, 0], [0, 0, 1], [0, -1, 0]]),
    "-z": np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]]),
    "x": np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]]),
    "-x": np.array([[0.0, 1, 0], [-1, 0, 0], [0, 0, 1]]),
}


def unit_factor(units: str, source: str = "<DataFrame>") -> float:
    """Metres per ``units`` (``m``, ``cm``, ``mm``; case and surrounding spaces ignored).

    Raises :class:`~skilllib.recordings.DataFormatError` naming ``source`` for any other unit.
    """
    key = str(units).strip().lower()
    if key not in UNIT_FACTORS:
        raise DataFormatError(f"{source}: unknown length unit {units!r} (known: {', '.join(UNIT_FACTORS)})")
    return UNIT_FACTORS[key]


def time_unit_factor(time_unit: str, source: str = "<DataFrame>") -> float:
    """Seconds per ``time_unit`` (``s``, ``ms``, ``us``; ``µs`` too; case and spaces ignored).

    Parameters
    ----------
    time_unit : str
        The unit of the table's ``t`` (text).
    source : str
        The table's name in messages (text).

    Returns
    -------
    float
        Seconds per unit (s).

    Raises
    ------
    DataFormatError
        For any other unit.
    """
    key = str(time_unit).strip().lower().replace("µ", "u")
    if key not in TIME_UNIT_FACTORS:
        raise DataFormatError(f"{source}: unknown time unit {time_unit!r} (known: {', '.join(TIME_UNIT_FACTORS)})")
    return TIME_UNIT_FACTORS[key]


def up_axis_rotation(up_axis: str) -> np.ndarray:
    """The proper rotation (3 x 3) taking ``up_axis`` to the book's ``+y``: ``p_book = R @ p_lab``.

    The table is in the module docstring.

    Parameters
    ----------
    up_axis : str
        The lab's vertical axis (text: ``y``, ``-y``, ``z``, ``-z``, ``x``, ``-x``; a leading ``+``
        allowed).

    Returns
    -------
    numpy.ndarray, shape (3, 3)
        The rotation matrix R (dimensionless).

    Raises
    ------
    DataFormatError
        For an unknown axis.
    """
    key = str(up_axis).strip().lower().removeprefix("+")
    if key not in UP_AXIS_ROTATIONS:
        raise DataFormatError(f"unknown up axis {up_axis!r} (known: {', '.join(UP_AXIS_ROTATIONS)})")
    return UP_AXIS_ROTATIONS[key]


def parse_columns(spec: str) -> dict[str, str]:
    """``"old=new,old2=new2"`` (the ``--columns`` option) as ``{old: new}``; spaces around names ignored.

    Parameters
    ----------
    spec : str
        The option's value (text).

    Returns
    -------
    dict of str to str
        The renames (text).

    Raises
    ------
    DataFormatError
        For an item without ``=``, an empty name or an old name given twice.
    """
    out: dict[str, str] = {}
    for item in str(spec).split(","):
        if not item.strip():
            continue
        old, sep, new = item.partition("=")
        old, new = old.strip(), new.strip()
        if not sep or not old or not new:
            raise DataFormatError(f"--columns: {item.strip()!r} is not old=new (e.g. --columns time=t,pos_x=x)")
        if old in out:
            raise DataFormatError(f"--columns: column {old!r} is renamed twice")
        out[old] = new
    return out


def rename_columns(df: pd.DataFrame, columns: Mapping[str, str], source: str = "<DataFrame>") -> pd.DataFrame:
    """``df`` with columns renamed ``old -> new``; an ``old`` that is not a column, or a rename that
    would give two columns one name, raises :class:`~skilllib.recordings.DataFormatError` listing the columns."""
    have = [str(c).strip() for c in df.columns]
    missing = [old for old in columns if old not in have]
    if missing:
        raise DataFormatError(
            f"{source}: --columns names column {missing[0]!r}, which the table does not have "
            f"({columns_found(have, df.attrs.get('sep'))})"
        )
    new_names = [columns.get(c, c) for c in have]
    dup = sorted({n for n in new_names if new_names.count(n) > 1})
    if dup:
        raise DataFormatError(
            f"{source}: after --columns, column {dup[0]!r} would appear twice (columns after renaming: "
            f"{', '.join(new_names)}; {columns_found(have, df.attrs.get('sep'))})"
        )
    out = df.copy()
    out.columns = new_names
    return out


def _number_column(df: pd.DataFrame, c: str, source: str, first_line: int | None) -> np.ndarray:
    """Column ``c`` as a float array; a cell that is not a number raises naming its row/line."""
    col = df[c]
    if pd.api.types.is_numeric_dtype(col) and not pd.api.types.is_bool_dtype(col):
        return col.to_numpy(dtype=float)
    text = col.astype("string").str.strip()
    num = pd.to_numeric(text, errors="coerce")
    bad = (num.isna() & text.notna() & (text != "")).to_numpy()
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        where = f"line {i + first_line}" if first_line is not None else f"row {i}"
        raise DataFormatError(f"{source}, {where}, column '{c}': {quote(text.iloc[i])} is not a number")
    return num.to_numpy(dtype=float, na_value=np.nan)


def _require(df: pd.DataFrame, names: tuple[str, ...], source: str) -> None:
    """DataFormatError naming the first of ``names`` that is not a column, with the columns found."""
    missing = [c for c in names if c not in df.columns]
    if missing:
        raise DataFormatError(
            f"{source}: required column {missing[0]!r} missing ({columns_found(df.columns, df.attrs.get('sep'))}); "
            f"rename with --columns old=new"
        )


def _positions(df: pd.DataFrame, source: str, first_line: int | None) -> np.ndarray:
    """x, y, z as an (N, 3) float array; a cell that is not a number raises naming its row/line."""
    _require(df, POSITION_COLUMNS, source)
    out = np.empty((len(df), 3))
    for j, c in enumerate(POSITION_COLUMNS):
        out[:, j] = _number_column(df, c, source, first_line)
    return out


def contact_from_height(y: np.ndarray, contact_height: float) -> np.ndarray:
    """The height rule for one trial: 1.0 from the first sample with ``y <= contact_height`` on, 0.0 before.

    All 0 when ``y`` never gets that low (NaN samples never count as low).

    Parameters
    ----------
    y : numpy.ndarray, shape (N,)
        The heights of the trial's samples (m).
    contact_height : float
        The height of the touched surface (m).

    Returns
    -------
    numpy.ndarray, shape (N,)
        The contact flag, 0.0 or 1.0 (dimensionless).
    """
    y = np.asarray(y, dtype=float)
    low = np.flatnonzero(y <= contact_height)
    c = np.zeros(len(y))
    if len(low):
        c[low[0] :] = 1.0
    return c


def _trial_keys(df: pd.DataFrame) -> pd.Series | None:
    """One label per row telling its trial (participant and trial as text), or None for a one-trial table."""
    if "participant" in df.columns and "trial" in df.columns:
        return df["participant"].astype(str) + "\x1f" + df["trial"].astype(str)
    return None


def map_frame(
    df: pd.DataFrame,
    *,
    columns: Mapping[str, str] | None = None,
    units: str | None = None,
    up_axis: str | None = None,
    contact_height: float | None = None,
    source: str = "<DataFrame>",
    first_line: int | None = None,
    time_unit: str | None = None,
) -> pd.DataFrame:
    """``df`` in the book's frame: columns renamed, positions in m, ``y`` up, contact filled where absent.

    The four steps and the rotation matrices are in the module docstring. Trials are told apart by
    ``participant`` and ``trial`` when the table has them (a table without them is one trial, as a C3D or
    TRC file). Other columns pass through unchanged; identifiers are never converted.

    Parameters
    ----------
    df : pandas.DataFrame
        The table: ``t`` (s), ``x, y, z`` (in ``units``), ids (text), ``contact`` (0/1) if present.
    columns : mapping of str to str or None
        Column renames ``{old: new}`` (text); None: no renaming.
    units : str or None
        The unit of the table's ``x, y, z`` (text: ``"m"``, ``"cm"``, ``"mm"``); None: already m.
    up_axis : str or None
        The lab's vertical axis with its sign (text: ``y``, ``-y``, ``z``, ``-z``, ``x``, ``-x``); None:
        already ``y``.
    contact_height : float or None
        The height of the touched surface in the book's frame, after the unit and axis change (m); None:
        no height rule.
    source : str
        The name of the table in messages (text).
    first_line : int or None
        The file line of row 0 (e.g. 2 after a CSV header; dimensionless), so that messages name file
        lines instead of rows; None: rows.
    time_unit : str or None
        The unit of the table's ``t`` (text: ``"s"``, ``"ms"``, ``"us"``), divided into seconds; None:
        already s.

    Returns
    -------
    pandas.DataFrame
        The table with ``t`` (s), ``x, y, z`` (m, y up) and ``contact`` (0/1).

    Raises
    ------
    DataFormatError
        For an unknown unit or axis, a ``columns`` entry naming a column that does not exist, a position
        cell that is not a number (only when positions are changed), and a table with no contact signal for
        some trial and no ``contact_height``.
    """
    factor = unit_factor(units, source) if units is not None else None
    t_factor = time_unit_factor(time_unit, source) if time_unit is not None else None
    try:
        rot = up_axis_rotation(up_axis) if up_axis is not None else None
    except DataFormatError as e:
        raise DataFormatError(f"{source}: {e}") from None
    out = rename_columns(df, columns, source) if columns else df.copy()
    if t_factor is not None and t_factor != 1.0:
        _require(out, ("t",), source)
        out["t"] = _number_column(out, "t", source, first_line) * t_factor
    if factor is not None or rot is not None:
        pos = _positions(out, source, first_line)
        if factor is not None:
            pos = pos * factor
        if rot is not None:
            pos = pos @ rot.T
        for j, c in enumerate(POSITION_COLUMNS):
            out[c] = pos[:, j]
    if "contact" in out.columns:
        raw = out["contact"]
        absent = raw.isna() | (raw.astype("string").str.strip() == "")
    else:
        absent = pd.Series(True, index=out.index)
    keys = _trial_keys(out)
    grouping = keys if keys is not None else pd.Series("", index=out.index)
    blank = out.isna().all(axis=1).to_numpy()  # blank lines of a CSV: no trial's
    rows = {k: r[~blank[r]] for k, r in grouping.groupby(grouping, sort=False).indices.items()}
    rows = {k: r for k, r in rows.items() if len(r)}
    absent_np = absent.to_numpy(dtype=bool)
    no_signal = [k for k, r in rows.items() if absent_np[r].all()]
    if not no_signal:
        return out
    if contact_height is None:
        what = (
            "no 'contact' column"
            if "contact" not in out.columns
            else f"no contact flag in {len(no_signal)} trial(s)"
            if keys is not None
            else "no contact flag"
        )
        raise DataFormatError(
            f"{source}: {what} and no contact height: give the height of the touched "
            f"surface (--contact-height M, in m, y up) or a contact channel"
        )
    pos_y = _positions(out, source, first_line)[:, 1]
    if "contact" not in out.columns:
        out["contact"] = np.nan
    # keep the column's values (a text cell that is no number stays for skilllib.recordings to report)
    filled = out["contact"].to_numpy(
        dtype=float if pd.api.types.is_numeric_dtype(out["contact"]) else object, copy=True
    )
    for k in no_signal:
        r = np.asarray(rows[k])
        filled[r] = contact_from_height(pos_y[r], float(contact_height))
    out["contact"] = filled
    return out
