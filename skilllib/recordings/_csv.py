"""A CSV file as a table of text cells, with the physical line of every row, as pandas reads it.

The first step of reading recordings (:func:`skilllib.recordings.read_recordings`): nothing is converted here,
so that identifiers stay text exactly as written, and line numbers count physical lines of the file (a
quoted cell spanning lines counts all of them), so that a message names the line an editor shows.
Compressed files are opened as pandas opens them (``.gz``, ``.bz2``, ``.zip``, ``.xz``, ``.zst``).
A row with more or fewer fields than the header is refused (:func:`check_alignment`), never shifted: a
trailing comma on every line, the header's included, lines up; on the data rows only, the message says
to remove it (dropping an extra last field would guess which name is missing).

**Separator.** A comma, a tab or a semicolon (:data:`SEPARATORS`), given (``--sep``, :func:`parse_sep`)
or detected (:func:`detect_sep`): the one that splits the header line into more than one field and
every one of the next lines (up to :data:`SNIFF_LINES`) into as many; of several, the one giving the
most fields; of none, the one splitting the header most (then :func:`check_alignment` names the first
line that does not line up). Every message that lists columns says how the line was split
(:func:`columns_found`); the table's ``attrs["sep"]`` keeps the separator for those messages.
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

#: The separators of a delimited table and how a message says a line was split at them.
SEPARATORS: dict[str, str] = {",": "commas", "\t": "tabs", ";": "semicolons"}
_SEP_NAMES = {",": ",", "comma": ",", "\t": "\t", "\\t": "\t", "tab": "\t", ";": ";", "semicolon": ";"}
SNIFF_LINES = 20  #: lines after the header that must split like it for a separator to be detected


def parse_sep(sep: str | None) -> str | None:
    """The separator character of a ``--sep`` value: ``,``, ``;``, ``tab`` or ``\\t`` (a tab also as itself).

    Parameters
    ----------
    sep : str or None
        The option's value (text; ``comma`` and ``semicolon`` are accepted too); None: detect it.

    Returns
    -------
    str or None
        ``","``, ``"\\t"`` or ``";"`` (text), or None when ``sep`` is None.

    Raises
    ------
    DataFormatError
        For any other value.
    """
    if sep is None:
        return None
    key = sep if sep == "\t" else str(sep).strip().lower()
    if key not in _SEP_NAMES:
        raise DataFormatError(f"--sep: unknown separator {sep!r} (known: ',', ';', 'tab')")
    return _SEP_NAMES[key]


def split_words(sep: str | None) -> str:
    """How a message says a line was split: ``"split at tabs"`` (``""`` for an unknown separator)."""
    return f"split at {SEPARATORS[sep]}" if sep in SEPARATORS else ""


def columns_found(columns: object, sep: str | None) -> str:
    """``"columns found (split at tabs): a, b, c"``; ``"columns: a, b, c"`` when ``sep`` is None.

    Parameters
    ----------
    columns : iterable
        The column names (text).
    sep : str or None
        The separator the line was split at (text), or None (a DataFrame given through the API).

    Returns
    -------
    str
        The phrase for a message (text).
    """
    names = ", ".join(str(c) for c in columns)
    how = split_words(sep)
    return f"columns found ({how}): {names}" if how else f"columns: {names}"


def detect_sep(text: str) -> str:
    """The separator of a delimited table's text, by the rule of the module docstring.

    Parameters
    ----------
    text : str
        The file's text, or its beginning (text).

    Returns
    -------
    str
        ``","``, ``"\\t"`` or ``";"`` (text).
    """
    lines = [line.rstrip("\r") for line in text.split("\n", SNIFF_LINES + 1)[: SNIFF_LINES + 1]]
    if len(lines) > SNIFF_LINES:  # the last piece holds the rest of the text (a line perhaps cut): not looked at
        lines = lines[:SNIFF_LINES]
    lines = [lines[0]] + [line for line in lines[1:] if line.strip()]
    best, best_n, fallback, fallback_n = None, 1, ",", 1
    for sep in SEPARATORS:
        try:
            rows = list(csv.reader(io.StringIO("\n".join(lines)), delimiter=sep, skipinitialspace=True))
        except csv.Error:
            continue
        if not rows:
            continue
        n = len(rows[0])
        if n > fallback_n:
            fallback, fallback_n = sep, n
        if n > best_n and all(len(r) == n for r in rows[1:] if r):
            best, best_n = sep, n
    return best if best is not None else fallback


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


def _record_widths(text: str, sep: str = ",") -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Fields of each record of a CSV text (header first), the record's first physical line, and the
    header's cells. Blank records (only spaces) count 0 fields. Counted as pandas reads (separator
    ``sep``, quotes, spaces after a separator skipped)."""
    if '"' in text:
        reader = csv.reader(io.StringIO(text), delimiter=sep, skipinitialspace=True)
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
    commas = np.flatnonzero(raw == ord(sep))
    widths = np.searchsorted(commas, ends) - np.searchsorted(commas, begins) + 1
    lines = text.split("\n", 1)
    header = lines[0].split(sep)
    one = np.flatnonzero(widths == 1)
    if widths[0] == 1 and raw[: ends[0]].tobytes().strip():  # one column: blank lines line up anyway
        one = one[:0]
    for i in one:  # blank lines (rare): 0 fields
        if not raw[begins[i] : ends[i]].tobytes().strip():
            widths[i] = 0
    return widths, np.arange(1, len(widths) + 1), header


def _last_cells_empty(text: str, rows: np.ndarray, sep: str = ",") -> bool:
    """Whether the last field of every record ``rows`` (indices after the header) is empty."""
    if '"' in text:
        records = [cells for cells in csv.reader(io.StringIO(text), delimiter=sep, skipinitialspace=True)]
        return all(not records[i][-1].strip() for i in rows)
    lines = text.split("\n")
    return all(lines[i].rstrip("\r\n ").endswith(sep) for i in rows)


def check_alignment(path: Path, text: str, sep: str = ",") -> str:
    """DataFormatError unless every record of the CSV ``text`` has as many fields as its header (blank
    lines aside); the message names the first other line, both counts, and the fix of a trailing comma
    on the header only. A trailing comma on every line, the header's included, lines up (pandas names
    that empty column ``Unnamed: k``; it is not one the recordings use). When every data row has one field
    more than the header and that field is empty on every row (a separator at the end of each data row,
    as some exporters write), the rows line up once it is dropped: the note returned says so, and the
    caller drops it (:func:`drop_trailing_separators`). Fields are split at ``sep`` (``","``, ``"\\t"`` or
    ``";"``); a message about another separator says so. Returns the note ('' when the rows line up)."""
    widths, lines, header = _record_widths(text, sep)
    if len(widths) < 2 or widths[0] == 0:  # a header alone, or blank lines before it: read_csv says so
        return
    h = int(widths[0])
    rows = np.flatnonzero(widths[1:] > 0) + 1
    bad = rows[widths[rows] != h]
    if not len(bad):
        return ""
    first, w = int(bad[0]), int(widths[bad[0]])
    # pandas' own words for a row too long (kept: the message users and tests know), for short rows too
    how = "" if sep == "," else f" ({split_words(sep)})"
    where = f"{path}: not a valid CSV table: Expected {h} fields in line {lines[first]}, saw {w}{how}"
    mark = {",": "comma", "\t": "tab", ";": "semicolon"}.get(sep, "separator")
    if len(bad) == len(rows) and np.all(widths[rows] == h + 1) and _last_cells_empty(text, rows, sep):
        return f"every data row ends with a {mark} the header lacks: the empty last field is ignored"
    if len(bad) == len(rows) and np.all(widths[rows] == h - 1) and not header[-1].strip():
        raise DataFormatError(
            f"{where}: the header ends with a separator the data rows lack: remove the trailing {mark} from line 1"
        )
    raise DataFormatError(where)


def drop_trailing_separators(text: str, sep: str) -> str:
    """``text`` without the one separator at the end of each line after the header that ends with one
    (:func:`check_alignment` found that every data row has such an empty last field). Line numbers are
    unchanged.

    Parameters
    ----------
    text : str
        The file's text.
    sep : str
        The separator (text).

    Returns
    -------
    str
        The text with the data rows' trailing separator removed.
    """
    head, _, body = text.partition("\n")
    out = [
        ln[: -len(sep)] if ln.rstrip("\r").endswith(sep) and not ln.endswith("\r") else ln for ln in body.split("\n")
    ]
    out = [ln[: -len(sep) - 1] + "\r" if ln.endswith(sep + "\r") else ln for ln in out]
    return head + "\n" + "\n".join(out)


def read_table(path: str | Path, sep: str | None = None) -> tuple[pd.DataFrame, np.ndarray]:
    """A delimited text file as a table of text cells and the physical line of each row.

    Nothing is converted; blank lines are kept as empty rows. The separator is ``sep`` or detected
    (module docstring) and kept in the table's ``attrs["sep"]``.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV (or tab- or semicolon-separated) file (text).
    sep : str or None
        The separator (text: ``","``, ``"\\t"``, ``";"``, or ``"tab"``, as :func:`parse_sep` takes it); None:
        detected.

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
    sep = parse_sep(sep) or detect_sep(text)
    note = check_alignment(path, text, sep)
    if note:
        text = drop_trailing_separators(text, sep)
    try:
        df = pd.read_csv(
            io.StringIO(text),
            sep=sep,
            dtype=str,
            keep_default_na=False,
            skip_blank_lines=False,
            skipinitialspace=True,
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
    df.attrs["sep"] = sep
    df.attrs["notes"] = [f"{path}: {note}"] if note else []
    return df, lines


def text_head(path: Path, size: int = 1 << 16) -> str:
    """The first ``size`` characters of a (perhaps compressed) text file, '' when it cannot be read as text."""
    from pandas.io.common import get_handle

    try:
        with get_handle(path, "r", encoding="utf-8-sig", compression="infer") as h:
            return h.handle.read(size)
    except (OSError, EOFError, ValueError, UnicodeDecodeError, ImportError):
        return ""


def file_sep(path: str | Path, sep: str | None = None) -> str:
    """The separator of a delimited file: ``sep`` (as :func:`parse_sep` takes it), else detected from its
    first lines (module docstring); ``","`` when the file cannot be read (the reader then says why).

    Parameters
    ----------
    path : str or pathlib.Path
        The file (text; compressed as pandas infers from the name).
    sep : str or None
        The separator given (text), or None: detect it.

    Returns
    -------
    str
        ``","``, ``"\\t"`` or ``";"`` (text).
    """
    given = parse_sep(sep)
    if given is not None:
        return given
    head = text_head(Path(path))
    return detect_sep(head) if head.strip() else ","


def file_stem_any(path: str | Path) -> str:
    """A file's name without a compression suffix and then its extension: ``walk.tsv.gz`` -> ``walk``."""
    name = Path(path).name
    for suffix in COMPRESSED:
        if name.lower().endswith(suffix):
            name = name[: -len(suffix)]
            break
    return name.rsplit(".", 1)[0] if "." in name.lstrip(".") else name


def file_ids(path: str | Path) -> tuple[str, str]:
    """(participant, trial) of a one-recording file, from its name as a single C3D file is named.

    The stem (the name without its extension and a compression suffix) split at its **last** ``_``
    (``kinesis_rtgData.txt``: participant ``kinesis``, trial ``rtgData``); a stem without ``_`` is
    participant and trial both.

    Parameters
    ----------
    path : str or pathlib.Path
        The file (text).

    Returns
    -------
    participant, trial : str
        The ids (text).
    """
    stem = file_stem_any(path)
    participant, us, trial = stem.rpartition("_")
    if not us or not participant or not trial:
        return stem, stem
    return participant, trial


def has_ids(columns: object) -> bool:
    """Whether a table's columns (text) name a participant or a trial (case and spaces ignored): a table
    without either is one recording (:func:`with_file_ids`)."""
    return any(str(c).strip().lower() in ("participant", "trial") for c in columns)


def with_file_ids(df: pd.DataFrame, path: str | Path) -> pd.DataFrame:
    """``df`` with ``participant`` and ``trial`` columns from the file's name (:func:`file_ids`) when it has
    neither (:func:`has_ids`) but has ``t, x, y, z``: the table is one recording. Blank rows (every cell
    empty) keep empty ids
    (NaN), so that they stay blank lines. Other tables are returned as they are.

    Parameters
    ----------
    df : pandas.DataFrame
        The table (text or numbers, as read).
    path : str or pathlib.Path
        The file it was read from (text).

    Returns
    -------
    pandas.DataFrame
        The table with the id columns first (text).
    """
    have = {str(c).strip() for c in df.columns}
    if has_ids(df.columns) or not {"t", "x", "y", "z"} <= have:  # not a recording: the checks say what lacks
        return df
    participant, trial = file_ids(path)
    blank = np.ones(len(df), dtype=bool)
    for c in df.columns:
        col = df[c]
        empty = col.isna().to_numpy(dtype=bool, copy=True)
        if col.dtype == object or pd.api.types.is_string_dtype(col):
            empty |= (col.astype("string").str.strip() == "").fillna(True).to_numpy(dtype=bool)
        blank &= empty
    out = df.copy()
    for name, value in (("trial", trial), ("participant", participant)):
        col = np.full(len(df), value, dtype=object)
        col[blank] = np.nan
        out.insert(0, name, col)
    out.attrs.update(df.attrs)
    return out


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
    path: str | Path,
    text_columns: tuple[str, ...],
    number_columns: tuple[str, ...],
    na_text: frozenset[str],
    sep: str | None = None,
) -> pd.DataFrame | None:
    """The columns of a plain CSV file (one record per line, no blank line), read by pyarrow's
    multi-threaded CSV reader: ``text_columns`` as text exactly as written, ``number_columns`` as float64
    (``na_text`` cells
    as NaN). None when the file is compressed, not plain, lacks one of the columns, or any cell does not
    parse, or a record is not one line (blank lines, line breaks inside quotes): the caller then reads it
    with :func:`read_table`, whose messages name the line and column.
    The rows are the file's lines 2, 3, ... in order; fields are split at ``sep`` (None: detected, as
    :func:`read_table` does), kept in the table's ``attrs["sep"]``."""
    import pyarrow as pa
    import pyarrow.csv as pacsv

    path = Path(path)
    if path.suffix.lower() in COMPRESSED or not path.is_file():
        return None
    sep = file_sep(path, sep)
    with open(path, "rb") as f:
        header = f.readline().decode("utf-8-sig", errors="replace").rstrip("\r\n").split(sep)
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
            parse_options=pacsv.ParseOptions(delimiter=sep, newlines_in_values=False),
            convert_options=convert,
        ) as reader:
            # None when the rows are not the lines: a blank line (pyarrow skips it) would shift line numbers
            out = frame_from_batches(reader, n_rows, text_columns, number_columns)
    except (pa.ArrowInvalid, pa.ArrowTypeError, UnicodeDecodeError, OSError):
        return None
    if out is not None:
        out.attrs["sep"] = sep
    return out
