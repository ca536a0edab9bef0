"""Open the book in JupyterLab, ready to step through (`make lab`).

    .venv/bin/python scripts/lab.py                       # the repository, chapter 1 open, a browser tab
    .venv/bin/python scripts/lab.py --root DIR -- --no-browser --port 8890   # options after -- go to jupyter lab

JupyterLab serves the repository (index.md, notebooks/, data/) and opens chapter 1. The chapters'
kernel is "skilllib" (scripts/kernel.py; `make venv` registers it): the venv's Python, so `import
skilllib` finds the editable install, started in the notebook's own folder (notebooks/), where the
chapters find the data. jupyterlab-myst renders the chapters' MyST: cross-references, numbered
equations, admonitions. Saving a notebook updates its percent script too (Jupytext, jupytext.toml).
Nothing is fetched from the network: JupyterLab's update check is off.

The repository's .jupyter/ folder is put first on JUPYTER_CONFIG_PATH, so that JupyterLab reads
.jupyter/jupyter_server_config.py, which
- saves a chapter without outputs (`clean_chapter` below, a pre-save hook): running a chapter and
  saving it (autosave does, every two minutes) leaves the tracked notebook and its percent script as
  they were; the outputs stay in the open tab;
- adds the extension in .jupyter/labextensions/skilllib-book (one plain script): citations read as
  on the site (author, year from references.bib) instead of jupyterlab-myst's "Citation Not Found",
  and references to figures show their numbers ("Figure 1.3").
Equations are numbered as on the site (1.1, 1.2, ...) by each chapter's own front matter
(scripts/notebook_front_matter.py); the check and setup cells open folded (their `jupyter:
source_hidden` cell metadata).
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path, PurePosixPath

ROOT = Path(__file__).resolve().parents[1]
FIRST_CHAPTER = "notebooks/01_sparc.ipynb"
CONFIG_DIR = ROOT / ".jupyter"  # jupyter_server_config.py, labextensions/
CHAPTERS_DIR = "notebooks"  # relative to the root JupyterLab serves


def is_chapter(path: str, nb: dict) -> bool:
    """A chapter: a notebook of notebooks/ paired with its percent script by Jupytext."""
    formats = str(((nb.get("metadata") or {}).get("jupytext") or {}).get("formats", ""))
    p = PurePosixPath(path.strip("/"))
    return p.suffix == ".ipynb" and p.parent.as_posix() == CHAPTERS_DIR and "py:percent" in formats


def clean_chapter(model: dict, path: str, **kwargs) -> None:
    """Jupyter pre-save hook: a chapter is saved as it is committed, without what running it adds.

    Its code cells lose their outputs and execution counts; the cell and notebook metadata keep only
    what the chapter's Jupytext filters keep in the percent script (`jupyter` and `tags`; `kernelspec`
    and `jupytext`), so the `language_info` a kernel adds is not saved either. Other notebooks are
    saved as they are. The model is changed in place, before Jupyter (and Jupytext) write it."""
    if model.get("type") != "notebook" or not isinstance(model.get("content"), dict):
        return
    nb = model["content"]
    if not is_chapter(path, nb):
        return
    from jupytext.cell_metadata import _IGNORE_CELL_METADATA
    from jupytext.header import _DEFAULT_NOTEBOOK_METADATA
    from jupytext.metadata_filter import filter_metadata

    jt = nb["metadata"]["jupytext"]
    for cell in nb.get("cells", []):
        if cell.get("cell_type") == "code":
            cell["outputs"] = []
            cell["execution_count"] = None
        cell["metadata"] = filter_metadata(
            cell.get("metadata", {}), jt.get("cell_metadata_filter"), _IGNORE_CELL_METADATA
        )
    nb["metadata"] = filter_metadata(nb["metadata"], jt.get("notebook_metadata_filter"), _DEFAULT_NOTEBOOK_METADATA)


def lab_environment(env: dict[str, str]) -> dict[str, str]:
    """env with the book's Jupyter configuration (.jupyter/) first on JUPYTER_CONFIG_PATH."""
    paths = [str(CONFIG_DIR), *[p for p in env.get("JUPYTER_CONFIG_PATH", "").split(os.pathsep) if p]]
    return {**env, "JUPYTER_CONFIG_PATH": os.pathsep.join(dict.fromkeys(paths))}


def lab_command(root: Path, notebook: str, extra: list[str]) -> list[str]:
    jupyter = Path(sys.executable).parent / "jupyter"
    cmd = [
        str(jupyter),
        "lab",
        f"--ServerApp.root_dir={root}",
        "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
        *extra,
    ]
    if hasattr(os, "getuid") and os.getuid() == 0:
        cmd.append("--allow-root")  # a container's root user; JupyterLab refuses root otherwise
    if notebook:  # opened at start (a URL relative to the root)
        cmd.append(f"--LabApp.default_url=/lab/tree/{Path(notebook).as_posix()}")
    return cmd


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--root", type=Path, default=ROOT, help="folder JupyterLab serves (default: the repository)")
    ap.add_argument(
        "--open", default=FIRST_CHAPTER, help=f"notebook to open, relative to the root (default {FIRST_CHAPTER})"
    )
    ap.add_argument("extra", nargs="*", help="options for jupyter lab (after --)")
    args = ap.parse_args(argv)
    if args.open and not (args.root / args.open).is_file():
        print(f"lab: {args.root / args.open} does not exist", file=sys.stderr)
        return 2
    cmd = lab_command(args.root.resolve(), args.open, args.extra)
    os.execve(cmd[0], cmd, lab_environment(dict(os.environ)))
    return 0  # not reached


if __name__ == "__main__":
    sys.exit(main())
