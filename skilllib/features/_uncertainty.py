"""How precisely SPARC is measured: its spread over the sampling phase and over the speed estimator.

At 60 Hz a segment cut at contact holds a few dozen samples, and where the sampling grid happens to fall on
the movement (its *phase*) decides where the segment starts and, above all, where it ends: the last
sample before contact lies anywhere between zero and one interval (1/60 s) before the touch, and SPARC on
these segments tracks the contact ratio (contact speed / peak speed; chapter 3). The same movement sampled
a fraction of an interval later can therefore have another SPARC. Real recordings have one phase only;
this module estimates the spread from them:

* :func:`sparc_shift_spread`: per trial, the approach (the samples before the end sample) is
  interpolated by a cubic spline (``scipy.interpolate.CubicSpline``, not-a-knot) and re-sampled a fraction
  ``delta`` of an interval later, at ``t + delta / fs``, on the samples that stay inside the recorded
  approach (the instant of contact between the last approach sample and the end sample is unknown, so the
  grid is not extrapolated past the last approach sample). The run's rules then segment the re-sampled
  approach again (:func:`skilllib.features.segment_arrays`: the run's filter, the same Savitzky-Golay
  derivative, the onset found again) and SPARC is computed with the same parameters. The spread of a
  trial is the SD (``ddof=0``: over a uniform grid of phases) and the range of its SPARC over the shifts,
  zero shift included.
* :func:`phase_spread`: the same table from recordings that *were* sampled at several phases (the
  synthetic cohort, ``CohortModel(phase=...)``): the exact experiment the estimate stands for.
* :func:`spread_share`: the share of SPARC's variance across trials that the phase accounts for.
* :func:`sparc_by_estimator`: SPARC of the same segments with the book's speed (the derivative of the
  approach only) and with a plain central difference of the positions (``numpy.gradient``), of the
  approach and of the whole trial.
* :func:`cluster_agreement`: two clusterings of (mostly) the same trials compared: the adjusted Rand
  index over the trials both cluster (Hubert & Arabie 1985) and, centres matched one to one by least
  total distance, which prototypes are the same trial.

Values of SPARC are dimensionless.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
from scipy.interpolate import CubicSpline
from scipy.optimize import linear_sum_assignment
from sklearn.metrics import adjusted_rand_score

from .. import smoothness
from ..recordings import ID_COLUMNS, Recordings
from ._filtering import Lowpass
from ._rules import PAPER_END, PAPER_START, StartRule
from ._segmentation import frame_at, segment_arrays, velocity
from ._table import SPARC_PARAMS, trial_events

#: Sub-sample shifts of :func:`sparc_shift_spread` (fractions of a sample interval, dimensionless).
SUBSAMPLE_SHIFTS: tuple[float, ...] = (0.25, 0.5, 0.75)


def _value_columns(table: pd.DataFrame) -> list[str]:
    """The columns holding the value at one phase or shift (``sparc_0``, ``sparc_0.25``, ...), in order."""
    pattern = re.compile(rf"^{re.escape(table.attrs.get('column', 'sparc'))}_(\d+(\.\d+)?)$")
    cols = [c for c in table.columns if pattern.match(str(c))]
    return sorted(cols, key=lambda c: float(pattern.match(c).group(1)))


def _finish(ids: pd.DataFrame, values: np.ndarray, shifts: Sequence[float], column: str = "sparc") -> pd.DataFrame:
    """The spread table: ids, one column per shift, ``<column>_sd`` (ddof 0) and ``<column>_range``."""
    out = ids.reset_index(drop=True).copy()
    for j, d in enumerate(shifts):
        out[f"{column}_{d:g}"] = values[:, j]
    with np.errstate(invalid="ignore"):
        ok = np.isfinite(values).sum(axis=1) > 0
        sd = np.full(len(values), np.nan)
        rng = np.full(len(values), np.nan)
        sd[ok] = np.nanstd(values[ok], axis=1)
        rng[ok] = np.nanmax(values[ok], axis=1) - np.nanmin(values[ok], axis=1)
    out[f"{column}_sd"], out[f"{column}_range"] = sd, rng
    out.attrs["shifts"] = tuple(float(d) for d in shifts)
    out.attrs["column"] = column
    return out


def _rows(features: pd.DataFrame, status: Iterable[str]) -> pd.DataFrame:
    if "status" not in features or "t_contact" not in features:
        raise ValueError("features must be a feature table of skilllib.trial_features (status, t_contact)")
    return features[features["status"].isin(tuple(status))].reset_index(drop=True)


def _shifted_speed(
    t: np.ndarray,
    pos: np.ndarray,
    spline: CubicSpline,
    fs: float,
    shift: float,
    start: StartRule,
    events: Mapping[str, np.ndarray] | None,
    lowpass: Lowpass | None,
) -> np.ndarray | None:
    """The segment's speed (m/s) after re-sampling the approach (times ``t`` in s, positions ``pos`` in m)
    ``shift`` of an interval later; None when the re-sampled approach cannot be segmented."""
    if shift:
        tn = t + shift / fs
        tn = tn[tn <= t[-1] + 1e-9 / fs]  # interpolation only: not past the last approach sample
        pos = spline(tn)
        t = tn
    t_all = np.r_[t, t[-1] + 1.0 / fs]
    pos_all = np.vstack([pos, pos[-1:]])  # the end sample: only marks where the approach ends
    contact = np.r_[np.zeros(len(t), dtype=bool), True]
    seg = segment_arrays(t_all, pos_all, contact, fs, start=start, end=PAPER_END, events=events, lowpass=lowpass)
    return None if isinstance(seg, str) else seg.speed


def sparc_shift_spread(
    recordings: Recordings,
    features: pd.DataFrame,
    *,
    shifts: Sequence[float] = SUBSAMPLE_SHIFTS,
    sparc_params: Mapping[str, float] | None = None,
    status: Iterable[str] = ("selected",),
) -> pd.DataFrame:
    """Per trial, SPARC of the approach re-sampled at sub-sample shifts: an uncertainty of SPARC from
    the recording alone.

    Each trial's approach (the samples before its end sample, ``t_contact`` of ``features``) is
    interpolated by a cubic spline and re-sampled at ``t + delta / fs`` for every ``delta`` of
    ``shifts`` (the samples that stay inside the recorded approach); the run's rules (start rule and
    filter in ``features.attrs``) segment it again and SPARC is computed with ``sparc_params``
    (:mod:`skilllib.features._uncertainty`). Zero shift, the recording itself, is always included.

    Parameters
    ----------
    recordings : Recordings
        The recordings the features were computed from (t in s, positions in m).
    features : pandas.DataFrame
        Their feature table, :func:`skilllib.features.trial_features` (t_contact in s).
    shifts : sequence of float
        Shifts, fractions of a sample interval in (0, 1) (dimensionless).
    sparc_params : mapping of str to float or None
        SPARC's ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless); None:
        :data:`skilllib.features.SPARC_PARAMS`. Pass those of the feature table.
    status : iterable of str
        The trials to measure, by ``status`` of the table (text; default the selected ones).

    Returns
    -------
    pandas.DataFrame
        One row per trial: ``participant``, ``trial``, ``sparc_0`` (the recording's SPARC), one column
        ``sparc_<delta>`` per shift (NaN when the shifted approach cannot be segmented), ``sparc_sd`` (SD
        over the shifts, ddof 0) and ``sparc_range`` (largest minus smallest); all SPARC values
        dimensionless. ``attrs["shifts"]``: the shifts, 0 first.

    Raises
    ------
    ValueError
        For shifts outside (0, 1) or a table that is not a feature table.
    """
    rec = recordings
    shifts = tuple(float(d) for d in shifts)
    if any(not 0.0 < d < 1.0 for d in shifts):
        raise ValueError(f"shifts must be fractions of a sample interval in (0, 1), got {shifts}")
    if not rec.fs or not np.isfinite(rec.fs):
        raise ValueError("the recordings need a sampling rate (fs, Hz) to shift by a fraction of an interval")
    params = {**SPARC_PARAMS, **(sparc_params or {})}
    rows = _rows(features, status)
    grid = (0.0, *shifts)
    values = np.full((len(rows), len(grid)), np.nan)
    start = features.attrs.get("start", PAPER_START)
    lowpass = features.attrs.get("lowpass")
    speeds, where = [], []
    for i, (p, tr, t_end) in enumerate(rows[["participant", "trial", "t_contact"]].itertuples(index=False)):
        d = rec.trial(p, tr)
        c = frame_at(d.t, float(t_end), rec.fs)
        t, pos = np.asarray(d.t[:c], dtype=float), np.asarray(d.pos[:c], dtype=float)
        spline = CubicSpline(t, pos, axis=0)
        events = trial_events(rec, p, tr) if start.kind == "event" else None
        for j, delta in enumerate(grid):
            v = _shifted_speed(t, pos, spline, rec.fs, delta, start, events, lowpass)
            if v is not None:
                speeds.append(v)
                where.append((i, j))
    if speeds:
        s = smoothness.sparc_many(speeds, rec.fs, **params)
        ii, jj = np.array(where).T
        values[ii, jj] = s
    return _finish(rows[list(ID_COLUMNS)], values, grid)


def phase_spread(
    features_by_phase: Mapping[float, pd.DataFrame], status: Iterable[str] = ("selected",), column: str = "sparc"
) -> pd.DataFrame:
    """Per trial, SPARC (or another feature) of recordings sampled at several phases (the exact
    experiment :func:`sparc_shift_spread` estimates).

    The trials are those of the first table (the reference phase) with a ``status`` in ``status``; each
    other phase gives their SPARC whatever its own status there (its contact speed, and so its selection,
    may change with the phase), NaN where it is invalid.

    Parameters
    ----------
    features_by_phase : mapping of float to pandas.DataFrame
        Phase (a fraction of a sample interval, dimensionless) -> the feature table of the recordings
        sampled at that phase (:func:`skilllib.features.trial_features`; SPARC dimensionless). The first
        entry is the reference.
    status : iterable of str
        The reference's trials to keep, by status (text; default the selected ones).
    column : str
        The feature (text): ``sparc`` (dimensionless), ``pv`` (m/s), any column of the tables.

    Returns
    -------
    pandas.DataFrame
        Columns as :func:`sparc_shift_spread`: ``participant``, ``trial``, one ``<column>_<phase>``
        column per phase, ``<column>_sd`` (ddof 0) and ``<column>_range`` (in the feature's unit: SPARC
        dimensionless, PV m/s); ``attrs["shifts"]``: the phases, ``attrs["column"]``: the feature.

    Raises
    ------
    ValueError
        For an empty mapping.
    """
    if not features_by_phase:
        raise ValueError("need the feature tables of at least one phase")
    phases = list(features_by_phase)
    ref = _rows(features_by_phase[phases[0]], status)
    ids = list(ID_COLUMNS)
    values = np.column_stack(
        [
            ref[ids]
            .merge(features_by_phase[ph][[*ids, "status", column]], on=ids, how="left")
            .pipe(lambda m: m[column].where(m["status"] != "invalid"))
            .to_numpy(dtype=float)
            for ph in phases
        ]
    )
    return _finish(ref[ids], values, phases, column)


def spread_share(table: pd.DataFrame) -> float:
    """The share of a feature's variance across trials and phases that lies within trials (dimensionless).

    ``mean_i var_phase(x_i) / var(x)`` over the trials measured at every phase or shift (both variances
    ddof 0, so the total splits exactly into the between-trial and within-trial parts): the part of the
    feature's spread that is the sampling phase, not the movement.

    Parameters
    ----------
    table : pandas.DataFrame
        A table of :func:`phase_spread` or :func:`sparc_shift_spread` (SPARC dimensionless, PV m/s).

    Returns
    -------
    float
        The within-trial share of the variance, in [0, 1] (dimensionless); NaN without complete rows.
    """
    v = table[_value_columns(table)].to_numpy(dtype=float)
    v = v[np.isfinite(v).all(axis=1)]
    if v.size == 0 or v.var() == 0:
        return np.nan
    return float(v.var(axis=1).mean() / v.var())


def sparc_by_estimator(
    recordings: Recordings,
    features: pd.DataFrame,
    *,
    sparc_params: Mapping[str, float] | None = None,
    status: Iterable[str] = ("selected",),
) -> pd.DataFrame:
    """Per trial, SPARC of the same segment with three speed estimators.

    The segment is the table's (onset ``t_onset`` to the sample before ``t_contact``); its speed is

    * ``sparc``: the book's (:func:`skilllib.features.velocity` of the approach only, filtered as the run
      was; at 60 Hz the second-order difference, one-sided three-point at the last sample);
    * ``sparc_gradient``: ``numpy.gradient`` of the approach's positions (central inside, a two-point
      backward difference at the last sample);
    * ``sparc_gradient_trial``: ``numpy.gradient`` of the whole trial's positions, then cut to the segment
      (the last sample's central difference reaches across contact into the first contact sample).

    Parameters
    ----------
    recordings : Recordings
        The recordings (t in s, positions in m).
    features : pandas.DataFrame
        Their feature table, :func:`skilllib.features.trial_features` (t in s).
    sparc_params : mapping of str to float or None
        SPARC's ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless); None:
        :data:`skilllib.features.SPARC_PARAMS`.
    status : iterable of str
        The trials, by ``status`` of the table (text; default the selected ones).

    Returns
    -------
    pandas.DataFrame
        ``participant``, ``trial``, ``sparc``, ``sparc_gradient``, ``sparc_gradient_trial``
        (dimensionless).
    """
    rec = recordings
    fs = rec.fs
    params = {**SPARC_PARAMS, **(sparc_params or {})}
    lowpass = features.attrs.get("lowpass")
    rows = _rows(features, status)
    book, grad, whole = [], [], []
    for p, tr, t_on, t_end in rows[["participant", "trial", "t_onset", "t_contact"]].itertuples(index=False):
        d = rec.trial(p, tr)
        o, c = frame_at(d.t, float(t_on), fs), frame_at(d.t, float(t_end), fs)
        pos = np.asarray(d.pos, dtype=float)
        approach = lowpass.apply(pos[:c], fs) if lowpass is not None else pos[:c]
        book.append(np.linalg.norm(velocity(approach, fs), axis=1)[o:c])
        grad.append(np.linalg.norm(np.gradient(approach, 1.0 / fs, axis=0), axis=1)[o:c])
        trial = lowpass.apply(pos, fs) if lowpass is not None else pos
        whole.append(np.linalg.norm(np.gradient(trial, 1.0 / fs, axis=0), axis=1)[o:c])
    out = rows[list(ID_COLUMNS)].copy()
    for name, speeds in (("sparc", book), ("sparc_gradient", grad), ("sparc_gradient_trial", whole)):
        out[name] = smoothness.sparc_many(speeds, fs, **params) if speeds else np.zeros(0)
    return out


@dataclass(frozen=True, eq=False)
class ClusterAgreement:
    """Two clusterings compared (:func:`cluster_agreement`).

    Attributes
    ----------
    ari : float
        Adjusted Rand index of the two partitions over the trials both cluster (dimensionless).
    n_common : int
        Trials both cluster (dimensionless).
    n_reference, n_other : int
        Trials each clusters (dimensionless).
    clusters : pandas.DataFrame
        One row per reference cluster: ``matched`` (the other's cluster matched to it), the centres
        (``pv_ref``, ``pv_other`` in m/s, ``sparc_ref``, ``sparc_other`` dimensionless; or the features
        clustered), ``prototype_ref`` and ``prototype_other`` ((participant, trial) ids, text),
        ``same_prototype`` (bool) and ``prototype_distance`` (Euclidean distance between the two prototypes'
        feature values, in the paper's clustering space: PV in m/s and SPARC together).
    """

    ari: float
    n_common: int
    n_reference: int
    n_other: int
    clusters: pd.DataFrame

    @property
    def prototypes_kept(self) -> int:
        """Matched clusters whose prototype is the same trial (dimensionless)."""
        return int(self.clusters["same_prototype"].sum())


def cluster_agreement(reference: Any, other: Any) -> ClusterAgreement:
    """How far two K-means fits of (mostly) the same trials agree: ARI and prototype identity.

    ARI (``sklearn.metrics.adjusted_rand_score``) over the trials both fits cluster, matched by
    (participant, trial). Clusters are paired one to one by their centres (``scipy.optimize.
    linear_sum_assignment`` on the Euclidean distances between centres in the features' units, the
    space the paper's K-means clusters in); a pair keeps its prototype when both prototypes are the same
    trial.

    Parameters
    ----------
    reference, other : PrototypeResult
        Two fits of :func:`skilllib.prototypes.fit_prototypes` with the same k and features (``data`` with
        participant, trial and cluster; ``centres`` in the features' units: PV m/s, SPARC dimensionless;
        ``prototypes`` with participant and trial).

    Returns
    -------
    ClusterAgreement
        The ARI, the trial counts and the matched clusters.

    Raises
    ------
    ValueError
        When the two fits have different k or features, or share fewer than two trials.
    """
    ids = list(ID_COLUMNS)
    if list(reference.centres.columns) != list(other.centres.columns) or len(reference.centres) != len(other.centres):
        raise ValueError("the two fits must have the same k and the same features")
    both = reference.data[[*ids, "cluster"]].merge(other.data[[*ids, "cluster"]], on=ids, suffixes=("_r", "_o"))
    if len(both) < 2:
        raise ValueError(f"the two fits share {len(both)} trial(s); need at least 2 to compare")
    ari = float(adjusted_rand_score(both["cluster_r"], both["cluster_o"]))
    cr, co = reference.centres.to_numpy(dtype=float), other.centres.to_numpy(dtype=float)
    rows, cols = linear_sum_assignment(np.linalg.norm(cr[:, None, :] - co[None, :, :], axis=2))
    pr = list(reference.prototypes[ids].itertuples(index=False, name=None))
    po = list(other.prototypes[ids].itertuples(index=False, name=None))
    table = pd.DataFrame({"matched": cols}, index=pd.Index(rows, name="cluster"))
    for f in reference.centres.columns:
        table[f"{f}_ref"] = reference.centres[f].to_numpy()[rows]
        table[f"{f}_other"] = other.centres[f].to_numpy()[cols]
    table["prototype_ref"] = [pr[r] for r in rows]
    table["prototype_other"] = [po[c] for c in cols]
    table["same_prototype"] = [pr[r] == po[c] for r, c in zip(rows, cols)]
    feats = list(reference.centres.columns)
    xr = reference.prototypes[feats].to_numpy(dtype=float)[rows]
    xo = other.prototypes[feats].to_numpy(dtype=float)[cols]
    table["prototype_distance"] = np.linalg.norm(xr - xo, axis=1)
    return ClusterAgreement(ari, len(both), len(reference.data), len(other.data), table)
