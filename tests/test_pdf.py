"""The book's PDF (scripts/build_pdf.py): built offline from the staged, executed project that
scripts/build_site.py writes (BUILD/site-src), checked on the PDF's own bytes (no PDF library): its
bookmarks (every page of the toc in order, chapters with their numbers), its images (one per figure
output), no link left pointing at a site URL, and the same bytes twice. A page that cannot be
converted stops the build with a message naming that page.

The PDFs checked are those the site builds wrote into their sites (book.pdf beside index.html); the
book's needs `_build/site-src` (or SITE_BUILD_ROOT/site-src): marker book_site, skipped when it is
missing. The fixture's site is built here when missing (tests/fixtures/site, by scripts/build_site.py).
"""

from __future__ import annotations

import base64
import hashlib
import json
import re
import shutil
import sys
from pathlib import Path

import nbformat
import pytest
import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import build_pdf  # noqa: E402
from test_site import SITES, built_site, toc_files  # noqa: E402

pytest.importorskip("typst", reason="the typst package (environment.txt) builds the PDF")

RASTER = ("image/png", "image/jpeg")
# ![alt](path) and the figure directive's argument, when the path is a raster image
MARKDOWN_IMAGE = re.compile(r"(?:!\[[^\]]*\]\(|[:`]{3,}\{figure\}\s*)([^)\s]+\.(?:png|jpe?g))")


# ------------------------------------------------------------------------------ reading the PDF --


def pdf_objects(pdf: bytes) -> dict[int, bytes]:
    """Every `N 0 obj ... endobj` of the file (Typst writes no object streams), its dictionary part."""
    objs = {}
    for m in re.finditer(rb"(\d+) 0 obj\s*(.*?)(?:\bstream\r?\n|endobj)", pdf, re.S):
        objs[int(m.group(1))] = m.group(2)
    return objs


def pdf_string(raw: bytes) -> str:
    """A PDF string token: (literal) or <hex>, UTF-16BE when it starts with a byte order mark."""
    if raw.startswith(b"<"):
        data = bytes.fromhex(raw[1:-1].decode())
    else:
        body = raw[1:-1]
        escapes = {b"n": b"\n", b"r": b"\r", b"t": b"\t", b"b": b"\b", b"f": b"\f"}
        out, i = bytearray(), 0
        while i < len(body):
            c = body[i : i + 1]
            if c == b"\\":
                nxt = body[i + 1 : i + 2]
                octal = re.match(rb"[0-7]{1,3}", body[i + 1 : i + 4])
                if octal:
                    out.append(int(octal.group(0), 8))
                    i += 1 + len(octal.group(0))
                    continue
                out += escapes.get(nxt, nxt)
                i += 2
                continue
            out += c
            i += 1
        data = bytes(out)
    if data.startswith(b"\xfe\xff"):
        return data[2:].decode("utf-16-be")
    return data.decode("latin-1")


STRING = rb"(\((?:[^()\\]|\\.)*\)|<[0-9A-Fa-f\s]*>)"


def bookmarks(pdf: bytes) -> list[tuple[int, str]]:
    """The PDF outline in reading order: (depth, title)."""
    objs = pdf_objects(pdf)
    catalog = next(d for d in objs.values() if re.search(rb"/Type\s*/Catalog", d))
    root = objs[int(re.search(rb"/Outlines\s+(\d+) 0 R", catalog).group(1))]

    def ref(d: bytes, key: bytes) -> int | None:
        m = re.search(rb"/" + key + rb"\s+(\d+) 0 R", d)
        return int(m.group(1)) if m else None

    out: list[tuple[int, str]] = []

    def walk(first: int | None, depth: int) -> None:
        n = first
        while n is not None:
            d = objs[n]
            out.append((depth, pdf_string(re.search(rb"/Title\s*" + STRING, d, re.S).group(1))))
            walk(ref(d, b"First"), depth + 1)
            n = ref(d, b"Next")

    walk(ref(root, b"First"), 0)
    return out


def raster_images(pdf: bytes) -> int:
    """Image XObjects that are pictures, not the alpha masks (/SMask) of other images."""
    objs = pdf_objects(pdf)
    masks = {int(m) for d in objs.values() for m in re.findall(rb"/SMask\s+(\d+) 0 R", d)}
    return sum(1 for n, d in objs.items() if re.search(rb"/Subtype\s*/Image", d) and n not in masks)


def page_count(pdf: bytes) -> int:
    return sum(1 for d in pdf_objects(pdf).values() if re.search(rb"/Type\s*/Page(?![A-Za-z])", d))


# ------------------------------------------------------------------------------ what the PDF should hold --


def page_title(site_src: Path, rel: str) -> str:
    path = site_src / rel
    if path.suffix == ".ipynb":
        nb = nbformat.read(path, as_version=4)
        first = next((c.source for c in nb.cells if c.cell_type == "markdown"), "")
    else:
        first = path.read_text(encoding="utf-8")
    m = re.match(r"---\s*\n(.*?\n)---", first, re.S)
    title = ((yaml.safe_load(m.group(1)) if m else None) or {}).get("title")
    if title is None:  # no front matter title: the page's first heading
        title = re.search(r"^#\s+(.+)$", first, re.M).group(1)
    return str(title)


def expected_outline(site_src: Path) -> list[tuple[int, str]]:
    """The bookmarks the PDF must have for the toc, in order, as (depth, title): each page's title (the
    landing page as "Introduction" when it repeats the book's title), "k Title" for the k-th notebook,
    the parts' titles, each at its depth in the toc, and the references."""
    cfg = yaml.safe_load((site_src / "myst.yml").read_text(encoding="utf-8"))
    book_title = cfg["project"]["title"]
    out, chapter = [], 0

    def walk(entries, depth):
        nonlocal chapter
        for e in entries:
            if e.get("file"):
                rel = e["file"].removeprefix("./")
                title = page_title(site_src, rel)
                if not out and title == book_title:
                    title = "Introduction"
                if rel.endswith(".ipynb"):
                    chapter += 1
                    title = f"{chapter} {title}"
                out.append((depth, title))
            elif e.get("title"):
                out.append((depth, e["title"]))
            walk(e.get("children") or [], depth + 1)

    walk(cfg["project"]["toc"], 0)
    return out + [(0, "References")]


def figure_images(site_src: Path) -> int:
    """Distinct raster images the chapters show: PNG/JPEG outputs of code cells that are not removed
    (remove-cell, remove-output), and raster images the Markdown pages include."""
    seen = set()
    cfg = yaml.safe_load((site_src / "myst.yml").read_text(encoding="utf-8"))
    for rel in toc_files(cfg["project"]["toc"]):
        path = site_src / rel
        if path.suffix == ".ipynb":
            for cell in nbformat.read(path, as_version=4).cells:
                tags = set(cell.metadata.get("tags", []))
                if cell.cell_type != "code" or tags & {"remove-cell", "remove-output"}:
                    continue
                for o in cell.get("outputs", []):
                    for mime in RASTER:
                        if mime in o.get("data", {}):
                            seen.add(hashlib.sha256(base64.b64decode(o["data"][mime])).hexdigest())
        texts = (
            [c.source for c in nbformat.read(path, as_version=4).cells if c.cell_type == "markdown"]
            if path.suffix == ".ipynb"
            else [path.read_text(encoding="utf-8")]
        )
        for text in texts:
            for ref in re.findall(MARKDOWN_IMAGE, text):
                img = (path.parent / ref).resolve()
                if img.is_file():
                    seen.add(hashlib.sha256(img.read_bytes()).hexdigest())
    return len(seen)


# ------------------------------------------------------------------------------ builds --


def _site_src(name: str) -> Path:
    src = SITES[name][1] / "site-src"
    if name == "book" and not (src / "myst.yml").is_file():
        pytest.skip(f"the book's staged project {src} is missing: build the site first (make book)")
    if name == "fixture":
        built_site("fixture")  # stages and renders the fixture project (seconds)
    return src


_PDFS: dict[str, bytes] = {}


def built_pdf(name: str, tmp_path_factory) -> tuple[Path, bytes]:
    """The PDF the site build wrote into the site (scripts/build_site.py's last step), and its sources."""
    src = _site_src(name)
    if name not in _PDFS:
        out = SITES[name][1] / "html" / "book.pdf"
        if name == "book" and not out.is_file():
            built_site("book")
        assert out.is_file(), f"the site build wrote no {out}"
        _PDFS[name] = out.read_bytes()
    return src, _PDFS[name]


PARAMS = [
    pytest.param("fixture", marks=pytest.mark.slow),
    pytest.param("book", marks=pytest.mark.book_site),
]


@pytest.fixture(scope="module", params=PARAMS)
def pdf(request, tmp_path_factory):
    return built_pdf(request.param, tmp_path_factory)


def test_the_pdf_has_every_page_of_the_toc_in_order(pdf):
    src, data = pdf
    assert data.startswith(b"%PDF-"), "not a PDF"
    marks = bookmarks(data)
    expected = expected_outline(src)
    got = [m for m in marks if m in expected]
    assert got == expected, f"bookmarks {got}\n  expected {expected}"
    # and nothing else sits at the top level: no page's section escaped its page
    top = {title for depth, title in marks if depth == 0}
    assert top <= {title for _, title in expected}, f"unexpected top-level bookmarks: {sorted(top - set(expected))}"
    # a title page, the contents, and at least a page for each page and part of the toc
    assert page_count(data) >= 2 + len(expected) - 1, f"only {page_count(data)} pages"


def test_every_figure_image_is_embedded(pdf):
    src, data = pdf
    expected = figure_images(src)
    assert expected > 0, "the project shows no raster figure: the count below would prove nothing"
    assert raster_images(data) == expected, f"{raster_images(data)} images in the PDF, {expected} figures in the pages"


def test_no_link_points_at_the_site_or_nowhere(pdf):
    """myst writes links between pages as site URLs ("/slug#id"); in the PDF they must be internal
    links (GoTo), and an unresolved reference leaves no "??"."""
    _, data = pdf
    uris = [pdf_string(m) for m in re.findall(rb"/URI\s*" + STRING, data)]
    relative = [u for u in uris if not re.match(r"^[a-z][a-z0-9+.-]*:", u, re.I)]
    assert not relative, f"links to site paths, dead in a PDF: {relative[:10]}"
    internal = re.findall(rb"/S\s*/GoTo\b|/Dest\s*[\[/(<]", data)
    assert internal, "no internal link at all: cross-references were not turned into links"


def test_the_build_is_deterministic(tmp_path):
    src = _site_src("fixture")
    a, b = tmp_path / "a.pdf", tmp_path / "b.pdf"
    build_pdf.build_pdf(src, a)
    build_pdf.build_pdf(src, b)
    assert a.read_bytes() == b.read_bytes(), "two builds of the same project gave different PDFs"


def _append_markdown(text):
    return lambda nb: nb.cells.append(nbformat.v4.new_markdown_cell(text))


@pytest.mark.slow
@pytest.mark.parametrize(
    "breakage",
    [
        # Typst cannot typeset it (raw Typst calling a function that does not exist)
        pytest.param(_append_markdown("```{raw} typst\n#no-such-function()\n```\n"), id="typst"),
        # myst cannot convert it: LaTeX math with an unknown macro
        pytest.param(_append_markdown(r"$\nosuchmacro{x}$"), id="math"),
        # myst cannot read it
        pytest.param(None, id="unreadable"),
    ],
)
def test_a_page_that_cannot_be_converted_is_named(tmp_path, breakage):
    src = tmp_path / "site-src"
    shutil.copytree(_site_src("fixture"), src, ignore=shutil.ignore_patterns("_build"))
    cfg = yaml.safe_load((src / "myst.yml").read_text(encoding="utf-8"))
    victim = [f for f in toc_files(cfg["project"]["toc"]) if f.endswith(".ipynb")][-1]
    if breakage is None:
        (src / victim).write_text('{"cells": [', encoding="utf-8")
    else:
        nb = nbformat.read(src / victim, as_version=4)
        breakage(nb)
        nbformat.write(nb, src / victim)
    with pytest.raises(build_pdf.PdfError) as err:
        build_pdf.build_pdf(src, tmp_path / "book.pdf")
    assert victim in str(err.value), f"the message does not name {victim}:\n{err.value}"
    assert not (tmp_path / "book.pdf").exists(), "a failed build left a PDF behind"


@pytest.mark.parametrize("chapter", ["1", "2", "10", "11", "17"])
def test_figure_and_equation_numbers_are_those_of_the_site(tmp_path, chapter):
    """The numbering myst writes for chapter k, as rewritten by build_pdf, typesets the second figure
    and equation of the chapter as "k.2" and "(k.2)" (Typst reads myst's own pattern "10.1" otherwise)."""
    import typst

    typ = tmp_path / "numbers.typ"
    typ.write_text(
        build_pdf.chapter_numbering(
            f'#set figure(numbering: "{chapter}.1")\n#set math.equation(numbering: "({chapter}.1)")\n'
        )
        + "#figure([a], caption: [one])\n#figure([b], caption: [two]) <f>\n"
        + "$ x $\n$ y $ <e>\n"
        + "#context {\n"
        + "  let n(el) = numbering(el.numbering, ..counter(el.func()).at(el.location()))\n"
        + "  let f = query(<f>).first()\n"
        + "  let fig = numbering(f.numbering, ..counter(figure.where(kind: f.kind)).at(f.location()))\n"
        + "  [#metadata((fig, n(query(<e>).first()))) <out>]\n"
        + "}\n",
        encoding="utf-8",
    )
    got = typst.query(str(typ), "<out>", field="value", one=True, ignore_system_fonts=True)
    assert json.loads(got) == [f"{chapter}.2", f"({chapter}.2)"]
