"""Edge cases of skilllib.robot and skilllib.robot that the main tests (tests/test_transfer.py) leave open:
the time stretch of a trajectory that does not start at t = 0, the resampled features of a stretched
profile, the sampling and argument checks of the synthetic minimum-jerk prototype, and the text of an IK
failure. Expected values come from the definitions in the docstrings (t -> t0 + s (t - t0), v -> v / s;
s(tau) = A (10 tau^3 - 15 tau^4 + 6 tau^5), T = 1.875 A / peak speed), computed here with numpy."""

from __future__ import annotations

import math

import numpy as np
import pytest
from robot_paths import minimum_jerk_descent
from roboticstoolbox.robot.IK import IKSolution
from scipy.spatial.transform import Rotation

from skilllib.robot import (
    BRANCH_JUMP_RAD,
    IK_CHAIN,
    JOINT_LIMIT_TOL_RAD,
    QD_LIMIT_RTOL,
    IKAnswer,
    TransferResult,
    apply_time_scale,
    default_pose,
    pose_residual,
    reach_shell,
    simple6,
    solve_ik,
    time_scale_factor,
    time_scaled_features,
    to_base_frame,
    transfer,
    transfer_summary,
)
from skilllib.robot import _ik as ik
from skilllib.robot import _velocity as tr
from skilllib.smoothness import DEFAULT_FC, sparc

#: The minimum-jerk peak speed is this factor times A / T (Flash & Hogan 1985).
MJ_PEAK_FACTOR = 1.875

#: Sampling rate of the experiment, Hz.
FS = 60.0


def _mj_position(t: np.ndarray, A: float, T: float) -> np.ndarray:
    """Minimum-jerk distance travelled (m) at times t (s): A (10 tau^3 - 15 tau^4 + 6 tau^5), tau = t / T
    held at 1 after T (the hand rests at A)."""
    tau = np.minimum(t / T, 1.0)
    return A * (10 * tau**3 - 15 * tau**4 + 6 * tau**5)


# --- apply_time_scale ---------------------------------------------------------------------------

T_OFFSET_S = 2.5  # a trajectory that starts 2.5 s into a recording


def test_time_scale_keeps_a_late_start_time():
    """t -> t0 + s (t - t0) with t0 != 0. Catches: the stretch anchored at t[1] instead of t[0], or
    t + t0 / t - t[1] in place of t - t0 (all invisible when t starts at 0)."""
    t = T_OFFSET_S + np.arange(5) / FS
    v = np.linspace(0.0, 1.0, 5)
    for s in (0.5, 1.0, 3.0):
        t2, v2 = apply_time_scale(t, v, s)
        np.testing.assert_allclose(t2, t[0] + s * (t - t[0]), rtol=1e-15)
        assert t2[0] == t[0]
        np.testing.assert_allclose(np.diff(t2), s / FS, rtol=1e-9)
        np.testing.assert_allclose(v2, v / s, rtol=1e-15)


def test_time_scale_accepts_a_speed_up_and_the_identity():
    """0 < s <= 1 is a valid factor (s < 1 speeds the movement up, s = 1 leaves it unchanged); only s <= 0
    or a non-finite s is rejected. Catches: the check written as s <= 1."""
    t, v = np.arange(4) / FS, np.array([[0.0, -1.0, 0.0]] * 4)
    t1, v1 = apply_time_scale(t, v, 1.0)
    np.testing.assert_array_equal(t1, t)
    np.testing.assert_array_equal(v1, v)
    t_half, v_half = apply_time_scale(t, v, 0.5)
    np.testing.assert_allclose(t_half, t / 2)
    np.testing.assert_allclose(v_half, 2 * v)
    for bad in (-1.0, 0.0, np.inf, np.nan):
        with pytest.raises(ValueError, match=f"time scale s must be positive and finite, got {bad}"):
            apply_time_scale(t, v, bad)


def test_time_scale_is_computed_in_double_precision():
    """Integer times with an integer factor, and single-precision (float32) recordings, are stretched in
    float64: the result equals the double-precision formula exactly. Catches: t or the velocities not
    converted to float (an integer array, or float32 rounding of about 1e-7, comes back)."""
    t2, v2 = apply_time_scale([0, 1, 2], [3, 6, 9], 3)
    assert t2.dtype == np.float64 and v2.dtype == np.float64
    np.testing.assert_array_equal(t2, [0.0, 3.0, 6.0])
    np.testing.assert_array_equal(v2, [1.0, 2.0, 3.0])
    t32 = (T_OFFSET_S + np.arange(6) / FS).astype(np.float32)
    v32 = np.linspace(0.1, 1.3, 6).astype(np.float32)
    s = 1.7
    t2, v2 = apply_time_scale(t32, v32, s)
    assert t2.dtype == np.float64 and v2.dtype == np.float64
    t64, v64 = t32.astype(np.float64), v32.astype(np.float64)
    np.testing.assert_array_equal(t2, t64[0] + s * (t64 - t64[0]))
    np.testing.assert_array_equal(v2, v64 / s)


def test_time_scale_rejects_mismatched_lengths_naming_both():
    """A velocity array with another number of samples than t is an error that names both counts.
    Catches: a message without the counts, or counts read from the wrong axis (v's 3 components, t's
    missing second axis)."""
    n_t, n_v = 3, 4
    with pytest.raises(ValueError, match=f"^velocity has {n_v} samples but t has {n_t}$"):
        apply_time_scale(np.arange(n_t) / FS, np.zeros((n_v, 3)), 2.0)
    with pytest.raises(ValueError, match=f"^velocity has {n_v} samples but t has {n_t}$"):
        apply_time_scale(np.arange(n_t) / FS, np.zeros(n_v), 2.0)


# --- time_scaled_features -----------------------------------------------------------------------


def _truncated_speed() -> np.ndarray:
    """Speed (m/s) of a minimum-jerk descent cut at 70 % of its amplitude: non-zero at contact, so its
    SPARC depends on the cut-off."""
    _, _, v = minimum_jerk_descent(0.2, 1.0, fs=FS, fraction=0.7)
    return np.linalg.norm(v, axis=1)


def _resampled(speed: np.ndarray, s: int) -> np.ndarray:
    """The profile stretched by an integer s, linearly resampled at FS from its first to its last stretched
    sample (which lies on the FS grid: (N - 1) s + 1 samples)."""
    t_s = s * np.arange(speed.size) / FS
    t_r = np.arange((speed.size - 1) * s + 1) / FS
    return np.interp(t_r, t_s, speed / s)


@pytest.mark.parametrize("s", [2, 3])
def test_time_scaled_features_resample_up_to_the_last_sample(s):
    """An integer stretch puts the last stretched sample exactly on the FS grid: it is part of the
    resampled profile ((N - 1) s + 1 samples). Catches: the end of the resampling grid rounded down."""
    v = _truncated_speed()
    m = time_scaled_features(v, FS, s)
    assert m["n_resampled"] == (v.size - 1) * s + 1
    v_r = _resampled(v, s)
    assert m["pv_resampled"] == pytest.approx(v_r.max(), rel=1e-12)


def test_time_scaled_features_cut_offs():
    """Each SPARC uses its documented cut-off: fc / s on the stretched samples (equal to the original's with
    fc) and on the resampled profile, fc itself for the fixed one; a non-default fc is passed on.
    Catches: the stretched samples given the rate fs s, a cut-off dropped (the default 20 Hz used), a key
    renamed."""
    v = _truncated_speed()
    s, fc = 2, DEFAULT_FC / 2
    m = time_scaled_features(v, FS, s, fc=fc)
    assert set(m) == {
        "pv",
        "sparc_fc_scaled",
        "n_resampled",
        "pv_resampled",
        "sparc_resampled_fc_scaled",
        "sparc_resampled_fixed_fc",
    }
    assert m["pv"] == pytest.approx(v.max() / s, rel=1e-12)
    assert m["sparc_fc_scaled"] == pytest.approx(sparc(v, FS, fc=fc), abs=1e-12)
    v_r = _resampled(v, s)
    scaled, fixed = sparc(v_r, FS, fc=fc / s), sparc(v_r, FS, fc=fc)
    # preconditions: the cut-offs matter for this profile, so a wrong one is seen
    assert min(abs(scaled - fixed), abs(scaled - sparc(v_r, FS)), abs(fixed - sparc(v_r, FS))) > 1e-3
    assert m["sparc_resampled_fc_scaled"] == pytest.approx(scaled, abs=1e-12)
    assert m["sparc_resampled_fixed_fc"] == pytest.approx(fixed, abs=1e-12)


# --- minimum_jerk_descent -----------------------------------------------------------------------

#: A movement of T = 0.5 s: at 60 Hz its end falls exactly on sample 30.
A_M, T_S = 0.2, 0.5
PEAK = MJ_PEAK_FACTOR * A_M / T_S


def test_full_descent_ends_on_the_sample_at_its_duration():
    """fraction = 1 keeps the whole movement: samples 0 .. T fs, the last one at rest at -A with zero
    speed, and none after T. Catches: the time grid cut before T or running past it (the position then
    taken beyond tau = 1), the last sample (s = A exactly) dropped by a tolerance of the wrong sign."""
    t, p, v = minimum_jerk_descent(A_M, PEAK, fs=FS, fraction=1.0)
    n_expected = round(T_S * FS) + 1
    assert t.size == n_expected
    np.testing.assert_allclose(t, np.arange(n_expected) / FS, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(-p[:, 1], _mj_position(t, A_M, T_S), rtol=1e-12, atol=1e-15)
    assert p[-1, 1] == pytest.approx(-A_M, rel=1e-12) and v[-1, 1] == pytest.approx(0.0, abs=1e-12)
    assert np.abs(v[:, 1]).max() == pytest.approx(PEAK, rel=1e-12)  # the middle sample, tau = 1/2
    np.testing.assert_array_equal(p[:, [0, 2]], 0.0)
    np.testing.assert_array_equal(v[:, [0, 2]], 0.0)


def test_full_descent_rounds_the_duration_to_the_nearest_sample():
    """When T fs is not an integer, the grid runs to the sample nearest T; a sample after T is the hand at
    rest (s = A, speed 0), not the polynomial continued past tau = 1. Catches: tau not clipped at 1 (the
    position overshoots A and the sample is dropped, a speed is left)."""
    peak = 1.0
    T = MJ_PEAK_FACTOR * A_M / peak  # 0.375 s: 22.5 samples at 60 Hz
    fs = 22.6 / T  # the nearest sample (23) lies after T
    t, p, v = minimum_jerk_descent(A_M, peak, fs=fs, fraction=1.0)
    assert t.size == 24 and t[-1] > T
    assert p[-1, 1] == -A_M and v[-1, 1] == 0.0


def test_descent_cut_at_the_fraction():
    """Samples from t = 0 while the distance is at most fraction A. Catches: a wrong time grid or cut."""
    fraction = 0.7
    t, p, _ = minimum_jerk_descent(A_M, PEAK, fs=FS, fraction=fraction)
    grid = np.arange(round(T_S * FS) + 1) / FS
    keep = _mj_position(grid, A_M, T_S) <= fraction * A_M
    np.testing.assert_allclose(t, grid[keep], rtol=1e-12, atol=1e-15)
    assert _mj_position(grid[t.size], A_M, T_S) > fraction * A_M  # the next sample is past contact


def test_descent_defaults():
    """The default prototype is a 0.2 m descent peaking at 1 m/s, sampled at 60 Hz and cut at 70 %.
    Catches: a default changed silently."""
    t, p, v = minimum_jerk_descent()
    t2, p2, v2 = minimum_jerk_descent(0.2, 1.0, 60.0, 0.7)
    np.testing.assert_array_equal(t, t2)
    np.testing.assert_array_equal(p, p2)
    np.testing.assert_array_equal(v, v2)


#: Rounding tolerance (m) of the cut at contact: a sample up to fraction A + this is kept.
CUT_TOL_M = 1e-12


def test_descent_cut_is_inclusive():
    """A sample whose distance equals the cut (fraction A, plus its rounding tolerance) exactly is kept;
    one just beyond is not. Catches: the cut written as a strict inequality."""
    k = round(T_S * FS) // 2  # the middle sample of the full movement
    _, p_full, _ = minimum_jerk_descent(A_M, PEAK, fs=FS, fraction=1.0)
    s_k = -p_full[k, 1]
    fraction = (s_k - CUT_TOL_M) / A_M
    for _ in range(100):  # the float fraction whose cut lands exactly on s_k (a few ulps away at most)
        if fraction * A_M + CUT_TOL_M >= s_k:
            break
        fraction = np.nextafter(fraction, 1.0)
    while np.nextafter(fraction, 0.0) * A_M + CUT_TOL_M >= s_k:
        fraction = np.nextafter(fraction, 0.0)
    assert fraction * A_M + CUT_TOL_M == s_k  # the constructed edge
    t, _, _ = minimum_jerk_descent(A_M, PEAK, fs=FS, fraction=fraction)
    assert t.size == k + 1
    t, _, _ = minimum_jerk_descent(A_M, PEAK, fs=FS, fraction=np.nextafter(fraction, 0.0))
    assert t.size == k


GOOD = {"amplitude": A_M, "peak_speed": PEAK, "fs": FS, "fraction": 0.7}
DESCENT_MESSAGE = "amplitude (m), peak_speed (m/s), fs (Hz) must be positive and 0 < fraction <= 1"


@pytest.mark.parametrize(
    "name,bad",
    [
        ("amplitude", 0.0),
        ("amplitude", -0.1),
        ("peak_speed", 0.0),
        ("peak_speed", -1.0),
        ("fs", 0.0),
        ("fs", -60.0),
        ("fraction", 0.0),
        ("fraction", -0.5),
        ("fraction", 1.5),
    ],
)
def test_descent_rejects_each_bad_argument(name, bad):
    """Each argument alone out of its range is an error with the documented message. Catches: conditions
    joined with ``and`` (one bad argument slips through), strict/non-strict comparisons swapped, the bound
    of fraction moved, the message lost."""
    with pytest.raises(ValueError) as err:
        minimum_jerk_descent(**{**GOOD, name: bad})
    assert str(err.value) == DESCENT_MESSAGE


@pytest.mark.parametrize("fs", [1.0, 0.5])
def test_descent_accepts_a_low_sampling_rate(fs):
    """Any positive fs is valid, also 1 Hz and below (a coarse grid: t = 0, 1/fs, ...). Catches: fs <= 1
    rejected."""
    t, _, _ = minimum_jerk_descent(1.0, 0.1, fs=fs, fraction=1.0)  # T = 18.75 s
    np.testing.assert_allclose(np.diff(t), 1 / fs)


# --- IKAnswer.why -------------------------------------------------------------------------------


def test_ik_why_lists_the_joints_outside_their_limits():
    """The flag text of a rejected IK attempt: both residuals, then the 1-based joints outside their
    limits, comma-separated. Catches: the joint list replacing the residuals, missing or garbled."""
    dp, dr = 1.5e-3, 2.5e-4
    ans = IKAnswer(np.zeros(6), dp, False, "", dr, (2, 5))
    residuals = f"best position residual {dp:.3g} m, orientation {dr:.3g} rad"
    assert ans.why() == residuals + ", outside the joint limits at q2, q5"
    assert IKAnswer(np.zeros(6), dp, False, "", dr, (4,)).why() == residuals + ", outside the joint limits at q4"
    assert IKAnswer(np.zeros(6), dp, False, "", dr).why() == residuals


# --- pose_residual ------------------------------------------------------------------------------


def test_orientation_residual_of_a_half_turn_is_pi_not_nan():
    """A tool turned by pi about any axis has orientation residual pi. The cosine (trace - 1) / 2 is then -1,
    and rounding can put it just below -1 (arccos: NaN), so it must be clipped. Catches: the lower clip
    dropped or loosened (NaN, which a tolerance check silently treats as 'not within')."""
    ets, q0 = simple6().ets(), default_pose()
    T0 = ets.eval(q0)
    axes = np.random.default_rng(0).normal(size=(50, 3))
    below = 0
    for axis in axes / np.linalg.norm(axes, axis=1, keepdims=True):
        target = T0.copy()
        target[:3, :3] = T0[:3, :3] @ Rotation.from_rotvec(np.pi * axis).as_matrix()
        below += (np.trace(target[:3, :3].T @ T0[:3, :3]) - 1.0) / 2.0 < -1.0
        dp, dr = pose_residual(ets, q0, target)
        assert dp == 0.0
        assert dr == pytest.approx(np.pi, abs=1e-7)
    assert below  # precondition: rounding did put the cosine below -1 for some axis


# --- solve_ik: the answer it returns --------------------------------------------------------------

#: Iterations per search and the solvers' own tolerance (on E = 0.5 e'e) asked by solve_ik (see skilllib.robot).
IK_ITERATION_LIMIT = 50
IK_SOLVER_TOL = 1e-14
TOL = 1e-6  # accepted residual, m and rad
JOINT_TOL = 1e-9  # rad
_E6 = np.eye(6)[5]  # Simple6's q6 turns the tool about its own axis through the tool point


class _ScriptedETS:
    """Simple6's kinematics (qlim, eval) with scripted IK searches: the i-th search (ikine_LM or ikine_GN)
    returns ``answer(i)`` as a claimed success and is recorded as (method, keyword arguments)."""

    def __init__(self, answer):
        self._ets = simple6().ets()
        self.qlim = self._ets.qlim
        self.answer = answer
        self.calls: list[tuple[str, dict]] = []

    def eval(self, q):
        return self._ets.eval(q)

    def _search(self, solver, Tep, **kw):
        q = self.answer(len(self.calls))
        self.calls.append((solver, kw))
        return IKSolution(q=q, success=True, reason="scripted")

    def ikine_LM(self, Tep, **kw):
        return self._search("ikine_LM", Tep, **kw)

    def ikine_GN(self, Tep, **kw):
        return self._search("ikine_GN", Tep, **kw)


def _e23(d: float) -> np.ndarray:
    """q2 + d, q3 - d: same tool orientation, tool point 2 sin(d / 2) m away (1 m upper arm)."""
    return np.array([0.0, d, -d, 0.0, 0.0, 0.0])


def _d_for(dp: float) -> float:
    """The q2/q3 offset d that moves Simple6's tool point by dp (m)."""
    return 2 * np.arcsin(dp / 2)


def test_solve_ik_success_reports_solver_and_both_residuals():
    """An accepted pose is returned with ok True, the name of the search that found it, its position
    and orientation residuals and no joint outside the limits. Catches: the solver name or the orientation
    residual not passed on (None, NaN), the fields shifted by a missing argument."""
    ets, q0 = simple6().ets(), default_pose()
    target = ets.eval(q0 + _e23(0.01))
    ans = solve_ik(ets, target, q0, 3, tol=TOL, joint_tol=JOINT_TOL)
    dp, dr = pose_residual(ets, ans.q, target)
    assert ans.ok is True and ans.solver == IK_CHAIN[0][0] == "LM seeded"
    assert ans.residual_m == dp <= TOL
    assert isinstance(ans.orientation_rad, float) and ans.orientation_rad == dr <= TOL
    assert ans.outside == ()


def test_solve_ik_asks_each_search_for_a_joint_limit_aware_solution():
    """Every search gets the seed, the tight solver tolerance, 50 iterations, joint_limits=True and its
    restarts (restarts + 1 searches seeded with k, the seeded search once without a seed). Catches: the
    iteration limit or the joint-limit flag dropped or changed."""
    q0 = default_pose()
    off = q0 + _e23(_d_for(1e-3))  # 1 mm off: every search rejected, all four run
    ets = _ScriptedETS(lambda i: off)
    restarts, k = 3, 7
    target = ets.eval(q0)
    solve_ik(ets, target, q0, k, tol=TOL, joint_tol=JOINT_TOL, restarts=restarts)
    common = {"tol": IK_SOLVER_TOL, "ilimit": IK_ITERATION_LIMIT, "joint_limits": True}
    want = [
        ("ikine_LM", {**common, "slimit": 1, "seed": None}),
        ("ikine_LM", {**common, "slimit": restarts + 1, "seed": k}),
        ("ikine_GN", {**common, "slimit": restarts + 1, "seed": k, "pinv": True}),
        ("ikine_LM", {**common, "slimit": restarts + 1, "seed": k, "method": "sugihara"}),
    ]
    assert [(m, {key: v for key, v in kw.items() if key != "q0"}) for m, kw in ets.calls] == want
    for _, kw in ets.calls:
        np.testing.assert_array_equal(kw["q0"], q0)


@pytest.mark.parametrize("restarts,n_searches", [(0, 1), (1, len(IK_CHAIN))])
def test_solve_ik_restart_count(restarts, n_searches):
    """restarts = 0 runs the seeded search only; one restart already runs the whole chain. Catches: the
    restarting searches skipped at restarts = 1, or run at restarts = 0."""
    q0 = default_pose()
    ets = _ScriptedETS(lambda i: q0 + _e23(_d_for(1e-3)))
    ans = solve_ik(ets, ets.eval(q0), q0, 0, tol=TOL, joint_tol=JOINT_TOL, restarts=restarts)
    assert len(ets.calls) == n_searches and not ans.ok
    assert [kw["slimit"] for _, kw in ets.calls[1:]] == [restarts + 1] * (n_searches - 1)


def test_solve_ik_without_restarts_still_runs_later_seeded_searches(monkeypatch):
    """With restarts = 0 only the restarting searches are skipped, wherever they are in the chain: a seeded
    search listed after a restarting one still runs. Catches: the chain abandoned at the first restarting
    search."""
    chain = (("LM restarts", "ikine_LM", {}, True), ("GN seeded", "ikine_GN", {}, False))
    monkeypatch.setattr(ik, "IK_CHAIN", chain)
    q0 = default_pose()
    ets = _ScriptedETS(lambda i: q0)
    ans = solve_ik(ets, ets.eval(q0), q0, 0, tol=TOL, joint_tol=JOINT_TOL, restarts=0)
    assert [m for m, _ in ets.calls] == ["ikine_GN"]
    assert ans.ok and ans.solver == "GN seeded"


def test_solve_ik_failure_returns_the_best_attempt():
    """Nothing accepted: the attempt with the smallest position residual is returned (ok False, no solver
    name) with its orientation residual and its joints outside the limits, 1-based; a non-finite attempt
    is skipped. Catches: the best attempt's q, flag, name, orientation or joint list lost, joints
    numbered from 0 or 2."""
    q0 = default_pose()
    wrapped = np.array([2 * np.pi, 0, 0, 0, 0, -2 * np.pi])  # q1 and q6 one turn out: beyond +-pi
    attempts = [
        q0 + _e23(_d_for(3e-3)),
        q0 + _e23(_d_for(1e-3)) + wrapped + 2e-3 * _E6,
        np.full(6, np.nan),
        q0 + _e23(_d_for(2e-3)),
    ]
    ets = _ScriptedETS(lambda i: attempts[i])
    target = ets.eval(q0)
    ans = solve_ik(ets, target, q0, 0, tol=TOL, joint_tol=JOINT_TOL)
    assert len(ets.calls) == len(IK_CHAIN)
    dp, dr = pose_residual(ets, attempts[1], target)
    assert dp == pytest.approx(1e-3, rel=1e-9) and dr == pytest.approx(2e-3, rel=1e-6)
    assert ans.ok is False and ans.solver == ""
    np.testing.assert_array_equal(ans.q, attempts[1])
    assert ans.residual_m == dp and ans.orientation_rad == dr
    assert ans.outside == (1, 6)


def test_solve_ik_failure_keeps_the_first_of_equal_attempts():
    """Two rejected attempts with exactly the same position residual: the earlier one (the seeded search,
    on the arm's branch) is reported. Catches: a later attempt replacing it on a tie."""
    q0 = default_pose()
    first = q0 + _e23(_d_for(1e-3))
    later = first + 2 * np.pi * _E6  # q6 one turn on: the same tool point, outside the limits
    ets = _ScriptedETS(lambda i: first if i == 0 else later)
    target = ets.eval(q0)
    assert pose_residual(ets, later, target)[0] == pose_residual(ets, first, target)[0]  # an exact tie
    ans = solve_ik(ets, target, q0, 0, tol=TOL, joint_tol=JOINT_TOL)
    np.testing.assert_array_equal(ans.q, first)
    assert ans.outside == ()


def test_solve_ik_with_no_finite_attempt_returns_the_seed():
    """Every search returns NaN: the answer is the seed itself (in float rad), residual inf, not ok, no
    solver, no joint listed. Catches: a wrong initial best answer (q missing or left as integers, ok or the
    solver name not False / "")."""
    seed = [0, -1, 2, 1, -1, 0]  # integer rad
    ets = _ScriptedETS(lambda i: np.full(6, np.nan))
    ans = solve_ik(ets, ets.eval(np.asarray(seed, dtype=float)), seed, 0, tol=TOL, joint_tol=JOINT_TOL)
    assert ans.q.dtype == np.float64
    np.testing.assert_array_equal(ans.q, seed)
    assert ans.residual_m == np.inf and ans.ok is False and ans.solver == ""
    assert np.isnan(ans.orientation_rad) and ans.outside == ()


def test_solve_ik_returns_float64_joint_angles():
    """A solver answering in single precision still gives a float64 q. Catches: the solver's q kept as is."""
    q0 = default_pose()
    q32 = q0.astype(np.float32)
    ets = _ScriptedETS(lambda i: q32)
    ans = solve_ik(ets, ets.eval(q32.astype(np.float64)), q0, 0, tol=TOL, joint_tol=JOINT_TOL)
    assert ans.ok and ans.q.dtype == np.float64
    np.testing.assert_array_equal(ans.q, q32.astype(np.float64))


@pytest.mark.parametrize("joint,side", [(1, 0), (2, 1)])
def test_solve_ik_joint_limit_edge(joint, side):
    """A joint exactly joint_tol beyond its limit is still inside (accepted); the next float beyond is
    outside (rejected and listed). Catches: the limit checks made strict at the edge."""
    q0 = default_pose()
    qlim = simple6().ets().qlim
    outward = -1.0 if side == 0 else 1.0
    edge = q0.copy()
    edge[joint] = qlim[side, joint] + outward * JOINT_TOL
    beyond = edge.copy()
    beyond[joint] = np.nextafter(edge[joint], outward * np.inf)
    for q, ok in ((edge, True), (beyond, False)):
        ets = _ScriptedETS(lambda i, q=q: q)
        ans = solve_ik(ets, ets.eval(q), q0, 0, tol=TOL, joint_tol=JOINT_TOL)
        assert ans.ok is ok
        assert ans.outside == (() if ok else (joint + 1,))


# --- transfer: start pose and limits of a named arm --------------------------------------------------


def test_named_arm_takes_a_given_start_pose():
    """A q0 given with an arm's name replaces the arm's default start pose. Catches: the given q0
    ignored."""
    q0 = default_pose() + _e23(0.1)
    r = transfer("simple6", [0.0], np.zeros((1, 3)), np.zeros((1, 3)), q0=q0)
    np.testing.assert_array_equal(r.q0, q0)
    np.testing.assert_allclose(r.q[0], q0, atol=1e-12)
    np.testing.assert_allclose(r.x_base[0], simple6().ets().eval(q0)[:3, 3], rtol=1e-15)


REQUIRED_MESSAGE = "q0 (rad) and qd_limits (rad/s) are required when robot is not given by name"


@pytest.mark.parametrize("given", [{"q0": "pose"}, {"qd_limits": np.pi}])
def test_arm_object_needs_both_start_pose_and_limits(given):
    """An arm given as an object needs q0 and qd_limits; either missing alone is an error with the
    documented message. Catches: only both missing rejected, the message changed."""
    kw = {k: (default_pose() if v == "pose" else v) for k, v in given.items()}
    with pytest.raises(ValueError) as err:
        transfer(simple6(), [0.0], np.zeros((1, 3)), np.zeros((1, 3)), **kw)
    assert str(err.value) == REQUIRED_MESSAGE


def test_transfer_inputs_are_float_seconds_and_radians():
    """Integer times and an integer start pose are taken as float s and rad. Catches: t or q0 kept as
    integer arrays in the result."""
    q0 = [0, -1, 2, 1, -1, 0]  # rad, inside Simple6's limits
    r = transfer(simple6(), [0, 1], np.zeros((2, 3)), np.zeros((2, 3)), q0=q0, qd_limits=np.pi)
    assert r.t.dtype == np.float64 and r.q0.dtype == np.float64
    np.testing.assert_array_equal(r.t, [0.0, 1.0])
    np.testing.assert_array_equal(r.q0, q0)


def test_transfer_uses_the_given_rotation():
    """A rotation other than EXP_TO_BASE maps the experiment frame: with the identity the base-frame
    velocity is the experiment one and the path is placed unrotated. Catches: the rotation argument not
    passed on."""
    v = np.array([[0.0, -0.5, 0.0], [0.0, -0.5, 0.0]])
    p = np.array([[0.0, 0.0, 0.0], [0.0, -0.01, 0.0]])
    r = transfer("simple6", [0.0, 1 / FS], p, v, rotation=np.eye(3))
    np.testing.assert_array_equal(r.v_base, v)
    start = simple6().ets().eval(default_pose())[:3, 3]
    np.testing.assert_allclose(r.x_base, start + p, rtol=1e-15)


@pytest.mark.parametrize("joint,side", [(1, 0), (2, 1)])
def test_start_pose_joint_limit_edge(joint, side):
    """q0 exactly JOINT_LIMIT_TOL_RAD beyond a limit is accepted; the next float beyond is an error naming
    the joint. Catches: the q0 limit checks made strict at the edge."""
    qlim = simple6().ets().qlim
    outward = -1.0 if side == 0 else 1.0
    q0 = default_pose()
    q0[joint] = qlim[side, joint] + outward * JOINT_LIMIT_TOL_RAD
    r = transfer(simple6(), [0.0], np.zeros((1, 3)), np.zeros((1, 3)), q0=q0, qd_limits=np.pi)
    np.testing.assert_array_equal(r.q0, q0)
    q0[joint] = np.nextafter(q0[joint], outward * np.inf)
    with pytest.raises(ValueError, match=rf"at joint\(s\) q{joint + 1}$"):
        transfer(simple6(), [0.0], np.zeros((1, 3)), np.zeros((1, 3)), q0=q0, qd_limits=np.pi)


def test_start_pose_outside_at_several_joints_names_them_all():
    """The error lists every joint of q0 outside its limits, comma-separated. Catches: a garbled list."""
    q0 = default_pose()
    q0[[1, 4]] = [-4.0, 4.0]  # beyond -pi and pi
    with pytest.raises(ValueError, match=r"outside the joint limits of Simple6 at joint\(s\) q2, q5$"):
        transfer(simple6(), [0.0], np.zeros((1, 3)), np.zeros((1, 3)), q0=q0, qd_limits=np.pi)


def _failing_at(monkeypatch, fail: set[int]) -> None:
    """Make the transfer's IK fail (best residual 1 mm) at the samples in ``fail``; the real solve_ik elsewhere."""
    real = tr.solve_ik

    def fake(ets, target, seed_q, k, **kw):
        if k in fail:
            return IKAnswer(np.asarray(seed_q, dtype=float), 1e-3, False, "", 0.0)
        return real(ets, target, seed_q, k, **kw)

    monkeypatch.setattr(tr, "solve_ik", fake)


def test_ik_failure_at_the_first_sample_says_nothing_was_solved(monkeypatch):
    """An IK failure before any sample was solved has no cond J to report. Catches: a cond J of a sample
    that was never solved (index -1) in the flag, a changed text."""
    _failing_at(monkeypatch, {0})
    r = transfer("simple6", *minimum_jerk_descent(0.05, 0.5)[:3])
    reason = r.flags[0]["reason"]
    assert r.flags[0]["sample"] == 0 and reason.startswith("ik_failed")
    assert reason.endswith("; no sample solved before") and "cond J" not in reason
    where = reach_shell(simple6()).describe(r.x_base[0])  # the failed target's distance from the shoulder
    assert f"although the target lies {where}; " in reason


def test_ik_failure_after_the_first_sample_names_its_cond(monkeypatch):
    """A failure right after sample 0 was solved reports cond J at sample 0. Catches: sample 0 not counted
    as solved (k_prev > 0)."""
    _failing_at(monkeypatch, {1})
    r = transfer("simple6", *minimum_jerk_descent(0.05, 0.5)[:3])
    ets = simple6().ets()
    s = np.linalg.svd(ets.jacob0(r.q[0]), compute_uv=False)
    reason = [f["reason"] for f in r.flags if f["sample"] == 1][0]
    assert reason.endswith(f"; cond J = {s[0] / s[-1]:.3g} at the last solved sample 0")


def test_a_step_of_exactly_the_branch_threshold_is_not_a_jump(monkeypatch):
    """A joint step equal to BRANCH_JUMP_RAD is still the same branch (only a larger one is flagged).
    Catches: the comparison made non-strict."""
    q0 = default_pose()
    assert q0[0] == 0.0  # so q1 moves by exactly BRANCH_JUMP_RAD
    q1 = q0 + BRANCH_JUMP_RAD * np.eye(6)[0]
    monkeypatch.setattr(
        tr, "solve_ik", lambda ets, target, seed_q, k, **kw: IKAnswer(q0 if k == 0 else q1, 0.0, True, "scripted", 0.0)
    )
    r = transfer("simple6", [0.0, 1 / FS], np.zeros((2, 3)), np.zeros((2, 3)))
    assert np.max(np.abs(r.q[1] - r.q[0])) == BRANCH_JUMP_RAD
    assert r.flags == []


def test_samples_after_a_singular_one_are_computed():
    """A singular Jacobian is flagged at its sample and the transfer goes on: the next sample (off the
    singularity) is computed by J^-1 v. Catches: the loop stopped at the singular sample."""
    q_sing = default_pose()
    q_sing[2] = 1e-13  # the arm stretched out: cond J about 6.6 / q3, far above SINGULAR_COND
    ets = simple6().ets()
    q_next = q_sing + _e23(-0.1)  # elbow bent by 0.1 rad, same tool orientation: cond J about 66
    x = np.array([ets.eval(q)[:3, 3] for q in (q_sing, q_next)])
    p = (x - x[0]) @ tr.EXP_TO_BASE  # experiment-frame positions of these tool points
    v = np.array([[0.0, -0.5, 0.0]] * 2)
    r = transfer(simple6(), [0.0, 1 / FS], p, v, q0=q_sing, qd_limits=np.pi)
    assert [(f["sample"], f["reason"].split(":")[0]) for f in r.flags] == [(0, "singular")]
    assert np.all(np.isfinite(r.qd[1]))
    J = ets.jacob0(r.q[1])
    np.testing.assert_allclose(J @ r.qd[1], np.r_[tr.EXP_TO_BASE @ v[1], 0, 0, 0], atol=1e-9)


# --- time_scale_factor and to_base_frame edges ---------------------------------------------------------


def test_time_scale_factor_edges_match_within_limits():
    """s = 1 (no stretch) whenever the peak is within the limit's relative tolerance, also exactly at
    limit (1 + QD_LIMIT_RTOL) and just below the limit; never a factor below 1. Catches: the tolerance
    edge made inclusive, or its sign flipped (a 'stretch' of 0.9999999995)."""
    lim = 1.0
    at_edge = lim * (1.0 + QD_LIMIT_RTOL)
    assert at_edge / lim == 1.0 + QD_LIMIT_RTOL  # exactly the edge in float
    assert time_scale_factor([at_edge, 0.5], lim) == 1.0
    assert time_scale_factor([lim * (1 - QD_LIMIT_RTOL / 2), 0.5], lim) == 1.0
    above = np.nextafter(at_edge, 2.0)
    assert time_scale_factor([above, 0.5], lim) == above


BASE_MESSAGE = "rotation must be a proper 3x3 rotation matrix (R R' = I, det R = +1)"


@pytest.mark.parametrize("rotation", [2.0 * np.eye(3), np.eye(4), np.eye(2)])
def test_to_base_frame_rejects_a_non_rotation(rotation):
    """A scaled 3x3 matrix (R R' != I) or a matrix of another size is rejected with the documented message.
    Catches: the shape and orthogonality checks joined with ``and``."""
    with pytest.raises(ValueError) as err:
        to_base_frame(np.zeros((2, 3)), np.zeros((2, 3)), np.zeros(3), rotation)
    assert str(err.value) == BASE_MESSAGE


def test_to_base_frame_orthogonality_tolerance():
    """R R' = I is checked to 1e-9 absolute: a matrix 5e-9 off orthogonal is rejected, one 1e-10 off is
    accepted. Catches: a looser tolerance (numpy's default 1e-8, or about 1)."""
    shear = np.zeros((3, 3))
    shear[0, 1] = 1.0
    for e, ok in ((1e-10, True), (5e-9, False)):
        R = np.eye(3) + e * shear  # R R' has e off the diagonal
        if ok:
            p, v = to_base_frame(np.ones((2, 3)), np.ones((2, 3)), np.zeros(3), R)
            np.testing.assert_allclose(v, np.ones((2, 3)) @ R.T)
        else:
            with pytest.raises(ValueError, match="proper 3x3 rotation"):
                to_base_frame(np.ones((2, 3)), np.ones((2, 3)), np.zeros(3), R)


def test_to_base_frame_accepts_a_rotation_with_det_rounded_below_one():
    """A proper rotation whose determinant rounds to just below 1 is accepted and applied:
    p_base = start + R (p - p[0]), v_base = R v, also when the path does not start at the origin.
    Catches: det R required to be >= 1 exactly, p[0] added instead of subtracted."""
    R = Rotation.from_rotvec(np.random.default_rng(0).normal(size=3)).as_matrix()
    assert np.linalg.det(R) < 1.0  # precondition: rounding put it below 1
    p = np.array([[0.3, -0.2, 0.1], [0.35, -0.1, 0.0], [0.2, 0.0, 0.4]])
    v = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    start = np.array([0.5, -0.25, 1.0])
    x_base, v_base = to_base_frame(p, v, start, R)
    for k in range(3):
        np.testing.assert_allclose(x_base[k], start + R @ (p[k] - p[0]), rtol=1e-14, atol=1e-15)
        np.testing.assert_allclose(v_base[k], R @ v[k], rtol=1e-14, atol=1e-15)


# --- transfer: input checks --------------------------------------------------------------------------------


@pytest.mark.parametrize("t,shape", [(np.zeros((2, 1)), "(2, 1)"), (np.zeros(0), "(0,)")])
def test_times_must_be_a_non_empty_vector(t, shape):
    """t of more than one dimension, or empty, is rejected with a message naming its shape. Catches: only
    a t that is both 2-D and empty rejected, the message lost."""
    n = max(len(t), 1) if t.ndim == 1 else t.shape[0]
    with pytest.raises(ValueError) as err:
        transfer("simple6", t, np.zeros((n, 3)), np.zeros((n, 3)))
    assert str(err.value) == f"t must be a non-empty 1-D array of times (s), got shape {shape}"


def test_non_finite_input_message():
    """A NaN or inf anywhere is rejected with the documented message. Catches: the message changed."""
    v = np.zeros((2, 3))
    v[1, 2] = np.inf
    with pytest.raises(ValueError) as err:
        transfer("simple6", [0.0, 1 / FS], np.zeros((2, 3)), v)
    assert str(err.value) == "t, positions and velocities must be finite (no NaN or inf)"


def test_two_samples_at_the_same_time_are_rejected():
    """Already two samples must have increasing times. Catches: the check skipped for two samples."""
    with pytest.raises(ValueError) as err:
        transfer("simple6", [0.0, 0.0], np.zeros((2, 3)), np.zeros((2, 3)))
    assert str(err.value) == "t must be strictly increasing"


# --- transfer_summary ----------------------------------------------------------------------------------------


def _result(robot: str = "Simple6", q0=None) -> TransferResult:
    """A one-sample result (nothing computed) of ``robot`` from start pose q0 (rad), for the summary block."""
    q0 = default_pose() if q0 is None else np.asarray(q0, dtype=float)
    nan6 = np.full((1, 6), np.nan)
    return TransferResult(
        robot=robot,
        q0=q0,
        qd_limits=np.full(6, np.pi),
        t=np.zeros(1),
        x_base=np.zeros((1, 3)),
        q=nan6,
        qd=nan6,
        det_j=np.full(1, np.nan),
        cond_j=np.full(1, np.nan),
        ik_residual_m=np.full(1, np.nan),
    )


def test_transfer_summary_needs_results_of_one_arm_and_pose():
    """No result, another arm with the same q0, or the same arm from another q0 are errors with the
    documented messages. Catches: only results differing in both arm and q0 rejected, messages changed."""
    with pytest.raises(ValueError) as err:
        transfer_summary([])
    assert str(err.value) == "transfer_summary needs at least one TransferResult"
    same = "all results must come from the same robot and start pose q0"
    for other in (_result(robot="UR5"), _result(q0=default_pose() + _e23(0.1))):
        with pytest.raises(ValueError) as err:
            transfer_summary([_result(), other])
        assert str(err.value) == same


def test_transfer_summary_start_pose_in_degrees_rounded_to_1e_9():
    """q0_deg is q0 in degrees rounded to 9 decimals, with no negative zero. Catches: rounding to whole
    degrees or to 10 decimals, -0.0 left in results.json."""
    deg = np.array([-1e-12, 30.5, 10.0000000004, -60.0, 12.3456789012, 0.0])
    block = transfer_summary([_result(q0=np.deg2rad(deg))])
    want = [round(float(d), 9) for d in np.rad2deg(np.deg2rad(deg))]
    assert block["q0_deg"] == want
    assert block["q0_deg"][0] == 0.0 and math.copysign(1.0, block["q0_deg"][0]) == 1.0  # not -0.0
    assert block["q0_deg"][1] == 30.5 and block["q0_deg"][2] == 10.0 and block["q0_deg"][4] == 12.345678901
