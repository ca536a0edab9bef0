"""The executed chapters' outputs fit the page: text lines in the code column, figures at 1:1.

The site shows a chapter's outputs in the code column, 88 characters of monospace wide on desktop, and
figures at 1:1 up to 9.2 in (920 CSS px; the inline PNGs are retina, drawn at 2 x 100 dpi). This test
reads the chapters nbmake executed (``BOOK_EXECUTED``, as tests/test_prose_numbers.py does) and holds
every output a reader sees (cells not tagged ``remove-cell`` or ``remove-output``) to both:

- every line of printed text (stdout, stderr, and a result shown as plain text: one with an HTML,
  Markdown or image form is shown as that) is at most :data:`WIDTH` characters, tabs expanded to the
  site's tab stops (4, ``tab-size`` in theme/static/theme.css);
- every PNG is at most :data:`FULL_WIDTH` in wide at its natural size: its pixel width / 2 / 100.

The browser-side check of the displayed against the natural size is tests/test_browser.py's.
"""

from __future__ import annotations

import base64
import json
import os
import struct
from pathlib import Path

import pytest

WIDTH = 88  #: characters of a code or output line the column shows without scrolling
TAB = 4  #: the site's tab stops (theme/static/theme.css: pre { tab-size: 4 })
FULL_WIDTH = 9.2  #: in, the widest figure shown at 1:1
RETINA_DPI = 200  #: pixels per inch of an inline PNG: 2 x figure.dpi (100)
HIDDEN = {"remove-cell", "remove-output"}
RICHER = ("text/html", "text/markdown", "image/png", "image/svg+xml", "image/jpeg")


def visible_outputs(nb: dict) -> list[tuple[int, dict]]:
    """(cell index, output) of every output the site shows."""
    out = []
    for i, cell in enumerate(nb["cells"]):
        if cell["cell_type"] != "code" or HIDDEN & set(cell.get("metadata", {}).get("tags", [])):
            continue
        out += [(i, o) for o in cell.get("outputs", [])]
    return out


def _text(value) -> str:
    return "".join(value) if isinstance(value, list) else str(value)


def text_lines(output: dict) -> list[str]:
    """The lines of text an output shows as text, tabs expanded to the site's stops."""
    if output["output_type"] == "stream":
        text = _text(output["text"])
    elif "data" in output and not any(k in output["data"] for k in RICHER):
        text = _text(output["data"].get("text/plain", ""))
    else:
        return []
    return [line.expandtabs(TAB) for line in text.splitlines()]


def png_widths(output: dict) -> list[float]:
    """The natural width (in) of the output's PNG, if it has one: pixels / 2 / 100 (retina)."""
    png = output.get("data", {}).get("image/png")
    if png is None:
        return []
    raw = base64.b64decode(_text(png))
    assert raw[:8] == b"\x89PNG\r\n\x1a\n" and raw[12:16] == b"IHDR", "not a PNG"
    (width_px,) = struct.unpack(">I", raw[16:20])
    return [width_px / RETINA_DPI]


def too_long(nb: dict) -> list[str]:
    """Every visible output line longer than :data:`WIDTH`, as 'cell i (n chars): line'."""
    return [
        f"cell {i} ({len(line)} chars): {line}"
        for i, o in visible_outputs(nb)
        for line in text_lines(o)
        if len(line) > WIDTH
    ]


def too_wide(nb: dict) -> list[str]:
    """Every visible PNG wider than :data:`FULL_WIDTH` at its natural size, as 'cell i: w in'."""
    return [f"cell {i}: {w:.2f} in" for i, o in visible_outputs(nb) for w in png_widths(o) if w > FULL_WIDTH]


# ------------------------------------------------------------------------------- the rules, alone --


def _png(width_px: int) -> str:
    head = b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + b"IHDR" + struct.pack(">II", width_px, 10)
    return base64.b64encode(head + b"\x08\x06\x00\x00\x00").decode()


def _notebook(*cells) -> dict:
    return {
        "cells": [
            {"cell_type": "code", "metadata": {"tags": tags}, "source": "", "outputs": outputs}
            for tags, outputs in cells
        ]
    }


def test_long_lines_are_found_in_shown_text_only():
    long = "x" * (WIDTH + 1)
    nb = _notebook(
        ([], [{"output_type": "stream", "name": "stdout", "text": ["ok\n", long + "\n"]}]),
        (["remove-cell"], [{"output_type": "stream", "name": "stdout", "text": long}]),
        (["hide-input"], [{"output_type": "execute_result", "data": {"text/plain": long}}]),
        ([], [{"output_type": "execute_result", "data": {"text/plain": long, "text/html": "<table>"}}]),
        ([], [{"output_type": "stream", "name": "stdout", "text": "a\t" * 22 + "b"}]),  # 45 chars, 89 shown
        ([], [{"output_type": "stream", "name": "stdout", "text": "y" * WIDTH}]),
    )
    assert [m.split(" (")[0] for m in too_long(nb)] == ["cell 0", "cell 2", "cell 4"]


def test_wide_figures_are_found_at_their_retina_size():
    nb = _notebook(
        ([], [{"output_type": "display_data", "data": {"image/png": _png(1840), "text/plain": "<Figure>"}}]),
        ([], [{"output_type": "display_data", "data": {"image/png": _png(1842)}}]),
        (["remove-output"], [{"output_type": "display_data", "data": {"image/png": _png(4000)}}]),
    )
    assert too_wide(nb) == ["cell 1: 9.21 in"]
    assert too_long(nb) == []  # the figure's text/plain is not shown


# ------------------------------------------------------------------------------- the book's test --


def _executed_chapters() -> list[Path]:
    folder = os.environ.get("BOOK_EXECUTED")  # set by `make test` after nbmake
    return sorted(Path(folder).glob("[0-9][0-9]_*.ipynb")) if folder else []


@pytest.mark.book_site
@pytest.mark.parametrize("path", _executed_chapters() or [None], ids=lambda p: p.stem if p else "none")
def test_every_output_fits_the_column_and_every_figure_is_shown_at_1_to_1(path):
    if path is None:
        pytest.skip("BOOK_EXECUTED is not set (make test sets it to the chapters nbmake executed)")
    nb = json.loads(path.read_text(encoding="utf-8"))
    assert visible_outputs(nb), f"{path} was not executed"
    problems = too_long(nb) + too_wide(nb)
    if problems:
        pytest.fail(f"{path.stem}: outputs wider than the page:\n" + "\n".join(problems), pytrace=False)
