"""Columnar data in: Apache Parquet files and folders of them, and Arrow record batches into the
recordings table without holding the numbers twice.

``--data`` may name a Parquet file or a folder of Parquet files (a partitioned dataset: ``part-0.parquet``,
``part-1.parquet``, ... read in natural order of their names) with the columns of the recordings format
(:mod:`skilllib.recordings`: ``participant, trial, t, x, y, z, contact``; other columns are ignored). The same
checks as for a CSV file follow (:func:`skilllib.recordings.recordings_from_frame`). Messages name the file
and the row within it (1-based), on one line.

**Datasets as tools write them.** The files of a folder may come from different tools:

* ids are unified to text whatever their type in each file (integers of any width, text, large text,
  dictionary-encoded, floats): an integer ``1`` is ``"1"``, an integer-valued float ``1.0`` too, the rule of
  ids given through the API (:func:`_id_text`), so a file of integer ids and one of text ids give the same
  trials;
* number columns may be integers in one file and floats (or booleans, decimals) in another; a column that
  is numbers in one file and text (or a date, ...) in another cannot be unified and is refused naming the
  file and the column, as is a file that lacks a column;
* a folder is a Parquet dataset when it holds Parquet files and no more files of other recording kinds
  (C3D, TRC, CSV, ..., also in its sub-folders) than Parquet files; what is not a Parquet file is skipped
  and said (``(path, reason)``: hidden files and AppleDouble ``._name`` files, ``_SUCCESS`` and
  ``_metadata`` as Spark and Dask write them, sub-folders, a stray CSV);
* a damaged file (a truncated file, a corrupt page, checksums that do not match when the writer wrote
  them) is one line naming it.

A trial whose rows lie in two files has rows that are not contiguous and is invalid with that reason.
"""

from __future__ import annotations

import bisect
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ._columns import ID_COLUMNS, POSITION_COLUMNS
from ._errors import DataFormatError

PARQUET_SUFFIXES = (".parquet",)  #: the file names read as Parquet (case ignored)
#: names of the files of other recording kinds (case ignored), counted to tell a Parquet dataset from a folder of trials
OTHER_SUFFIXES = (".c3d", ".trc", ".csv", ".tsv", ".txt", ".gz", ".zip", ".bz2", ".xz", ".zst")


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


def _skip_reason(p: Path) -> str | None:
    """Why the entry ``p`` of a Parquet dataset folder is not read (text), or None for a Parquet file."""
    name = p.name
    if name.startswith("._"):
        return "an AppleDouble file (macOS metadata), not data"
    if name.startswith("."):
        return f"a hidden {'folder' if p.is_dir() else 'file'}"
    if name.startswith("_"):
        return "dataset metadata (a name starting with '_', as Spark and Dask write), not data"
    if p.is_dir():
        return "a folder inside a Parquet dataset (only the dataset folder's own files are read)"
    if not name.lower().endswith(PARQUET_SUFFIXES):
        return "not a Parquet file in a Parquet dataset"
    if not p.is_file():
        return "not a regular file (a device, pipe or socket)"
    return None


def dataset_files(
    path: str | Path, name_key: Callable[[str], object] = str
) -> tuple[list[Path], list[tuple[Path, str]]]:
    """The Parquet files of a file or folder in order, and the entries of the folder that are skipped.

    Parameters
    ----------
    path : str or pathlib.Path
        The Parquet file or folder (text).
    name_key : callable
        Sort key of a file name (text), e.g. :func:`natural_key`.

    Returns
    -------
    files : list of pathlib.Path
        The Parquet files, ordered by ``name_key`` of their names (the path itself for a file).
    skipped : list of (pathlib.Path, str)
        The folder's other entries and why each is not read (text): hidden, AppleDouble, metadata, a
        sub-folder, not a Parquet file.
    """
    path = Path(path)
    if not path.is_dir():
        return [path], []
    files, skipped = [], []
    for p in sorted(path.iterdir(), key=lambda p: name_key(p.name)):
        reason = _skip_reason(p)
        if reason is None:
            files.append(p)
        else:
            skipped.append((p, reason))
    return files, skipped


def skipped_notes(skipped: Iterable[tuple[Path, str]]) -> tuple[str, ...]:
    """The notes saying the skipped entries of a dataset: ``"stray.csv: skipped: not a Parquet file in a
    Parquet dataset"``.

    Parameters
    ----------
    skipped : iterable of (pathlib.Path, str)
        The entries and their reasons (text), as :func:`dataset_files` gives them.

    Returns
    -------
    tuple of str
        One note per entry, naming it (text).
    """
    return tuple(f"{Path(p).name}: skipped: {reason}" for p, reason in skipped)


def with_skipped(rec: Any, skipped: Iterable[tuple[Path, str]]) -> Any:
    """``rec`` (a :class:`~skilllib.recordings.Recordings`) with the skipped entries of its Parquet dataset
    said in its ``notes`` (:func:`skipped_notes`). Not in its ``skipped`` field: that one is a folder of
    trial files' (one file per trial, counted as files by the run), and a Parquet file holds many trials.

    Parameters
    ----------
    rec : Recordings
        The recordings read (t in s, positions in m).
    skipped : iterable of (pathlib.Path, str)
        The entries skipped and their reasons (text).

    Returns
    -------
    Recordings
        The same recordings with the skipped entries said.
    """
    import dataclasses

    notes = skipped_notes(skipped)
    return dataclasses.replace(rec, notes=tuple(rec.notes) + notes) if notes else rec


def parquet_files(path: Path, name_key: Callable[[str], object] = str, skipped: list | None = None) -> list[Path]:
    """The Parquet file, or the folder's Parquet files ordered by ``name_key`` of their names.

    Hidden files, AppleDouble ``._name`` files, ``_name`` metadata, sub-folders and files of other kinds
    are not read (:func:`dataset_files`).

    Parameters
    ----------
    path : pathlib.Path
        The file or folder (text).
    name_key : callable
        Sort key of a file name (text), e.g. :func:`natural_key`.
    skipped : list or None
        When a list, the entries not read are appended to it as ``(path, reason)`` (text).

    Returns
    -------
    list of pathlib.Path
        The Parquet files in order.
    """
    files, left = dataset_files(path, name_key)
    if skipped is not None:
        skipped.extend(left)
    return files


def _is_other_recording(p: Path) -> bool:
    name = p.name.lower()
    return p.is_file() and not name.startswith((".", "_")) and name.endswith(OTHER_SUFFIXES)


def is_parquet(path: str | Path) -> bool:
    """A ``.parquet`` file, or a folder holding Parquet files and no more files of other recording kinds
    (C3D, TRC, CSV, ...; its sub-folders' too) than Parquet files: those are skipped and said.

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
    if not path.is_dir():
        return path.suffix.lower() in PARQUET_SUFFIXES
    files, skipped = dataset_files(path)
    if not files:
        return False
    others = 0
    for p, _ in skipped:
        if p.is_dir() and not p.name.startswith((".", "_")):
            others += sum(_is_other_recording(q) for q in p.iterdir())
        else:
            others += _is_other_recording(p)
    return len(files) >= others


def _one_line(e: BaseException) -> str:
    """An exception's message on one line of printable text, cut to 200 characters."""
    text = "".join(ch if ch.isprintable() else " " for ch in str(e))
    text = " ".join(text.split()) or type(e).__name__
    return text if len(text) <= 200 else text[:200] + "..."


def _id_cell(v: Any) -> str | None:
    """One id value as text, the rule of ids given through the API (``skilllib.recordings._id_text``
    without the stripping, done later): an integer-valued float without ``.0``; missing as None."""
    if v is None or isinstance(v, str):
        return v
    if isinstance(v, float):
        if np.isnan(v):
            return None
        return str(int(v)) if v.is_integer() else str(v)
    return str(v)


def id_text(arr: Any) -> Any:
    """An Arrow array of ids (any type: integers, text, large text, dictionary-encoded, floats) as an
    Arrow ``string`` array, the same text whatever the type: ``1``, ``"1"`` and ``1.0`` are ``"1"``.

    Parameters
    ----------
    arr : pyarrow.Array
        The ids (text or numbers, dimensionless).

    Returns
    -------
    pyarrow.Array
        The ids as text (nulls stay null).
    """
    import pyarrow as pa
    import pyarrow.compute as pc

    t = arr.type
    if pa.types.is_dictionary(t):
        return id_text(arr.dictionary_decode())
    if t == pa.string():
        return arr
    if pa.types.is_string(t) or pa.types.is_large_string(t) or pa.types.is_integer(t) or pa.types.is_null(t):
        return arr.cast(pa.string())  # an integer's digits, as str(int)
    if getattr(pa.types, "is_string_view", lambda _: False)(t):
        return arr.cast(pa.string())
    enc = pc.dictionary_encode(arr)  # floats, booleans, decimals, ...: each distinct value once
    texts = pa.array([_id_cell(v) for v in enc.dictionary.to_pylist()], type=pa.string())
    return pc.take(texts, enc.indices)


def _kind(t: Any, is_id: bool) -> str:
    """How a column of Arrow type ``t`` is unified across files: ``"ids"`` (to text), ``"numbers"`` (to
    float64), ``"text"`` (to string, converted by the validation), ``"null"`` (any), or the type itself."""
    import pyarrow as pa

    if pa.types.is_dictionary(t):
        t = t.value_type
    if pa.types.is_null(t):
        return "null"
    if is_id:
        nested = pa.types.is_nested(t)
        return str(t) if nested else "ids"
    if pa.types.is_integer(t) or pa.types.is_floating(t) or pa.types.is_boolean(t) or pa.types.is_decimal(t):
        return "numbers"
    if pa.types.is_string(t) or pa.types.is_large_string(t) or getattr(pa.types, "is_string_view", lambda _: False)(t):
        return "text"
    return str(t)


def _unified(col: Any, kind: str | None) -> Any:
    """A number column of one batch as its dataset's ``kind`` wants it: float64 numbers, or string text."""
    import pyarrow as pa

    if pa.types.is_dictionary(col.type):
        col = col.dictionary_decode()
    t = col.type
    if kind in ("numbers", None) and not (pa.types.is_floating(t) or pa.types.is_integer(t)):
        return col.cast(pa.float64())  # booleans (contact), decimals, an all-null column: numbers
    if kind == "text" and t != pa.string():
        return col.cast(pa.string())
    return col


def read_parquet(
    path: str | Path,
    columns: tuple[str, ...],
    name_key: Callable[[str], object] = str,
    *,
    renames: Mapping[str, str] | None = None,
    optional: tuple[str, ...] = (),
) -> tuple[pd.DataFrame, Callable[[int], str]]:
    """The recordings columns of a Parquet file or folder, and a function naming row r.

    Row r is 0-based, of all files in order, named as ``"part-3.parquet, row 12"``. Ids are text
    (:func:`id_text`), number columns float64 (or text for the validation to convert and check, when a file
    stores them as text); the files' types are unified as the module docstring says. The entries of a folder
    that are not read are in the frame's ``attrs["skipped"]`` as ``(path, reason)``.

    Parameters
    ----------
    path : str or pathlib.Path
        The Parquet file or folder (text).
    columns : tuple of str
        The columns to read (text).
    name_key : callable
        Sort key of the file names of a folder (text).
    renames : mapping of str to str or None
        Column renames ``{old: new}`` (text, as ``--columns``): column ``new`` is read from the files'
        column ``old``; None: none.
    optional : tuple of str
        Columns of ``columns`` that may be missing from every file (text; e.g. ``contact`` when a contact
        height gives it): then absent from the frame.

    Returns
    -------
    frame : pandas.DataFrame
        The columns read, files concatenated in order (t in s, positions in m, as in the files).
    place : callable
        Row (0-based) to its file and row (text).

    Raises
    ------
    DataFormatError
        One line naming the file when it cannot be read (damaged, truncated), lacks a column, or stores a
        column in a type the other files' cannot be unified with.
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    path = Path(path)
    files, skipped = dataset_files(path, name_key)
    if not files:
        raise DataFormatError(f"{path}: no Parquet files in this folder")
    renames = dict(renames or {})
    handles, sizes = [], []
    kinds: dict[str, tuple[str, Any, Path]] = {}
    present = set(columns)
    for f in files:
        try:
            pf = pq.ParquetFile(f, page_checksum_verification=True)
            schema = pf.schema_arrow
        except (OSError, ValueError, pa.ArrowException) as e:
            raise DataFormatError(f"{f}: not a readable Parquet file ({_one_line(e)})") from None
        names = schema.names
        unknown = [old for old in renames if old not in names]
        if unknown:
            raise DataFormatError(
                f"{f}: --columns names column {unknown[0]!r}, which the file does not have (found: {', '.join(names)})"
            )
        after = [renames.get(n, n) for n in names]
        source = {new: old for old, new in zip(names, after)}
        dup = sorted({n for n in after if n in columns and after.count(n) > 1})
        if dup:
            raise DataFormatError(
                f"{f}: column {dup[0]!r} would appear twice after --columns (found: {', '.join(names)})"
            )
        missing = [c for c in columns if c not in source and c not in optional]
        if missing:
            raise DataFormatError(
                f"{f}: required column '{missing[0]}' missing (found: {', '.join(names)}; "
                f"expected: {', '.join(columns)})"
            )
        if f is not files[0] and present != {c for c in columns if c in source}:
            c = sorted(present ^ {c for c in columns if c in source})[0]
            raise DataFormatError(f"{f if c in present else files[0]}: column '{c}' missing (the other files have it)")
        present = {c for c in columns if c in source}
        for c in present:
            t = schema.field(source[c]).type
            kind = _kind(t, c in ID_COLUMNS)
            if kind == "null":
                continue
            first = kinds.setdefault(c, (kind, t, f))
            if first[0] != kind:
                raise DataFormatError(
                    f"{f}: column '{c}' is {t} here but {first[1]} in {first[2].name}: the files of a Parquet "
                    f"dataset cannot be read together when a column holds numbers in one and not in another"
                )
            if kind not in ("ids", "numbers", "text"):
                raise DataFormatError(f"{f}: column '{c}' holds {t}, not {'ids' if c in ID_COLUMNS else 'numbers'}")
        handles.append((pf, {source[c]: c for c in present}))
        sizes.append(pf.metadata.num_rows)
    offsets = np.cumsum([0, *sizes]).tolist()
    wanted = tuple(c for c in columns if c in present)
    ids = tuple(c for c in wanted if c in ID_COLUMNS)
    numbers = tuple(c for c in wanted if c not in ids)

    def batches():
        for f, (pf, back), size in zip(files, handles, sizes):
            done = 0
            try:
                for b in pf.iter_batches(columns=list(back), batch_size=1 << 20):
                    cols = {back[n]: b.column(n) for n in back}
                    arrays = [id_text(cols[c]) for c in ids]
                    arrays += [_unified(cols[c], kinds.get(c, (None,))[0]) for c in numbers]
                    done += b.num_rows
                    yield pa.RecordBatch.from_arrays(arrays, names=[*ids, *numbers])
            except (OSError, ValueError, pa.ArrowException) as e:
                raise DataFormatError(f"{f}: cannot be read, damaged ({_one_line(e)})") from None
            if done != size:
                raise DataFormatError(f"{f}: holds {done} rows, its metadata says {size}: damaged")

    frame = frame_from_batches(batches(), offsets[-1], ids, numbers)
    if frame is None:
        raise DataFormatError(f"{path}: the files hold more rows than their metadata says: damaged")
    frame.attrs["skipped"] = skipped

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
