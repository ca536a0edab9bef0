"""Every chapter is a Jupytext pair: the percent script and the notebook hold the same cells."""

from __future__ import annotations

from pathlib import Path

import jupytext
import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
SCRIPTS = sorted(NOTEBOOKS.glob("[0-9][0-9]_*.py"))
IPYNBS = sorted(NOTEBOOKS.glob("*.ipynb"))


def _cells(nb) -> list[tuple[str, str, tuple[str, ...]]]:
    """Type, source and tags of every cell (tags such as remove-cell decide what the site shows)."""
    return [(c.cell_type, c.source.strip(), tuple(c.metadata.get("tags", ()))) for c in nb.cells]


def test_there_are_chapters():
    assert SCRIPTS, "no chapter scripts found in notebooks/"


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_script_has_its_notebook_in_sync(script: Path):
    ipynb = script.with_suffix(".ipynb")
    assert ipynb.exists(), f"{ipynb.name} is missing: run `make sync`"
    from_script = jupytext.read(script)
    from_notebook = jupytext.read(ipynb)
    assert _cells(from_script) == _cells(from_notebook), (
        f"{script.name} and {ipynb.name} differ: run `make sync` and commit both"
    )


@pytest.mark.parametrize("ipynb", IPYNBS, ids=lambda p: p.name)
def test_notebook_has_its_script(ipynb: Path):
    assert ipynb.with_suffix(".py").exists(), f"{ipynb.name} has no paired .py script"


@pytest.mark.parametrize("ipynb", IPYNBS, ids=lambda p: p.name)
def test_committed_notebook_has_no_outputs(ipynb: Path):
    nb = jupytext.read(ipynb)
    with_outputs = [i for i, c in enumerate(nb.cells) if c.cell_type == "code" and c.get("outputs")]
    assert not with_outputs, f"{ipynb.name}: cells {with_outputs} carry outputs; the build executes a copy"


def test_every_chapter_is_in_the_table_of_contents():
    toc = (ROOT / "myst.yml").read_text()
    for ipynb in IPYNBS:
        assert f"notebooks/{ipynb.name}" in toc, f"{ipynb.name} is not listed in myst.yml"


CODE_COLUMN = 88  #: characters: the site's code column (notebooks/ruff.toml formats to it)
FRONT_DOOR = {"import skilllib as sk", "import skilllib.figures as skf"}


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_code_lines_fit_the_sites_column(script: Path):
    """Every line of a code cell fits the site's code column (cell options such as ``#| caption:`` are
    not shown as code and may be longer); a long line would scroll sideways on the page."""
    long = [
        f"cell {i}: {line[:60]}..."
        for i, cell in enumerate(jupytext.read(script).cells)
        if cell.cell_type == "code"
        for line in cell.source.splitlines()
        if len(line) > CODE_COLUMN and not line.startswith("#|")
    ]
    assert not long, f"{script.name}: {len(long)} code lines over {CODE_COLUMN} characters: {long[:5]}"


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_chapters_import_skilllib_through_the_front_door(script: Path):
    """A chapter reaches the library as ``sk`` (and its figures as ``skf``), never by a module path."""
    imports = [
        line.strip()
        for cell in jupytext.read(script).cells
        if cell.cell_type == "code"
        for line in cell.source.splitlines()
        if "skilllib" in line and line.strip().startswith(("import ", "from "))
    ]
    assert imports and set(imports) <= FRONT_DOOR, f"{script.name}: {sorted(set(imports) - FRONT_DOOR)}"
