"""Joint accelerations, jerks and torques of a transferred trajectory; every limit at once; time scaling.

The transfer (:mod:`skilllib.robot`) gives joint angles q and velocities qd = J^+ v per sample.
:func:`joint_dynamics` adds, per sample and joint:

* **Accelerations** qdd (rad/s^2) from the task-space acceleration a (the hand's, m/s^2) with the time
  derivative of the Jacobian (Haviland & Corke 2023, "Manipulator differential kinematics", part II):
  differentiating J qd = v gives J qdd = a - Jdot qd, and for the minimum-norm solution qd = J^+ v of a
  redundant arm the exact derivative is

      qdd = J^+ (a - Jdot qd) + (I - J^+ J) Jdot' (J J')^-1 v,

  which is J^-1 (a - Jdot qd) for a square J (the second term vanishes). Jdot is the Hessian contracted
  with qd (``ETS.hessian0``; roboticstoolbox's ``jacob0_dot`` computes the same, the tests compare). The
  hand's acceleration a is the derivative of its velocity with the same Savitzky-Golay derivative over
  2/60 s that gave the velocity from the positions (:func:`skilllib.features.velocity`; at 60 Hz the
  second-order central difference). The tests check qdd against that derivative of qd itself.
* **Jerks** qddd (rad/s^3): the same derivative of qdd (a stated numerical choice; no analytic Jddot).
* **Torques** tau (N m) by recursive Newton-Euler inverse dynamics, roboticstoolbox's ``rne(q, qd, qdd)``
  with gravity along the base's -z, on arms whose models carry dynamic parameters
  (:func:`skilllib.robot.has_dynamics`). As roboticstoolbox computes it, tau includes the motor armature
  inertia and joint friction (viscous and Coulomb) where the model has them (the Puma 560's does).

**Time scaling under every limit.** Stretching time uniformly by s keeps the path and divides qd by s and
qdd by s^2, so the velocity limits need ``s_v = max_j peak|qd_j| / qd_max_j`` and the acceleration limits
``s_a = sqrt(max_j peak|qdd_j| / qdd_max_j)``. Torque is not a power of s: tau(s) = M(q) qdd / s^2 +
C(q, qd) qd / s^2 + viscous qd / s + Coulomb + g(q). The smallest s >= max(1, s_v, s_a) at which every
``|tau_j|`` stays within its limit on every sample is found numerically: the largest feasible x = 1/s is
bracketed on a grid and refined with Brent's method (``scipy.optimize.brentq``) on the largest
normalised torque ``max |tau_j| / tau_max_j - 1``. When gravity and friction alone exceed a limit no slowing
helps (s = inf). The limit that sets s is the *binding* one.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import roboticstoolbox as rtb
from scipy.optimize import brentq

from ..features import velocity as sg_derivative
from ..prototypes import json_value
from ._arms import has_dynamics, limits_vector
from ._velocity import QD_LIMIT_RTOL, TransferResult

#: Grid points of x = 1/s on which the torque constraint is bracketed before Brent's method.
TORQUE_GRID: int = 129

#: Names of the limits, in the order they are reported.
LIMIT_NAMES: tuple[str, ...] = ("velocity", "acceleration", "torque")


def derivative(x: np.ndarray, t: np.ndarray) -> np.ndarray:
    """d/dt of samples x (N, ...) at times t (N,) s: the Savitzky-Golay derivative of
    :func:`skilllib.features.velocity` over its fixed 2/60 s span when t is uniform (to 1e-6 relative),
    else ``numpy.gradient`` with second-order edges. Rows with NaN (samples not computed) stay NaN, and each
    run of computed rows is differentiated on its own (a single computed row between gaps: NaN).

    Parameters
    ----------
    x : numpy.ndarray, shape (N, ...)
        The samples, in any unit u (m, m/s, rad, rad/s, rad/s^2, ...); NaN rows for samples not computed.
    t : numpy.ndarray, shape (N,)
        Their time stamps, increasing (s).

    Returns
    -------
    numpy.ndarray
        dx/dt, shape of ``x``, in u per s (e.g. m/s^2 from m/s, rad/s^3 from rad/s^2); NaN where ``x`` is
        NaN or a run has a single row.
    """
    x = np.asarray(x, dtype=float)
    t = np.asarray(t, dtype=float)
    out = np.full_like(x, np.nan)
    good = np.all(np.isfinite(x.reshape(len(x), -1)), axis=1)
    edges = np.flatnonzero(np.diff(np.r_[0, good.astype(int), 0]))
    for a, b in zip(edges[::2], edges[1::2]):  # runs good[a:b]
        if b - a >= 2:
            out[a:b] = _derivative_run(x[a:b], t[a:b])
    return out


def _derivative_run(x: np.ndarray, t: np.ndarray) -> np.ndarray:
    dt = np.diff(t)
    if np.ptp(dt) <= 1e-6 * dt.mean():
        return sg_derivative(x, 1.0 / dt.mean())
    return np.gradient(x, t, axis=0, edge_order=2 if len(t) > 2 else 1)


def jacobian_dot(ets: rtb.ETS, q: np.ndarray, qd: np.ndarray, J: np.ndarray | None = None) -> np.ndarray:
    """Time derivative of the world-frame Jacobian (6, n) at q (rad) moving at qd (rad/s): the Hessian
    ``ETS.hessian0`` contracted with qd (Haviland & Corke 2023, part II).

    Parameters
    ----------
    ets : roboticstoolbox.ETS
        The arm's elementary transform sequence.
    q : numpy.ndarray, shape (n,)
        The joint angles (rad).
    qd : numpy.ndarray, shape (n,)
        The joint velocities (rad/s).
    J : numpy.ndarray, shape (6, n), optional
        The world-frame Jacobian at ``q`` if already computed (m per rad in its linear rows,
        dimensionless in its angular rows); computed when None.

    Returns
    -------
    numpy.ndarray, shape (6, n)
        Jdot: linear rows in m/s per rad, angular rows in 1/s (rad/s per rad).
    """
    H = ets.hessian0(np.asarray(q, dtype=float), J0=J)
    return np.einsum("ijk,i->jk", H, np.asarray(qd, dtype=float))


def joint_accelerations(ets: rtb.ETS, q: np.ndarray, qd: np.ndarray, v: np.ndarray, a: np.ndarray) -> np.ndarray:
    """qdd (N, n) rad/s^2 of joint samples q (rad), qd (rad/s) that realise spatial velocities v (N, 6)
    with spatial accelerations a (N, 6) (m/s, rad/s and their derivatives): the exact derivative of the
    (minimum-norm) solution qd = J^+ v, see the module docstring. NaN rows stay NaN.

    Parameters
    ----------
    ets : roboticstoolbox.ETS
        The arm's elementary transform sequence.
    q : numpy.ndarray, shape (N, n)
        The joint angles (rad).
    qd : numpy.ndarray, shape (N, n)
        The joint velocities (rad/s).
    v : numpy.ndarray, shape (N, 6)
        The spatial velocities in the base frame: linear (m/s), angular (rad/s).
    a : numpy.ndarray, shape (N, 6)
        Their time derivatives: linear (m/s^2), angular (rad/s^2).

    Returns
    -------
    numpy.ndarray, shape (N, n)
        The joint accelerations qdd (rad/s^2); NaN rows where q or qd is NaN.
    """
    N, n = q.shape
    qdd = np.full((N, n), np.nan)
    for k in range(N):
        if not (np.all(np.isfinite(q[k])) and np.all(np.isfinite(qd[k]))):
            continue
        J = ets.jacob0(q[k])
        Jd = jacobian_dot(ets, q[k], qd[k], J)
        rhs = a[k] - Jd @ qd[k]
        if n == 6 and np.linalg.cond(J) < 1e12:
            qdd[k] = np.linalg.solve(J, rhs)
        else:
            Jp = np.linalg.pinv(J)
            qdd[k] = Jp @ rhs + (np.eye(n) - Jp @ J) @ Jd.T @ np.linalg.lstsq(J @ J.T, v[k], rcond=None)[0]
    return qdd


@dataclass
class JointDynamics:
    """Accelerations, jerks and torques of one transferred trajectory and what every limit asks of it.

    ``transfer`` the :class:`~skilllib.robot.TransferResult`; ``qdd`` (N, n) rad/s^2; ``qddd`` (N, n)
    rad/s^3; ``tau`` (N, n) N m or None (no dynamic parameters); ``qdd_limits`` (n,) rad/s^2 or None;
    ``tau_limits`` (n,) N m or None; ``robot`` the roboticstoolbox arm (for torques at other speeds).
    NaN rows are samples the transfer could not compute.

    Attributes
    ----------
    transfer : TransferResult
        The transferred trajectory: q (rad), qd (rad/s) per sample.
    qdd : numpy.ndarray, shape (N, n)
        The joint accelerations (rad/s^2).
    qddd : numpy.ndarray, shape (N, n)
        The joint jerks (rad/s^3).
    tau : numpy.ndarray, shape (N, n), or None
        The joint torques (N m); None without dynamic parameters.
    qdd_limits : numpy.ndarray, shape (n,), or None
        The joint acceleration limits (rad/s^2); None for no such limit.
    tau_limits : numpy.ndarray, shape (n,), or None
        The joint torque limits (N m); None for no such limit.
    robot : roboticstoolbox.Robot
        The arm, for the torques at other speeds.
    ok : numpy.ndarray of bool, shape (N,)
        Samples with q, qd and qdd computed (dimensionless).
    peak_abs_qdd, peak_abs_qddd : numpy.ndarray, shape (n,)
        Peak absolute joint acceleration (rad/s^2) and jerk (rad/s^3) per joint.
    peak_abs_tau : numpy.ndarray, shape (n,), or None
        Peak absolute joint torque per joint (N m).
    time_scale : float
        The smallest uniform stretch s >= 1 after which every limit holds (dimensionless).
    binding_limit : str or None
        The limit that sets ``time_scale`` (text).
    feasible : bool
        Nothing flagged and every limit holds as recorded (dimensionless).
    """

    transfer: TransferResult
    qdd: np.ndarray
    qddd: np.ndarray
    tau: np.ndarray | None
    qdd_limits: np.ndarray | None
    tau_limits: np.ndarray | None
    robot: rtb.Robot = field(repr=False)
    _scales: dict[float, float] = field(default_factory=dict, repr=False, compare=False)

    @property
    def ok(self) -> np.ndarray:
        """Samples with q, qd and qdd computed (N,) bool."""
        r = self.transfer
        return (
            np.all(np.isfinite(r.q), axis=1) & np.all(np.isfinite(r.qd), axis=1) & np.all(np.isfinite(self.qdd), axis=1)
        )

    def _peak(self, x: np.ndarray | None) -> np.ndarray | None:
        if x is None:
            return None
        good = np.all(np.isfinite(x), axis=1)
        return np.max(np.abs(x[good]), axis=0) if good.any() else np.full(x.shape[1], np.nan)

    @property
    def peak_abs_qdd(self) -> np.ndarray:
        """Peak ``|qdd_j|`` per joint over the computed samples, rad/s^2."""
        return self._peak(self.qdd)

    @property
    def peak_abs_qddd(self) -> np.ndarray:
        """Peak ``|qddd_j|`` per joint, rad/s^3 (samples whose neighbours were computed)."""
        return self._peak(self.qddd)

    @property
    def peak_abs_tau(self) -> np.ndarray | None:
        """Peak ``|tau_j|`` per joint, N m, or None without dynamic parameters."""
        return self._peak(self.tau)

    def torques(self, s: float = 1.0) -> np.ndarray | None:
        """tau (N, n) N m of the trajectory slowed uniformly by s: rne(q, qd / s, qdd / s^2); None without
        dynamic parameters. NaN rows where the transfer failed."""
        if self.tau is None:
            return None
        out = np.full(self.qdd.shape, np.nan)
        ok = self.ok
        if ok.any():
            r = self.transfer
            out[ok] = np.atleast_2d(self.robot.rne(r.q[ok], r.qd[ok] / s, self.qdd[ok] / s**2))
        return out

    def _torque_ratio(self, x: float) -> float:
        """Largest ``|tau_j| / tau_max_j`` over the computed samples at speed factor x = 1/s."""
        tau = self.torques(1.0 / x)
        return float(np.nanmax(np.abs(tau) / self.tau_limits))

    def _torque_scale(self, s_min: float) -> float:
        """Smallest s >= s_min at which every torque is within its limit (inf when none is); cached."""
        if self.tau_limits is None or not self.ok.any():
            return s_min
        if s_min not in self._scales:
            self._scales[s_min] = self._search_torque_scale(s_min)
        return self._scales[s_min]

    def _search_torque_scale(self, s_min: float) -> float:
        x0 = 1.0 / s_min
        if self._torque_ratio(x0) <= 1 + QD_LIMIT_RTOL:
            return s_min
        xs = np.linspace(x0, 0.0, TORQUE_GRID)[:-1]  # from the fastest allowed speed down to (almost) rest
        xs = np.r_[xs, 1e-6 * x0]
        ratio = np.array([self._torque_ratio(x) for x in xs])
        inside = np.flatnonzero(ratio <= 1)
        if not inside.size:
            return float("inf")
        i = int(inside[0])  # the fastest feasible grid point; the one before it (faster) is infeasible
        lo, hi = xs[i], xs[i - 1]
        x = brentq(lambda y: self._torque_ratio(y) - 1.0, lo, hi, xtol=1e-12 * hi, rtol=1e-12)
        for _ in range(100):  # keep the feasible side of the root (a step or two of xtol)
            if self._torque_ratio(x) <= 1 + QD_LIMIT_RTOL:
                return 1.0 / x
            x -= 1e-12 * hi
        return 1.0 / lo

    def time_scales(self) -> dict[str, float | None]:
        """The smallest stretch s >= 1 each limit asks for alone: ``velocity`` (s_v), ``acceleration``
        (s_a; None without acceleration limits) and ``torque`` (None without torque limits or dynamics);
        NaN when no sample was computed."""
        r = self.transfer
        s_v = r.time_scale
        s_a = None
        if self.qdd_limits is not None:
            ratio = self.peak_abs_qdd / self.qdd_limits
            ratio = ratio[np.isfinite(ratio)]
            s_a = float(np.sqrt(ratio.max())) if ratio.size else float("nan")
            if s_a <= 1 + QD_LIMIT_RTOL:  # within the tolerance of limits_hold: no stretch
                s_a = 1.0
        s_t = self._torque_scale(1.0) if self.tau_limits is not None and self.tau is not None else None
        return {"velocity": s_v, "acceleration": s_a, "torque": s_t}

    @property
    def time_scale(self) -> float:
        """The smallest uniform stretch s >= 1 after which every limit (velocity, acceleration, torque)
        holds on every computed sample (inf when the torque limits cannot be met; NaN when nothing was
        computed)."""
        scales = self.time_scales()
        if not np.isfinite(scales["velocity"]):
            return float("nan")
        s_va = max([1.0] + [s for s in (scales["velocity"], scales["acceleration"]) if s is not None])
        return self._torque_scale(s_va) if scales["torque"] is not None else s_va

    @property
    def binding_limit(self) -> str | None:
        """The limit that sets :attr:`time_scale`: "velocity", "acceleration" or "torque"; None when the
        trajectory is executable as recorded (s = 1) or nothing was computed."""
        s = self.time_scale
        if np.isnan(s) or s <= 1.0:
            return None
        scales = self.time_scales()
        s_va = {k: v for k, v in scales.items() if k != "torque" and v is not None}
        best = max(s_va, key=lambda k: s_va[k])
        if scales["torque"] is not None and s > s_va[best] * (1 + QD_LIMIT_RTOL):
            return "torque"
        return best

    def limits_hold(self, s: float = 1.0) -> bool:
        """True when, slowed by s, every computed sample has ``|qd_j| <= qd_max_j``, ``|qdd_j| <= qdd_max_j`` and
        ``|tau_j| <= tau_max_j`` (relative tolerance :data:`~skilllib.robot.QD_LIMIT_RTOL`)."""
        ok = self.ok
        if not ok.any():
            return False
        r, tol = self.transfer, 1 + QD_LIMIT_RTOL
        good = np.all(np.abs(r.qd[ok]) / s <= r.qd_limits * tol)
        if self.qdd_limits is not None:
            good &= np.all(np.abs(self.qdd[ok]) / s**2 <= self.qdd_limits * tol)
        if self.tau_limits is not None and self.tau is not None:
            good &= np.all(np.abs(self.torques(s)[ok]) <= self.tau_limits * tol)
        return bool(good)

    @property
    def feasible(self) -> bool:
        """Nothing flagged and every limit holds as recorded (s = 1)."""
        return not self.transfer.flags and self.limits_hold(1.0)

    def summary(self) -> dict[str, Any]:
        """The per-prototype entries of results.json this module adds (plain floats and lists):
        ``time_scale`` and ``feasible`` cover every limit checked (velocity, acceleration, torque);
        ``time_scales`` gives the stretch each limit asks for alone."""
        return {
            "peak_abs_qdd": json_value(self.peak_abs_qdd),
            "peak_abs_qddd": json_value(self.peak_abs_qddd),
            "peak_abs_tau": json_value(self.peak_abs_tau),
            "time_scales": json_value(self.time_scales()),
            "time_scale": json_value(self.time_scale),
            "binding_limit": self.binding_limit,
            "feasible": bool(self.feasible),
        }


def joint_dynamics(
    robot: rtb.Robot,
    result: TransferResult,
    qdd_limits: float | np.ndarray | None = None,
    tau_limits: float | np.ndarray | None = None,
    rotation: np.ndarray | None = None,
) -> JointDynamics:
    """Accelerations, jerks and (where the model allows) torques of ``result`` on ``robot``.

    ``qdd_limits`` rad/s^2 and ``tau_limits`` N m: scalar, per joint, or None for no such limit (torque
    limits need dynamic parameters: ValueError otherwise). The hand's velocity in the base frame is
    J qd (the transfer made it so); its acceleration is its derivative over time (:func:`derivative`).

    Parameters
    ----------
    robot : roboticstoolbox.Robot
        The arm the trajectory was transferred to.
    result : TransferResult
        The transfer: t (s), q (rad), qd (rad/s), v_base (m/s).
    qdd_limits : float or numpy.ndarray, shape (n,), optional
        Joint acceleration limits (rad/s^2); None for none.
    tau_limits : float or numpy.ndarray, shape (n,), optional
        Joint torque limits (N m); None for none.
    rotation : numpy.ndarray, shape (3, 3), optional
        Not used: the base-frame hand velocity comes from the transfer (dimensionless).

    Returns
    -------
    JointDynamics
        qdd (rad/s^2), qddd (rad/s^3), tau (N m, or None without dynamic parameters) and the limits.

    Raises
    ------
    ValueError
        A limit of the wrong length, not positive or not finite, or torque limits on an arm without
        dynamic parameters.
    """
    ets = robot.ets()
    n = ets.n
    qdd_lim = None if qdd_limits is None else limits_vector(qdd_limits, n, "qdd_limits", "rad/s^2")
    tau_lim = None if tau_limits is None else limits_vector(tau_limits, n, "tau_limits", "N m")
    dynamic = has_dynamics(robot)
    if tau_lim is not None and not dynamic:
        raise ValueError(
            f"{robot.name} has no dynamic parameters (no link masses): torque limits cannot be checked on it"
        )
    v = _spatial_velocity(result, ets)
    a = derivative(v, result.t)
    qdd = joint_accelerations(ets, result.q, result.qd, v, a)
    qddd = derivative(qdd, result.t)
    out = JointDynamics(result, qdd, qddd, None, qdd_lim, tau_lim, robot)
    if dynamic:
        out.tau = np.zeros_like(qdd)  # marks "has dynamics" for torques()
        out.tau = out.torques(1.0)
    return out


def _spatial_velocity(result: TransferResult, ets: rtb.ETS) -> np.ndarray:
    """The commanded spatial velocity (N, 6) in the base frame, (v_hand, 0) in m/s and rad/s: the
    transfer's ``v_base``, or J(q) qd where a result does not carry it (NaN where q is NaN)."""
    if result.v_base is not None:
        return np.hstack([result.v_base, np.zeros((len(result.t), 3))])
    return np.array(
        [ets.jacob0(q) @ qd if np.all(np.isfinite(q)) else np.full(6, np.nan) for q, qd in zip(result.q, result.qd)]
    )
