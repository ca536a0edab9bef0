"""Figures of the transfer to an arm with dynamics: joint accelerations and torques against their limits,
commanded against executed tool speed, the time scale every limit asks for."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np

from ..robot import LIMIT_NAMES, Assessment, JointDynamics
from ..smoothness import sparc
from ._common import unique_legend_entries
from ._style import book_figure, grid
from .robot import JOINT_COLORS

#: Colours of the three limits in the time-scale figure.
LIMIT_COLORS = {"velocity": "#4C72B0", "acceleration": "#DD8452", "torque": "#55A868"}


def _panels(n_panels: int, ncols: int, sharey: bool = True) -> tuple[plt.Figure, np.ndarray, float]:
    nrows, ncols, width = grid(n_panels, ncols, 3.0)
    height = 2.8 * nrows + 0.8
    fig, axs = plt.subplots(nrows, ncols, figsize=(width, height), sharex=True, sharey=sharey, squeeze=False)
    for ax in axs.flat[n_panels:]:
        ax.set_visible(False)
    return fig, axs, height


def _title(d: JointDynamics, i: int, titles: Sequence[str] | None) -> str:
    r = d.transfer
    return titles[i] if titles else (f"cluster {r.cluster}" if r.cluster is not None else f"trajectory {i}")


def _joint_figure(
    dyns: Sequence[JointDynamics],
    series: Callable[[JointDynamics], np.ndarray],
    limits: Callable[[JointDynamics], np.ndarray | None],
    ylabel: str,
    unit: str,
    describe: Callable[[JointDynamics], str],
    suptitle: str,
    titles: Sequence[str] | None,
    ncols: int,
    extra: Callable[[plt.Axes, JointDynamics], None] | None = None,
) -> plt.Figure:
    """One panel per trajectory: a quantity per joint against time with +-its limits (dashed)."""
    if not dyns:
        raise ValueError("the figure needs at least one JointDynamics")
    fig, axs, height = _panels(len(dyns), ncols)
    for i, (ax, d) in enumerate(zip(axs.flat, dyns)):
        y = series(d)
        t = d.transfer.t - d.transfer.t[0]
        for j in range(y.shape[1]):
            ax.plot(t, y[:, j], color=JOINT_COLORS[j % len(JOINT_COLORS)], lw=1.5, label=f"$q_{j + 1}$")
        lim = limits(d)
        if lim is not None:
            for g, value in enumerate(np.unique(lim)):
                joints = np.nonzero(lim == value)[0] + 1
                who = "" if joints.size == y.shape[1] else " ($q_{" + ",".join(str(j) for j in joints) + "}$)"
                for sgn in (1, -1):
                    ax.axhline(
                        sgn * value,
                        color=("k", "0.45", "0.7")[g % 3],
                        ls=("--", "-.", ":")[g % 3],
                        lw=0.9,
                        label=(f"limit ±{value:.4g}" + ("" if unit == "1" else f" {unit}") + who) if sgn > 0 else None,
                    )
        if extra is not None:
            extra(ax, d)
        ax.axhline(0, color="0.7", lw=0.5)
        ax.set_title(f"{_title(d, i, titles)}: {describe(d)}", fontsize="small")
        ax.grid(alpha=0.3)
    for ax in axs[-1]:
        ax.set_xlabel("time from start (s)")
    for ax in axs[:, 0]:
        ax.set_ylabel(ylabel if unit == "1" else f"{ylabel} ({unit})")
    handles, labels = axs.flat[0].get_legend_handles_labels()
    width = fig.get_figwidth()
    per_row = min(len(labels), int(width / 1.1))
    fig.legend(
        handles,
        labels,
        loc="upper center",
        ncol=per_row,
        frameon=False,
        bbox_to_anchor=(0.5, 1 - 0.3 / height),
        fontsize="small",
    )
    fig.suptitle(suptitle, y=0.995, fontsize="medium")
    rows = -(-len(labels) // per_row)
    fig.tight_layout(rect=(0, 0, 1, 1 - (0.3 + 0.2 * rows) / height))
    return fig


@book_figure
def plot_joint_accelerations(
    dyns: Sequence[JointDynamics], titles: Sequence[str] | None = None, ncols: int = 3
) -> plt.Figure:
    """Joint accelerations qdd_j(t) of each trajectory against time, one panel each.

    Accelerations in rad/s^2 against time in s, with the acceleration limits dashed (when the arm has
    them); the title gives the peak and the stretch s_a the limits ask for alone.
    qdd = J^+ (a - Jdot qd) (+ the pseudo-inverse's null-space term; skilllib.robot).

    Parameters
    ----------
    dyns : sequence of JointDynamics
        The trajectories' dynamics (rad/s^2, N m).
    titles : sequence of str or None
        A title per panel (text); None: default titles.
    ncols : int
        Panels per row (dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; joint acceleration (rad/s^2) against time (s).
    """

    def describe(d: JointDynamics) -> str:
        s_a = d.time_scales()["acceleration"]
        peak = np.nanmax(d.peak_abs_qdd)
        return f"max {peak:.1f} rad/s²" + ("" if s_a is None else f", $s_a$ = {s_a:.2f}")

    if not dyns:
        raise ValueError("plot_joint_accelerations needs at least one JointDynamics")
    return _joint_figure(
        dyns,
        lambda d: d.qdd,
        lambda d: d.qdd_limits,
        "joint acceleration",
        "rad/s²",
        describe,
        f"{dyns[0].transfer.robot}: joint accelerations",
        titles,
        ncols,
    )


@book_figure
def plot_joint_torques(
    dyns: Sequence[JointDynamics], titles: Sequence[str] | None = None, ncols: int = 3
) -> plt.Figure:
    """Joint torques tau_j(t) of each trajectory against time, each divided by its joint's torque limit.

    Torques from roboticstoolbox ``rne`` (rigid body, motor inertia, friction) against time (s), so that
    +-1, dashed, is the limit of every joint; thin dotted lines: the same path traversed very slowly
    (gravity and Coulomb friction only: what no time scaling removes). Without torque limits the torques
    in N m.

    Parameters
    ----------
    dyns : sequence of JointDynamics
        The trajectories' dynamics (torques in N m).
    titles : sequence of str or None
        A title per panel (text); None: default titles.
    ncols : int
        Panels per row (dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; torque / limit (dimensionless), or N m, against time (s).
    """
    if not dyns or any(d.tau is None for d in dyns):
        raise ValueError("torques need at least one trajectory on an arm with dynamic parameters")
    limited = all(d.tau_limits is not None for d in dyns)

    def norm(d: JointDynamics, tau: np.ndarray) -> np.ndarray:
        return tau / d.tau_limits if limited else tau

    def describe(d: JointDynamics) -> str:
        if limited:
            j = int(np.nanargmax(d.peak_abs_tau / d.tau_limits))
            return f"max |τ|/limit {d.peak_abs_tau[j] / d.tau_limits[j]:.2f} ($q_{j + 1}$: {d.peak_abs_tau[j]:.0f} N m)"
        return f"max |τ| {np.nanmax(d.peak_abs_tau):.1f} N m"

    def slow(ax: plt.Axes, d: JointDynamics) -> None:
        rest = norm(d, d.torques(1e6))
        t = d.transfer.t - d.transfer.t[0]
        for j in range(rest.shape[1]):
            ax.plot(t, rest[:, j], color=JOINT_COLORS[j % len(JOINT_COLORS)], lw=0.9, ls=":")

    return _joint_figure(
        dyns,
        lambda d: norm(d, d.tau),
        lambda d: np.ones(d.tau.shape[1]) if limited else None,
        "joint torque / its limit" if limited else "joint torque",
        "1" if limited else "N m",
        describe,
        f"{dyns[0].transfer.robot}: joint torques (dotted: the same path at rest speed)",
        titles,
        ncols,
        extra=slow,
    )


@book_figure
def plot_executed_speed(
    assessments: Sequence[Assessment], titles: Sequence[str] | None = None, ncols: int = 3
) -> plt.Figure:
    """Commanded and executed tool speed against time, one panel per prototype.

    Speed in m/s against time in s: the prototype's speed at its samples (black dots), the simulated
    execution as recorded (coloured, controller rate) and the execution slowed by the time scale s of every
    limit, drawn on the recorded time axis (t / s) with its speed times s (dashed), so that a faithful
    slowed execution lies on the black dots. The title gives SPARC of the three.

    Parameters
    ----------
    assessments : sequence of Assessment
        The assessments of :mod:`skilllib.robot` (speeds in m/s, times in s).
    titles : sequence of str or None
        A title per panel (text); None: default titles.
    ncols : int
        Panels per row (dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; tool speed (m/s) against time (s).
    """
    if not assessments:
        raise ValueError("plot_executed_speed needs at least one Assessment")
    fig, axs, height = _panels(len(assessments), ncols)
    for i, (ax, a) in enumerate(zip(axs.flat, assessments)):
        r = a.transfer
        t0 = r.t[0]
        speed = np.linalg.norm(r.v_base, axis=1)
        ax.plot(r.t - t0, speed, "o", color="k", ms=3.5, label="commanded (prototype)", zorder=3)
        parts = []
        e, es = a.executed, a.executed_scaled
        if e is not None:
            ax.plot(e.t - t0, e.speed, color="#C44E52", lw=1.6, label="executed as recorded")
            parts.append(f"exec. {e.sparc:.3f}")
        if es is not None and es.time_scale > 1:
            s = es.time_scale
            ax.plot(
                (es.t - t0) / s,
                es.speed * s,
                color="#4C72B0",
                lw=1.4,
                ls="--",
                label="executed slowed by s (t / s, speed × s)",
            )
            parts.append(f"slowed {es.sparc:.3f}")
        fs = (len(r.t) - 1) / (r.t[-1] - r.t[0]) if len(r.t) > 1 else np.nan
        proto = sparc(speed, fs) if len(r.t) > 1 else np.nan
        scale = a.dynamics.time_scale
        head = (
            f"{_title(a.dynamics, i, titles)}, s = {scale:.2f}" if np.isfinite(scale) else _title(a.dynamics, i, titles)
        )
        ax.set_title(f"{head}\nSPARC {proto:.3f}; " + "; ".join(parts), fontsize="small")
        ax.grid(alpha=0.3)
    for ax in axs[-1]:
        ax.set_xlabel("time from start (s)")
    for ax in axs[:, 0]:
        ax.set_ylabel("tool speed (m/s)")
    handles, labels = unique_legend_entries(axs.flat)
    fig.legend(
        handles,
        labels,
        loc="upper center",
        ncol=len(labels),
        frameon=False,
        bbox_to_anchor=(0.5, 1 - 0.3 / height),
        fontsize="small",
    )
    fig.suptitle(f"{assessments[0].transfer.robot}: commanded and executed tool speed", y=0.995, fontsize="medium")
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.55 / height))
    return fig


@book_figure
def dynamics_figures(assessments: Sequence[Assessment]) -> list[tuple[plt.Figure, str]]:
    """The pipeline's figures of the assessments of one arm, with their file names.

    Joint accelerations, joint torques (arms with dynamic parameters), executed speed and time scales.

    Parameters
    ----------
    assessments : sequence of Assessment
        The assessments of one arm (rad/s^2, N m, m/s).

    Returns
    -------
    list of tuple
        (figure, file name without extension (text)) pairs.
    """
    dyns = [a.dynamics for a in assessments]
    out = [(plot_joint_accelerations(dyns), "joint_accelerations")]
    if all(d.tau is not None for d in dyns):
        out.append((plot_joint_torques(dyns), "joint_torques"))
    out.append((plot_executed_speed(assessments), "executed_speed"))
    out.append((plot_time_scales({dyns[0].transfer.robot: dyns}), "time_scales"))
    return out


@book_figure
def plot_time_scales(by_arm: Mapping[str, Sequence[JointDynamics]]) -> plt.Figure:
    """The stretch s each limit asks for alone and the one that satisfies all, per prototype and arm.

    Markers: velocity, acceleration, torque (absent where the arm has no such limit); black dash: the one
    that satisfies all, labelled with the binding limit; per prototype (cluster) and arm (one panel each).
    s = 1: executable as recorded.

    Parameters
    ----------
    by_arm : mapping of str to sequence of JointDynamics
        Arm name (text) -> the dynamics of its prototypes (time scales dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; time scale s (dimensionless) per prototype.
    """
    if not by_arm:
        raise ValueError("plot_time_scales needs at least one arm")
    n = len(by_arm)
    nrows, ncols, width = grid(n, 2, 4.5)
    fig, axs = plt.subplots(nrows, ncols, figsize=(width, 3.0 * nrows + 0.6), sharey=True, squeeze=False)
    for ax in axs.flat[n:]:
        ax.set_visible(False)
    markers = {"velocity": "o", "acceleration": "s", "torque": "^"}
    top = 1.0
    for ax, (arm, dyns) in zip(axs.flat, by_arm.items()):
        x = np.arange(len(dyns))
        for m, name in enumerate(LIMIT_NAMES):
            vals = np.array([np.nan if (v := d.time_scales()[name]) is None else v for d in dyns], dtype=float)
            if np.isfinite(vals).any():
                ax.plot(
                    x + (m - 1) * 0.18,
                    vals,
                    markers[name],
                    color=LIMIT_COLORS[name],
                    ms=6,
                    label=f"{name} alone",
                    zorder=3,
                )
                top = max(top, np.nanmax(vals[np.isfinite(vals)]))
        for xi, d in zip(x, dyns):
            s = d.time_scale
            if np.isfinite(s):
                ax.plot([xi - 0.35, xi + 0.35], [s, s], color="k", lw=2, zorder=2)
                if d.binding_limit:
                    ax.text(xi, s + 0.04, d.binding_limit[:3] + ".", ha="center", va="bottom", fontsize="small")
        ax.axhline(1, color="0.5", lw=0.8, ls="--")
        ax.set_xticks(x, [str(d.transfer.cluster if d.transfer.cluster is not None else i) for i, d in enumerate(dyns)])
        ax.set_xlabel("cluster", fontsize="small")
        ax.set_title(arm, fontsize="medium")
        ax.grid(alpha=0.3, axis="y")
    axs[0, 0].set_ylim(0.9, top * 1.08 + 0.1)
    for ax in axs[:, 0]:
        ax.set_ylabel("time scale s")
    handles, labels = unique_legend_entries(axs.flat)
    order = [labels.index(f"{name} alone") for name in LIMIT_NAMES if f"{name} alone" in labels]
    handles = [handles[i] for i in order] + [plt.Line2D([], [], color="k", lw=2)]
    labels = [labels[i] for i in order] + ["all limits (binding one named)"]
    fig.legend(handles, labels, loc="upper center", ncol=len(labels), frameon=False, fontsize="small")
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.45 / fig.get_figheight()))
    return fig
