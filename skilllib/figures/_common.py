"""Shared parts of the figures: colours and :func:`save` (PNG and SVG)."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt

#: Colours of the clusters, in cluster order (ordered by centre PV).
CLUSTER_COLORS = plt.get_cmap("tab10").colors


def unique_legend_entries(axes) -> tuple[list, list[str]]:
    """The legend handles and labels of several axes, each label once, in the order first met.

    Parameters
    ----------
    axes : iterable of matplotlib.axes.Axes
        The axes whose artists carry labels (text).

    Returns
    -------
    tuple of (list, list of str)
        The handles and their labels (text), for one legend of the whole figure.
    """
    handles, labels = [], []
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    return handles, labels


#: A plot with more points than this (scatter points, line vertices) has its data drawn as an image in the SVG.
DENSE = 20_000


def save(fig: plt.Figure, out_dir: str | Path, name: str, dpi: int = 150) -> list[Path]:
    """Write ``fig`` as ``out_dir/name.png`` and ``out_dir/name.svg``; return both paths.

    In the SVG, a plot holding more than :data:`DENSE` points in all (a corpus of 10^5 trials) has its data
    layers rasterized at ``dpi``, so that the file stays small (axes, text and sparse layers stay vectors).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    out_dir : str or pathlib.Path
        The folder (text), created when missing.
    name : str
        The file name without extension (text).
    dpi : int
        Resolution of the PNG and of the rasterized SVG layers (dots per inch).

    Returns
    -------
    list of pathlib.Path
        The PNG and the SVG written.
    """
    for ax in fig.axes:
        layers = [
            (c, max(len(c.get_offsets()), sum(len(p.vertices) for p in c.get_paths()))) for c in ax.collections
        ] + [(line, len(line.get_xdata())) for line in ax.lines]
        if sum(n for _, n in layers) > DENSE:  # the axes' data layers as one image; reference lines stay vectors
            for artist, n in layers:
                artist.set_rasterized(n > 100)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / f"{name}.png", out / f"{name}.svg"]
    fig.savefig(paths[0], dpi=dpi, bbox_inches="tight")
    fig.savefig(paths[1], bbox_inches="tight", metadata={"Date": None})
    return paths
