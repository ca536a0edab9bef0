"""The seeded generative model of the synthetic VR touch experiment (the book's cohort).

The recordings of Maldonado & Zetzsche (KI 2020) are not public. This model produces recordings in the
same form -- 10 participants x 150 trials, spoon-tip position at 60 Hz (Phantom Premium 1.5), a downward
approach from a start box that ends by touching the top of a contact box, aiming at 0.5 m/s -- and is
calibrated to the paper's aggregate numbers only (:func:`calibration_table`). It is synthetic data.

One trial, in the device frame (x mediolateral, y vertical up, z anteroposterior; m, s):

1. **Rest** in the start box for ``rest_before`` s.
2. **Approach**: the vertical drop ``s(t)`` is a superposition of minimum-jerk submovements (Flash & Hogan
   1985; submovement decomposition: Rohrer & Hogan 2003, Biol Cybern 89:190). Each submovement has onset,
   amplitude ``D``, duration ``T`` and relative time to peak speed ``k`` (speed ``D/T * 30 s^2 (1 - s)^2``
   in local time, peak ``1.875 D/T``; ``k != 0.5`` joins the rising half of a minimum-jerk profile of
   duration ``2kT`` to the falling half of one of duration ``2(1-k)T``, same peak, continuous acceleration).
   Normalised profiles are invariant across speed (Atkeson & Hollerbach 1985, J Neurosci 5:2318);
   downward movements accelerate for relatively longer (``k > 0.5``, Papaxanthis et al. 1998, Neurosci Lett
   253:103) and ``k`` grows with speed (Nagasaki 1989, Exp Brain Res 74:319).

   * Without correction the primary submovement aims *through* the surface: it is planned so that the tip
     reaches the surface on its decelerating flank at the intended contact speed (contact with non-zero
     speed ends the approach early; the field notes' truncated profile).
   * With a correction (participant-specific rate) the primary undershoots the surface, as primary
     submovements tend to (Meyer et al. 1988, Psychol Rev 95:340; Elliott et al. 2004), and one or two
     corrective submovements start during its deceleration; the last one is scaled so that the tip reaches
     the surface at the intended contact speed.

3. **Contact**: the tip meets a stiff virtual wall (critically damped, time constant ``wall_tau``) and
   rests on it, pressed ``press_depth`` into it, for ``rest_after`` s; ``contact = 1`` from the first
   sample at or after the touch.
4. **Off-axis**: a participant-specific tilt of the movement from the vertical, a per-trial lateral bow,
   slow postural sway; **noise**: white noise at the device's position resolution (0.03 mm) on every axis.

Participant parameters: start-to-surface distance, preferred peak speed, typical (biased) contact speed,
``k``, correction rate, tilt. Trial variability: start position in the start box, peak speed, intended
contact speed (log-normal; its tails compressed smoothly into 0.1-1.8 m/s), corrections, rest durations.
Randomness: ``numpy.random.default_rng`` streams spawned from one seed, one for the participants' traits
and one per trial, so changing how one trial is drawn leaves every other trial unchanged.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from functools import cached_property
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.special import ndtri

from ..recordings import COLUMNS, Recordings, recordings_from_frame, write_recordings
from ..smoothness import minimum_jerk_speed

#: The seed of data/cohort.csv: the first seed 0, 1, 2, ... whose cohort meets every target of
#: :func:`skilllib.cohort.calibration_table` (survey of seeds 0..SEED: ``data/seed_survey.csv``, data/README.md).
SEED = 9


@dataclass(frozen=True)
class CohortModel:
    """Population parameters of the generator (ranges are uniform; see :func:`model_table`).

    Ranges are (low, high) of a uniform draw; pairs marked "mean and SD" are those of a normal one.

    Attributes
    ----------
    n_participants : int
        Number of participants (dimensionless).
    n_trials : int
        Number of trials per participant (dimensionless).
    fs : float
        Sampling rate of the positions (Hz; the paper: 60 Hz).
    travel : tuple of float
        Range of a participant's start-to-surface distance (m).
    start_box : float
        Edge of the start box; trial start positions vary inside it (m).
    surface_y : tuple of float
        Range of the height of the contact surface in the device frame (m).
    dur_median : float
        Median of the participants' preferred primary-submovement durations (s).
    dur_between : float
        Spread of the preferred duration across participants (dimensionless, a log-SD).
    dur_within : tuple of float
        Range of the spread of duration across one participant's trials (dimensionless, a log-SD).
    min_duration : float
        Shortest primary submovement (an assumption: no faster aiming) (s).
    aim_median : float
        Median of the participants' typical contact speeds (the instruction) (m/s).
    aim_between : float
        Bias of the typical contact speed across participants (dimensionless, a log-SD).
    aim_within : tuple of float
        Range of the spread of the intended contact speed across trials (dimensionless, a log-SD).
    aim_soft_min : tuple of float
        Knee and floor of the smooth lower limit of intended contact speeds (m/s).
    aim_soft_max : tuple of float
        Knee and ceiling of the smooth upper limit of intended contact speeds (m/s).
    rtpv : tuple of float
        Range of the relative time to peak speed at a 0.5 s duration (downward movement) (dimensionless).
    rtpv_slope : float
        Change of the relative time to peak speed per second of duration (per s).
    rtpv_within : float
        SD of the relative time to peak speed across one participant's trials (dimensionless).
    correction_rate : tuple of float
        Range of a participant's share of corrected trials (dimensionless).
    correction_pv_ref : float
        Primary peak speed at which trials are corrected at the participant's rate (m/s).
    correction_speed_exp : float
        Exponent of the growth of the correction probability with peak speed (dimensionless).
    second_correction : float
        Probability of a second correction after a first (0: off) (dimensionless).
    primary_reach : tuple of float
        Mean and SD of the share of the distance a short primary covers (dimensionless).
    correction_delay : tuple of float
        Mean and SD of a correction's onset, as a share of the previous duration (dimensionless).
    correction_duration : tuple of float
        Range of a corrective submovement's duration (s).
    rest_before : tuple of float
        Range of the rest in the start box before onset (s).
    rest_after : tuple of float
        Range of the rest on the surface after contact (s).
    tilt_sd : float
        SD of a participant's tilt of the movement from the vertical (x and z) (deg).
    bow_sd : float
        SD of the per-trial lateral bow at mid-movement (m).
    sway : float
        Amplitude of the slow postural sway (0.2-1 Hz) (m).
    noise_sd : float
        SD of the white position noise on each axis (the device's resolution) (m).
    wall_tau : float
        Time constant of the critically damped virtual wall (s).
    press_depth : tuple of float
        Range of the static penetration while resting on the surface (m).
    stamp_jitter : float
        Half-width of the uniform jitter of the logged time stamps (s; 0: stamps on the grid). Each sample
        is taken at its jittered stamp (a VR or game-engine log); the jitter comes from its own generator
        per trial, so a jittered cohort holds the same movements as the regular one.
    phase : float
        Sampling phase, a fraction of a sample interval in [0, 1) (dimensionless): sample ``i`` of a trial
        is taken at ``(i + phase) / fs`` s instead of ``i / fs``. The movements, the noise (drawn per sample
        index) and the number of samples are those of ``phase = 0``; only the instants at which the same
        continuous movement is sampled move (the sampling-phase experiment of the book's SPARC-measurement
        chapter). ``phase = 0`` is the committed cohort, bit for bit.
    """

    n_participants: int = 10
    n_trials: int = 150
    fs: float = 60.0  # Hz, sampling rate (the paper)
    travel: tuple[float, float] = (0.08, 0.20)  # m, a participant's start-to-surface distance
    start_box: float = 0.02  # m, edge of the start box: trial start positions vary inside it
    surface_y: tuple[float, float] = (-0.12, -0.09)  # m, height of the contact surface in the device frame
    dur_median: float = 0.35  # s, median of the participants' preferred primary-submovement durations
    dur_between: float = 0.37  # log-SD of the preferred duration across participants
    dur_within: tuple[float, float] = (0.15, 0.25)  # log-SD of the duration across one participant's trials
    min_duration: float = 0.2  # s, floor of a primary submovement's duration (assumption: no faster aiming)
    aim_median: float = 0.5  # m/s, median of the participants' typical contact speeds (the instruction)
    aim_between: float = 0.6  # log-SD of the typical contact speed across participants (bias)
    aim_within: tuple[float, float] = (0.55, 0.75)  # log-SD of the intended contact speed across trials
    aim_soft_min: tuple[float, float] = (0.2, 0.1)  # m/s, knee and floor: intended contact speeds below
    aim_soft_max: tuple[float, float] = (1.0, 1.8)  # the knee (above it) approach the floor (ceiling) smoothly
    rtpv: tuple[float, float] = (0.5, 0.6)  # relative time to peak speed at T = 0.5 s (downward)
    rtpv_slope: float = -0.2  # change of k per s of duration (faster: later peak), k in [0.35, 0.7]
    rtpv_within: float = 0.06  # SD of k across one participant's trials
    correction_rate: tuple[float, float] = (0.45, 0.75)  # a participant's share of corrected trials
    correction_pv_ref: float = 0.9  # m/s: a primary with this peak speed is corrected at the participant's rate
    correction_speed_exp: float = 1.6  # correction probability grows as (peak speed / correction_pv_ref)^this
    second_correction: float = 0.0  # probability of a second correction after a first (off: data/README.md)
    primary_reach: tuple[float, float] = (0.84, 0.07)  # mean, SD: share of the distance a short primary covers
    correction_delay: tuple[float, float] = (0.68, 0.15)  # mean, SD: correction onset, share of previous T
    correction_duration: tuple[float, float] = (0.15, 0.35)  # s
    rest_before: tuple[float, float] = (0.3, 0.6)  # s, rest in the start box before onset
    rest_after: tuple[float, float] = (0.2, 0.4)  # s, rest on the surface after contact
    tilt_sd: float = 4.0  # deg, SD of a participant's tilt from the vertical (x and z)
    bow_sd: float = 0.003  # m, SD of the per-trial lateral bow at mid-movement
    sway: float = 0.0003  # m, amplitude of postural sway (0.2-1 Hz)
    noise_sd: float = 0.00003  # m, position noise (Phantom Premium 1.5 resolution about 0.03 mm)
    wall_tau: float = 0.01  # s, time constant of the critically damped virtual wall
    press_depth: tuple[float, float] = (0.0002, 0.001)  # m, static penetration while resting on the surface
    stamp_jitter: float = 0.0  # s, half-width of the time stamps' uniform jitter (0: on the grid)
    phase: float = 0.0  # fraction of a sample interval in [0, 1): samples at (i + phase) / fs

    def __post_init__(self) -> None:
        if not 0.0 <= self.phase < 1.0:
            raise ValueError(f"phase must be a fraction of a sample interval in [0, 1), got {self.phase!r}")


@dataclass(frozen=True, eq=False)
class Cohort:
    """``frame``: the recordings (long table, :data:`skilllib.recordings.COLUMNS`); ``participants``: one row of
    parameters per participant; ``truth``: per trial the generator's ground truth (onset and contact
    times in s, peak and contact speed in m/s of the noise-free continuous movement, corrections)."""

    frame: pd.DataFrame
    participants: pd.DataFrame
    truth: pd.DataFrame
    model: CohortModel
    seed: int

    @cached_property
    def recordings(self) -> Recordings:
        """The generated recordings, validated once (what :func:`skilllib.features.trial_features` takes)."""
        return recordings_from_frame(self.frame, f"<cohort seed {self.seed}>")


def _mj(s: np.ndarray) -> np.ndarray:
    """Minimum-jerk position, 0..1 over local time s in [0, 1]."""
    s = np.clip(s, 0.0, 1.0)
    return s**3 * (10 - 15 * s + 6 * s**2)


def submovement(t: np.ndarray, onset: float, amp: float, dur: float, k: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    """Displacement (m) and speed (m/s) at times ``t`` (s) of one minimum-jerk submovement with onset (s),
    amplitude ``amp`` (m), duration ``dur`` (s) and relative time to peak speed ``k`` (module docstring)."""
    tau = (np.asarray(t, dtype=float) - onset) / dur
    rise = tau <= k
    sig = np.where(rise, tau / (2 * k), 0.5 + (tau - k) / (2 * (1 - k)))
    scale = np.where(rise, 2 * k, 2 * (1 - k))
    pos = amp * np.where(rise, scale * _mj(sig), k + scale * (_mj(sig) - 0.5))
    pos = np.where(tau <= 0, 0.0, np.where(tau >= 1, amp, pos))
    return pos, amp / dur * minimum_jerk_speed(sig)  # d/ds of _mj: 30 s**2 (1 - s)**2 on [0, 1]


def _drop(t: np.ndarray, subs: list[tuple[float, float, float, float]]) -> tuple[np.ndarray, np.ndarray]:
    s, v = np.zeros_like(t, dtype=float), np.zeros_like(t, dtype=float)
    for sub in subs:
        ds, dv = submovement(t, *sub)
        s, v = s + ds, v + dv
    return s, v


def _crossing(t: np.ndarray, s: np.ndarray, v: np.ndarray, h: float) -> tuple[float, float]:
    """First time (s) the drop ``s`` sampled at ``t`` reaches ``h`` (m), linearly interpolated, and the
    speed ``v`` (m/s) then; (nan, nan) if it never does."""
    i = np.flatnonzero(s >= h)
    if i.size == 0:
        return np.nan, np.nan
    j = int(i[0])
    if j == 0:
        return float(t[0]), float(v[0])
    w = (h - s[j - 1]) / (s[j] - s[j - 1])
    return float(t[j - 1] + w * (t[j] - t[j - 1])), float(v[j - 1] + w * (v[j] - v[j - 1]))


_SIG = np.linspace(0.53, 0.999, 2000)  # local time on the falling flank of the primary submovement


def _flank_speed(h: float, dur: float, k: float) -> np.ndarray:
    """Speed (m/s) at contact for contact at each local time :data:`_SIG` of the falling flank of a
    submovement of duration ``dur`` (s) that reaches the surface ``h`` (m) below there: decreasing."""
    frac = k + 2 * (1 - k) * (_mj(_SIG) - 0.5)
    return 1.875 * h / (frac * dur) * 16 * _SIG**2 * (1 - _SIG) ** 2


def _soft_max(v: float, knee: float, ceiling: float) -> float:
    """``v`` (m/s) unchanged up to ``knee``; above it compressed smoothly (in log speed, continuous slope)
    towards ``ceiling``, which it never reaches. A hard clip would pile the far tail of the log-normal up at
    one speed, a spike no person produces."""
    a, w = np.log(knee), np.log(ceiling / knee)
    return float(v) if v <= knee else float(np.exp(a + w * (1 - np.exp(-(np.log(v) - a) / w))))


def _strata(rng: np.random.Generator, n: int) -> np.ndarray:
    """n probabilities, one in each of n equal strata of (0, 1), randomly permuted (Latin hypercube)."""
    return (rng.permutation(n) + rng.random(n)) / n


def _participants(rng: np.random.Generator, m: CohortModel) -> list[dict]:
    """Participant traits by Latin-hypercube sampling: every trait's n values fall one per stratum of its
    distribution, so a cohort of 10 covers each range evenly (i.i.d. draws often leave gaps)."""
    n = m.n_participants

    def uni(r: tuple[float, float]) -> np.ndarray:
        return r[0] + (r[1] - r[0]) * _strata(rng, n)

    def lognorm(median: float, sd: float) -> np.ndarray:
        return median * np.exp(sd * ndtri(_strata(rng, n)))

    cols = {
        "travel": uni(m.travel),
        "surface_y": uni(m.surface_y),
        "dur_pref": lognorm(m.dur_median, m.dur_between),
        "dur_within": uni(m.dur_within),
        "contact_aim": lognorm(m.aim_median, m.aim_between),
        "aim_within": uni(m.aim_within),
        "rtpv": uni(m.rtpv),
        "correction_rate": uni(m.correction_rate),
        "start_x": rng.normal(0, 0.02, n),
        "start_z": rng.normal(0, 0.02, n),
        "tilt_x": np.deg2rad(rng.normal(0, m.tilt_sd, n)),
        "tilt_z": np.deg2rad(rng.normal(0, m.tilt_sd, n)),
    }
    return [{"participant": str(i + 1), **{k: float(v[i]) for k, v in cols.items()}} for i in range(n)]


def _plan(rng: np.random.Generator, m: CohortModel, p: dict, h: float, onset: float) -> tuple[list, float, float, int]:
    """Submovements (onset s, amplitude m, duration s, k), contact time (s), intended contact speed, n corrections."""
    dur = max(p["dur_pref"] * np.exp(rng.normal(0, p["dur_within"])), m.min_duration)  # PV = 1.875 D / T
    vc = p["contact_aim"] * np.exp(rng.normal(0, p["aim_within"]))
    vc = 1 / _soft_max(1 / _soft_max(vc, *m.aim_soft_max), *(1 / np.array(m.aim_soft_min)))  # soft floor, too
    n_corr = 0  # faster primaries are less accurate and corrected more often (Meyer et al. 1988)
    p_corr = p["correction_rate"] * (1.875 * h / dur / m.correction_pv_ref) ** m.correction_speed_exp
    if rng.random() < min(p_corr, 0.98):
        n_corr = 2 if rng.random() < m.second_correction else 1

    k = float(np.clip(p["rtpv"] + m.rtpv_slope * (dur - 0.5) + rng.normal(0, m.rtpv_within), 0.35, 0.7))
    if n_corr == 0:  # aim through the surface: contact on the falling flank at speed vc
        sig = _SIG[np.argmax(_flank_speed(h, dur, k) <= vc)] if _flank_speed(h, dur, k)[0] > vc else _SIG[0]
        frac = k + 2 * (1 - k) * (_mj(sig) - 0.5)  # share of the planned amplitude done at contact
        if sig == _SIG[0]:  # vc above what this duration allows: move faster (not below the floor)
            dur = max(1.875 * h / frac * 16 * sig**2 * (1 - sig) ** 2 / vc, m.min_duration)
        return [(onset, h / frac, dur, k)], onset + (k + (sig - 0.5) * 2 * (1 - k)) * dur, vc, 0
    reach = np.sort(np.clip(rng.normal(*m.primary_reach, size=n_corr), 0.5, 0.97))
    subs = [(onset, h * reach[0], max(dur * reach[0], m.min_duration), k)]  # stops short, same peak speed
    for j in range(n_corr):  # corrections start during the previous submovement's deceleration
        o = subs[-1][0] + subs[-1][2] * float(np.clip(rng.normal(*m.correction_delay), 0.2, 1.3))
        d = rng.uniform(*m.correction_duration)
        if j < n_corr - 1:  # an intermediate correction still falls short
            subs.append((o, h * reach[j + 1] - sum(a for _, a, _, _ in subs), d, 0.5))
    done = sum(a for _, a, _, _ in subs)
    grid = np.arange(onset, max(o + d, *(a + c for a, _, c, _ in subs)) + 1e-3, 1e-3)  # 1 kHz
    s0, v0 = _drop(grid, subs)
    s1, v1 = submovement(grid, o, 1.0, d)  # the last submovement with unit amplitude
    lo, hi = (h - done) * 1.001, (h - done) + h  # bisection on its amplitude for contact speed vc
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        _, v = _crossing(grid, s0 + mid * s1, v0 + mid * v1, h)
        lo, hi = (mid, hi) if v < vc else (lo, mid)
    amp = 0.5 * (lo + hi)
    subs.append((o, amp, d, 0.5))
    tc, _ = _crossing(grid, s0 + amp * s1, v0 + amp * v1, h)
    if not np.isfinite(tc):  # cannot happen (the last amplitude exceeds the gap); keep a clear failure
        raise RuntimeError("planned approach never reaches the surface")
    return subs, tc, vc, n_corr


def _trial(rng: np.random.Generator, m: CohortModel, p: dict, trial: int) -> tuple[tuple, dict]:
    """Samples (t, pos (N, 3), contact) of one trial and its ground truth."""
    half = m.start_box / 2
    h = p["travel"] + rng.uniform(-half, half)
    x0 = p["start_x"] + rng.uniform(-half, half)
    z0 = p["start_z"] + rng.uniform(-half, half)
    onset = rng.uniform(*m.rest_before)
    subs, tc, vc_aim, n_corr = _plan(rng, m, p, h, onset)
    bow = rng.normal(0, m.bow_sd, size=2)
    sway_a = m.sway * rng.uniform(0.3, 1.0, size=3)
    sway_f = rng.uniform(0.2, 1.0, size=3)
    sway_ph = rng.uniform(0, 2 * np.pi, size=3)
    press = rng.uniform(*m.press_depth)
    t_end = tc + rng.uniform(*m.rest_after)

    def position(t: np.ndarray) -> np.ndarray:
        s, _ = _drop(t, subs)
        s = np.minimum(s, h)
        u = s / h
        sway = sway_a * np.sin(2 * np.pi * sway_f * t[:, None] + sway_ph)
        x = x0 + np.tan(p["tilt_x"]) * s + 4 * bow[0] * u * (1 - u)
        z = z0 + np.tan(p["tilt_z"]) * s + 4 * bow[1] * u * (1 - u)
        y = p["surface_y"] + h - s
        after = t >= tc
        tp = np.where(after, t - tc, 0.0)
        _, vtc = _drop(np.array([tc]), subs)
        e = np.exp(-tp / m.wall_tau)
        depth = vtc[0] * tp * e + press * (1 - (1 + tp / m.wall_tau) * e)
        y = np.where(after, p["surface_y"] - depth, y)
        return np.column_stack([x, y, z]) + sway

    t = np.arange(int(np.floor(t_end * m.fs)) + 1) / m.fs
    if m.phase:  # the same samples (count, noise), taken a fraction of an interval later
        t = (np.arange(len(t)) + m.phase) / m.fs
    if m.stamp_jitter:  # its own generator: the movements stay those of the regular cohort
        jitter = np.random.default_rng([trial, *map(ord, p["participant"])]).uniform(-1, 1, len(t) - 1)
        t = np.sort(np.r_[t[0], t[1:] + m.stamp_jitter * jitter])
    pos = position(t) + rng.normal(0, m.noise_sd, size=(len(t), 3))
    frame = (t, pos, (t >= tc).astype(np.int64))
    tf = np.linspace(onset, tc, max(int(np.ceil((tc - onset) * 1e3)), 2) + 1)  # noise-free truth, ~1 kHz
    vf = np.linalg.norm(np.gradient(position(tf), tf, axis=0), axis=1)
    truth = {
        "participant": p["participant"],
        "trial": str(trial),
        "travel": h,
        "t_onset": onset,
        "t_contact": tc,
        "pv": float(vf.max()),
        "contact_speed": float(vf[-1]),
        "contact_aim": vc_aim,
        "n_corrections": n_corr,
        "rtpv": subs[0][3],
    }
    return frame, truth


def generate_cohort(seed: int = SEED, model: CohortModel | None = None) -> Cohort:
    """The synthetic cohort: ``model.n_participants`` x ``model.n_trials`` trials.

    The default is the paper's 10 x 150 at 60 Hz. Same seed and model give the same cohort. Each trial has
    its own random stream (``SeedSequence(seed).spawn`` per participant, plus one for the traits, then
    ``spawn`` per trial), so changing ``n_trials`` leaves earlier trials unchanged and a trial's draws never
    shift another's.

    Parameters
    ----------
    seed : int
        The seed of the cohort (dimensionless); the book's is :data:`skilllib.cohort.SEED`.
    model : CohortModel or None
        The population parameters (units in :class:`CohortModel`); None: the defaults.

    Returns
    -------
    Cohort
        ``frame``: the recordings (t in s, positions in m, contact 0/1); ``participants``: one row of
        parameters per participant; ``truth``: per trial the generator's ground truth (onset and contact
        times in s, peak and contact speed in m/s); ``model`` and ``seed``.
    """
    m = model or CohortModel()
    frames, truths = [], []
    streams = np.random.SeedSequence(seed).spawn(m.n_participants + 1)
    parts = _participants(np.random.default_rng(streams[0]), m)
    for p, ss in zip(parts, streams[1:]):
        for tr, ts in enumerate(ss.spawn(m.n_trials), start=1):
            f, tru = _trial(np.random.default_rng(ts), m, p, tr)
            frames.append(f)
            truths.append(tru)
    n = np.array([len(f[0]) for f in frames])
    pos = np.concatenate([f[1] for f in frames])
    frame = pd.DataFrame(
        {
            "participant": np.repeat(np.array([tr["participant"] for tr in truths], dtype=object), n),
            "trial": np.repeat(np.array([tr["trial"] for tr in truths], dtype=object), n),
            "t": np.concatenate([f[0] for f in frames]),
            "x": pos[:, 0],
            "y": pos[:, 1],
            "z": pos[:, 2],
            "contact": np.concatenate([f[2] for f in frames]),
        }
    )[list(COLUMNS)]
    participants = pd.DataFrame(parts).set_index("participant")
    return Cohort(frame, participants, pd.DataFrame(truths), m, seed)


def write_cohort(path: str | Path, seed: int = SEED, model: CohortModel | None = None) -> Path:
    """Generate the cohort and write it with :func:`skilllib.recordings.write_recordings` (deterministic)."""
    return write_recordings(generate_cohort(seed, model).frame, path)


#: Unit and meaning of every parameter of :class:`CohortModel` (for :func:`model_table`).
PARAMETER_DOCS: dict[str, tuple[str, str]] = {
    "n_participants": ("", "participants"),
    "n_trials": ("", "trials per participant"),
    "fs": ("Hz", "sampling rate of the positions (the paper: 60 Hz)"),
    "travel": ("m", "range of a participant's start-to-surface distance"),
    "start_box": ("m", "edge of the start box; trial start positions vary inside it"),
    "surface_y": ("m", "range of the height of the contact surface in the device frame"),
    "dur_median": ("s", "median of the participants' preferred primary-submovement durations"),
    "dur_between": ("log-SD", "spread of the preferred duration across participants"),
    "dur_within": ("log-SD", "range of the spread of duration across one participant's trials"),
    "min_duration": ("s", "shortest primary submovement (an assumption: no faster aiming)"),
    "aim_median": ("m/s", "median of the participants' typical contact speeds (the instruction)"),
    "aim_between": ("log-SD", "bias of the typical contact speed across participants"),
    "aim_within": ("log-SD", "range of the spread of the intended contact speed across trials"),
    "aim_soft_min": ("m/s", "knee and floor of the smooth lower limit of intended contact speeds"),
    "aim_soft_max": ("m/s", "knee and ceiling of the smooth upper limit of intended contact speeds"),
    "rtpv": ("", "range of the relative time to peak speed at a 0.5 s duration (downward movement)"),
    "rtpv_slope": ("1/s", "change of the relative time to peak speed per second of duration"),
    "rtpv_within": ("", "SD of the relative time to peak speed across one participant's trials"),
    "correction_rate": ("", "range of a participant's share of corrected trials"),
    "correction_pv_ref": ("m/s", "primary peak speed at which trials are corrected at the participant's rate"),
    "correction_speed_exp": ("", "exponent of the growth of the correction probability with peak speed"),
    "second_correction": ("", "probability of a second correction after a first (0: off)"),
    "primary_reach": ("", "mean and SD of the share of the distance a short primary covers"),
    "correction_delay": ("", "mean and SD of a correction's onset, as a share of the previous duration"),
    "correction_duration": ("s", "range of a corrective submovement's duration"),
    "rest_before": ("s", "range of the rest in the start box before onset"),
    "rest_after": ("s", "range of the rest on the surface after contact"),
    "tilt_sd": ("deg", "SD of a participant's tilt of the movement from the vertical (x and z)"),
    "bow_sd": ("m", "SD of the per-trial lateral bow at mid-movement"),
    "sway": ("m", "amplitude of the slow postural sway (0.2-1 Hz)"),
    "noise_sd": ("m", "SD of the white position noise on each axis (the device's resolution)"),
    "wall_tau": ("s", "time constant of the critically damped virtual wall"),
    "press_depth": ("m", "range of the static penetration while resting on the surface"),
    "stamp_jitter": ("s", "half-width of the uniform jitter of the logged time stamps (0: on the grid)"),
    "phase": ("", "sampling phase: sample i taken at (i + phase) / fs, a fraction of an interval in [0, 1)"),
}


def model_table(model: CohortModel | None = None) -> pd.DataFrame:
    """The generator's parameters as a table (value, unit, meaning).

    Ranges are (low, high) of a uniform draw, pairs marked "mean and SD" are those of a normal one.

    Parameters
    ----------
    model : CohortModel or None
        The population parameters; None: the defaults.

    Returns
    -------
    pandas.DataFrame
        One row per parameter: ``value``, ``unit`` and ``meaning`` (text).
    """
    m = asdict(model or CohortModel())
    rows = {k: {"value": str(v), "unit": PARAMETER_DOCS[k][0], "meaning": PARAMETER_DOCS[k][1]} for k, v in m.items()}
    return pd.DataFrame.from_dict(rows, orient="index").rename_axis("parameter")
