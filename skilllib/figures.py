"""The figures of the pipeline; the chapters draw the same ones.

Every function takes data (arrays, DataFrames, result objects) and returns a matplotlib Figure;
``save`` writes it as PNG and SVG. Axes carry units. This module may import the other skilllib
modules; none of them imports it.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib


import matplotlib.pyplot as plt  # noqa: E402

#: Colours of the clusters, in cluster order (ordered by centre PV).
CLUSTER_COLORS = plt.get_cmap("tab10").colors


def save(fig: plt.Figure, out_dir: str | Path, name: str, dpi: int = 150) -> list[Path]:
    """Write ``fig`` as ``out_dir/name.png`` and ``out_dir/name.svg``; return both paths."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / f"{name}.png", out / f"{name}.svg"]
    fig.savefig(paths[0], dpi=dpi, bbox_inches="tight")
    fig.savefig(paths[1], bbox_inches="tight", metadata={"Date": None})
    return paths


# --- smoothness (issue 3) --------------------------------------------------------------------

# --- the experiment and its data (issue 4) ---------------------------------------------------

# --- clusters and prototypes (issue 5) -------------------------------------------------------

# --- transfer to the robot (issue 6) ---------------------------------------------------------
