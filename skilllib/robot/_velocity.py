"""Kinematic transfer of a hand trajectory to a robot arm: IK, Jacobian, joint velocities.

The paper (Sec. 4) turns each prototype's end-effector velocity into joint velocities with

    qd = J(q)^-1 v,    v = (vx, vy, vz, wx, wy, wz)  (paper eq. 2; Corke 2017, sec. 8.2)

after 1) inverse kinematics for q, 2) the manipulator Jacobian in the world frame, 3) a
singularity check. :func:`transfer` does exactly that for every sample of a trajectory, on any
roboticstoolbox arm:

* **Frames.** The experiment frame has x mediolateral, y up, z anteroposterior (m). The robot
  base frame has z up. :data:`EXP_TO_BASE` maps experiment to base coordinates,
  ``p_base = R @ p_exp``: robot x = experiment z (forward), robot y = experiment x,
  robot z = experiment y (up). It is a cyclic permutation, a proper rotation (det +1).
* **Placement.** The movement's start is put at the tool point of the start pose ``q0``;
  the tool orientation is held at that of ``q0`` (v has no angular part: w = 0).
* **IK.** A target outside the arm's reach shell (:mod:`skilllib.robot`: the distances from
  the shoulder the tool point can take) is *unreachable* and not searched. Inside it,
  :func:`skilllib.robot.solve_ik` runs Levenberg-Marquardt seeded with the previous sample's solution,
  then restarts and other roboticstoolbox solvers, until the position residual ``|p(q) - p*|`` is within
  :data:`IK_RESIDUAL_TOL_M` (and the orientation residual within the same number in rad) inside the
  joint limits; if none succeeds it is an *IK failure*, reported with cond J at the last solved sample.
* **Jacobian and singularity.** ``ETS.jacob0`` (world frame). For a square J: det J and the
  2-norm condition number; for a redundant arm (n > 6) ``det_j`` is Yoshikawa's manipulability
  sqrt(det(J J')) (equal to ``|det J|`` when J is square; Corke 2017, sec. 8.2.2) and qd is the
  minimum-norm solution J^+ v (pseudo-inverse; Corke 2017, sec. 8.4.2).

Problems are flagged per sample ({sample, reason}) and never hidden: an unreachable target or an
IK failure leaves NaN in q, qd, det_j and cond_j of that sample, with a flag; a solution on another IK
branch, a Jacobian with ``cond_j`` above
:data:`COND_THRESHOLD` or a numerically singular one are flagged and still computed. The other
samples are computed as usual.

Feasibility and time scaling: a uniform time stretch t -> s t keeps the path and divides every
velocity by s, so the smallest stretch that brings every joint within its limit is
s = max(1, max_j peak|qd_j| / limit_j) (:func:`time_scale_factor`, :func:`apply_time_scale`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import roboticstoolbox as rtb

from ..prototypes import json_value
from ..smoothness import DEFAULT_FC, sparc
from ._arms import Arm, get_robot, qd_limits_vector
from ._ik import IK_RESTARTS, solve_ik
from ._reach import reach_shell

#: Experiment -> robot base rotation, ``p_base = EXP_TO_BASE @ p_exp`` (det +1):
#: base x = exp z (anteroposterior, forward), base y = exp x (mediolateral), base z = exp y (up).
EXP_TO_BASE: np.ndarray = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])

#: Largest accepted IK position residual, m (and orientation residual, rad).
IK_RESIDUAL_TOL_M: float = 1e-6

#: Condition number of J above which a sample is flagged ill-conditioned. J mixes m/rad (linear
#: rows) and 1 (angular rows), so cond depends on the length unit; with metres the start poses
#: of the book's arms have cond 3 to 9, and 100 means a velocity error is amplified 100 times
#: more in one direction than in another: close to a singularity.
COND_THRESHOLD: float = 100.0

#: Condition number above which J is treated as numerically singular (qd by least squares).
SINGULAR_COND: float = 1e12

#: Largest joint step between consecutive samples (rad) still taken as the same IK branch.
BRANCH_JUMP_RAD: float = 0.5

#: Tolerance (rad) of the joint-limit checks of q0 and of every IK solution.
JOINT_LIMIT_TOL_RAD: float = 1e-9

#: Relative tolerance of the velocity-limit check: a peak up to limit * (1 + this) is within the limit.
QD_LIMIT_RTOL: float = 1e-9


@dataclass
class TransferResult:
    """Joint-space transfer of one trajectory; arrays per sample (N samples, n joints).

    t (s), x_base (N, 3) target tool positions in the base frame (m), q (N, n) rad, qd (N, n)
    rad/s, det_j (det J, or manipulability for n != 6), cond_j, ik_residual_m (m), flags
    (list of ``{"sample": int, "reason": str}``; ``reason`` starts with ``unreachable`` (outside the
    reach shell), ``ik_failed`` (inside it, no solver succeeded), ``ik_branch_jump``, ``ill_conditioned``
    or ``singular``), qd_limits (n,) rad/s, v_base (N, 3) the commanded tool velocities in the base
    frame (m/s).

    Attributes
    ----------
    robot : str
        The arm's name (text).
    q0 : numpy.ndarray, shape (n,)
        The start pose (rad).
    qd_limits : numpy.ndarray, shape (n,)
        The joint velocity limits (rad/s).
    t : numpy.ndarray, shape (N,)
        The time stamps (s).
    x_base : numpy.ndarray, shape (N, 3)
        The target tool positions in the base frame (m).
    q : numpy.ndarray, shape (N, n)
        The joint angles (rad); NaN at unreachable and IK-failed samples.
    qd : numpy.ndarray, shape (N, n)
        The joint velocities (rad/s); NaN where ``q`` is.
    det_j : numpy.ndarray, shape (N,)
        det J, or Yoshikawa's manipulability sqrt(det(J J')) for n != 6 (m^3: J's three linear rows are
        in m per rad, its three angular rows dimensionless).
    cond_j : numpy.ndarray, shape (N,)
        The 2-norm condition number of J (dimensionless, for lengths in m).
    ik_residual_m : numpy.ndarray, shape (N,)
        The IK position residual ``|p(q) - p*|`` (m).
    flags : list of dict
        One ``{"sample": int, "reason": str}`` per problem (samples, text).
    cluster : int or None
        The prototype's cluster label (dimensionless), None for a trajectory not from a cluster.
    v_base : numpy.ndarray, shape (N, 3), or None
        The commanded tool velocities in the base frame (m/s).
    peak_abs_qd : numpy.ndarray, shape (n,)
        Peak ``|qd_j|`` per joint over the computed samples (rad/s).
    min_abs_det_j, max_cond_j : float
        The smallest ``|det J|`` and the largest cond J over the computed samples (as ``det_j``,
        ``cond_j``; dimensionless for cond J).
    ik_max_residual_m : float
        The largest IK position residual (m).
    time_scale : float
        The smallest uniform time stretch s >= 1 bringing every joint within its limit (dimensionless).
    within_limits, feasible : bool
        Every joint within its velocity limit; that and nothing flagged (dimensionless).
    """

    robot: str
    q0: np.ndarray
    qd_limits: np.ndarray
    t: np.ndarray
    x_base: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    det_j: np.ndarray
    cond_j: np.ndarray
    ik_residual_m: np.ndarray
    flags: list[dict[str, Any]] = field(default_factory=list)
    cluster: int | None = None
    v_base: np.ndarray | None = None

    @property
    def peak_abs_qd(self) -> np.ndarray:
        """Peak ``|qd_j|`` per joint over the computed samples, rad/s (NaN if none was computed)."""
        ok = np.all(np.isfinite(self.qd), axis=1)
        if not ok.any():
            return np.full(self.qd.shape[1], np.nan)
        return np.max(np.abs(self.qd[ok]), axis=0)

    @property
    def min_abs_det_j(self) -> float:
        """Smallest ``|det J|`` (manipulability for n != 6) over the computed samples."""
        return _nan_reduce(np.min, np.abs(self.det_j))

    @property
    def max_cond_j(self) -> float:
        """Largest condition number of J over the computed samples."""
        return _nan_reduce(np.max, self.cond_j)

    @property
    def ik_max_residual_m(self) -> float:
        """Largest IK position residual, m (failed samples included where a best attempt had a finite residual)."""
        return _nan_reduce(np.max, self.ik_residual_m)

    @property
    def time_scale(self) -> float:
        """Smallest uniform time stretch s >= 1 bringing every joint within its limit."""
        return time_scale_factor(self.peak_abs_qd, self.qd_limits)

    @property
    def within_limits(self) -> bool:
        """True when every computed joint velocity is within its limit (relative tolerance QD_LIMIT_RTOL)."""
        peak = self.peak_abs_qd
        return bool(np.all(np.isfinite(peak)) and np.all(peak <= self.qd_limits * (1 + QD_LIMIT_RTOL)))

    @property
    def feasible(self) -> bool:
        """True when nothing was flagged and every joint is within its velocity limit."""
        return not self.flags and self.within_limits

    def summary(self) -> dict[str, Any]:
        """The per-prototype entry of results.json (plain floats/lists; None for undefined)."""
        return {
            "cluster": None if self.cluster is None else int(self.cluster),
            "peak_abs_qd": json_value(self.peak_abs_qd),
            "min_abs_det_j": json_value(self.min_abs_det_j),
            "max_cond_j": json_value(self.max_cond_j),
            "ik_max_residual_m": json_value(self.ik_max_residual_m),
            "feasible": bool(self.feasible),
            "time_scale": json_value(self.time_scale),
            "flags": [{"sample": int(f["sample"]), "reason": str(f["reason"])} for f in self.flags],
        }


def _nan_reduce(fn: Any, x: np.ndarray) -> float:
    x = np.asarray(x, dtype=float)
    x = x[np.isfinite(x)]
    return float(fn(x)) if x.size else float("nan")


def time_scale_factor(peak_abs_qd: np.ndarray, qd_limits: float | np.ndarray) -> float:
    """Smallest uniform time-scaling factor s >= 1 that brings every joint within its limit.

    A uniform stretch t -> s t of the same path divides every joint velocity by s, so
    s = max(1, max_j peak|qd_j| / limit_j). ``peak_abs_qd`` rad/s (n,), ``qd_limits`` rad/s
    (scalar or (n,)). NaN peaks (joints never computed) are ignored; all NaN gives NaN.

    Parameters
    ----------
    peak_abs_qd : numpy.ndarray, shape (n,)
        Peak absolute joint velocity per joint (rad/s); NaN for a joint never computed.
    qd_limits : float or numpy.ndarray, shape (n,)
        Joint velocity limits, one for every joint or one per joint (rad/s).

    Returns
    -------
    float
        The time-scaling factor s >= 1 (dimensionless); NaN when every peak is NaN.

    Raises
    ------
    ValueError
        When ``qd_limits`` has the wrong length or a limit is not positive and finite.
    """
    peak = np.asarray(peak_abs_qd, dtype=float)
    lim = qd_limits_vector(qd_limits, peak.size)
    ratio = peak / lim
    ratio = ratio[np.isfinite(ratio)]
    if not ratio.size:
        return float("nan")
    s = float(ratio.max())
    return s if s > 1.0 + QD_LIMIT_RTOL else 1.0  # within the tolerance of within_limits: no stretch


def apply_time_scale(t: np.ndarray, velocity: np.ndarray, s: float) -> tuple[np.ndarray, np.ndarray]:
    """Stretch a trajectory uniformly in time by ``s`` (> 0): t -> t0 + s (t - t0), v -> v / s.

    ``t`` in s, ``velocity`` a speed profile (N,) or velocities (N, 3) in m/s (or joint velocities,
    rad/s). The start time t0 and the positions are unchanged; the sampling interval becomes s dt.
    Peak speed (PV) is divided by s. SPARC is unchanged when its frequency band is ended by the
    amplitude threshold: the spectrum is only rescaled in frequency (by 1/s) and amplitude, both
    normalised away by SPARC. With a fixed cut-off fc (Hz) and a profile truncated at contact (spectrum
    still above the threshold at fc), SPARC changes unless fc is scaled by 1/s too.

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s).
    velocity : numpy.ndarray, shape (N,) or (N, 3)
        A speed profile or velocities (m/s), or joint velocities (rad/s).
    s : float
        The time stretch, positive (dimensionless).

    Returns
    -------
    t_scaled : numpy.ndarray, shape (N,)
        The stretched time stamps t0 + s (t - t0) (s).
    velocity_scaled : numpy.ndarray
        ``velocity / s``, same shape and unit as ``velocity`` (m/s or rad/s).

    Raises
    ------
    ValueError
        When ``s`` is not positive and finite, or ``velocity`` and ``t`` differ in their number of samples.
    """
    t = np.asarray(t, dtype=float)
    v = np.asarray(velocity, dtype=float)
    if not np.isfinite(s) or s <= 0:
        raise ValueError(f"time scale s must be positive and finite, got {s}")
    if v.shape[0] != t.shape[0]:
        raise ValueError(f"velocity has {v.shape[0]} samples but t has {t.shape[0]}")
    return t[0] + s * (t - t[0]), v / s


def time_scaled_features(speed: np.ndarray, fs: float, s: float, fc: float = DEFAULT_FC) -> dict[str, float]:
    """PV (m/s) and SPARC of a speed profile (m/s, sampled at ``fs`` Hz) slowed uniformly by ``s``.

    On the stretched samples themselves (``fs / s`` Hz apart, :func:`apply_time_scale`): ``pv`` and
    ``sparc_fc_scaled``, SPARC with the cut-off scaled to ``fc / s``, which equals the original's exactly
    (the same samples on a frequency axis compressed by s). As a recording of the slowed movement at the
    experiment's rate would give it, after linear resampling at ``fs`` (``n_resampled`` samples):
    ``pv_resampled``, ``sparc_resampled_fc_scaled`` (cut-off fc / s) and ``sparc_resampled_fixed_fc``
    (cut-off fc, the pipeline's measurement). A fixed fc on the stretched samples themselves is not
    offered: their Nyquist frequency fs / (2 s) falls below fc once s > fs / (2 fc).

    Parameters
    ----------
    speed : numpy.ndarray, shape (N,)
        The speed profile (m/s).
    fs : float
        Its sampling rate (Hz).
    s : float
        The time stretch, positive (dimensionless).
    fc : float
        The SPARC maximum cut-off frequency of the unstretched profile (Hz).

    Returns
    -------
    dict of str to float
        ``pv`` and ``pv_resampled`` (m/s), ``sparc_fc_scaled``, ``sparc_resampled_fc_scaled`` and
        ``sparc_resampled_fixed_fc`` (dimensionless), ``n_resampled`` (samples).

    Raises
    ------
    ValueError
        When ``s`` is not positive and finite, or SPARC rejects the profile or its parameters.
    """
    v = np.asarray(speed, dtype=float)
    t_s, v_s = apply_time_scale(np.arange(v.size) / fs, v, s)  # the stretched samples, s / fs apart
    t_r = np.arange(t_s[0], t_s[-1] + 1e-9, 1 / fs)
    v_r = np.interp(t_r, t_s, v_s)
    return {
        "pv": float(v_s.max()),
        "sparc_fc_scaled": sparc(v_s, fs / s, fc=fc / s),
        "n_resampled": int(v_r.size),
        "pv_resampled": float(v_r.max()),
        "sparc_resampled_fc_scaled": sparc(v_r, fs, fc=fc / s),
        "sparc_resampled_fixed_fc": sparc(v_r, fs, fc=fc),
    }


def to_base_frame(
    positions: np.ndarray, velocities: np.ndarray, start: np.ndarray, rotation: np.ndarray = EXP_TO_BASE
) -> tuple[np.ndarray, np.ndarray]:
    """Experiment-frame positions (N, 3) m and velocities (N, 3) m/s in the robot base frame.

    ``p_base = start + R (p - p[0])`` puts the movement's start at ``start`` (m, base frame);
    ``v_base = R v``.

    Parameters
    ----------
    positions : numpy.ndarray, shape (N, 3)
        Positions in the experiment frame (m).
    velocities : numpy.ndarray, shape (N, 3)
        Velocities in the experiment frame (m/s).
    start : numpy.ndarray, shape (3,)
        Where the movement's start goes, in the base frame (m).
    rotation : numpy.ndarray, shape (3, 3)
        The experiment -> base rotation R, a proper rotation (dimensionless); :data:`EXP_TO_BASE` by default.

    Returns
    -------
    positions_base : numpy.ndarray, shape (N, 3)
        The positions in the base frame (m).
    velocities_base : numpy.ndarray, shape (N, 3)
        The velocities in the base frame (m/s).

    Raises
    ------
    ValueError
        When ``rotation`` is not a proper 3x3 rotation matrix.
    """
    R = np.asarray(rotation, dtype=float)
    if R.shape != (3, 3) or not np.allclose(R @ R.T, np.eye(3), atol=1e-9) or np.linalg.det(R) < 0:
        raise ValueError("rotation must be a proper 3x3 rotation matrix (R R' = I, det R = +1)")
    p = np.asarray(positions, dtype=float)
    v = np.asarray(velocities, dtype=float)
    return np.asarray(start, dtype=float) + (p - p[0]) @ R.T, v @ R.T


def _check_inputs(t: np.ndarray, pos: np.ndarray, vel: np.ndarray) -> None:
    if t.ndim != 1 or t.size < 1:
        raise ValueError(f"t must be a non-empty 1-D array of times (s), got shape {t.shape}")
    if pos.shape != (t.size, 3) or vel.shape != (t.size, 3):
        raise ValueError(f"positions and velocities must have shape ({t.size}, 3), got {pos.shape} and {vel.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(pos)) and np.all(np.isfinite(vel))):
        raise ValueError("t, positions and velocities must be finite (no NaN or inf)")
    if t.size > 1 and np.any(np.diff(t) <= 0):
        raise ValueError("t must be strictly increasing")


def transfer(
    robot: Arm | rtb.Robot | str,
    t: Any,
    positions: np.ndarray | None = None,
    velocities: np.ndarray | None = None,
    q0: np.ndarray | None = None,
    qd_limits: float | np.ndarray | None = None,
    rotation: np.ndarray = EXP_TO_BASE,
    cond_threshold: float = COND_THRESHOLD,
    cluster: int | None = None,
) -> TransferResult:
    """Joint angles and velocities that make ``robot`` execute a hand trajectory (paper Sec. 4).

    ``transfer(arm, segment)``: ``arm`` an :class:`~skilllib.robot.Arm` (or a name for
    :func:`skilllib.robot.get_robot`; either supplies ``q0`` and ``qd_limits`` unless given), ``segment`` a
    :class:`~skilllib.features.Segment` (its ``time`` from the onset, ``pos`` and ``vel``). The same with
    arrays: ``transfer(robot, t, positions, velocities, q0=..., qd_limits=...)`` with a roboticstoolbox arm,
    ``t`` (N,) s, ``positions`` (N, 3) m and ``velocities`` (N, 3) m/s in the experiment frame
    (x mediolateral, y up, z anteroposterior).
    ``q0`` (n,) rad: the start pose, whose tool point receives the movement's start and whose
    tool orientation is kept; it must lie within the joint limits ``qlim``. ``qd_limits`` rad/s, scalar or
    (n,); required for an arm given as
    an object. Per sample: IK seeded with the previous solution (position residual <= 1e-6 m,
    checked), J = jacob0(q), det J / cond J, qd = J^-1 v with v = (R v_exp, 0, 0, 0)
    (``np.linalg.solve``; least-squares minimum-norm solution J^+ v when n != 6). Corke 2017,
    sec. 7.2.2 (numerical IK) and 8.2 (resolved-rate motion).

    Parameters
    ----------
    robot : Arm, roboticstoolbox.Robot or str
        The arm: an :class:`Arm`, a name for :func:`get_robot`, or a roboticstoolbox model with at
        least 6 joints.
    t : numpy.ndarray, shape (N,), or Segment
        The time stamps, strictly increasing (s); or a :class:`~skilllib.features.Segment` (its time
        from the onset in s, positions in m, velocities in m/s), then without ``positions`` and
        ``velocities``.
    positions : numpy.ndarray, shape (N, 3), optional
        Hand positions in the experiment frame (m).
    velocities : numpy.ndarray, shape (N, 3), optional
        Hand velocities in the experiment frame (m/s).
    q0 : numpy.ndarray, shape (n,), optional
        The start pose, within the joint limits (rad); the arm's by default.
    qd_limits : float or numpy.ndarray, shape (n,), optional
        Joint velocity limits (rad/s); the arm's by default.
    rotation : numpy.ndarray, shape (3, 3)
        The experiment -> base rotation (dimensionless); :data:`EXP_TO_BASE` by default.
    cond_threshold : float
        cond J above which a sample is flagged ``ill_conditioned`` (dimensionless).
    cluster : int, optional
        The prototype's cluster label, copied into the result (dimensionless).

    Returns
    -------
    TransferResult
        Per sample: q (rad), qd (rad/s), det J, cond J (dimensionless), IK residual (m) and the flags.

    Raises
    ------
    ValueError
        No trajectory, ``q0`` or ``qd_limits`` missing for an arm given as an object, an arm with fewer
        than 6 joints, ``q0`` of the wrong length or outside the joint limits, bad velocity limits, or
        time stamps, positions and velocities of wrong shapes, not finite or not strictly increasing.
    """
    if positions is None and velocities is None and hasattr(t, "pos") and hasattr(t, "vel"):
        t, positions, velocities = t.time, t.pos, t.vel  # a Segment
    if positions is None or velocities is None:
        raise ValueError("transfer needs a Segment, or time stamps with positions and velocities")
    if isinstance(robot, str):
        robot = get_robot(robot)
    if isinstance(robot, Arm):
        q0 = robot.q0 if q0 is None else q0
        qd_limits = robot.qd_limits if qd_limits is None else qd_limits
        robot = robot.robot
    if q0 is None or qd_limits is None:
        raise ValueError("q0 (rad) and qd_limits (rad/s) are required when robot is not given by name")
    ets = robot.ets()
    n = ets.n
    if n < 6:
        raise ValueError(f"{robot.name} has {n} joints; a fixed tool orientation plus a path needs at least 6")
    q0 = np.asarray(q0, dtype=float)
    if q0.shape != (n,):
        raise ValueError(f"q0 must have {n} joint angles (rad), got shape {q0.shape}")
    qlim = np.asarray(ets.qlim, dtype=float)
    outside = np.nonzero((q0 < qlim[0] - JOINT_LIMIT_TOL_RAD) | (q0 > qlim[1] + JOINT_LIMIT_TOL_RAD))[0]
    if outside.size:
        raise ValueError(
            f"q0 is outside the joint limits of {robot.name} at joint(s) {', '.join(f'q{j + 1}' for j in outside)}"
        )
    lim = qd_limits_vector(qd_limits, n)
    t = np.asarray(t, dtype=float)
    pos = np.asarray(positions, dtype=float)
    vel = np.asarray(velocities, dtype=float)
    _check_inputs(t, pos, vel)

    T0 = ets.eval(q0)
    x_base, v_base = to_base_frame(pos, vel, T0[:3, 3], rotation)
    N = t.size
    q = np.full((N, n), np.nan)
    qd = np.full((N, n), np.nan)
    det_j = np.full(N, np.nan)
    cond_j = np.full(N, np.nan)
    residual = np.full(N, np.nan)
    flags: list[dict[str, Any]] = []
    shell = reach_shell(robot)
    out_of_reach = shell.outside(x_base)
    q_prev, k_prev = q0, -1
    for k in range(N):
        if out_of_reach[k]:
            flags.append({"sample": k, "reason": f"unreachable: the target lies {shell.describe(x_base[k])}"})
            continue
        target = T0.copy()
        target[:3, 3] = x_base[k]
        ans = solve_ik(
            ets, target, q_prev, k, tol=IK_RESIDUAL_TOL_M, joint_tol=JOINT_LIMIT_TOL_RAD, restarts=IK_RESTARTS
        )
        qk, residual[k] = ans.q, ans.residual_m
        if not ans.ok:
            last = (
                f"cond J = {cond_j[k_prev]:.3g} at the last solved sample {k_prev}"
                if k_prev >= 0
                else "no sample solved before"
            )
            flags.append(
                {
                    "sample": k,
                    "reason": f"ik_failed: no solver found a pose within the joint limits "
                    f"({ans.why()}) although the target lies "
                    f"{shell.describe(x_base[k])}; {last}",
                }
            )
            continue
        step = float(np.max(np.abs(qk - q_prev)))
        if step > BRANCH_JUMP_RAD:
            flags.append({"sample": k, "reason": f"ik_branch_jump: joints move {step:.3g} rad in one sample"})
        q[k] = q_prev = qk
        k_prev = k
        J = ets.jacob0(qk)
        s = np.linalg.svd(J, compute_uv=False)
        cond_j[k] = s[0] / s[-1] if s[-1] > 0 else np.inf
        det_j[k] = np.linalg.det(J) if J.shape[0] == J.shape[1] else float(np.prod(s))
        v = np.concatenate([v_base[k], np.zeros(3)])
        if not np.isfinite(cond_j[k]) or cond_j[k] > SINGULAR_COND:
            flags.append({"sample": k, "reason": f"singular: cond J = {cond_j[k]:.3g}; least-squares qd"})
            qd[k] = np.linalg.lstsq(J, v, rcond=None)[0]
            continue
        if cond_j[k] > cond_threshold:
            flags.append({"sample": k, "reason": f"ill_conditioned: cond J = {cond_j[k]:.3g} > {cond_threshold:g}"})
        qd[k] = np.linalg.solve(J, v) if J.shape[0] == J.shape[1] else np.linalg.lstsq(J, v, rcond=None)[0]
    return TransferResult(
        robot=robot.name,
        q0=q0,
        qd_limits=lim,
        t=t,
        x_base=x_base,
        q=q,
        qd=qd,
        det_j=det_j,
        cond_j=cond_j,
        ik_residual_m=residual,
        flags=flags,
        cluster=cluster,
        v_base=v_base,
    )


def transfer_summary(results: list[TransferResult]) -> dict[str, Any]:
    """The ``transfer`` block of results.json for results on one arm from one start pose.

    Keys: ``robot``, ``q0_deg`` (deg, rounded to 1e-9), ``qd_limits`` (rad/s) and ``prototypes`` (one
    :meth:`TransferResult.summary` per result, in the given order).

    Parameters
    ----------
    results : list of TransferResult
        At least one result, all on the same arm from the same start pose (joint angles in rad).

    Returns
    -------
    dict
        The block: ``robot`` (text), ``q0_deg`` (deg), ``qd_limits`` (rad/s), ``prototypes``.

    Raises
    ------
    ValueError
        When ``results`` is empty or mixes arms or start poses.
    """
    if not results:
        raise ValueError("transfer_summary needs at least one TransferResult")
    first = results[0]
    for r in results[1:]:
        if r.robot != first.robot or not np.allclose(r.q0, first.q0):
            raise ValueError("all results must come from the same robot and start pose q0")
    return {
        "robot": first.robot,
        "q0_deg": [round(float(v), 9) + 0.0 for v in np.rad2deg(first.q0)],  # -60, not -59.99999999999999
        "qd_limits": [float(v) for v in first.qd_limits],
        "prototypes": [r.summary() for r in results],
    }
