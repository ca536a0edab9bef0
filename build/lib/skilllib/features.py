"""Speed, onset/contact segmentation, per-trial features and the paper's selection (KI 2020, Sect. 5).

For every trial of :class:`skilllib.data.Recordings`:

* **speed** (m/s): norm of the velocity obtained by differentiating the positions over the samples
  *before* contact only, with a Savitzky-Golay derivative (quadratic fit, ``scipy.signal.savgol_filter``)
  over a window of fixed duration, :data:`DIFF_SPAN_S` = 2/60 s. At the experiment's 60 Hz that window is
  3 samples, and the estimate is exactly the second-order finite difference (central inside, one-sided
  three-point at the ends, as ``numpy.gradient(edge_order=2)``). The Phantom's own velocity signal is
  noisy (field notes), so positions are differentiated. No further low-pass filter: at the device's
  position resolution (about 0.03 mm) the velocity noise at 60 Hz is about ``0.03 mm * 60 Hz / sqrt(2)`` =
  1.3 mm/s per axis (the 3-D speed of pure noise has a median about 1.5 times that, about 2 mm/s), a few
  thousandths of a typical peak speed; SPARC only reads the spectrum above 5 % of its maximum
  and below its adaptive cut-off (Balasubramanian et al. 2015), so that noise does not reach it, while a
  stronger filter would itself smooth the profile that SPARC measures. The span is fixed in seconds, not
  in samples, because a difference over one sample interval amplifies position noise in proportion to
  ``fs``: at 1 kHz a three-point difference turns 0.03 mm of noise into about 20 mm/s and onset detection
  at 0.05 m/s fails; over 2/60 s the speed noise stays near its 60 Hz level at any rate.
  The differentiation never uses a sample taken in contact: the impact is a velocity discontinuity and a
  derivative across it would mix the approach with the rest on the surface.
* **contact**: the first sample flagged ``contact == 1``; the approach is every sample before it.
* **onset**: the first approach sample whose speed exceeds 0.05 m/s (the paper).
* **segment**: onset to the last sample before contact, ``N`` samples; ``duration = N / fs`` (s), which is
  the time from the onset sample to the first contact sample.
* **features**: ``pv`` peak speed of the segment (m/s); ``contact_speed`` speed at the last sample before
  contact (m/s; the backward (one-sided) derivative there, an estimate of the speed at that sample, which
  lies between 0 and 1 interval before the touch); ``sparc`` (Balasubramanian et al. 2015) with
  :data:`SPARC_PARAMS`, with ``sparc_band_end_hz`` (Hz, the last frequency of its band) and
  ``sparc_capped`` (True when the maximum cut-off fc, not the amplitude threshold, ended the band; see
  :func:`skilllib.smoothness.sparc_bands`); ``ldlj`` log dimensionless jerk (Balasubramanian et al. 2015).
* **selection**: ``0.3 <= contact_speed <= 0.7`` m/s (the paper: 650 of 1500 trials).

Every trial stays in the table: ``status`` is ``selected``, ``excluded`` (outside the window, with the
reason) or ``invalid`` (cannot be segmented or bad samples, with the reason; features NaN).
"""
from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
from scipy.signal import savgol_filter

from . import smoothness
from .data import Recordings, recordings_from_frame, sort_ids
from .filtering import Lowpass, choose_lowpass

ONSET_SPEED = 0.05  #: m/s, movement onset threshold (the paper)
CONTACT_WINDOW = (0.3, 0.7)  #: m/s, selected contact speeds, inclusive (the paper)
MIN_SEGMENT_SAMPLES = 5  #: fewer samples from onset to contact: too short to analyse
DIFF_SPAN_S = 2 / 60  #: s, span of the differentiating window (3 samples at the experiment's 60 Hz)
MIN_DIFF_WINDOW = 3  #: samples: the smallest differentiating window (a quadratic needs three points)
MIN_APPROACH_SAMPLES = 2  #: fewer samples before contact leave nothing to differentiate
#: SPARC settings of the SPARC chapter (Balasubramanian et al. 2015 defaults): fc in Hz, amp_th, padlevel
SPARC_PARAMS: dict[str, float] = dict(smoothness.SPARC_PARAMS)
FEATURE_COLUMNS = ("participant", "trial", "status", "reason", "pv", "contact_speed", "duration", "sparc",
                   "sparc_band_end_hz", "sparc_capped", "ldlj", "n", "t_onset", "t_contact", "resampled")


@dataclass(frozen=True)
class Segment:
    """The approach of one trial from onset to the last sample before contact.

    ``t`` (N,) s as recorded; ``pos`` (N, 3) m; ``vel`` (N, 3) m/s; ``speed`` (N,) m/s; ``fs`` Hz;
    ``onset`` and ``contact``: indices in the trial of the onset sample and of the first contact sample.
    """

    participant: str
    trial: str
    t: np.ndarray
    pos: np.ndarray
    vel: np.ndarray
    speed: np.ndarray
    fs: float
    onset: int
    contact: int

    @property
    def duration(self) -> float:
        """Onset to contact in s (``N / fs``)."""
        return len(self.speed) / self.fs


def diff_window(fs: float, span_s: float = DIFF_SPAN_S) -> int:
    """Samples (odd, at least 3) of the differentiating window that spans ``span_s`` s at ``fs`` Hz."""
    return max(MIN_DIFF_WINDOW, 2 * int(round(span_s * fs / 2)) + 1)


def velocity(pos: np.ndarray, fs: float, span_s: float = DIFF_SPAN_S) -> np.ndarray:
    """Velocity (N, 3) in m/s of positions (N, 3) in m sampled at ``fs`` Hz.

    Savitzky-Golay derivative of a quadratic fitted over :func:`diff_window` samples (``span_s`` s;
    quadratic fits to the first/last window at the ends). At 60 Hz the window has 3 samples and this is
    ``numpy.gradient(pos, 1/fs, edge_order=2)``. Shorter inputs use the largest odd window that fits;
    2 samples give their difference quotient. Needs N >= 2.
    """
    pos = np.asarray(pos, dtype=float)
    if len(pos) < 2:
        raise ValueError(f"need at least 2 samples to differentiate, got {len(pos)}")
    if len(pos) == 2:
        return np.repeat((pos[1:] - pos[:1]) * fs, 2, axis=0)
    window = min(diff_window(fs, span_s), len(pos) - (1 - len(pos) % 2))
    return savgol_filter(pos, window, polyorder=2, deriv=1, delta=1.0 / fs, axis=0, mode="interp")


def segment_arrays(t: np.ndarray, pos: np.ndarray, contact: np.ndarray, fs: float, *,
                   onset_speed: float = ONSET_SPEED, min_samples: int = MIN_SEGMENT_SAMPLES,
                   participant: Any = None, trial: Any = None, lowpass: Lowpass | None = None) -> Segment | str:
    """Segment one trial's samples (``contact`` boolean); returns the :class:`Segment` or the reason
    (a string) why the trial cannot be segmented. ``lowpass``: the filter applied to the approach's
    positions before they are differentiated (:mod:`skilllib.filtering`; None: none); the segment's
    ``pos`` are then the filtered positions."""
    hits = np.flatnonzero(contact)
    if hits.size == 0:
        return "no contact: the contact flag is never 1"
    c = int(hits[0])
    if c < MIN_APPROACH_SAMPLES:
        return f"in contact from sample {c + 1}: no approach recorded before contact"
    if lowpass is not None and lowpass.cutoff_hz is not None:
        pos = np.concatenate([lowpass.apply(pos[:c], fs), pos[c:]])
    vel = velocity(pos[:c], fs)
    speed = np.linalg.norm(vel, axis=1)
    moving = np.flatnonzero(speed > onset_speed)
    if moving.size == 0:
        return f"no onset: speed stays below {onset_speed:g} m/s before contact (max {speed.max():.3f} m/s)"
    o = int(moving[0])
    if o == 0:
        return (f"no rest before onset: speed {speed[0]:.2f} m/s > {onset_speed:g} m/s at the first sample "
                f"(the movement started before the recording)")
    n = c - o
    if n < min_samples:
        return f"too short: {n} samples from onset to contact (need at least {min_samples})"
    return Segment(participant, trial, np.asarray(t[o:c], dtype=float), np.asarray(pos[o:c], dtype=float),
                   vel[o:], speed[o:], float(fs), o, c)


def _as_recordings(recordings: Recordings | pd.DataFrame) -> Recordings:
    return recordings if isinstance(recordings, Recordings) else recordings_from_frame(recordings)


def segment(recordings: Recordings | pd.DataFrame, participant: Any, trial: Any, *,
            onset_speed: float = ONSET_SPEED, min_samples: int = MIN_SEGMENT_SAMPLES,
            lowpass: Lowpass | None = None) -> Segment:
    """The segmented approach (onset to the last sample before contact) of one trial; ``lowpass`` as in
    :func:`segment_arrays` (a run's filter: ``features.attrs["lowpass"]`` of :func:`trial_features`).

    Raises KeyError for an unknown trial and ValueError, with the reason, for an invalid one.
    """
    rec = _as_recordings(recordings)
    tr = rec.trial(participant, trial)
    participant, trial = tr.participant, tr.trial
    row = rec.trials[(rec.trials["participant"] == participant) & (rec.trials["trial"] == trial)].iloc[0]
    if row["status"] != "ok":
        raise ValueError(f"trial {trial!r} of participant {participant!r} is invalid: {row['reason']}")
    seg = segment_arrays(tr.t, tr.pos, tr.contact, rec.fs, onset_speed=onset_speed, min_samples=min_samples,
                         participant=participant, trial=trial, lowpass=lowpass)
    if isinstance(seg, str):
        raise ValueError(f"trial {trial!r} of participant {participant!r} cannot be segmented: {seg}")
    return seg


def _window_reason(v: float, window: tuple[float, float]) -> str:
    lo, hi = window
    if v < lo:
        return f"contact speed {v:.3f} m/s below {lo:g} m/s"
    if v > hi:
        return f"contact speed {v:.3f} m/s above {hi:g} m/s"
    return ""


def approaches(recordings: Recordings | pd.DataFrame) -> list[np.ndarray]:
    """The positions (m) before first contact of every usable trial (status ok), in trial order: what
    :func:`skilllib.filtering.choose_lowpass` looks at to choose a cut-off."""
    rec = _as_recordings(recordings)
    out = []
    for (p, tr), status in zip(rec.keys(), rec.trials["status"]):
        if status == "ok":
            d = rec.trial(p, tr)
            hits = np.flatnonzero(d.contact)
            out.append(d.pos[:int(hits[0])] if hits.size else d.pos)
    return out


def run_lowpass(recordings: Recordings | pd.DataFrame, lowpass: str | float | Lowpass | None = "auto") -> Lowpass:
    """The :class:`skilllib.filtering.Lowpass` that ``lowpass`` (``"auto"``, ``"none"``, Hz or a Lowpass)
    means for these recordings (``"auto"``: Winter's residual analysis over their approaches)."""
    rec = _as_recordings(recordings)
    if isinstance(lowpass, Lowpass):
        return lowpass
    fs = rec.fs
    window = diff_window(fs) if np.isfinite(fs) else MIN_DIFF_WINDOW
    return choose_lowpass(lowpass, approaches(rec) if lowpass == "auto" else [], fs, window)


def trial_features(recordings: Recordings | pd.DataFrame, *, sparc_params: Mapping[str, float] | None = None,
                   window: tuple[float, float] = CONTACT_WINDOW, onset_speed: float = ONSET_SPEED,
                   min_samples: int = MIN_SEGMENT_SAMPLES, lowpass: str | float | Lowpass | None = "auto",
                   progress: Callable[[Sequence[Any], str], Iterable[Any]] | None = None) -> pd.DataFrame:
    """One row per trial of ``recordings`` (all of them, in their order) with its features and status.

    Columns: ``participant, trial, status`` (``selected`` / ``excluded`` / ``invalid``), ``reason``
    (empty when selected), ``pv`` (m/s), ``contact_speed`` (m/s), ``duration`` (s), ``sparc``,
    ``sparc_band_end_hz`` (Hz), ``sparc_capped`` (nullable boolean: fc ended the band), ``ldlj``, ``n``
    (segment samples), ``t_onset``, ``t_contact`` (s, time stamps of the onset sample and of the
    first contact sample), ``resampled`` (the trial's time stamps were irregular and it was resampled onto
    the uniform grid, :mod:`skilllib.timing`). Features are NaN (NA) only for invalid trials.
    ``sparc_params`` defaults to :data:`SPARC_PARAMS`; ``window`` is the inclusive contact-speed window in
    m/s; ``lowpass``: the positions' low-pass filter (:func:`run_lowpass`; default ``"auto"``, which does
    not filter the book's cohort), recorded in ``attrs["lowpass"]`` of the result; ``progress(items,
    description)`` may wrap the loop over trials (e.g. tqdm).
    """
    rec = _as_recordings(recordings)
    params = {**SPARC_PARAMS, **(sparc_params or {})}
    filt = run_lowpass(rec, lowpass)
    rows, speeds = [], []
    items = list(zip(rec.keys(), rec.trials["status"], rec.trials["reason"], rec.trials["timing"]))
    for (p, tr), status, reason, timing_note in (progress(items, "features") if progress else items):
        row = {"participant": p, "trial": tr, "status": "invalid", "reason": reason, "resampled": bool(timing_note)}
        if status == "ok":
            d = rec.trial(p, tr)
            seg = segment_arrays(d.t, d.pos, d.contact, rec.fs, onset_speed=onset_speed, min_samples=min_samples,
                                 lowpass=filt)
            if isinstance(seg, str):
                row["reason"] = seg
            else:
                v = seg.speed
                row.update(status="", pv=float(v.max()), contact_speed=float(v[-1]), duration=seg.duration,
                           ldlj=float(smoothness.ldlj(v, rec.fs)), n=len(v), t_onset=float(d.t[seg.onset]),
                           t_contact=float(d.t[seg.contact]), _k=len(speeds))
                speeds.append(v)
        rows.append(row)
    bands = smoothness.sparc_bands(speeds, rec.fs, **params) if speeds else None
    for row in rows:
        if row["status"] == "":
            i = row.pop("_k")
            row.update(sparc=float(bands.sparc[i]), sparc_band_end_hz=float(bands.band_end_hz[i]),
                       sparc_capped=bool(bands.capped[i]))
            row["reason"] = _window_reason(row["contact_speed"], window)
            row["status"] = "excluded" if row["reason"] else "selected"
    out = pd.DataFrame(rows, columns=list(FEATURE_COLUMNS))
    out["n"] = out["n"].astype("Int64")
    out["sparc_capped"] = out["sparc_capped"].astype("boolean")
    out["resampled"] = out["resampled"].astype(bool)
    out.attrs["lowpass"] = filt
    return out


def select(features: pd.DataFrame) -> pd.DataFrame:
    """The selected trials (status ``selected``), index reset: the input of the clustering chapter."""
    return features[features["status"] == "selected"].reset_index(drop=True)


def status_counts(features: pd.DataFrame) -> pd.DataFrame:
    """Trials per participant and status (columns selected, excluded, invalid, total), with a total row."""
    t = pd.crosstab(features["participant"], features["status"])
    t = t.reindex(index=sort_ids(t.index), columns=["selected", "excluded", "invalid"], fill_value=0)
    t["total"] = t.sum(axis=1)
    t.loc["all"] = t.sum(axis=0)
    return t


def participant_summary(features: pd.DataFrame) -> pd.DataFrame:
    """Per participant, over its valid (selected or excluded) trials: median and interquartile range of
    peak speed (m/s), contact speed (m/s), duration (s) and SPARC, and the number of selected trials."""
    valid = features[features["status"] != "invalid"]
    g = valid.groupby("participant", sort=True)
    cols = {"pv": "PV (m/s)", "contact_speed": "contact speed (m/s)", "duration": "duration (s)",
            "sparc": "SPARC"}
    out = pd.DataFrame({"valid trials": g.size(),
                        "selected": g["status"].agg(lambda s: int((s == "selected").sum()))})
    for c, name in cols.items():
        q = g[c].quantile([0.25, 0.5, 0.75]).unstack()
        out[f"{name} median"] = q[0.5]
        out[f"{name} IQR"] = q[0.75] - q[0.25]
    return out.reindex(sort_ids(out.index))


def rest_speed(recordings: Recordings | pd.DataFrame, features: pd.DataFrame, margin: float = 0.2) -> np.ndarray:
    """Speeds (m/s) at the interior samples (central differences, as inside a segment) more than
    ``margin`` s before onset in the valid trials: the noise floor at rest (white position noise of SD s
    gives s * fs / sqrt(2) per axis). The margin leaves out the slow start of the movement; the first
    sample is left out because its one-sided three-point difference amplifies noise about 3.6 times more
    than a central difference (coefficients 3/2, -2, 1/2 against 1/2, -1/2)."""
    rec = _as_recordings(recordings)
    out = []
    valid = features.loc[features["status"] != "invalid", ["participant", "trial", "t_onset"]]
    for p, tr, t_on in valid.itertuples(index=False):
        d = rec.trial(p, tr)
        o = int(np.searchsorted(d.t, t_on - margin))
        if o >= 3:
            out.append(np.linalg.norm(velocity(d.pos[:o], rec.fs), axis=1)[1:-1])
    return np.concatenate(out) if out else np.array([])
