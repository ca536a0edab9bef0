"""Speed, onset/contact segmentation, per-trial features and the paper's selection (KI 2020, Sect. 5).

For every trial of :class:`skilllib.recordings.Recordings`:

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
  :func:`skilllib.smoothness.sparc_bands`); ``ldlj`` log dimensionless jerk (Balasubramanian et al. 2015);
  ``peak_acc`` the peak magnitude of the tangential acceleration (m/s^2), the largest ``|d speed / dt|`` over the
  segment with ``numpy.gradient(speed, 1 / fs)`` (NaN below 2 samples); ``path_length`` the distance
  travelled over the segment (m), the trapezoidal integral of the speed, ``numpy.trapezoid(speed,
  dx=1 / fs)``.
* **other rules**: the task may start and end the movement otherwise (``start`` and ``end`` of
  :func:`trial_features`, :mod:`skilllib.features._rules`): a relative onset (a fraction of the peak
  speed), an event, the speed's offset, a height crossed on the up axis; :func:`segment_arrays` states
  each. The end sample then stands where ``contact`` stands above: ``t_contact`` is its time stamp and
  ``contact_speed`` the speed at the last sample before it. Events come from the recordings'
  ``trial_events`` (C3D events).
* **selection**: ``0.3 <= contact_speed <= 0.7`` m/s (the paper: 650 of 1500 trials).

Every trial stays in the table: ``status`` is ``selected``, ``excluded`` (outside the window, with the
reason) or ``invalid`` (cannot be segmented or bad samples, with the reason; features NaN).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
import pandas as pd

from .. import smoothness
from ..recordings import ID_COLUMNS, Recordings, first_true, sort_ids
from . import _vectorised as batch
from ._contact import CONTACT_ESTIMATORS, contact_speed_estimates
from ._filtering import NO_FILTER, Lowpass, choose_lowpass, measure_rest_noise
from ._rules import PAPER_END, PAPER_START, EndRule, StartRule
from ._segmentation import (
    CONTACT_WINDOW,
    MIN_DIFF_WINDOW,
    MIN_SEGMENT_SAMPLES,
    Segment,
    diff_window,
    segment_arrays,
    start_rule,
    velocity,
)

#: SPARC settings of the SPARC chapter (Balasubramanian et al. 2015 defaults): fc in Hz, amp_th, padlevel
SPARC_PARAMS: dict[str, float] = dict(smoothness.SPARC_PARAMS)
FEATURE_COLUMNS = (
    *ID_COLUMNS,
    "status",
    "reason",
    "pv",
    "contact_speed",
    "duration",
    "sparc",
    "sparc_band_end_hz",
    "sparc_capped",
    "ldlj",
    "peak_acc",
    "path_length",
    "n",
    "t_onset",
    "t_contact",
    "resampled",
    "repairs",
    "n_repaired",
)


def _as_recordings(recordings: Recordings) -> Recordings:
    """The feature code takes :class:`Recordings` only: a table is validated once, at the door
    (:func:`skilllib.recordings.load_recordings`), not again by every function that reads it."""
    if not isinstance(recordings, Recordings):
        raise TypeError(
            f"expected Recordings, got {type(recordings).__name__}: read or validate the data first with "
            "skilllib.load_recordings(...)"
        )
    return recordings


def trial_events(recordings: Recordings, participant: Any, trial: Any) -> dict[str, np.ndarray] | None:
    """One trial's events (label, text -> sorted times in s), when the recordings have ``trial_events``.

    Parameters
    ----------
    recordings : Recordings
        The recordings (t in s).
    participant, trial : Any
        The trial's ids (text).

    Returns
    -------
    dict of str to numpy.ndarray or None
        The events (times in s); None when the recordings cannot say.
    """
    get = getattr(recordings, "trial_events", None)
    return get(participant, trial) if callable(get) else None


def _needs_events(start: StartRule, end: EndRule) -> bool:
    return start.kind == "event" or end.kind == "event"


def segment(
    recordings: Recordings,
    participant: Any,
    trial: Any,
    *,
    start: StartRule = PAPER_START,
    end: EndRule = PAPER_END,
    onset_speed: float | None = None,
    min_samples: int = MIN_SEGMENT_SAMPLES,
    lowpass: Lowpass | None = None,
) -> Segment:
    """The segmented movement (onset to the last sample before the end; the paper: before contact) of one
    trial, under the task's rules (:func:`segment_arrays`; events from the recordings' ``trial_events``).

    Parameters
    ----------
    recordings : Recordings or pandas.DataFrame
        The recordings (t in s, positions in m), or a long table :func:`skilllib.recordings.recordings_from_frame`
        validates.
    participant : Any
        The participant's id (text; a number is looked up as its text).
    trial : Any
        The trial's id (text; a number is looked up as its text).
    start : StartRule
        Where the movement starts (:func:`skilllib.features.parse_start`; speeds in m/s).
    end : EndRule
        Where it ends (:func:`skilllib.features.parse_end`; speeds in m/s, heights in m, hold in s).
    onset_speed : float or None
        Kept for older callers: the start ``speed`` with this absolute threshold (m/s); None: ``start``.
    min_samples : int
        The fewest samples a segment may have (samples).
    lowpass : Lowpass or None
        As in :func:`segment_arrays` (a run's filter: ``features.attrs["lowpass"]`` of
        :func:`trial_features`; cut-off in Hz); None: none.

    Returns
    -------
    Segment
        The segment: times (s), positions (m), speeds (m/s).

    Raises
    ------
    KeyError
        For an unknown trial.
    ValueError
        With the reason, for an invalid one.
    """
    rec = _as_recordings(recordings)
    tr = rec.trial(participant, trial)
    participant, trial = tr.participant, tr.trial
    row = rec.trials[(rec.trials["participant"] == participant) & (rec.trials["trial"] == trial)].iloc[0]
    if row["status"] != "ok":
        raise ValueError(f"trial {trial!r} of participant {participant!r} is invalid: {row['reason']}")
    start = start_rule(start, onset_speed)
    seg = segment_arrays(
        tr.t,
        tr.pos,
        tr.contact,
        rec.fs,
        start=start,
        end=end,
        events=trial_events(rec, participant, trial) if _needs_events(start, end) else None,
        min_samples=min_samples,
        participant=participant,
        trial=trial,
        lowpass=lowpass,
    )
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


def approaches(recordings: Recordings, *, end: EndRule = PAPER_END) -> list[np.ndarray]:
    """The positions before first contact of every usable trial (status ok), in trial order.

    What :func:`skilllib.features.choose_lowpass` looks at to choose a cut-off. For an end rule other than
    ``contact`` (offset, event, height), the whole trial: where such an end lies depends on the filter
    being chosen, so the residual analysis reads every sample the movement may hold.

    Parameters
    ----------
    recordings : Recordings or pandas.DataFrame
        The recordings (t in s, positions in m), or a long table :func:`skilllib.recordings.recordings_from_frame`
        validates.
    end : EndRule
        The task's end rule (:func:`skilllib.features.parse_end`; speeds in m/s, heights in m).

    Returns
    -------
    list of numpy.ndarray
        One (N, 3) array of positions (m) per usable trial.
    """
    rec = _as_recordings(recordings)
    out = []
    for (p, tr), status in zip(rec.keys(), rec.trials["status"]):
        if status == "ok":
            d = rec.trial(p, tr)
            hits = np.flatnonzero(d.contact) if end.kind == "contact" else np.zeros(0, int)
            out.append(d.pos[: int(hits[0])] if hits.size else d.pos)
    return out


def run_lowpass(
    recordings: Recordings, lowpass: str | float | Lowpass | None = "auto", *, end: EndRule = PAPER_END
) -> Lowpass:
    """The :class:`skilllib.features.Lowpass` that ``lowpass`` means for these recordings.

    ``"auto"``: Winter's residual analysis over their approaches (:func:`approaches`: the samples before
    contact, or the whole trial for an end other than ``contact``), the noise at rest measured per axis in
    every trial's rest window (:func:`skilllib.features.measure_rest_noise`).

    Parameters
    ----------
    recordings : Recordings or pandas.DataFrame
        The recordings (t in s, positions in m), or a long table :func:`skilllib.recordings.recordings_from_frame`
        validates.
    lowpass : str, float, Lowpass or None
        ``"auto"``, ``"none"`` (text), a cut-off frequency (Hz) or a :class:`Lowpass`.
    end : EndRule
        The task's end rule (:func:`skilllib.features.parse_end`; speeds in m/s, heights in m).

    Returns
    -------
    Lowpass
        The filter (cut-off in Hz).
    """
    rec = _as_recordings(recordings)
    if isinstance(lowpass, Lowpass):
        return lowpass
    fs = rec.fs
    window = diff_window(fs) if np.isfinite(fs) else MIN_DIFF_WINDOW
    if lowpass != "auto":
        return choose_lowpass(lowpass, [], fs, window)
    keys, runs = rec.keys(), rec.runs()
    t, pos, contact = rec.arrays()
    ok = (rec.trials["status"] == "ok").to_numpy()
    by_contact = end.kind == "contact"
    # the approach: rows before the first contact (all without one; all for another end)
    length = first_true(contact, runs) if by_contact else np.asarray(runs.length).copy()
    separate = {}
    for i in np.flatnonzero(ok):
        if rec.is_resampled(*keys[i]):
            d = rec.trial(*keys[i])
            hits = np.flatnonzero(d.contact) if by_contact else np.zeros(0, int)
            separate[int(i)] = d.pos[: int(hits[0])] if hits.size else d.pos
            length[i] = len(separate[int(i)])
    picked = np.flatnonzero(ok & (length >= 4))
    if not picked.size or not np.isfinite(fs):
        return choose_lowpass("auto", [], fs, window)
    views = [
        separate[int(i)] if int(i) in separate else pos[runs.start[i] : runs.start[i] + length[i]] for i in picked
    ]  # the approaches (views, no copies), as approaches() gives them
    return choose_lowpass("auto", views, fs, window, noise=measure_rest_noise(views, fs, window))


def trial_features(
    recordings: Recordings,
    *,
    sparc_params: Mapping[str, float] | None = None,
    window: tuple[float, float] | None = CONTACT_WINDOW,
    start: StartRule = PAPER_START,
    end: EndRule = PAPER_END,
    onset_speed: float | None = None,
    min_samples: int = MIN_SEGMENT_SAMPLES,
    lowpass: str | float | Lowpass | None = "auto",
    progress: Callable[[Sequence[Any], str], Iterable[Any]] | None = None,
    contact_estimator: str = "last-sample",
) -> pd.DataFrame:
    """One row per trial of ``recordings`` (all of them, in their order) with its features and status.

    Computed for all trials at once (:mod:`skilllib.features`), with the same values as the per-trial
    :func:`segment_arrays`, :func:`skilllib.smoothness.ldlj` and :func:`skilllib.smoothness.sparc_bands`
    (the paper's rules batched; other start and end rules trial by trial through :func:`segment_arrays`).

    Columns: ``participant, trial, status`` (``selected`` / ``excluded`` / ``invalid``), ``reason``
    (empty when selected), ``pv`` (m/s), ``contact_speed`` (m/s; the speed at the last sample before the
    end), ``duration`` (s), ``sparc``, ``sparc_band_end_hz`` (Hz), ``sparc_capped`` (nullable boolean: fc
    ended the band), ``ldlj``, ``peak_acc`` (m/s^2, the largest ``|d speed / dt|``), ``path_length`` (m, distance
    travelled over the segment), ``n`` (segment samples), ``t_onset``, ``t_contact`` (s, time stamps of
    the onset sample and of the end sample: the first contact sample, or the offset, event or height
    sample of another end rule), ``resampled`` (the trial's time stamps were irregular and it was resampled onto
    the uniform grid, :mod:`skilllib.recordings`), ``repairs`` (text, '' when none: the real-data defects
    repaired, :func:`skilllib.recordings.repair_trial`) and ``n_repaired`` (samples replaced by
    interpolation). Features are NaN (NA) only for invalid trials.

    Parameters
    ----------
    recordings : Recordings or pandas.DataFrame
        The recordings (t in s, positions in m), or a long table :func:`skilllib.recordings.recordings_from_frame`
        validates.
    sparc_params : mapping of str to float or None
        SPARC's parameters ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless); None:
        :data:`SPARC_PARAMS`.
    window : tuple of float or None
        The inclusive contact-speed window of the selected trials (m/s); None: every valid trial is
        selected (other windows: :func:`skilllib.features.apply_selection`).
    start : StartRule
        Where a movement starts (:func:`skilllib.features.parse_start`; speeds in m/s); recorded in
        ``attrs["start"]`` of the result.
    end : EndRule
        Where it ends (:func:`skilllib.features.parse_end`; speeds in m/s, heights in m, hold in s);
        recorded in ``attrs["end"]``. Events (for ``event:LABEL``) come from the recordings'
        ``trial_events`` when they have it; without it, an event rule names the missing event per trial.
    onset_speed : float or None
        Kept for older callers: the start ``speed`` with this absolute threshold (m/s); None: ``start``.
    min_samples : int
        The fewest samples a segment may have (samples).
    lowpass : str, float, Lowpass or None
        The positions' low-pass filter (:func:`run_lowpass`, with the approaches of ``end``): ``"auto"``
        (which does not filter the book's cohort), ``"none"`` (text), a cut-off (Hz) or a :class:`Lowpass`;
        recorded in ``attrs["lowpass"]`` of the result.
    progress : callable or None
        ``progress(items, description)`` may wrap the loop over trials (e.g. tqdm; description text).
    contact_estimator : str
        How ``contact_speed`` (and so the selection) is estimated (text): ``"last-sample"`` (the speed at
        the last sample before the end, the default) or ``"midpoint"`` / ``"crossing"`` with a cubic fit
        to the last 4 samples (:func:`skilllib.features.contact_speed_at`); recorded in
        ``attrs["contact_estimator"]``. A trial it cannot estimate becomes invalid with the reason.

    Returns
    -------
    pandas.DataFrame
        The feature table (columns and units above).
    """
    rec = _as_recordings(recordings)
    if contact_estimator not in CONTACT_ESTIMATORS:
        raise ValueError(f"unknown contact_estimator {contact_estimator!r}; expected one of {CONTACT_ESTIMATORS}")
    start = start_rule(start, onset_speed)
    params = {**SPARC_PARAMS, **(sparc_params or {})}
    filt = run_lowpass(rec, lowpass, end=end)
    trials = rec.trials
    keys = rec.keys()
    ok = (trials["status"] == "ok").to_numpy()
    for _ in progress([len(keys)], "features") if progress else ():  # vectorised: the bar has one step
        pass
    separate = {i: rec.trial(*keys[i]) for i in np.flatnonzero(ok) if rec.is_resampled(*keys[i])}
    events = {int(i): trial_events(rec, *keys[i]) for i in np.flatnonzero(ok)} if _needs_events(start, end) else None
    t, pos, contact = rec.arrays()
    seg = batch.segment_many(
        t,
        pos,
        contact,
        rec.runs(),
        rec.fs,
        which=ok,
        separate=separate,
        start=start,
        end=end,
        events=events,
        min_samples=min_samples,
        lowpass=filt,
    )
    done = seg.segmented
    n_all = len(keys)
    sparc = np.full(n_all, np.nan)
    band_end = np.full(n_all, np.nan)
    capped = pd.array([pd.NA] * n_all, dtype="boolean")
    if seg.speeds:
        bands = smoothness.sparc_bands(seg.speeds, rec.fs, **params)
        sparc[done], band_end[done] = bands.sparc, bands.band_end_hz
        capped[done] = bands.capped
    reason = np.where(ok, seg.reason, trials["reason"].to_numpy(dtype=object)).astype(object)
    status = np.full(n_all, "invalid", dtype=object)
    cs = seg.contact_speed
    if contact_estimator != "last-sample":
        done, cs = _estimated_contact_speed(rec, keys, done, seg.t_contact, reason, contact_estimator)
    lo, hi = window if window is not None else (-np.inf, np.inf)
    inside = done & (cs >= lo) & (cs <= hi)
    status[inside] = "selected"
    status[done & ~inside] = "excluded"
    for i in np.flatnonzero(done & ~inside):
        reason[i] = _window_reason(cs[i], window)
    out = pd.DataFrame(
        {
            "participant": np.array([k[0] for k in keys], dtype=object),
            "trial": np.array([k[1] for k in keys], dtype=object),
            "status": status,
            "reason": reason,
            "pv": seg.pv,
            "contact_speed": cs,
            "duration": seg.duration,
            "sparc": sparc,
            "sparc_band_end_hz": band_end,
            "sparc_capped": capped,
            "ldlj": seg.ldlj,
            "peak_acc": seg.peak_acc,
            "path_length": seg.path_length,
            "n": pd.array(np.where(done, seg.n, 0), dtype="Int64"),
            "t_onset": seg.t_onset,
            "t_contact": seg.t_contact,
            "resampled": trials["timing"].astype(str).str.contains("resampled:", regex=False).to_numpy(),
            "repairs": trials.get("repairs", pd.Series([""] * n_all)).fillna("").astype(str).to_numpy(),
            "n_repaired": trials.get("n_repaired", pd.Series([0] * n_all)).fillna(0).astype(int).to_numpy(),
        },
        columns=list(FEATURE_COLUMNS),
    )
    out.loc[~done, "n"] = pd.NA
    lost = seg.segmented & ~done  # segmented, but the contact estimator could not estimate it
    if lost.any():
        out.loc[lost, ["sparc_capped"]] = pd.NA
        out.loc[lost, [*_FEATURES_OF_SEGMENT]] = np.nan
    if filt.borderline and not filt.note:  # what the other choice would change (skilllib.features._filtering)
        other = NO_FILTER if filt.cutoff_hz is not None else Lowpass(filt.alternative_hz, "given", fs=rec.fs)
        if other.cutoff_hz is not None or filt.cutoff_hz is not None:
            kw = dict(sparc_params=sparc_params, window=window, start=start, end=end, min_samples=min_samples)
            kw["contact_estimator"] = contact_estimator
            filt = replace(filt, note=borderline_note(filt, out, trial_features(rec, lowpass=other, **kw)))
    out.attrs["lowpass"] = filt
    out.attrs["start"], out.attrs["end"] = start, end
    out.attrs["contact_estimator"] = contact_estimator
    return out


#: The columns of a segmented trial's features that are NaN when it is not (numbers; ``n`` and
#: ``sparc_capped`` are nullable and set to NA apart).
_FEATURES_OF_SEGMENT = (
    "pv",
    "contact_speed",
    "duration",
    "sparc",
    "sparc_band_end_hz",
    "ldlj",
    "peak_acc",
    "path_length",
    "t_onset",
    "t_contact",
)


def _estimated_contact_speed(
    rec: Recordings, keys: list, done: np.ndarray, t_end: np.ndarray, reason: np.ndarray, method: str
) -> tuple[np.ndarray, np.ndarray]:
    """The segmented trials (bool) and their contact speeds (m/s) by ``method`` (cubic, 4 samples); a
    trial it cannot estimate is no longer segmented and gets the estimator's reason in ``reason``."""
    rows = pd.DataFrame(
        {
            "participant": [k[0] for k in keys],
            "trial": [k[1] for k in keys],
            "status": np.where(done, "ok", "invalid"),
            "reason": reason,
            "t_contact": np.where(done, t_end, np.nan),
        }
    )
    est = contact_speed_estimates(rec, rows, method=method, degree=3, n_fit=4)
    cs = est["contact_speed"].to_numpy(dtype=float)
    lost = done & ~np.isfinite(cs)
    reason[lost] = "contact speed: " + est["reason"].to_numpy(dtype=object)[lost]
    return done & ~lost, cs


def borderline_note(lowpass: Lowpass, features: pd.DataFrame, other: pd.DataFrame) -> str:
    """The note of a borderline ``auto`` filter decision: what the other choice changes.

    Parameters
    ----------
    lowpass : Lowpass
        The run's filter (speed noise in m/s, cut-offs in Hz), ``borderline``.
    features : pandas.DataFrame
        The feature table with that filter (:func:`trial_features`; SPARC dimensionless).
    other : pandas.DataFrame
        The feature table with the other choice.

    Returns
    -------
    str
        The note (text): the speed noise against the limit (mm/s), the trials whose status changes, the
        median absolute change of SPARC over the trials valid both ways (dimensionless).
    """
    from ._filtering import BORDERLINE_FRACTION, SPEED_NOISE_LIMIT

    changed = int((features["status"].to_numpy() != other["status"].to_numpy()).sum())
    both = (features["status"] != "invalid").to_numpy() & (other["status"] != "invalid").to_numpy()
    d = np.abs(features["sparc"].to_numpy(dtype=float)[both] - other["sparc"].to_numpy(dtype=float)[both])
    instead = (
        "not filtering"
        if lowpass.cutoff_hz is not None
        else f"filtering at {lowpass.alternative_hz:.3g} Hz (Winter's residual analysis)"
    )
    return (
        f"the automatic low-pass decision is borderline: the unfiltered speed noise at rest, "
        f"{1e3 * lowpass.speed_noise:.2f} mm/s, is within {100 * BORDERLINE_FRACTION:g} % of the "
        f"{1e3 * SPEED_NOISE_LIMIT:g} mm/s limit; {instead} would change the status of {changed} of "
        f"{len(features)} trials and SPARC by a median |change| of {np.median(d) if d.size else np.nan:.3g} "
        f"(over the {int(both.sum())} trials valid both ways); choose explicitly with --lowpass none or HZ "
        f"(chapter 13)"
    )


def select(features: pd.DataFrame) -> pd.DataFrame:
    """The selected trials (status ``selected``), index reset: the input of the clustering chapter.

    Parameters
    ----------
    features : pandas.DataFrame
        The feature table of :func:`trial_features` (pv and contact_speed in m/s, duration in s, sparc
        dimensionless).

    Returns
    -------
    pandas.DataFrame
        The rows of the selected trials, same columns and units.
    """
    return features[features["status"] == "selected"].reset_index(drop=True)


def status_counts(features: pd.DataFrame) -> pd.DataFrame:
    """Trials per participant and status (columns selected, excluded, invalid, total), with a total row.

    Parameters
    ----------
    features : pandas.DataFrame
        The feature table of :func:`trial_features` (pv and contact_speed in m/s, duration in s, sparc
        dimensionless).

    Returns
    -------
    pandas.DataFrame
        The counts of trials (dimensionless).
    """
    t = pd.crosstab(features["participant"], features["status"])
    t = t.reindex(index=sort_ids(t.index), columns=["selected", "excluded", "invalid"], fill_value=0)
    t["total"] = t.sum(axis=1)
    t.loc["all"] = t.sum(axis=0)
    return t


def participant_summary(features: pd.DataFrame) -> pd.DataFrame:
    """Per participant, over its valid (selected or excluded) trials: medians and interquartile ranges.

    Median and interquartile range of peak speed (m/s), contact speed (m/s), duration (s) and SPARC, and
    the number of selected trials.

    Parameters
    ----------
    features : pandas.DataFrame
        The feature table of :func:`trial_features` (pv and contact_speed in m/s, duration in s, sparc
        dimensionless).

    Returns
    -------
    pandas.DataFrame
        One row per participant: the medians and interquartile ranges (m/s, s, SPARC dimensionless) and
        the number of selected trials.
    """
    valid = features[features["status"] != "invalid"]
    g = valid.groupby("participant", sort=True)
    cols = {"pv": "PV (m/s)", "contact_speed": "contact speed (m/s)", "duration": "duration (s)", "sparc": "SPARC"}
    out = pd.DataFrame({"valid trials": g.size(), "selected": g["status"].agg(lambda s: int((s == "selected").sum()))})
    for c, name in cols.items():
        q = g[c].quantile([0.25, 0.5, 0.75]).unstack()
        out[f"{name} median"] = q[0.5]
        out[f"{name} IQR"] = q[0.75] - q[0.25]
    return out.reindex(sort_ids(out.index))


def rest_speed(recordings: Recordings, features: pd.DataFrame, margin: float = 0.2) -> np.ndarray:
    """Speeds at the interior samples more than ``margin`` s before onset in the valid trials.

    Central differences, as inside a segment: the noise floor at rest (white position noise of SD s gives
    s * fs / sqrt(2) per axis). The margin leaves out the slow start of the movement; the first sample is
    left out because its one-sided three-point difference amplifies noise about 3.6 times more than a
    central difference (coefficients 3/2, -2, 1/2 against 1/2, -1/2).

    Parameters
    ----------
    recordings : Recordings or pandas.DataFrame
        The recordings (t in s, positions in m), or a long table :func:`skilllib.recordings.recordings_from_frame`
        validates.
    features : pandas.DataFrame
        The feature table of :func:`trial_features` (pv and contact_speed in m/s, duration in s, sparc
        dimensionless).
    margin : float
        The time before onset left out (s).

    Returns
    -------
    numpy.ndarray
        The speeds at rest (m/s).
    """
    rec = _as_recordings(recordings)
    out = []
    valid = features.loc[features["status"] != "invalid", ["participant", "trial", "t_onset"]]
    for p, tr, t_on in valid.itertuples(index=False):
        d = rec.trial(p, tr)
        o = int(np.searchsorted(d.t, t_on - margin))
        if o >= 3:
            out.append(np.linalg.norm(velocity(d.pos[:o], rec.fs), axis=1)[1:-1])
    return np.concatenate(out) if out else np.array([])
