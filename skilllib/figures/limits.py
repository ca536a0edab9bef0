"""The robot verdicts against the limits they assume: how many prototypes an arm executes as recorded when
one kind of limit (velocity, acceleration, torque) is scaled, the others as assumed."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from ..robot import LIMIT_NAMES, Assessment, JointDynamics, feasible_counts, limit_margins, verdict_range
from ._common import unique_legend_entries
from ._style import book_figure, grid
from .dynamics import LIMIT_COLORS

#: Unit of each kind of limit, as the axes write it.
_AXIS_UNITS = {"velocity": "rad/s", "acceleration": "rad/s²", "torque": "N m"}


def _plain_log_ticks(axis: plt.Axis) -> None:
    """Ticks at 1, 2 and 5 times the powers of ten, written as plain numbers (0.2, 5, 20) on a log axis."""
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))
    axis.set_minor_formatter(NullFormatter())


@book_figure
def plot_limit_sensitivity(
    by_arm: Mapping[str, Sequence[JointDynamics | Assessment]],
    kinds: Sequence[str] = LIMIT_NAMES,
    scale_range: tuple[float, float] = (0.1, 10.0),
    top_axis: str | None = "acceleration",
) -> plt.Figure:
    """Per arm, the number of prototypes executable as recorded against the scale of each kind of limit.

    One panel per arm; one step line per kind of limit the arm has (:func:`skilllib.robot.feasible_counts`:
    every joint's limit of that kind multiplied by the scale, the other limits as assumed), slightly offset
    vertically so that lines on the same count stay visible. The assumed limits (scale 1) are the dotted
    vertical line, the count there a black dot, and the range of the ``top_axis`` kind over which that count
    holds (:func:`skilllib.robot.verdict_range`) is shaded. Where that kind's limit is one number for every
    joint, a top axis gives it in its unit.

    Parameters
    ----------
    by_arm : mapping of str to sequence of JointDynamics or Assessment
        Arm name (text) -> its prototypes' assessments: qd (rad/s), qdd (rad/s^2), tau (N m) with limits.
    kinds : sequence of str
        The kinds of limit drawn, of ``velocity``, ``acceleration``, ``torque`` (text).
    scale_range : tuple of float
        The smallest and largest scale drawn (dimensionless, log axis).
    top_axis : str or None
        The kind whose range is shaded and, when uniform over the joints, shown on a top axis in its unit
        (rad/s, rad/s^2, N m); None for neither.

    Returns
    -------
    matplotlib.figure.Figure
        Count of prototypes (dimensionless) against the scale of the limits (dimensionless).

    Raises
    ------
    ValueError
        No arm, an unknown kind, or a scale range that is not positive and increasing.
    """
    if not by_arm:
        raise ValueError("plot_limit_sensitivity needs at least one arm")
    bad = [k for k in kinds if k not in LIMIT_NAMES] + ([top_axis] if top_axis not in (*LIMIT_NAMES, None) else [])
    if bad:
        raise ValueError(f"unknown limit {bad[0]!r}; valid: {', '.join(LIMIT_NAMES)}")
    lo, hi = map(float, scale_range)
    if not 0 < lo < hi:
        raise ValueError(f"scale_range must be positive and increasing (dimensionless), got {scale_range}")
    n = len(by_arm)
    nrows, ncols, width = grid(n, 2, 4.5)
    fig, axs = plt.subplots(nrows, ncols, figsize=(width, 3.3 * nrows + 0.6), squeeze=False)
    for ax in axs.flat[n:]:
        ax.set_visible(False)
    offsets = {k: 0.08 * (i - 1) for i, k in enumerate(LIMIT_NAMES)}
    for ax, (arm, assessed) in zip(axs.flat, by_arm.items()):
        margins = limit_margins(assessed)
        n_protos = len(margins)
        top_limit = None
        for kind in kinds:
            v = verdict_range(margins, kind)
            if v is None:
                continue
            inside = v.steps[(v.steps > lo) & (v.steps < hi)]
            xs = np.r_[lo, inside, hi]
            ax.step(
                xs,
                feasible_counts(margins, kind, xs) + offsets[kind],
                where="post",
                color=LIMIT_COLORS[kind],
                lw=1.8,
                label=f"{kind} limits scaled",
            )
            if kind == top_axis:
                ax.axvspan(max(v.lo, lo), min(v.hi, hi), color=LIMIT_COLORS[kind], alpha=0.12, lw=0)
                top_limit = v.assumed
        ax.plot([1.0], [sum(m.feasible for m in margins)], "o", color="k", ms=5, zorder=4)
        ax.axvline(1.0, color="k", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_xlim(lo, hi)
        _plain_log_ticks(ax.xaxis)
        if top_limit is not None:  # after the log scale, which would reset a secondary axis' ticks
            a = top_limit
            top = ax.secondary_xaxis("top", functions=(lambda x, a=a: x * a, lambda y, a=a: y / a))
            top.set_xlabel(f"{top_axis} limit ({_AXIS_UNITS[top_axis]}), every joint", fontsize="small")
            _plain_log_ticks(top.xaxis)
            top.tick_params(labelsize="small")
        ax.set_ylim(-0.4, n_protos + 0.4)
        ax.set_yticks(range(n_protos + 1))
        ax.set_xlabel("scale of the assumed limits", fontsize="small")
        ax.set_ylabel("prototypes executable as recorded", fontsize="small")
        ax.set_title(arm, fontsize="medium", loc="left")
        ax.grid(alpha=0.3)
    handles, labels = unique_legend_entries(axs.flat)
    order = sorted(range(len(labels)), key=lambda i: [f"{k} limits scaled" for k in LIMIT_NAMES].index(labels[i]))
    handles = [handles[i] for i in order] + [plt.Line2D([], [], color="k", marker="o", ls=":", lw=0.8)]
    labels = [labels[i] for i in order] + ["limits assumed"]
    fig.legend(handles, labels, loc="upper center", ncol=len(labels), frameon=False, fontsize="small")
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.4 / fig.get_figheight()))
    return fig
