"""Register the book's Jupyter kernel in the virtual environment (`make venv` runs this).

    .venv/bin/python scripts/kernel.py

The chapters' notebooks name the kernel "skilllib" (display name: the project's); JupyterLab (`make lab`)
and nbmake (`make test`) start it from .venv/share/jupyter/kernels/skilllib. It is the venv's Python
with two settings: figures inline (--matplotlib=inline), and MPLBACKEND=Agg in its environment, which
is what the processes a chapter starts inherit: with ipykernel's default, the inline backend, a
`python -m skilllib run` from a chapter prints `Figure(650x600)` for every figure roboticstoolbox shows.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from ipykernel.kernelspec import install

NAME = "skilllib"
DISPLAY_NAME = "Smoothness-based prototypes (skilllib)"


def main() -> int:
    path = Path(install(kernel_name=NAME, display_name=DISPLAY_NAME, prefix=sys.prefix, env={"MPLBACKEND": "Agg"}))
    spec_file = path / "kernel.json"
    spec = json.loads(spec_file.read_text(encoding="utf-8"))
    if "--matplotlib=inline" not in spec["argv"]:
        spec["argv"].append("--matplotlib=inline")
    spec_file.write_text(json.dumps(spec, indent=1) + "\n", encoding="utf-8")
    print(f"kernel {NAME!r} ({DISPLAY_NAME}) in {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
