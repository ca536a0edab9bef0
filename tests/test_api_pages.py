"""The API reference (scripts/api_page.py): one page per sub-package, parameter tables with units, links
to the source line, an outline of the entries only.

The generator is checked on a small package written here (any package, not only skilllib), the built
book's API pages in headless Chromium (what the reader sees: the tables' columns, the outline, a phone).
The built pages' content is checked in tests/test_site.py (section "the API reference").
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from test_browser import CHROMIUM, browser  # noqa: F401  (browser: the fixture)
from test_site import ROOT, built_site

GENERATOR = ROOT / "scripts" / "api_page.py"

FILES = {
    "__init__.py": '''
        """The front door: every name of the sub-packages."""

        from .alpha import Thing, decorated
        from .beta import b
        ''',
    "alpha/__init__.py": '''
        """Alpha: the first concern.

        Its functions: :func:`decorated` and the class :class:`Thing`.
        """

        from ._impl import Thing, decorated

        __all__ = ["Thing", "decorated"]
        ''',
    "alpha/_impl.py": '''
        import functools
        from dataclasses import dataclass


        def deco(f):
            @functools.wraps(f)
            def wrapper(*args):
                return f(*args)

            return wrapper


        @deco
        def decorated(x, fs=100.0):
            """A length, decorated.

            Parameters
            ----------
            x : float
                A length (m).
            fs : float
                A sampling rate (Hz), see :class:`Thing`.

            Returns
            -------
            float
                The same length (m).

            Raises
            ------
            ValueError
                When ``x`` is negative.

            Notes
            -----
            A note.
            """
            return x


        @dataclass(frozen=True)
        class Thing:
            """A thing that moves.

            Attributes
            ----------
            speed : float
                Its speed (m/s).
            """

            speed: float

            def scaled(self, k):
                """The thing at another speed.

                Parameters
                ----------
                k : float
                    The factor (dimensionless).

                Returns
                -------
                scaled : Thing
                    Its speed in m/s.
                """
                return Thing(self.speed * k)

            @property
            def doubled(self):
                """Twice the speed (m/s)."""
                return 2 * self.speed
        ''',
    "beta/__init__.py": '''
        """Beta: the second concern.

        Section
        -------
        A reST section in a module's docstring.
        """


        def b():
            """B, after :meth:`pkg.alpha.Thing.scaled`."""
        ''',
    "beta/sub.py": '''
        """A public module below a sub-package."""


        def deep():
            """Deep, in s."""
        ''',
}


@pytest.fixture(scope="module")
def pages(tmp_path_factory) -> dict[str, str]:
    """The pages api_page.py writes for the package above, with BOOK_SOURCE_URL unset."""
    return _generate(tmp_path_factory.mktemp("api"), {})


def _generate(tmp: Path, env: dict[str, str]) -> dict[str, str]:
    for rel, text in FILES.items():
        path = tmp / "pkg" / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text).lstrip(), encoding="utf-8")
    base = {k: v for k, v in os.environ.items() if k != "BOOK_SOURCE_URL"}
    proc = subprocess.run(
        [sys.executable, str(GENERATOR), "--package", "pkg", "--out-dir", str(tmp / "out")],
        cwd=tmp,
        capture_output=True,
        text=True,
        env={**base, "PYTHONPATH": str(tmp), **env},
    )
    assert proc.returncode == 0, proc.stderr
    return {p.name: p.read_text(encoding="utf-8") for p in (tmp / "out").glob("*.md")}


def _line_of(pattern: str) -> int:
    lines = textwrap.dedent(FILES["alpha/_impl.py"]).lstrip().splitlines()
    return next(i for i, line in enumerate(lines, 1) if re.match(pattern, line))


def test_one_page_per_sub_package_and_an_index(pages):
    assert set(pages) == {"api.md", "api-alpha.md", "api-beta.md"}
    index = pages["api.md"]
    assert "label: pkg\n" in index
    assert "| [`pkg.alpha`](#pkg.alpha) | Alpha: the first concern | 1 | 1 |" in index
    assert "| [`pkg.beta`](#pkg.beta) | Beta: the second concern | 2 | 0 |" in index
    assert "[`decorated`](#pkg.alpha.decorated)" in index  # the front door's names, each linked
    alpha = pages["api-alpha.md"]
    assert alpha.startswith("---\ntitle: pkg.alpha\nshort_title: alpha\nlabel: pkg.alpha\n")
    assert 'subtitle: "Alpha: the first concern."' in alpha
    # a deeper public module is a section of its sub-package's page, its functions below it
    beta = pages["api-beta.md"]
    assert "(pkg.beta.sub)=\n## `pkg.beta.sub`" in beta and "(pkg.beta.sub.deep)=\n### `deep`" in beta


def test_headings_are_the_entries_only(pages):
    headings = {name: re.findall(r"^(#+) (.*)$", text, re.M) for name, text in pages.items()}
    assert headings["api-alpha.md"] == [("##", "`Thing`"), ("##", "`decorated`")]
    assert headings["api-beta.md"] == [("##", "`b`"), ("##", "`pkg.beta.sub`"), ("###", "`deep`")]
    assert headings["api.md"] == []
    alpha = pages["api-alpha.md"]
    # a docstring's own sections are bold labels, never headings (in HTML neither)
    assert "<p><strong>Notes</strong></p>" in alpha and "<h" not in alpha
    assert "<p><strong>Section</strong></p>" in pages["api-beta.md"]
    # methods and properties: the label on their signature, a code block
    assert "```{code} python\n:label: pkg.alpha.Thing.scaled\nscaled(k)\n```" in alpha
    assert "```{code} python\n:label: pkg.alpha.Thing.doubled\ndoubled\n```" in alpha


def _table(page: str, header: str) -> list[list[str]]:
    m = re.search(rf"<thead><tr><th>{header}</th>(.*?)</tbody>", page, re.S)
    assert m, f"no table headed {header}"
    rows = re.findall(r"<tr>(.*?)</tr>", m.group(0), re.S)
    return [re.findall(r"<t[hd]>(.*?)</t[hd]>", r, re.S) for r in rows]


def test_parameters_and_returns_are_tables_with_units(pages):
    alpha = pages["api-alpha.md"]
    dec = alpha[alpha.index("(pkg.alpha.decorated)=") :]
    params = _table(dec, "Parameter")
    assert params[0] == ["Parameter", "Type", "Unit", "Description"]
    assert params[1] == ["<code>x</code>", "float", "m", "A length (m)."]
    assert params[2][:3] == ["<code>fs</code>", "float", "Hz"]
    assert 'href="#pkg.alpha.Thing"' in params[2][3]  # :class: resolved to the entry's label
    assert _table(dec, "Returns")[:2] == [["Returns", "Unit", "Description"], ["float", "m", "The same length (m)."]]
    assert _table(dec, "Raises")[1] == ["<code>ValueError</code>", "When <code>x</code> is negative."]
    assert _table(alpha, "Attribute")[1] == ["<code>speed</code>", "float", "m/s", "Its speed (m/s)."]
    # a named return keeps its name; a row with no unit stated has an empty unit cell
    scaled = alpha[alpha.index(":label: pkg.alpha.Thing.scaled") :]
    assert _table(scaled, "Returns")[1][:3] == ["<code>scaled</code>", "Thing", "m/s"]
    assert _table(scaled, "Parameter")[1][2] == "dimensionless"


def test_source_links_are_the_lines_of_def_and_class(pages, tmp_path):
    alpha = pages["api-alpha.md"]
    # after the decorators: the def's and the class's own line
    line_def, line_class = _line_of(r"def decorated"), _line_of(r"class Thing")
    assert _line_of(r"@deco") == line_def - 1 and _line_of(r"@dataclass") == line_class - 1
    # as source: links, which the theme resolves (under BOOK_SOURCE_URL, or relative to the site)
    assert f'<a href="source:pkg/alpha/_impl.py#L{line_def}">source: <code>pkg/alpha/_impl.py</code>' in alpha
    assert f'<a href="source:pkg/alpha/_impl.py#L{line_class}">' in alpha
    assert f'<a href="source:pkg/alpha/_impl.py#L{_line_of(r"    def scaled")}">' in alpha
    assert f'<a href="source:pkg/alpha/_impl.py#L{_line_of(r"    def doubled")}">' in alpha
    assert "../../" not in alpha


# ------------------------------------------------------------------------ in the browser (the book) --

API_OUTLINE_MAX = 70  # as tests/test_site.py: about 60


@pytest.mark.book_site
@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium found (apt-get install chromium)")
def test_api_pages_fit_the_screen(browser):  # noqa: F811
    site = built_site("book")
    pages = [p for p in site.pages if re.fullmatch(r"api(-[\w-]+)?\.md", p.file)]
    assert len(pages) > 5
    try:
        browser.send("Emulation.setDeviceMetricsOverride", width=1400, height=900, deviceScaleFactor=1, mobile=False)
        for page in pages:
            browser.open(page.path)
            n = browser.eval("document.querySelectorAll('#outline a').length")
            assert n <= API_OUTLINE_MAX, f"{page.url}: {n} outline entries"
            # every table shows all its columns at once: a parameter's unit is not scrolled away
            cut = browser.eval("""[...document.querySelectorAll('main article table')].filter((t) => {
                const box = t.parentElement; const r = t.getBoundingClientRect();
                return box.scrollWidth > box.clientWidth + 1 || r.right > window.innerWidth; }).length""")
            assert cut == 0, f"{page.url}: {cut} tables cut at 1400 px"
        smoothness = next(p for p in pages if p.file == "api-smoothness.md")
        browser.open(smoothness.path)
        unit = browser.eval("""(() => { let el = document.getElementById('skilllib-smoothness-sparc');
            while ((el = el.nextElementSibling) && !el.querySelector('table'));
            const tab = el.querySelector('table');
            const col = [...tab.querySelectorAll('th')].findIndex((th) => th.textContent === 'Unit');
            const cell = tab.querySelectorAll('tbody tr')[0].children[col];
            return {text: cell.textContent, width: cell.getBoundingClientRect().width,
                    font: parseFloat(getComputedStyle(cell).fontSize)}; })()""")
        assert unit["text"] == "m/s" and unit["width"] > 20 and unit["font"] >= 12, unit
        # a phone: the page does not scroll sideways (a wide table scrolls in its own frame)
        browser.send("Emulation.setDeviceMetricsOverride", width=390, height=844, deviceScaleFactor=2, mobile=True)
        for page in pages:
            browser.open(page.path)
            assert browser.eval("document.documentElement.scrollWidth") <= 390, f"{page.url} scrolls sideways"
    finally:
        browser.send("Emulation.clearDeviceMetricsOverride")
