"""Figures of the transfer chapter: the robot, the frame mapping, joint velocities."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import roboticstoolbox as rtb
from matplotlib.ticker import MaxNLocator

with plt.rc_context():  # roboticstoolbox's PyPlot backend sets the ggplot style globally on import;
    import roboticstoolbox.backends.PyPlot.PyPlot  # noqa: F401  the context undoes that.

from ..robot import DEFAULT_POSE_DEG, EXP_TO_BASE, TransferResult, default_pose, joint_origins, simple6

#: Colours of the joints q1..q7 in the transfer figures.
JOINT_COLORS = plt.get_cmap("Dark2").colors


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


def plot_robot_joints(
    robot: rtb.DHRobot | None = None,
    q: np.ndarray | None = None,
    ax: plt.Axes | None = None,
    view: tuple[float, float] = (22.0, -35.0),
) -> plt.Figure:
    """An arm (default: Simple6 at the paper's default pose) with its joint axes labelled q1..qn:
    paper Fig. 3a.

    Joint j turns about the arrow labelled q_j (the z axis of DH frame j-1; Corke 2017, sec. 7.1);
    the arm is drawn by roboticstoolbox's PyPlot backend; ``view`` = (elevation, azimuth) deg.
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


def plot_robot_pose(
    robot: rtb.DHRobot | None = None,
    q: np.ndarray | None = None,
    ax: plt.Axes | None = None,
    view: tuple[float, float] = (18.0, -70.0),
) -> plt.Figure:
    """An arm in a pose (default: Simple6 at the paper's default pose ``DEFAULT_POSE_DEG``):
    paper Fig. 3b. The tool frame is drawn (x_t red, y_t green, z_t blue); the tool point (m) and
    the joint angles (deg) are written on the figure. Axes in m."""
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


def plot_simple6_figure() -> plt.Figure:
    """The paper's Fig. 3: (a) Simple6's joint labels, (b) its default pose, both at
    ``DEFAULT_POSE_DEG``; axes in m."""
    fig = plt.figure(figsize=(10, 5))
    robot, q = simple6(), default_pose()
    a = fig.add_subplot(121, projection="3d", proj_type="ortho")
    b = fig.add_subplot(122, projection="3d", proj_type="ortho")
    plot_robot_joints(robot, q, ax=a)
    plot_robot_pose(robot, q, ax=b)
    a.set_title("(a) joint labels", fontsize="medium")
    b.set_title("(b) default pose q = (" + ", ".join(f"{v:g}" for v in DEFAULT_POSE_DEG) + ") deg", fontsize="medium")
    return fig


def plot_joint_velocities(
    results: list[TransferResult],
    qd_limits: float | np.ndarray | None = None,
    titles: list[str] | None = None,
    ncols: int = 3,
) -> plt.Figure:
    """Joint velocities qd_j(t) (rad/s) against time (s from movement start), one panel per
    transfer result (prototype/cluster): the paper's Fig. 4.

    Dashed lines: +-the joint velocity limits (``qd_limits`` rad/s, scalar or per joint; default
    each result's own). Samples with a flag are marked with a red x on the time axis. Panels share
    the y axis so the prototypes can be compared.
    """
    if not results:
        raise ValueError("plot_joint_velocities needs at least one TransferResult")
    n_panels = len(results)
    ncols = min(ncols, n_panels)
    nrows = -(-n_panels // ncols)
    width, height = max(3.6 * ncols, 7.5), 2.8 * nrows + 0.8
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


def plot_frame_mapping(
    robot: rtb.DHRobot,
    result: TransferResult,
    rotation: np.ndarray = EXP_TO_BASE,
    view: tuple[float, float] = (20.0, -55.0),
) -> plt.Figure:
    """The experiment frame and the robot base frame, with the mapped path and the arm.

    The arm is drawn at its start pose ``result.q0`` and (grey) at the last solved sample; the
    target path ``result.x_base`` (m, base frame) in black. Arrows: the base frame at the origin
    (x, y, z) and, at the path's start, the experiment axes x_e (mediolateral), y_e (up) and z_e
    (anteroposterior) as seen in the base frame, i.e. the columns of ``rotation``
    (``p_base = rotation @ p_exp``).
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


def plot_start_poses(
    arms: list[tuple[rtb.Robot, TransferResult]], view: tuple[float, float] = (20.0, -55.0)
) -> plt.Figure:
    """Several arms, one panel each, at their start pose ``result.q0`` with the hand path
    ``result.x_base`` (m, base frame; black) that the transfer made them follow.

    ``arms`` holds (robot, result) pairs; the title gives the start pose (deg) and cond J there.
    Drawn with roboticstoolbox's PyPlot backend; axes in m.
    """
    if not arms:
        raise ValueError("plot_start_poses needs at least one (robot, TransferResult) pair")
    fig = plt.figure(figsize=(3.6 * len(arms), 4.2))
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
        ax.tick_params(labelsize="x-small", pad=0)
    fig.subplots_adjust(left=0.0, right=0.95, wspace=0.25)
    return fig
