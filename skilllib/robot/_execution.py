"""Executed motion: the arm following a prototype's joint velocity commands, with limits and a lag.

The transfer (:mod:`skilllib.robot`) says which joint velocities qd_k the tool's path asks for at the
recording's samples t_k. Whether the tool then gets the prototype's speed profile, PV and SPARC is a
question of execution. :func:`execute` simulates it with a joint velocity controller at
:data:`CONTROL_RATE_HZ`:

* **command**: qd_k / s between the (time-scaled) sample instants s (t_k - t_0) (s = 1: as recorded),
  interpolated by a cubic Hermite spline through the samples' velocities and accelerations qdd_k / s^2
  when these are given (:mod:`skilllib.robot`), else linearly; the arm starts at the first sample's
  pose, already moving at the first command (the recorded hand was moving at onset too). Between samples
  the interpolated command can ask for more acceleration than any sample does (a peak between samples):
  a time scale computed at the samples can leave a little clipping there, which :attr:`Execution.saturated`
  shows;
* per controller tick dt: the command is clipped to the **velocity limits**; a **first-order lag** of
  bandwidth f_b (time constant 1 / (2 pi f_b); exact discretisation, gain 1 - exp(-2 pi f_b dt)) moves the
  joint velocity towards it; its change per tick is clipped to +-qdd_max dt (**acceleration limits**);
  the joint angles integrate the joint velocity (trapezoidal rule);
* the **executed tool path** is the forward kinematics of the joint angles, p(q) (m, base frame), and the
  tool velocity J(q) qd (its linear part, m/s; no differencing); the **tracking error** is ``|p(q(t_k)) - p_k|``
  at the command's sample instants, against the prototype's path.

The executed speed is measured as the prototype's was: at the command's sample instants (the executed
profile at the controller rate, linearly interpolated there), so that the executed and the commanded
profile have the same samples. PV is the largest of them; SPARC is
:func:`skilllib.smoothness.sparc` with the run's parameters, at the samples' rate fs / s and with the cut-off
scaled to fc / s when the command was slowed by s (a perfect execution of a slowed prototype then
returns the prototype's SPARC exactly, and fc / s stays below the Nyquist frequency fs / (2 s) whenever fc
stays below fs / 2; the samples' rate is taken from their stamps, and fc / s is capped at its Nyquist
frequency when stamps written imprecisely put it a little below fs / s). An arm that does not move at all
(limits too low to leave the start) has no SPARC (NaN). Torque limits are not simulated (no forward
dynamics): the acceleration limits stand in for the drives' capacity.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import roboticstoolbox as rtb
from scipy.interpolate import CubicHermiteSpline

from ..smoothness import SPARC_PARAMS, sparc
from ._arms import limits_vector
from ._velocity import TransferResult

#: Controller rate, Hz (a Universal Robots e-Series controller runs at 500 Hz).
CONTROL_RATE_HZ: float = 500.0

#: Bandwidth of the first-order actuator lag, Hz: the default cut-off frequency of the first-order
#: low-pass filter libfranka applies to the commands of a Franka Emika arm (``kDefaultCutoffFrequency``,
#: 100 Hz), a stand-in for every arm here (an assumption; pass another to :func:`execute`).
ACTUATOR_BANDWIDTH_HZ: float = 100.0


@dataclass
class Execution:
    """One simulated execution. At the controller ticks: ``t`` (M,) s, ``q`` (M, n) rad, ``qd`` (M, n) rad/s,
    ``qd_cmd`` (M, n) rad/s (before saturation), ``x`` (M, 3) m and ``v`` (M, 3) m/s (tool, base frame),
    ``saturated`` (M, n) bool (velocity or acceleration limit active). At the command's samples:
    ``t_samples`` (N,) s, ``speed_samples`` (N,) m/s, ``tracking_error`` (N,) m. ``time_scale`` s, ``pv``
    (m/s), ``sparc`` and the settings ``rate_hz``, ``bandwidth_hz`` (None: no lag)."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qd_cmd: np.ndarray
    x: np.ndarray
    v: np.ndarray
    saturated: np.ndarray
    t_samples: np.ndarray
    speed_samples: np.ndarray
    tracking_error: np.ndarray
    time_scale: float
    pv: float
    sparc: float
    rate_hz: float
    bandwidth_hz: float | None

    @property
    def speed(self) -> np.ndarray:
        """Executed tool speed at the controller ticks, m/s."""
        return np.linalg.norm(self.v, axis=1)

    @property
    def max_tracking_error_m(self) -> float:
        """Largest distance (m) of the executed tool point from the prototype's path at its samples."""
        return float(np.max(self.tracking_error))

    @property
    def saturated_fraction(self) -> float:
        """Share of controller ticks at which some joint was held by a limit."""
        return float(np.mean(np.any(self.saturated, axis=1)))

    def summary(self) -> dict[str, float]:
        """``pv`` (m/s), ``sparc``, ``max_tracking_error_m`` (m), ``saturated_fraction``, ``time_scale``."""
        return {
            "pv": float(self.pv),
            "sparc": float(self.sparc),
            "max_tracking_error_m": self.max_tracking_error_m,
            "saturated_fraction": self.saturated_fraction,
            "time_scale": float(self.time_scale),
        }


def execute(
    robot: rtb.Robot,
    result: TransferResult,
    qd_limits: float | np.ndarray | None = None,
    qdd_limits: float | np.ndarray | None = None,
    *,
    time_scale: float = 1.0,
    rate_hz: float = CONTROL_RATE_HZ,
    bandwidth_hz: float | None = ACTUATOR_BANDWIDTH_HZ,
    sparc_params: Mapping[str, float] = SPARC_PARAMS,
    qdd: np.ndarray | None = None,
) -> Execution:
    """Simulate ``robot`` following the joint velocities of ``result`` (see the module docstring).

    ``qd_limits`` rad/s (default the result's own) and ``qdd_limits`` rad/s^2 (None: no acceleration
    limit), scalar or per joint; ``time_scale`` s >= 1 slows the command uniformly; ``rate_hz`` the
    controller rate (Hz); ``bandwidth_hz`` the first-order lag's bandwidth (Hz; None for none);
    ``sparc_params`` fc (Hz), amp_th, padlevel of :func:`skilllib.smoothness.sparc`; ``qdd`` (N, n)
    rad/s^2 the samples' accelerations (of the recorded timing) for the Hermite command. ValueError when a
    sample of ``result`` was not computed (IK failure): such a command cannot be executed.

    Parameters
    ----------
    robot : roboticstoolbox.Robot
        The arm the trajectory was transferred to.
    result : TransferResult
        The transfer: t (s), q (rad), qd (rad/s), x_base (m) per sample, every sample computed.
    qd_limits : float or numpy.ndarray, shape (n,), optional
        Joint velocity limits (rad/s); the result's own by default.
    qdd_limits : float or numpy.ndarray, shape (n,), optional
        Joint acceleration limits (rad/s^2); None for no acceleration limit.
    time_scale : float
        The uniform time stretch s > 0 of the command, normally >= 1 (dimensionless).
    rate_hz : float
        The controller rate (Hz).
    bandwidth_hz : float or None
        The bandwidth of the first-order actuator lag (Hz); None for no lag.
    sparc_params : mapping of str to float
        ``fc`` (Hz), ``amp_th`` (dimensionless) and ``padlevel`` (dimensionless) of
        :func:`skilllib.smoothness.sparc`; missing keys take :data:`~skilllib.smoothness.SPARC_PARAMS`.
    qdd : numpy.ndarray, shape (N, n), optional
        The samples' joint accelerations at the recorded timing (rad/s^2), for the Hermite command; None
        for a linearly interpolated command.

    Returns
    -------
    Execution
        The simulated execution: at the controller ticks t (s), q (rad), qd (rad/s), tool x (m) and v (m/s);
        at the command's samples the speed (m/s) and tracking error (m); PV (m/s) and SPARC (dimensionless).

    Raises
    ------
    ValueError
        A sample of ``result`` without joint angles, a ``time_scale`` or ``rate_hz`` not positive, a
        ``bandwidth_hz`` not positive, or a bad limit.
    """
    ets = robot.ets()
    n = ets.n
    if not (np.all(np.isfinite(result.q)) and np.all(np.isfinite(result.qd))):
        raise ValueError("the transfer left samples without joint angles (flagged IK failures): nothing to execute")
    if not (np.isfinite(time_scale) and time_scale > 0 and rate_hz > 0):
        raise ValueError(f"time_scale and rate_hz must be positive, got {time_scale}, {rate_hz}")
    if bandwidth_hz is not None and not bandwidth_hz > 0:
        raise ValueError(f"bandwidth_hz must be positive (Hz) or None, got {bandwidth_hz}")
    qd_lim = limits_vector(result.qd_limits if qd_limits is None else qd_limits, n, "qd_limits", "rad/s")
    qdd_lim = None if qdd_limits is None else limits_vector(qdd_limits, n, "qdd_limits", "rad/s^2")
    s = float(time_scale)
    t_k = s * (result.t - result.t[0])  # the command's (stretched) sample instants from 0
    qd_k = result.qd / s
    dt = 1.0 / rate_hz
    t = np.unique(np.r_[np.arange(0.0, t_k[-1], dt), t_k[-1]])
    if qdd is None:
        qd_cmd = np.column_stack([np.interp(t, t_k, qd_k[:, j]) for j in range(n)])
    else:
        qd_cmd = CubicHermiteSpline(t_k, qd_k, np.asarray(qdd) / s**2, axis=0)(t)
    M = len(t)
    q = np.empty((M, n))
    qd = np.empty((M, n))
    saturated = np.zeros((M, n), dtype=bool)
    u0 = np.clip(qd_cmd[0], -qd_lim, qd_lim)
    q[0], qd[0], saturated[0] = result.q[0], u0, u0 != qd_cmd[0]
    for i in range(1, M):
        h = t[i] - t[i - 1]
        u = np.clip(qd_cmd[i], -qd_lim, qd_lim)
        gain = 1.0 if bandwidth_hz is None else 1.0 - np.exp(-2 * np.pi * bandwidth_hz * h)
        step = gain * (u - qd[i - 1])
        sat = u != qd_cmd[i]
        if qdd_lim is not None:
            clipped = np.clip(step, -qdd_lim * h, qdd_lim * h)
            sat |= clipped != step
            step = clipped
        qd[i] = qd[i - 1] + step
        q[i] = q[i - 1] + 0.5 * h * (qd[i - 1] + qd[i])
        saturated[i] = sat
    x = np.array([ets.eval(qi)[:3, 3] for qi in q])
    v = np.array([ets.jacob0(qi)[:3] @ qdi for qi, qdi in zip(q, qd)])
    speed = np.linalg.norm(v, axis=1)
    speed_k = np.interp(t_k, t, speed)
    x_k = np.column_stack([np.interp(t_k, t, x[:, j]) for j in range(3)])
    error = np.linalg.norm(x_k - result.x_base, axis=1)
    fs = (len(t_k) - 1) / t_k[-1] if len(t_k) > 1 else float("nan")
    params = dict(SPARC_PARAMS) | dict(sparc_params)
    fc = min(params["fc"] / s, fs / 2)  # the samples' rate from imprecise stamps can fall just below fs / s
    value = (
        sparc(speed_k, fs, fc=fc, amp_th=params["amp_th"], padlevel=params["padlevel"])
        if len(t_k) > 1 and np.any(speed_k > 0)
        else float("nan")  # one sample, or an arm that did not move (limits too low to leave the start)
    )
    return Execution(
        t=t + result.t[0],
        q=q,
        qd=qd,
        qd_cmd=qd_cmd,
        x=x,
        v=v,
        saturated=saturated,
        t_samples=t_k + result.t[0],
        speed_samples=speed_k,
        tracking_error=error,
        time_scale=s,
        pv=float(speed_k.max()),
        sparc=value,
        rate_hz=float(rate_hz),
        bandwidth_hz=None if bandwidth_hz is None else float(bandwidth_hz),
    )
