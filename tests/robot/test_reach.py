"""Tests of skilllib.robot (the reach shell that decides "unreachable") against closed forms and
random poses, and of the IK chain of skilllib.robot on a real failure of its first search."""

from __future__ import annotations

import numpy as np
import pytest
import roboticstoolbox as rtb

from skilllib.robot import (
    REACH_TOL_M,
    ROBOT_NAMES,
    get_robot,
    joint_axes,
    joint_origins,
    reach_shell,
    shoulder_point,
    simple6,
)
from skilllib.robot import _ik as ik


def test_simple6_shell_is_zero_to_two_metres_around_the_origin():
    shell = reach_shell(simple6())
    np.testing.assert_allclose(shell.shoulder, 0.0, atol=1e-12)
    assert shell.r_min == 0.0 and shell.r_max == pytest.approx(2.0, abs=1e-9)  # L1 + L2, |L1 - L2|
    assert not shell.outside([2.0, 0.0, 0.0]) and shell.outside([2.0 + 2 * REACH_TOL_M, 0.0, 0.0])
    assert shell.outside(np.array([[1.0, 0.0, -1.8], [1.0, 0.0, -1.7]])).tolist() == [True, False]


def test_puma_shell_matches_its_closed_form():
    # spherical wrist at the tool point: r_max = sqrt(d3^2 + (a2 + sqrt(a3^2 + d4^2))^2) from (0, 0, d1)
    robot = get_robot("puma560").robot
    L = robot.links
    shell = reach_shell(robot)
    np.testing.assert_allclose(shell.shoulder, [0, 0, L[0].d], atol=1e-12)
    r_max = np.hypot(L[2].d, L[1].a + np.hypot(L[2].a, L[3].d))
    assert shell.r_max == pytest.approx(r_max, abs=1e-9)
    # the elbow's limits (-225 to 45 deg) keep the forearm from folding back: r_min from q3 alone
    ets = robot.ets()
    q3 = np.linspace(*robot.qlim[:, 2], 4001)
    r = [np.linalg.norm(ets.eval(np.r_[0, 0, x, 0, 0, 0])[:3, 3] - shell.shoulder) for x in q3]
    assert shell.r_min == pytest.approx(min(r), abs=1e-6) and shell.r_min > 0.3


@pytest.mark.parametrize("name", ROBOT_NAMES)
def test_random_poses_lie_in_the_shell_and_its_distance_ignores_q1_q2(name):
    robot = get_robot(name).robot
    ets = robot.ets()
    shell = reach_shell(robot)
    rng = np.random.default_rng(3)
    qs = rng.uniform(ets.qlim[0], ets.qlim[1], size=(400, ets.n))
    r = shell.distance(np.array([ets.eval(q)[:3, 3] for q in qs]))
    assert np.all(r <= shell.r_max + 1e-9) and np.all(r >= shell.r_min - 1e-9)
    assert r.max() > 0.8 * shell.r_max  # the shell is not a loose bound: random poses come close to it
    for q in qs[:20]:  # rotating about axes through the shoulder point keeps the distance
        q2 = q.copy()
        q2[:2] = rng.uniform(ets.qlim[0, :2], ets.qlim[1, :2])
        assert shell.distance(ets.eval(q2)[:3, 3]) == pytest.approx(shell.distance(ets.eval(q)[:3, 3]), abs=1e-12)


@pytest.mark.parametrize("name", ["simple6", "ur5", "puma560"])
def test_joint_axes_from_the_jacobian_are_the_dh_axes(name):
    arm = get_robot(name)
    robot, q0 = arm.robot, arm.q0
    w, o = joint_axes(robot.ets(), q0)
    pos, axes = joint_origins(robot, q0)  # fkine_all: z axis and origin of DH frame j-1
    np.testing.assert_allclose(w, axes, atol=1e-12)
    for j in range(robot.n):  # the DH origin lies on the axis found
        np.testing.assert_allclose(np.cross(pos[j] - o[j], w[j]), 0.0, atol=1e-12)


def test_arm_without_a_shoulder_point_gets_the_loose_shell():
    # joints 1 and 2 parallel (alpha1 = 0): no shoulder point; the shell falls back to the base and the
    # sum of the link lengths
    links = [rtb.RevoluteDH(a=0.3), rtb.RevoluteDH(a=0.3, alpha=np.pi / 2)] + [
        rtb.RevoluteDH(a=0.1, alpha=np.pi / 2) for _ in range(4)
    ]
    arm = rtb.DHRobot(links, name="Planar-ish")
    with pytest.raises(ValueError, match="parallel"):
        shoulder_point(arm.ets(), np.zeros(6))
    shell = reach_shell(arm)
    assert shell.r_min == 0.0 and shell.r_max == pytest.approx(arm.reach)
    np.testing.assert_array_equal(shell.shoulder, [0, 0, 0])


def test_ik_chain_solves_what_the_seeded_search_cannot(monkeypatch):
    # Puma 560: a target 0.3 m away from the start pose's tool point; the seeded LM search is limited to
    # 2 iterations here, so it stops short; the restarting searches solve it inside the joint limits
    arm = get_robot("puma560")
    robot, q0 = arm.robot, arm.q0
    ets = robot.ets()
    target = ets.eval(q0)
    target[:3, 3] += [-0.1, 0.2, -0.2]
    real = rtb.ETS.ikine_LM

    def short_first(self, Tep, q0=None, **kw):
        if kw.get("slimit") == 1:
            kw["ilimit"] = 2
        return real(self, Tep, q0=q0, **kw)

    monkeypatch.setattr(rtb.ETS, "ikine_LM", short_first)
    ans = ik.solve_ik(ets, target, q0, 7, tol=1e-6, joint_tol=1e-9)
    assert ans.ok and ans.solver != "LM seeded" and ans.residual_m <= 1e-6
    assert np.all(ans.q >= ets.qlim[0]) and np.all(ans.q <= ets.qlim[1])
    seeded_only = ik.solve_ik(ets, target, q0, 7, tol=1e-6, joint_tol=1e-9, restarts=0)
    assert not seeded_only.ok and seeded_only.residual_m > 1e-3
