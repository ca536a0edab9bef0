"""The book's one figure style: figure widths chosen for the page and fonts that stay legible there.

The site shows a figure at 1:1 (a figure ``W`` in wide as ``W * 100`` CSS px: the inline PNG is drawn at
twice ``figure.dpi`` = 100) up to :data:`FULL_WIDTH`; wider figures would be scaled down, and their text
with them. Every figure function therefore draws at most :data:`WIDE` in wide (the PNG's tight crop adds
0.1 in on each side) and with no text below :data:`MIN_FONT` pt (8 pt = 11.1 CSS px at 1:1).

Every public figure function is wrapped in :func:`book_figure`: it draws inside :data:`BOOK_RC`, whatever
the caller's matplotlib settings, so the style holds whether or not a chapter called anything. A chapter's
own plot gets the same settings from :func:`book_style` (its setup cell calls it once).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, TypeVar

import matplotlib.pyplot as plt

#: in: the widest figure the site shows at 1:1 (920 CSS px), the PNG's padding included.
FULL_WIDTH = 9.2
#: in: the figure width of a full-width figure (the saved PNG adds 0.1 in of padding on each side).
WIDE = 9.0
#: in: the width of a single-panel plot, so that it does not sprawl across the page.
SINGLE = 6.0
#: pt: the base font size of the figures' text.
BASE_FONT = 10.0
#: pt: no text of a figure is smaller (tick labels, legends and annotations included).
MIN_FONT = 8.0

#: The matplotlib settings of every figure of the book. Relative sizes resolve against ``font.size``:
#: "small" is 8.3 pt, "x-small" (6.9 pt) is below :data:`MIN_FONT` and not used.
BOOK_RC: dict[str, Any] = {
    "font.size": BASE_FONT,
    "axes.titlesize": BASE_FONT,
    "axes.labelsize": BASE_FONT,
    "xtick.labelsize": 9.0,
    "ytick.labelsize": 9.0,
    "legend.fontsize": 9.0,
    "legend.title_fontsize": 9.0,
    "figure.titlesize": 11.0,
    "figure.labelsize": BASE_FONT,
    "figure.dpi": 100,
    "figure.figsize": (SINGLE, 3.6),
}

_F = TypeVar("_F", bound=Callable[..., Any])


def book_style() -> None:
    """Apply :data:`BOOK_RC` to matplotlib's global settings (a chapter's setup cell calls it once).

    The figure functions do not need it: each draws inside the style itself (:func:`book_figure`).
    """
    plt.rcParams.update(BOOK_RC)


def book_figure(draw: _F) -> _F:
    """Wrap a figure function: it draws inside :data:`BOOK_RC` and its figures keep that style when shown."""

    @functools.wraps(draw)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        with plt.rc_context(BOOK_RC):  # the sizes are fixed when the artists are made: they outlast the context
            return draw(*args, **kwargs)

    return wrapper  # type: ignore[return-value]


def grid(n_panels: int, max_cols: int, panel_width: float) -> tuple[int, int, float]:
    """Rows, columns and figure width (in) of ``n_panels`` panels at most ``max_cols`` a row, each about
    ``panel_width`` in wide, wrapped into rows so that the figure is at most :data:`WIDE` in wide."""
    if n_panels < 1:
        raise ValueError("the figure needs at least one panel")
    cols = max(1, min(n_panels, max_cols, int(WIDE // panel_width) or 1))
    rows = -(-n_panels // cols)
    return rows, cols, min(WIDE, panel_width * cols)
