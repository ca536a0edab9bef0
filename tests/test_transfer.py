"""Tests of skilllib.transfer (IK, Jacobian, joint velocities, feasibility, time scaling) and of
the transfer figures."""
from __future__ import annotations

import json

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from scipy.integrate import cumulative_trapezoid  # noqa: E402

from skilllib import sparc  # noqa: E402
from skilllib.robots import ROBOT_NAMES, default_pose, get_robot, simple6  # noqa: E402
from skilllib.transfer import (  # noqa: E402
    EXP_TO_BASE,
    IK_RESIDUAL_TOL_M,
    TransferResult,
    apply_time_scale,
    minimum_jerk_descent,
    time_scale_factor,
    to_base_frame,
    transfer,
    transfer_summary,
)

SUMMARY_KEYS = {"cluster", "peak_abs_qd", "min_abs_det_j", "max_cond_j", "ik_max_residual_m",
                "feasible", "time_scale", "flags"}


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
    robot, q0, _ = get_robot(name)
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
    robot, q0, _ = get_robot(name)
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


def test_time_scaling_makes_an_infeasible_prototype_feasible():
    t, p, v = minimum_jerk_descent(0.25, 1.5)
    r = transfer("ur5", t, p, v)
    assert not r.feasible and r.flags == []
    s = r.time_scale
    assert s == pytest.approx(np.max(r.peak_abs_qd / r.qd_limits)) and s > 1
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
    assert bad and all(f["reason"].startswith("ik_failed") for f in r.flags)
    assert bad == list(range(bad[0], len(t)))  # the end of the path is out of reach
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
    import skilllib.transfer as tr

    t, p, v = minimum_jerk_descent(0.2, 1.0)
    t, p, v = t[:6], p[:6], v[:6]
    monkeypatch.setattr(tr, "IK_RESIDUAL_TOL_M", 0.0)
    r = tr.transfer("simple6", t, p, v)
    failed = [f["sample"] for f in r.flags if f["reason"].startswith("ik_failed")]
    assert failed and 0 not in failed  # sample 0 is the start pose itself: residual exactly 0
    assert failed == list(range(failed[0], len(t)))
    assert np.all(r.ik_residual_m[failed] > 0) and np.all(np.isnan(r.qd[failed]))
    assert "best position residual" in r.flags[0]["reason"]


def test_ill_conditioned_is_flagged_and_computed():
    t, p, v = minimum_jerk_descent(0.2, 1.0)
    r = transfer("simple6", t, p, v, cond_threshold=3.0)  # cond J is about 3.4 along this path
    assert len(r.flags) == len(t)
    assert all(f["reason"].startswith("ill_conditioned") for f in r.flags)
    assert np.all(np.isfinite(r.qd)) and not r.feasible


def test_singular_start_pose_is_flagged():
    q0 = np.deg2rad([0, -60, 120, 90, 0, 30])  # q5 = 0: wrist axes 4 and 6 aligned
    r = transfer(simple6(), [0.0], np.zeros((1, 3)), np.array([[0.0, -0.5, 0.0]]), q0=q0, qd_limits=np.pi)
    assert r.flags[0]["reason"].startswith("singular")
    assert np.all(np.isfinite(r.qd)) and abs(r.det_j[0]) < 1e-12
    json.dumps(r.summary(), allow_nan=False)


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
    assert r.min_abs_det_j > 0 and r.max_cond_j >= 1


def test_time_scaled_features_divide_pv_and_keep_sparc_with_the_scaled_cut_off():
    from skilllib import minimum_jerk_speed
    from skilllib.transfer import time_scaled_features

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
