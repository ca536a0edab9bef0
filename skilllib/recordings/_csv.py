"""A CSV file as a table of text cells, with the physical line of every row, as pandas reads it.

The first step of reading recordings (:func:`skilllib.recordings.read_recordings`): nothing is converted here,
so that identifiers stay text exactly as written, and line numbers count physical lines of the file (a
quoted cell spanning lines counts all of them), so that a message names the line an editor shows.
Compressed files are opened as pandas opens them (``.gz``, ``.bz2``, ``.zip``, ``.xz``, ``.zst``).
A row with more or fewer fields than the header is refused (:func:`check_alignment`), never shifted: a
trailing comma on every line, the header's included, lines up; on the data rows only, the message says
to remove it (dropping an extra last field would guess which name is missing).
:class:`DataFormatError` is defined here and re-exported by :mod:`skilllib.recordings`.
"""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path

import numpy as np
import pandas as pd

from ._errors import DataFormatError, check_file


def _read_text(path: Path) -> str:
    """The file's text, decompressed as pandas infers from the extension; DataFormatError when missing,
    a folder, or not UTF-8 text."""
    from pandas.io.common import get_handle  # how read_csv opens (and decompresses) a path

    check_file(path, "CSV")
    try:
        with get_handle(path, "r", encoding="utf-8-sig", compression="infer") as h:
            return h.handle.read()
    except UnicodeDecodeError:
        raise DataFormatError(
            f"{path}: not a text (UTF-8) CSV file (compressed files need their extension: .gz, .bz2, .zip, .xz, .zst)"
        ) from None
    except (OSError, EOFError, ValueError) as e:  # a damaged archive
        raise DataFormatError(f"{path}: cannot be decompressed: {e}") from None


def record_lines(text: str) -> np.ndarray:
    """1-based physical line of each record of a CSV text after its header.

    Blank lines are included as records (as ``read_csv(skip_blank_lines=False)`` keeps them): a quoted
    cell spanning lines counts them.

    Parameters
    ----------
    text : str
        The CSV file's text (text).

    Returns
    -------
    numpy.ndarray of int
        The physical line of each record (dimensionless).
    """
    if '"' not in text:  # one record per line
        n = text.count("\n") + (0 if text.endswith("\n") else 1)
        return np.arange(2, n + 1)
    reader = csv.reader(io.StringIO(text))
    starts, end = [], 0
    for _ in reader:
        starts.append(end + 1)
        end = reader.line_num
    return np.asarray(starts[1:], dtype=np.int64)


def _is_blank(cells: list[str]) -> bool:
    return len(cells) <= 1 and not "".join(cells).strip()


def _record_widths(text: str) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Fields of each record of a CSV text (header first), the record's first physical line, and the
    header's cells. Blank records (only spaces) count 0 fields. Counted as pandas reads (separator ',',
    quotes, spaces after a separator skipped)."""
    if '"' in text:
        reader = csv.reader(io.StringIO(text), skipinitialspace=True)
        widths, starts, end, header = [], [], 0, []
        for cells in reader:
            header = header or cells
            widths.append(0 if _is_blank(cells) else len(cells))
            starts.append(end + 1)
            end = reader.line_num
        return np.asarray(widths, dtype=np.int64), np.asarray(starts, dtype=np.int64), header
    raw = np.frombuffer(text.encode("utf-8"), dtype=np.uint8)
    ends = np.flatnonzero(raw == ord("\n"))
    if len(raw) and raw[-1] != ord("\n"):
        ends = np.append(ends, len(raw))
    begins = np.concatenate(([0], ends[:-1] + 1))
    commas = np.flatnonzero(raw == ord(","))
    widths = np.searchsorted(commas, ends) - np.searchsorted(commas, begins) + 1
    lines = text.split("\n", 1)
    header = lines[0].split(",")
    one = np.flatnonzero(widths == 1)
    if widths[0] == 1 and raw[: ends[0]].tobytes().strip():  # one column: blank lines line up anyway
        one = one[:0]
    for i in one:  # blank lines (rare): 0 fields
        if not raw[begins[i] : ends[i]].tobytes().strip():
            widths[i] = 0
    return widths, np.arange(1, len(widths) + 1), header


def _last_cells_empty(text: str, rows: np.ndarray) -> bool:
    """Whether the last field of every record ``rows`` (indices after the header) is empty."""
    if '"' in text:
        records = [cells for cells in csv.reader(io.StringIO(text), skipinitialspace=True)]
        return all(not records[i][-1].strip() for i in rows)
    lines = text.split("\n")
    return all(lines[i].rstrip().endswith(",") for i in rows)


def check_alignment(path: Path, text: str) -> None:
    """DataFormatError unless every record of the CSV ``text`` has as many fields as its header (blank
    lines aside); the message names the first other line, both counts, and the fix of a trailing comma
    on the data rows only or on the header only. A trailing comma on every line, the header's included,
    lines up (pandas names that empty column ``Unnamed: k``; it is not one the recordings use)."""
    widths, lines, header = _record_widths(text)
    if len(widths) < 2 or widths[0] == 0:  # a header alone, or blank lines before it: read_csv says so
        return
    h = int(widths[0])
    rows = np.flatnonzero(widths[1:] > 0) + 1
    bad = rows[widths[rows] != h]
    if not len(bad):
        return
    first, w = int(bad[0]), int(widths[bad[0]])
    # pandas' own words for a row too long (kept: the message users and tests know), for short rows too
    where = f"{path}: not a valid CSV table: Expected {h} fields in line {lines[first]}, saw {w}"
    if len(bad) == len(rows) and np.all(widths[rows] == h + 1) and _last_cells_empty(text, rows):
        raise DataFormatError(
            f"{where}: every data row ends with a separator the header lacks, which would shift the columns: "
            "remove the trailing comma from the data rows (or add one to the header)"
        )
    if len(bad) == len(rows) and np.all(widths[rows] == h - 1) and not header[-1].strip():
        raise DataFormatError(
            f"{where}: the header ends with a separator the data rows lack: remove the trailing comma from line 1"
        )
    raise DataFormatError(where)


def read_table(path: str | Path) -> tuple[pd.DataFrame, np.ndarray]:
    """A CSV file as a table of text cells and the physical line of each row.

    Nothing is converted; blank lines are kept as empty rows.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file (text).

    Returns
    -------
    table : pandas.DataFrame
        The cells (text).
    lines : numpy.ndarray of int
        The 1-based physical line of each row (dimensionless).

    Raises
    ------
    DataFormatError
        For a missing, empty, binary or malformed file.
    """
    path = Path(path)
    text = _read_text(path)
    if not text.strip():
        raise DataFormatError(f"{path}: file is empty")
    check_alignment(path, text)
    try:
        df = pd.read_csv(
            io.StringIO(text), dtype=str, keep_default_na=False, skip_blank_lines=False, skipinitialspace=True
        )
    except pd.errors.ParserError as e:  # e.g. "Expected 7 fields in line 12, saw 8"
        msg = str(e).replace("Error tokenizing data. C error: ", "").strip()
        m = re.search(r"in line (\d+)", msg)
        if m and '"' in text:  # the parser counts records; name the physical line
            lines = record_lines(text)
            rec = int(m.group(1)) - 2
            if 0 <= rec < len(lines):
                msg = msg.replace(m.group(0), f"in line {lines[rec]}")
        raise DataFormatError(f"{path}: not a valid CSV table: {msg}") from None
    except pd.errors.EmptyDataError:  # text is not blank (checked above): a blank line before the header
        raise DataFormatError(
            f"{path}: no column names on line 1: the header must be the first line, not after blank lines"
        ) from None
    lines = record_lines(text)[: len(df)]
    return df, lines


#: Extensions pandas decompresses; :func:`read_plain` leaves such files to :func:`read_table`.
COMPRESSED = (".gz", ".bz2", ".zip", ".xz", ".zst", ".tar")
_SCAN_BLOCK = 1 << 24  #: bytes read at a time when counting a file's lines


def _count_lines(path: Path) -> int:
    """Lines of the file (a last line without a line break counts)."""
    n, last = 0, b"\n"
    with open(path, "rb") as f:
        while block := f.read(_SCAN_BLOCK):
            n += block.count(b"\n")
            last = block[-1:]
    return n + (last != b"\n")


def read_plain(
    path: str | Path, text_columns: tuple[str, ...], number_columns: tuple[str, ...], na_text: frozenset[str]
) -> pd.DataFrame | None:
    """The columns of a plain CSV file (one record per line, no blank line), read by pyarrow's
    multi-threaded CSV reader: ``text_columns`` as text exactly as written, ``number_columns`` as float64
    (``na_text`` cells
    as NaN). None when the file is compressed, not plain, lacks one of the columns, or any cell does not
    parse, or a record is not one line (blank lines, line breaks inside quotes): the caller then reads it
    with :func:`read_table`, whose messages name the line and column.
    The rows are the file's lines 2, 3, ... in order."""
    import pyarrow as pa
    import pyarrow.csv as pacsv

    path = Path(path)
    if path.suffix.lower() in COMPRESSED or not path.is_file():
        return None
    with open(path, "rb") as f:
        header = f.readline().decode("utf-8-sig", errors="replace").rstrip("\r\n").split(",")
    wanted = (*text_columns, *number_columns)
    if len(set(header)) != len(header) or any(c not in header for c in wanted):
        return None
    types = {**{c: pa.string() for c in text_columns}, **{c: pa.float64() for c in number_columns}}
    convert = pacsv.ConvertOptions(
        column_types=types,
        include_columns=list(wanted),
        null_values=sorted(na_text),
        strings_can_be_null=False,
        quoted_strings_can_be_null=False,
    )
    n_rows = _count_lines(path) - 1
    if n_rows < 1:  # a header alone: read_table says so
        return None
    from ._parquet import frame_from_batches

    try:
        with pacsv.open_csv(
            path,
            read_options=pacsv.ReadOptions(block_size=1 << 23),
            parse_options=pacsv.ParseOptions(newlines_in_values=False),
            convert_options=convert,
        ) as reader:
            # None when the rows are not the lines: a blank line (pyarrow skips it) would shift line numbers
            return frame_from_batches(reader, n_rows, text_columns, number_columns)
    except (pa.ArrowInvalid, pa.ArrowTypeError, UnicodeDecodeError, OSError):
        return None
