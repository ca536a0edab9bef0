"""Give every chapter its equation and figure numbering in its own front matter (k.1, k.2, ... in chapter k).

    .venv/bin/python scripts/notebook_front_matter.py            # add it where missing (percent script and notebook)
    .venv/bin/python scripts/notebook_front_matter.py --check    # exit 1 if a chapter lacks it, change nothing

The site numbers chapter k's equations and figures k.1, k.2, ... (scripts/build_site.py adds
`numbering: enumerator: "k.%s"` at build time unless the chapter sets `numbering` itself). JupyterLab's
MyST renderer (jupyterlab-myst) knows nothing of the book: it reads a notebook's front matter from the
YAML block at the top of the first markdown cell (its ReferenceState gets that front matter's
`numbering`) and numbered the equations (1), (2), ... So each chapter states it there:

    # %% [markdown]
    # ---
    # numbering:
    #   enumerator: "1.%s"
    # ---
    # # SPARC from first principles

k is the chapter's place among the notebooks of myst.yml's table of contents, as in build_site.py.
The percent script is the source: the numbering goes into it, and the paired notebook is written from
it as Jupytext writes it when JupyterLab saves the chapter (the script's cells and header, the
notebook's cell ids and outputs), so that opening and saving a chapter in `make lab` changes neither
file. (A notebook written otherwise differs in details Jupytext then rewrites: the chapters of
commit 281e6ef said `cell_metadata_filter: jupyter,tags,-all` where their scripts say
`tags,jupyter,-all`.) A second run changes nothing; --check says which chapters need a run.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import jupytext
import nbformat
import yaml
from jupytext.combine import combine_inputs_with_outputs

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from build_site import toc_files  # noqa: E402  (the toc's order is the chapters' numbers, as the site has them)

FRONT_MATTER = re.compile(r"---[ \t]*\n(.*?\n)?---[ \t]*(\n|$)", re.S)


def chapters(project: Path) -> list[tuple[int, Path]]:
    """(k, notebook) for the notebooks of myst.yml's toc, in order, k from 1."""
    cfg = yaml.safe_load((project / "myst.yml").read_text(encoding="utf-8"))
    files = [f for f in toc_files((cfg.get("project") or {}).get("toc")) if f.endswith(".ipynb")]
    return [(k, project / f) for k, f in enumerate(files, start=1)]


def with_numbering(markdown: str, chapter: int) -> str:
    """The markdown with `numbering: enumerator: "k.%s"` in its front matter (added, or the block created);
    unchanged when the front matter already sets `numbering`."""
    block = f'numbering:\n  enumerator: "{chapter}.%s"\n'
    m = FRONT_MATTER.match(markdown)
    if m is None:
        return "---\n" + block + "---\n" + markdown
    meta = yaml.safe_load(m.group(1) or "") or {}
    if "numbering" in meta:
        return markdown
    at = m.end(1) if m.group(1) is not None else markdown.index("\n") + 1  # before the closing ---
    return markdown[:at] + block + markdown[at:]


def numbered(nb, chapter: int) -> bool:
    """Set the numbering in nb's first markdown cell; True if the cell changed."""
    first = next((c for c in nb.cells if c.cell_type == "markdown"), None)
    if first is None:
        raise ValueError("no markdown cell to hold the front matter")
    new = with_numbering(first.source, chapter)
    changed = new != first.source
    first.source = new
    return changed


def paired_notebook(script_nb, ipynb: Path) -> str:
    """The .ipynb text Jupytext's contents manager writes for a chapter read from its percent script
    (script_nb) and its notebook: the script's cells and metadata, the notebook's ids and outputs."""
    nb = combine_inputs_with_outputs(script_nb, nbformat.read(ipynb, as_version=4), fmt="py:percent")
    nb.metadata.get("jupytext", {}).pop("text_representation", None)
    return nbformat.writes(nb) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--project", type=Path, default=ROOT, help="the book's folder, with myst.yml (default: this one)")
    ap.add_argument("--check", action="store_true", help="change nothing; exit 1 if a chapter lacks its numbering")
    args = ap.parse_args(argv)
    missing = []
    for k, ipynb in chapters(args.project):
        script = ipynb.with_suffix(".py")
        rel = ipynb.relative_to(args.project)
        old_ipynb = ipynb.read_text(encoding="utf-8")
        if script.is_file():
            text = jupytext.read(script, fmt="py:percent")
            new_script = numbered(text, k)
            new_ipynb = paired_notebook(text, ipynb)
        else:  # a notebook alone: the numbering in its own first cell
            nb = nbformat.read(ipynb, as_version=4)
            new_script = False
            new_ipynb = nbformat.writes(nb) + "\n" if numbered(nb, k) else old_ipynb
        if not new_script and new_ipynb == old_ipynb:
            continue
        missing.append(str(rel))
        if args.check:
            continue
        if new_script:
            jupytext.write(text, script, fmt="py:percent")
        ipynb.write_text(new_ipynb, encoding="utf-8")
        print(f"{rel}: numbering {k}.%s" + (", notebook written from its percent script" if script.is_file() else ""))
    if args.check and missing:
        print("chapters without their numbering, or whose notebook is not as Jupytext writes it: " + ", ".join(missing))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
