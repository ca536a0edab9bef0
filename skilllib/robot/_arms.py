"""The robot arms of the book: Simple6 (the paper's arm) and three arms shipped by roboticstoolbox.

The paper transfers its prototypes to *Simple6*, the generic 6-DOF arm of the MATLAB Robotics
Toolbox 10 (``mdl_simple6``; Corke 2017, *Robotics, Vision and Control*, 2nd ed., Springer).
roboticstoolbox-python does not ship it, so :func:`simple6` builds it from its standard
Denavit-Hartenberg table (lengths in m, angles in rad):

===== === === ======
joint  d   a  alpha
===== === === ======
1      0   0  +pi/2
2      0   1   0
3      0   1  -pi/2
4      0   0  -pi/2
5      0   0  +pi/2
6      0   0   0
===== === === ======

Two 1 m links (shoulder-elbow, elbow-wrist) and a spherical wrist whose three axes meet at the
tool point (no tool offset). At the paper's default pose :data:`DEFAULT_POSE_DEG` the tool point
is at (1, 0, 0) m in the base frame.

Joint velocity limits (rad/s), the numbers the feasibility check compares with:

* Simple6 has none (it is a kinematic model only). The book uses :data:`GENERIC_QD_LIMIT` = pi rad/s
  (180 deg/s) on every joint: the joint speed of the Universal Robots UR5 (CB3 technical
  specifications: 180 deg/s on all joints), a typical value for small industrial and collaborative
  arms. Simple6's links (1 m) are longer than a UR5's (0.43 m), so for the same joint speed its
  tool moves faster: the limit is a design assumption, not a property of Simple6.
* UR5: pi rad/s on all joints (the datasheet value above).
* Puma 560: no velocity limits in roboticstoolbox's model; the book uses the same generic
  pi rad/s (an assumption, not a Unimation datasheet value).
* Panda: the Franka Emika datasheet limits, (2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61) rad/s,
  the ``qdlim`` of roboticstoolbox's URDF model ``rtb.models.Panda()``.

Joint acceleration limits (rad/s^2) and joint torque limits (N m), :func:`dynamic_limits`:

* Simple6: no dynamic parameters (every link mass is 0), so no torques; the book gives it the UR5's
  acceleration value below, :data:`GENERIC_QDD_LIMIT` = 5 rad/s^2 on every joint, as it gives it the UR5's
  joint speed: a design assumption.
* UR5: Universal Robots publish no joint acceleration limits (the arm limits torques only); their own
  MoveIt configuration (Universal_Robots_ROS2_Driver, ``ur_moveit_config/config/joint_limits.yaml``) uses
  5 rad/s^2 on every joint, "chosen conservatively". Torques: (150, 150, 150, 28, 28, 28) N m, UR's
  support article "Max. joint torques" for the UR5 (CB3), as in ``Universal_Robots_ROS2_Description``
  ``config/ur5/joint_limits.yaml``. roboticstoolbox's UR5 model carries the link masses and centres of
  mass UR publish but no link inertias, so its torques are those of point masses.
* Puma 560: torques (97.6, 186.4, 89.4, 24.2, 20.1, 21.3) N m, the maximum joint torques of Armstrong,
  Khatib & Burdick (1986, "The explicit dynamic model and inertial parameters of the PUMA 560 arm", ICRA,
  Table 7). No separate acceleration limit: with a dynamic model (roboticstoolbox's, Corke &
  Armstrong-Helouvry 1994, with motor inertias, gear ratios and friction) the torque limits bound the
  accelerations.
* Panda: the Franka Emika datasheet ("Robot and interface specifications" of the Franka Control Interface),
  accelerations (15, 7.5, 10, 12.5, 15, 20, 20) rad/s^2 and torques (87, 87, 87, 87, 12, 12, 12) N m;
  roboticstoolbox's DH model carries masses, centres of mass and inertias of every link.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

if TYPE_CHECKING:  # roboticstoolbox takes about a second to import: only when an arm is built
    import roboticstoolbox as rtb

#: The paper's default dexterous pose of Simple6, deg (q1..q6).
DEFAULT_POSE_DEG: tuple[float, ...] = (0.0, -60.0, 120.0, 90.0, -90.0, 30.0)

#: The book's generic joint velocity limit, rad/s (180 deg/s; UR5 CB3 joint speed).
GENERIC_QD_LIMIT: float = float(np.pi)

#: Franka Emika Panda joint velocity limits, rad/s (datasheet; ``rtb.models.Panda().qdlim[:7]``).
PANDA_QD_LIMITS: tuple[float, ...] = (2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61)

#: The book's generic joint acceleration limit, rad/s^2: the value Universal Robots' MoveIt configuration
#: uses for every UR5 joint (UR publish no acceleration limit).
GENERIC_QDD_LIMIT: float = 5.0

#: Franka Emika Panda joint acceleration limits, rad/s^2 (datasheet).
PANDA_QDD_LIMITS: tuple[float, ...] = (15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0)

#: Franka Emika Panda joint jerk limits, rad/s^3 (datasheet; reported beside the jerks, not enforced).
PANDA_QDDD_LIMITS: tuple[float, ...] = (7500.0, 3750.0, 5000.0, 6250.0, 7500.0, 10000.0, 10000.0)

#: Joint torque limits, N m: Panda (datasheet), UR5 (UR "Max. joint torques"), Puma 560 (Armstrong et al. 1986).
PANDA_TAU_LIMITS: tuple[float, ...] = (87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0)
UR5_TAU_LIMITS: tuple[float, ...] = (150.0, 150.0, 150.0, 28.0, 28.0, 28.0)
PUMA560_TAU_LIMITS: tuple[float, ...] = (97.6, 186.4, 89.4, 24.2, 20.1, 21.3)

#: Start poses (deg) of the other arms: reachable, inside the joint limits, well conditioned
#: (cond J about 8 to 9) along a 0.35 m vertical descent with the orientation held fixed.
UR5_Q0_DEG: tuple[float, ...] = (0.0, -90.0, 90.0, -90.0, -90.0, 0.0)  # tool pointing down
PUMA560_Q0_DEG: tuple[float, ...] = (0.0, 45.0, -180.0, 0.0, 45.0, 0.0)  # Corke's nominal pose qn
#: The Panda's ready pose ``qr`` of roboticstoolbox, tool pointing (almost) down.
PANDA_Q0_RAD: tuple[float, ...] = (0.0, -0.3, 0.0, -2.2, 0.0, 2.0, np.pi / 4)

#: The names :func:`get_robot` accepts.
ROBOT_NAMES: tuple[str, ...] = ("simple6", "ur5", "puma560", "panda")


Limits = float | Sequence[float] | np.ndarray


@dataclass(frozen=True, eq=False)
class Arm:
    """A robot arm as the transfer uses it: the model, its start pose and every joint limit checked.

    Made by :func:`get_robot` (the book's arms, with the user's overrides); :meth:`with_limits` gives the
    same arm with other limits.

    Attributes
    ----------
    name : str
        The name :func:`get_robot` knows it by (``simple6``, ``ur5``, ``puma560``, ``panda``).
    robot : roboticstoolbox.Robot
        The kinematic (and, where the model has them, dynamic) model.
    q0 : numpy.ndarray
        Start pose, (n,) rad: its tool point receives the movement's start, its orientation is kept.
    qd_limits : numpy.ndarray
        Joint velocity limits, (n,) rad/s.
    qdd_limits : numpy.ndarray or None
        Joint acceleration limits, (n,) rad/s^2; None where the arm has none.
    tau_limits : numpy.ndarray or None
        Joint torque limits, (n,) N m; None without dynamic parameters.
    """

    name: str
    robot: rtb.Robot
    q0: np.ndarray
    qd_limits: np.ndarray
    qdd_limits: np.ndarray | None
    tau_limits: np.ndarray | None

    @property
    def n(self) -> int:
        """The number of joints."""
        return int(self.robot.n)

    @property
    def dynamic_limits(self) -> DynamicLimits:
        """The acceleration (rad/s^2) and torque (N m) limits, as :func:`skilllib.robot.assess` takes them."""
        return DynamicLimits(self.qdd_limits, self.tau_limits)

    def with_limits(
        self, qd_max: Limits | None = None, qdd_max: Limits | None = None, tau_max: Limits | None = None
    ) -> Arm:
        """The same arm with the user's limits where given (one value for every joint, or one per joint).

        Parameters
        ----------
        qd_max : float or sequence of float, optional
            Joint velocity limits, rad/s.
        qdd_max : float or sequence of float, optional
            Joint acceleration limits, rad/s^2.
        tau_max : float or sequence of float, optional
            Joint torque limits, N m; only for an arm with dynamic parameters.

        Returns
        -------
        Arm
            A new arm; the limits not given are this arm's.

        Raises
        ------
        ValueError
            A limit of the wrong length, not positive or not finite (the message names the option and its
            unit), or torque limits for an arm without dynamic parameters.
        """
        n = self.n
        qd = self.qd_limits if qd_max is None else limits_vector(qd_max, n, "qd_max", "rad/s")
        qdd = self.qdd_limits if qdd_max is None else limits_vector(qdd_max, n, "qdd_max", "rad/s^2")
        if tau_max is not None and not has_dynamics(self.robot):
            raise ValueError(
                f"tau_max: {self.robot.name} has no dynamic parameters (a kinematic model), so no torques "
                f"to limit; choose an arm with dynamics (ur5, puma560, panda)"
            )
        tau = self.tau_limits if tau_max is None else limits_vector(tau_max, n, "tau_max", "N m")
        return replace(self, qd_limits=qd, qdd_limits=qdd, tau_limits=tau)


def simple6() -> rtb.DHRobot:
    """Simple6, the generic 6-DOF arm of the MATLAB Robotics Toolbox 10 (``mdl_simple6``).

    Standard DH (Corke 2017, sec. 7.1), L1 = L2 = 1 m, revolute joints, no joint limits in the
    original model (roboticstoolbox stores the default +-pi rad); named poses ``qz`` (zero) and
    ``qn`` (the paper's default dexterous pose, :data:`DEFAULT_POSE_DEG`).

    Returns
    -------
    roboticstoolbox.DHRobot
        The kinematic model (link lengths in m, joint angles in rad), without dynamic parameters.
    """
    import roboticstoolbox as rtb

    links = [
        rtb.RevoluteDH(d=0.0, a=0.0, alpha=np.pi / 2),
        rtb.RevoluteDH(d=0.0, a=1.0, alpha=0.0),
        rtb.RevoluteDH(d=0.0, a=1.0, alpha=-np.pi / 2),
        rtb.RevoluteDH(d=0.0, a=0.0, alpha=-np.pi / 2),
        rtb.RevoluteDH(d=0.0, a=0.0, alpha=np.pi / 2),
        rtb.RevoluteDH(d=0.0, a=0.0, alpha=0.0),
    ]
    robot = rtb.DHRobot(links, name="Simple6", manufacturer="MATLAB Robotics Toolbox 10 (generic)")
    robot.addconfiguration_attr("qz", np.zeros(6))
    robot.addconfiguration_attr("qn", np.deg2rad(DEFAULT_POSE_DEG))
    return robot


def default_pose() -> np.ndarray:
    """The paper's default dexterous pose of Simple6 as a (6,) array in rad.

    Returns
    -------
    numpy.ndarray, shape (6,)
        The joint angles q1..q6 of :data:`DEFAULT_POSE_DEG` (rad).
    """
    return np.deg2rad(np.asarray(DEFAULT_POSE_DEG, dtype=float))


def qd_limits_vector(qd_limits: float | np.ndarray | list[float] | tuple[float, ...], n: int) -> np.ndarray:
    """Joint velocity limits (rad/s) as an (n,) array; a scalar applies to every joint.

    Parameters
    ----------
    qd_limits : float or array_like of float
        One joint velocity limit for every joint, or one per joint (rad/s).
    n : int
        The number of joints (dimensionless).

    Returns
    -------
    numpy.ndarray, shape (n,)
        The joint velocity limits (rad/s).

    Raises
    ------
    ValueError
        When the length is not 1 or ``n`` or a limit is not positive and finite.
    """
    return limits_vector(qd_limits, n, "qd_limits", "rad/s")


def get_robot(
    name: str, *, qd_max: Limits | None = None, qdd_max: Limits | None = None, tau_max: Limits | None = None
) -> Arm:
    """An arm by name, with its start pose and every limit the book checks (or the user's).

    Names (case-insensitive): ``"simple6"`` (the paper's arm at :data:`DEFAULT_POSE_DEG`),
    ``"ur5"`` and ``"puma560"`` (roboticstoolbox's DH models with their joint limits ``qlim``),
    ``"panda"`` (the 7-DOF DH model of the Franka Emika Panda: redundant, so the transfer uses the
    pseudo-inverse). The limits and poses are justified in the module docstring.

    Parameters
    ----------
    name : str
        One of :data:`ROBOT_NAMES`, any case.
    qd_max, qdd_max, tau_max : float or sequence of float, optional
        The user's joint velocity (rad/s), acceleration (rad/s^2) and torque (N m) limits, one value for
        every joint or one per joint, in place of the book's (:meth:`Arm.with_limits`).

    Returns
    -------
    Arm
        The arm, its start pose ``q0`` (rad) and its limits.

    Raises
    ------
    ValueError
        An unknown name, or a bad limit (:meth:`Arm.with_limits`).
    """
    import roboticstoolbox as rtb

    key = str(name).strip().lower()
    if key == "simple6":
        robot = simple6()
        q0 = default_pose()
        lim = qd_limits_vector(GENERIC_QD_LIMIT, 6)
    elif key == "ur5":
        robot = rtb.models.DH.UR5()
        q0 = np.deg2rad(UR5_Q0_DEG)
        lim = qd_limits_vector(GENERIC_QD_LIMIT, 6)
    elif key == "puma560":
        robot = rtb.models.DH.Puma560()
        q0 = np.deg2rad(PUMA560_Q0_DEG)
        lim = qd_limits_vector(GENERIC_QD_LIMIT, 6)
    elif key == "panda":
        robot = rtb.models.DH.Panda()
        q0 = np.asarray(PANDA_Q0_RAD, dtype=float)
        lim = np.asarray(PANDA_QD_LIMITS, dtype=float)
    else:
        raise ValueError(f"unknown robot {name!r}; valid names: {', '.join(ROBOT_NAMES)}")
    book = dynamic_limits(key)
    arm = Arm(key, robot, np.asarray(q0, dtype=float), lim, book.qdd_limits, book.tau_limits)
    return arm.with_limits(qd_max, qdd_max, tau_max)


class DynamicLimits(NamedTuple):
    """Joint acceleration limits ``qdd_limits`` (rad/s^2) and torque limits ``tau_limits`` (N m), each an
    (n,) array or None where the arm has none (see the module docstring for the values and sources)."""

    qdd_limits: np.ndarray | None
    tau_limits: np.ndarray | None


def has_dynamics(robot: rtb.Robot) -> bool:
    """True when the model carries dynamic parameters (some link has a mass), so that inverse dynamics
    (``rne``) gives torques; Simple6 has none.

    Parameters
    ----------
    robot : roboticstoolbox.Robot
        The arm's model; only its links' masses are read.

    Returns
    -------
    bool
        True when some link has a positive mass (dimensionless).
    """
    return any(float(getattr(link, "m", 0.0) or 0.0) > 0 for link in robot.links)


def dynamic_limits(name: str) -> DynamicLimits:
    """The book's acceleration and torque limits of an arm by name (as :func:`get_robot`).

    Parameters
    ----------
    name : str
        One of :data:`ROBOT_NAMES`, any case (text).

    Returns
    -------
    DynamicLimits
        ``qdd_limits`` (n,) rad/s^2 and ``tau_limits`` (n,) N m, each None where the arm has none.

    Raises
    ------
    ValueError
        An unknown name.
    """
    key = str(name).strip().lower()
    table = {
        "simple6": (GENERIC_QDD_LIMIT, None),
        "ur5": (GENERIC_QDD_LIMIT, UR5_TAU_LIMITS),
        "puma560": (None, PUMA560_TAU_LIMITS),
        "panda": (PANDA_QDD_LIMITS, PANDA_TAU_LIMITS),
    }
    if key not in table:
        raise ValueError(f"unknown robot {name!r}; valid names: {', '.join(ROBOT_NAMES)}")
    n = 7 if key == "panda" else 6
    qdd, tau = table[key]
    return DynamicLimits(
        None if qdd is None else limits_vector(qdd, n, "qdd_limits", "rad/s^2"),
        None if tau is None else limits_vector(tau, n, "tau_limits", "N m"),
    )


def limits_vector(
    limits: float | np.ndarray | list[float] | tuple[float, ...], n: int, what: str, unit: str
) -> np.ndarray:
    """Per-joint limits as an (n,) array (a scalar applies to every joint); ValueError naming ``what`` and
    ``unit`` when the length is not 1 or ``n`` or a limit is not positive and finite."""
    lim = np.asarray(limits, dtype=float)
    if lim.ndim == 0:
        lim = np.full(n, float(lim))
    if lim.shape != (n,):
        raise ValueError(f"{what} must be a scalar or have {n} entries (one per joint), got shape {lim.shape}")
    if not np.all(np.isfinite(lim)) or np.any(lim <= 0):
        raise ValueError(f"{what} must be positive and finite ({unit}), got {lim.tolist()}")
    return lim


def joint_origins(robot: rtb.DHRobot, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Positions (n, 3) m and unit axes (n, 3) of the joints of a standard-DH arm in the base frame.

    Joint j turns about the z axis of DH frame j-1 through its origin (Corke 2017, sec. 7.1.1),
    so both come from ``fkine_all``. Used to label the joints in the figures.

    Parameters
    ----------
    robot : roboticstoolbox.DHRobot
        A standard-DH arm.
    q : numpy.ndarray, shape (n,)
        The joint angles (rad).

    Returns
    -------
    positions : numpy.ndarray, shape (n, 3)
        The joints' positions in the base frame (m).
    axes : numpy.ndarray, shape (n, 3)
        The joints' unit axes in the base frame (dimensionless).
    """
    frames = robot.fkine_all(np.asarray(q, dtype=float))
    pos = np.array([frames[j].t for j in range(robot.n)])
    axes = np.array([frames[j].R[:, 2] for j in range(robot.n)])
    return pos, axes
