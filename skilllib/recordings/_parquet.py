"""Columnar data in: Apache Parquet files and folders of them, and Arrow record batches into the
recordings table without holding the numbers twice.

``--data`` may name a Parquet file or a folder of Parquet files (a partitioned dataset: ``part-0.parquet``,
``part-1.parquet``, ... read in natural order of their names) with the columns of the recordings format
(:mod:`skilllib.recordings`: ``participant, trial, t, x, y, z, contact``; other columns are ignored). The same
checks as for a CSV file follow (:func:`skilllib.recordings.recordings_from_frame`): ids are text (a Parquet
integer id ``1`` is the text ``"1"``), a column of text where numbers belong is converted and its first
cell that is not a number named, a trial whose rows lie in two files has rows that are not contiguous and
is invalid with that reason. Messages name the file and the row within it (1-based).
"""

from __future__ import annotations

import bisect
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np
import pandas as pd

from ._columns import ID_COLUMNS, POSITION_COLUMNS
from ._errors import DataFormatError


def frame_from_batches(
    batches: Iterable, n_rows: int, text_columns: tuple[str, ...], number_columns: tuple[str, ...]
) -> pd.DataFrame | None:
    """The columns of Arrow record ``batches`` (``n_rows`` rows in all) as a DataFrame: text columns
    as Arrow-backed Series; number columns of a numeric Arrow type filled batch by batch into
    preallocated float64 arrays (nulls as NaN; x, y, z as the columns of one (R, 3) array), of another
    type (text) kept as a Series for the validation to convert and check. None when the batches hold
    another number of rows than ``n_rows``."""
    import pyarrow as pa

    numbers: dict[str, np.ndarray] = {c: np.empty(n_rows) for c in number_columns}
    if all(c in number_columns for c in POSITION_COLUMNS):
        pos = np.empty((n_rows, 3))
        numbers.update({c: pos[:, j] for j, c in enumerate(POSITION_COLUMNS)})
    kept: dict[str, list] = {c: [] for c in text_columns}
    done = 0
    for batch in batches:
        k = batch.num_rows
        if done + k > n_rows:
            return None
        for c in number_columns:
            col = batch.column(c)
            numeric = pa.types.is_floating(col.type) or pa.types.is_integer(col.type)
            if c in numbers and numeric:
                numbers[c][done : done + k] = col.to_numpy(zero_copy_only=False)
            elif c in numbers and done == 0:  # text where numbers belong: checked by the validation
                del numbers[c]
                kept[c] = [col]
            elif c in kept:
                kept[c].append(col.cast(pa.string()) if numeric else col)
            else:
                raise DataFormatError(f"column '{c}' holds numbers in one file and {col.type} in another")
        for c in text_columns:
            kept[c].append(batch.column(c))
        done += k
    if done != n_rows:
        return None
    out = {
        c: pd.Series(pa.chunked_array(v).combine_chunks(), dtype=pd.ArrowDtype(v[0].type))
        if v
        else pd.Series([], dtype=object)
        for c, v in kept.items()
    }
    del kept
    out.update(numbers)
    release_arrow_memory()
    return pd.DataFrame(out, copy=False)


def parquet_files(path: Path, name_key: Callable[[str], object] = str) -> list[Path]:
    """The Parquet file, or the folder's ``*.parquet`` files ordered by ``name_key`` of their names.

    Parameters
    ----------
    path : pathlib.Path
        The file or folder (text).
    name_key : callable
        Sort key of a file name (text), e.g. :func:`natural_key`.

    Returns
    -------
    list of pathlib.Path
        The Parquet files in order.
    """
    if path.is_dir():
        return sorted(path.glob("*.parquet"), key=lambda p: name_key(p.name))
    return [path]


def is_parquet(path: str | Path) -> bool:
    """A ``.parquet`` file, or a folder whose files include Parquet files and no other recordings.

    Parameters
    ----------
    path : str or pathlib.Path
        The file or folder (text).

    Returns
    -------
    bool
        True when it is read as Parquet.
    """
    path = Path(path)
    if path.is_dir():
        names = [p.suffix.lower() for p in path.iterdir() if p.is_file() and not p.name.startswith(".")]
        return ".parquet" in names and not {".csv", ".c3d", ".trc", ".gz"} & set(names)
    return path.suffix.lower() == ".parquet"


def read_parquet(
    path: str | Path, columns: tuple[str, ...], name_key: Callable[[str], object] = str
) -> tuple[pd.DataFrame, Callable[[int], str]]:
    """The recordings columns of a Parquet file or folder, and a function naming row r.

    Row r is 0-based, of all files in order, named as ``"part-3.parquet, row 12"``.

    Parameters
    ----------
    path : str or pathlib.Path
        The Parquet file or folder (text).
    columns : tuple of str
        The columns to read (text).
    name_key : callable
        Sort key of the file names of a folder (text).

    Returns
    -------
    frame : pandas.DataFrame
        The columns read, files concatenated in order (t in s, positions in m).
    place : callable
        Row (0-based) to its file and row (text).

    Raises
    ------
    DataFormatError
        Naming the file when it cannot be read or lacks a column.
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    path = Path(path)
    files = parquet_files(path, name_key)
    if not files:
        raise DataFormatError(f"{path}: no Parquet files in this folder")
    handles, sizes = [], []
    for f in files:
        try:
            pf = pq.ParquetFile(f)
        except (OSError, pa.ArrowException) as e:
            raise DataFormatError(f"{f}: not a readable Parquet file ({e})") from None
        names = pf.schema_arrow.names
        missing = [c for c in columns if c not in names]
        if missing:
            raise DataFormatError(
                f"{f}: required column '{missing[0]}' missing (found: {', '.join(names)}; "
                f"expected: {', '.join(columns)})"
            )
        handles.append(pf)
        sizes.append(pf.metadata.num_rows)
    offsets = np.cumsum([0, *sizes]).tolist()
    ids = tuple(c for c in columns if c in ID_COLUMNS)
    numbers = tuple(c for c in columns if c not in ids)

    def batches():
        for f, pf in zip(files, handles):
            try:
                yield from pf.iter_batches(columns=list(columns), batch_size=1 << 20)
            except (OSError, pa.ArrowException) as e:
                raise DataFormatError(f"{f}: cannot be read ({e})") from None

    frame = frame_from_batches(batches(), offsets[-1], ids, numbers)
    if frame is None:
        raise DataFormatError(f"{path}: the files hold another number of rows than their metadata says")

    def place(r: int) -> str:
        k = bisect.bisect_right(offsets, r) - 1
        name = files[k].name if path.is_dir() else str(files[k])
        return f"{name}, row {r - offsets[k] + 1}"

    return frame, place


def release_arrow_memory() -> None:
    """Give the memory pyarrow's pool keeps after its arrays are freed back to the system (mimalloc keeps
    it for reuse otherwise: about 600 MB after reading a 430 MB file)."""
    import sys

    if "pyarrow" in sys.modules:
        sys.modules["pyarrow"].default_memory_pool().release_unused()
