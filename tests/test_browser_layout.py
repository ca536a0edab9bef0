"""The page fits the reader, measured in headless Chromium on both sites (the book and the fixture).

At 1400 px the text column stays ~704 px and code cells, figures and tables use a wide frame up to
920 px (88 characters of code); figures of at most 920 px are shown at the size they were drawn; what
still scrolls sideways (at 1400 px and on a 390 px phone) shows the fade of the scroll cue; the copy
button never covers code; a figure opens at full size and closes; printing keeps tables whole and
folded code open; no page loads the search index before the search box is used.
"""

from __future__ import annotations

import json

import pytest
from test_browser import Browser
from test_site import SITE_PARAMS, built_site

DESKTOP = {"width": 1400, "height": 900, "deviceScaleFactor": 1, "mobile": False}
PHONE = {"width": 390, "height": 844, "deviceScaleFactor": 2, "mobile": True}
SCROLLERS = "main pre, main .table-wrap, main .output.html, main .image-frame"


@pytest.fixture(scope="module")
def browser():
    b = Browser()
    yield b
    b.close()


@pytest.fixture(scope="module", params=SITE_PARAMS)
def site(request):
    return built_site(request.param)


# Every image loaded now (they are lazy), then a moment for site.js to mark what scrolls.
LOAD_IMAGES = """Promise.all([...document.querySelectorAll('main img')].map(i => {
  i.loading = 'eager'; return i.decode().catch(() => 0); })).then(() => new Promise(r => setTimeout(r, 150)))"""


def _open(browser: Browser, page, metrics: dict, dark: bool = False) -> None:
    browser.send("Emulation.setDeviceMetricsOverride", **metrics)
    browser.send(
        "Emulation.setEmulatedMedia",
        features=[{"name": "prefers-color-scheme", "value": "dark" if dark else "light"}],
    )
    browser.open(page.path)
    browser.eval(LOAD_IMAGES)


def _reset(browser: Browser) -> None:
    browser.send("Emulation.setEmulatedMedia", media="", features=[])
    browser.send("Emulation.clearDeviceMetricsOverride")


def _chapters(site):
    return [site.page(f) for f in site.files if f.endswith(".ipynb")]


def _scrolling_without_cue(browser: Browser) -> list[str]:
    return browser.eval(f"""[...document.querySelectorAll({json.dumps(SCROLLERS)})]
        .filter(e => e.offsetParent && e.scrollWidth > e.clientWidth + 1)
        .filter(e => !/^(left|right|both)$/.test(e.dataset.overflow || '')
                     || getComputedStyle(e).maskImage === 'none')
        .map(e => e.className + ': ' + e.textContent.trim().slice(0, 50))""")


@pytest.mark.parametrize("metrics", [DESKTOP, PHONE], ids=["1400px", "phone"])
def test_nothing_scrolls_sideways_without_the_cue(browser, site, metrics):
    """Every code block, output, table and figure frame that scrolls sideways fades at its hidden edge."""
    scrolling = 0
    try:
        for page in site.pages:
            _open(browser, page, metrics)
            bad = _scrolling_without_cue(browser)
            assert not bad, f"{page.url} at {metrics['width']} px: scrolls with no cue: {bad[:3]}"
            scrolling += browser.eval(
                f"[...document.querySelectorAll({json.dumps(SCROLLERS)})]"
                ".filter(e => e.offsetParent && e.scrollWidth > e.clientWidth + 1).length"
            )
    finally:
        _reset(browser)
    if metrics is PHONE:
        assert scrolling, "on a phone nothing scrolls sideways: the cue was not exercised"


def test_the_cue_follows_the_scroll(browser, site):
    """Scrolled to its end, a long line's box fades on the left only; back at the start, on the right."""
    page = next(
        p
        for p in site.pages
        if any(len(ln) > 140 for pre in p.soup.select("main pre.code") for ln in pre.get_text().splitlines())
    )
    try:
        _open(browser, page, DESKTOP)
        js = """(() => { const pre = [...document.querySelectorAll('main pre.code')]
            .find(e => e.offsetParent && e.scrollWidth > e.clientWidth + 1);
          window.__pre = pre; return pre ? pre.dataset.overflow : null; })()"""
        assert browser.eval(js) == "right"
        browser.eval("window.__pre.scrollLeft = window.__pre.scrollWidth; new Promise(r => setTimeout(r, 100))")
        assert browser.eval("window.__pre.dataset.overflow") == "left"
        browser.eval("window.__pre.scrollLeft = 40; new Promise(r => setTimeout(r, 100))")
        assert browser.eval("window.__pre.dataset.overflow") == "both"
    finally:
        _reset(browser)


def test_text_column_and_wide_frame_at_1400px(browser, site):
    """Prose stays ~704 px; a code cell is 900-920 px wide and shows 88 characters without scrolling."""
    page = max(_chapters(site), key=lambda p: len(p.soup.select("main .cell pre.code")))
    try:
        _open(browser, page, DESKTOP)
        m = browser.eval("""(() => {
          const p = document.querySelector('main article > p');
          const cell = [...document.querySelectorAll('main .cell')].find(e => e.offsetParent);
          const pre = cell.querySelector('pre.code');
          const span = document.createElement('span');
          span.textContent = 'x'.repeat(88);
          pre.querySelector('code').appendChild(span);
          const cs = getComputedStyle(pre);
          const room = pre.clientWidth - parseFloat(cs.paddingLeft) - parseFloat(cs.paddingRight);
          const chars = span.getBoundingClientRect().width;
          span.remove();
          return {prose: p.getBoundingClientRect().width, cell: cell.getBoundingClientRect().width, room, chars,
                  font: parseFloat(cs.fontSize), overflow: document.documentElement.scrollWidth
                    - document.documentElement.clientWidth};
        })()""")
    finally:
        _reset(browser)
    assert 680 <= m["prose"] <= 710, f"{page.url}: the text column is {m['prose']} px wide"
    assert 900 <= m["cell"] <= 921, f"{page.url}: a code cell is {m['cell']} px wide at 1400 px"
    assert m["chars"] <= m["room"], f"{page.url}: 88 characters need {m['chars']} px, the code box has {m['room']}"
    assert m["font"] >= 13.5, f"code at {m['font']} px"
    assert m["overflow"] <= 0, "the page itself scrolls sideways"


@pytest.mark.parametrize("dark", [False, True], ids=["light", "dark"])
def test_figures_are_shown_at_their_drawn_size_at_1400px(browser, site, dark):
    """Every figure of at most 920 px (retina PNG: natural width / 2) is displayed at >= 0.98 of it."""
    checked = 0
    try:
        for page in _chapters(site):
            if not page.soup.select("main img.output"):
                continue
            _open(browser, page, DESKTOP, dark=dark)
            sizes = browser.eval("""[...document.querySelectorAll('main img.output')]
              .filter(i => i.naturalWidth && /\\.(png|webp)$/.test(i.src))
              .map(i => [i.getBoundingClientRect().width - parseFloat(getComputedStyle(i).paddingLeft)
                         - parseFloat(getComputedStyle(i).paddingRight), i.naturalWidth / 2,
                         +i.getAttribute('width'), i.src.split('/').pop()])""")
            for shown, drawn, attr, name in sizes:
                assert attr and abs(attr - drawn) <= 1, f"{page.url}: {name} width={attr}, drawn {drawn} px"
                assert shown <= drawn + 0.5, f"{page.url}: {name} enlarged to {shown} px (drawn {drawn})"
                if drawn <= 920:
                    checked += 1
                    assert shown / drawn >= 0.98, f"{page.url}: {name} shown at {shown:.0f} of {drawn:.0f} px"
    finally:
        _reset(browser)
    assert checked, "no figure of at most 920 px to check"


def test_a_figure_on_a_phone_scrolls_in_its_frame_with_a_cue(browser, site):
    """At 390 px a figure wider than the screen keeps its drawn size and its frame scrolls, with the cue."""
    page = next(p for p in _chapters(site) if p.soup.select("main figure img.output"))
    try:
        _open(browser, page, PHONE)
        m = browser.eval("""(() => {
          const img = [...document.querySelectorAll('main figure img.output')]
            .find(i => i.naturalWidth / 2 > document.documentElement.clientWidth);
          if (!img) return null;
          const frame = img.closest('.image-frame');
          const before = frame.dataset.overflow;
          return {shown: img.getBoundingClientRect().width, drawn: img.naturalWidth / 2, before,
                  frame: frame.clientWidth, scroll: frame.scrollWidth,
                  page: document.documentElement.scrollWidth - document.documentElement.clientWidth};
        })()""")
        assert m, f"{page.url}: no figure wider than a phone"
        assert m["shown"] / m["drawn"] >= 0.98, f"{page.url}: on a phone a figure is shrunk to {m['shown']} px"
        assert m["scroll"] > m["frame"] + 1 and m["before"] == "right", m
        assert m["page"] <= 0, "the page itself scrolls sideways on a phone"
        browser.eval("""(() => { const f = [...document.querySelectorAll('main figure .image-frame')]
            .find(f => f.scrollWidth > f.clientWidth + 1); window.__f = f; f.scrollLeft = f.scrollWidth; })();
            new Promise(r => setTimeout(r, 100))""")
        assert browser.eval("window.__f.dataset.overflow") == "left"
    finally:
        _reset(browser)


def test_copy_button_shows_on_hover_or_focus_and_never_covers_code(browser, site):
    """The copy button overlaps no line of its code box (at scroll 0); hidden until hover or focus."""
    checked = 0
    try:
        for metrics in (DESKTOP, PHONE):
            for page in [p for p in site.pages if p.soup.select("main pre.code")][:8]:
                _open(browser, page, metrics)
                hits = browser.eval("""[...document.querySelectorAll('main .code-box')].filter(b => b.offsetParent)
                  .map(box => {
                    const b = box.querySelector('button.copy').getBoundingClientRect();
                    const code = box.querySelector('pre code');
                    const r = document.createRange(); r.selectNodeContents(code);
                    const lines = [...r.getClientRects()].filter(l => l.width > 0 && l.height > 0);
                    const hit = lines.some(l => l.left < b.right && l.right > b.left
                                                && l.top < b.bottom && l.bottom > b.top);
                    return hit ? code.textContent.split('\\n')[0].slice(0, 60) : null;
                  }).filter(Boolean)""")
                assert not hits, f"{page.url} at {metrics['width']} px: the copy button covers {hits[:2]}"
                checked += browser.eval("document.querySelectorAll('main .code-box').length")
        page = next(p for p in site.pages if p.soup.select("main pre.code"))
        _open(browser, page, DESKTOP)
        sel = "[...document.querySelectorAll('main .code-box')].find(b => b.offsetParent)"
        # hidden until hover or focus where there is a mouse; always shown on touch screens (headless: none)
        hover = browser.eval("matchMedia('(hover: hover)').matches")
        assert browser.eval(f"getComputedStyle({sel}.querySelector('button.copy')).opacity") == ("0" if hover else "1")
        browser.eval(f"{sel}.querySelector('button.copy').focus()")
        browser.eval("new Promise(r => setTimeout(r, 300))")
        assert browser.eval(f"getComputedStyle({sel}.querySelector('button.copy')).opacity") == "1"
    finally:
        _reset(browser)
    assert checked


def test_a_figure_opens_full_size_and_closes(browser, site):
    """Click opens a figure in an overlay at least as large as shown; Escape and a click close it, Enter
    on the focused figure opens it, and the focus returns to the figure."""
    page = next(p for p in _chapters(site) if p.soup.select("main figure img"))
    try:
        _open(browser, page, DESKTOP)
        browser.eval("window.__img = document.querySelector('main figure img.zoomable'); __img.scrollIntoView()")
        assert browser.eval("__img.tabIndex") == 0 and browser.eval("__img.getAttribute('role')") == "button"
        browser.eval("__img.click()")
        m = browser.eval("""(() => { const o = document.querySelector('.figure-overlay');
          return o && {big: o.querySelector('img').getBoundingClientRect().width,
                       shown: __img.getBoundingClientRect().width, modal: o.getAttribute('aria-modal'),
                       focus: document.activeElement.getAttribute('aria-label')}; })()""")
        assert m and m["big"] >= m["shown"] - 0.5 and m["modal"] == "true", m
        assert m["focus"] == "Close the figure"
        browser.send("Input.dispatchKeyEvent", type="keyDown", key="Escape", code="Escape", windowsVirtualKeyCode=27)
        assert browser.eval("!document.querySelector('.figure-overlay')"), "Escape does not close the figure"
        assert browser.eval("document.activeElement === __img"), "the focus does not return to the figure"
        browser.send("Input.dispatchKeyEvent", type="keyDown", key="Enter", code="Enter", windowsVirtualKeyCode=13)
        assert browser.eval("!!document.querySelector('.figure-overlay')"), "Enter does not open the figure"
        browser.eval("document.querySelector('.figure-overlay').click()")
        assert browser.eval("!document.querySelector('.figure-overlay')"), "a click does not close the figure"
    finally:
        _reset(browser)


def test_print_keeps_tables_whole_and_folded_code_open(browser, site):
    """Printed: no table is cut (scrollWidth <= clientWidth), folded code is shown and its button is not."""
    try:
        for page in site.pages:
            if not page.soup.select("main table, main details"):
                continue
            _open(browser, page, {"width": 1280, "height": 900, "deviceScaleFactor": 1, "mobile": False})
            browser.send("Emulation.setEmulatedMedia", media="print")
            browser.eval("new Promise(r => setTimeout(r, 100))")
            cut = browser.eval("""[...document.querySelectorAll('main .table-wrap, main .output.html, main table')]
                .filter(e => e.offsetParent && e.scrollWidth > e.clientWidth + 1)
                .map(e => e.className + ': ' + e.textContent.trim().slice(0, 40))""")
            assert not cut, f"{page.url}: printed tables cut: {cut[:2]}"
            folded = browser.eval("""[...document.querySelectorAll('main details')].map(d => [
                [...d.children].filter(c => c.tagName !== 'SUMMARY').every(c => c.getBoundingClientRect().height > 0),
                [...d.querySelectorAll(':scope > summary')].every(s => getComputedStyle(s).display === 'none')])""")
            assert all(shown for shown, _ in folded), f"{page.url}: folded content is not printed"
            assert all(hidden for _, hidden in folded), f"{page.url}: a 'Show code' button is printed"
            browser.send("Emulation.setEmulatedMedia", media="")
    finally:
        _reset(browser)


def test_no_page_loads_the_search_index_on_opening(browser, site):
    """The search index and MiniSearch are not loaded before the search box is used."""
    try:
        for page in site.pages[:6]:
            browser.events.clear()
            _open(browser, page, DESKTOP)
            loaded = [u for u in browser.requested_urls() if u.endswith(("search-index.js", "minisearch.js"))]
            assert not loaded, f"{page.url} loads {loaded} when it opens"
            assert browser.eval("typeof window.BOOK_SEARCH") == "undefined"
            assert browser.eval("!!document.querySelector('script[src$=\"search.js\"]')")
    finally:
        _reset(browser)
