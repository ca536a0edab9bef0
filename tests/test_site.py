"""The static site: built by scripts/build_site.py with the offline theme (theme/), read from disk.

Two sites are checked: the book (myst.yml at the repository root, into _build/html) and a small
fixture project (tests/fixtures/site, into _build/fixture/html) that exercises every element the
theme renders. Each is rebuilt once per session if it is missing or older than its sources.
What only a browser can check (the outline marking the section in view, copy, dark mode, previews on
hover, print layout) is in tests/test_browser.py.
"""

from __future__ import annotations

import base64
import functools
import json
import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import nbformat
import pytest
import yaml
from bs4 import BeautifulSoup

ROOT = Path(__file__).resolve().parents[1]
BUILD_SCRIPT = ROOT / "scripts" / "build_site.py"
FIXTURE = ROOT / "tests" / "fixtures" / "site"
# SITE_BUILD_ROOT (a folder) builds both sites there instead of _build, and BOOK_PROJECT (a copy of the
# repository) is built as the book instead of the repository: for work on the theme beside other work.
_BUILD_ROOT = Path(os.environ["SITE_BUILD_ROOT"]) if os.environ.get("SITE_BUILD_ROOT") else ROOT / "_build"
SITES = {
    # name: (project folder, build folder; the site is BUILD/html, the executed notebooks BUILD/site-src)
    "book": (Path(os.environ.get("BOOK_PROJECT") or ROOT), _BUILD_ROOT),
    "fixture": (FIXTURE, _BUILD_ROOT / "fixture"),
}
IMAGE_TYPES = ("image/png", "image/jpeg", "image/gif", "image/svg+xml")
REMOTE = re.compile(r"^(https?:)?//", re.I)


# ------------------------------------------------------------------------------------ building --


def toc_files(entries) -> list[str]:
    out: list[str] = []
    for e in entries or []:
        if isinstance(e, dict):
            if e.get("file"):
                out.append(str(e["file"]).removeprefix("./"))
            out += toc_files(e.get("children"))
    return out


def _newest_source(project: Path, files: list[str], cfg: dict) -> float:
    paths = [project / "myst.yml", *(ROOT / "scripts").glob("*.py"), *(project / f for f in files)]
    paths += [project / b for b in (cfg.get("project") or {}).get("bibliography", [])]
    paths += [p for p in (ROOT / "theme").rglob("*") if "node_modules" not in p.parts and p.is_file()]
    if project == ROOT:  # chapters run skilllib on the data: their outputs change with them
        for folder in ("skilllib", "data", "images"):
            paths += [p for p in (ROOT / folder).rglob("*") if p.is_file() and "__pycache__" not in p.parts]
    return max(p.stat().st_mtime for p in paths if p.exists())


_BUILT: dict[str, Site | str] = {}  # a site, or why it could not be built (not retried)


def built_site(name: str) -> Site:
    """The site `name`, (re)built once per session with scripts/build_site.py when missing or stale."""
    if name not in _BUILT:
        try:
            _BUILT[name] = _build(name)
        except RuntimeError as err:
            _BUILT[name] = str(err)
    site = _BUILT[name]
    if isinstance(site, str):
        pytest.fail(site, pytrace=False)
    return site


def _build(name: str) -> Site:
    project, build_dir = SITES[name]
    cfg = yaml.safe_load((project / "myst.yml").read_text(encoding="utf-8"))
    files = toc_files(cfg["project"]["toc"])
    missing = [f for f in files if not (project / f).exists() and f not in _build_module().GENERATED_PAGES]
    if missing:
        raise RuntimeError(f"myst.yml ({name}) lists pages that do not exist: {missing}")
    out = build_dir / "html"
    stamp = out / "_static" / "pages.json"
    stale = not stamp.exists() or stamp.stat().st_mtime < _newest_source(project, files, cfg)
    if not stale:  # same sources, but built at another commit: its footer would name that commit
        built_at = json.loads(stamp.read_text(encoding="utf-8")).get("build", {}).get("commit")
        stale = built_at != _build_module().build_info(project)["BOOK_COMMIT"]
    if stale:
        if shutil.which("node") is None:
            raise RuntimeError("node is not installed: the site cannot be built (Node 18+ is required)")
        executed = os.environ.get("BOOK_EXECUTED") if name == "book" else None  # set by `make test`
        proc = subprocess.run(
            [
                sys.executable,
                str(BUILD_SCRIPT),
                "--project",
                str(project),
                "--build-dir",
                str(build_dir),
                *(["--executed", executed] if executed else []),
            ],
            cwd=ROOT,
            capture_output=True,
            text=True,
            stdin=subprocess.DEVNULL,
            timeout=3600,
        )
        if proc.returncode != 0:
            raise RuntimeError(f"building the {name} site failed:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}")
    return Site(name, project, build_dir, out, cfg, files)


class _Collector(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.tags: list[tuple[str, dict]] = []
        self.ids: set[str] = set()
        self.stack: list[str] = []
        self.figures: dict[str, list[tuple[str, dict]]] = {}  # figure id -> tags inside it
        self._open_figures: list[str] = []

    def handle_starttag(self, tag, attrs):
        a = {k: (v or "") for k, v in attrs}
        self.tags.append((tag, a))
        if "id" in a:
            self.ids.add(a["id"])
        for fid in self._open_figures:
            self.figures[fid].append((tag, a))
        if tag == "figure":
            fid = a.get("id", f"_anon{len(self.figures)}")
            self.figures[fid] = []
            self._open_figures.append(fid)

    def handle_endtag(self, tag):
        if tag == "figure" and self._open_figures:
            self._open_figures.pop()


@dataclass
class Page:
    file: str
    url: str
    title: str
    download: str | None
    path: Path
    html: str = field(repr=False)
    tags: list[tuple[str, dict]] = field(repr=False)
    ids: set[str] = field(repr=False)
    figures: dict[str, list[tuple[str, dict]]] = field(repr=False)

    def attr_values(self, *names: str) -> list[tuple[str, str, str]]:
        return [(t, n, a[n]) for t, a in self.tags for n in names if n in a]

    @functools.cached_property
    def soup(self) -> BeautifulSoup:
        return BeautifulSoup(self.html, "html.parser")

    @functools.cached_property
    def article(self):
        return self.soup.select_one("main article.page")


@dataclass
class Site:
    name: str
    project: Path
    build_dir: Path
    out: Path
    cfg: dict
    files: list[str]

    @functools.cached_property
    def manifest(self) -> dict:
        return json.loads((self.out / "_static" / "pages.json").read_text(encoding="utf-8"))

    @functools.cached_property
    def pages(self) -> list[Page]:
        pages = []
        for p in self.manifest["pages"]:
            path = self.out / p["url"]
            html = path.read_text(encoding="utf-8")
            c = _Collector()
            c.feed(html)
            pages.append(Page(p["file"], p["url"], p["title"], p["download"], path, html, c.tags, c.ids, c.figures))
        return pages

    def page(self, file: str) -> Page:
        return next(p for p in self.pages if p.file == file)

    def executed(self, file: str):
        return nbformat.read(self.build_dir / "site-src" / file, as_version=4)


# The book's site renders the chapters nbmake executed (`make test`): tests of it are marked `book_site`,
# so that `make test` can run every other test while nbmake works (see the Makefile).
SITE_PARAMS = [pytest.param(name, marks=[pytest.mark.book_site] if name == "book" else []) for name in SITES]


@pytest.fixture(scope="module", params=SITE_PARAMS)
def site(request) -> Site:
    return built_site(request.param)


# ------------------------------------------------------------------------------------ the tests --


def test_one_page_per_toc_entry(site):
    assert [p["file"] for p in site.manifest["pages"]] == site.files
    assert (site.out / "index.html").is_file()
    assert site.pages[0].url == "index.html"
    title = site.cfg["project"]["title"]
    assert site.manifest["title"] == title
    for page in site.pages:
        assert page.path.is_file(), page
        assert "<title>" in page.html and title in page.html, f"{page.url}: no site title"
        assert "<h1>" in page.html, f"{page.url}: no page title"


def test_sidebar_marks_the_current_page_and_links_prev_next(site):
    urls = [p.url for p in site.pages]
    for i, page in enumerate(site.pages):
        toc_links = [a["href"] for t, a in page.tags if t == "a" and a.get("aria-current") == "page"]
        assert toc_links == [page.url], f"{page.url}: current page not marked in the contents"
        rel = {a.get("rel"): a["href"] for t, a in page.tags if t == "a" and a.get("rel") in ("prev", "next")}
        assert rel.get("prev") == (urls[i - 1] if i else None), page.url
        assert rel.get("next") == (urls[i + 1] if i + 1 < len(urls) else None), page.url


def _image_outputs(nb) -> list[tuple[str, bytes]]:
    found = []
    for cell in nb.cells:
        for out in cell.get("outputs", []) if cell.cell_type == "code" else []:
            data = out.get("data", {})
            for mime in IMAGE_TYPES:
                if mime in data:
                    value = data[mime]
                    value = "".join(value) if isinstance(value, list) else value
                    blob = value.encode() if mime == "image/svg+xml" else base64.b64decode(value)
                    found.append((mime, blob))
                    break
    return found


def test_notebook_pages_show_every_figure(site):
    """Every image output of an executed chapter is an <img> on its page whose file has its bytes."""
    for file in [f for f in site.files if f.endswith(".ipynb")]:
        page = site.page(file)
        shown = []
        for tag, attr in page.tags:
            if tag == "img":
                target = page.path.parent / unquote(attr["src"])
                assert target.is_file(), f"{page.url}: <img src={attr['src']}> has no file"
                shown.append(target.read_bytes())
        for mime, blob in _image_outputs(site.executed(file)):
            ok = any(blob == s or (mime == "image/svg+xml" and blob.strip() == s.strip()) for s in shown)
            ok = ok or (mime == "image/png" and _same_pixels(blob, shown))  # the site's lossless WebP
            assert ok, f"{page.url}: an {mime} output of {file} is not shown"


def _same_pixels(png: bytes, shown: list[bytes]) -> bool:
    import io

    from PIL import Image, ImageChops, UnidentifiedImageError

    im = Image.open(io.BytesIO(png)).convert("RGBA")
    for s in shown:
        try:
            other = Image.open(io.BytesIO(s)).convert("RGBA")
        except UnidentifiedImageError:
            continue
        if other.size == im.size and ImageChops.difference(other, im).getbbox() is None:
            return True
    return False


def test_labelled_figure_cells_are_numbered_figures(site):
    """A cell starting `#| label: fig-x` / `#| caption:` is <figure id=fig-x> with its image and caption."""
    for file in [f for f in site.files if f.endswith(".ipynb")]:
        page = site.page(file)
        for cell in site.executed(file).cells:
            m = re.match(r"\s*#\|\s*label:\s*(\S+)", cell.source) if cell.cell_type == "code" else None
            if not m:
                continue
            label = m.group(1)
            assert label in page.figures, f"{page.url}: no <figure id={label}>"
            inside = [t for t, _ in page.figures[label]]
            assert "figcaption" in inside, f"{page.url}: figure {label} has no caption"
            if _image_outputs(nbformat.from_dict({"cells": [cell]})):
                assert "img" in inside, f"{page.url}: figure {label} shows no image"
            assert re.search(
                rf'<figure id="{re.escape(label)}"[^>]*>.*?class="caption-number">[^<]*\d', page.html, re.S
            ), f"{page.url}: figure {label} is not numbered"


def test_internal_links_and_cross_references_resolve(site):
    by_url = {p.url: p for p in site.pages}
    for page in site.pages:
        for tag, name, value in page.attr_values("href", "src"):
            parts = urlsplit(value)
            if parts.scheme or value.startswith("//"):
                continue
            target = by_url.get(parts.path, page) if parts.path else page
            if parts.path:
                assert (page.path.parent / unquote(parts.path)).exists(), (
                    f"{page.url}: <{tag} {name}={value}> is missing"
                )
            if parts.fragment and parts.path in ("", *by_url):
                assert unquote(parts.fragment) in target.ids, f"{page.url}: <{tag} {name}={value}>: no such anchor"


def test_every_cross_reference_is_resolved(site):
    """myst only warns about `[](#label)` with no target; the theme marks it, and this fails."""
    for page in site.pages:
        bad = re.findall(r'<span class="xref unresolved">(.*?)</span>', page.html)
        assert not bad, f"{page.url} ({page.file}): unresolved cross-references {bad}"


def test_no_remote_scripts_styles_fonts_or_images(site):
    for page in site.pages:
        for tag, name, value in page.attr_values("src", "href", "srcset", "poster", "data"):
            if tag == "a":
                continue  # links to the web are fine; what a page loads is not
            assert not REMOTE.match(value.strip()), f"{page.url}: <{tag} {name}={value}> loads from the network"
        assert not re.search(r"@import\s+url\(\s*['\"]?(https?:)?//", page.html), page.url
    for css in site.out.rglob("*.css"):
        for url in re.findall(r"url\(\s*['\"]?([^'\")]+)", css.read_text(encoding="utf-8")):
            assert not REMOTE.match(url), f"{css}: url({url}) is remote"
            if not url.startswith("data:"):
                assert (css.parent / url.split("#")[0].split("?")[0]).is_file(), f"{css}: url({url}) is missing"


def test_no_root_absolute_links(site):
    for page in site.pages:
        for tag, name, value in page.attr_values("src", "href", "action", "srcset"):
            assert not (value.startswith("/") and not value.startswith("//")), (
                f"{page.url}: <{tag} {name}={value}> is root-absolute: the site must open from the file system"
            )


def _search_data(site) -> dict:
    js = (site.out / "_static" / "search-index.js").read_text(encoding="utf-8")
    m = re.fullmatch(r"window\.BOOK_SEARCH = (.*);\s*", js, re.S)
    assert m, "search-index.js does not set window.BOOK_SEARCH"
    return json.loads(m.group(1))


def test_search_index_covers_every_page(site):
    data = _search_data(site)
    indexed_pages = {data["pages"][s[0]]["url"] for s in data["sections"]}
    for page in site.pages:
        assert page.url in indexed_pages, f"{page.url} is not in the search index"
        assert 'src="_static/search-index.js"' not in page.html, "the index is loaded by search.js on first use"
        assert '<script src="_static/search.js">' in page.html and 'id="search-input"' in page.html
    assert len(data["sections"]) >= len(site.pages)
    assert {p["kind"] for p in data["pages"]} <= {"chapter", "docs", "api"}


def test_notebook_download_links_resolve(site):
    for file in site.files:
        page = site.page(file)
        links = [a["href"] for t, a in page.tags if t == "a" and "download" in a]
        if not file.endswith(".ipynb"):
            assert not links, f"{page.url}: only notebook pages have a download link"
            continue
        assert links[0] == page.download and len([x for x in links if x.endswith(".ipynb")]) == 1, (
            f"{page.url}: expected one notebook download, {page.download}, first"
        )
        target = page.path.parent / links[0]
        assert target.is_file() and target.suffix == ".ipynb", f"{page.url}: {links[0]} does not exist"
        nb = nbformat.read(target, as_version=4)
        source = nbformat.read(site.project / file, as_version=4)
        assert len(nb.cells) == len(source.cells), f"{links[0]} is not the chapter {file}"


def test_math_is_rendered_at_build_time(site):
    pages_with_math = [p for p in site.pages if 'class="katex' in p.html]
    sources = [(site.project / f).read_text(encoding="utf-8") for f in site.files if (site.project / f).is_file()]
    if any("$" in s or "{math}" in s for s in sources):
        assert pages_with_math, "the sources have math but no page has KaTeX output"
    assert (site.out / "_static" / "katex" / "katex.min.css").is_file()


# ---------------------------------------------------------------- the fixture's elements --


def test_fixture_renders_every_element():
    site = built_site("fixture")
    index = site.page("index.md")
    demo = site.page("notebooks/01_demo.ipynb")
    second = site.page("notebooks/02_second.ipynb")
    # numbered equation with its label, and a reference to it
    assert 'id="eq-sparc"' in index.html and 'class="eq-number">(1)' in index.html
    assert '<a class="xref" href="#eq-sparc" data-xref="index.html#eq-sparc">(1)</a>' in index.html
    # chapter-numbered figure, referred to from another page
    assert 'href="demo.html#fig-sine" data-xref="demo.html#fig-sine">Figure\u00a01.1</a>' in index.html
    assert 'href="demo.html#fig-sine" data-xref="demo.html#fig-sine">Figure\u00a01.1</a>' in second.html
    assert 'href="#fig-cos" data-xref="second.html#fig-cos">Figure\u00a02.1</a>' in second.html
    assert 'id="tbl-speeds"' in index.html and "Table\u00a01:" in index.html
    # admonitions, footnotes, citation and its reference list
    for kind in ("note", "warning", "tip"):
        assert f'class="admonition {kind}"' in index.html
    assert 'href="#fn-speed"' in index.html and 'id="fn-speed"' in index.html
    assert 'href="#cite-balasubramanian2015"' in index.html and "On the analysis of movement smoothness" in index.html
    # outputs: stdout, stderr, execute_result, pandas HTML, errors without ANSI codes, markdown
    assert '<pre class="output stream stdout prose">hello from stdout' in demo.html  # prose prints wrap
    assert '<pre class="output stream stderr prose">a warning on stderr' in demo.html
    assert '<pre class="output text">42</pre>' in demo.html
    assert 'class="dataframe"' in demo.html
    outputs = "".join(re.findall(r'<pre class="output[^"]*">(.*?)</pre>', second.html, re.S))
    assert "ZeroDivisionError: division by zero" in outputs and "red text after ANSI" in outputs
    assert "\x1b" not in second.html and "[31m" not in outputs and "[0m" not in outputs
    assert re.search(r'<pre class="output stream stderr( prose)?">progress 3/3', second.html)
    assert "<strong>markdown</strong>" in second.html
    # outputs over mystmd's 25,000 characters are shown whole, in a scrolling box when tagged so
    assert "line 2999\n" in second.html and 'class="outputs scroll"' in second.html
    assert "<th>399</th>" in second.html
    # remove-input hides the code, not the output; hide-input folds the code; remove-output and
    # remove-cell leave nothing of what they remove
    assert "input hidden, output shown" in second.html and "print('input hidden" not in second.html
    folded = demo.soup.select("details.code-hidden")
    assert len(folded) == 1 and "def helper" in folded[0].get_text() and "helper output shown 42" in demo.html
    assert "remove_output_marker = 1" in demo.article.get_text()
    assert "this output is removed" not in "".join(o.get_text() for o in demo.soup.select(".outputs"))
    assert "a hidden check: remove-cell" not in demo.html
    # highlighted code, internal links made relative
    assert 'class="hljs-keyword"' in demo.html
    assert 'href="index.html">link to the landing page' in second.html


def test_a_page_myst_cannot_read_fails_the_render(tmp_path):
    """myst carries on past a broken page; the theme must not (non-zero exit, the page named)."""
    site = built_site("fixture")
    project = tmp_path / "broken"
    shutil.copytree(site.build_dir / "site-src", project, ignore=shutil.ignore_patterns("_build"))
    (project / "notebooks" / "02_second.ipynb").write_text('{"cells": [', encoding="utf-8")
    myst = Path(sys.executable).parent / "myst"
    proc = subprocess.run(
        [str(myst), "build", "--html"],
        cwd=project,
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        env={**os.environ, "CI": "1", "PWD": str(project)},
        timeout=300,
    )
    assert proc.returncode != 0
    assert "notebooks/02_second.ipynb" in proc.stdout + proc.stderr


def test_a_failing_cell_stops_the_build_naming_chapter_and_cell(tmp_path):
    project = tmp_path / "proj"
    (project / "notebooks").mkdir(parents=True)
    (project / "index.md").write_text("# Home\n\nA page.\n", encoding="utf-8")
    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nb.cells = [
        nbformat.v4.new_markdown_cell("# Broken"),
        nbformat.v4.new_code_cell("x = 1"),
        nbformat.v4.new_code_cell("1 / 0"),
    ]
    nbformat.write(nb, project / "notebooks" / "01_broken.ipynb")
    (project / "myst.yml").write_text(
        yaml.safe_dump(
            {
                "version": 1,
                "project": {"title": "Broken", "toc": [{"file": "index.md"}, {"file": "notebooks/01_broken.ipynb"}]},
                "site": {"template": str(ROOT / "theme")},
            }
        ),
        encoding="utf-8",
    )
    proc = subprocess.run(
        [sys.executable, str(BUILD_SCRIPT), "--project", str(project)],
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        timeout=600,
    )
    assert proc.returncode != 0
    assert "notebooks/01_broken.ipynb: cell 3 (code cell 2) raised ZeroDivisionError: division by zero" in proc.stderr
    assert not (project / "_build" / "html").exists()


def _build_module():
    import importlib.util

    spec = importlib.util.spec_from_file_location("build_site", BUILD_SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_outputs_executed_elsewhere_are_taken_only_for_the_same_code_run_without_error(tmp_path):
    """`make test` renders the outputs nbmake wrote (--executed): the chapter's markdown with the copy's
    outputs; a copy with other code, a cell that did not run or an error output stops the build."""
    bs = _build_module()
    src_dir, done_dir = tmp_path / "src", tmp_path / "done"
    src_dir.mkdir()
    done_dir.mkdir()
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# Title, edited since"), nbformat.v4.new_code_cell("print(1)")]
    nbformat.write(nb, src_dir / "01_x.ipynb")
    ran = nbformat.v4.new_notebook()
    ran.cells = [nbformat.v4.new_markdown_cell("# Title"), nbformat.v4.new_code_cell("print(1)")]
    ran.cells[1].execution_count = 1
    ran.cells[1].outputs = [nbformat.v4.new_output("stream", name="stdout", text="1\n")]
    nbformat.write(ran, done_dir / "01_x.ipynb")
    got = bs.executed_elsewhere(src_dir / "01_x.ipynb", "01_x.ipynb", done_dir)
    assert got.cells[0].source == "# Title, edited since" and got.cells[1].outputs[0]["text"] == "1\n"
    for broken, words in (
        (lambda c: setattr(c, "source", "print(2)"), "other code"),
        (lambda c: setattr(c, "execution_count", None), "did not run"),
        (
            lambda c: c.outputs.append(nbformat.v4.new_output("error", ename="E", evalue="", traceback=[])),
            "did not run",
        ),
    ):
        bad = nbformat.v4.new_notebook()
        bad.cells = [nbformat.v4.new_markdown_cell("# Title"), nbformat.v4.new_code_cell("print(1)")]
        bad.cells[1].execution_count = 1
        broken(bad.cells[1])
        nbformat.write(bad, done_dir / "01_x.ipynb")
        with pytest.raises(bs.BuildError, match=words):
            bs.executed_elsewhere(src_dir / "01_x.ipynb", "01_x.ipynb", done_dir)
    (done_dir / "01_x.ipynb").unlink()
    with pytest.raises(bs.BuildError, match="no executed copy"):
        bs.executed_elsewhere(src_dir / "01_x.ipynb", "01_x.ipynb", done_dir)


# ---------------------------------------------------------------- what readers of MyST books expect --


def _headings(page) -> list[tuple[str, str]]:
    """(id, text) of the article's h2/h3 headings (the section anchors "#" left out), in order."""
    out = []
    for h in page.article.find_all(["h2", "h3"]):
        if h.get("id"):
            out.append((h["id"], h.get_text(" ", strip=True).removesuffix("#").strip()))
    return out


def test_outline_lists_the_pages_sections(site):
    """ "On this page": one link per h2/h3 of the article, in order, with the heading's text."""
    for page in site.pages:
        headings = _headings(page)
        nav = page.soup.select_one("nav#outline")
        if not headings:
            assert nav is None, f"{page.url}: an outline without sections"
            continue
        assert nav is not None and nav.get("aria-label") == "On this page", f"{page.url}: no outline"
        assert nav.select_one("details > summary").get_text() == "On this page"
        links = [(a["href"], a.get_text(" ", strip=True)) for a in nav.select("a")]
        assert links == [(f"#{i}", t) for i, t in headings], (
            f"{page.url}: outline {links[:3]}... != headings {headings[:3]}..."
        )
        assert not nav.find_parent("main"), "the outline is a column of its own, not inside the text"


def test_every_code_block_has_a_copy_button(site):
    for page in site.pages:
        pres = page.soup.select("main pre.code")
        buttons = page.soup.select("main button.copy")
        assert len(buttons) == len(pres), f"{page.url}: {len(pres)} code blocks, {len(buttons)} copy buttons"
        for b in buttons:
            assert b.get("type") == "button" and b.parent.select_one(":scope > pre.code"), (
                f"{page.url}: a copy button without its code"
            )


def test_cell_tags_hide_and_remove_what_they_say(site):
    """remove-cell: neither code nor output on the page; remove-input: no code; remove-output: no output;
    hide-input: the code folded in a <details>. Checked against the executed notebooks' cells."""
    for file in [f for f in site.files if f.endswith(".ipynb")]:
        page = site.page(file)
        folded = "".join(d.get_text() for d in page.soup.select("details.code-hidden"))
        shown_outputs = "".join(o.get_text() for o in page.soup.select("main .outputs"))
        shown_code = [
            pre.get_text()
            for pre in page.soup.select("main pre.code")
            if not pre.find_parent("details", class_="code-hidden")
        ]
        for cell in site.executed(file).cells:
            if cell.cell_type != "code":
                continue
            tags = set(cell.metadata.get("tags", []))
            body = "\n".join(ln for ln in cell.source.splitlines() if not ln.startswith("#|")).strip()
            if not body:
                continue
            in_code = any(body in c for c in shown_code)
            if tags & {"remove-cell", "remove-input"}:
                assert not in_code and body not in folded, f"{page.url}: a {sorted(tags)} cell's code is on the page"
            elif "hide-input" in tags:
                assert body in folded and not in_code, f"{page.url}: a hide-input cell is not folded"
            else:
                assert in_code, f"{page.url}: the code of a visible cell is missing: {body[:60]!r}"
            texts = [o.get("text", "") for o in cell.get("outputs", []) if o.get("output_type") == "stream"]
            for t in (t.strip() for t in texts if t.strip() and "\x1b" not in t and "\r" not in t):
                if tags & {"remove-cell", "remove-output"}:
                    assert t.splitlines()[0] not in shown_outputs, (
                        f"{page.url}: a {sorted(tags)} cell's output is shown"
                    )
                elif "remove-input" not in tags:
                    assert t.splitlines()[0] in shown_outputs, f"{page.url}: a cell's output is missing"


def test_no_stray_object_reprs_in_outputs(site):
    """No `Figure(650x600)` or `<Figure size ... with 1 Axes>` where a figure should be."""
    for page in site.pages:
        for out in page.soup.select("pre.output"):
            text = out.get_text()
            assert not re.search(r"^Figure\(\d+x\d+\)$|<Figure size \d+x\d+|<matplotlib\.\w+", text, re.M), (
                f"{page.url}: stray output {text[:80]!r}"
            )


def test_hover_previews_carry_their_targets(site):
    """Each cross-reference names its target (data-xref="page.html#id"); the page carries a preview of
    every target: a figure's caption and image, an equation's KaTeX, a section's heading and first text."""
    by_url = {p.url: p for p in site.pages}
    kinds = set()
    for page in site.pages:
        templates = {t["data-xref"]: t for t in page.soup.select("div#xref-previews > template")}
        for a in page.soup.select("main a.xref"):
            key = a["data-xref"]
            target_url, target_id = key.split("#", 1)
            target = by_url[target_url].soup.find(id=target_id)
            assert target is not None, f"{page.url}: {key} has no target"
            assert key in templates, f"{page.url}: no preview for {key}"
            preview = templates[key]
            assert preview.find(id=True) is None, f"{page.url}: the preview of {key} repeats ids"
            if target.name == "figure":
                kinds.add("figure")
                caption = target.find("figcaption").get_text(" ", strip=True)
                assert caption and caption in preview.get_text(" ", strip=True)
                assert bool(target.find("img")) == bool(preview.find("img"))
            elif "math-block" in (target.get("class") or []):
                kinds.add("equation")
                assert preview.select_one(".katex") is not None
            elif target.name in ("h2", "h3", "h4"):
                kinds.add("section")
                title = target.get_text(" ", strip=True).removesuffix("#").strip()
                assert title in preview.get_text(" ", strip=True)
    assert {"figure", "equation", "section"} <= kinds, f"{site.name}: previews seen only for {kinds}"


def _bib_keys(path: Path) -> dict[str, dict]:
    entries = {}
    for m in re.finditer(r"@(\w+)\{([^,\s]+),(.*?)\n\}", path.read_text(encoding="utf-8"), re.S):
        fields = dict(re.findall(r"(\w+)\s*=\s*\{(.*?)\},?\s*$", m.group(3), re.M))
        entries[m.group(2)] = {"type": m.group(1), **fields}
    return entries


def _markdown_sources(site) -> dict[str, str]:
    out = {}
    for f in site.files:
        path = site.project / f
        if f.endswith(".ipynb"):
            nb = nbformat.read(path, as_version=4)
            out[f] = "\n\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
        elif path.is_file():
            out[f] = path.read_text(encoding="utf-8")
    return out


CITE_KEY = re.compile(r"(?<![\w@.`])@([A-Za-z][\w:-]*\w)")
PLAIN_CITATION = re.compile(r"\b(?!KI\b)[A-Z][A-Za-z-]+(?: et al\.| (?:&|and) [A-Z][A-Za-z-]+)?,? \(?(?:19|20)\d\d\b")


def test_citations_link_to_bibliography_entries(site):
    """Every citation is a link to its entry in the page's reference list, which shows every work the
    page cites (and only those), each with its DOI link when references.bib has one."""
    bib = {}
    for f in site.cfg["project"].get("bibliography", []):
        bib |= _bib_keys(site.project / f)
    assert bib, f"{site.name}: myst.yml names no bibliography"
    cited_anywhere = set()
    for page in site.pages:
        cites = page.soup.select("main a.cite")
        refs = {li["id"].removeprefix("cite-"): li for li in page.soup.select("section.references li[id^=cite-]")}
        labels = {a["href"].removeprefix("#cite-") for a in cites}
        assert all(a["href"].startswith("#cite-") for a in cites), page.url
        assert labels == set(refs), f"{page.url}: cited {sorted(labels)}, listed {sorted(refs)}"
        assert all(a.get_text(strip=True) for a in cites), f"{page.url}: an empty citation"
        for label in labels:
            assert label in bib, f"{page.url}: {label} is not in the bibliography"
            doi = bib[label].get("doi")
            if doi:
                assert refs[label].find("a", href=f"https://doi.org/{doi}"), f"{page.url}: {label}'s DOI is not linked"
        cited_anywhere |= labels
    if site.name == "book":
        assert cited_anywhere == set(bib), (
            f"references.bib lists works no page cites: {sorted(set(bib) - cited_anywhere)}"
        )


def test_no_citation_is_left_as_plain_text(site):
    """The markdown of every page cites with [@key] / @key: no "Author et al. 2015" in the prose (the
    KI 2020 paper's name is a name, not a citation) and every cited key is in the bibliography."""
    bib = set()
    for f in site.cfg["project"].get("bibliography", []):
        bib |= set(_bib_keys(site.project / f))
    for file, text in _markdown_sources(site).items():
        prose = re.sub(r"```.*?```|`[^`]*`|\$\$.*?\$\$|\$[^$]*\$|https?://\S+", " ", text, flags=re.S)
        found = [m.group(0) for m in PLAIN_CITATION.finditer(prose)]
        assert not found, f"{file}: plain-text citations {found}: cite with [@key]"
        for key in CITE_KEY.findall(prose):
            assert key in bib, f"{file}: @{key} is not in the bibliography"


def test_notebook_pages_offer_the_notebook_and_its_script(site):
    """A chapter paired with a percent script offers both: the executed .ipynb and the .py source."""
    for file in [f for f in site.files if f.endswith(".ipynb")]:
        page = site.page(file)
        links = {a["href"]: a for a in page.soup.select("header.page-header p.download a[download]")}
        script = (site.project / file).with_suffix(".py")
        expected = {file} | ({str(Path(file).with_suffix(".py"))} if script.is_file() else set())
        assert set(links) == expected, f"{page.url}: downloads {sorted(links)} != {sorted(expected)}"
        if script.is_file():
            assert (page.path.parent / Path(file).with_suffix(".py")).read_bytes() == script.read_bytes()


def test_footer_names_version_commit_and_build_date(site):
    commit = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], cwd=ROOT, capture_output=True, text=True)
    for page in site.pages:
        footer = page.soup.select_one("main footer.site-footer")
        assert footer is not None, f"{page.url}: no footer"
        text = footer.get_text(" ", strip=True)
        if commit.returncode == 0:
            assert commit.stdout.strip() in footer.select_one(".build-commit code").get_text(), f"{page.url}: {text}"
        assert re.search(r"Built \d{4}-\d\d-\d\d \d\d:\d\d UTC", text), text
        if site.name == "book":
            import skilllib

            assert f"Version {skilllib.__version__}" in text, text


def _css_block(css: str, selector: str) -> dict[str, str]:
    m = re.search(re.escape(selector) + r"\s*\{(.*?)\}", css, re.S)
    assert m, f"theme.css has no {selector} block"
    return dict(re.findall(r"(--[\w-]+)\s*:\s*([^;]+);", m.group(1)))


def test_dark_mode_redefines_every_colour():
    """The dark theme (system setting or the switch) sets every colour variable of the light one, to
    another value, and the same values both ways."""
    css = (ROOT / "theme" / "static" / "theme.css").read_text(encoding="utf-8")
    light = {k: v for k, v in _css_block(css, ":root").items() if re.match(r"#|rgb|transparent", v.strip())}
    by_switch = _css_block(css, ':root[data-theme="dark"]')
    by_system = _css_block(css, ':root:not([data-theme="light"])')
    assert by_switch == by_system
    assert set(light) <= set(by_switch), f"not redefined in dark: {sorted(set(light) - set(by_switch))}"
    same = [k for k in light if light[k].strip() == by_switch[k].strip() and k not in ("--figure-bg",)]
    assert not same, f"dark keeps the light values of {same}"
    assert by_switch["--figure-bg"].strip() == "#ffffff", "figures need their white card in dark mode"


# ---------------------------------------------------------------- the API reference --


def _public_api(package: str = "skilllib") -> dict[str, object]:
    """Every public function and class of every public module (a sub-package's face included), found
    independently of scripts/api_page.py: module path -> object."""
    import importlib
    import inspect
    import pkgutil

    pkg = importlib.import_module(package)
    found = {}
    for info in pkgutil.walk_packages(pkg.__path__, prefix=f"{package}."):
        if any(part.startswith("_") for part in info.name.split(".")[1:]):
            continue
        module = importlib.import_module(info.name)
        names = getattr(module, "__all__", None) or list(vars(module))  # a lazy face lists its names
        for name in names:
            obj = getattr(module, name, None)
            if (
                not name.startswith("_")
                and (inspect.isfunction(obj) or inspect.isclass(obj))
                # defined in the module, or in a private module behind the sub-package's face
                and (obj.__module__ == info.name or obj.__module__.startswith(f"{info.name}._"))
            ):
                found[f"{info.name}.{name}"] = obj
    return found


def _api_pages(site) -> dict[str, Page]:
    """The API reference's pages: api.md (the index) and api-<sub-package>.md."""
    return {p.file: p for p in site.pages if re.fullmatch(r"api(-[\w-]+)?\.md", p.file)}


def _html_id(label: str) -> str:
    return label.replace(".", "-").replace("_", "-").lower()


def _entry_blocks(heading) -> list:
    """The elements of an API entry: from its heading to the next h2/h3."""
    out = []
    for sib in heading.find_next_siblings():
        if sib.name in ("h2", "h3"):
            break
        out.append(sib)
    return out


def _numpydoc_names(doc: str, section: str) -> list[str]:
    """The names a numpydoc section lists (``name : type`` or ``name1, name2 : type`` at the left margin),
    read independently of scripts/api_page.py."""
    m = re.search(rf"^{section}\n-+\n(.*?)(?=^[A-Z][\w ]*\n-{{3,}}\n|\Z)", doc, re.S | re.M)
    return [n.replace("\\", "") for n in re.findall(r"^(\S[^:\n]*?) : ", m.group(1), re.M)] if m else []


# A unit as docstrings state it, in parentheses after the quantity: "(m/s)", "(Hz)", "(dimensionless)".
STATED_UNIT = re.compile(r"\((m|s|m/s|m/s\^2|rad|rad/s|deg|Hz|dimensionless)\)")
# About 60: a sub-package page's outline lists its functions and classes (features: 61) or, on the figures
# page, its modules and their functions; never methods, properties or docstring sections (75 on features).
API_OUTLINE_MAX = 70


@pytest.mark.book_site
def test_api_page_per_sub_package_lists_every_public_function_once_with_a_parameter_table():
    import inspect

    site = built_site("book")
    pages = _api_pages(site)
    api = _public_api()
    assert len(api) > 50
    assert set(pages) == {"api.md"} | {f"api-{d.split('.')[1]}.md" for d in api}, sorted(pages)
    where: dict[str, list[tuple[str, object]]] = {}
    for file, page in pages.items():
        for tag in page.article.select("[id]"):
            where.setdefault(tag["id"], []).append((file, tag))
    stated = 0
    for dotted, obj in api.items():
        # a class named like a function of its module has the label <name>-class (MyST ignores case)
        found = (inspect.isclass(obj) and where.get(f"{_html_id(dotted)}-class")) or where.get(_html_id(dotted)) or []
        assert len(found) == 1, f"{dotted}: on {[f for f, _ in found]} (one sub-package page expected)"
        file, heading = found[0]
        assert file == f"api-{dotted.split('.')[1]}.md", f"{dotted} is on {file}"
        assert heading.name in ("h2", "h3"), f"{dotted}: <{heading.name}>"
        # the numpydoc Parameters: a table with one row per parameter, the unit in its column
        names = _numpydoc_names(inspect.getdoc(obj) or "", "Attributes" if inspect.isclass(obj) else "Parameters")
        if not names:
            continue
        header = "Attribute" if inspect.isclass(obj) else "Parameter"
        tables = [t for b in _entry_blocks(heading) for t in b.select("table")]
        table = next((t for t in tables if t.select_one("th").get_text() == header), None)
        assert table is not None, f"{dotted}: no {header} table"
        cols = [th.get_text() for th in table.select("thead th")]
        assert cols == [header, "Type", "Unit", "Description"], f"{dotted}: columns {cols}"
        rows = [[td.get_text(" ", strip=True) for td in tr.select("td")] for tr in table.select("tbody tr")]
        assert [r[0] for r in rows] == names, f"{dotted}: rows {[r[0] for r in rows]}, docstring {names}"
        for name, _type, unit, desc in rows:
            for u in STATED_UNIT.findall(desc):
                stated += 1
                shown = unit.replace("²", "^2").split(", ")
                assert u in shown, f"{dotted}, {name}: the description states ({u}), the unit column {unit!r}"
    assert stated > 100, f"only {stated} table rows state a unit"

    def row(dotted, name):
        page_file, heading = where[_html_id(dotted)][0]
        for b in _entry_blocks(heading):
            for tr in b.select("tbody tr"):
                cells = [td.get_text(" ", strip=True) for td in tr.select("td")]
                if cells[0] == name:
                    return cells
        raise AssertionError(f"{dotted}: no row {name}")

    assert row("skilllib.smoothness.sparc", "speed")[2] == "m/s"
    assert row("skilllib.smoothness.sparc", "fs")[2] == "Hz"
    assert "rad/s" in row("skilllib.robot.transfer", "qd_limits")[2]
    # docstrings rendered, not shown as reST source or as docutils error messages
    for page in pages.values():
        text = page.article.get_text(" ")
        assert not re.search(r":(func|class|mod|meth|attr|data):`", text), f"{page.file}: reST roles left"
        assert "System Message" not in text and "problematic" not in page.html, page.file
    assert pages["api-smoothness.md"].article.select(".docstring a.xref"), "the docstrings' :func: are not links"


@pytest.mark.book_site
def test_api_page_outline_lists_functions_and_classes_only():
    site = built_site("book")
    pages = _api_pages(site)
    modules = {d.rsplit(".", 1)[0] for d in _public_api()}
    sizes = {}
    for file, page in pages.items():
        headings = page.article.select("h2, h3, h4, h5, h6")
        deeper = [h.get_text(strip=True) for h in headings if h.name not in ("h2", "h3")]
        assert not deeper, f"{file}: headings below h3 (a docstring's sections?): {deeper[:5]}"
        # every heading is an entry (skilllib.sub.name) or a module's section, none a docstring's
        stray = [h.get_text(strip=True) for h in headings if not h.get("id", "").startswith("skilllib-")]
        assert not stray, f"{file}: headings that are no API entry: {stray[:5]}"
        links = page.soup.select("nav#outline a")
        sizes[file] = len(links)
        assert len(links) <= API_OUTLINE_MAX, f"{file}: {len(links)} outline entries"
        # methods and properties are not headings: their label is on their signature
        for h in headings:
            name = (h.code or h).get_text(strip=True)
            assert "." not in name or name in modules, f"{file}: heading {name}"
    assert sum(sizes.values()) >= len(_public_api()), sizes
    robot = pages["api-robot.md"]
    member = robot.soup.find(id="skilllib-robot-arm-with-limits")
    assert member is not None and "code-box" in member.get("class", []), "Arm.with_limits has no anchored signature"


@pytest.mark.book_site
def test_api_page_source_links_point_at_the_def_line():
    import importlib

    site = built_site("book")
    root = Path(importlib.import_module("skilllib").__file__).resolve().parents[1]
    base = os.environ.get("BOOK_SOURCE_URL", "").strip()
    checked = 0
    for file, page in _api_pages(site).items():
        for kind in page.article.select("div.api-kind"):
            link = next((a for a in kind.select("a") if a.get_text().startswith("source:")), None)
            assert link is not None, f"{file}: {kind.get_text(' ', strip=True)}: no source link"
            href = link["href"]
            prefix = "../../" if href.startswith("../../") else (base if base and href.startswith(base) else None)
            assert prefix is not None, f"{file}: {href} is neither relative to the checkout nor under BOOK_SOURCE_URL"
            path, _, line = href[len(prefix) :].partition("#L")
            source = root / path
            assert source.is_file(), f"{file}: {href}: no such file"
            name = kind.select_one("code").get_text().rsplit(".", 1)[-1].removesuffix("-class")
            text = source.read_text(encoding="utf-8").splitlines()[int(line) - 1]
            assert re.match(rf"\s*(async\s+def|def|class)\s+{re.escape(name)}\b", text), (
                f"{file}: {href} is {text.strip()!r}, not the def/class of {name}"
            )
            checked += 1
    assert checked >= len(_public_api()), checked


@pytest.mark.book_site
def test_api_page_index_and_chapters_link_to_the_entries():
    site = built_site("book")
    pages = _api_pages(site)
    index = pages["api.md"]
    by_url = {p.url: p for p in site.pages}
    linked = {a["href"] for a in index.article.select("table a[href]")}
    assert linked == {p.url for f, p in pages.items() if f != "api.md"}, "the index links every sub-package page"
    toc = {a.get("href") for a in site.page("index.md").soup.select("nav.toc a")}
    assert {p.url for p in pages.values()} <= toc, "the contents list the API pages"
    entries = set()
    for p in site.pages:
        if p.file in pages:
            continue
        for a in p.soup.select("main a[href]"):
            path, _, frag = a["href"].partition("#")
            if path not in {q.url for q in pages.values()}:
                continue
            assert not frag or frag in by_url[path].ids, f"{p.url}: {a['href']} has no target"
            entries.add(a["href"])
    assert len(entries) >= 10, f"the chapters link to {len(entries)} API entries"


def _api_page_cli(tmp_path, source: str, *args: str) -> subprocess.CompletedProcess:
    pkg = tmp_path / "brokenpkg"
    pkg.mkdir(exist_ok=True)
    (pkg / "__init__.py").write_text('"""A package."""\n', encoding="utf-8")
    (pkg / "mod.py").write_text(source, encoding="utf-8")
    return subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "api_page.py"), "--package", "brokenpkg", *args],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(tmp_path)},
    )


def test_api_page_stops_on_a_docstring_markup_error(tmp_path):
    """A docstring docutils cannot read stops the pages, naming the object and the docstring's line
    (in a parameter's description too)."""
    broken = (
        'def f(x):\n    """Speed.\n\n    Parameters\n    ----------\n    x : float\n'
        '        Speed |v| (m/s).\n    """\n    return x\n\n\ndef g():\n    """Fine, in s."""\n'
    )
    proc = _api_page_cli(tmp_path, broken, "--page", "api-mod.md")
    assert proc.returncode == 1
    assert "brokenpkg.mod.f" in proc.stderr and "docstring line 6" in proc.stderr and "substitution" in proc.stderr
    fixed = broken.replace("Speed |v| (m/s).", "Speed ``|v|`` (m/s), see :func:`g`.")
    proc = _api_page_cli(tmp_path, fixed, "--page", "api-mod.md")
    assert proc.returncode == 0, proc.stderr
    assert "(brokenpkg.mod.f)=" in proc.stdout and "label: brokenpkg.mod" in proc.stdout
    assert "<tr><td><code>x</code></td><td>float</td><td>m/s</td><td>Speed <code>|v|</code> (m/s), see " in proc.stdout
    assert '<a class="reference external" href="#brokenpkg.mod.g"><code>g()</code></a>' in proc.stdout
    assert _api_page_cli(tmp_path, fixed).stdout.split() == ["api.md", "api-mod.md"]


# ---------------------------------------------------------------- the execution cache --


def test_cache_reuses_outputs_when_only_prose_changed(tmp_path):
    """The cache key is the code cells (in order) and the inputs' digest: a markdown edit or a tag
    reuses the outputs, a code edit or a changed input (skilllib/, data/, ...) does not."""
    bs = _build_module()
    project = tmp_path / "p"
    (project / "data").mkdir(parents=True)
    (project / "data" / "x.csv").write_text("1\n", encoding="utf-8")
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# T\n\nProse."), nbformat.v4.new_code_cell("print(1)")]
    src = project / "n.ipynb"
    nbformat.write(nb, src)
    ran = nbformat.from_dict(json.loads(json.dumps(nb)))
    ran.cells[1].outputs = [nbformat.v4.new_output("stream", name="stdout", text="1\n")]
    ran.cells[1].execution_count = 1
    cache = bs.ExecutionCache(tmp_path / "cache", bs.inputs_digest(project))
    assert cache.get(src, "n.ipynb") is None
    cache.put("n.ipynb", ran)
    nb.cells[0].source = "# T\n\nOther prose."
    nb.cells[1].metadata["tags"] = ["hide-input"]
    nbformat.write(nb, src)
    hit = cache.get(src, "n.ipynb")
    assert hit is not None and hit.cells[0].source.endswith("Other prose.") and hit.cells[1].outputs[0]["text"] == "1\n"
    assert hit.cells[1].metadata["tags"] == ["hide-input"]
    nb.cells[1].source = "print(2)"
    nbformat.write(nb, src)
    assert cache.get(src, "n.ipynb") is None, "a code edit must execute again"
    nb.cells[1].source = "print(1)"
    nbformat.write(nb, src)
    assert cache.get(src, "n.ipynb") is not None
    (project / "data" / "x.csv").write_text("2\n", encoding="utf-8")
    assert bs.ExecutionCache(tmp_path / "cache", bs.inputs_digest(project)).get(src, "n.ipynb") is None, (
        "a changed data file must execute again"
    )
    assert len(list((tmp_path / "cache").glob("n-*.ipynb"))) == 1


def test_serve_rebuilds_on_save_and_pages_reload(tmp_path):
    """`make serve`: the site is served, a saved edit is rebuilt and the served page has it; the pages
    poll the server's build number to reload themselves."""
    import signal
    import urllib.request

    built_site("fixture")  # its execution cache makes the builds below render-only
    project = tmp_path / "site"
    shutil.copytree(FIXTURE, project)
    cfg = yaml.safe_load((project / "myst.yml").read_text(encoding="utf-8"))
    cfg["site"]["template"] = str(ROOT / "theme")
    (project / "myst.yml").write_text(yaml.safe_dump(cfg, sort_keys=False), encoding="utf-8")
    if (SITES["fixture"][1] / "cache").is_dir():
        shutil.copytree(SITES["fixture"][1] / "cache", tmp_path / "build" / "cache")
    proc = subprocess.Popen(
        [
            sys.executable,
            str(ROOT / "scripts" / "serve.py"),
            "--project",
            str(project),
            "--build-dir",
            str(tmp_path / "build"),
            "--port",
            "0",
            "--interval",
            "0.3",
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        stdin=subprocess.DEVNULL,
    )
    try:
        lines = []
        for line in proc.stdout:
            lines.append(line)
            m = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
            if m:
                base = m.group(0)
                break
        else:
            pytest.fail("serve.py did not start: " + "".join(lines))

        def get(path: str) -> str:
            with urllib.request.urlopen(base + path, timeout=10) as r:
                return r.read().decode()

        assert json.loads(get("__build")) == {"id": 1, "ok": True}
        page = get("index.html")
        assert "fetch('/__build')" in page and "Fixture book" in page
        index = project / "index.md"
        index.write_text(index.read_text(encoding="utf-8") + "\nA sentence saved while serving.\n", encoding="utf-8")
        deadline = time.monotonic() + 120
        while json.loads(get("__build"))["id"] < 2:
            assert proc.poll() is None and time.monotonic() < deadline, "no rebuild after the save"
            time.sleep(0.3)
        assert "A sentence saved while serving." in get("index.html")
        assert not (tmp_path / "build" / "html" / "index.html").read_text(encoding="utf-8").count("__build"), (
            "the reload script belongs to the server, not to the built files"
        )
    finally:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
