"""Tests of skilllib.robot (joint accelerations, jerks, torques, every limit, time scaling) against
independent computations: finite differences, roboticstoolbox's jacob0_dot, a hand-computed gravity
torque, the potential energy's gradient, a closed-form root of the torque constraint, and a transfer of
the time-scaled trajectory recomputed from scratch."""

from __future__ import annotations

import json

import numpy as np
import pytest
import roboticstoolbox as rtb
from robot_paths import minimum_jerk_descent

from skilllib.robot import (
    EXP_TO_BASE,
    PUMA560_TAU_LIMITS,
    ROBOT_NAMES,
    apply_time_scale,
    derivative,
    dynamic_limits,
    get_robot,
    has_dynamics,
    jacobian_dot,
    joint_accelerations,
    joint_dynamics,
    simple6,
    transfer,
)


def _descent_acceleration(t: np.ndarray, amplitude: float, peak_speed: float) -> np.ndarray:
    """Exact acceleration (N, 3) m/s^2 of minimum_jerk_descent (experiment frame): s'' = A/T^2 60 tau (1 - tau)
    (1 - 2 tau) along -y."""
    T = 1.875 * amplitude / peak_speed
    tau = t / T
    a = np.zeros((t.size, 3))
    a[:, 1] = -amplitude / T**2 * 60 * tau * (1 - tau) * (1 - 2 * tau)
    return a


# --- the Jacobian's derivative and the accelerations ---------------------------------------------------


@pytest.mark.parametrize("name", ROBOT_NAMES)
def test_jacobian_dot_matches_finite_differences_and_roboticstoolbox(name):
    arm = get_robot(name)
    robot, q0 = arm.robot, arm.q0
    ets = robot.ets()
    rng = np.random.default_rng(5)
    for q in (q0, q0 + rng.uniform(-0.3, 0.3, robot.n)):
        qd = rng.uniform(-1, 1, robot.n)
        h = 1e-6
        fd = (ets.jacob0(q + h * qd) - ets.jacob0(q - h * qd)) / (2 * h)  # dJ/dt along q(t) = q + t qd
        Jd = jacobian_dot(ets, q, qd)
        np.testing.assert_allclose(Jd, fd, atol=1e-7)
        np.testing.assert_allclose(Jd, robot.jacob0_dot(q, qd), atol=1e-12)


@pytest.mark.parametrize("name", ROBOT_NAMES)
def test_joint_accelerations_are_the_derivative_of_qd(name):
    # the analytic qdd (exact task acceleration, Jacobian derivative; the pseudo-inverse's derivative for the
    # Panda) against the second-order central difference of qd itself: the gap shrinks 4x per halved step
    gaps = []
    for fs in (240.0, 480.0):
        t, p, v = minimum_jerk_descent(0.2, 0.8, fs=fs)
        r = transfer(name, t, p, v)
        assert r.flags == []
        ets = get_robot(name).robot.ets()
        a = np.hstack([_descent_acceleration(t, 0.2, 0.8) @ EXP_TO_BASE.T, np.zeros((t.size, 3))])
        vv = np.hstack([r.v_base, np.zeros((t.size, 3))])
        qdd = joint_accelerations(ets, r.q, r.qd, vv, a)
        fd = (r.qd[2:] - r.qd[:-2]) / (2 / fs)
        gaps.append(np.abs(qdd[1:-1] - fd).max())
        assert gaps[-1] < 0.01 * np.abs(qdd).max()
    assert 3.0 < gaps[0] / gaps[1] < 5.0  # second order


def test_pseudo_inverse_derivative_of_the_redundant_panda():
    # qd = J(q)^+ v with v and q moving (q' = qd, v' = a): the analytic qdd against the central difference
    # of J(q(t))^+ v(t) at random states; without the null-space term (I - J+ J) Jdot' (J J')^-1 v it is
    # not the derivative
    arm = get_robot("panda")
    robot, q0 = arm.robot, arm.q0
    ets = robot.ets()
    rng = np.random.default_rng(11)
    for _ in range(3):
        q = q0 + rng.uniform(-0.4, 0.4, 7)
        v, a = rng.uniform(-1, 1, 6), rng.uniform(-5, 5, 6)
        qd = np.linalg.pinv(ets.jacob0(q)) @ v
        h = 1e-6
        fd = (
            np.linalg.pinv(ets.jacob0(q + h * qd)) @ (v + h * a) - np.linalg.pinv(ets.jacob0(q - h * qd)) @ (v - h * a)
        ) / (2 * h)
        qdd = joint_accelerations(ets, q[None], qd[None], v[None], a[None])[0]
        np.testing.assert_allclose(qdd, fd, atol=1e-6)
        naive = np.linalg.pinv(ets.jacob0(q)) @ (a - jacobian_dot(ets, q, qd) @ qd)
        assert np.abs(naive - fd).max() > 1e-2


def test_joint_dynamics_of_a_60_hz_recording_agrees_with_differentiating_qd():
    # the book's method (hand acceleration by the 3-point derivative, then the Jacobian's derivative)
    # against the same derivative of qd: both O(dt^2), within 3% of the peak at 60 Hz
    t, p, v = minimum_jerk_descent(0.2, 1.0)
    r = transfer("simple6", t, p, v)
    d = joint_dynamics(simple6(), r)
    fd = derivative(r.qd, r.t)
    np.testing.assert_allclose(fd, np.gradient(r.qd, r.t, axis=0, edge_order=2))  # 3 samples at 60 Hz
    assert np.abs(d.qdd - fd).max() < 0.03 * np.abs(d.qdd).max()
    np.testing.assert_allclose(d.qddd, np.gradient(d.qdd, r.t, axis=0, edge_order=2))  # jerk: stated method
    np.testing.assert_array_equal(d.peak_abs_qdd, np.abs(d.qdd).max(axis=0))
    assert d.tau is None and d.peak_abs_tau is None and not has_dynamics(simple6())


# --- torques --------------------------------------------------------------------------------------------


def test_rne_gravity_torque_of_a_two_link_arm_by_hand():
    # two links in a vertical plane (joint axes horizontal), point masses at the link ends, arm horizontal:
    # tau1 = g (m1 l1 + m2 (l1 + l2)), tau2 = g m2 l2 (N m); at 30 deg up, times cos(30 deg)
    m1, m2, l1, l2, g = 2.0, 1.5, 0.5, 0.4, 9.81
    links = [
        rtb.RevoluteDH(a=l1, m=m1, r=[0, 0, 0], I=np.zeros(6)),
        rtb.RevoluteDH(a=l2, m=m2, r=[0, 0, 0], I=np.zeros(6)),
    ]
    arm = rtb.DHRobot(links, name="two-link", gravity=[0, -g, 0])  # y up in the arm's plane (z the axes)
    for q1 in (0.0, np.pi / 6):
        tau = arm.rne([q1, 0.0], [0, 0], [0, 0])
        c = np.cos(q1)
        np.testing.assert_allclose(tau, [g * c * (m1 * l1 + m2 * (l1 + l2)), g * c * m2 * l2], rtol=1e-12)


def test_puma_static_torque_is_the_gradient_of_the_potential_energy():
    # at rest rne gives the gravity load, dV/dq with V = sum_i m_i g z_i of the centres of mass
    arm = get_robot("puma560")
    robot, q0 = arm.robot, arm.q0

    def potential(q):
        frames = robot.fkine_all(q)
        return sum(link.m * 9.81 * np.ravel(frames[i + 1] * link.r)[2] for i, link in enumerate(robot.links))

    for q in (q0, q0 + np.array([0.2, -0.3, 0.4, 0.1, -0.2, 0.3])):
        h = 1e-6
        grad = np.array([(potential(q + h * e) - potential(q - h * e)) / (2 * h) for e in np.eye(6)])
        np.testing.assert_allclose(robot.rne(q, np.zeros(6), np.zeros(6)), grad, atol=1e-6)


def test_torque_is_gravity_friction_plus_speed_terms_not_a_power_of_s():
    # tau(s) = g + Coulomb + viscous / s + (M qdd + C qd) / s^2 on every sample: three speeds fix the three
    # coefficients, a fourth checks them; neither 1/s nor 1/s^2 alone fits
    t, p, v = minimum_jerk_descent(0.15, 1.0)
    robot = get_robot("puma560").robot
    d = joint_dynamics(robot, transfer("puma560", t, p, v))
    x = np.array([1.0, 0.7, 0.4])
    T = np.stack([d.torques(1 / xi) for xi in x])  # (3, N, n)
    V = np.vander(x, 3, increasing=True)  # 1, x, x^2
    coef = np.einsum("ij,jkl->ikl", np.linalg.inv(V), T)
    np.testing.assert_allclose(coef[0] + 0.55 * coef[1] + 0.55**2 * coef[2], d.torques(1 / 0.55), atol=1e-9)
    np.testing.assert_allclose(d.torques(1e9), coef[0], atol=1e-6)  # at rest (moving): gravity and Coulomb
    np.testing.assert_allclose(d.torques(1.0), d.tau)
    assert np.abs(coef[0]).max() > 10 and np.abs(coef[2]).max() > 10  # both parts matter on the Puma


# --- every limit and the time scale ----------------------------------------------------------------------


def _quadratic_scale(d, lim: np.ndarray, s_min: float) -> float:
    """Independent smallest s >= s_min with |tau(s)| <= lim: per sample and joint tau = c0 + c1 x + c2 x^2
    (x = 1/s), the largest x <= 1/s_min below every crossing of +-lim, from the roots of the quadratics."""
    x = np.array([1.0, 0.5, 0.25])
    T = np.stack([d.torques(1 / xi) for xi in x])
    c0, c1, c2 = np.einsum("ij,jkl->ikl", np.linalg.inv(np.vander(x, 3, increasing=True)), T)
    x_best = 1 / s_min
    for k in range(c0.shape[0]):
        for j in range(c0.shape[1]):
            for sign in (1, -1):
                roots = np.roots([c2[k, j], c1[k, j], c0[k, j] - sign * lim[j]])
                real = roots[np.isreal(roots)].real
                real = real[(real > 0) & (real < x_best)]
                for xr in np.sort(real):
                    if abs(c0[k, j] + c1[k, j] * (xr + 1e-9) + c2[k, j] * (xr + 1e-9) ** 2) > lim[j]:
                        x_best = min(x_best, xr)  # crossing into violation at larger x
    return 1 / x_best


def test_torque_time_scale_is_the_root_of_the_torque_constraint():
    t, p, v = minimum_jerk_descent(0.2, 1.3)
    robot = get_robot("puma560").robot
    r = transfer("puma560", t, p, v)
    full = joint_dynamics(robot, r, tau_limits=PUMA560_TAU_LIMITS)
    lim = np.array(PUMA560_TAU_LIMITS)
    lim[1] = 0.7 * full.peak_abs_tau[1]  # the shoulder: 66 N m, above its 32 N m at rest
    assert lim[1] > 1.5 * np.abs(full.torques(1e9)[:, 1]).max()
    d = joint_dynamics(robot, r, tau_limits=lim)
    s = d.time_scale
    assert d.binding_limit == "torque" and s > 1.05
    assert s == pytest.approx(_quadratic_scale(d, lim, 1.0), rel=1e-9)
    ratio = np.nanmax(np.abs(d.torques(s)) / lim)
    assert 1 - 1e-9 < ratio <= 1 + 1e-9  # exactly at the limit
    assert d.limits_hold(s) and not d.limits_hold(s * (1 - 1e-6))
    assert d.time_scales()["torque"] == pytest.approx(s)


def test_no_slowing_helps_when_gravity_exceeds_a_torque_limit():
    t, p, v = minimum_jerk_descent(0.2, 1.0)
    robot = get_robot("puma560").robot
    r = transfer("puma560", t, p, v)
    static = np.abs(joint_dynamics(robot, r).torques(1e9)).max(axis=0)
    lim = np.array(PUMA560_TAU_LIMITS)
    lim[1] = 0.9 * static[1]  # the shoulder cannot even hold the arm
    d = joint_dynamics(robot, r, tau_limits=lim)
    assert d.time_scale == np.inf and d.binding_limit == "torque" and not d.feasible
    assert d.summary()["time_scale"] is None
    json.dumps(d.summary(), allow_nan=False)


@pytest.mark.parametrize("case", ["velocity", "acceleration", "torque"])
def test_after_time_scaling_every_limit_holds_on_every_sample_recomputed_from_scratch(case):
    # the stretched trajectory is transferred and differentiated again (60 Hz: the same 3-sample derivative)
    # and its qd, qdd and tau checked against every limit on every sample; 0.1% less stretch breaks one
    name = "simple6" if case == "acceleration" else "puma560"
    t, p, v = minimum_jerk_descent(0.2, 1.2)
    robot = get_robot(name).robot
    limits = {"velocity": dict(qd_limits=0.5), "acceleration": dict(), "torque": dict()}[case]
    r = transfer(name, t, p, v, **limits)
    book = dynamic_limits(name)
    tau = None if book.tau_limits is None else book.tau_limits.copy()
    if case == "torque":
        tau[1] = 0.6 * joint_dynamics(robot, r).peak_abs_tau[1]  # a weaker shoulder drive
    d = joint_dynamics(robot, r, book.qdd_limits, tau)
    s = d.time_scale
    assert d.binding_limit == case and s > 1.05
    t2, v2 = apply_time_scale(t, v, s)
    r2 = transfer(name, t2, p, v2, **limits)
    d2 = joint_dynamics(robot, r2, book.qdd_limits, tau)
    np.testing.assert_allclose(r2.q, r.q, atol=1e-9)
    np.testing.assert_allclose(d2.qdd, d.qdd / s**2, rtol=1e-6, atol=1e-9)
    rtol = 1 + 1e-6
    assert np.all(np.abs(r2.qd) <= r2.qd_limits * rtol)
    if book.qdd_limits is not None:
        assert np.all(np.abs(d2.qdd) <= book.qdd_limits * rtol)
    if tau is not None:
        assert np.all(np.abs(d2.tau) <= tau * rtol)
    assert d2.limits_hold(1.0 + 1e-6) and d2.time_scale == pytest.approx(1.0, abs=1e-6)
    assert not d.limits_hold(s * 0.999)


def test_binding_limit_switches_with_the_limits():
    t, p, v = minimum_jerk_descent(0.2, 1.2)
    robot = get_robot("puma560").robot
    r = transfer("puma560", t, p, v)
    tau = np.array(PUMA560_TAU_LIMITS)
    assert joint_dynamics(robot, r, None, tau).binding_limit is None  # as recorded: within every limit
    weak = tau.copy()
    weak[1] = 0.7 * joint_dynamics(robot, r).peak_abs_tau[1]
    assert joint_dynamics(robot, r, None, weak).binding_limit == "torque"
    peak_qdd = joint_dynamics(robot, r).peak_abs_qdd.max()
    assert joint_dynamics(robot, r, peak_qdd / 4, weak).binding_limit == "acceleration"  # s_a = 2
    slow = transfer("puma560", t, p, v, qd_limits=r.peak_abs_qd.max() / 3)  # s_v = 3
    d = joint_dynamics(robot, slow, peak_qdd / 4, weak)
    assert d.binding_limit == "velocity" and d.time_scale == pytest.approx(3.0)
    scales = d.time_scales()
    assert scales["acceleration"] == pytest.approx(2.0) and 1 < scales["torque"] < 3


def test_summary_and_input_errors():
    t, p, v = minimum_jerk_descent(0.2, 1.0)
    r = transfer("simple6", t, p, v)
    with pytest.raises(ValueError, match="no dynamic parameters"):
        joint_dynamics(simple6(), r, tau_limits=10.0)
    with pytest.raises(ValueError, match="qdd_limits must be positive"):
        joint_dynamics(simple6(), r, qdd_limits=[1, 2, 3, 4, 5, -6])
    summary = joint_dynamics(simple6(), r, qdd_limits=2.0).summary()
    assert set(summary) == {
        "peak_abs_qdd",
        "peak_abs_qddd",
        "peak_abs_tau",
        "time_scales",
        "time_scale",
        "binding_limit",
        "feasible",
    }
    assert summary["peak_abs_tau"] is None and summary["time_scales"]["torque"] is None
    assert summary["binding_limit"] == "acceleration" and not summary["feasible"]
    assert summary["time_scale"] == pytest.approx(np.sqrt(max(summary["peak_abs_qdd"]) / 2.0))
    json.dumps(summary, allow_nan=False)


def test_failed_samples_stay_nan_and_are_left_out():
    t, p, v = minimum_jerk_descent(2.9, 1.0)  # the end is out of Simple6's reach
    r = transfer("simple6", t, p, v)
    d = joint_dynamics(simple6(), r, qdd_limits=5.0)
    bad = [f["sample"] for f in r.flags]
    assert np.all(np.isnan(d.qdd[bad])) and np.all(np.isfinite(d.qdd[: bad[0]]))
    assert np.all(np.isfinite(d.peak_abs_qdd)) and not d.feasible
    json.dumps(d.summary(), allow_nan=False)
