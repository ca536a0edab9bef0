"""Inverse kinematics that does not give up inside the workspace: a chain of searches and solvers.

The transfer (:mod:`skilllib.robot`) asks, at every sample, for joint angles q (rad) whose tool pose
is the target (position m, orientation held fixed). Near a singularity a single Levenberg-Marquardt
search seeded with the previous solution can stall although a solution exists: the stretched elbow of
Simple6 is one such place. :func:`solve_ik` therefore runs the searches of :data:`IK_CHAIN` in turn
until one returns an acceptable pose:

1. ``ikine_LM`` seeded with the previous sample's solution (stays on the arm's branch);
2. ``ikine_LM`` again, with :data:`IK_RESTARTS` random restarts (seeded with the sample index, so a run
   is reproducible);
3. ``ikine_GN``, Gauss-Newton with the pseudo-inverse of J (``pinv=True``: defined at a singularity),
   with as many seeded restarts;
4. ``ikine_LM`` with Sugihara's damping (E + w_n I; ``method="sugihara"``), which stays well-posed
   where J loses rank, with as many seeded restarts.

All are roboticstoolbox's compiled solvers (Corke 2017, sec. 7.2.2; Haviland & Corke 2023, "Manipulator
differential kinematics", part I). Every search draws its restarts inside the joint limits and rejects
solutions outside them (``joint_limits=True``: a joint-limit-aware search); a pose is accepted here only
when its position residual (m) and orientation residual (rad) are within ``tol`` and every joint lies
within ``qlim`` (``ikine_*`` tolerances bound E = 0.5 e'e, not the distance, so they are asked for
1e-14 and the residual is checked here). Whether a target is reachable at all is not decided here but
geometrically (:mod:`skilllib.robot`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import roboticstoolbox as rtb

#: Random restarts of each restarting search (seeded with the sample index).
IK_RESTARTS: int = 10

#: The searches of :func:`solve_ik`, in order: (name, ETS method, keyword arguments, restart?).
IK_CHAIN: tuple[tuple[str, str, dict, bool], ...] = (
    ("LM seeded", "ikine_LM", {}, False),
    ("LM restarts", "ikine_LM", {}, True),
    ("GN pinv restarts", "ikine_GN", {"pinv": True}, True),
    ("LM Sugihara restarts", "ikine_LM", {"method": "sugihara"}, True),
)


class IKAnswer(NamedTuple):
    """What :func:`solve_ik` found: ``q`` (rad; the best attempt when not ``ok``), ``residual_m`` (its
    position residual, m), ``ok``, ``solver`` (the name in :data:`IK_CHAIN` that succeeded, or ""),
    and of the best attempt its orientation residual ``orientation_rad`` and the joints (1-based) outside
    their limits ``outside``.

    Attributes
    ----------
    q : numpy.ndarray, shape (n,)
        The joint angles found, or the best attempt's (rad).
    residual_m : float
        Their position residual (m).
    ok : bool
        True when the pose was accepted (dimensionless).
    solver : str
        The name in :data:`IK_CHAIN` of the search that succeeded, or "" (text).
    orientation_rad : float
        The orientation residual, the angle of the relative rotation (rad).
    outside : tuple of int
        The joints (1-based) outside their limits (dimensionless).
    """

    q: np.ndarray
    residual_m: float
    ok: bool
    solver: str
    orientation_rad: float = float("nan")
    outside: tuple[int, ...] = ()

    def why(self) -> str:
        """Why the best attempt was not accepted, for a flag: its residuals and the joints outside limits."""
        text = f"best position residual {self.residual_m:.3g} m, orientation {self.orientation_rad:.3g} rad"
        if self.outside:
            text += ", outside the joint limits at " + ", ".join(f"q{j}" for j in self.outside)
        return text


def pose_residual(ets: rtb.ETS, q: np.ndarray, target: np.ndarray) -> tuple[float, float]:
    """Position (m) and orientation (rad, angle of the relative rotation) residual of the tool pose at
    ``q`` against the 4x4 ``target``.

    Parameters
    ----------
    ets : roboticstoolbox.ETS
        The arm's elementary transform sequence.
    q : numpy.ndarray, shape (n,)
        The joint angles (rad).
    target : numpy.ndarray, shape (4, 4)
        The target tool pose, a homogeneous transform in the base frame (translation in m).

    Returns
    -------
    position : float
        The distance of the tool point from the target's (m).
    orientation : float
        The angle of the rotation from the target's orientation to the tool's (rad).
    """
    T = ets.eval(q)
    dp = float(np.linalg.norm(T[:3, 3] - target[:3, 3]))
    c = (np.trace(target[:3, :3].T @ T[:3, :3]) - 1.0) / 2.0
    return dp, float(np.arccos(np.clip(c, -1.0, 1.0)))


def solve_ik(
    ets: rtb.ETS,
    target: np.ndarray,
    seed_q: np.ndarray,
    k: int,
    *,
    tol: float,
    joint_tol: float,
    restarts: int = IK_RESTARTS,
) -> IKAnswer:
    """IK for one sample: the searches of :data:`IK_CHAIN` from ``seed_q`` (rad) until one gives a pose
    within ``tol`` (m and rad) of the 4x4 ``target`` and inside the joint limits (``joint_tol`` rad).

    ``k`` seeds the random restarts (reproducible); ``restarts`` is their number per restarting search
    (0: only the seeded search). Returns an :class:`IKAnswer`; when nothing is accepted, the attempt with
    the smallest position residual.

    Parameters
    ----------
    ets : roboticstoolbox.ETS
        The arm's elementary transform sequence, with its joint limits ``qlim`` (rad).
    target : numpy.ndarray, shape (4, 4)
        The target tool pose, a homogeneous transform in the base frame (translation in m).
    seed_q : numpy.ndarray, shape (n,)
        The seed, normally the previous sample's solution (rad).
    k : int
        The seed of the random restarts, normally the sample index (samples).
    tol : float
        The largest accepted position residual (m) and orientation residual (rad).
    joint_tol : float
        The tolerance of the joint-limit check (rad).
    restarts : int
        Random restarts per restarting search; 0 for only the seeded search (dimensionless).

    Returns
    -------
    IKAnswer
        The accepted pose (rad) with its residuals (m, rad), or the best attempt with ``ok`` False.
    """
    qlim = np.asarray(ets.qlim, dtype=float)
    best = IKAnswer(np.asarray(seed_q, dtype=float), np.inf, False, "")
    for name, method, kwargs, restarting in IK_CHAIN:
        if restarting and restarts <= 0:
            continue
        slimit, seed = (restarts + 1, k) if restarting else (1, None)
        sol = getattr(ets, method)(
            target, q0=seed_q, tol=1e-14, ilimit=50, slimit=slimit, joint_limits=True, seed=seed, **kwargs
        )
        q = np.asarray(sol.q, dtype=float)
        if not np.all(np.isfinite(q)):
            continue
        dp, dr = pose_residual(ets, q, target)
        outside = tuple(int(j) + 1 for j in np.flatnonzero((q < qlim[0] - joint_tol) | (q > qlim[1] + joint_tol)))
        if dp <= tol and dr <= tol and not outside:
            return IKAnswer(q, dp, True, name, dr)
        if dp < best.residual_m:
            best = IKAnswer(q, dp, False, "", dr, outside)
    return best
