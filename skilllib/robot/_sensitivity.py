"""How far the assumed limits can move before a verdict changes: the robot verdicts' sensitivity.

A prototype is *feasible as recorded* (:attr:`skilllib.robot.JointDynamics.feasible`) when the transfer
flagged nothing and, on every computed sample, every joint stays within its velocity, acceleration and
torque limit. For each kind of limit K (``velocity``, ``acceleration``, ``torque``) that is one number,
the *demand ratio*

    rho_K = max_j max_t |x_j(t)| / x_j^max ,

with x = qd (rad/s), qdd (rad/s^2) or tau (N m) of the trajectory as recorded (s = 1) over the samples the
assessment computed, and x^max the limits assumed. The verdict is "feasible" iff nothing is flagged and
rho_K <= 1 for every K (to the relative tolerance :data:`~skilllib.robot.QD_LIMIT_RTOL`, as
:meth:`~skilllib.robot.JointDynamics.limits_hold`).

Scaling every joint's limit of one kind K by a factor f (the other kinds as assumed) changes only that
kind's condition, to rho_K <= f; the demands do not depend on the limits (the torques are those of the
trajectory as recorded, inverse dynamics at s = 1). So :func:`limit_margins` reads the ratios off the
assessment objects (:class:`~skilllib.robot.JointDynamics` or :class:`~skilllib.robot.Assessment`, nothing
is transferred or differentiated again) and

* a prototype's verdict flips at f = rho_K exactly, provided it is not flagged and the other kinds hold
  (rho_L <= 1 for L != K); otherwise no scaling of K alone makes it feasible and its verdict never flips
  (:meth:`LimitMargin.critical_scale` is None);
* the *critical limit* of kind K is rho_K times the assumed limits, per joint (in rad/s, rad/s^2 or N m);
* the number of an arm's prototypes feasible as recorded is a step function of f,
  N_K(f) = #{p : p can flip on K and rho_K(p) <= f}, non-decreasing, right-continuous, with a step at each
  rho_K (:func:`feasible_counts`); it keeps its value at f = 1 (the book's count) exactly on
  [largest rho_K <= 1, smallest rho_K > 1) (:func:`verdict_range`).

Only the verdict "as recorded" is covered: the time scale s that slows a prototype into its limits, and the
limit that binds it, change with the limits in other ways (s_a grows with the square root of 1/f).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ._dynamics import LIMIT_NAMES, JointDynamics
from ._feasibility import Assessment
from ._velocity import QD_LIMIT_RTOL

#: The unit of each kind of limit (for the tables).
LIMIT_UNITS: dict[str, str] = {"velocity": "rad/s", "acceleration": "rad/s^2", "torque": "N m"}


@dataclass(frozen=True)
class LimitMargin:
    """One prototype on one arm: its demand ratio under each kind of limit and the scale that flips it.

    Made by :func:`limit_margins` from an assessment; see the module docstring for the definitions.

    Attributes
    ----------
    robot : str
        The arm's name (text).
    cluster : int or None
        The prototype's cluster (dimensionless).
    flagged : bool
        The transfer flagged samples (or computed none): infeasible whatever the limits.
    ratios : dict of str to float or None
        ``velocity``, ``acceleration``, ``torque`` -> rho_K = max_j peak ``|x_j|`` / x_j^max
        (dimensionless); None where the arm has no such limit; NaN when no sample was computed.
    limits : dict of str to numpy.ndarray or None
        The limits assumed, per joint: velocity (rad/s), acceleration (rad/s^2), torque (N m); None where
        the arm has none.
    """

    robot: str
    cluster: int | None
    flagged: bool
    ratios: dict[str, float | None]
    limits: dict[str, np.ndarray | None]

    def _holds(self, kind: str, scale: float) -> bool:
        rho = self.ratios[kind]
        return rho is None or bool(rho <= scale * (1 + QD_LIMIT_RTOL))

    def feasible_at(self, kind: str | None = None, scale: float = 1.0) -> bool:
        """The verdict with every limit of ``kind`` scaled by ``scale``, the others as assumed.

        Parameters
        ----------
        kind : str, optional
            ``velocity``, ``acceleration`` or ``torque`` (text); None for the limits as assumed.
        scale : float
            The factor applied to every joint's limit of that kind (dimensionless, > 0).

        Returns
        -------
        bool
            Feasible as recorded: nothing flagged and rho_L <= 1 for every other kind L, rho_K <= scale.

        Raises
        ------
        ValueError
            An unknown kind, or a scale that is not positive.
        """
        if kind is not None:
            _check_kind(kind)
        if not scale > 0:
            raise ValueError(f"scale must be positive (dimensionless), got {scale}")
        if self.flagged:
            return False
        return all(self._holds(k, scale if k == kind else 1.0) for k in LIMIT_NAMES)

    @property
    def feasible(self) -> bool:
        """The verdict at the limits assumed (equals :attr:`JointDynamics.feasible`)."""
        return self.feasible_at()

    def critical_scale(self, kind: str) -> float | None:
        """The factor on the limits of ``kind`` at which the verdict flips: rho_K (dimensionless).

        Feasible for every scale >= rho_K, infeasible below. None when the arm has no such limit, the
        transfer is flagged, or another kind's limit fails as assumed (no scale of ``kind`` alone flips it).

        Parameters
        ----------
        kind : str
            ``velocity``, ``acceleration`` or ``torque`` (text).

        Returns
        -------
        float or None
            rho_K (dimensionless), or None.
        """
        _check_kind(kind)
        rho = self.ratios[kind]
        if rho is None or not np.isfinite(rho) or self.flagged:
            return None
        if not all(self._holds(k, 1.0) for k in LIMIT_NAMES if k != kind):
            return None
        return float(rho)

    def critical_limit(self, kind: str) -> np.ndarray | None:
        """The limits of ``kind`` at which the verdict flips: rho_K times the assumed ones, per joint.

        Parameters
        ----------
        kind : str
            ``velocity``, ``acceleration`` or ``torque`` (text).

        Returns
        -------
        numpy.ndarray, shape (n,), or None
            The critical limits (rad/s, rad/s^2 or N m), None as :meth:`critical_scale`.
        """
        scale = self.critical_scale(kind)
        lim = self.limits[kind]
        return None if scale is None or lim is None else scale * lim


def _check_kind(kind: str) -> None:
    if kind not in LIMIT_NAMES:
        raise ValueError(f"unknown limit {kind!r}; valid: {', '.join(LIMIT_NAMES)}")


def _ratio(x: np.ndarray | None, limits: np.ndarray | None, ok: np.ndarray) -> float | None:
    if limits is None or x is None:
        return None
    if not ok.any():
        return float("nan")
    return float(np.max(np.abs(x[ok]) / limits))


def limit_margin(assessment: JointDynamics | Assessment) -> LimitMargin:
    """The :class:`LimitMargin` of one assessed prototype (its demand ratio under each kind of limit).

    Parameters
    ----------
    assessment : JointDynamics or Assessment
        The prototype's dynamics on one arm, with its limits: qd (rad/s), qdd (rad/s^2), tau (N m).

    Returns
    -------
    LimitMargin
        The demand ratios (dimensionless) and the limits assumed (rad/s, rad/s^2, N m).
    """
    dyn = assessment.dynamics if isinstance(assessment, Assessment) else assessment
    r, ok = dyn.transfer, dyn.ok
    tau = dyn.tau if dyn.tau_limits is not None else None
    return LimitMargin(
        robot=r.robot,
        cluster=r.cluster,
        flagged=bool(r.flags) or not ok.any(),
        ratios={
            "velocity": _ratio(r.qd, r.qd_limits, ok),
            "acceleration": _ratio(dyn.qdd, dyn.qdd_limits, ok),
            "torque": _ratio(tau, dyn.tau_limits, ok),
        },
        limits={"velocity": r.qd_limits, "acceleration": dyn.qdd_limits, "torque": dyn.tau_limits},
    )


def limit_margins(assessments: Iterable[JointDynamics | Assessment]) -> list[LimitMargin]:
    """:func:`limit_margin` of each assessment (one arm's prototypes, in order).

    Parameters
    ----------
    assessments : iterable of JointDynamics or Assessment
        The prototypes' dynamics with their limits: qd (rad/s), qdd (rad/s^2), tau (N m).

    Returns
    -------
    list of LimitMargin
        One per assessment; demand ratios dimensionless.
    """
    return [limit_margin(a) for a in assessments]


def feasible_counts(margins: Sequence[LimitMargin], kind: str, scales: float | Sequence[float]) -> np.ndarray:
    """The number of prototypes feasible as recorded with the limits of ``kind`` scaled by each factor.

    A step function of the scale f: N(f) = #{p : p feasible with ``kind`` scaled by f, the other limits as
    assumed}, non-decreasing, with a step at each prototype's :meth:`LimitMargin.critical_scale`.

    Parameters
    ----------
    margins : sequence of LimitMargin
        One arm's prototypes.
    kind : str
        ``velocity``, ``acceleration`` or ``torque`` (text).
    scales : float or sequence of float
        Factors on every joint's limit of that kind (dimensionless, > 0).

    Returns
    -------
    numpy.ndarray of int
        The count at each scale (prototypes), shape of ``scales``.

    Raises
    ------
    ValueError
        An unknown kind, or a scale that is not positive.
    """
    _check_kind(kind)
    f = np.asarray(scales, dtype=float)
    if not np.all(f > 0):
        raise ValueError(f"scales must be positive (dimensionless), got {f.tolist()}")
    counts = [sum(m.feasible_at(kind, float(x)) for m in margins) for x in f.ravel()]
    return np.asarray(counts, dtype=int).reshape(f.shape)


@dataclass(frozen=True)
class VerdictRange:
    """The scales of one kind of limit over which an arm's count of feasible prototypes stays as assumed.

    Attributes
    ----------
    robot : str
        The arm's name (text).
    kind : str
        ``velocity``, ``acceleration`` or ``torque`` (text).
    count : int
        Prototypes feasible as recorded at the limits assumed, f = 1 (a count, dimensionless).
    lo, hi : float
        The count is ``count`` for every scale f with lo <= f < hi (dimensionless); lo = 0 when no step lies
        at or below 1, hi = inf when none lies above.
    steps : numpy.ndarray
        Every scale at which the count rises by one (sorted, dimensionless; a value twice for a step of two).
    assumed : float or None
        The assumed limit when it is one number for every joint (rad/s, rad/s^2 or N m), else None.
    """

    robot: str
    kind: str
    count: int
    lo: float
    hi: float
    steps: np.ndarray
    assumed: float | None

    @property
    def limit_range(self) -> tuple[float, float] | None:
        """(lo, hi) times the assumed limit, in its unit; None when the limit differs between joints."""
        return None if self.assumed is None else (self.lo * self.assumed, self.hi * self.assumed)

    def scale_for(self, count: int) -> float:
        """The smallest scale at which at least ``count`` prototypes are feasible as recorded.

        Parameters
        ----------
        count : int
            The number of prototypes asked for (dimensionless).

        Returns
        -------
        float
            The scale (dimensionless): 0 for a count of 0 or less, inf when no scale of this limit alone
            reaches ``count``.
        """
        if count <= 0:
            return 0.0
        return float(self.steps[count - 1]) if count <= self.steps.size else float("inf")

    @property
    def saturates_at(self) -> float:
        """The scale from which raising this limit adds no prototype (the largest step; 0 without steps)."""
        return float(self.steps.max()) if self.steps.size else 0.0


def verdict_range(margins: Sequence[LimitMargin], kind: str) -> VerdictRange | None:
    """The range of scales of the limits of ``kind`` over which the count of feasible prototypes stays.

    Parameters
    ----------
    margins : sequence of LimitMargin
        One arm's prototypes (at least one), as :func:`limit_margins` gives them.
    kind : str
        ``velocity``, ``acceleration`` or ``torque`` (text).

    Returns
    -------
    VerdictRange or None
        The count at the assumed limits (prototypes), the range [lo, hi) of scales (dimensionless) and, for
        a limit that is one number for every joint, that number (rad/s, rad/s^2, N m); None when the arm has
        no limit of this kind.

    Raises
    ------
    ValueError
        No margins, margins of several arms, or an unknown kind.
    """
    _check_kind(kind)
    if not margins:
        raise ValueError("verdict_range needs the margins of at least one prototype")
    robots = {m.robot for m in margins}
    if len(robots) > 1:
        raise ValueError(f"verdict_range takes one arm's prototypes, got {sorted(robots)}")
    lim = margins[0].limits[kind]
    if lim is None:
        return None
    steps = np.sort([s for m in margins if (s := m.critical_scale(kind)) is not None])
    tol = 1 + QD_LIMIT_RTOL
    below, above = steps[steps <= tol], steps[steps > tol]
    return VerdictRange(
        robot=margins[0].robot,
        kind=kind,
        count=sum(m.feasible for m in margins),
        lo=float(below.max()) if below.size else 0.0,
        hi=float(above.min()) if above.size else float("inf"),
        steps=steps,
        assumed=float(lim[0]) if np.all(lim == lim[0]) else None,
    )


def limit_sensitivity(by_arm: Mapping[str, Sequence[JointDynamics | Assessment]]) -> pd.DataFrame:
    """The table of :func:`verdict_range` for every arm and every kind of limit it has.

    Parameters
    ----------
    by_arm : mapping of str to sequence of JointDynamics or Assessment
        Arm name (text) -> its prototypes' assessments: qd (rad/s), qdd (rad/s^2), tau (N m).

    Returns
    -------
    pandas.DataFrame
        Indexed by (``robot``, ``limit``); columns ``feasible`` (count at the assumed limits), ``scale_from``
        and ``scale_to`` (the range [from, to) of factors keeping that count, dimensionless), ``assumed``,
        ``limit_from`` and ``limit_to`` (the same in the limit's ``unit`` when the limit is one number for every
        joint, else NaN), ``saturates_at`` (the factor from which raising the limit adds no prototype) and
        ``unit`` (text).
    """
    rows = []
    for margins in (limit_margins(a) for a in by_arm.values()):
        for kind in LIMIT_NAMES:
            v = verdict_range(margins, kind)
            if v is None:
                continue
            a = np.nan if v.assumed is None else v.assumed
            rows.append(
                {
                    "robot": v.robot,
                    "limit": kind,
                    "feasible": v.count,
                    "scale_from": v.lo,
                    "scale_to": v.hi,
                    "assumed": a,
                    "limit_from": v.lo * a,
                    "limit_to": v.hi * a,
                    "saturates_at": v.saturates_at,
                    "unit": LIMIT_UNITS[kind],
                }
            )
    return pd.DataFrame(rows).set_index(["robot", "limit"])
