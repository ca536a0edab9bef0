"""Checks of a transfer that the chapters print and the tests make: joint limits, the tool velocity the
joint velocities produce, and the first bin of a speed spectrum a fixed cut-off can add to SPARC's band.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..smoothness import DEFAULT_AMP_TH, DEFAULT_FC, sparc_spectrum
from ._arms import Arm
from ._velocity import TransferResult

if TYPE_CHECKING:
    import roboticstoolbox as rtb


def within_joint_limits(robot: Arm | rtb.Robot, q: np.ndarray) -> bool:
    """Whether every joint angle lies within the arm's joint limits ``qlim``.

    Parameters
    ----------
    robot : Arm or roboticstoolbox.Robot
        The arm; its ``qlim`` (2, n) gives the lower and upper limit of every joint (rad or m).
    q : numpy.ndarray
        The joint angles, (n,) rad (m for a prismatic joint).

    Returns
    -------
    bool
        True when ``qlim[0] <= q <= qlim[1]`` for every joint (no tolerance).
    """
    model = robot.robot if isinstance(robot, Arm) else robot
    q = np.asarray(q, dtype=float)
    qlim = np.asarray(model.qlim, dtype=float)
    return bool(np.all((q >= qlim[0]) & (q <= qlim[1])))


def tool_velocity_error(robot: Arm | rtb.Robot, result: TransferResult) -> float:
    """The largest deviation of the tool velocity ``J(q) qd`` from the commanded one over the samples.

    The commanded spatial velocity is ``(v_base, 0, 0, 0)``: the hand's velocity in the base frame and no
    rotation. Samples without joint angles (unreachable, IK failure) are left out.

    Parameters
    ----------
    robot : Arm or roboticstoolbox.Robot
        The arm the transfer ran on.
    result : TransferResult
        The transfer: joint angles ``q`` (rad), joint velocities ``qd`` (rad/s) and the commanded tool
        velocities ``v_base`` (m/s).

    Returns
    -------
    float
        ``max_k max_i |(J(q_k) qd_k - v_k)_i|``, m/s for the linear and rad/s for the angular rows; NaN
        when no sample was computed.

    Raises
    ------
    ValueError
        A result without commanded velocities ``v_base``.
    """
    if result.v_base is None:
        raise ValueError("the transfer result carries no commanded tool velocities (v_base)")
    ets = (robot.robot if isinstance(robot, Arm) else robot).ets()
    ok = np.all(np.isfinite(result.q), axis=1) & np.all(np.isfinite(result.qd), axis=1)
    if not ok.any():
        return float("nan")
    v = np.hstack([result.v_base, np.zeros((len(result.v_base), 3))])
    return float(max(np.abs(ets.jacob0(q) @ qd - vk).max() for q, qd, vk in zip(result.q[ok], result.qd[ok], v[ok])))


def next_band_frequency(speed: np.ndarray, fs: float, fc: float = DEFAULT_FC, amp_th: float = DEFAULT_AMP_TH) -> float:
    """The lowest frequency above the cut-off at which a speed profile's spectrum reaches SPARC's threshold.

    A recording of the movement slowed by ``s`` and measured with the fixed cut-off ``fc`` takes into its
    band what lay up to ``s fc`` in the original spectrum: the first bin above ``fc`` (and at or below the
    Nyquist frequency ``fs / 2``) whose normalised magnitude reaches ``amp_th`` gives the stretch
    ``s* = f / fc`` from which it can. Such a bin is what makes a band *capped*.

    Parameters
    ----------
    speed : numpy.ndarray
        The speed profile, (N,) m/s.
    fs : float
        Its sampling rate, Hz.
    fc : float
        SPARC's maximum cut-off, Hz.
    amp_th : float
        SPARC's amplitude threshold on the normalised magnitude, dimensionless.

    Returns
    -------
    float
        The frequency, Hz; inf when no bin between ``fc`` and ``fs / 2`` reaches ``amp_th``.
    """
    sp = sparc_spectrum(np.asarray(speed, dtype=float), fs, fc=fc, amp_th=amp_th)
    beyond = (sp.f > fc) & (sp.f <= fs / 2) & (sp.Mf >= amp_th)
    return float(sp.f[beyond][0]) if beyond.any() else float("inf")
