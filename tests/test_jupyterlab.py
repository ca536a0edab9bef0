"""Chapter 1 in JupyterLab, as `make lab` starts it (scripts/lab.py), read and run in headless Chromium.

The other way the book is read should read like the site: the book's kernel; jupyterlab-myst renders
the MyST (an admonition is an admonition); every citation reads author, year as on the site, none is
"Citation Not Found"; a reference to a figure reads "Figure k.n", the site's number, also for a figure
of another chapter; equations are numbered (k.n) as on the site; the check cells and the setup cell
open folded. Every cell runs without an error and the figures appear; saving the notebook after
that writes the chapter and its percent script exactly as they were (no outputs), while the tab
still shows the outputs. The server is stopped at the end.

JupyterLab serves a copy of the book's chapters (BOOK_PROJECT, default: this repository), so
running it never touches the repository's notebooks.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import nbformat
import pytest
import yaml
from test_browser import CHROMIUM, browser  # noqa: F401  (the module's Chromium, a fixture)
from test_site import ROOT

pytestmark = [
    pytest.mark.jupyterlab,
    pytest.mark.skipif(CHROMIUM is None, reason="no Chromium found (apt-get install chromium)"),
]

PROJECT = Path(os.environ.get("BOOK_PROJECT") or ROOT)
LAB_CHAPTER = "notebooks/01_sparc.ipynb"
NOTEBOOK = "[...jupyterapp.shell.widgets('main')].find(w => w.content && w.content.widgets && w.sessionContext)"


class JupyterLab:
    """JupyterLab as `make lab` starts it (scripts/lab.py), headless on a free localhost port, serving a
    copy of the book's chapters, its percent script, references.bib and jupytext.toml."""

    def __init__(self, tmp: Path) -> None:
        import secrets
        import socket

        self.tmp = tmp
        self.root = tmp / "root"
        (self.root / "notebooks").mkdir(parents=True)
        for nb in sorted((PROJECT / "notebooks").glob("[0-9][0-9]_*.ipynb")):  # figures of other chapters
            shutil.copy(nb, self.root / "notebooks" / nb.name)
        for name in (LAB_CHAPTER.replace(".ipynb", ".py"), "references.bib", "jupytext.toml"):
            shutil.copy(PROJECT / name, self.root / name)
        # every cell in the page (no windowing), so that the whole notebook can be inspected
        settings = tmp / "settings" / "@jupyterlab" / "notebook-extension"
        settings.mkdir(parents=True)
        (settings / "tracker.jupyterlab-settings").write_text(json.dumps({"windowingMode": "none"}))
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.port = s.getsockname()[1]
        self.token = secrets.token_hex(16)
        cmd = [
            sys.executable,
            str(ROOT / "scripts" / "lab.py"),
            "--root",
            str(self.root),
            "--open",
            LAB_CHAPTER,
            "--",
            "--no-browser",
            "--ip=127.0.0.1",
            f"--port={self.port}",
            "--ServerApp.port_retries=0",
            f"--IdentityProvider.token={self.token}",
            "--LabApp.expose_app_in_browser=True",
            f"--LabApp.user_settings_dir={tmp / 'settings'}",
            f"--LabApp.workspaces_dir={tmp / 'workspaces'}",
        ]
        env = {**os.environ, "JUPYTER_RUNTIME_DIR": str(tmp / "runtime"), "JUPYTER_CONFIG_DIR": str(tmp / "config")}
        self.log = tmp / "lab.log"
        self.proc = subprocess.Popen(
            cmd,
            env=env,
            stdout=self.log.open("w"),
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            start_new_session=True,
        )
        deadline = time.monotonic() + 90
        while True:
            try:
                urllib.request.urlopen(f"{self.base}/api/status?token={self.token}", timeout=2)
                break
            except OSError:
                if self.proc.poll() is not None or time.monotonic() > deadline:
                    self.stop()
                    raise RuntimeError("JupyterLab did not start:\n" + self.log.read_text()[-2000:]) from None
                time.sleep(0.2)

    @property
    def base(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def stop(self) -> int | None:
        if self.proc.poll() is None:
            self.proc.terminate()  # JupyterLab shuts its kernels down on SIGTERM
            try:
                self.proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(timeout=10)
        return self.proc.returncode


# ---------------------------------------------------------------- what the site shows, from the sources --


def toc_chapters() -> list[str]:
    """The notebooks of myst.yml's toc in order: the k-th is chapter k (scripts/build_site.py)."""

    def files(entries):
        for e in entries or []:
            if isinstance(e, dict):
                if e.get("file"):
                    yield str(e["file"]).removeprefix("./")
                yield from files(e.get("children"))

    cfg = yaml.safe_load((PROJECT / "myst.yml").read_text(encoding="utf-8"))
    return [f for f in files(cfg["project"]["toc"]) if f.endswith(".ipynb")]


def figure_numbers() -> dict[str, str]:
    """{label: "Figure k.n"}: chapter k's code cells labelled `#| label: fig-...`, in order."""
    numbers = {}
    for k, rel in enumerate(toc_chapters(), start=1):
        nb = nbformat.read(PROJECT / rel, as_version=4)
        labels = [m.group(1) for c in nb.cells if c.cell_type == "code" for m in [LABEL.match(c.source)] if m]
        numbers.update({label: f"Figure\xa0{k}.{n}" for n, label in enumerate(labels, start=1)})
    return numbers


LABEL = re.compile(r"(?:#\|.*\n)*?#\|\s*label:\s*[\"']?(fig-[\w-]+)")


def first_authors_and_years() -> dict[str, tuple[str, str]]:
    """{key: (the first author's family name, year)} of references.bib, read with regular expressions
    (independently of the extension's parser)."""
    text = (PROJECT / "references.bib").read_text(encoding="utf-8")
    out = {}
    for m in re.finditer(r"@\w+\s*\{\s*([^,\s]+)\s*,(.*?)\n\}", text, re.S):
        author = re.search(r"\bauthor\s*=\s*\{(.*?)\},?\s*\n", m.group(2), re.S)
        year = re.search(r"\byear\s*=\s*[{\"]?(\d{4})", m.group(2))
        first = re.split(r"\s+and\s+", author.group(1))[0] if author else ""
        family = first.split(",")[0] if "," in first else first.strip("{}").split()[0] if first else ""
        out[m.group(1)] = (re.sub(r"[{}\\'\"]", "", family).strip(), year.group(1) if year else "n.d.")
    return out


# ---------------------------------------------------------------- the test --


def test_chapter_1_reads_like_the_site_and_runs_in_jupyterlab(browser, tmp_path):  # noqa: F811
    lab = JupyterLab(tmp_path)
    chapter = nbformat.read(PROJECT / LAB_CHAPTER, as_version=4)
    saved = [lab.root / p for p in (LAB_CHAPTER, LAB_CHAPTER.replace(".ipynb", ".py"))]
    before = {p: (p.read_bytes(), p.stat().st_mtime_ns) for p in saved}
    k = toc_chapters().index(LAB_CHAPTER) + 1
    markdown = "\n".join(c.source for c in chapter.cells if c.cell_type == "markdown")
    try:
        browser.send("Emulation.setFocusEmulationEnabled", enabled=True)  # JupyterLab tracks the focused panel
        browser.send("Emulation.setDeviceMetricsOverride", width=1400, height=1000, deviceScaleFactor=1, mobile=False)
        browser.send("Page.navigate", url=f"{lab.base}/lab/tree/{LAB_CHAPTER}?token={lab.token}")
        browser.wait_for(
            f"window.jupyterapp && {NOTEBOOK} && {NOTEBOOK}.sessionContext.session && "
            f"{NOTEBOOK}.sessionContext.session.kernel",
            timeout=120,
        )
        kernel = browser.eval(
            f"(() => {{ const k = {NOTEBOOK}.sessionContext; return [k.session.kernel.name, k.kernelDisplayName]; }})()"
        )
        assert kernel == ["skilllib", "Smoothness-based prototypes (skilllib)"], kernel

        # Equations: a reference reads as the number its equation shows, (k.n) as on the site.
        n_refs = markdown.count("](#eq-sparc)")
        refs_js = """[...document.querySelectorAll('.jp-MarkdownCell a[href="#eq-sparc"]')]
            .filter(a => !a.closest('#eq-sparc')).map(a => a.textContent.trim())"""
        browser.wait_for(f"document.getElementById('eq-sparc') && {refs_js}.length >= {n_refs}", timeout=60)
        number = browser.eval("document.getElementById('eq-sparc').textContent.trim().match(/\\([\\d.]+\\)$/)[0]")
        assert re.fullmatch(rf"\({k}\.\d+\)", number), f"eq-sparc is numbered {number}, the site numbers ({k}.n)"
        refs = browser.eval(refs_js)
        assert refs and all(r == number for r in refs), f"references to eq-sparc read {refs}, it shows {number}"
        assert browser.eval(
            "[...document.querySelectorAll('.jp-MarkdownCell aside')].some(a => /Note/.test(a.textContent))"
        )

        # Citations: none "Citation Not Found"; each reads its first author and year from references.bib.
        cited = [c for c in re.findall(r"@([\w:-]+)", markdown) if c in first_authors_and_years()]
        assert cited, "chapter 1 cites nothing from references.bib: the test checks nothing"
        browser.wait_for(f"document.querySelectorAll('[data-book-cite]').length >= {len(cited)}", timeout=60)
        shown = browser.eval(
            "[...document.querySelectorAll('.jp-MarkdownCell [data-book-cite]')]"
            ".map(e => [e.dataset.bookCite, e.textContent, getComputedStyle(e).color, e.title])"
        )
        not_found = browser.eval(
            "[...document.querySelectorAll('.jp-MarkdownCell *')].filter(e => e.title === 'Citation Not Found' ||"
            " /Citation Not Found/.test(e.textContent) && !e.children.length).length"
        )
        assert not_found == 0, f"{not_found} citations still read 'Citation Not Found'"
        assert sorted(key for key, *_ in shown) == sorted(cited), (sorted(key for key, *_ in shown), sorted(cited))
        body_color = browser.eval("getComputedStyle(document.querySelector('.jp-MarkdownCell p')).color")
        for key, text, color, title in shown:
            family, year = first_authors_and_years()[key]
            assert family in text and year in text and key not in text, f"[@{key}] reads {text!r}"
            assert re.search(rf"{re.escape(family)}\b.*(, | \(){re.escape(year)}", text), f"[@{key}] reads {text!r}"
            assert color == body_color, f"[@{key}] is coloured {color} (the text: {body_color})"
            assert year in title and len(title) > 40, f"[@{key}]'s tooltip is {title!r}, not the reference"

        # Figure references: "Figure k.n", the site's number, also for a figure of another chapter.
        numbers = figure_numbers()
        fig_refs = re.findall(r"\]\(#(fig-[\w-]+)\)", markdown)
        assert fig_refs and any(numbers[f].startswith(f"Figure\xa0{k}.") for f in fig_refs)
        links_js = (
            "[...document.querySelectorAll('.jp-MarkdownCell a[href^=\"#fig-\"]')]"
            ".map(a => [a.getAttribute('href').slice(1), a.textContent])"
        )
        browser.wait_for(f"{links_js}.filter(([l, t]) => t.startsWith('Figure')).length >= {len(fig_refs)}", 60)
        links = browser.eval(links_js)
        assert sorted(map(tuple, links)) == sorted((f, numbers[f]) for f in fig_refs), links
        # following one shows the figure's cell
        own = next(f for f in fig_refs if numbers[f].startswith(f"Figure\xa0{k}."))
        browser.eval(f"document.querySelector('.jp-MarkdownCell a[href=\"#{own}\"]').click()")
        browser.wait_for(
            f"(() => {{ const c = {NOTEBOOK}.content.activeCell; const top = c.node.getBoundingClientRect().top;"
            f" return c.model.sharedModel.getSource().includes('label: {own}') && top >= 0 && top < innerHeight; }})()",
            timeout=10,
        )

        # The check cells (remove-cell) and the setup cell open folded: their jupyter.source_hidden.
        folded = [i for i, c in enumerate(chapter.cells) if c.metadata.get("jupyter", {}).get("source_hidden")]
        checks = [i for i, c in enumerate(chapter.cells) if "remove-cell" in c.metadata.get("tags", [])]
        assert checks and set(checks) <= set(folded) and len(folded) > len(checks), (checks, folded)
        hidden = browser.eval(f"{NOTEBOOK}.content.widgets.map((c, i) => c.inputHidden ? i : -1).filter(i => i >= 0)")
        assert hidden == folded, f"cells shown folded {hidden}, folded in the chapter {folded}"

        # Run every cell, as a reader stepping through would.
        browser.eval(f"jupyterapp.shell.activateById({NOTEBOOK}.id)")
        browser.eval("jupyterapp.commands.execute('notebook:run-all-cells')")
        browser.wait_for(
            f"""(() => {{ const p = {NOTEBOOK};
            const code = p.content.widgets.filter(c => c.model.type === 'code');
            return code.every(c => c.model.executionCount !== null)
              && p.sessionContext.session.kernel.status === 'idle'; }})()""",
            timeout=400,
        )
        errors = browser.eval(f"""{NOTEBOOK}.content.widgets.filter(c => c.model.type === 'code')
            .flatMap((c, i) => c.model.outputs.toJSON().filter(o => o.output_type === 'error')
            .map(o => [i + 1, o.ename, o.evalue]))""")
        assert not errors, f"cells raised errors (code cell, exception, message): {errors}"
        shown_errors = browser.eval(
            "document.querySelectorAll('.jp-ErrorOutput, [data-mime-type=\"application/vnd.jupyter.error\"]').length"
        )
        assert shown_errors == 0
        figures_js = (
            "[...document.querySelectorAll('.jp-OutputArea-output img')].filter(i => i.naturalWidth > 100).length"
        )
        browser.wait_for(f"{figures_js} > 0")
        n_figures = browser.eval(figures_js)
        expected = sum(1 for c in chapter.cells if c.cell_type == "code" and "#| label: fig-" in c.source)
        assert n_figures >= expected > 0, f"{n_figures} figures shown, {expected} figure cells"

        # Save (as autosave does): the chapter and its percent script are written as they were.
        browser.eval(f"jupyterapp.shell.activateById({NOTEBOOK}.id)")
        browser.eval("jupyterapp.commands.execute('docmanager:save')")
        browser.wait_for(f"!{NOTEBOOK}.model.dirty", timeout=30)
        for p in saved:
            assert p.stat().st_mtime_ns > before[p][1], f"{p.name} was not saved"
            after = p.read_bytes()
            assert after == before[p][0], (
                f"saving after running changed {p.name}: {len(before[p][0])} -> {len(after)} bytes"
            )
        assert browser.eval(figures_js) == n_figures, "saving took the outputs out of the open tab"
    finally:
        browser.send("Emulation.clearDeviceMetricsOverride")
        browser.send("Emulation.setFocusEmulationEnabled", enabled=False)
        browser.send("Page.navigate", url="about:blank")
        code = lab.stop()
    assert code is not None, "the JupyterLab server is still running"
    with pytest.raises(OSError):
        urllib.request.urlopen(f"{lab.base}/api/status", timeout=2)
