"""The book's draw among many draws of the generative model: one strip per headline quantity."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from ..cohort import DRAW_QUANTITIES, SEED
from ._style import WIDE, book_figure

#: Colours: the draws, the book's draw, the paper's value.
DRAW_COLOR, BOOK_COLOR, PAPER_COLOR = "0.55", "tab:red", "black"


def _value_text(v: float) -> str:
    """A value in its unit for the right margin: integers as such, others to 3 decimals (``0.000``)."""
    return f"{v:.0f}" if float(v).is_integer() or abs(v) >= 100 else f"{v:.3f}"


@book_figure
def plot_draws(
    table: pd.DataFrame,
    seed: int = SEED,
    columns: Sequence[str] | None = None,
    labels: Mapping[str, str] | None = None,
    paper: Mapping[str, float] | None = None,
) -> plt.Figure:
    """One strip per quantity: every draw as a dot, the book's draw highlighted, normalised per quantity.

    Each quantity x is drawn as z = (x - mean) / SD over the draws (a quantity equal in every draw at z = 0),
    so that quantities in different units share one axis. The draws are grey dots (spread a little vertically,
    seeded), the book's draw a red diamond and a published value, where given, a black cross. The right
    margin gives each quantity's range over the draws and the book's value, in the quantity's own unit.

    Parameters
    ----------
    table : pandas.DataFrame
        A :func:`skilllib.cohort.replication_table` (index ``seed``; PV in m/s, the rest counts or
        dimensionless).
    seed : int
        The book's draw (dimensionless); default :data:`skilllib.cohort.SEED`.
    columns : sequence of str or None
        The quantities, top to bottom (text); None: every column that is not boolean.
    labels : mapping of str to str or None
        The label of each quantity (text); default :data:`skilllib.cohort.DRAW_QUANTITIES`.
    paper : mapping of str to float or None
        Published values of some quantities (m/s for speeds, dimensionless otherwise: each
        quantity's unit), drawn as crosses.

    Returns
    -------
    matplotlib.figure.Figure
        The strips: z (dimensionless, SDs from the draws' mean) per quantity.

    Raises
    ------
    ValueError
        When ``seed`` is not a row of the table or a column is missing.
    """
    cols = list(columns) if columns is not None else [c for c in table.columns if table[c].dtype != bool]
    missing = [c for c in cols if c not in table.columns]
    if missing:
        raise ValueError(f"no column(s) {missing} in the table")
    if seed not in table.index:
        raise ValueError(f"seed {seed} is not a row of the table")
    names = {**DRAW_QUANTITIES, **(labels or {})}
    paper = dict(paper or {})
    rng = np.random.default_rng(0)
    fig, ax = plt.subplots(figsize=(WIDE, 0.36 * len(cols) + 1.3))
    for i, col in enumerate(cols):
        x = table[col].astype(float)
        mean, sd = x.mean(), x.std(ddof=1)
        z = (x - mean) / sd if sd > 0 else x * 0.0
        y = -i + rng.uniform(-0.18, 0.18, len(x))
        ax.scatter(z, y, s=14, color=DRAW_COLOR, alpha=0.8, linewidths=0, label="draws" if i == 0 else None)
        ax.scatter(
            z.loc[seed],
            -i,
            s=60,
            marker="D",
            color=BOOK_COLOR,
            zorder=3,
            label=f"book (seed {seed})" if i == 0 else None,
        )
        if col in paper:
            zp = (paper[col] - mean) / sd if sd > 0 else 0.0
            ax.scatter(zp, -i, s=70, marker="X", color=PAPER_COLOR, zorder=4, label="paper")
        text = f"{_value_text(x.min())} to {_value_text(x.max())}  (book {_value_text(x.loc[seed])})"
        ax.annotate(text, (1.01, -i), xycoords=("axes fraction", "data"), va="center", fontsize=8)
    ax.set_yticks(-np.arange(len(cols)), [names.get(c, c) for c in cols], fontsize=8)
    ax.set_ylim(-len(cols) + 0.5, 0.5)
    ax.axvline(0.0, color="0.8", lw=0.8, zorder=0)
    for yy in -np.arange(len(cols)):
        ax.axhline(yy - 0.5, color="0.92", lw=0.6, zorder=0)
    ax.set_xlabel("(value − mean of the draws) / SD of the draws")
    ax.annotate("range over the draws (book)", (1.01, 0.5), xycoords=("axes fraction", "data"), va="bottom", fontsize=8)
    handles, labs = ax.get_legend_handles_labels()
    seen = dict(zip(labs, handles))
    ax.legend(
        seen.values(),
        [f"{len(table)} draws" if k == "draws" else k for k in seen],
        loc="lower center",
        bbox_to_anchor=(0.5, 1.0),
        ncol=len(seen),
        fontsize=8,
        frameon=False,
    )
    fig.tight_layout()
    return fig
