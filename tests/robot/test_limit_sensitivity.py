"""Tests of skilllib.robot's limit sensitivity (``_sensitivity``): demand ratios whose critical scale is
known by construction (limits set to exactly twice a trajectory's peak demand), checked against the
verdicts :func:`skilllib.robot.joint_dynamics` gives when the limits themselves are scaled; the count of
feasible prototypes as a step function; the arm without dynamics has no torque range."""

from __future__ import annotations

import numpy as np
import pytest
from robot_paths import minimum_jerk_descent

from skilllib.robot import (
    LIMIT_NAMES,
    Assessment,
    LimitMargin,
    feasible_counts,
    get_robot,
    joint_dynamics,
    limit_margin,
    limit_margins,
    limit_sensitivity,
    transfer,
    verdict_range,
)

NEAR = 1e-6  # relative step either side of a critical scale


@pytest.fixture(scope="module")
def simple6_descent():
    """Simple6's transfer of a 1 m/s minimum-jerk descent and its dynamics at the book's limits."""
    arm = get_robot("simple6")
    t, p, v = minimum_jerk_descent(amplitude=0.2, peak_speed=1.0)
    r = transfer(arm, t, p, v)
    return arm, r, joint_dynamics(arm.robot, r, arm.qdd_limits)


@pytest.fixture(scope="module")
def ur5_descent():
    arm = get_robot("ur5")
    t, p, v = minimum_jerk_descent(amplitude=0.2, peak_speed=0.8)
    return arm, transfer(arm, t, p, v)


def test_a_demand_at_half_the_acceleration_limit_flips_at_scale_one_half(simple6_descent):
    arm, r, d0 = simple6_descent
    qdd_lim = 2.0 * d0.peak_abs_qdd  # every joint's peak at exactly half its limit
    d = joint_dynamics(arm.robot, r, qdd_lim)
    m = limit_margin(d)
    assert m.ratios["acceleration"] == pytest.approx(0.5, rel=1e-12)
    assert m.critical_scale("acceleration") == pytest.approx(0.5, rel=1e-12)
    np.testing.assert_allclose(m.critical_limit("acceleration"), d0.peak_abs_qdd, rtol=1e-12)
    assert m.feasible_at("acceleration", 0.5 * (1 + NEAR))
    assert not m.feasible_at("acceleration", 0.5 * (1 - NEAR))
    # the same verdicts from the library's own feasibility, the limits themselves scaled
    for f, expected in ((0.5 * (1 + NEAR), True), (0.5 * (1 - NEAR), False)):
        assert joint_dynamics(arm.robot, r, f * qdd_lim).feasible is expected


def test_the_velocity_ratio_flips_the_transfer_s_own_verdict(simple6_descent):
    arm, r, _ = simple6_descent
    m = limit_margin(joint_dynamics(arm.robot, r))  # velocity limits only
    rho = m.critical_scale("velocity")
    assert rho == pytest.approx(np.max(r.peak_abs_qd / r.qd_limits), rel=1e-12) and rho < 1
    t, p, v = minimum_jerk_descent(amplitude=0.2, peak_speed=1.0)
    for f, expected in ((rho * (1 + NEAR), True), (rho * (1 - NEAR), False)):
        assert m.feasible_at("velocity", f) is expected
        assert transfer(arm.with_limits(qd_max=f * arm.qd_limits), t, p, v).feasible is expected


def test_a_torque_at_half_its_limit_flips_at_one_half_on_an_arm_with_dynamics(ur5_descent):
    arm, r = ur5_descent
    free = joint_dynamics(arm.robot, r)  # no acceleration or torque limits: only the torques computed
    peak = free.peak_abs_tau
    tau_lim = 2.0 * np.maximum(peak, peak.max())  # the most loaded joint at exactly half, the others less
    d = joint_dynamics(arm.robot, r, None, tau_lim)
    m = limit_margin(d)
    assert m.ratios["acceleration"] is None
    assert m.critical_scale("torque") == pytest.approx(0.5, rel=1e-12)
    for f, expected in ((0.5 * (1 + NEAR), True), (0.5 * (1 - NEAR), False)):
        assert m.feasible_at("torque", f) is expected
        assert joint_dynamics(arm.robot, r, None, f * tau_lim).feasible is expected


def test_the_verdict_at_the_assumed_limits_is_the_assessment_s(simple6_descent, ur5_descent):
    arm, r, d0 = simple6_descent
    ur5, r5 = ur5_descent
    cases = [
        joint_dynamics(arm.robot, r, qdd)
        for qdd in (d0.peak_abs_qdd * 1.01, d0.peak_abs_qdd * 0.99, arm.qdd_limits, None)
    ] + [joint_dynamics(ur5.robot, r5, ur5.qdd_limits, ur5.tau_limits)]
    verdicts = [d.feasible for d in cases]
    assert True in verdicts and False in verdicts  # both verdicts are exercised
    assert [m.feasible for m in limit_margins(cases)] == verdicts
    # an Assessment is read through its dynamics, nothing recomputed
    via_assessment, direct = limit_margin(Assessment(cases[0], None, None)), limit_margin(cases[0])
    assert via_assessment.ratios == direct.ratios and via_assessment.flagged == direct.flagged


def _margin(acc: float, vel: float = 0.5, flagged: bool = False, robot: str = "Simple6") -> LimitMargin:
    lim = np.full(6, 5.0)
    return LimitMargin(
        robot,
        None,
        flagged,
        {"velocity": vel, "acceleration": acc, "torque": None},
        {"velocity": np.full(6, np.pi), "acceleration": lim, "torque": None},
    )


def test_the_count_is_a_step_function_with_a_step_at_each_critical_scale():
    ratios = [0.5, 0.8, 1.5, 3.0]
    margins = [_margin(a) for a in ratios] + [
        _margin(0.2, flagged=True),  # flagged: infeasible whatever the limits
        _margin(0.3, vel=1.2),  # its velocity fails: scaling acceleration alone never flips it
    ]
    grid = np.geomspace(0.05, 20, 400)
    counts = feasible_counts(margins, "acceleration", grid)
    assert np.all(np.diff(counts) >= 0)
    assert counts[0] == 0 and counts[-1] == len(ratios)
    for rho in ratios:  # one step up at each ratio, nowhere else
        below, at = feasible_counts(margins, "acceleration", [rho * (1 - NEAR), rho])
        assert at == below + 1
    expected = [sum(rho <= f for rho in ratios) for f in grid]
    np.testing.assert_array_equal(counts, expected)
    v = verdict_range(margins, "acceleration")
    assert v.count == sum(m.feasible for m in margins) == sum(rho <= 1 for rho in ratios)
    assert (v.lo, v.hi) == (0.8, 1.5)  # the count at scale 1 holds on [0.8, 1.5)
    assert v.limit_range == (0.8 * 5.0, 1.5 * 5.0)  # in rad/s^2: the assumed 5 on every joint
    np.testing.assert_array_equal(v.steps, ratios)
    assert v.saturates_at == 3.0
    for m in range(len(ratios) + 2):  # scale_for inverts the step function
        f = v.scale_for(m)
        if m == 0:
            assert f == 0.0
        elif m > len(ratios):
            assert f == np.inf
        else:
            assert feasible_counts(margins, "acceleration", f) >= m
            assert feasible_counts(margins, "acceleration", f * (1 - NEAR)) < m
    assert feasible_counts(margins, "acceleration", v.lo) == feasible_counts(margins, "acceleration", 1.0)
    assert feasible_counts(margins, "acceleration", v.hi) == v.count + 1
    assert feasible_counts(margins, "acceleration", v.lo * (1 - NEAR)) == v.count - 1


def test_open_ends_of_the_range_and_per_joint_limits():
    all_fail = [_margin(a) for a in (1.2, 2.0)]
    v = verdict_range(all_fail, "acceleration")
    assert v.count == 0 and v.lo == 0.0 and v.hi == 1.2
    all_hold = [_margin(a) for a in (0.3, 0.9)]
    v = verdict_range(all_hold, "acceleration")
    assert v.count == 2 and v.lo == 0.9 and v.hi == np.inf
    m = _margin(0.5)
    per_joint = LimitMargin(m.robot, None, False, m.ratios, {**m.limits, "acceleration": np.arange(1.0, 7.0)})
    assert verdict_range([per_joint], "acceleration").limit_range is None


def test_the_arm_without_dynamics_has_no_torque_range(simple6_descent, ur5_descent):
    arm, r, d0 = simple6_descent
    ur5, r5 = ur5_descent
    margins = limit_margins([d0])
    assert margins[0].ratios["torque"] is None and margins[0].critical_scale("torque") is None
    assert verdict_range(margins, "torque") is None
    table = limit_sensitivity({"simple6": [d0], "ur5": [joint_dynamics(ur5.robot, r5, ur5.qdd_limits, ur5.tau_limits)]})
    assert ("Simple6", "torque") not in table.index
    assert set(table.loc["UR5"].index) == set(LIMIT_NAMES)
    row = table.loc[("Simple6", "acceleration")]
    assert row["assumed"] == 5.0 and row["unit"] == "rad/s^2"
    assert row["limit_from"] == pytest.approx(row["scale_from"] * 5.0)
    assert np.isnan(table.loc[("UR5", "torque"), "assumed"])  # 150 and 28 N m: no single value


def test_bad_input_is_refused(simple6_descent, ur5_descent):
    _, _, d0 = simple6_descent
    m = limit_margin(d0)
    with pytest.raises(ValueError, match="unknown limit"):
        m.critical_scale("jerk")
    with pytest.raises(ValueError, match="positive"):
        m.feasible_at("velocity", 0.0)
    with pytest.raises(ValueError, match="positive"):
        feasible_counts([m], "velocity", [1.0, -1.0])
    with pytest.raises(ValueError, match="at least one"):
        verdict_range([], "velocity")
    with pytest.raises(ValueError, match="one arm"):
        verdict_range([m, _margin(0.5, robot="UR5")], "velocity")
