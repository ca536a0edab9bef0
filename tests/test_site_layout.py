"""The built pages' shell and weight (issue 26), read with BeautifulSoup on both sites.

Each page: a favicon, its own <meta name="description">, authors and licence in the footer, a "View
source" link to its file in the checkout, images with their drawn size and lazy loading, KaTeX's CSS
only where there is math, no search index loaded with the page; prints that read as prose may wrap and
tables of text keep their columns; the figures are lossless WebP with the notebook's pixels.
"""

from __future__ import annotations

import base64
import io
import re
import sys
from urllib.parse import unquote

import nbformat
import pytest
import yaml
from test_site import ROOT, SITE_PARAMS, built_site

sys.path.insert(0, str(ROOT / "scripts"))
import build_site  # noqa: E402


@pytest.fixture(scope="module", params=SITE_PARAMS)
def site(request):
    return built_site(request.param)


def test_every_page_has_a_favicon_and_its_own_description(site):
    descriptions = {}
    for page in site.pages:
        icon = page.soup.select_one('head link[rel="icon"]')
        assert icon and (page.path.parent / icon["href"]).is_file(), f"{page.url}: no favicon file"
        meta = page.soup.select_one('head meta[name="description"]')
        assert meta and 40 <= len(meta["content"]) <= 160, f"{page.url}: description {meta and meta['content']!r}"
        assert "<" not in meta["content"], f"{page.url}: markup in the description"
        descriptions[page.url] = meta["content"]
    assert len(set(descriptions.values())) == len(descriptions), "pages share a description"


def test_footer_names_the_authors_and_the_licence(site):
    project = yaml.safe_load((site.project / "myst.yml").read_text(encoding="utf-8"))["project"]
    authors = [a["name"] if isinstance(a, dict) else str(a) for a in project.get("authors") or []]
    licence = project.get("license")
    for page in site.pages:
        footer = page.soup.select_one("footer.site-footer")
        for name in authors:
            assert name in footer.get_text(), f"{page.url}: the footer does not name {name}"
        if licence:
            assert str(licence) in footer.select_one(".book-license").get_text(), f"{page.url}: no licence"
            link = footer.select_one(".book-license a")
            if link and not re.match(r"^[a-z]+:", link["href"]):
                assert (page.path.parent / link["href"]).resolve().is_file(), f"{page.url}: {link['href']} missing"


def test_view_source_links_resolve_to_the_pages_file_in_the_checkout(site):
    for file in site.files:
        page = site.page(file)
        link = page.soup.select_one("a.source-link")
        if not (site.project / file).is_file():  # a generated page (the API reference) has no source file
            assert link is None, f"{page.url}: links a source that is not in the checkout"
            continue
        assert link, f"{page.url}: no View source link"
        target = (page.path.parent / unquote(link["href"])).resolve()
        assert target.is_file(), f"{page.url}: View source {link['href']} -> {target} does not exist"
        paired = (site.project / file).with_suffix(".py")
        want = paired if file.endswith(".ipynb") and paired.is_file() else site.project / file
        assert target == want.resolve(), f"{page.url}: View source links {target}, not {want}"


def test_source_links_are_relative_to_the_site_or_at_book_source_url(tmp_path):
    env = build_site.source_env(ROOT, ROOT / "_build" / "html")
    assert env["BOOK_SOURCE_RELATIVE"] == "../../" and env["BOOK_SOURCE_ROOT"] == str(ROOT)
    other = build_site.source_env(tmp_path / "repo", tmp_path / "b" / "html")
    assert other["BOOK_SOURCE_RELATIVE"] == "../../repo/"
    render = (ROOT / "theme" / "render.mjs").read_text(encoding="utf-8")
    assert "process.env.BOOK_SOURCE_URL" in render, "render.mjs does not read BOOK_SOURCE_URL"


def test_output_images_have_their_size_and_load_lazily(site):
    count = 0
    for page in site.pages:
        for img in page.soup.select("main img"):
            assert img.get("loading") == "lazy" and img.get("decoding") == "async", f"{page.url}: {img['src']}"
            if "output" in img.get("class", []) and re.search(r"\.(png|webp)$", img["src"]):
                count += 1
                assert int(img["width"]) > 0 and int(img["height"]) > 0, f"{page.url}: {img['src']} without size"
                assert img.find_parent(class_="image-frame"), f"{page.url}: {img['src']} not in a frame"
    assert count, "no output image"


def test_scripts_and_styles_only_where_used(site):
    for page in site.pages:
        scripts = [s.get("src") for s in page.soup.select("script[src]")]
        assert not [s for s in scripts if s.endswith(("search-index.js", "minisearch.js"))], (
            f"{page.url}: the search index is loaded with the page"
        )
        assert "_static/search.js" in scripts and "_static/site.js" in scripts
        katex_css = page.soup.select_one('link[href$="katex.min.css"]')
        assert bool(katex_css) == ('class="katex' in page.html), (
            f"{page.url}: KaTeX CSS {'without' if katex_css else 'missing with'} math"
        )


def test_prose_prints_wrap_and_tables_of_text_do_not(site):
    prose = table = 0
    for page in site.pages:
        for pre in page.soup.select("main pre.output.stream"):
            aligned = [ln for ln in pre.get_text().splitlines() if re.search(r"\S {2,}\S", ln)]
            if "prose" in pre.get("class", []):
                prose += 1
                assert len(aligned) <= 1, f"{page.url}: a table of text marked as prose: {aligned[:2]}"
            elif len(aligned) >= 2:
                table += 1
    assert prose and table, f"{site.name}: {prose} prose prints, {table} tables of text: nothing to compare"


def test_figures_are_lossless_webp_with_the_notebooks_pixels(site):
    from PIL import Image, ImageChops

    assert list((site.out / "assets").glob("*.webp")), "no figure was converted to WebP"
    file = next(f for f in site.files if f.endswith(".ipynb"))
    page = site.page(file)
    shown = [page.path.parent / unquote(i["src"]) for i in page.soup.select("main img.output")]
    shown = [Image.open(p).convert("RGBA") for p in shown if p.suffix == ".webp"]
    outputs = [
        o["data"]["image/png"]
        for c in site.executed(file).cells
        if c.cell_type == "code"
        for o in c.get("outputs", [])
        if "image/png" in o.get("data", {})
    ]
    assert outputs and shown
    for blob in outputs:
        im = Image.open(io.BytesIO(base64.b64decode(blob))).convert("RGBA")
        same = [s for s in shown if s.size == im.size and ImageChops.difference(s, im).getbbox() is None]
        assert same, f"{page.url}: a PNG output of {file} is not shown with the same pixels"


def test_build_reports_each_pages_weight(site):
    weights = build_site.page_weights(site.out)
    assert set(weights) == {p.path.name for p in site.pages}
    for page, w in weights.items():
        assert w["total"] == w["html"] + w["img"] + w["script"] + w["css"]
        assert w["script"] < 120_000, f"{page}: {w['script']} bytes of script when it opens"


def test_figure_cells_keep_their_image_in_notebooks(site):
    """The executed notebook a page offers still holds PNGs (the site's WebP are for the pages only)."""
    file = next(f for f in site.files if f.endswith(".ipynb"))
    nb = nbformat.read(site.page(file).path.parent / site.page(file).download, as_version=4)
    assert any("image/png" in o.get("data", {}) for c in nb.cells if c.cell_type == "code" for o in c.outputs)


def test_every_page_links_the_books_pdf_which_the_build_wrote(site):
    pdf = site.out / build_site.PDF_NAME
    assert pdf.is_file() and pdf.read_bytes().startswith(b"%PDF-"), f"the build wrote no PDF at {pdf}"
    for page in site.pages:
        links = [a for a in page.soup.select("a[href]") if a["href"].split("#")[0] == build_site.PDF_NAME]
        assert links, f"{page.url}: no link to the book's PDF"
        assert all((page.path.parent / a["href"]).resolve() == pdf.resolve() for a in links)
