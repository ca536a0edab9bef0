"""The scaling figure of the chapter "At scale": wall time and peak memory of whole runs against the
number of trials, from the measurements of ``benchmarks/bench_scale.py`` (its JSON ``rows``)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import matplotlib.ticker as mticker
import numpy as np

from ._style import book_figure

#: Series of the benchmark: (mode, input) -> label and colour.
SERIES = {
    ("inmemory", "csv"): ("in memory, one CSV file", "tab:blue"),
    ("inmemory", "parquet"): ("in memory, Parquet folder", "tab:green"),
    ("dask", "parquet"): ("Dask, 2 local workers, Parquet folder", "tab:orange"),
}


@book_figure
def plot_scaling(rows: Sequence[dict[str, Any]]) -> plt.Figure:
    """Wall time and peak memory against the number of trials, per series.

    Top: wall time (s) against trials, log-log, per series, with a dotted line of slope 1 over the last
    decade through the in-memory CSV series' largest run; bottom: peak memory (MB) of the main process
    (solid) and of the largest Dask worker (dashed). Failed runs are left out (the table beside the figure
    lists them).

    Parameters
    ----------
    rows : sequence of dict
        The benchmark's runs: series name (text), trials (dimensionless), wall time (s), memory (MB).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; time (s) and memory (MB) against trials.
    """
    fig, (a, b) = plt.subplots(2, 1, figsize=(6.4, 8.2))
    for (mode, kind), (label, color) in SERIES.items():
        ok = sorted(
            (r for r in rows if r["mode"] == mode and r["input"] == kind and not r["failed"]), key=lambda r: r["trials"]
        )
        if not ok:
            continue
        n = np.array([r["trials"] for r in ok], dtype=float)
        a.plot(n, [r["wall_s"] for r in ok], "o-", color=color, label=label)
        b.plot(n, [r["peak_main_mb"] for r in ok], "o-", color=color, label=f"{label}: main process")
        if mode == "dask":
            b.plot(n, [r["peak_worker_mb"] for r in ok], "s--", color=color, label="largest Dask worker")
        if (mode, kind) == ("inmemory", "csv") and len(n) > 1:
            ref = np.array([n[-1] / 10, n[-1]])
            a.plot(
                ref, ok[-1]["wall_s"] * ref / n[-1], ":", color="0.4", lw=2, label="slope 1 (time proportional to N)"
            )
    for ax, what in ((a, "wall time (s)"), (b, "peak memory (MB)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("trials N")
        ax.set_ylabel(what)
        ax.grid(True, which="both", alpha=0.3)
        ax.yaxis.set_major_locator(mticker.LogLocator(base=10, subs=(1, 2, 5)))
        ax.yaxis.set_major_formatter(mticker.FuncFormatter(lambda v, _: f"{v:,.0f}" if v >= 1 else f"{v:g}"))
        ax.yaxis.set_minor_formatter(mticker.NullFormatter())
        ax.legend(fontsize="small", frameon=False)
    a.set_title("time of a whole run without figures")
    b.set_title("peak resident memory")
    fig.tight_layout()
    return fig
