"""Open the book in JupyterLab, ready to step through (`make lab`).

    .venv/bin/python scripts/lab.py                       # the repository, chapter 1 open, a browser tab
    .venv/bin/python scripts/lab.py --root DIR -- --no-browser --port 8890   # options after -- go to jupyter lab

JupyterLab serves the repository (index.md, notebooks/, data/) and opens chapter 1. The chapters'
kernel is "skilllib" (scripts/kernel.py; `make venv` registers it): the venv's Python, so `import
skilllib` finds the editable install, started in the notebook's own folder (notebooks/), where the
chapters find the data. jupyterlab-myst renders the chapters' MyST: cross-references, numbered
equations, admonitions. Saving a notebook updates its percent script too (Jupytext, jupytext.toml).
Nothing is fetched from the network: JupyterLab's update check is off.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FIRST_CHAPTER = "notebooks/01_sparc.ipynb"


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
    os.execv(cmd[0], cmd)
    return 0  # not reached


if __name__ == "__main__":
    sys.exit(main())
