"""The landing page (index.md): a map of the book, and the paper's claims beside the book's values.

index.md is not executed, so nothing in it is checked by a hidden cell. This holds it to the chapters:

- the map ("The pipeline, step by step"): six steps, each named by a link to the chapter (or its
  section) that builds it; every link of the map opens a page of the built site, at an id that exists;
- "How to read it" names every chapter of the table of contents, each by a link whose text is that
  chapter's title;
- the summary table: each number of its "This book" column is printed by one of the chapters its
  "Where" column links to (the executed chapters of ``BOOK_EXECUTED``, read as tests/test_prose_numbers.py
  reads them: the same number extraction and rounding), each count ("680 of 1,500") printed as such and
  each robot verdict ("UR5 5 of 6") on a printed line of that arm; each number of its "The paper"
  column is one of the paper's values that tests/prose_constants.toml cites (or in ``LANDING_CONSTANTS``);
- every other number of the page is printed by a chapter its paragraph links to, or is cited;
- the page has a description of its own, and the reference the paper cites its experiment by
  (``maldonado2019``) reads as what it is: incomplete;
- in Chromium at 1400 px and on a 390 px phone the map's text is at the body's size, inside the
  screen, and neither the page nor the summary table scrolls sideways.

What this cannot catch (as in tests/test_prose_numbers.py): a number that drifted onto another number
the linked chapter prints (a small count, "0.05" -> "0.08" m/s where the chapter prints 0.08 m). Counts
and robot verdicts are held more tightly: "21 of 24", and a verdict on its arm's line.
These tests are of the book's landing page only; the fixture site has no such page.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest
import yaml
from test_prose_numbers import (
    _MD,
    Constant,
    ProseNumber,
    _Values,
    load_constants,
    output_numbers,
    prose_numbers,
)
from test_site import ROOT, built_site

INDEX = Path(os.environ.get("BOOK_PROJECT") or ROOT) / "index.md"
TABLE_LABEL = "tbl-paper-and-book"
MAP_CLASS = "pipeline-map"
ARMS = ("Simple6", "UR5", "Puma 560", "Panda")

# Numbers the landing page states that are neither the book's results nor in tests/prose_constants.toml
# (its entries hold in the chapters; these on this page only).
LANDING_CONSTANTS = [
    Constant(2, "clusters", "the paper's smallest number of clusters that gives valid clusters (Sect. 5)"),
    Constant(16, "clusters", "the paper's largest number of clusters that gives valid clusters (Sect. 5)"),
    Constant(150, "times", "the paper's trials per participant (Sect. 5)", context=r"ten people"),
    Constant(1500, "", "the paper's trials in all, 10 participants x 150 (Sect. 5)", context=r"ten people"),
    Constant(6, "", "the paper's 6-DOF arm, Simple6 (Sect. 4)", context=r"6-joint arm"),
    Constant(1.5, "", "the name of the paper's haptic device, Phantom Premium 1.5 (Sect. 5)", context="Premium 1.5"),
    Constant(3.11, "", "the oldest Python pyproject.toml's requires-python allows", context=r"Python 3\.11\+"),
    Constant(18, "", "the oldest Node the theme's renderer runs on (theme/README.md)", context=r"Node 18\+"),
]


# ----------------------------------------------------------------------------------- the source --


def _front_matter(text: str) -> tuple[dict, str]:
    m = re.match(r"---\n(.*?)\n---\n", text, re.S)
    return (yaml.safe_load(m[1]), text[m.end() :]) if m else ({}, text)


def _plain_markdown(body: str) -> str:
    """index.md as CommonMark: a colon fence's line keeps only its argument (an admonition's or a table's
    title), its options (``:label:``, ``:class:``) go."""
    body = re.sub(r"^:{3,}(?:\{[\w-]+\})?[ \t]*(.*)$", r"\1", body, flags=re.M)
    return re.sub(r"^:[\w-]+:.*$", "", body, flags=re.M)


def _blocks(markdown: str) -> tuple[list[tuple[str, list[str]]], list[list[tuple[str, list[str]]]]]:
    """(paragraphs, table rows): each paragraph, heading or list item as (its inline markdown, the link
    targets in it); each table row as its cells, the same way. Fenced code is not prose."""
    paragraphs, rows, row = [], [], None
    for tok in _MD.parse(markdown):
        if tok.type == "tr_open":
            row = []
        elif tok.type == "tr_close":
            rows.append(row)
            row = None
        elif tok.type == "inline":
            cell = (tok.content, [c.attrGet("href") for c in tok.children or [] if c.type == "link_open"])
            (row if row is not None else paragraphs).append(cell)
    return paragraphs, rows


def _source():
    meta, body = _front_matter(INDEX.read_text(encoding="utf-8"))
    return meta, _blocks(_plain_markdown(body))


def _summary_rows() -> list[list[tuple[str, list[str]]]]:
    _, (_, rows) = _source()
    assert rows and [c for c, _ in rows[0]] == ["The paper", "This book", "Where"], "index.md: no summary table"
    return rows[1:]


def _chapter_stem(href: str) -> str | None:
    m = re.fullmatch(r"notebooks/(\d\d_\w+)\.ipynb(?:#.*)?", href or "")
    return m[1] if m else None


_EXECUTED: dict[str, dict] = {}


def _executed(stem: str) -> dict:
    folder = os.environ.get("BOOK_EXECUTED")  # set by `make test` after nbmake
    if not folder:
        pytest.skip("BOOK_EXECUTED is not set (make test sets it to the chapters nbmake executed)")
    if stem not in _EXECUTED:
        path = Path(folder) / f"{stem}.ipynb"
        assert path.is_file(), f"index.md links to {stem}, which is not among the executed chapters in {folder}"
        _EXECUTED[stem] = json.loads(path.read_text(encoding="utf-8"))
    return _EXECUTED[stem]


def _covered(n: ProseNumber, constants: list[Constant], *, context: bool = True) -> bool:
    return any(
        (not c.unit or c.unit == n.unit)
        and (not context or not c.context or re.search(c.context, n.sentence, re.IGNORECASE))
        and abs(c.value - n.value) <= n.tolerance
        for c in constants
    )


def _printed_lines(nb: dict) -> list[str]:
    lines = []
    for cell in nb["cells"]:
        for out in cell.get("outputs", []) if cell["cell_type"] == "code" else []:
            texts = [out.get("text", "")] if out.get("output_type") == "stream" else []
            texts.append(out.get("data", {}).get("text/plain", ""))
            lines += "".join("".join(t) if isinstance(t, list) else t for t in texts).splitlines()
    return lines


def _integers(line: str) -> set[int]:
    """The whole numbers standing alone in a printed line: not "3" of "3.574", "4" of "q4" or "6" of "UR6"."""
    return {
        int(t.replace(",", ""))
        for t in re.findall(r"(?<![\w.,])\d{1,3}(?:,\d{3})+(?![\w.])|(?<![\w.,])\d+(?![\w.,])", line)
    }


def _verdict_is_printed(nbs: list[dict], arm: str, count: int) -> bool:
    """Some printed line begins with the arm's name and has `count` among its whole numbers (a table row
    such as "UR5   6   5   3.574 ...": the verdicts' tables of chapters 5 and 9)."""
    return any(
        line.startswith(arm + " ") and count in _integers(line[len(arm) :]) for nb in nbs for line in _printed_lines(nb)
    )


def _count_is_printed(nbs: list[dict], part: int, whole: int) -> bool:
    """A count "680 of 1,500" is printed as such: "680 of 1500", "680 selected trials of 1500" (at most
    three words between the number and "of")."""
    said = re.compile(rf"(?<![\w.,]){part}(?:\s+[^\W\d]+){{0,3}}\s+of\s+{whole}(?![\w.]|,\d)")
    return any(said.search(line.replace(f"{whole:,}", str(whole))) for nb in nbs for line in _printed_lines(nb))


# --------------------------------------------------------------------------- the numbers' tests --


def _stdout(text: str) -> dict:
    return {"cell_type": "code", "outputs": [{"output_type": "stream", "text": text}]}


def test_the_summary_table_reads_its_numbers_right():
    """The table's parser on a made-up row: what it extracts and what it holds each number to."""
    md = (
        "| The paper | This book | Where |\n|---|---|---|\n"
        "| 650 trials of 0.3 to 0.7 m/s | 680 of 1,500; UR5 5 of 6 | [Ch.&nbsp;3](notebooks/03_experiment.ipynb) |\n"
    )
    _, rows = _blocks(md)
    (paper, book, where) = rows[1]
    assert [n.text for n in prose_numbers(paper[0])] == ["650", "0.3", "0.7"]
    assert [n.value for n in prose_numbers(book[0])] == [680, 1500, 5, 6]
    assert [_chapter_stem(h) for h in where[1]] == ["03_experiment"]
    printed = {"cells": [_stdout("UR5  6  5  3.574\n")]}
    assert _verdict_is_printed([printed], "UR5", 5)
    assert not _verdict_is_printed([printed], "UR5", 4), "3.574 is not a 3, and 4 is printed nowhere"
    assert not _verdict_is_printed([printed], "Panda", 5)
    assert not _verdict_is_printed([{"cells": [_stdout("UR5  0  q4  3.4\n")]}], "UR5", 4), "q4 is a name"
    counted = {"cells": [_stdout("680 selected trials of 1500\n"), _stdout("22 of 24; 20 Hz\n")]}
    assert _count_is_printed([counted], 680, 1500) and _count_is_printed([counted], 22, 24)
    assert not _count_is_printed([counted], 20, 24) and not _count_is_printed([counted], 80, 1500)
    paper_values = load_constants()["global"]
    assert all(_covered(n, paper_values, context=False) for n in prose_numbers(paper[0]))
    assert not _covered(prose_numbers("655 trials")[0], paper_values, context=False)


@pytest.mark.book_site
def test_each_number_of_the_summary_table_is_printed_by_its_chapters():
    rows = _summary_rows()
    assert len(rows) >= 8, "the summary table has lost rows"
    constants = load_constants()["global"] + LANDING_CONSTANTS
    problems = []
    for (paper, _), (book, _), (_, hrefs) in rows:
        stems = [s for s in map(_chapter_stem, hrefs) if s]
        if not stems:
            problems.append(f"row {book!r}: its Where cell links to no chapter")
            continue
        nbs = [_executed(s) for s in stems]
        values = _Values(v for nb in nbs for v in output_numbers(nb))
        numbers = prose_numbers(book)
        if not numbers:
            problems.append(f"row {book!r}: no number of the book")
        for n in numbers:
            if not values.matches(n):
                problems.append(f"{n.text!r} of {book!r} is printed by none of {stems}")
        for arm, count in re.findall(rf"({'|'.join(ARMS)}) (\d+) of 6", book):
            if not _verdict_is_printed(nbs, arm, int(count)):
                problems.append(f"{arm} {count} of 6 ({book!r}): no line of {stems} prints it for {arm}")
        counts = re.sub(rf"(?:{'|'.join(ARMS)}) \d+ of 6", "", book)  # the verdicts, checked above
        for part, whole in re.findall(r"(?<![\w.,])(\d[\d,]*) of (\d[\d,]*)", counts):
            if not _count_is_printed(nbs, int(part.replace(",", "")), int(whole.replace(",", ""))):
                problems.append(f"{part} of {whole} ({book!r}): no line of {stems} prints it")
        for n in prose_numbers(paper):
            if not _covered(n, constants, context=False):
                problems.append(f"{n.text!r} of the paper's column ({paper!r}) is not a value the paper states")
    assert not problems, "index.md, the summary table:\n" + "\n".join(problems)


@pytest.mark.book_site
def test_every_other_number_of_the_landing_page_is_printed_or_cited():
    _, (paragraphs, _) = _source()
    constants = load_constants()["global"] + LANDING_CONSTANTS
    problems = []
    for text, hrefs in paragraphs:
        stems = sorted({s for s in map(_chapter_stem, hrefs) if s})
        values = _Values(v for s in stems for v in output_numbers(_executed(s)))
        for n in prose_numbers(text):
            if not values.matches(n) and not _covered(n, constants):
                where = f"printed by none of {stems}" if stems else "in a paragraph that links no chapter"
                problems.append(f"{n.text!r} ({where}, not cited): {n.excerpt(60)}")
    assert not problems, "index.md:\n" + "\n".join(problems)


# ------------------------------------------------------------------------------ the built page --


def _landing():
    site = built_site("book")
    return site, site.page("index.md")


def _resolve(site, page, href: str):
    """(page, fragment) that a link of `page` opens, or a string saying why it opens nothing."""
    parts = urlsplit(href)
    if parts.scheme or parts.netloc:
        return f"{href}: not a page of the site"
    target = (page.path.parent / unquote(parts.path)).resolve() if parts.path else page.path
    found = next((p for p in site.pages if p.path.resolve() == target), None)
    if found is None:
        return f"{href}: no such page"
    if parts.fragment and unquote(parts.fragment) not in found.ids:
        return f"{href}: {found.url} has no id {parts.fragment!r}"
    return found, parts.fragment


def _section(article, heading_id: str) -> list:
    """The elements after the h2 `heading_id` up to the next h2."""
    h2 = article.find("h2", id=heading_id)
    assert h2 is not None, f"the landing page has no section #{heading_id}"
    out = []
    for el in h2.find_next_siblings():
        if el.name == "h2":
            break
        out.append(el)
    return out


@pytest.mark.book_site
def test_every_step_of_the_map_links_to_its_chapter():
    site, page = _landing()
    steps = page.article.select(f"div.{MAP_CLASS} > ol > li")
    assert len(steps) == 6, f"the map has {len(steps)} steps, not the pipeline's six"
    problems = []
    for li in steps:
        name = li.select_one("strong > a[href]")
        if name is None or li.get_text(" ", strip=True).find(name.get_text(strip=True)) != 0:
            problems.append(f"step {li.get_text(' ', strip=True)[:40]!r} does not begin with a link")
            continue
        for a in li.select("a[href]"):
            target = _resolve(site, page, a["href"])
            if isinstance(target, str):
                problems.append(f"step {name.get_text(strip=True)!r}: {target}")
            elif not target[0].file.endswith(".ipynb"):
                problems.append(f"step {name.get_text(strip=True)!r}: {a['href']} is not a chapter")
    assert not problems, "\n".join(problems)


@pytest.mark.book_site
def test_how_to_read_it_names_every_chapter_by_a_link_to_it():
    site, page = _landing()
    titles = {p.file: p.title for p in site.pages}
    items = [li for el in _section(page.article, "how-to-read-it") for li in el.select("li")]
    linked, problems = [], []
    for li in items:
        first = li.find("a", href=True)  # the item must begin with it
        begins = first is not None and li.get_text(strip=True).startswith(first.get_text(strip=True))
        target = _resolve(site, page, first["href"]) if begins else None
        if target is None or isinstance(target, str):
            problems.append(f"{li.get_text(' ', strip=True)[:50]!r}: its chapter name is not a link ({target})")
            continue
        linked.append(target[0].file)
        shown, title = first.get_text(" ", strip=True), re.sub(r"^\d+\s+", "", titles[target[0].file])
        if shown != title:
            problems.append(f"{target[0].file}: listed as {shown!r}, its title is {title!r}")
    chapters = [f for f in site.files if f.endswith(".ipynb")]
    missing = [f for f in chapters if f not in linked]
    assert not problems and not missing, "\n".join(problems + [f"not listed: {missing}"])
    assert linked[: len(chapters)] == chapters, "the chapters are not listed in the book's order"


@pytest.mark.book_site
def test_the_summary_table_is_on_the_page_and_links_its_chapters():
    site, page = _landing()
    table = page.article.select_one(f"#{TABLE_LABEL} table")
    assert table is not None, f"no table #{TABLE_LABEL} on the landing page"
    assert [th.get_text(strip=True) for th in table.select("thead th")] == ["The paper", "This book", "Where"]
    rows = table.select("tbody tr")
    assert len(rows) == len(_summary_rows())
    for tr in rows:
        links = tr.select("td:last-child a[href]")
        assert links, f"row {tr.get_text(' ', strip=True)[:60]!r} links no chapter"
        for a in links:
            target = _resolve(site, page, a["href"])
            assert not isinstance(target, str), target
            assert target[0].file.endswith(".ipynb"), f"{a['href']} is not a chapter"


@pytest.mark.book_site
def test_the_landing_page_has_its_own_description():
    site, page = _landing()
    meta, _ = _source()
    own = " ".join(str(meta.get("description", "")).split())
    project = " ".join(str(site.cfg["project"].get("description", "")).split())
    assert len(own) > 60 and own != project, "index.md needs a `description:` of its own"
    tag = page.soup.select_one('meta[name="description"]')
    assert tag is not None, "no <meta name=description> on the landing page"
    shown = " ".join(tag["content"].split()).removesuffix("…")
    assert len(shown) > 60 and own.startswith(shown), f"the page's description is not index.md's: {shown!r}"


@pytest.mark.book_site
def test_the_experiments_reference_reads_as_incomplete():
    _, page = _landing()
    entry = page.soup.select_one("li#cite-maldonado2019")
    assert entry is not None, "the landing page no longer cites the experiment (maldonado2019)"
    text = " ".join(entry.get_text(" ", strip=True).split())
    assert "Incomplete reference" in text, text
    # what the paper (Sect. 5) says of the experiment, and nothing that looks like a venue or a DOI
    for fact in ("Phantom Premium 1.5", "60 Hz", "10 participants", "150 trials"):
        assert fact in text, f"the entry does not say {fact!r}: {text}"
    assert not entry.select("a[href]"), "an incomplete reference links nowhere"
    cites = [a.get_text(" ", strip=True) for a in page.article.select('a.cite[href="#cite-maldonado2019"]')]
    assert cites and all(c.startswith("Maldonado et al.") for c in cites), cites


# ------------------------------------------------------------------------------------ in a browser --


@pytest.mark.book_site
@pytest.mark.parametrize("width,height", [(1400, 1000), (390, 844)], ids=["desktop", "phone"])
def test_the_map_and_the_table_are_legible_at_desktop_and_phone_widths(width, height):
    from test_browser import CHROMIUM, Browser

    if CHROMIUM is None:
        pytest.skip("no Chromium found (apt-get install chromium)")
    site, _ = _landing()
    browser = Browser()
    try:
        browser.send(
            "Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1, mobile=width < 600
        )
        browser.open(site.out / "index.html")
        m = browser.eval(f"""(() => {{
            const px = (el) => parseFloat(getComputedStyle(el).fontSize);
            const body = px(document.querySelector('main article p'));
            const items = [...document.querySelectorAll('.{MAP_CLASS} li')];
            const links = [...document.querySelectorAll('.{MAP_CLASS} a')].map((a) => a.getBoundingClientRect());
            const wrap = document.querySelector('#{TABLE_LABEL} .table-wrap');
            const cells = [...document.querySelectorAll('#{TABLE_LABEL} td, #{TABLE_LABEL} th')];
            return {{
              body, items: items.length, smallest: Math.min(...items.map(px)),
              outside: links.filter((r) => r.width === 0 || r.left < 0 || r.right > innerWidth).length,
              links: links.length, pageScroll: document.documentElement.scrollWidth, view: innerWidth,
              tableScroll: wrap.scrollWidth - wrap.clientWidth, cellFont: Math.min(...cells.map(px)),
            }};
        }})()""")
    finally:
        browser.close()
    assert m["items"] == 6 and m["links"] >= 6, m
    assert m["smallest"] >= min(m["body"], 16) - 0.5 and m["smallest"] >= 14, f"the map's text is small: {m}"
    assert m["outside"] == 0, f"links of the map lie outside the screen: {m}"
    assert m["pageScroll"] <= m["view"], f"the landing page scrolls sideways at {width} px: {m}"
    assert m["tableScroll"] <= 1, f"the summary table scrolls sideways at {width} px: {m}"
    assert m["cellFont"] >= 12, f"the summary table's text is small: {m}"
