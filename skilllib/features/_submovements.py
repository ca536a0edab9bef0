"""Measures of a trial's corrective submovements: speed peaks, the deepest dip, SPARC of the whole movement.

On the experiment's contact-cut 60 Hz segments SPARC follows how abruptly contact ends the movement more
than the corrections (chapter 3). The measures here look at the corrections directly:

* **speed peaks** (:func:`speed_peaks`): the local maxima of the segment's speed whose prominence reaches
  a threshold, the segment taken between two samples at rest (speed 0) so that a profile still rising at
  contact counts its last sample as a peak (a corrective submovement cut by the contact before its peak).
  A peak's prominence is its height above the higher of the two lowest speeds that separate it from a
  higher peak (``scipy.signal.find_peaks``), so a dip between two submovements counts when it is at least
  that deep below the lower of the two.
* **threshold**: a rule on the noise, not on the truth. :data:`PEAK_NOISE_FACTOR` (3) times the noise SD
  of a prominence, which is a difference of two speeds each carrying the run's speed noise
  (``features.attrs["lowpass"].speed_noise``, the 3-D speed noise RMS at rest, m/s): ``3 sqrt(2)`` times
  it. With the synthetic cohort's 0.03 mm position noise at 60 Hz that is about 0.01 m/s, about 1 % of a
  typical PV.
* **dip depth** (:func:`dip_depth`): the deepest fall of the speed between two maxima, as a share of PV
  (:func:`skilllib.smoothness.speed_dip` finds the lowest speed between the first and the last maximum).
* **SPARC of the whole movement**: from the onset through contact to the first sample at rest after it
  (speed below the onset threshold) or the recording's end, the positions differentiated across the
  contact as the segment's are (:func:`skilllib.features.velocity`), without the run's low-pass filter.
  On the synthetic cohort the surface stops the tip within one 60 Hz sample, so this adds one to three
  samples of an abrupt stop to the segment (chapter 7).

:func:`correction_measures` gives them per trial, beside the trial's LDLJ.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike
from scipy.signal import find_peaks

from .. import smoothness
from ..recordings import Recordings
from ._filtering import measure_rest_noise
from ._segmentation import ONSET_SPEED, diff_window, velocity
from ._table import SPARC_PARAMS, approaches, segment

#: A prominence counts when it reaches this many noise SDs of a difference of two speeds (dimensionless).
PEAK_NOISE_FACTOR = 3.0

#: The columns of :func:`correction_measures`, after ``participant`` and ``trial``.
CORRECTION_MEASURES = ("n_peaks", "dip_depth", "ldlj", "sparc_whole")


def _at_rest(speed: ArrayLike) -> np.ndarray:
    v = np.asarray(speed, dtype=float)
    if v.ndim != 1 or v.size == 0 or not np.all(np.isfinite(v)) or np.any(v < 0):
        raise ValueError("need a non-empty 1-D array of finite, non-negative speeds")
    return np.r_[0.0, v, 0.0]


def speed_peaks(speed: ArrayLike, prominence: float) -> np.ndarray:
    """The peaks of a speed profile whose prominence reaches ``prominence``: its submovements.

    The profile is taken between two samples at rest (speed 0), so its first or last sample is a peak
    when the speed falls towards it from neither side (a movement cut while still accelerating).

    Parameters
    ----------
    speed : array_like, shape (N,)
        The speed samples (m/s), finite and non-negative.
    prominence : float
        The smallest prominence a peak needs (m/s), >= 0: the peak's height above the higher of the
        lowest speeds separating it from a higher peak on either side (``scipy.signal.find_peaks``).

    Returns
    -------
    numpy.ndarray of int
        The peaks' sample indices in ``speed`` (samples), ascending; at least one for a profile that is
        not all zero and a prominence not above its peak speed.
    """
    if not (np.isfinite(prominence) and prominence >= 0):
        raise ValueError(f"prominence must be a finite speed >= 0 m/s, got {prominence}")
    v = _at_rest(speed)
    peaks, _ = find_peaks(v, prominence=max(float(prominence), np.finfo(float).tiny))
    return peaks - 1


def dip_depth(speed: ArrayLike) -> float:
    """The deepest fall of the speed between two of its maxima, as a share of the peak speed.

    The lowest speed between the first and the last local maximum (:func:`skilllib.smoothness.speed_dip`,
    on the profile taken between two samples at rest, as :func:`speed_peaks` does) below the lower of
    the highest speeds before and after it, divided by the peak speed.

    Parameters
    ----------
    speed : array_like, shape (N,)
        The speed samples (m/s), finite, non-negative and not all zero.

    Returns
    -------
    float
        The depth (dimensionless, 0 to 1): 0 for a single maximum, 1 for a stop between two
        submovements.
    """
    v = _at_rest(speed)
    peak = v.max()
    if peak <= 0:
        raise ValueError("the speed is all zero: no peak")
    low = smoothness.speed_dip(v)  # the peak itself when there is a single maximum
    inside = [i for i in np.flatnonzero(v == low) if 0 < i < v.size - 1]
    depth = max((min(v[:i].max(), v[i + 1 :].max()) - low for i in inside), default=0.0)
    return float(max(depth, 0.0) / peak)


def _whole_speed(recordings: Recordings, participant: str, trial: str, onset: int, contact: int) -> np.ndarray:
    """Speed (m/s) from the onset sample through contact to the first sample at rest after it."""
    tr = recordings.trial(participant, trial)
    v = np.linalg.norm(velocity(tr.pos, recordings.fs), axis=1)
    rest = np.flatnonzero(v[contact:] < ONSET_SPEED)
    end = contact + int(rest[0]) + 1 if rest.size else v.size
    return v[onset:end]


def correction_measures(
    recordings: Recordings,
    features: pd.DataFrame,
    *,
    prominence: float | None = None,
    sparc_params: Mapping[str, float] | None = None,
) -> pd.DataFrame:
    """Per trial the measures that may see corrective submovements (module docstring).

    Parameters
    ----------
    recordings : Recordings
        The recordings the features come from (t in s, positions in m).
    features : pandas.DataFrame
        Rows of :func:`skilllib.features.trial_features` (its ``attrs`` carry the run's rules and
        filter), e.g. the selected trials of :func:`skilllib.features.select`; invalid rows are left out.
        Needs ``participant``, ``trial``, ``status`` and ``ldlj`` (dimensionless).
    prominence : float or None
        The prominence a speed peak needs (m/s); None: :data:`PEAK_NOISE_FACTOR` ``* sqrt(2)`` times the
        run's speed noise at rest (``features.attrs["lowpass"].speed_noise``, or measured on the
        recordings' approaches when the table does not carry it).
    sparc_params : mapping of str to float or None
        SPARC's ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless) for ``sparc_whole``; None:
        :data:`skilllib.features.SPARC_PARAMS`.

    Returns
    -------
    pandas.DataFrame
        One row per valid trial of ``features``, in its order: ``participant``, ``trial``, ``n_peaks``
        (speed peaks of the segment, dimensionless), ``dip_depth`` (share of PV, dimensionless), ``ldlj``
        (the table's, dimensionless), ``sparc_whole`` (dimensionless) and ``n_after`` (samples of the whole
        movement after the segment: contact to rest). ``attrs["prominence"]`` holds the threshold (m/s).
    """
    valid = features[features["status"] != "invalid"]
    lowpass = features.attrs.get("lowpass")
    if prominence is None:
        noise = getattr(lowpass, "speed_noise", np.nan)
        if not np.isfinite(noise):
            noise = measure_rest_noise(approaches(recordings), recordings.fs, diff_window(recordings.fs)).speed
        prominence = PEAK_NOISE_FACTOR * np.sqrt(2) * float(noise)
    params = dict(SPARC_PARAMS if sparc_params is None else sparc_params)
    rules = {k: features.attrs[k] for k in ("start", "end") if k in features.attrs}
    rows = []
    for p, t, ldlj in zip(valid["participant"], valid["trial"], valid["ldlj"]):
        seg = segment(recordings, p, t, lowpass=lowpass, **rules)
        whole = _whole_speed(recordings, seg.participant, seg.trial, seg.onset, seg.contact)
        rows.append(
            {
                "participant": p,
                "trial": t,
                "n_peaks": len(speed_peaks(seg.speed, prominence)),
                "dip_depth": dip_depth(seg.speed),
                "ldlj": float(ldlj),
                "sparc_whole": smoothness.sparc(whole, recordings.fs, **params),
                "n_after": whole.size - seg.speed.size,
            }
        )
    out = pd.DataFrame(rows, columns=["participant", "trial", *CORRECTION_MEASURES, "n_after"])
    out.attrs["prominence"] = float(prominence)
    return out
