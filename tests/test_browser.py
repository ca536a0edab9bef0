"""The built site in a real browser: headless Chromium opens pages from file:// (no server).

Checks what only a browser can: KaTeX math is laid out with its local fonts, the search box finds a
word and links to its page, nothing is requested from the network, on a phone-sized screen the
contents collapse behind the menu button; the outline marks the section in view, copy buttons copy,
dark mode follows the system and the switch, references preview their targets on hover, and a printed
page keeps every line of code. Chapter 1 in JupyterLab (`make lab`) is in tests/test_jupyterlab.py.
Chromium is driven over the DevTools protocol (websocket-client); skipped only when no Chromium is
installed (CI installs Debian's).
"""

from __future__ import annotations

import base64
import json
import os
import re
import shutil
import subprocess
import tempfile
import time
import urllib.request
from pathlib import Path

import pytest
from test_site import SITE_PARAMS, built_site

websocket = pytest.importorskip("websocket", reason="websocket-client is needed to drive Chromium")

CHROMIUM = os.environ.get("CHROMIUM") or next(
    (
        p
        for p in (shutil.which("chromium"), shutil.which("chromium-browser"), "/usr/bin/chromium")
        if p and Path(p).exists()
    ),
    None,
)
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="no Chromium found (apt-get install chromium)")

FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--disable-extensions",
    "--remote-debugging-port=0",
    "--remote-allow-origins=*",
]


class Browser:
    """A headless Chromium with one page, spoken to over the DevTools protocol."""

    def __init__(self) -> None:
        self.profile = tempfile.mkdtemp(prefix="book-chromium-")
        self.proc = subprocess.Popen(
            [CHROMIUM, *FLAGS, f"--user-data-dir={self.profile}", "about:blank"],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        port_file = Path(self.profile) / "DevToolsActivePort"
        deadline = time.monotonic() + 30
        while not port_file.exists() or not port_file.read_text().strip():
            if time.monotonic() > deadline or self.proc.poll() is not None:
                self.close()
                raise RuntimeError("Chromium did not start its DevTools endpoint")
            time.sleep(0.05)
        port = port_file.read_text().split()[0]
        targets = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=10))
        page = next(t for t in targets if t["type"] == "page")
        self.ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=30, suppress_origin=True)
        self.next_id = 0
        self.events: list[dict] = []
        self.send("Page.enable")
        self.send("Network.enable")

    def send(self, method: str, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == self.next_id:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})
            self.events.append(msg)

    def eval(self, expression: str):
        res = self.send("Runtime.evaluate", expression=expression, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in res:
            raise RuntimeError(f"{expression!r} raised {res['exceptionDetails']}")
        return res["result"].get("value")

    def open(self, path: Path) -> None:
        self.send("Page.navigate", url=path.resolve().as_uri())
        self.wait_for("document.readyState === 'complete' && !!document.querySelector('main')")
        self.eval("document.fonts.ready.then(() => true)")

    def wait_for(self, expression: str, timeout: float = 15) -> None:
        deadline = time.monotonic() + timeout
        while True:
            try:
                if self.eval(f"!!({expression})"):
                    return
            except RuntimeError as err:  # the page navigated while the expression ran: ask the new one
                if "navigated or closed" not in str(err) and "context was destroyed" not in str(err):
                    raise
            if time.monotonic() > deadline:
                raise AssertionError(f"timed out waiting for {expression}")
            time.sleep(0.05)

    def requested_urls(self) -> list[str]:
        return [e["params"]["request"]["url"] for e in self.events if e.get("method") == "Network.requestWillBeSent"]

    def close(self) -> None:
        try:
            self.ws.close()
        except Exception:
            pass
        self.proc.terminate()
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        shutil.rmtree(self.profile, ignore_errors=True)


@pytest.fixture(scope="module")
def browser():
    b = Browser()
    yield b
    b.close()


@pytest.fixture(scope="module", params=SITE_PARAMS)
def site(request):
    return built_site(request.param)


def _page_with_math(site):
    page = next((p for p in site.pages if 'class="katex' in p.html), None)
    if page is None:
        pytest.skip(f"no page of the {site.name} site has math")
    return page


def test_math_is_laid_out_with_katex_fonts(browser, site):
    page = _page_with_math(site)
    browser.open(page.path)
    assert browser.eval("document.querySelectorAll('.katex').length") > 0
    # The KaTeX fonts load from _static/katex/fonts over file://: the math font is available.
    assert browser.eval("document.fonts.check('16px KaTeX_Main') && document.fonts.check('16px KaTeX_Math')")
    assert browser.eval("[...document.fonts].some(f => f.family.includes('KaTeX') && f.status === 'loaded')")
    width = browser.eval("document.querySelector('.katex .katex-html').getBoundingClientRect().width")
    assert width > 5


def _a_word_of(page) -> str:
    """A distinctive word of a page's title to search for."""
    words = [w for w in re.findall(r"[A-Za-z]{5,}", page.title) if w.lower() not in {"their", "about", "which"}]
    return max(words, key=len) if words else page.title.split()[0]


def test_search_finds_a_word_and_links_its_page(browser, site):
    target = site.pages[-1]
    word = _a_word_of(target)
    browser.open(site.out / "index.html")
    browser.eval("(() => { const i = document.getElementById('search-input'); i.focus(); i.value = ''; })()")
    browser.send("Input.insertText", text=word.lower())
    browser.wait_for("document.querySelectorAll('#search-results a.search-result').length > 0")
    hrefs = browser.eval("[...document.querySelectorAll('#search-results a')].map(a => a.getAttribute('href'))")
    assert any(h.split("#")[0] == target.url for h in hrefs), f"searching {word!r} did not list {target.url}: {hrefs}"
    # Following the first result opens a page of the site.
    browser.eval("document.querySelector('#search-results a').click()")
    browser.wait_for(
        f"location.href.endsWith({json.dumps(hrefs[0].split('#')[0])}) || location.href.includes({json.dumps(hrefs[0])})"
    )


def test_pages_request_nothing_from_the_network(browser, site):
    browser.events.clear()
    for page in site.pages:
        browser.open(page.path)
    urls = browser.requested_urls()
    assert urls, "no request seen: the Network domain is not reporting"
    remote = [u for u in urls if not u.startswith(("file:", "data:", "about:"))]
    assert not remote, f"pages requested from the network: {remote[:5]}"
    failed = [e["params"] for e in browser.events if e.get("method") == "Network.loadingFailed"]
    assert not failed, f"resources that failed to load: {failed[:3]}"


def test_phone_width_collapses_the_contents(browser, site):
    browser.send("Emulation.setDeviceMetricsOverride", width=390, height=844, deviceScaleFactor=2, mobile=True)
    try:
        browser.open(site.out / site.pages[-1].url)
        sidebar_right = "document.getElementById('sidebar').getBoundingClientRect().right"
        assert browser.eval(sidebar_right) <= 0, "the contents cover the text on a phone"
        assert browser.eval("getComputedStyle(document.getElementById('nav-toggle')).display") != "none"
        assert browser.eval("document.documentElement.scrollWidth") <= 390, "the page scrolls sideways on a phone"
        browser.eval("document.getElementById('nav-toggle').click()")
        browser.wait_for(f"{sidebar_right} > 200")
        assert browser.eval("document.getElementById('nav-toggle').getAttribute('aria-expanded')") == "true"
    finally:
        browser.send("Emulation.clearDeviceMetricsOverride")


# ---------------------------------------------------------------- outline, copy, dark mode, previews, print --


def _page_with_most_sections(site):
    return max(site.pages, key=lambda p: len(p.soup.select("nav#outline a")))


def test_outline_is_beside_the_text_and_marks_the_section_in_view(browser, site):
    page = _page_with_most_sections(site)
    n = len(page.soup.select("nav#outline a"))
    if n < 2:
        pytest.skip(f"no page of the {site.name} site has two sections")
    browser.send("Emulation.setDeviceMetricsOverride", width=1440, height=900, deviceScaleFactor=1, mobile=False)
    try:
        browser.open(page.path)
        assert browser.eval("document.querySelector('#outline details').open"), "the outline is closed on a wide screen"
        right_of_text = browser.eval(
            "document.getElementById('outline').getBoundingClientRect().left >= "
            "document.querySelector('main article').getBoundingClientRect().right"
        )
        assert right_of_text, "the outline is not beside the text"
        for k in (n - 1, n // 2, 1):
            browser.eval(f"""(() => {{ const a = document.querySelectorAll('#outline a')[{k}];
                document.getElementById(decodeURIComponent(a.getAttribute('href').slice(1))).scrollIntoView(); }})()""")
            browser.wait_for(f"document.querySelectorAll('#outline a')[{k}].classList.contains('active')")
            assert browser.eval("document.querySelectorAll('#outline a.active').length") == 1
            assert (
                browser.eval(f"document.querySelectorAll('#outline a')[{k}].getAttribute('aria-current')") == "location"
            )
    finally:
        browser.send("Emulation.clearDeviceMetricsOverride")


def test_outline_is_collapsed_above_the_text_on_a_phone(browser, site):
    page = _page_with_most_sections(site)
    browser.send("Emulation.setDeviceMetricsOverride", width=390, height=844, deviceScaleFactor=2, mobile=True)
    try:
        browser.open(page.path)
        assert browser.eval("document.querySelector('#outline details').open") is False
        assert browser.eval(
            "document.getElementById('outline').getBoundingClientRect().bottom <= "
            "document.querySelector('main h1').getBoundingClientRect().top"
        ), "the outline is not above the text"
        browser.eval("document.querySelector('#outline summary').click()")
        assert browser.eval("document.querySelector('#outline details').open") is True
        assert browser.eval("document.querySelector('#outline a').getBoundingClientRect().height") > 0
        assert browser.eval("document.documentElement.scrollWidth") <= 390
    finally:
        browser.send("Emulation.clearDeviceMetricsOverride")


def test_copy_button_copies_its_code(browser, site):
    page = next(p for p in site.pages if p.soup.select("main button.copy"))
    browser.open(page.path)
    for index in (0, -1):
        code = browser.eval(
            f"[...document.querySelectorAll('main button.copy')].at({index}).parentNode.querySelector('pre').textContent"
        )
        browser.eval(
            f"window.BOOK_LAST_COPY = null; [...document.querySelectorAll('main button.copy')].at({index}).click()"
        )
        browser.wait_for("window.BOOK_LAST_COPY !== null")
        assert browser.eval("window.BOOK_LAST_COPY") == code.rstrip("\n")
        label = browser.eval(f"[...document.querySelectorAll('main button.copy')].at({index}).textContent")
        assert label in ("Copied", "Press Ctrl+C"), label


def _luminance(rgb: str) -> float:
    r, g, b = (int(x) / 255 for x in re.findall(r"\d+", rgb)[:3])
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def test_dark_mode_follows_the_system_and_the_switch(browser, site):
    page = next((p for p in site.pages if p.soup.select("main img")), site.pages[0])
    bg = "getComputedStyle(document.body).backgroundColor"
    try:
        browser.send("Emulation.setEmulatedMedia", features=[{"name": "prefers-color-scheme", "value": "light"}])
        browser.open(page.path)
        browser.eval("localStorage.removeItem('book-theme'); delete document.documentElement.dataset.theme")
        assert _luminance(browser.eval(bg)) > 0.9
        browser.send("Emulation.setEmulatedMedia", features=[{"name": "prefers-color-scheme", "value": "dark"}])
        browser.open(page.path)
        assert _luminance(browser.eval(bg)) < 0.15, "the system's dark setting is not followed"
        assert _luminance(browser.eval("getComputedStyle(document.body).color")) > 0.7
        if page.soup.select("main img"):  # figures keep a white card
            assert (
                _luminance(browser.eval("getComputedStyle(document.querySelector('main img')).backgroundColor")) > 0.95
            )
        browser.eval("document.getElementById('theme-toggle').click()")  # the reader's choice: light
        assert _luminance(browser.eval(bg)) > 0.9
        browser.open(page.path)  # the choice holds on the next page load, before the first paint
        assert browser.eval("document.documentElement.dataset.theme") == "light" and _luminance(browser.eval(bg)) > 0.9
        browser.eval("document.getElementById('theme-toggle').click()")
        assert _luminance(browser.eval(bg)) < 0.15
    finally:
        browser.eval("localStorage.removeItem('book-theme')")
        browser.send("Emulation.setEmulatedMedia", features=[])


def _hover(browser, selector: str) -> None:
    browser.eval(f"document.querySelector({json.dumps(selector)}).scrollIntoView({{block: 'center'}})")
    x, y = browser.eval(f"""(() => {{ const r = document.querySelector({json.dumps(selector)}).getBoundingClientRect();
        return [r.left + r.width / 2, r.top + r.height / 2]; }})()""")
    browser.send("Input.dispatchMouseEvent", type="mouseMoved", x=0, y=0)  # a move onto the link from elsewhere
    browser.send("Input.dispatchMouseEvent", type="mouseMoved", x=x, y=y)


def test_hovering_a_reference_previews_its_target(browser, site):
    page = next(p for p in site.pages if p.soup.select('main a.xref[data-xref*="#fig-"]'))
    key = page.soup.select_one('main a.xref[data-xref*="#fig-"]')["data-xref"]
    caption = (
        site.page(next(p.file for p in site.pages if p.url == key.split("#")[0]))
        .soup.find(id=key.split("#")[1])
        .find("figcaption")
        .get_text(" ", strip=True)
    )
    browser.send("Emulation.setDeviceMetricsOverride", width=1440, height=900, deviceScaleFactor=1, mobile=False)
    try:
        browser.open(page.path)
        _hover(browser, f'main a.xref[data-xref="{key}"]')
        browser.wait_for("document.querySelector('.preview') && document.querySelector('.preview').offsetHeight > 0")
        assert browser.eval("!!document.querySelector('.preview img')")
        assert caption[:40].replace("\xa0", " ") in browser.eval(
            "document.querySelector('.preview').textContent.replace(/\\s+/g, ' ')"
        )
        inside = browser.eval("""(() => { const r = document.querySelector('.preview').getBoundingClientRect();
            return r.left >= 0 && r.right <= innerWidth; })()""")
        assert inside, "the preview runs off the screen"
        browser.send("Input.dispatchMouseEvent", type="mouseMoved", x=2, y=2)
        browser.wait_for("!document.querySelector('.preview')")
        cited = next((p for p in site.pages if p.soup.select("main a.cite")), None)
        if cited is not None:  # a citation previews its reference
            browser.open(cited.path)
            label = cited.soup.select_one("main a.cite")["href"].removeprefix("#")
            entry = cited.soup.find(id=label).get_text(" ", strip=True)
            _hover(browser, "main a.cite")
            browser.wait_for("!!document.querySelector('.preview')")
            assert entry[:30].replace("\xa0", " ") in browser.eval(
                "document.querySelector('.preview').textContent.replace(/\\s+/g, ' ')"
            )
    finally:
        browser.send("Emulation.clearDeviceMetricsOverride")


def test_print_shows_the_text_only_with_every_line_of_code(browser, site):
    """Printed (to PDF): no sidebar, search box, outline or buttons, and no code line cut off."""
    page = max(
        (p for p in site.pages if p.soup.select("main pre.code")),
        key=lambda p: max(len(ln) for pre in p.soup.select("main pre.code") for ln in pre.get_text().splitlines()),
    )
    browser.send("Emulation.setDeviceMetricsOverride", width=1280, height=900, deviceScaleFactor=1, mobile=False)
    browser.open(page.path)
    try:
        wide = browser.eval(
            "[...document.querySelectorAll('main pre.code')].some(p => p.scrollWidth > p.clientWidth + 1)"
        )
        assert wide, f"{page.url}: no code line wider than its box on screen, nothing to check"
        browser.send("Emulation.setEmulatedMedia", media="print")
        for sel in ("#sidebar", ".search", "#outline", ".topbar", "nav.prev-next", "button.copy"):
            shown = browser.eval(
                f"[...document.querySelectorAll({json.dumps(sel)})].some(e => getComputedStyle(e).display !== 'none')"
            )
            assert not shown, f"{sel} is printed"
        cut = browser.eval("""[...document.querySelectorAll('main pre')].filter(p => p.offsetParent)
            .filter(p => p.scrollWidth > p.clientWidth + 1).map(p => p.textContent.slice(0, 60))""")
        assert not cut, f"code cut off in print: {cut[:2]}"
        assert browser.eval("getComputedStyle(document.querySelector('main pre.code')).whiteSpace") == "pre-wrap"
        pdf = base64.b64decode(browser.send("Page.printToPDF", printBackground=True)["data"])
        assert pdf.startswith(b"%PDF") and pdf.count(b"/Type /Page") >= 2
    finally:
        browser.send("Emulation.setEmulatedMedia", media="")
        browser.send("Emulation.clearDeviceMetricsOverride")
