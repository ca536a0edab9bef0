"""The error a file that cannot be read raises, and how a message quotes a cell of it."""

from __future__ import annotations

from pathlib import Path
from typing import Any

MAX_QUOTE = 40  #: characters of a cell quoted in a message; longer cells are cut


class DataFormatError(ValueError):
    """The file cannot be read as recordings; the message names the file, line and column."""


def check_file(path: Path, kind: str) -> None:
    """:class:`DataFormatError` naming ``path`` when it does not exist or is a folder, not a ``kind``
    (``"CSV"``, ``"C3D"``, ``"TRC"``) file: the one check of an input path before any reader opens it."""
    if not path.exists():
        raise DataFormatError(f"{path}: file not found")
    if path.is_dir():
        raise DataFormatError(f"{path}: is a directory, not a {kind} file")
    if not path.is_file():  # a device (/dev/zero), a pipe or a socket: it may never end
        raise DataFormatError(f"{path}: is not a regular file (a device, pipe or socket), not a {kind} file")


def quote(text: Any) -> str:
    """A cell for a message: repr, cut to :data:`MAX_QUOTE` characters with its full length said.

    Parameters
    ----------
    text : Any
        The cell's value (text or any object; its repr is quoted).

    Returns
    -------
    str
        The quoted cell (text).
    """
    s = str(text)
    if len(s) <= MAX_QUOTE:
        return repr(s)
    return f"{s[:MAX_QUOTE]!r}... ({len(s):,} characters)"
