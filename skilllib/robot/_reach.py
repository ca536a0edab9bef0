"""The reachable workspace of an arm, checked geometrically: may a tool point be reached at all?

The transfer (:mod:`skilllib.robot`) calls a target *unreachable* only when it lies outside the
arm's workspace, not when an IK search fails (:mod:`skilllib.robot` retries; a failure inside the
workspace is reported as an IK failure). The workspace is bounded here by a **reach shell**:

* the **shoulder point** S is where the axes of joints 1 and 2 meet (Simple6, Puma 560, UR5 and
  Panda: on the base's vertical axis at the height of the shoulder). The joint axes come from the
  Jacobian at any pose: column j of ``jacob0`` is (w_j x (p - o_j), w_j) for a revolute joint with unit
  axis w_j through o_j, so p + w_j x v_j is the point of axis j nearest the tool point p.
* Rotating about an axis that passes through S does not change a point's distance from S, so the
  distance ``r(q) = |p(q) - S|`` of the tool point does not depend on q1 and q2 (nor on the last joint when
  the tool point lies on its axis). Its range [r_min, r_max] over the joint limits ``qlim`` is found
  numerically: a seeded random sample of poses, then bounded local optimisation (L-BFGS-B) from the
  best of them, for the largest and the smallest distance.

Every reachable tool point satisfies ``r_min <= |p - S| <= r_max``, whatever the orientation, so a target
outside the shell is certainly out of reach (:data:`REACH_TOL_M` allows for rounding). Inside the shell a
target may still be unreachable with the orientation the transfer holds or within the joint limits; that
is never decided here. For Simple6 (two 1 m links, spherical wrist at the tool point, no tool offset) the
shell is exact: 0 to 2 m from the shoulder (Corke 2017, sec. 7.1; the paper's arm). For the Puma 560 the
largest distance has a closed form, sqrt(d3^2 + (a2 + sqrt(a3^2 + d4^2))^2) = 0.877 m (its wrist centre
is the tool point; the tests compare).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import roboticstoolbox as rtb
from scipy.optimize import minimize

#: Tolerance (m) of the reach test: a target this far beyond the shell still counts as inside.
REACH_TOL_M: float = 1e-6

#: Random poses (seeded) sampled before the local optimisation of the reach shell.
REACH_SAMPLES: int = 2000

#: Best samples refined by L-BFGS-B, for each of the largest and the smallest distance.
REACH_REFINE: int = 4


@dataclass(frozen=True)
class ReachShell:
    """The distances from the shoulder point ``shoulder`` (3,) m, base frame, that the tool point can
    take within the joint limits: ``r_min`` to ``r_max`` (m)."""

    robot: str
    shoulder: np.ndarray
    r_min: float
    r_max: float

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distance (m) of base-frame points (N, 3) or (3,) from the shoulder point."""
        return np.linalg.norm(np.asarray(points, dtype=float) - self.shoulder, axis=-1)

    def outside(self, points: np.ndarray, tol: float = REACH_TOL_M) -> np.ndarray:
        """True where a base-frame point (m) lies outside the shell by more than ``tol`` m: out of reach."""
        r = self.distance(points)
        return (r > self.r_max + tol) | (r < self.r_min - tol)

    def describe(self, point: np.ndarray) -> str:
        """'r m from the shoulder, reach r_min to r_max m' for one base-frame point."""
        return (
            f"{float(self.distance(point)):.4g} m from the shoulder; the arm reaches "
            f"{self.r_min:.4g} to {self.r_max:.4g} m"
        )


def joint_axes(ets: rtb.ETS, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit directions (n, 3) and points (n, 3) m of the joint axes at pose ``q`` (rad), base frame.

    From the world-frame Jacobian (Corke 2017, sec. 8.1): column j is (w_j x (p - o_j), w_j) for a
    revolute joint, so o = p + w_j x v_j is the point of axis j nearest the tool point p.

    Parameters
    ----------
    ets : roboticstoolbox.ETS
        The arm's elementary transform sequence, revolute joints only.
    q : numpy.ndarray, shape (n,)
        The joint angles (rad).

    Returns
    -------
    directions : numpy.ndarray, shape (n, 3)
        The unit directions of the joint axes (dimensionless).
    points : numpy.ndarray, shape (n, 3)
        The point of each axis nearest the tool point (m).

    Raises
    ------
    ValueError
        When a joint is not revolute (an angular Jacobian column not of unit length).
    """
    J = ets.jacob0(np.asarray(q, dtype=float))
    p = ets.eval(np.asarray(q, dtype=float))[:3, 3]
    w = J[3:].T
    if np.any(np.abs(np.linalg.norm(w, axis=1) - 1) > 1e-9):
        raise ValueError("the reach shell needs revolute joints only (unit angular Jacobian columns)")
    return w, p + np.cross(w, J[:3].T)


def shoulder_point(ets: rtb.ETS, q: np.ndarray) -> np.ndarray:
    """The point (3,) m where the axes of joints 1 and 2 meet (the midpoint of their common
    perpendicular); ValueError when they are parallel or more than 1e-9 m apart (the shell's distance
    would then depend on q2).

    Parameters
    ----------
    ets : roboticstoolbox.ETS
        The arm's elementary transform sequence, revolute joints only.
    q : numpy.ndarray, shape (n,)
        The joint angles (rad).

    Returns
    -------
    numpy.ndarray, shape (3,)
        The shoulder point in the base frame (m).

    Raises
    ------
    ValueError
        When the axes of joints 1 and 2 are parallel or do not meet, or a joint is not revolute.
    """
    w, o = joint_axes(ets, q)
    (w1, w2), (o1, o2) = w[:2], o[:2]
    n = np.cross(w1, w2)
    if np.linalg.norm(n) < 1e-9:
        raise ValueError("the axes of joints 1 and 2 are parallel: no shoulder point")
    # o1 + a w1 and o2 + b w2 closest: solve the 2x2 normal equations
    A = np.array([[w1 @ w1, -w1 @ w2], [w1 @ w2, -w2 @ w2]])
    a, b = np.linalg.solve(A, [(o2 - o1) @ w1, (o2 - o1) @ w2])
    p1, p2 = o1 + a * w1, o2 + b * w2
    if np.linalg.norm(p1 - p2) > 1e-9:
        raise ValueError(f"the axes of joints 1 and 2 do not meet ({np.linalg.norm(p1 - p2):.3g} m apart)")
    return (p1 + p2) / 2


def reach_shell(robot: rtb.Robot) -> ReachShell:
    """The reach shell of ``robot`` (cached per arm: name, kinematics and joint limits).

    An arm whose first two axes do not meet gets a looser shell around its base origin: 0 to
    ``robot.reach`` (roboticstoolbox's sum of the link lengths, an upper bound) plus the tool offset.

    Parameters
    ----------
    robot : roboticstoolbox.Robot
        The arm, with its joint limits ``qlim`` (rad).

    Returns
    -------
    ReachShell
        The shoulder point (m, base frame) and the smallest and largest distance ``r_min``, ``r_max`` (m)
        of the tool point from it.
    """
    ets = robot.ets()
    qlim = np.asarray(ets.qlim, dtype=float)
    key = (robot.name, str(ets), qlim.tobytes())
    if key not in _SHELLS:
        _SHELLS[key] = _reach_shell(robot.name, ets, robot)
    return _SHELLS[key]


_SHELLS: dict[tuple[str, str, bytes], ReachShell] = {}


def _reach_shell(name: str, ets: rtb.ETS, robot: rtb.Robot) -> ReachShell:
    qlim = np.asarray(ets.qlim, dtype=float)
    q_mid = qlim.mean(axis=0)
    try:
        S = shoulder_point(ets, q_mid)
    except ValueError:
        return ReachShell(
            robot=name,
            shoulder=np.asarray(robot.base.t, dtype=float),
            r_min=0.0,
            r_max=float(robot.reach) + float(np.linalg.norm(robot.tool.t)),
        )

    free = qlim[:, 2:]  # r does not depend on q1 and q2 (their axes pass through S)

    def r(x: np.ndarray) -> float:
        return float(np.linalg.norm(ets.eval(np.r_[q_mid[:2], x])[:3, 3] - S))

    rng = np.random.default_rng(0)
    samples = rng.uniform(free[0], free[1], size=(REACH_SAMPLES, free.shape[1]))
    samples[:3, 0] = free[0, 0], free[1, 0], free[:, 0].mean()  # q3 (the elbow) at its limits and centre
    dist = np.array([r(x) for x in samples])
    bounds = list(zip(free[0], free[1]))
    extremes = []
    for sign in (-1.0, 1.0):  # -1: largest distance, +1: smallest
        best = float(np.min(sign * dist))
        for x in samples[np.argsort(sign * dist)[:REACH_REFINE]]:
            res = minimize(
                lambda y: sign * r(y),  # noqa: B023  (used at once, inside the loop)
                x,
                method="L-BFGS-B",
                bounds=bounds,
                options={"ftol": 1e-15, "gtol": 1e-12, "maxiter": 500},
            )
            best = min(best, float(res.fun))
        extremes.append(sign * best)
    r_max, r_min = extremes
    return ReachShell(robot=name, shoulder=S, r_min=r_min if r_min > REACH_TOL_M else 0.0, r_max=r_max)
