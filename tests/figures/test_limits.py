"""Tests of skilllib.figures.limits: the count of prototypes executable as recorded against the scale of
each kind of limit, drawn as the library's step function, with the assumed limits and their range marked."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import skilllib as sk  # noqa: E402
import skilllib.figures as skf  # noqa: E402


def _descent(peak_speed: float, amplitude: float = 0.2, fs: float = 60.0):
    """A vertical minimum-jerk descent (experiment frame, -y) cut at 70 % of its amplitude: t (s),
    positions (m), velocities (m/s)."""
    T = 1.875 * amplitude / peak_speed
    t = np.arange(0.0, T, 1.0 / fs)
    tau = t / T
    s = amplitude * (10 * tau**3 - 15 * tau**4 + 6 * tau**5)
    ds = amplitude / T * (30 * tau**2 - 60 * tau**3 + 30 * tau**4)
    keep = s <= 0.7 * amplitude
    pos, vel = np.zeros((keep.sum(), 3)), np.zeros((keep.sum(), 3))
    pos[:, 1], vel[:, 1] = -s[keep], -ds[keep]
    return t[keep], pos, vel


@pytest.fixture(scope="module")
def by_arm():
    """Three descents of rising speed on Simple6 (5 rad/s^2 on every joint) and on the UR5 (per-joint
    torques, so no single torque value)."""
    out = {}
    for name in ("simple6", "ur5"):
        arm = sk.get_robot(name)
        out[arm.robot.name] = [
            sk.joint_dynamics(arm.robot, sk.transfer(arm, *_descent(pv)), arm.qdd_limits, arm.tau_limits)
            for pv in (0.3, 0.6, 1.0)
        ]
    return out


def test_each_line_is_the_library_s_count_and_the_assumed_count_is_marked(by_arm):
    fig = skf.plot_limit_sensitivity(by_arm, scale_range=(0.05, 20.0))
    try:
        axes = [ax for ax in fig.axes if ax.get_visible() and ax.get_ylabel()]
        assert len(axes) == len(by_arm)
        for ax, dyns in zip(axes, by_arm.values()):
            margins = sk.limit_margins(dyns)
            steps = [line for line in ax.lines if line.get_label().endswith("limits scaled")]
            kinds = [line.get_label().split()[0] for line in steps]
            expected = [k for k in sk.LIMIT_NAMES if sk.verdict_range(margins, k) is not None]
            assert kinds == expected  # Simple6 has no torque line
            for line, kind in zip(steps, kinds):
                x, y = np.asarray(line.get_xdata()), np.asarray(line.get_ydata())
                counts = sk.feasible_counts(margins, kind, x)
                np.testing.assert_allclose(y - counts, y[0] - counts[0])  # a constant offset only
                assert abs(y[0] - counts[0]) < 0.2
            dot = [line for line in ax.lines if line.get_marker() == "o"]
            assert dot[0].get_ydata()[0] == sum(d.feasible for d in dyns)
            assert ax.get_xscale() == "log" and ax.get_xlim() == pytest.approx((0.05, 20.0))
            assert "scale" in ax.get_xlabel() and "prototypes" in ax.get_ylabel()
            (span,) = ax.patches  # the range of the acceleration limit keeping the count
            x0, x1 = span.get_x(), span.get_x() + span.get_width()
            v = sk.verdict_range(margins, "acceleration")
            assert x0 == pytest.approx(max(v.lo, 0.05)) and x1 == pytest.approx(min(v.hi, 20.0))
        # a top axis in rad/s^2 where the acceleration limit is one number for every joint (both arms: 5)
        tops = [c for ax in axes for c in ax.child_axes if "rad/s²" in c.get_xlabel()]
        assert len(tops) == 2
    finally:
        plt.close(fig)


def test_no_top_axis_for_limits_that_differ_between_joints(by_arm):
    arm = sk.get_robot("simple6", qdd_max=[5.0, 6.0, 7.0, 8.0, 9.0, 10.0])
    dyns = [sk.joint_dynamics(arm.robot, d.transfer, arm.qdd_limits) for d in by_arm["Simple6"]]
    fig = skf.plot_limit_sensitivity({"Simple6 per joint": dyns})
    try:
        assert not [c for ax in fig.axes for c in ax.child_axes if "rad/s²" in c.get_xlabel()]
    finally:
        plt.close(fig)


def test_bad_input_is_refused(by_arm):
    with pytest.raises(ValueError, match="at least one arm"):
        skf.plot_limit_sensitivity({})
    with pytest.raises(ValueError, match="unknown limit"):
        skf.plot_limit_sensitivity(by_arm, kinds=["jerk"])
    with pytest.raises(ValueError, match="positive and increasing"):
        skf.plot_limit_sensitivity(by_arm, scale_range=(2.0, 1.0))
