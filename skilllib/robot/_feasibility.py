"""Can an arm execute a prototype? Every limit, the time scaling, the executed motion: results.json.

For each prototype's :class:`~skilllib.robot.TransferResult` on one arm, :func:`assess` computes

* the joint accelerations, jerks and torques and the time scale that satisfies the velocity,
  acceleration and torque limits at once, with the limit that binds (:mod:`skilllib.robot`);
* the simulated execution of the joint velocity commands as recorded and after that time scaling,
  with the executed PV, SPARC and tracking error (:mod:`skilllib.robot`).

:func:`transfer_block` turns the assessments into the ``transfer`` block of results.json (docs/results.md):
the entries of :func:`skilllib.robot.transfer_summary` with the dynamics' and executions' entries, plus
``qdd_limits``, ``tau_limits`` and ``execution`` (controller rate, actuator bandwidth). In each
prototype's entry ``feasible`` and ``time_scale`` cover every limit checked (velocity, acceleration,
torque); the velocity limits alone, the paper's question, are ``feasible_velocity`` and
``time_scales.velocity``.
The limits an arm gets by default, and their sources, are those of :func:`skilllib.robot.dynamic_limits`;
:func:`skilllib.robot.get_robot` applies the user's (an :class:`~skilllib.robot.Arm` carries them all).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import roboticstoolbox as rtb

from ..prototypes import json_value
from ..smoothness import SPARC_PARAMS
from ._arms import DynamicLimits
from ._dynamics import JointDynamics, joint_dynamics
from ._execution import ACTUATOR_BANDWIDTH_HZ, CONTROL_RATE_HZ, Execution, execute
from ._velocity import TransferResult, transfer_summary

#: The largest time scale whose slowed execution is simulated (dimensionless). The simulation steps the
#: controller at :data:`~skilllib.robot.CONTROL_RATE_HZ` over the whole slowed motion, so its time and
#: memory grow with the time scale: a prototype of 1 s slowed by 1e6 (limits of 1e-6 rad/s) would be 5e8
#: ticks, gigabytes. A stretch beyond 100 (a 1 s reach taking minutes) is no execution anyone would run;
#: its value is still reported (``time_scale``), the slowed execution is not simulated (``note``).
MAX_TIME_SCALE: float = 100.0


@dataclass
class Assessment:
    """One prototype on one arm: its :class:`~skilllib.robot.JointDynamics`, its execution as recorded
    (``executed``) and after the time scale of every limit (``executed_scaled``), each None with the reason
    in ``note`` when it cannot be simulated (samples the transfer could not compute; no finite time scale).

    Attributes
    ----------
    dynamics : JointDynamics
        Joint accelerations (rad/s^2), jerks (rad/s^3), torques (N m) and the time scale of every limit.
    executed : Execution or None
        The simulated execution as recorded: PV (m/s), SPARC (dimensionless), tracking error (m).
    executed_scaled : Execution or None
        The simulated execution after the time scale of every limit (same units).
    note : str or None
        Why an execution is None (text).
    transfer : TransferResult
        The transfer result assessed, ``dynamics.transfer``: q (rad), qd (rad/s).
    """

    dynamics: JointDynamics
    executed: Execution | None
    executed_scaled: Execution | None
    note: str | None = None

    @property
    def transfer(self) -> TransferResult:
        return self.dynamics.transfer

    def summary(self) -> dict[str, Any]:
        """The prototype's entry of results.json: the transfer's, the dynamics' and the executions'.

        ``feasible`` and ``time_scale`` are those of every limit (:meth:`JointDynamics.summary`); the
        transfer's velocity-only verdict is kept as ``feasible_velocity`` (its stretch is
        ``time_scales.velocity``)."""
        entry = self.transfer.summary()
        entry["feasible_velocity"] = entry.pop("feasible")
        del entry["time_scale"]  # the velocity limits' stretch: time_scales.velocity
        entry.update(self.dynamics.summary())
        entry["executed"] = None if self.executed is None else json_value(self.executed.summary())
        entry["executed_time_scaled"] = (
            None if self.executed_scaled is None else json_value(self.executed_scaled.summary())
        )
        return entry


def assess_one(
    robot: rtb.Robot,
    result: TransferResult,
    limits: DynamicLimits,
    *,
    sparc_params: Mapping[str, float] = SPARC_PARAMS,
    rate_hz: float = CONTROL_RATE_HZ,
    bandwidth_hz: float | None = ACTUATOR_BANDWIDTH_HZ,
) -> Assessment:
    """The :class:`Assessment` of one transfer result under ``limits``.

    Parameters
    ----------
    robot : roboticstoolbox.Robot
        The arm the trajectory was transferred to.
    result : TransferResult
        The transfer: t (s), q (rad), qd (rad/s) per sample, and the velocity limits (rad/s).
    limits : DynamicLimits
        Joint acceleration limits ``qdd_limits`` (rad/s^2) and torque limits ``tau_limits`` (N m), each
        None for none.
    sparc_params : mapping of str to float
        ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless) of the executed SPARC.
    rate_hz : float
        The simulated controller rate (Hz).
    bandwidth_hz : float or None
        The bandwidth of the simulated actuator lag (Hz); None for no lag.

    Returns
    -------
    Assessment
        The dynamics, the execution as recorded and after time scaling, and a note where one is missing.

    Raises
    ------
    ValueError
        A limit of the wrong length, not positive or not finite, or torque limits on an arm without
        dynamic parameters.
    """
    dyn = joint_dynamics(robot, result, limits.qdd_limits, limits.tau_limits)
    kw = dict(
        qdd_limits=limits.qdd_limits, rate_hz=rate_hz, bandwidth_hz=bandwidth_hz, sparc_params=sparc_params, qdd=dyn.qdd
    )
    if not dyn.ok.all():
        return Assessment(dyn, None, None, "not executed: the transfer left samples without joint angles")
    executed = execute(robot, result, **kw)
    s = dyn.time_scale
    if not np.isfinite(s):
        return Assessment(dyn, executed, None, "no time scale meets the torque limits: not executed slowed")
    if s > MAX_TIME_SCALE:
        return Assessment(dyn, executed, None, _too_slow_note(s))
    return Assessment(dyn, executed, executed if s == 1.0 else execute(robot, result, time_scale=s, **kw))


def _too_slow_note(time_scale: float) -> str:
    """Why the slowed execution of a time scale beyond :data:`MAX_TIME_SCALE` is not simulated.

    Parameters
    ----------
    time_scale : float
        The time scale every limit asks for (dimensionless).

    Returns
    -------
    str
        The note (text), naming the time scale, the bound and the controller ticks it would take.
    """
    return (
        f"time scale {time_scale:.3g} beyond {MAX_TIME_SCALE:g} (limits so low that the arm barely moves): "
        f"the slowed execution is not simulated"
    )


def assess(
    robot: rtb.Robot,
    results: Sequence[TransferResult],
    limits: DynamicLimits,
    *,
    sparc_params: Mapping[str, float] = SPARC_PARAMS,
    rate_hz: float = CONTROL_RATE_HZ,
    bandwidth_hz: float | None = ACTUATOR_BANDWIDTH_HZ,
) -> list[Assessment]:
    """:func:`assess_one` for each result (same arm, same limits).

    Parameters
    ----------
    robot : roboticstoolbox.Robot
        The arm the trajectories were transferred to.
    results : sequence of TransferResult
        The transfer results: t (s), q (rad), qd (rad/s) per sample.
    limits : DynamicLimits
        Joint acceleration limits ``qdd_limits`` (rad/s^2) and torque limits ``tau_limits`` (N m), each
        None for none.
    sparc_params : mapping of str to float
        ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless) of the executed SPARC.
    rate_hz : float
        The simulated controller rate (Hz).
    bandwidth_hz : float or None
        The bandwidth of the simulated actuator lag (Hz); None for no lag.

    Returns
    -------
    list of Assessment
        One per result, in the given order.

    Raises
    ------
    ValueError
        As :func:`assess_one`.
    """
    return [
        assess_one(robot, r, limits, sparc_params=sparc_params, rate_hz=rate_hz, bandwidth_hz=bandwidth_hz)
        for r in results
    ]


def transfer_block(assessments: Sequence[Assessment]) -> dict[str, Any]:
    """The ``transfer`` block of results.json: ``robot``, ``q0_deg``, ``qd_limits`` (rad/s), ``qdd_limits``
    (rad/s^2 or null), ``tau_limits`` (N m or null), ``execution`` {``control_rate_hz``,
    ``actuator_bandwidth_hz``} and ``prototypes`` (:meth:`Assessment.summary`, in the given order).

    Parameters
    ----------
    assessments : sequence of Assessment
        At least one, all on the same arm from the same start pose (rad).

    Returns
    -------
    dict
        The block, JSON-ready: limits in rad/s, rad/s^2 and N m, rates in Hz.

    Raises
    ------
    ValueError
        When ``assessments`` is empty or mixes arms or start poses.
    """
    if not assessments:
        raise ValueError("transfer_block needs at least one Assessment")
    block = transfer_summary([a.transfer for a in assessments])
    first = assessments[0]
    block["qdd_limits"] = json_value(first.dynamics.qdd_limits)
    block["tau_limits"] = json_value(first.dynamics.tau_limits)
    e = next((a.executed for a in assessments if a.executed is not None), None)
    block["execution"] = {
        "control_rate_hz": CONTROL_RATE_HZ if e is None else e.rate_hz,
        "actuator_bandwidth_hz": ACTUATOR_BANDWIDTH_HZ if e is None else e.bandwidth_hz,
    }
    block["prototypes"] = [a.summary() for a in assessments]
    return block


def limits_text(dyn: JointDynamics) -> str:
    """The limits of an assessment for a summary line: 'joint velocity limits 3.14 rad/s; acceleration
    5 rad/s^2' (one value when every joint has the same, else one per joint; absent limits left out).

    Parameters
    ----------
    dyn : JointDynamics
        The dynamics whose limits are told: velocity (rad/s), acceleration (rad/s^2), torque (N m).

    Returns
    -------
    str
        The limits with their units, joined by "; " (text).
    """

    def one(what: str, lim: np.ndarray | None, unit: str) -> str:
        if lim is None:
            return ""
        values = f"{lim[0]:.3g}" if np.all(lim == lim[0]) else ", ".join(f"{v:.3g}" for v in lim)
        return f"{what} {values} {unit}"

    parts = [
        one("joint velocity limits", dyn.transfer.qd_limits, "rad/s"),
        one("acceleration", dyn.qdd_limits, "rad/s^2"),
        one("torque", dyn.tau_limits, "N m"),
    ]
    return "; ".join(p for p in parts if p)
