"""Tests of skilllib.robot (the simulated execution of joint velocity commands) and of
skilllib.robot (the assessment and results.json block built from it)."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
from robot_paths import minimum_jerk_descent

from skilllib.robot import (
    ACTUATOR_BANDWIDTH_HZ,
    CONTROL_RATE_HZ,
    assess,
    assess_one,
    dynamic_limits,
    execute,
    get_robot,
    joint_dynamics,
    simple6,
    transfer,
    transfer_block,
)
from skilllib.smoothness import sparc


@pytest.fixture(scope="module")
def fast_descent():
    """A fast minimum-jerk descent (0.2 m, peak 1.4 m/s, cut at contact) on Simple6 and its dynamics."""
    t, p, v = minimum_jerk_descent(0.2, 1.4)
    r = transfer("simple6", t, p, v)
    return r, joint_dynamics(simple6(), r, qdd_limits=dynamic_limits("simple6").qdd_limits)


def test_loose_limits_and_no_lag_reproduce_the_prototype(fast_descent):
    # nothing limits the arm and nothing lags: the executed speed at the samples is the commanded one, PV and
    # SPARC those of the prototype, the path within 1 mm (the velocity samples integrated)
    r, d = fast_descent
    speed = np.linalg.norm(r.v_base, axis=1)
    fs = 1 / (r.t[1] - r.t[0])
    e = execute(simple6(), r, qd_limits=1e6, qdd_limits=None, bandwidth_hz=None, qdd=d.qdd)
    np.testing.assert_allclose(e.speed_samples, speed, rtol=5e-3)
    assert e.pv == pytest.approx(speed.max(), rel=2e-3)
    assert e.sparc == pytest.approx(sparc(speed, fs), abs=2e-3)
    assert e.max_tracking_error_m < 1e-3 and e.saturated_fraction == 0.0
    np.testing.assert_allclose(e.t[[0, -1]], r.t[[0, -1]])
    assert np.all(np.diff(e.t) <= 1 / CONTROL_RATE_HZ + 1e-12)
    # the fast default lag changes little: SPARC within 0.01, the path within 3 mm
    lag = execute(simple6(), r, qd_limits=1e6, qdd=d.qdd)
    assert lag.bandwidth_hz == ACTUATOR_BANDWIDTH_HZ and abs(lag.sparc - e.sparc) < 0.01
    assert lag.max_tracking_error_m < 3e-3


def test_first_order_lag_decays_exactly(fast_descent):
    # a command that is constant after the first sample: the executed joint velocity approaches it as
    # 1 - exp(-2 pi f t) (exact discretisation), f = 5 Hz
    r, _ = fast_descent
    qd = np.zeros_like(r.qd)
    qd[1:, 0] = 0.2
    step = replace(r, qd=qd)
    e = execute(simple6(), step, bandwidth_hz=5.0)
    after = e.t >= r.t[1]
    gap = 0.2 - e.qd[after, 0]
    expected = gap[0] * np.exp(-2 * np.pi * 5.0 * (e.t[after] - e.t[after][0]))
    np.testing.assert_allclose(gap, expected, rtol=1e-9, atol=1e-15)


def test_acceleration_and_velocity_saturation(fast_descent):
    r, d = fast_descent
    e = execute(simple6(), r, qd_limits=0.8, qdd_limits=2.0, bandwidth_hz=None, qdd=d.qdd)
    assert np.all(np.abs(e.qd) <= 0.8 + 1e-12)
    acc = np.diff(e.qd, axis=0) / np.diff(e.t)[:, None]
    assert np.all(np.abs(acc) <= 2.0 + 1e-9)
    assert np.isclose(np.abs(acc).max(), 2.0)  # the ramp at the limit
    assert e.saturated_fraction > 0.5 and e.max_tracking_error_m > 0.02


def test_limits_change_the_smoothness_and_time_scaling_restores_it(fast_descent):
    # the book's 5 rad/s^2 clip the fast descent: SPARC moves and the tool falls behind; slowed by the time
    # scale of every limit, the execution keeps the prototype's SPARC (measured at fc / s) and path
    r, d = fast_descent
    fs = 1 / (r.t[1] - r.t[0])
    proto = sparc(np.linalg.norm(r.v_base, axis=1), fs)
    s = d.time_scale
    assert d.binding_limit == "acceleration" and s > 1.3
    as_recorded = execute(simple6(), r, qdd_limits=d.qdd_limits, qdd=d.qdd)
    slowed = execute(simple6(), r, qdd_limits=d.qdd_limits, time_scale=s, qdd=d.qdd)
    assert abs(as_recorded.sparc - proto) > 0.03 and as_recorded.max_tracking_error_m > 0.01
    assert abs(slowed.sparc - proto) < 0.01 and slowed.max_tracking_error_m < 3e-3
    assert slowed.pv == pytest.approx(np.linalg.norm(r.v_base, axis=1).max() / s, rel=0.02)
    np.testing.assert_allclose(np.diff(slowed.t_samples), s * np.diff(r.t))


def test_stretch_without_limits_keeps_sparc_with_the_scaled_cut_off(fast_descent):
    r, d = fast_descent
    free = dict(qd_limits=1e6, bandwidth_hz=None, qdd=d.qdd)
    one, two = execute(simple6(), r, **free), execute(simple6(), r, time_scale=2.0, **free)
    assert two.sparc == pytest.approx(one.sparc, abs=2e-3) and two.pv == pytest.approx(one.pv / 2, rel=2e-3)


def test_execution_refuses_failed_samples_and_bad_settings():
    t, p, v = minimum_jerk_descent(2.9, 1.0)  # out of reach at the end
    r = transfer("simple6", t, p, v)
    with pytest.raises(ValueError, match="nothing to execute"):
        execute(simple6(), r)
    ok = transfer("simple6", *minimum_jerk_descent(0.2, 1.0))
    with pytest.raises(ValueError, match="bandwidth_hz"):
        execute(simple6(), ok, bandwidth_hz=0.0)
    with pytest.raises(ValueError, match="positive"):
        execute(simple6(), ok, time_scale=0.0)
    a = assess_one(simple6(), r, dynamic_limits("simple6"))  # assessed, not executed, with the reason
    assert a.executed is None and "without joint angles" in a.note
    entry = a.summary()
    assert entry["executed"] is None and entry["executed_time_scaled"] is None
    json.dumps(entry, allow_nan=False)


def test_assessment_and_block():
    robot = get_robot("puma560").robot
    results = [transfer("puma560", *minimum_jerk_descent(0.2, vp), cluster=c) for c, vp in enumerate((0.6, 1.3))]
    limits = get_robot("puma560", tau_max=[97.6, 60.0, 89.4, 24.2, 20.1, 21.3]).dynamic_limits
    block = transfer_block(assess(robot, results, limits))
    assert block["qdd_limits"] is None and block["tau_limits"][1] == 60.0
    assert block["execution"] == {"control_rate_hz": CONTROL_RATE_HZ, "actuator_bandwidth_hz": ACTUATOR_BANDWIDTH_HZ}
    slow, fast = block["prototypes"]
    assert slow["binding_limit"] is None and slow["feasible"] and slow["time_scale"] == 1.0
    assert fast["binding_limit"] == "torque" and fast["time_scale"] > 1 and not fast["feasible"]
    assert fast["feasible_velocity"]  # the velocity limits alone
    assert "feasible_all_limits" not in fast and "time_scale_all_limits" not in fast
    assert fast["time_scales"]["velocity"] == 1.0 and fast["time_scales"]["acceleration"] is None
    assert slow["executed_time_scaled"] == slow["executed"]
    assert fast["executed_time_scaled"]["time_scale"] == fast["time_scale"]
    assert set(fast["executed"]) == {"pv", "sparc", "max_tracking_error_m", "saturated_fraction", "time_scale"}
    json.dumps(block, allow_nan=False)
    with pytest.raises(ValueError, match="no dynamic parameters"):
        get_robot("simple6", tau_max=10.0)
    with pytest.raises(ValueError, match="qdd_max must be a scalar or have 6 entries"):
        get_robot("puma560", qdd_max=[1.0, 2.0])
    assert get_robot("panda").qdd_limits[1] == 7.5
    assert get_robot("panda", qd_max=1.0).qdd_limits[1] == 7.5  # one override leaves the other limits


def test_dynamics_figures():
    import matplotlib

    matplotlib.use("Agg")
    from skilllib import figures

    results = [transfer("puma560", *minimum_jerk_descent(0.2, vp), cluster=c) for c, vp in enumerate((0.6, 1.3))]
    robot = get_robot("puma560").robot
    assessed = assess(robot, results, dynamic_limits("puma560"))
    dyns = [a.dynamics for a in assessed]
    fig = figures.plot_joint_accelerations(dyns)
    assert fig.axes[0].get_ylabel() == "joint acceleration (rad/s²)" and "(s)" in fig.axes[0].get_xlabel()
    fig = figures.plot_joint_torques(dyns)
    assert fig.axes[0].get_ylabel() == "joint torque / its limit"
    limits = [ln for ln in fig.axes[0].get_lines() if ln.get_linestyle() == "--"]
    assert {tuple(ln.get_ydata()) for ln in limits} == {(1, 1), (-1, -1)}  # the normalised limits
    fig = figures.plot_executed_speed(assessed)
    assert fig.axes[0].get_ylabel() == "tool speed (m/s)"
    fig = figures.plot_time_scales(
        {
            "Puma 560": dyns,
            "Simple6": [
                joint_dynamics(simple6(), transfer("simple6", *minimum_jerk_descent(0.2, 1.4)), qdd_limits=5.0)
            ],
        }
    )
    assert fig.axes[0].get_ylabel() == "time scale s" and [ax.get_title() for ax in fig.axes] == ["Puma 560", "Simple6"]
    with pytest.raises(ValueError, match="dynamic parameters"):
        figures.plot_joint_torques([joint_dynamics(simple6(), transfer("simple6", *minimum_jerk_descent(0.2, 1.0)))])
    for f in (figures.plot_joint_accelerations, figures.plot_executed_speed):
        with pytest.raises(ValueError):
            f([])
    figures.plt.close("all")
