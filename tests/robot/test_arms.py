"""Tests of skilllib.robot: Simple6 and the registry of arms."""

from __future__ import annotations

import numpy as np
import pytest
import roboticstoolbox as rtb

from skilllib.robot import (
    DEFAULT_POSE_DEG,
    GENERIC_QD_LIMIT,
    PANDA_QD_LIMITS,
    ROBOT_NAMES,
    default_pose,
    get_robot,
    joint_origins,
    qd_limits_vector,
    simple6,
)


def test_simple6_dh_table_matches_mdl_simple6():
    r = simple6()
    assert isinstance(r, rtb.DHRobot) and r.name == "Simple6" and r.n == 6 and not r.mdh
    expected = [(0, 0, np.pi / 2), (0, 1, 0), (0, 1, -np.pi / 2), (0, 0, -np.pi / 2), (0, 0, np.pi / 2), (0, 0, 0)]
    for link, (d, a, alpha) in zip(r.links, expected):
        assert link.isrevolute
        assert (link.d, link.a, link.alpha) == pytest.approx((d, a, alpha))
        assert link.offset == 0


def test_default_pose():
    assert DEFAULT_POSE_DEG == (0, -60, 120, 90, -90, 30)
    np.testing.assert_allclose(default_pose(), np.deg2rad(DEFAULT_POSE_DEG))
    T = simple6().fkine(default_pose())
    np.testing.assert_allclose(T.t, [1.0, 0.0, 0.0], atol=1e-12)  # two 1 m links, tool at the wrist


def test_spherical_wrist_joint_origins():
    pos, axes = joint_origins(simple6(), default_pose())
    np.testing.assert_allclose(pos[0], pos[1], atol=1e-12)  # q1, q2 at the shoulder
    np.testing.assert_allclose(pos[2], [0.5, 0, -np.sqrt(3) / 2], atol=1e-12)  # elbow
    for j in (3, 4, 5):  # wrist axes meet at the tool point
        np.testing.assert_allclose(pos[j], [1, 0, 0], atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(axes, axis=1), 1.0)


EXPECTED_QD_LIMITS = {
    "simple6": [np.pi] * 6,
    "ur5": [np.pi] * 6,
    "puma560": [np.pi] * 6,  # 180 deg/s
    "panda": [2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61],
}  # Franka datasheet


@pytest.mark.parametrize("name", ROBOT_NAMES)
def test_registry(name):
    arm = get_robot(name.upper())
    robot, q0, lim = arm.robot, arm.q0, arm.qd_limits
    assert arm.name == name and arm.n == robot.n
    n = robot.n
    assert q0.shape == (n,) and lim.shape == (n,)
    np.testing.assert_allclose(lim, EXPECTED_QD_LIMITS[name], rtol=1e-15)  # the documented limits, rad/s
    assert np.all(q0 >= robot.qlim[0] - 1e-12) and np.all(q0 <= robot.qlim[1] + 1e-12)
    J = robot.jacob0(q0)
    assert np.linalg.cond(J) < 20  # well away from a singularity


def test_registry_rejects_unknown_name():
    with pytest.raises(ValueError, match="simple6, ur5, puma560, panda"):
        get_robot("kuka")


def test_limits():
    assert GENERIC_QD_LIMIT == pytest.approx(np.pi)
    assert get_robot("ur5").qd_limits == pytest.approx(np.full(6, np.pi))
    # the Panda limits are those of roboticstoolbox's URDF model (Franka datasheet)
    np.testing.assert_allclose(rtb.models.Panda().qdlim[:7], PANDA_QD_LIMITS)
    assert get_robot("panda").robot.n == 7


def test_qd_limits_vector():
    np.testing.assert_allclose(qd_limits_vector(2.0, 3), [2, 2, 2])
    np.testing.assert_allclose(qd_limits_vector([1, 2, 3], 3), [1, 2, 3])
    with pytest.raises(ValueError, match="3 entries"):
        qd_limits_vector([1, 2], 3)
    with pytest.raises(ValueError, match="positive"):
        qd_limits_vector([1, 0, 3], 3)
    with pytest.raises(ValueError, match="positive"):
        qd_limits_vector(np.nan, 3)
