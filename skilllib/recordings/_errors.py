"""The error a file that cannot be read raises, and how a message quotes a cell of it."""

from __future__ import annotations

from typing import Any

MAX_QUOTE = 40  #: characters of a cell quoted in a message; longer cells are cut


class DataFormatError(ValueError):
    """The file cannot be read as recordings; the message names the file, line and column."""


def quote(text: Any) -> str:
    """A cell for a message: repr, cut to :data:`MAX_QUOTE` characters with its full length said."""
    s = str(text)
    if len(s) <= MAX_QUOTE:
        return repr(s)
    return f"{s[:MAX_QUOTE]!r}... ({len(s):,} characters)"
