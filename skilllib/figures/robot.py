"""Figures of the transfer chapter: the robot, the frame mapping, joint velocities, time scaling.

The 3-D figures draw the arm with roboticstoolbox's PyPlot backend. In a notebook that backend displays
SVG snapshots of its own and switches matplotlib's interactive mode off; the functions here swallow the
former and restore the latter (:func:`_quiet_robot_plot`), so that a chapter calls them like any other
figure function and sees the returned figure once.
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import roboticstoolbox as rtb
from matplotlib.ticker import MaxNLocator

with plt.rc_context():  # roboticstoolbox's PyPlot backend sets the ggplot style globally on import;
    import roboticstoolbox.backends.PyPlot.PyPlot  # noqa: F401  the context undoes that.

from ..robot import DEFAULT_POSE_DEG, EXP_TO_BASE, TransferResult, default_pose, joint_origins, simple6
from ._common import CLUSTER_COLORS
from ._style import WIDE, book_figure, grid

#: Colours of the joints q1..q7 in the transfer figures.
JOINT_COLORS = plt.get_cmap("Dark2").colors

_F = TypeVar("_F", bound=Callable[..., Any])


def _quiet_robot_plot(draw: _F) -> _F:
    """Wrap a figure function that draws with roboticstoolbox's PyPlot backend: in IPython, the backend's
    own display of SVG snapshots is captured (and dropped) and matplotlib's interactive mode is restored
    to what it was before the call; outside IPython only the latter."""

    @functools.wraps(draw)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        interactive = plt.isinteractive()
        try:
            from IPython.utils.capture import capture_output
        except ImportError:  # pragma: no cover - IPython ships with the book's environment
            capture_output = contextlib.nullcontext
        try:
            with capture_output():
                return draw(*args, **kwargs)
        finally:
            if interactive:
                plt.ion()
            else:
                plt.ioff()

    return wrapper  # type: ignore[return-value]


def _auto_limits(points: np.ndarray, margin: float) -> list[float]:
    """Cubic 3-D limits [x0, x1, y0, y1, z0, z1] (m) around ``points`` plus ``margin`` m."""
    lo, hi = points.min(axis=0) - margin, points.max(axis=0) + margin
    half = float((hi - lo).max()) / 2
    mid = (lo + hi) / 2
    return [float(v) for m in mid for v in (m - half, m + half)]


def _metre_labels(ax: plt.Axes) -> None:
    """Axis labels in m (roboticstoolbox writes X, Y, Z on every ``plot``)."""
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")


def _draw_robot(ax: plt.Axes, robot: rtb.DHRobot, q: np.ndarray, limits: list[float], **plot_kwargs) -> None:
    """Draw ``robot`` at ``q`` on the 3-D axes ``ax`` with roboticstoolbox's PyPlot backend."""
    kw = dict(jointaxes=False, eeframe=False, shadow=False, name=False)
    kw.update(plot_kwargs)
    robot.plot(np.asarray(q, dtype=float), backend="pyplot", block=False, ax=ax, limits=limits, **kw)
    _metre_labels(ax)
    base = robot.base.t
    ax.scatter(*base, marker="^", s=60, color="k", zorder=10)
    ax.set_box_aspect((1, 1, 1))
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(5))
    ax.tick_params(labelsize="small", pad=0)


def _label_joints(ax: plt.Axes, robot: rtb.DHRobot, q: np.ndarray, length: float) -> None:
    """Arrows along the joint axes of a standard-DH arm from the joint origins (black dots),
    labelled q1..qn beyond their tips on a white box (co-located axes stay legible)."""
    pos, axes = joint_origins(robot, q)
    ax.scatter(*np.unique(pos.round(9), axis=0).T, color="k", s=18, zorder=12, depthshade=False)
    for j, (p, a) in enumerate(zip(pos, axes)):
        c = JOINT_COLORS[j % len(JOINT_COLORS)]
        ax.quiver(*p, *(a * length), color=c, lw=2.2, arrow_length_ratio=0.18)
        ax.text(
            *(p + a * length * 1.38),
            f"$q_{j + 1}$",
            color=c,
            fontsize=13,
            ha="center",
            va="center",
            zorder=20,
            bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.8),
        )


def _label_tool_frame(ax: plt.Axes, T: np.ndarray, length: float) -> None:
    """The tool frame of the 4x4 pose ``T``: arrows x_t (red), y_t (green), z_t (blue), labelled."""
    for k, (name, c) in enumerate((("x", "#d62728"), ("y", "#2ca02c"), ("z", "#1f77b4"))):
        a = T[:3, k] * length
        ax.quiver(*T[:3, 3], *a, color=c, lw=2.2, arrow_length_ratio=0.18)
        ax.text(
            *(T[:3, 3] + a * 1.38),
            f"${name}_t$",
            color=c,
            fontsize=12,
            ha="center",
            va="center",
            zorder=20,
            bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.8),
        )


@book_figure
@_quiet_robot_plot
def plot_robot_joints(
    robot: rtb.DHRobot | None = None,
    q: np.ndarray | None = None,
    ax: plt.Axes | None = None,
    view: tuple[float, float] = (22.0, -35.0),
) -> plt.Figure:
    """An arm with its joint axes labelled q1..qn: paper Fig. 3a.

    Default: Simple6 at the paper's default pose. Joint j turns about the arrow labelled q_j (the z axis of
    DH frame j-1; Corke 2017, sec. 7.1); the arm is drawn by roboticstoolbox's PyPlot backend.

    Parameters
    ----------
    robot : roboticstoolbox.DHRobot or None
        The arm (lengths in m); None: Simple6.
    q : numpy.ndarray or None
        The joint angles (rad); None: the paper's default pose ``DEFAULT_POSE_DEG``.
    ax : matplotlib.axes.Axes or None
        The axes to draw into; None: a new figure.
    view : tuple of float
        (elevation, azimuth) of the 3-D view (deg).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; axes in m.
    """
    robot = simple6() if robot is None else robot
    q = default_pose() if q is None else np.asarray(q, dtype=float)
    pos, _ = joint_origins(robot, q)
    reach = float(robot.reach)
    pts = np.vstack([pos, robot.fkine(q).t, np.zeros(3)])
    limits = _auto_limits(pts, 0.3 * reach)
    fig = plt.figure(figsize=(5.5, 5.5)) if ax is None else ax.figure
    ax = ax or fig.add_subplot(111, projection="3d", proj_type="ortho")
    _draw_robot(ax, robot, q, limits)
    _label_joints(ax, robot, q, 0.25 * reach)
    ax.view_init(elev=view[0], azim=view[1])
    ax.set_title(f"{robot.name}: joint axes", fontsize="medium")
    return fig


@book_figure
@_quiet_robot_plot
def plot_robot_pose(
    robot: rtb.DHRobot | None = None,
    q: np.ndarray | None = None,
    ax: plt.Axes | None = None,
    view: tuple[float, float] = (18.0, -70.0),
) -> plt.Figure:
    """An arm in a pose: paper Fig. 3b.

    Default: Simple6 at the paper's default pose ``DEFAULT_POSE_DEG``. The tool frame is drawn (x_t red,
    y_t green, z_t blue); the tool point (m) and the joint angles (deg) are written on the figure.

    Parameters
    ----------
    robot : roboticstoolbox.DHRobot or None
        The arm (lengths in m); None: Simple6.
    q : numpy.ndarray or None
        The joint angles (rad); None: the paper's default pose ``DEFAULT_POSE_DEG``.
    ax : matplotlib.axes.Axes or None
        The axes to draw into; None: a new figure.
    view : tuple of float
        (elevation, azimuth) of the 3-D view (deg).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; axes in m.
    """
    robot = simple6() if robot is None else robot
    q = default_pose() if q is None else np.asarray(q, dtype=float)
    pos, _ = joint_origins(robot, q)
    tool = robot.fkine(q).t
    reach = float(robot.reach)
    limits = _auto_limits(np.vstack([pos, tool, np.zeros(3)]), 0.3 * reach)
    fig = plt.figure(figsize=(5.5, 5.5)) if ax is None else ax.figure
    ax = ax or fig.add_subplot(111, projection="3d", proj_type="ortho")
    _draw_robot(ax, robot, q, limits)
    _label_tool_frame(ax, robot.fkine(q).A, 0.25 * reach)
    ax.scatter(*tool, color="k", s=20, zorder=12, depthshade=False)
    ax.text2D(
        0.02,
        0.97,
        f"tool point ({tool[0]:.2f}, {tool[1]:.2f}, {tool[2]:.2f}) m, tool frame $x_t, y_t, z_t$; base ▲",
        transform=ax.transAxes,
        fontsize="small",
        va="top",
    )
    ax.view_init(elev=view[0], azim=view[1])
    deg = ", ".join(f"{v:g}" for v in np.round(np.rad2deg(q), 1))
    ax.set_title(f"{robot.name} at q = ({deg}) deg", fontsize="medium")
    return fig


@book_figure
@_quiet_robot_plot
def plot_simple6_figure() -> plt.Figure:
    """The paper's Fig. 3: (a) Simple6's joint labels, (b) its default pose, both at ``DEFAULT_POSE_DEG``.

    Returns
    -------
    matplotlib.figure.Figure
        The two panels; axes in m.
    """
    fig = plt.figure(figsize=(WIDE, 4.6))
    robot, q = simple6(), default_pose()
    a = fig.add_subplot(121, projection="3d", proj_type="ortho")
    b = fig.add_subplot(122, projection="3d", proj_type="ortho")
    plot_robot_joints(robot, q, ax=a)
    plot_robot_pose(robot, q, ax=b)
    a.set_title("(a) joint labels", fontsize="medium")
    b.set_title("(b) default pose q = (" + ", ".join(f"{v:g}" for v in DEFAULT_POSE_DEG) + ") deg", fontsize="medium")
    return fig


@book_figure
def plot_joint_velocities(
    results: list[TransferResult],
    qd_limits: float | np.ndarray | None = None,
    titles: list[str] | None = None,
    ncols: int = 3,
) -> plt.Figure:
    """Joint velocities qd_j(t) against time, one panel per transfer result: the paper's Fig. 4.

    Velocities in rad/s against time in s from movement start, one panel per prototype/cluster. Dashed
    lines: +-the joint velocity limits. Samples with a flag are marked with a red x on the time axis.
    Panels share the y axis so the prototypes can be compared.

    Parameters
    ----------
    results : list of TransferResult
        The transfers (joint velocities in rad/s).
    qd_limits : float, numpy.ndarray or None
        The joint velocity limits (rad/s), scalar or per joint; None: each result's own.
    titles : list of str or None
        A title per panel (text); None: default titles.
    ncols : int
        Panels per row (dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; joint velocity (rad/s) against time (s).
    """
    if not results:
        raise ValueError("plot_joint_velocities needs at least one TransferResult")
    n_panels = len(results)
    nrows, ncols, width = grid(n_panels, ncols, 3.0)
    height = 2.8 * nrows + 0.8
    fig, axs = plt.subplots(nrows, ncols, figsize=(width, height), sharex=True, sharey=True, squeeze=False)
    for i, (ax, r) in enumerate(zip(axs.flat, results)):
        n = r.qd.shape[1]
        lim = r.qd_limits if qd_limits is None else np.broadcast_to(np.asarray(qd_limits, float), (n,))
        t = r.t - r.t[0]
        for j in range(n):
            ax.plot(t, r.qd[:, j], color=JOINT_COLORS[j % len(JOINT_COLORS)], lw=1.5, label=f"$q_{j + 1}$")
        for g, value in enumerate(np.unique(lim)):
            joints = np.nonzero(lim == value)[0] + 1
            who = "" if joints.size == n else " ($q_{" + ",".join(str(j) for j in joints) + "}$)"
            for sgn in (1, -1):
                ax.axhline(
                    sgn * value,
                    color=("k", "0.45", "0.7")[g % 3],
                    ls=("--", "-.", ":")[g % 3],
                    lw=0.9,
                    label=f"limit ±{value:.4g} rad/s{who}" if sgn > 0 else None,
                )
        bad = sorted({f["sample"] for f in r.flags})
        if bad:
            ax.plot(t[bad], np.zeros(len(bad)), "x", color="r", ms=6, label="flagged sample")
        ax.axhline(0, color="0.7", lw=0.5)
        title = titles[i] if titles else (f"cluster {r.cluster}" if r.cluster is not None else f"trajectory {i}")
        peak = r.peak_abs_qd
        state = (
            "within limits"
            if r.feasible
            else (f"time scale {r.time_scale:.2f}" if not r.flags else f"{len(r.flags)} flagged samples")
        )
        peak_txt = f"{np.nanmax(peak):.2f}" if np.isfinite(peak).any() else "n/a"
        ax.set_title(f"{title}: max " + r"$|\dot{q}_j|$" + f" {peak_txt} rad/s, {state}", fontsize="small")
        ax.grid(alpha=0.3)
    for ax in axs.flat[n_panels:]:
        ax.set_visible(False)
    for ax in axs[-1]:
        ax.set_xlabel("time from start (s)")
    for ax in axs[:, 0]:
        ax.set_ylabel("joint velocity (rad/s)")
    handles, labels = axs.flat[0].get_legend_handles_labels()
    per_row = min(len(labels), int(width / 0.95))
    fig.legend(
        handles,
        labels,
        loc="upper center",
        ncol=per_row,
        frameon=False,
        bbox_to_anchor=(0.5, 1 - 0.3 / height),
        fontsize="small",
    )
    law = r"$\dot{q} = J(q)^{-1} v$" if results[0].qd.shape[1] == 6 else r"$\dot{q} = J(q)^{+} v$"
    fig.suptitle(f"{results[0].robot}: joint velocities {law}", y=0.995, fontsize="medium")
    legend_rows = -(-len(labels) // per_row)
    fig.tight_layout(rect=(0, 0, 1, 1 - (0.3 + 0.2 * legend_rows) / height))
    return fig


@book_figure
@_quiet_robot_plot
def plot_frame_mapping(
    robot: rtb.DHRobot,
    result: TransferResult,
    rotation: np.ndarray = EXP_TO_BASE,
    view: tuple[float, float] = (20.0, -55.0),
) -> plt.Figure:
    """The experiment frame and the robot base frame, with the mapped path and the arm.

    The arm is drawn at its start pose ``result.q0`` and (grey) at the last solved sample; the target path
    ``result.x_base`` (m, base frame) in black. Arrows: the base frame at the origin (x, y, z) and, at the
    path's start, the experiment axes x_e (mediolateral), y_e (up) and z_e (anteroposterior) as seen in the
    base frame, i.e. the columns of ``rotation`` (``p_base = rotation @ p_exp``).

    Parameters
    ----------
    robot : roboticstoolbox.DHRobot
        The arm (lengths in m).
    result : TransferResult
        Its transfer (joint angles in rad, path in m).
    rotation : numpy.ndarray, shape (3, 3)
        The rotation from the experiment frame to the base frame (dimensionless).
    view : tuple of float
        (elevation, azimuth) of the 3-D view (deg).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; axes in m.
    """
    R = np.asarray(rotation, dtype=float)
    reach = float(robot.reach)
    pos0, _ = joint_origins(robot, result.q0)
    pts = np.vstack([pos0, result.x_base, np.zeros(3)])
    limits = _auto_limits(pts, 0.25 * reach)
    fig = plt.figure(figsize=(6.5, 6))
    ax = fig.add_subplot(111, projection="3d", proj_type="ortho")
    _draw_robot(ax, robot, result.q0, limits, eeframe=False)
    ok = np.nonzero(np.all(np.isfinite(result.q), axis=1))[0]
    if ok.size and ok[-1] > 0:
        robot.plot(
            result.q[ok[-1]],
            backend="pyplot",
            block=False,
            ax=ax,
            limits=limits,
            jointaxes=False,
            eeframe=False,
            shadow=False,
            name=False,
            color="0.6",
        )
        _metre_labels(ax)
    x = result.x_base
    ax.plot(x[:, 0], x[:, 1], x[:, 2], color="k", lw=2.5, label="hand path (base frame)", zorder=20)
    ax.scatter(*x[-1], color="k", marker="v", s=40, zorder=21)
    L = 0.35 * reach
    for k, name in enumerate(("x", "y", "z")):
        e = np.eye(3)[k] * L
        ax.quiver(0, 0, 0, *e, color="0.3", lw=1.5, arrow_length_ratio=0.15)
        ax.text(
            *(e * 1.15),
            f"${name}_0$",
            color="0.3",
            fontsize=11,
            ha="center",
            va="center",
            bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.8),
        )
    exp_names = ("$x_e$ mediolateral", "$y_e$ up", "$z_e$ anteroposterior")
    for k in range(3):
        e = R[:, k] * L * 0.8
        c = JOINT_COLORS[k]
        ax.quiver(*x[0], *e, color=c, lw=2, arrow_length_ratio=0.15)
        ax.text(
            *(x[0] + e * 1.2),
            exp_names[k],
            color=c,
            fontsize=9,
            ha="center",
            va="center",
            bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.8),
        )
    ax.plot([], [], color="#E16F6D", lw=4, label="arm at the start pose $q_0$")
    ax.plot([], [], color="0.6", lw=4, label="arm at the last sample")
    ax.view_init(elev=view[0], azim=view[1])
    ax.set_title(f"{result.robot}: experiment frame (coloured) in the base frame (grey)", fontsize="medium")
    fig.legend(
        *ax.get_legend_handles_labels(),
        loc="lower center",
        bbox_to_anchor=(0.5, 0.07),
        ncol=3,
        fontsize="small",
        frameon=False,
    )
    return fig


@book_figure
@_quiet_robot_plot
def plot_start_poses(
    arms: list[tuple[rtb.Robot, TransferResult]], view: tuple[float, float] = (20.0, -55.0)
) -> plt.Figure:
    """Several arms, one panel each, at their start pose with the hand path the transfer made them follow.

    The start pose is ``result.q0``, the hand path ``result.x_base`` (m, base frame; black); the title
    gives the start pose (deg) and cond J there. Drawn with roboticstoolbox's PyPlot backend.

    Parameters
    ----------
    arms : list of tuple
        (robot, result) pairs: a roboticstoolbox arm (lengths in m) and its ``TransferResult`` (rad, m).
    view : tuple of float
        (elevation, azimuth) of the 3-D view (deg).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; axes in m.
    """
    if not arms:
        raise ValueError("plot_start_poses needs at least one (robot, TransferResult) pair")
    fig = plt.figure(figsize=(min(WIDE, 2.9 * len(arms)), 4.2))
    for i, (robot, r) in enumerate(arms):
        ax = fig.add_subplot(1, len(arms), i + 1, projection="3d", proj_type="ortho")
        frames = robot.fkine_all(r.q0)
        pts = np.vstack([np.array([T.t for T in frames]), r.x_base, np.zeros(3)])
        limits = _auto_limits(pts, 0.1 * float(np.ptp(pts, axis=0).max()))
        _draw_robot(ax, robot, r.q0, limits)
        flange, tool = frames[-1].t, robot.fkine(r.q0).t
        if np.linalg.norm(tool - flange) > 1e-9:  # a tool offset (Panda): drawn thinner
            ax.plot(*np.c_[flange, tool], color="#E16F6D", lw=2)
        ax.plot(*r.x_base.T, color="k", lw=3, zorder=20)
        ax.scatter(*r.x_base[-1], color="k", marker="v", s=30, zorder=21, depthshade=False)
        ax.view_init(elev=view[0], azim=view[1])
        cond = np.linalg.cond(robot.ets().jacob0(r.q0))
        deg = ", ".join(f"{v:.0f}" for v in np.rad2deg(r.q0))
        ax.set_title(f"{r.robot}\n$q_0$ = ({deg}) deg\ncond J = {cond:.1f}", fontsize="small")
        ax.tick_params(labelsize="small", pad=0)
        for axis, n in ((ax.xaxis, 3), (ax.yaxis, 3), (ax.zaxis, 4)):  # fewer ticks on the narrow axes
            axis.set_major_locator(MaxNLocator(n))
    fig.subplots_adjust(left=0.0, right=0.95, wspace=0.25)
    return fig


@book_figure
def plot_sparc_stretch(
    change_a: pd.DataFrame,
    change_b: pd.DataFrame,
    change_resampled: pd.DataFrame,
    time_scales: Sequence[float] | None = None,
    capped: Sequence[bool] | None = None,
    fs: float = 60.0,
    fc: float = 20.0,
    ncols: int = 3,
) -> plt.Figure:
    """The change of each prototype's SPARC when its speed profile is slowed by s, measured three ways.

    One panel per prototype (a column of the tables, its index the stretch s): (a) on the stretched
    samples with the cut-off scaled to fc / s (black dashed), (b) on a recording of the slowed movement at
    ``fs`` with the fixed cut-off ``fc`` (the cluster's colour) and the same recording with the cut-off
    fc / s (thick grey, under (b) where the two agree). Each is SPARC(s) - SPARC(1), as
    :func:`skilllib.robot.time_scaled_features` measures it.

    Parameters
    ----------
    change_a, change_b, change_resampled : pandas.DataFrame
        The three changes of SPARC (dimensionless), indexed by the stretch s (dimensionless), one column
        per cluster (its number, dimensionless).
    time_scales : sequence of float or None
        Per cluster, the stretch a limit asks for (dimensionless), drawn as a dotted vertical line where
        above 1; None: none.
    capped : sequence of bool or None
        Per cluster, whether its band is capped by ``fc`` (said in the title); None: not said.
    fs : float
        The recording's sampling rate, Hz (in the legend).
    fc : float
        SPARC's maximum cut-off, Hz (in the legend).
    ncols : int
        Panels per row (dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; change of SPARC (dimensionless) against the time scale s (dimensionless).
    """

    clusters = list(change_b.columns)
    if not clusters:
        raise ValueError("plot_sparc_stretch needs at least one cluster")
    ncols = min(ncols, len(clusters))
    nrows = -(-len(clusters) // ncols)
    fig, axes = plt.subplots(
        nrows, ncols, figsize=(8, 2.5 * nrows), sharex=True, sharey=True, squeeze=False, layout="constrained"
    )
    s = change_b.index.to_numpy(dtype=float)
    for i, (c, ax) in enumerate(zip(clusters, axes.flat)):
        ax.plot(s, change_resampled[c], color="0.7", lw=3)
        ax.plot(s, change_b[c], color=CLUSTER_COLORS[i % len(CLUSTER_COLORS)], lw=1.4)
        ax.plot(s, change_a[c], color="k", lw=1, ls="--")
        if time_scales is not None and time_scales[i] > 1:
            ax.axvline(time_scales[i], color="0.4", lw=1, ls=":")
        band = ", capped band" if capped is not None and capped[i] else ""
        ax.set_title(f"cluster {c}{band}", fontsize="medium")
    for ax in axes.flat[len(clusters) :]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("time scale s")
    for ax in axes[:, 0]:
        ax.set_ylabel("SPARC(s) - SPARC(1)")
    handles = [
        plt.Line2D([], [], color="k", lw=1, ls="--", label="(a) stretched samples, fc / s"),
        plt.Line2D([], [], color="0.2", lw=1.4, label=f"(b) {fs:g} Hz recording, fixed fc = {fc:g} Hz"),
        plt.Line2D([], [], color="0.7", lw=3, label=f"{fs:g} Hz recording, fc / s"),
    ]
    if time_scales is not None:
        handles.append(plt.Line2D([], [], color="0.4", lw=1, ls=":", label="stretch the limit asks for"))
    fig.legend(handles=handles, loc="outside lower center", ncols=2, fontsize="small", frameon=False)
    return fig


@book_figure
def plot_time_scaled_plane(
    data: pd.DataFrame,
    centres: pd.DataFrame,
    moved: pd.DataFrame,
    prototypes: pd.DataFrame,
    zoom: tuple[tuple[float, float], tuple[float, float]] | None = None,
    mark_centre: int | None = None,
    fs: float = 60.0,
) -> plt.Figure:
    """Where time scaling takes prototypes in the PV-SPARC plane: the whole plane and a zoom.

    Left: the trials (dots coloured by cluster), the prototypes (circles) and, for each slowed prototype,
    an arrow to (a) PV / s with SPARC on the stretched samples at fc / s (filled diamond) and (b) PV and
    SPARC of a recording of the slowed movement at ``fs`` with the fixed cut-off (open square). Right: the
    same zoomed in, each diamond joined to its square by a thin line.

    Parameters
    ----------
    data : pandas.DataFrame
        The clustered trials: columns ``pv`` (m/s), ``sparc`` (dimensionless) and ``cluster``
        (dimensionless), as :attr:`skilllib.prototypes.PrototypeResult.data`.
    centres : pandas.DataFrame
        The cluster centres, columns ``pv`` (m/s) and ``sparc`` (dimensionless), indexed by cluster.
    moved : pandas.DataFrame
        One row per slowed prototype, indexed by its cluster: ``pv_a`` (m/s) and ``sparc_a``
        (dimensionless) of (a), ``pv_b`` (m/s) and ``sparc_b`` (dimensionless) of (b).
    prototypes : pandas.DataFrame
        The prototypes before scaling, columns ``pv`` (m/s) and ``sparc`` (dimensionless), indexed by
        cluster.
    zoom : tuple or None
        ((PV from, to) in m/s, (SPARC from, to) dimensionless) of the right panel; None: around the moved
        points.
    mark_centre : int or None
        A cluster (dimensionless) whose centre the zoom marks with a cross; None: none.
    fs : float
        The recording's sampling rate of (b), Hz (in the legend).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; SPARC (dimensionless) against PV (m/s).
    """

    fig, axes = plt.subplots(1, 2, figsize=(9, 4), layout="constrained")
    for ax in axes:
        for c in sorted(data["cluster"].unique()):
            m = data["cluster"] == c
            ax.scatter(data.loc[m, "pv"], data.loc[m, "sparc"], s=6, alpha=0.35, lw=0, color=CLUSTER_COLORS[c])
        ax.scatter(
            prototypes["pv"], prototypes["sparc"], s=70, facecolor="none", edgecolor="k", lw=1.3, label="prototype"
        )
    for c, row in moved.iterrows():
        color = CLUSTER_COLORS[int(c)]
        start = (prototypes.at[c, "pv"], prototypes.at[c, "sparc"])
        axes[0].annotate(
            "", xy=(row["pv_a"], row["sparc_a"]), xytext=start, arrowprops=dict(arrowstyle="->", color=color, lw=1.5)
        )
        axes[1].plot([row["pv_a"], row["pv_b"]], [row["sparc_a"], row["sparc_b"]], color=color, lw=0.8)
        for ax, size in zip(axes, [40, 70]):
            ax.scatter(row["pv_a"], row["sparc_a"], marker="D", s=size, color=color, edgecolor="k", zorder=3)
            ax.scatter(
                row["pv_b"], row["sparc_b"], marker="s", s=size, facecolor="none", edgecolor=color, lw=1.5, zorder=3
            )
    if mark_centre is not None:
        axes[1].scatter(
            centres.at[mark_centre, "pv"], centres.at[mark_centre, "sparc"], marker="x", s=60, color="k", zorder=4
        )
    if zoom is None and len(moved):
        pv = moved[["pv_a", "pv_b"]].to_numpy().ravel()
        sp = moved[["sparc_a", "sparc_b"]].to_numpy().ravel()
        zoom = ((pv.min() - 0.02, pv.max() + 0.02), (sp.min() - 0.02, sp.max() + 0.02))
    if zoom is not None:
        axes[1].set(xlim=zoom[0], ylim=zoom[1])
    axes[1].set_title("zoom on the slowed prototypes")
    axes[0].scatter([], [], marker="D", color="0.5", edgecolor="k", label="(a) time-scaled, fc/s")
    axes[0].scatter(
        [], [], marker="s", facecolor="none", edgecolor="0.3", lw=1.5, label=f"(b) {fs:g} Hz recording, fixed fc"
    )
    for ax in axes:
        ax.set(xlabel="peak speed PV (m/s)", ylabel="SPARC")
    axes[0].legend(fontsize="small", frameon=False, loc="lower right")
    return fig
