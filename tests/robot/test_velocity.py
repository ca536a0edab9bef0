"""Tests of skilllib.robot (IK, Jacobian, joint velocities, feasibility, time scaling) and of
the transfer figures."""

from __future__ import annotations

import json

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
import roboticstoolbox as rtb  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from robot_paths import minimum_jerk_descent  # noqa: E402
from roboticstoolbox.robot.IK import IKSolution  # noqa: E402
from scipy.integrate import cumulative_trapezoid  # noqa: E402
from scipy.optimize import brentq  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

from skilllib.robot import (
    BRANCH_JUMP_RAD,
    COND_THRESHOLD,
    EXP_TO_BASE,
    IK_CHAIN,
    IK_RESIDUAL_TOL_M,
    IK_RESTARTS,
    ROBOT_NAMES,
    SINGULAR_COND,
    TransferResult,
    apply_time_scale,
    default_pose,
    get_robot,
    simple6,
    time_scale_factor,
    to_base_frame,
    transfer,
    transfer_summary,
)
from skilllib.robot import _velocity as tr
from skilllib.smoothness import sparc

SUMMARY_KEYS = {
    "cluster",
    "peak_abs_qd",
    "min_abs_det_j",
    "max_cond_j",
    "ik_max_residual_m",
    "feasible",
    "time_scale",
    "flags",
}


def _fd_jacobian(robot, q: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """Central finite differences of fkine: linear rows from the position, angular rows from
    R(q+h) R(q-h)' = I + 2h [w]x (world frame)."""
    J = np.zeros((6, robot.n))
    for j in range(robot.n):
        dq = np.zeros(robot.n)
        dq[j] = h
        Tp, Tm = robot.fkine(q + dq).A, robot.fkine(q - dq).A
        J[:3, j] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        S = Tp[:3, :3] @ Tm[:3, :3].T
        J[3:, j] = np.array([S[2, 1] - S[1, 2], S[0, 2] - S[2, 0], S[1, 0] - S[0, 1]]) / 2 / (2 * h)
    return J


# --- the paper's check at the default pose -----------------------------------------------------


def test_default_pose_jacobian_inverse():
    robot, q = simple6(), default_pose()
    J = robot.ets().jacob0(q)
    qd = np.linalg.solve(J, [0, 0, -0.5, 0, 0, 0])
    np.testing.assert_allclose(qd, [0, -0.5, 0, 0, 0, 0.5], atol=1e-12)
    assert np.linalg.det(J) == pytest.approx(-np.sqrt(3) / 2)


def test_default_pose_through_transfer():
    # 0.5 m/s straight down in the experiment frame (-y) is -z in the base frame
    r = transfer("simple6", [0.0], np.zeros((1, 3)), np.array([[0.0, -0.5, 0.0]]))
    np.testing.assert_allclose(r.q[0], default_pose(), atol=1e-12)
    np.testing.assert_allclose(r.qd[0], [0, -0.5, 0, 0, 0, 0.5], atol=1e-9)
    assert r.flags == [] and r.feasible and r.time_scale == 1.0


# --- Jacobian and IK cross-checks --------------------------------------------------------------


@pytest.mark.parametrize("name", ROBOT_NAMES)
def test_jacobian_matches_finite_differences(name):
    arm = get_robot(name)
    robot, q0 = arm.robot, arm.q0
    rng = np.random.default_rng(1)
    for q in (q0, q0 + rng.uniform(-0.3, 0.3, robot.n)):
        np.testing.assert_allclose(robot.ets().jacob0(q), _fd_jacobian(robot, q), atol=1e-7)


@settings(max_examples=25, deadline=None)
@given(st.lists(st.floats(-np.pi, np.pi), min_size=6, max_size=6))
def test_simple6_jacobian_fd_property(q):
    robot = simple6()
    q = np.asarray(q)
    np.testing.assert_allclose(robot.ets().jacob0(q), _fd_jacobian(robot, q), atol=1e-7)


@pytest.mark.parametrize("name", ROBOT_NAMES)
def test_integrated_qd_reproduces_ik_path(name):
    # trapezoidal integration of qd = J^-1 v is second order: 10x finer sampling, 100x smaller error.
    # For the Panda too: the seeded IK steps, like J^+ v, add no null-space motion.
    errors = []
    for fs in (60.0, 600.0):
        t, p, v = minimum_jerk_descent(0.2, 1.0, fs=fs)
        r = transfer(name, t, p, v)
        assert r.flags == []
        q_int = r.q0 + cumulative_trapezoid(r.qd, t, axis=0, initial=0)
        errors.append(np.abs(q_int - r.q).max())
    assert errors[0] < 1e-3
    assert errors[1] < errors[0] / 50


@pytest.mark.parametrize("name", ROBOT_NAMES)
def test_ik_residual_orientation_and_placement(name):
    t, p, v = minimum_jerk_descent(0.2, 0.8)
    r = transfer(name, t, p, v)
    arm = get_robot(name)
    robot, q0 = arm.robot, arm.q0
    ets = robot.ets()
    T0 = ets.eval(q0)
    np.testing.assert_allclose(r.x_base[0], T0[:3, 3])  # the movement starts at the tool point of q0
    np.testing.assert_allclose(r.q[0], q0, atol=1e-9)
    assert r.ik_max_residual_m <= IK_RESIDUAL_TOL_M
    for k in range(len(t)):
        T = ets.eval(r.q[k])
        assert np.linalg.norm(T[:3, 3] - r.x_base[k]) <= IK_RESIDUAL_TOL_M
        np.testing.assert_allclose(T[:3, :3], T0[:3, :3], atol=1e-6)  # orientation held fixed
    # J qd reproduces the commanded spatial velocity (also for the redundant Panda)
    _, v_base = to_base_frame(p, v, T0[:3, 3])
    for k in range(len(t)):
        np.testing.assert_allclose(ets.jacob0(r.q[k]) @ r.qd[k], np.r_[v_base[k], 0, 0, 0], atol=1e-9)


def test_panda_uses_minimum_norm_pseudo_inverse():
    t, p, v = minimum_jerk_descent(0.2, 0.8)
    r = transfer("panda", t, p, v)
    ets = get_robot("panda").robot.ets()
    for k in (3, len(t) - 1):
        J = ets.jacob0(r.q[k])
        null = np.eye(7) - np.linalg.pinv(J) @ J
        np.testing.assert_allclose(null @ r.qd[k], 0, atol=1e-9)  # no null-space component
        s = np.linalg.svd(J, compute_uv=False)
        assert r.det_j[k] == pytest.approx(np.prod(s))  # manipulability sqrt(det(J J'))


# --- frames ------------------------------------------------------------------------------------


def test_exp_to_base_is_a_proper_rotation():
    R = EXP_TO_BASE
    np.testing.assert_allclose(R @ R.T, np.eye(3))
    assert np.linalg.det(R) == pytest.approx(1.0)
    np.testing.assert_allclose(R @ [0, 1, 0], [0, 0, 1])  # experiment up -> base z
    np.testing.assert_allclose(R @ [0, 0, 1], [1, 0, 0])  # anteroposterior -> base x
    np.testing.assert_allclose(R @ [1, 0, 0], [0, 1, 0])  # mediolateral -> base y


def test_to_base_frame_rejects_improper_rotation():
    with pytest.raises(ValueError, match="proper"):
        to_base_frame(np.zeros((2, 3)), np.zeros((2, 3)), np.zeros(3), np.diag([1.0, 1.0, -1.0]))


# --- feasibility and time scaling --------------------------------------------------------------


def test_time_scale_factor():
    assert time_scale_factor([1.0, 2.0], 4.0) == 1.0
    assert time_scale_factor([1.0, 6.0], [2.0, 3.0]) == pytest.approx(2.0)
    assert time_scale_factor([3.0, 1.0], [1.0, 3.0]) == pytest.approx(3.0)
    # at and just above the limit
    assert time_scale_factor([np.pi, 1.0], np.pi) == 1.0
    assert time_scale_factor([1.0, np.pi * (1 + 1e-8)], np.pi) == pytest.approx(1 + 1e-8, rel=1e-12)
    assert time_scale_factor([1.0, np.pi * (1 + 1e-8)], np.pi) > 1.0
    # joints never computed (NaN) are ignored; none computed gives NaN
    assert time_scale_factor([np.nan, 2.0], [1.0, 0.5]) == pytest.approx(4.0)
    assert np.isnan(time_scale_factor([np.nan, np.nan], 1.0))


def test_time_scaling_makes_an_infeasible_prototype_feasible():
    t, p, v = minimum_jerk_descent(0.25, 1.5)
    r = transfer("ur5", t, p, v)
    # hand computation: qd = J^-1 (R v, 0) at each reported q, then the largest |qd| / pi
    ets = get_robot("ur5").robot.ets()
    qd_hand = np.array([np.linalg.solve(ets.jacob0(q), np.r_[EXP_TO_BASE @ vk, 0, 0, 0]) for q, vk in zip(r.q, v)])
    s_hand = np.abs(qd_hand).max() / np.pi
    assert s_hand > 1.1  # the constructed case is clearly too fast for the UR5
    assert not r.feasible and r.flags == []
    s = r.time_scale
    assert s == pytest.approx(s_hand, rel=1e-9)
    t2, v2 = apply_time_scale(t, v, s)
    np.testing.assert_allclose(np.diff(t2), s * np.diff(t))
    r2 = transfer("ur5", t2, p, v2)
    np.testing.assert_allclose(r2.q, r.q, atol=1e-9)  # same path
    np.testing.assert_allclose(r2.qd, r.qd / s, atol=1e-9)  # every velocity divided by s
    assert r2.feasible and r2.time_scale == 1.0
    assert np.max(r2.peak_abs_qd / r2.qd_limits) == pytest.approx(1.0)  # the binding joint at its limit


def test_time_scaling_divides_pv_and_keeps_sparc():
    # full minimum-jerk bell: the SPARC band ends at the amplitude threshold (about 1.6 Hz), far below
    # fc = 5 Hz, which stays below the Nyquist frequency of every stretched version (60 / 3.7 / 2 Hz)
    t, _, v = minimum_jerk_descent(0.2, 1.0, fraction=1.0)
    speed = np.linalg.norm(v, axis=1)
    fs = 1 / (t[1] - t[0])
    for s in (1.26, 2.0, 3.7):
        t2, speed2 = apply_time_scale(t, speed, s)
        assert speed2.max() == pytest.approx(speed.max() / s)
        assert sparc(speed2, 1 / (t2[1] - t2[0]), fc=5.0) == pytest.approx(sparc(speed, fs, fc=5.0), abs=1e-12)


def test_sparc_of_a_truncated_profile_needs_a_scaled_cutoff():
    # truncated at contact: the spectrum is still above the threshold at fc = 10 Hz, so SPARC is
    # time-scale invariant only when fc scales with 1/s
    t, _, v = minimum_jerk_descent(0.2, 1.0, fraction=0.7)
    speed = np.linalg.norm(v, axis=1)
    fs, s = 1 / (t[1] - t[0]), 2.0
    _, speed2 = apply_time_scale(t, speed, s)
    assert sparc(speed2, fs / s, fc=10.0 / s) == pytest.approx(sparc(speed, fs, fc=10.0), abs=1e-12)
    assert abs(sparc(speed2, fs / s, fc=10.0) - sparc(speed, fs, fc=10.0)) > 0.05


def test_apply_time_scale_rejects_bad_factor():
    with pytest.raises(ValueError, match="positive"):
        apply_time_scale(np.arange(3.0), np.ones(3), 0.0)


# --- flags: unreachable, ill-conditioned, singular ---------------------------------------------


def test_unreachable_path_is_flagged_not_silent():
    t, p, v = minimum_jerk_descent(2.9, 1.0)  # 2 m down from Simple6's tool: beyond its 2 m reach
    r = transfer("simple6", t, p, v, cluster=4)
    bad = [f["sample"] for f in r.flags]
    assert bad and all(f["reason"].startswith("unreachable") for f in r.flags)
    beyond = np.flatnonzero(np.linalg.norm(r.x_base, axis=1) > 2.0)  # Simple6: 2 m from its shoulder at the origin
    assert bad == beyond.tolist() == list(range(bad[0], len(t)))  # exactly the end of the path beyond 2 m
    assert "m from the shoulder; the arm reaches 0 to 2 m" in r.flags[0]["reason"]
    nan_rows = np.nonzero(np.isnan(r.qd).any(axis=1))[0]
    assert nan_rows.tolist() == bad  # NaN only where flagged
    assert np.all(np.isfinite(r.qd[: bad[0]]))  # the rest still computed
    assert not r.feasible
    summary = r.summary()
    assert set(summary) == SUMMARY_KEYS and summary["cluster"] == 4
    json.dumps(summary, allow_nan=False)
    assert summary["flags"][0] == {"sample": bad[0], "reason": r.flags[0]["reason"]}


def test_ik_residual_check_is_applied(monkeypatch):
    # with an impossible tolerance every sample the solver cannot hit exactly must be flagged, not kept
    t, p, v = minimum_jerk_descent(0.2, 1.0)
    t, p, v = t[:6], p[:6], v[:6]
    monkeypatch.setattr(tr, "IK_RESIDUAL_TOL_M", 0.0)
    r = tr.transfer("simple6", t, p, v)
    failed = [f["sample"] for f in r.flags if f["reason"].startswith("ik_failed")]
    assert failed and 0 not in failed  # sample 0 is the start pose itself: residual exactly 0
    assert failed == list(range(failed[0], len(t)))
    assert np.all(r.ik_residual_m[failed] > 0) and np.all(np.isnan(r.qd[failed]))
    assert "best position residual" in r.flags[0]["reason"]


def _cond(ets, q: np.ndarray) -> float:
    """2-norm condition number of jacob0(q) from numpy's singular values (independent of transfer)."""
    s = np.linalg.svd(ets.jacob0(q), compute_uv=False)
    return float(s[0] / s[-1])


def test_ill_conditioned_is_flagged_and_computed():
    t, p, v = minimum_jerk_descent(0.2, 1.0)
    ets = simple6().ets()
    r0 = transfer("simple6", t, p, v)
    cond = np.array([_cond(ets, q) for q in r0.q])  # at the reported q, from numpy's SVD
    np.testing.assert_allclose(r0.cond_j, cond, rtol=1e-12)
    threshold = float(np.median(cond))  # about 3.4: half of the samples above it
    r = transfer("simple6", t, p, v, cond_threshold=threshold)
    above = np.nonzero(cond > threshold)[0].tolist()
    assert 0 < len(above) < len(t)
    assert [f["sample"] for f in r.flags] == above  # exactly the samples above the threshold
    assert all(f["reason"].startswith("ill_conditioned") and f"> {threshold:g}" in f["reason"] for f in r.flags)
    np.testing.assert_array_equal(r.qd, r0.qd)  # flagged samples still computed, the same way
    assert not r.feasible and r0.feasible


def test_singular_start_pose_is_flagged():
    q0 = np.deg2rad([0, -60, 120, 90, 0, 30])  # q5 = 0: wrist axes 4 and 6 aligned
    r = transfer(simple6(), [0.0], np.zeros((1, 3)), np.array([[0.0, -0.5, 0.0]]), q0=q0, qd_limits=np.pi)
    assert r.flags[0]["reason"].startswith("singular")
    assert np.all(np.isfinite(r.qd)) and abs(r.det_j[0]) < 1e-12
    json.dumps(r.summary(), allow_nan=False)


# --- robustness paths: IK branches, restarts, residual checks, conditioning edges ---------------

_E23 = np.array([0.0, 1.0, -1.0, 0.0, 0.0, 0.0])  # Simple6: q2 + d, q3 - d keeps the forearm direction,
#                                                   so the tool orientation is unchanged and the tool
#                                                   point moves by 2 sin(d / 2) (1 m upper arm)
_REAL_SOLVERS = {name: getattr(rtb.ETS, name) for name in ("ikine_LM", "ikine_GN")}


def _path_through(ets, qs) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """t (60 Hz), experiment-frame positions and zero velocities whose targets are the tool points of
    the poses ``qs`` (the first one being the start pose)."""
    x = np.array([ets.eval(q)[:3, 3] for q in qs])
    p = (x - x[0]) @ EXP_TO_BASE  # row form of p_exp = R' p_base
    return np.arange(len(qs)) / 60.0, p, np.zeros_like(p)


def _one_sample() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return np.array([0.0]), np.zeros((1, 3)), np.zeros((1, 3))


def _patch_ik(monkeypatch, answer=None) -> list[dict]:
    """Replace the IK solvers of the chain (ETS.ikine_LM, ETS.ikine_GN) by a recording wrapper.
    ``answer(i)`` gives the q (rad) the i-th call returns, claimed as a success, or None to run the real
    solver. Returns the list of calls (solver, q0, keyword arguments and the solution)."""
    calls: list[dict] = []

    def patched(name):
        def fake(self, Tep, q0=None, **kw):
            q = None if answer is None else answer(len(calls))
            if q is None:
                sol = _REAL_SOLVERS[name](self, Tep, q0=q0, **kw)
            else:
                sol = IKSolution(q=np.asarray(q, dtype=float), success=True, reason="fake")
            calls.append({"solver": name, "q0": np.array(q0, dtype=float), **kw, "sol": sol})
            return sol

        return fake

    for name in _REAL_SOLVERS:
        monkeypatch.setattr(rtb.ETS, name, patched(name))
    return calls


def _reasons(r: TransferResult, k: int) -> list[str]:
    return [f["reason"].split(":")[0] for f in r.flags if f["sample"] == k]


def test_branch_jump_flagged_above_threshold_not_below():
    ets, q0 = simple6().ets(), default_pose()
    for sign in (1.0, -1.0):
        for factor, jump in ((1 - 1e-5, False), (1 + 1e-5, True)):
            d = sign * factor * BRANCH_JUMP_RAD  # q2 and q3 both move by |d|: max step |d|, norm |d| sqrt 2
            r = transfer(simple6(), *_path_through(ets, [q0, q0 + d * _E23]), q0=q0, qd_limits=np.pi)
            np.testing.assert_allclose(r.q[1], q0 + d * _E23, atol=1e-7)  # IK stayed on the branch
            step = np.max(np.abs(r.q[1] - r.q[0]))
            assert (step > BRANCH_JUMP_RAD) == jump  # the constructed step is on the intended side
            assert r.flags == (
                [{"sample": 1, "reason": f"ik_branch_jump: joints move {step:.3g} rad in one sample"}] if jump else []
            )
            assert np.all(np.isfinite(r.qd))  # a jump is flagged, the sample still computed
    # steps of 0.6 BRANCH_JUMP_RAD: never flagged although the pose drifts 1.2 from q0 (the step is taken
    # from the previous sample); one jump of 1.2 is flagged once, the sample after it (no motion) is not
    qs = [
        q0,
        q0 + 0.6 * BRANCH_JUMP_RAD * _E23,
        q0 + 1.2 * BRANCH_JUMP_RAD * _E23,
        q0 + 2.4 * BRANCH_JUMP_RAD * _E23,
        q0 + 2.4 * BRANCH_JUMP_RAD * _E23,
    ]
    r = transfer(simple6(), *_path_through(ets, qs), q0=q0, qd_limits=np.pi)
    np.testing.assert_allclose(r.q, qs, atol=1e-7)
    assert [(f["sample"], f["reason"].split(":")[0]) for f in r.flags] == [(3, "ik_branch_jump")]


def test_ik_on_another_branch_is_flagged(monkeypatch):
    # the solver returns the wrist-flipped solution (q4 + pi, -q5, q6 + pi) of the same pose: zero residual,
    # every wrist joint turns by pi
    ets, q0 = simple6().ets(), default_pose()
    flipped = q0 + np.array([0, 0, 0, -np.pi, -2 * q0[4], -np.pi])  # (0, -60, 120, -90, 90, -150) deg
    np.testing.assert_allclose(ets.eval(flipped), ets.eval(q0), atol=1e-12)
    _patch_ik(monkeypatch, lambda i: flipped if i == 1 else None)
    t, p, v = _path_through(ets, [q0, q0])
    v[:] = [0.0, -0.5, 0.0]
    r = transfer(simple6(), t, p, v, q0=q0, qd_limits=np.pi)
    assert r.flags == [{"sample": 1, "reason": f"ik_branch_jump: joints move {np.pi:.3g} rad in one sample"}]
    np.testing.assert_array_equal(r.q[1], flipped)  # kept, not replaced by the seed
    np.testing.assert_allclose(r.qd[1], np.linalg.solve(ets.jacob0(flipped), [0, 0, -0.5, 0, 0, 0]), atol=1e-12)


def test_random_restart_solves_when_the_seeded_search_fails(monkeypatch):
    # UR5: a 0.72 m jump of the target; LM from the previous solution (50 iterations) does not converge,
    # a random restart does. The restart RNG is seeded with the sample index: the same q on every run.
    calls = _patch_ik(monkeypatch)
    ets = get_robot("ur5").robot.ets()
    p = np.array([[0.0, 0.0, 0.0], [0.6, 0.0, -0.4]]) @ EXP_TO_BASE  # base-frame offset (0.6, 0, -0.4) m
    t, v = np.array([0.0, 1 / 60]), np.zeros((2, 3))
    r = transfer("ur5", t, p, v)
    assert [(c["slimit"], c["seed"]) for c in calls] == [(1, None), (1, None), (IK_RESTARTS + 1, 1)]
    assert not calls[1]["sol"].success and calls[2]["sol"].success  # the restart, not the seeded try, solved it
    assert not any(f["reason"].startswith("ik_failed") for f in r.flags)
    T0 = ets.eval(r.q0)
    T = ets.eval(r.q[1])
    assert np.linalg.norm(T[:3, 3] - r.x_base[1]) <= IK_RESIDUAL_TOL_M and r.ik_residual_m[1] <= IK_RESIDUAL_TOL_M
    np.testing.assert_allclose(T[:3, :3], T0[:3, :3], atol=IK_RESIDUAL_TOL_M)
    assert np.all(r.q[1] >= ets.qlim[0]) and np.all(r.q[1] <= ets.qlim[1])
    step = np.max(np.abs(r.q[1] - r.q[0]))
    assert (step > BRANCH_JUMP_RAD) == ("ik_branch_jump" in _reasons(r, 1))
    r2 = transfer("ur5", t, p, v)
    np.testing.assert_array_equal(r2.q, r.q)  # reproducible to the bit
    np.testing.assert_array_equal(r2.qd, r.qd)


def test_ik_residual_tolerance_edge(monkeypatch):
    # the solver returns q0 + d (0, 1, -1, 0, 0, 0): same orientation, tool point 2 sin(d / 2) from the target
    ets, q0 = simple6().ets(), default_pose()
    for factor, ok in ((1 - 1e-6, True), (1 + 1e-6, False)):
        d = 2 * np.arcsin(factor * IK_RESIDUAL_TOL_M / 2)
        q_bad = q0 + d * _E23
        dp = np.linalg.norm(ets.eval(q_bad)[:3, 3] - ets.eval(q0)[:3, 3])
        assert dp == pytest.approx(factor * IK_RESIDUAL_TOL_M, rel=1e-8)
        calls = _patch_ik(monkeypatch, lambda i, q=q_bad: q)
        r = transfer(simple6(), *_one_sample(), q0=q0, qd_limits=np.pi)
        assert r.ik_residual_m[0] == pytest.approx(dp, rel=1e-8)  # the position residual, m
        if ok:
            assert r.flags == [] and len(calls) == 1
            np.testing.assert_array_equal(r.q[0], q_bad)
        else:
            # every search of the chain was tried and rejected: seeded LM, then the restarting searches
            assert [(c["solver"], c["slimit"], c["seed"], c.get("method"), c.get("pinv")) for c in calls] == [
                ("ikine_LM", 1, None, None, None),
                ("ikine_LM", IK_RESTARTS + 1, 0, None, None),
                ("ikine_GN", IK_RESTARTS + 1, 0, None, True),
                ("ikine_LM", IK_RESTARTS + 1, 0, "sugihara", None),
            ]
            assert _reasons(r, 0) == ["ik_failed"] and f"{dp:.3g} m" in r.flags[0]["reason"]
            assert np.all(np.isnan(r.q[0])) and np.all(np.isnan(r.qd[0]))


def test_orientation_residual_is_checked(monkeypatch):
    # q6 turns the tool about its own axis through the tool point: the position is exact, the
    # orientation off by eps rad; IK_RESIDUAL_TOL_M is also the orientation tolerance (rad)
    ets, q0 = simple6().ets(), default_pose()
    R0 = ets.eval(q0)[:3, :3]
    e6 = np.eye(6)[5]
    for factor, ok in ((0.99, True), (1.01, False)):
        q_bad = q0 + factor * IK_RESIDUAL_TOL_M * e6
        T = ets.eval(q_bad)
        assert np.linalg.norm(T[:3, 3] - ets.eval(q0)[:3, 3]) < 1e-15
        assert Rotation.from_matrix(R0.T @ T[:3, :3]).magnitude() == pytest.approx(factor * IK_RESIDUAL_TOL_M, rel=1e-6)
        _patch_ik(monkeypatch, lambda i, q=q_bad: q)
        r = transfer(simple6(), *_one_sample(), q0=q0, qd_limits=np.pi)
        if ok:
            assert r.flags == []
            np.testing.assert_array_equal(r.q[0], q_bad)
        else:
            assert _reasons(r, 0) == ["ik_failed"] and np.all(np.isnan(r.q[0]))
    # a wrong orientation from the first try is discarded and the next attempt (the real solver) used
    calls = _patch_ik(monkeypatch, lambda i: q0 + 10 * IK_RESIDUAL_TOL_M * e6 if i == 0 else None)
    r = transfer(simple6(), *_one_sample(), q0=q0, qd_limits=np.pi)
    assert len(calls) == 2 and r.flags == []
    np.testing.assert_allclose(r.q[0], q0, atol=1e-12)


def test_non_finite_ik_result_is_skipped(monkeypatch):
    q0 = default_pose()
    v = np.array([[0.0, -0.5, 0.0]])
    # NaN from every attempt: the sample fails, nothing of it is computed
    calls = _patch_ik(monkeypatch, lambda i: np.full(6, np.nan))
    r = transfer(simple6(), [0.0], np.zeros((1, 3)), v, q0=q0, qd_limits=np.pi)
    assert len(calls) == len(IK_CHAIN) and _reasons(r, 0) == ["ik_failed"]
    assert np.all(np.isnan(r.q)) and np.all(np.isnan(r.qd)) and np.isnan(r.det_j[0]) and np.isnan(r.cond_j[0])
    assert not np.isfinite(r.ik_residual_m[0]) and not r.feasible
    json.dumps(r.summary(), allow_nan=False)
    # one NaN joint from the seeded try: skipped, the restart (real solver) is used
    calls = _patch_ik(monkeypatch, lambda i: np.r_[q0[:5], np.nan] if i == 0 else None)
    r = transfer(simple6(), [0.0], np.zeros((1, 3)), v, q0=q0, qd_limits=np.pi)
    assert len(calls) == 2 and r.flags == []
    np.testing.assert_allclose(r.q[0], q0, atol=1e-12)
    np.testing.assert_allclose(r.qd[0], [0, -0.5, 0, 0, 0, 0.5], atol=1e-9)


@pytest.mark.parametrize("n", [5, 4])
def test_arm_with_fewer_than_six_joints_is_rejected(n):
    links = [rtb.RevoluteDH(a=0.5, alpha=np.pi / 2 if j % 2 == 0 else 0.0) for j in range(n)]
    arm = rtb.DHRobot(links, name=f"Arm{n}")
    with pytest.raises(ValueError, match=rf"Arm{n} has {n} joints"):
        transfer(arm, *_one_sample(), q0=np.zeros(n), qd_limits=1.0)


def test_out_of_reach_is_unreachable_without_a_search(monkeypatch):
    # Simple6 reaches 2 m from its shoulder; the tool starts 1 m in front of it, so 2.5 m below the start is
    # out of reach (sqrt(1 + 2.5^2) = 2.69 m). Path: start, out, out, start, out: the three out-of-reach
    # samples are "unreachable" and not searched; the return to the start is solved by the seeded search.
    calls = _patch_ik(monkeypatch)
    p = np.array([[0, 0, 0], [0, -2.5, 0], [0, -2.5, 0], [0, 0, 0], [0, -2.5, 0]], dtype=float)
    r = transfer("simple6", np.arange(5) / 60, p, np.zeros((5, 3)))
    assert [f["sample"] for f in r.flags] == [1, 2, 4]
    assert all(
        f["reason"] == "unreachable: the target lies 2.693 m from the shoulder; the arm reaches 0 to 2 m"
        for f in r.flags
    )
    assert [(c["solver"], c["slimit"]) for c in calls] == [("ikine_LM", 1), ("ikine_LM", 1)]  # samples 0 and 3
    for c in calls:  # every search starts from the last solved pose (q0)
        np.testing.assert_array_equal(c["q0"], default_pose())
    np.testing.assert_allclose(r.q[3], default_pose(), atol=1e-12)
    assert np.all(np.isnan(r.qd[[1, 2, 4]])) and np.all(np.isnan(r.ik_residual_m[[1, 2, 4]]))


def test_ik_failure_inside_the_reach_names_the_conditioning(monkeypatch):
    # every solver returns a pose 1 mm off for sample 2 (inside the reach): an IK failure, not "unreachable",
    # with the best residual and cond J at the last solved sample (1); the next sample is solved again
    ets, q0 = simple6().ets(), default_pose()
    qs = [q0, q0 + 0.05 * _E23, q0 + 0.1 * _E23, q0 + 0.15 * _E23]
    off = q0 + 0.1 * _E23 + np.r_[0, 0, 0.001, 0, 0, 0]
    n_fail = len(IK_CHAIN)
    calls = _patch_ik(monkeypatch, lambda i: off if 2 <= i < 2 + n_fail else None)
    r = transfer(simple6(), *_path_through(ets, qs), q0=q0, qd_limits=np.pi)
    assert [(f["sample"], f["reason"].split(":")[0]) for f in r.flags] == [(2, "ik_failed")]
    reason = r.flags[0]["reason"]
    assert f"cond J = {_cond(ets, r.q[1]):.3g} at the last solved sample 1" in reason
    assert "although the target lies" in reason and "the arm reaches 0 to 2 m" in reason
    assert f"best position residual {r.ik_residual_m[2]:.3g} m" in reason and r.ik_residual_m[2] > 1e-4
    assert len(calls) == 3 + n_fail and np.all(np.isnan(r.q[2]))
    np.testing.assert_allclose(r.q[3], qs[3], atol=1e-7)
    np.testing.assert_array_equal(calls[-1]["q0"], r.q[1])  # sample 3 searched from the last solved pose


def test_ik_near_the_elbow_singularity_is_solved_by_the_chain():
    # targets approaching Simple6's 2 m reach along the stretched arm (cond J grows without bound): every
    # one inside the reach is solved to the tolerance, none is called unreachable; beyond 2 m all are
    d = np.array([0.0, 0.5, 1.0, 1.5, 1.7, 1.72, 1.73, 1.732, 1.7320508, 1.74, 1.8])  # descents below (1, 0, 0)
    p = np.c_[np.zeros_like(d), -d, np.zeros_like(d)]
    r = transfer("simple6", np.arange(d.size) / 60, p, np.zeros_like(p))
    inside = np.hypot(1.0, d) <= 2.0 + 1e-6
    assert inside.sum() == 9 and not inside[-2:].any()
    assert {f["sample"] for f in r.flags if f["reason"].startswith("unreachable")} == {9, 10}
    assert not [f for f in r.flags if f["reason"].startswith("ik_failed")]
    assert np.nanmax(r.ik_residual_m[inside]) <= IK_RESIDUAL_TOL_M
    assert r.cond_j[8] > 100  # the last one is practically at the singularity


def test_condition_number_edges(monkeypatch):
    # Simple6 stretches out (elbow singularity) as q3 -> 0: cond J is about 6.6 / q3 near it
    ets, q0 = simple6().ets(), default_pose()
    v = np.array([[0.0, -0.5, 0.0]])

    def pose(q3):
        q = q0.copy()
        q[2] = q3
        return q

    def q3_at(c):  # q3 where cond J = c (cond falls as q3 grows)
        return brentq(lambda x: np.log(_cond(ets, pose(x))) - np.log(c), 1e-14, 1.0, xtol=1e-300, rtol=1e-15)

    def run(q):
        return transfer(simple6(), [0.0], np.zeros((1, 3)), v, q0=q, qd_limits=np.pi)

    for c_edge, rel in ((COND_THRESHOLD, 1e-6), (SINGULAR_COND, 1e-2)):
        x = q3_at(c_edge)
        for q3 in (x * (1 + rel), x * (1 - rel)):
            q = pose(q3)
            c = _cond(ets, q)
            assert abs(c / c_edge - 1) < 3 * rel
            r = run(q)
            np.testing.assert_array_equal(r.q[0], q)
            assert r.cond_j[0] == pytest.approx(c, rel=1e-3)
            J = ets.jacob0(q)
            if c > SINGULAR_COND:
                assert _reasons(r, 0) == ["singular"]  # not also ill-conditioned
                np.testing.assert_allclose(r.qd[0], np.linalg.lstsq(J, [0, 0, -0.5, 0, 0, 0], rcond=None)[0])
            elif c > COND_THRESHOLD:
                assert _reasons(r, 0) == ["ill_conditioned"]
                assert np.all(np.isfinite(r.qd[0]))
            else:
                assert r.flags == []
                np.testing.assert_allclose(r.qd[0], np.linalg.solve(J, [0, 0, -0.5, 0, 0, 0]), rtol=1e-12)
    # exactly at a threshold is not above it
    r = run(q0)
    c = r.cond_j[0]
    assert c == pytest.approx(_cond(ets, q0), rel=1e-12)
    assert run(q0).flags == [] and transfer("simple6", *_one_sample(), cond_threshold=c).flags == []
    assert _reasons(transfer("simple6", *_one_sample(), cond_threshold=np.nextafter(c, 0)), 0) == ["ill_conditioned"]
    monkeypatch.setattr(tr, "SINGULAR_COND", c)
    assert run(q0).flags == []
    monkeypatch.setattr(tr, "SINGULAR_COND", np.nextafter(c, 0))
    assert _reasons(run(q0), 0) == ["singular"]


def test_q0_joint_limit_tolerance():
    # Puma 560 (asymmetric limits): q0 at a limit or 1e-9 rad inside it is accepted and is the first
    # sample's solution; 1e-8 rad outside is an error naming the joint
    arm = get_robot("puma560")
    robot, q_start = arm.robot, arm.q0
    qlim = robot.ets().qlim
    for j in range(robot.n):
        for side, outward in ((0, -1.0), (1, 1.0)):
            for offset in (0.0, -1e-9):
                q = q_start.copy()
                q[j] = qlim[side, j] + outward * offset
                r = transfer(robot, *_one_sample(), q0=q, qd_limits=np.pi)
                assert not [f for f in r.flags if f["reason"].startswith("ik")]
                np.testing.assert_array_equal(r.q[0], q)
            q = q_start.copy()
            q[j] = qlim[side, j] + outward * 1e-8
            with pytest.raises(ValueError, match=rf"at joint\(s\) q{j + 1}$"):
                transfer(robot, *_one_sample(), q0=q, qd_limits=np.pi)


def test_ik_solution_outside_the_joint_limits_is_not_accepted():
    # Puma 560 with q1 0.01 rad below its upper limit (160 deg), moved 1 cm per sample along the direction
    # q1 turns the tool: from sample 1 on the targets need q1 > 160 deg (or another branch)
    arm = get_robot("puma560")
    robot, q_start = arm.robot, arm.q0
    ets = robot.ets()
    q0 = q_start.copy()
    q0[0] = ets.qlim[1, 0] - 0.01
    d = ets.jacob0(q0)[:3, 0] / np.linalg.norm(ets.jacob0(q0)[:3, 0])
    p = np.outer(np.arange(5) * 0.01, d) @ EXP_TO_BASE
    r = transfer(robot, np.arange(5) / 60, p, np.zeros((5, 3)), q0=q0, qd_limits=np.pi)
    failed = {f["sample"] for f in r.flags if f["reason"].startswith("ik_failed")}
    for k in range(5):  # every sample either flagged as failed or solved inside the joint limits
        assert k in failed or (np.all(r.q[k] >= ets.qlim[0]) and np.all(r.q[k] <= ets.qlim[1])), (k, np.rad2deg(r.q[k]))


def _result_with_qd(qd, qd_limits, flags=()) -> TransferResult:
    qd = np.asarray(qd, dtype=float)
    N, n = qd.shape
    return TransferResult(
        robot="test",
        q0=np.zeros(n),
        qd_limits=np.asarray(qd_limits, dtype=float),
        t=np.arange(N) / 60.0,
        x_base=np.zeros((N, 3)),
        q=np.zeros((N, n)),
        qd=qd,
        det_j=np.ones(N),
        cond_j=np.ones(N),
        ik_residual_m=np.zeros(N),
        flags=list(flags),
    )


def test_within_limits_edges_and_feasibility():
    lim = np.array([2.0, 3.0])
    nan_row = [np.nan, np.nan]  # a failed sample: not counted
    at_limit = _result_with_qd([[1.0, -3.0], [-2.0, 0.5], nan_row], lim)  # peaks exactly at the limits
    assert at_limit.within_limits and at_limit.feasible and at_limit.time_scale == 1.0
    np.testing.assert_array_equal(at_limit.peak_abs_qd, lim)
    inside_tol = _result_with_qd([[2.0 * (1 + 5e-10), -3.0 * (1 + 5e-10)]], lim)  # within the relative 1e-9
    assert inside_tol.within_limits and inside_tol.time_scale == pytest.approx(1.0, abs=1e-9)
    for j in range(2):  # either joint 1e-8 above its own limit
        qd = lim * 0.5
        qd[j] = -lim[j] * (1 + 1e-8)
        over = _result_with_qd([qd, -lim * 0.9], lim)
        assert not over.within_limits and not over.feasible
        assert over.time_scale == pytest.approx(1 + 1e-8, rel=1e-12) and over.time_scale > 1
    flagged = _result_with_qd([[0.1, 0.1]], lim, flags=[{"sample": 0, "reason": "ill_conditioned: test"}])
    assert flagged.within_limits and not flagged.feasible
    assert not _result_with_qd([nan_row], lim).within_limits  # nothing computed: not within


# --- results.json contract and input checks ----------------------------------------------------


def test_summary_contract():
    results = []
    for k, (A, vp) in enumerate([(0.15, 0.5), (0.25, 1.5)]):
        t, p, v = minimum_jerk_descent(A, vp)
        results.append(transfer("ur5", t, p, v, cluster=k))
    block = transfer_summary(results)
    assert set(block) == {"robot", "q0_deg", "qd_limits", "prototypes"}
    assert block["robot"] == "UR5" and block["q0_deg"] == pytest.approx([0, -90, 90, -90, -90, 0])
    assert block["qd_limits"] == pytest.approx([np.pi] * 6)
    for k, entry in enumerate(block["prototypes"]):
        assert set(entry) == SUMMARY_KEYS and entry["cluster"] == k
        assert len(entry["peak_abs_qd"]) == 6 and all(type(x) is float for x in entry["peak_abs_qd"])
    assert block["prototypes"][0]["feasible"] and block["prototypes"][0]["time_scale"] == 1.0
    assert not block["prototypes"][1]["feasible"] and block["prototypes"][1]["time_scale"] > 1
    json.dumps(block, allow_nan=False)
    with pytest.raises(ValueError, match="same robot"):
        transfer_summary([results[0], transfer("simple6", [0.0], np.zeros((1, 3)), np.zeros((1, 3)))])


def test_input_errors():
    t, p, v = minimum_jerk_descent(0.2, 1.0)
    with pytest.raises(ValueError, match="shape"):
        transfer("simple6", t, p[:-1], v)
    with pytest.raises(ValueError, match="increasing"):
        transfer("simple6", t[::-1], p, v)
    p_nan = p.copy()
    p_nan[2, 1] = np.nan
    with pytest.raises(ValueError, match="finite"):
        transfer("simple6", t, p_nan, v)
    with pytest.raises(ValueError, match="required"):
        transfer(simple6(), t, p, v)
    with pytest.raises(ValueError, match="6 joint angles"):
        transfer(simple6(), t, p, v, q0=np.zeros(5), qd_limits=1.0)
    with pytest.raises(ValueError, match="valid names"):
        transfer("abb", t, p, v)
    with pytest.raises(ValueError, match="joint limits of Puma 560 at joint"):  # the paper's pose
        transfer(get_robot("puma560").robot, t, p, v, q0=default_pose(), qd_limits=np.pi)
    with pytest.raises(ValueError, match="one per joint"):
        transfer("simple6", t, p, v, qd_limits=[1.0, 2.0])


def test_minimum_jerk_descent():
    t, p, v = minimum_jerk_descent(0.2, 1.0, fs=60.0, fraction=0.7)
    np.testing.assert_allclose(np.diff(t), 1 / 60)
    assert -p[-1, 1] <= 0.7 * 0.2 + 1e-12 and -p[-1, 1] > 0.6 * 0.2
    assert v[-1, 1] < -0.5  # contact with non-zero speed
    full_t, _, full_v = minimum_jerk_descent(0.2, 1.0, fraction=1.0)
    assert np.abs(full_v[:, 1]).max() == pytest.approx(1.0, rel=1e-3)
    assert (np.abs(np.gradient(p[:, 1], t) - v[:, 1])).max() < 0.05  # velocities match positions


# --- figures ------------------------------------------------------------------------------------


def test_transfer_figures():
    from skilllib import figures

    style_before = plt.rcParams["axes.facecolor"]
    res = []
    for k, (A, vp) in enumerate([(0.15, 0.5), (0.25, 1.5), (2.9, 1.0)]):
        t, p, v = minimum_jerk_descent(A, vp)
        res.append(transfer("simple6", t, p, v, cluster=k))
    fig = figures.plot_simple6_figure()
    assert len(fig.axes) == 2 and fig.axes[0].get_zlabel() == "z (m)"
    fig_qd = figures.plot_joint_velocities(res)
    ax = fig_qd.axes[0]
    assert ax.get_ylabel() == "joint velocity (rad/s)" and "(s)" in fig_qd.axes[-1].get_xlabel()
    assert len(ax.get_lines()) >= 6 + 2  # six joints, +-limit
    texts = {t.get_text() for ax in fig.axes for t in ax.texts}
    assert {f"$q_{j}$" for j in range(1, 7)} | {"$x_t$", "$y_t$", "$z_t$"} <= texts  # joints and tool frame labelled
    fig_map = figures.plot_frame_mapping(simple6(), res[0])
    assert fig_map.axes[0].get_xlabel() == "x (m)"
    assert "$y_e$ up" in {t.get_text() for t in fig_map.axes[0].texts}
    arms = [(get_robot(n).robot, transfer(n, *minimum_jerk_descent(0.15, 0.5))) for n in ("ur5", "panda")]
    fig_arms = figures.robot.plot_start_poses(arms)
    assert len(fig_arms.axes) == 2 and all(ax.get_zlabel() == "z (m)" for ax in fig_arms.axes)
    assert "Panda" in fig_arms.axes[1].get_title()
    plt.close(fig_arms)
    with pytest.raises(ValueError):
        figures.robot.plot_start_poses([])
    # drawing with roboticstoolbox must not switch the book's matplotlib style to ggplot
    assert plt.rcParams["axes.facecolor"] == style_before
    for f in (fig, fig_qd, fig_map):
        plt.close(f)
    with pytest.raises(ValueError):
        figures.plot_joint_velocities([])


def test_result_is_a_dataclass_with_per_sample_arrays():
    t, p, v = minimum_jerk_descent(0.2, 1.0)
    r = transfer("puma560", t, p, v)
    assert isinstance(r, TransferResult)
    N = len(t)
    assert r.q.shape == r.qd.shape == (N, 6)
    assert r.det_j.shape == r.cond_j.shape == r.ik_residual_m.shape == (N,)
    ets = get_robot("puma560").robot.ets()
    cond = np.array([_cond(ets, q) for q in r.q])  # numpy's SVD at the reported q
    det = np.array([np.linalg.det(ets.jacob0(q)) for q in r.q])
    np.testing.assert_allclose(r.cond_j, cond, rtol=1e-12)
    np.testing.assert_allclose(r.det_j, det, rtol=1e-9)
    assert r.max_cond_j == pytest.approx(cond.max(), rel=1e-12)
    assert r.min_abs_det_j == pytest.approx(np.abs(det).min(), rel=1e-9)


def test_time_scaled_features_divide_pv_and_keep_sparc_with_the_scaled_cut_off():
    from skilllib.robot import time_scaled_features
    from skilllib.smoothness import minimum_jerk_speed

    t = np.arange(0, 0.5, 1 / 60)
    v = minimum_jerk_speed(t, T=0.6, D=0.2)  # cut before the end: non-zero speed at contact
    m = time_scaled_features(v, 60.0, 1.7)
    assert m["pv"] == pytest.approx(v.max() / 1.7, rel=1e-12)
    assert m["sparc_fc_scaled"] == pytest.approx(sparc(v, 60.0), abs=1e-12)
    assert m["n_resampled"] > v.size and m["pv_resampled"] <= m["pv"] + 1e-12
    assert "sparc_fixed_fc" not in m  # the stretched samples' Nyquist frequency (17.6 Hz) is below fc
    t_r = np.arange(0, (v.size - 1) / 60 * 1.7 + 1e-9, 1 / 60)
    v_r = np.interp(t_r, np.arange(v.size) / 60 * 1.7, v / 1.7)
    assert m["sparc_resampled_fixed_fc"] == pytest.approx(sparc(v_r, 60.0), abs=1e-12)
