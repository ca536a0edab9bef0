"""Noisy 100 Hz "foreign" touch recordings: what a camera-based tracker, not the book's haptic device, gives.

60 sound touch trials (3 participants x 20): the hand rests a short 0.05-0.3 s, then reaches 0.2-0.4 m
down and forwards along a minimum-jerk profile (:func:`skilllib.minimum_jerk_speed`, Flash & Hogan 1985)
and meets a surface on the decelerating flank, at 0.35-0.65 m/s; it then rests on the surface for
0.2-0.3 s with ``contact = 1``. Sampled at 100 Hz with white Gaussian position noise of 0.5 mm on the
tracker's depth axis only (z, the axis a camera resolves worst), or on the axes given. Seeded: the same
seed gives the same table. Without noise every trial is valid (selected or excluded, never invalid).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd

FS = 100.0  #: Hz
NOISE_SD = 0.0005  #: m, SD of the white position noise on each noisy axis
DEPTH_AXIS = ("z",)  #: the noisy axis of the tracker
N_PARTICIPANTS, N_TRIALS = 3, 20
REST_RANGE = (0.05, 0.3)  #: s, rest before onset
AMP_RANGE = (0.2, 0.4)  #: m, planned reach
DUR_RANGE = (0.55, 0.8)  #: s, planned duration of the reach
CONTACT_SPEED_RANGE = (0.35, 0.65)  #: m/s, speed at which the surface is met
SEED = 2020


def _mj(s: np.ndarray) -> np.ndarray:
    s = np.clip(s, 0.0, 1.0)
    return s**3 * (10 - 15 * s + 6 * s**2)


def foreign_trial(
    rng: np.random.Generator,
    *,
    rest: float | None = None,
    fs: float = FS,
    noise_sd: float = NOISE_SD,
    noise_axes: Sequence[str] = DEPTH_AXIS,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """One trial: time stamps (s), positions (N, 3) m, contact flag, and the true onset time (s)."""
    from skilllib import minimum_jerk_speed

    rest = rng.uniform(*REST_RANGE) if rest is None else rest
    amp, dur, vc = rng.uniform(*AMP_RANGE), rng.uniform(*DUR_RANGE), rng.uniform(*CONTACT_SPEED_RANGE)
    direction = np.array([rng.uniform(-0.2, 0.2), -1.0, rng.uniform(0.3, 0.8)])
    direction /= np.linalg.norm(direction)
    start = np.array([rng.uniform(-0.05, 0.05), rng.uniform(0.15, 0.25), rng.uniform(-0.05, 0.05)])
    # the surface is met on the decelerating flank where the planned speed falls to vc
    s = np.linspace(0.5, 1.0, 5001)
    speed = amp / dur * minimum_jerk_speed(s)
    s_contact = float(s[np.flatnonzero(speed <= vc)[0]])
    t_contact = rest + s_contact * dur
    t = np.arange(int(np.ceil((t_contact + rng.uniform(0.2, 0.3)) * fs))) / fs
    travel = amp * _mj((np.minimum(t, t_contact) - rest) / dur)
    pos = start + travel[:, None] * direction
    contact = (t >= t_contact).astype(int)
    for ax in noise_axes:
        pos[:, "xyz".index(ax)] += rng.normal(0, noise_sd, len(t))
    return t, pos, contact, rest


def foreign_frame(
    seed: int = SEED,
    *,
    noise_axes: Sequence[str] = DEPTH_AXIS,
    noise_sd: float = NOISE_SD,
    fs: float = FS,
    n_participants: int = N_PARTICIPANTS,
    n_trials: int = N_TRIALS,
) -> pd.DataFrame:
    """The long table (participant, trial, t in s, x, y, z in m, contact) of the foreign recordings.

    Parameters
    ----------
    seed : int
        The random seed (dimensionless).
    noise_axes : sequence of str
        The axes ("x", "y", "z") with white position noise; () for none.
    noise_sd : float
        The noise's SD on each of those axes (m).
    fs : float
        The sampling rate (Hz).
    n_participants, n_trials : int
        Participants and trials per participant (dimensionless).

    Returns
    -------
    pandas.DataFrame
        One row per sample.
    """
    rng = np.random.default_rng(seed)
    parts = []
    for p in range(1, n_participants + 1):
        for tr in range(1, n_trials + 1):
            t, pos, contact, _ = foreign_trial(rng, fs=fs, noise_sd=noise_sd, noise_axes=noise_axes)
            parts.append(
                pd.DataFrame(
                    {
                        "participant": str(p),
                        "trial": str(tr),
                        "t": t,
                        "x": pos[:, 0],
                        "y": pos[:, 1],
                        "z": pos[:, 2],
                        "contact": contact,
                    }
                )
            )
    return pd.concat(parts, ignore_index=True)
