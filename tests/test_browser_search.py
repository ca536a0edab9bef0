"""The search box in headless Chromium, on the book and on the fixture site (static/search.js).

Nothing of the search is loaded before the box is used: no request for minisearch.js or
search-index.js until it is focused, and then the search works. Results are grouped by page with a
snippet in which the query's word is marked; the arrow keys move the selection and Enter opens it;
Escape closes the list. On the book, the issue's queries ("C3D", "jacobian", "SPARC", "contact
speed", "dask") list a chapter (or a docs page) before any API entry. The list is readable: wide
enough beside the sidebar on a desktop, inside the screen on a phone, its marks and selection
contrasted in light and dark.
"""

from __future__ import annotations

import json
import re
import time

import pytest
from test_browser import Browser
from test_site import SITE_PARAMS, _search_data, built_site

SEARCH_FILES = ("_static/minisearch.js", "_static/search-index.js")
RESULTS = "#search-results a.search-result"


@pytest.fixture(scope="module")
def browser():
    b = Browser()
    yield b
    b.close()


@pytest.fixture(scope="module", params=SITE_PARAMS)
def site(request):
    return built_site(request.param)


def _kinds(book) -> dict[str, str]:
    """Page URL -> its kind (chapter, docs, api) as the index states it."""
    return {p["url"]: p["kind"] for p in _search_data(book)["pages"]}


def _a_word_in(book, kind: str = "chapter") -> str:
    """A long word of the text of a page of `kind` that is in few sections (a distinctive query)."""
    data = _search_data(book)
    counts: dict[str, int] = {}
    for sec in data["sections"]:
        for w in set(re.findall(r"[a-z]{7,}", sec[3].lower())):
            counts[w] = counts.get(w, 0) + 1
    words = [
        w
        for sec in data["sections"]
        if data["pages"][sec[0]]["kind"] == kind
        for w in re.findall(r"[a-z]{7,}", sec[3].lower())
        if 2 <= counts[w] <= 4
    ]
    if not words:
        pytest.skip(f"the {book.name} site has no {kind} page with a distinctive word")
    return sorted(words)[len(words) // 2]


def _type(b: Browser, query: str) -> None:
    """Focus the box (that loads the index), type `query`, wait for the list to answer."""
    b.eval("(() => { const i = document.getElementById('search-input'); i.focus(); i.value = ''; })()")
    b.send("Input.insertText", text=query)
    b.wait_for(
        f"document.querySelector({json.dumps(RESULTS)}) || "
        "[...document.querySelectorAll('#search-results .search-none')].some(e => !/Loading/.test(e.textContent))"
    )


def _key(b: Browser, key: str) -> None:
    codes = {"ArrowDown": 40, "ArrowUp": 38, "Enter": 13, "Escape": 27}
    for kind in ("rawKeyDown", "keyUp"):
        b.send("Input.dispatchKeyEvent", type=kind, key=key, code=key, windowsVirtualKeyCode=codes[key])


def _click(b: Browser, selector: str) -> None:
    x, y = b.eval(
        f"(r => [r.left + r.width / 2, r.top + r.height / 2])(document.querySelector({json.dumps(selector)})"
        ".getBoundingClientRect())"
    )
    for kind in ("mousePressed", "mouseReleased"):
        b.send("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left", clickCount=1)


def _results(b: Browser) -> list[dict]:
    return b.eval(
        f"""[...document.querySelectorAll({json.dumps(RESULTS)})].map(a => ({{
            href: a.getAttribute('href'), id: a.id, selected: a.getAttribute('aria-selected') === 'true',
            section: a.querySelector('.search-section').textContent,
            group: a.closest('.search-group').querySelector('.search-page').firstChild.textContent,
            marks: [...a.querySelectorAll('mark')].map(m => m.textContent),
            snippetMarks: [...a.querySelectorAll('.search-snippet mark')].map(m => m.textContent),
            snippet: (a.querySelector('.search-snippet') || {{textContent: ''}}).textContent }}))"""
    )


def _search_requests(b: Browser) -> list[str]:
    return [u for u in b.requested_urls() if u.endswith(SEARCH_FILES)]


def test_the_index_is_loaded_when_the_box_is_first_used(browser, site):
    browser.events.clear()
    browser.open(site.out / "index.html")
    time.sleep(0.3)  # anything the page loads by itself has been asked for by now
    assert browser.requested_urls(), "no request seen: the Network domain is not reporting"
    assert _search_requests(browser) == [], "the search files are loaded before the search box is used"
    assert browser.eval("typeof window.BOOK_SEARCH === 'undefined' && typeof window.MiniSearch === 'undefined'")
    # Clicking into the box loads both files (from file://, as <script> tags) and builds the index.
    if not browser.eval(
        "document.getElementById('search-input').getBoundingClientRect().width > 0 && "
        "getComputedStyle(document.getElementById('sidebar')).transform === 'none'"
    ):
        _click(browser, "#nav-toggle")  # a narrow window: the box is in the contents menu
        time.sleep(0.3)
    _click(browser, "#search-input")
    browser.wait_for("window.BOOK_SEARCH_READY === true")
    assert sorted(u.rsplit("/", 1)[-1] for u in _search_requests(browser)) == ["minisearch.js", "search-index.js"]
    word = _a_word_in(site)
    _type(browser, word)
    assert _results(browser), f"searching {word!r} listed nothing once the index was loaded"
    # Another page: again nothing until the box is used; the "/" key (site.js focuses the box) loads it.
    browser.events.clear()
    browser.open(site.pages[-1].path)
    time.sleep(0.3)
    assert _search_requests(browser) == []
    browser.send("Input.dispatchKeyEvent", type="keyDown", key="/", code="Slash", text="/", windowsVirtualKeyCode=191)
    browser.send("Input.dispatchKeyEvent", type="keyUp", key="/", code="Slash", windowsVirtualKeyCode=191)
    browser.wait_for("window.BOOK_SEARCH_READY === true")
    assert browser.eval("document.activeElement.id") == "search-input"
    assert browser.eval("document.getElementById('search-input').value") == "", "the '/' was typed into the box"


def test_results_are_grouped_by_page_with_the_query_marked(browser, site):
    word = _a_word_in(site)
    browser.open(site.out / "index.html")
    _type(browser, word)
    results = _results(browser)
    assert results, f"searching {word!r} listed nothing"
    # grouped: each page's title once, and its sections together under it
    groups = browser.eval(
        "[...document.querySelectorAll('#search-results .search-group')]"
        ".map(g => g.querySelector('.search-page').firstChild.textContent)"
    )
    assert len(groups) == len(set(groups)), f"a page heads two groups: {groups}"
    pages_of_hits = [r["href"].split("#")[0] for r in results]
    for url in set(pages_of_hits):
        first, last = pages_of_hits.index(url), len(pages_of_hits) - pages_of_hits[::-1].index(url)
        assert set(pages_of_hits[first:last]) == {url}, f"the sections of {url} are not listed together"
    titles = {p.url: p.title for p in site.pages}
    for r in results:
        assert r["group"] == titles[r["href"].split("#")[0]], f"{r['href']} listed under {r['group']!r}"
    # every result marks what it matched (a word, or a near one), the first the word itself in its snippet
    for r in results:
        assert r["marks"], f"{r['href']}: nothing marked in {r}"
    first = results[0]
    assert any(m.lower().startswith(word) for m in first["snippetMarks"]), f"no marked {word!r} in {first['snippet']!r}"
    assert len(first["snippet"]) <= 260, "a snippet is an excerpt, not the section"
    # the snippet is the target page's text: its marked word is there, and the anchor exists
    href = first["href"]
    browser.eval(f"document.querySelector('#{first['id']}').click()")
    browser.wait_for(f"location.href.endsWith({json.dumps(href)})")
    browser.wait_for("document.readyState === 'complete'")
    if "#" in href:
        assert browser.eval(f"!!document.getElementById({json.dumps(href.split('#')[1])})"), f"{href}: no such anchor"
    assert word in browser.eval("document.querySelector('main').textContent.toLowerCase()")


def test_arrow_keys_move_the_selection_and_enter_opens_it(browser, site):
    word = "the"  # in every section: many results
    browser.open(site.out / "index.html")
    _type(browser, word)
    results = _results(browser)
    assert len(results) >= 3, f"searching {word!r} listed {len(results)} sections"
    assert [r["selected"] for r in results].count(True) == 1 and results[0]["selected"], "the first is not chosen"
    active = "document.getElementById('search-input').getAttribute('aria-activedescendant')"
    assert browser.eval(active) == results[0]["id"]
    _key(browser, "ArrowDown")
    _key(browser, "ArrowDown")
    now = _results(browser)
    assert [r["selected"] for r in now] == [i == 2 for i in range(len(now))], "two ArrowDown do not choose the third"
    assert browser.eval(active) == now[2]["id"]
    _key(browser, "ArrowUp")
    assert [r["selected"] for r in _results(browser)].index(True) == 1
    _key(browser, "ArrowUp")
    _key(browser, "ArrowUp")  # from the first: round to the last
    assert [r["selected"] for r in _results(browser)].index(True) == len(now) - 1
    _key(browser, "ArrowDown")  # and back to the first
    _key(browser, "ArrowDown")
    # the caret stays in the box, and the chosen result is visible in the list
    assert browser.eval("document.activeElement.id") == "search-input"
    assert browser.eval(
        "(() => { const a = document.querySelector('#search-results a.selected');"
        " const r = a.getBoundingClientRect(), b = document.getElementById('search-results').getBoundingClientRect();"
        " return r.top >= b.top - 1 && r.bottom <= b.bottom + 1; })()"
    )
    # Escape closes the list and keeps the query; a second Escape clears it
    _key(browser, "Escape")
    assert browser.eval("document.getElementById('search-results').hidden")
    assert browser.eval("document.getElementById('search-input').getAttribute('aria-expanded')") == "false"
    assert browser.eval("document.getElementById('search-input').value") == word
    _key(browser, "Escape")
    assert browser.eval("document.getElementById('search-input').value") == ""
    # Enter opens the chosen result (here the second)
    _type(browser, word)
    _key(browser, "ArrowDown")
    target = _results(browser)[1]["href"]
    _key(browser, "Enter")
    browser.wait_for(f"location.href.endsWith({json.dumps(target)})")
    # Enter with nothing chosen by the keys opens the first
    browser.open(site.out / "index.html")
    _type(browser, word)
    target = _results(browser)[0]["href"]
    _key(browser, "Enter")
    browser.wait_for(f"location.href.endsWith({json.dumps(target)})")


ISSUE_QUERIES = ["C3D", "jacobian", "SPARC", "contact speed", "dask"]
# "C3D" is what the input-format page ("The input formats", a docs page) is about: there a docs page
# may come first; a chapter must still come before any API entry.
DOCS_MAY_LEAD = {"C3D"}


@pytest.mark.parametrize("query", ISSUE_QUERIES)
def test_the_issue_queries_put_a_chapter_before_the_api(browser, site, query):
    if site.name != "book":
        pytest.skip("the issue's queries are about the book")
    kinds = _kinds(site)
    assert "api" in kinds.values(), "the index marks no page as API reference"
    browser.open(site.out / "index.html")
    _type(browser, query)
    top = [kinds[r["href"].split("#")[0]] for r in _results(browser)[:6]]
    assert top, f"{query!r} found nothing"
    assert top[0] == "chapter" or (query in DOCS_MAY_LEAD and top[0] == "docs"), f"{query!r}: top 6 are {top}"
    assert "chapter" in top, f"{query!r}: no chapter in the top 6 ({top})"
    if "api" in top:
        assert top.index("chapter") < top.index("api"), f"{query!r}: an API entry before the chapters ({top})"
    # words of the query are marked in the first result
    first = _results(browser)[0]
    for w in query.lower().split():
        assert any(m.lower().startswith(w) for m in first["marks"]), f"{query!r}: {w!r} not marked in {first}"


def test_short_words_are_not_fuzzy(browser, site):
    """A four-letter query finds that word, not its one-letter neighbours ("dask" is not "task")."""
    if site.name != "book":
        pytest.skip("about the book's words")
    browser.open(site.out / "index.html")
    _type(browser, "dask")
    for r in _results(browser):
        assert any(m.lower().startswith("dask") for m in r["marks"]), f"'dask' listed {r['href']}: {r['marks']}"


def _contrast(fg: str, bg: str) -> float:
    def lum(css: str) -> float:
        r, g, b = (int(x) / 255 for x in re.findall(r"[\d.]+", css)[:3])
        lin = [c / 12.92 if c <= 0.03928 else ((c + 0.055) / 1.055) ** 2.4 for c in (r, g, b)]
        return 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]

    hi, lo = sorted((lum(fg), lum(bg)), reverse=True)
    return (hi + 0.05) / (lo + 0.05)


@pytest.mark.parametrize("scheme", ["light", "dark"])
def test_the_list_is_readable_on_desktop_and_phone(browser, site, scheme):
    word = _a_word_in(site)
    browser.send("Emulation.setEmulatedMedia", features=[{"name": "prefers-color-scheme", "value": scheme}])
    try:
        # Desktop: the list floats over the text, wider than the sidebar, inside the window, not clipped.
        browser.send("Emulation.setDeviceMetricsOverride", width=1400, height=900, deviceScaleFactor=1, mobile=False)
        browser.open(site.out / "index.html")
        _type(browser, word)
        box = browser.eval(
            "(() => { const r = document.getElementById('search-results').getBoundingClientRect();"
            " const s = document.getElementById('sidebar').getBoundingClientRect();"
            " return {left: r.left, right: r.right, width: r.width, bottom: r.bottom, sidebar: s.right}; })()"
        )
        assert box["width"] >= 480 and box["right"] > box["sidebar"] + 100, f"narrower than the sidebar: {box}"
        assert box["right"] <= 1400 and box["bottom"] <= 900, f"the list leaves the window: {box}"
        hit = browser.eval(
            f"(() => {{ const e = document.elementFromPoint({box['right'] - 20}, "
            "document.querySelector('#search-results a.search-result').getBoundingClientRect().top + 8);"
            " return !!e && !!e.closest('#search-results'); })()"
        )
        assert hit, "the list's right part is covered or clipped"
        colors = browser.eval(
            "(() => { const cs = (e) => getComputedStyle(e), l = document.getElementById('search-results');"
            " const m = l.querySelector('mark'), a = l.querySelector('a.selected');"
            " const s = l.querySelector('.search-snippet');"
            " return {mark: [cs(m).color, cs(m).backgroundColor], sel: cs(a).backgroundColor,"
            "  list: cs(l).backgroundColor, snippet: cs(s).color, border: cs(a).borderLeftColor}; })()"
        )
        assert _contrast(*colors["mark"]) >= 4.5, f"marked text hard to read ({scheme}): {colors}"
        assert _contrast(colors["snippet"], colors["list"]) >= 4.5, f"snippet text hard to read ({scheme}): {colors}"
        assert colors["sel"] != colors["list"] and _contrast(colors["border"], colors["sel"]) >= 3, (
            f"the chosen result is not shown ({scheme}): {colors}"
        )
        # Phone: the list stays inside the open contents menu and the screen.
        browser.send("Emulation.setDeviceMetricsOverride", width=390, height=844, deviceScaleFactor=2, mobile=True)
        browser.open(site.out / "index.html")
        browser.eval("document.getElementById('nav-toggle').click()")
        _type(browser, word)
        assert _results(browser)
        right = browser.eval("document.getElementById('search-results').getBoundingClientRect().right")
        width = browser.eval("(l => l.scrollWidth - l.clientWidth)(document.getElementById('search-results'))")
        assert right <= 390 and width <= 1, f"the list is cut on a phone: right {right}, scrolls {width} px"
        # Escape closes the list only, not the menu around it
        _key(browser, "Escape")
        assert browser.eval("document.body.classList.contains('nav-open')")
    finally:
        browser.send("Emulation.clearDeviceMetricsOverride")
        browser.send("Emulation.setEmulatedMedia", features=[])
