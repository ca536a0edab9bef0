"""The built site in a real browser: headless Chromium opens pages from file:// (no server).

Checks what only a browser can: KaTeX math is laid out with its local fonts, the search box finds a
word and links to its page, nothing is requested from the network, and on a phone-sized screen the
contents collapse behind the menu button. Chromium is driven over the DevTools protocol
(websocket-client); skipped only when no Chromium is installed (CI installs Debian's).
"""
from __future__ import annotations

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

from test_site import SITES, built_site

websocket = pytest.importorskip("websocket", reason="websocket-client is needed to drive Chromium")

CHROMIUM = os.environ.get("CHROMIUM") or next(
    (p for p in (shutil.which("chromium"), shutil.which("chromium-browser"), "/usr/bin/chromium") if p and Path(p).exists()),
    None,
)
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="no Chromium found (apt-get install chromium)")

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-extensions",
         "--remote-debugging-port=0", "--remote-allow-origins=*"]


class Browser:
    """A headless Chromium with one page, spoken to over the DevTools protocol."""

    def __init__(self) -> None:
        self.profile = tempfile.mkdtemp(prefix="book-chromium-")
        self.proc = subprocess.Popen([CHROMIUM, *FLAGS, f"--user-data-dir={self.profile}", "about:blank"],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
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
        while not self.eval(f"!!({expression})"):
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


@pytest.fixture(scope="module", params=list(SITES))
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
    browser.wait_for(f"location.href.endsWith({json.dumps(hrefs[0].split('#')[0])}) || location.href.includes({json.dumps(hrefs[0])})")


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
