"""Shared parts of the figures: colours and :func:`save` (PNG and SVG)."""
from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt

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

