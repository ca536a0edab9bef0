"""The pieces of `make lab` that need no browser: the pre-save hook that keeps a chapter's outputs out of
the repository (scripts/lab.py), the chapters' own numbering front matter (scripts/notebook_front_matter.py)
and the JupyterLab extension's reading of references.bib (.jupyter/labextensions/skilllib-book, run by node).
The whole of it in a real JupyterLab is tests/test_jupyterlab.py."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import jupytext
import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))

import lab  # noqa: E402
import notebook_front_matter as nfm  # noqa: E402

BOOK_JS = ROOT / ".jupyter" / "labextensions" / "skilllib-book" / "static" / "book.js"


def _ran(nb: dict) -> dict:
    """nb as JupyterLab sends it to be saved after running it: outputs, counts, language_info."""
    nb = json.loads(json.dumps(nb))
    for i, cell in enumerate(nb["cells"]):
        if cell["cell_type"] == "code":
            cell["outputs"] = [{"output_type": "stream", "name": "stdout", "text": "ran\n"}]
            cell["execution_count"] = i + 1
            cell["metadata"]["execution"] = {"iopub.status.idle": "2026-01-01T00:00:00Z"}
    nb["metadata"]["language_info"] = {"name": "python", "version": "3.11"}
    return nb


def test_saving_a_chapter_drops_what_running_it_added():
    committed = json.loads((ROOT / "notebooks" / "01_sparc.ipynb").read_text(encoding="utf-8"))
    model = {"type": "notebook", "content": _ran(committed)}
    lab.clean_chapter(model, path="/notebooks/01_sparc.ipynb")
    assert model["content"] == committed
    # a notebook that is not a chapter (elsewhere, or not paired) is saved as it is
    for path, nb in (("scratch/01_sparc.ipynb", committed), ("notebooks/mine.ipynb", {**committed, "metadata": {}})):
        ran = _ran(nb)
        model = {"type": "notebook", "content": json.loads(json.dumps(ran))}
        lab.clean_chapter(model, path=path)
        assert model["content"] == ran, path


def test_lab_reads_the_books_jupyter_configuration():
    env = lab.lab_environment({"JUPYTER_CONFIG_PATH": "/elsewhere"})
    assert env["JUPYTER_CONFIG_PATH"].split(":") == [str(ROOT / ".jupyter"), "/elsewhere"]
    config = (ROOT / ".jupyter" / "jupyter_server_config.py").read_text(encoding="utf-8")
    assert "clean_chapter" in config and "extra_labextensions_path" in config
    pkg = json.loads((ROOT / ".jupyter" / "labextensions" / "skilllib-book" / "package.json").read_text())
    assert (BOOK_JS.parent.parent / pkg["jupyterlab"]["_build"]["load"]).is_file()


def test_with_numbering_adds_the_enumerator_once():
    md = "# Title\n\nText."
    once = nfm.with_numbering(md, 3)
    assert once == '---\nnumbering:\n  enumerator: "3.%s"\n---\n# Title\n\nText.'
    assert nfm.with_numbering(once, 3) == once
    kept = "---\ntitle: T\n---\n# Title"
    assert nfm.with_numbering(kept, 2) == '---\ntitle: T\nnumbering:\n  enumerator: "2.%s"\n---\n# Title'
    own = "---\nnumbering:\n  figure: false\n---\nx"
    assert nfm.with_numbering(own, 2) == own  # a chapter's own numbering is kept (as build_site.py does)


def test_front_matter_script_numbers_the_toc_chapters_and_pairs_them(tmp_path):
    (tmp_path / "notebooks").mkdir()
    toc = ["notebooks/02_sparc_parameters.ipynb", "notebooks/01_sparc.ipynb"]  # the toc's order counts
    (tmp_path / "myst.yml").write_text(
        "version: 1\nproject:\n  toc:\n    - file: index.md\n" + "".join(f"    - file: {f}\n" for f in toc)
    )
    for f in toc:  # the chapters as they were before the script ran: no numbering of their own
        for ext in (".ipynb", ".py"):
            text = (ROOT / f.replace(".ipynb", ext)).read_text(encoding="utf-8")
            text = re.sub(r'# ---\n# numbering:\n#   enumerator: "\d+\.%s"\n# ---\n', "", text)
            text = re.sub(r'"---\\n",\s*"numbering:\\n",\s*"  enumerator: \\"\d+\.%s\\"\\n",\s*"---\\n",\s*', "", text)
            (tmp_path / f.replace(".ipynb", ext)).write_text(text, encoding="utf-8")
    project = ["--project", str(tmp_path)]
    assert nfm.main([*project, "--check"]) == 1
    assert nfm.main(project) == 0
    assert nfm.main([*project, "--check"]) == 0
    for k, f in enumerate(toc, start=1):
        script = jupytext.read(tmp_path / f.replace(".ipynb", ".py"), fmt="py:percent")
        nb = nbformat.read(tmp_path / f, as_version=4)
        first = next(c for c in nb.cells if c.cell_type == "markdown")
        assert first.source.startswith(f'---\nnumbering:\n  enumerator: "{k}.%s"\n---\n'), f
        assert [c.source for c in nb.cells] == [c.source for c in script.cells]
        original = nbformat.read(ROOT / f, as_version=4)
        assert [c.id for c in nb.cells] == [c.id for c in original.cells]  # the notebook's cell ids kept
        assert nb.metadata["jupytext"]["cell_metadata_filter"] == script.metadata["jupytext"]["cell_metadata_filter"]
    before = {p: p.read_bytes() for p in tmp_path.rglob("*.*")}
    nfm.main(project)
    assert {p: p.read_bytes() for p in tmp_path.rglob("*.*")} == before


def test_the_extension_reads_every_reference_as_author_year():
    node = shutil.which("node")
    if node is None:
        pytest.skip("node is needed to run the extension's script")
    script = (
        "global.window = {}; require(process.argv[1]); const b = window.SKILLLIB_BOOK_LAB.bib;"
        "const e = b.parse(require('fs').readFileSync(process.argv[2], 'utf8')); const out = {};"
        "for (const k in e) out[k] = [b.authorYear(e[k]), b.fullReference(e[k])];"
        "console.log(JSON.stringify(out));"
    )
    bib = ROOT / "references.bib"
    got = json.loads(
        subprocess.run([node, "-e", script, str(BOOK_JS), str(bib)], capture_output=True, text=True, check=True).stdout
    )
    keys = re.findall(r"^@\w+\{([^,\s]+),", bib.read_text(encoding="utf-8"), re.M)
    assert sorted(got) == sorted(keys)
    for key, ((who, year), full) in got.items():
        entry = re.search(rf"@\w+\{{{re.escape(key)},(.*?)\n\}}", bib.read_text(encoding="utf-8"), re.S).group(1)
        author = re.search(r"author\s*=\s*\{(.*)\},?\s*$", entry, re.M).group(1)
        names = re.split(r"\s+and\s+", author)
        first = names[0].strip("{}").split(",")[0] if "," in names[0] else names[0].strip("{}")
        assert re.sub(r"[{}\\'\"]", "", first) in _ascii(who) or first.strip("{}") == who, (key, who)
        assert (len(names) >= 3) == who.endswith(" et al.") or "et al." in first, (key, who)
        assert (len(names) == 2) == (" & " in who), (key, who)
        y = re.search(r"year\s*=\s*\{?(\d{4})", entry)
        assert year == (y.group(1) if y else "n.d."), (key, year)
        assert not re.search(r"[{}\\]", who + full), (key, who, full)  # no LaTeX left


def _ascii(s: str) -> str:
    import unicodedata

    return "".join(c for c in unicodedata.normalize("NFD", s) if not unicodedata.combining(c))


def test_every_chapter_carries_its_numbering():
    """The repository's chapters number their equations and figures as the site does, in JupyterLab too:
    a new chapter (or a renumbered toc) fails here until scripts/notebook_front_matter.py is run."""
    assert nfm.main(["--project", str(ROOT), "--check"]) == 0
