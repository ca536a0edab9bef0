"""How much the paper's procedure depends on the SPARC parameters: the pipeline under several settings.

SPARC's band is capped at a maximum cut-off ``fc`` (Hz). On long, smooth profiles the amplitude
threshold ends the band well below any sensible ``fc`` and the cap does not matter; on short segments
cut at contact the spectrum is wide, the cap ends many bands, and the cap then decides the value
(chapter 2). :func:`sparc_sensitivity` runs the clustering part of the pipeline -- features, selection,
silhouette sweep, K-means prototypes (:mod:`skilllib.features`, :mod:`skilllib.prototypes`) -- once per
setting and compares every setting with the first one, the reference: which trials' SPARC changes and by
how much, how many bands the cap ends, the adjusted Rand index between the two k-cluster partitions
(Hubert & Arabie 1985) and which prototype trials survive. The selection (contact speed) does not
depend on SPARC, so every setting clusters the same trials. Every setting clusters the same features,
by default the paper's (PV, SPARC); a feature set without ``sparc`` is refused (ValueError): its
clusters could not change with the SPARC setting.

The chapters (1 and 3) and ``python -m skilllib run --sensitivity`` call it.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
from sklearn.metrics import adjusted_rand_score

from ..features import select, trial_features
from ..recordings import Recordings
from ..smoothness import SPARC_PARAMS
from . import _kmeans as pt
from ._json import json_value

#: The settings the book compares: its own (the paper's 0-20 Hz) first, then the authors' Python default.
DEFAULT_SETTINGS: tuple[dict[str, float], ...] = ({"fc": 20.0}, {"fc": 10.0})
#: A trial's SPARC "changes" between two settings when the values differ by more than this (rounding).
CHANGE_TOL = 1e-9


def setting_label(params: Mapping[str, float]) -> str:
    """``"fc 20 Hz, amp_th 0.05, padlevel 4"`` for a complete parameter dict.

    Parameters
    ----------
    params : mapping of str to float
        ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless).

    Returns
    -------
    str
        The label (text).
    """
    return f"fc {params['fc']:g} Hz, amp_th {params['amp_th']:g}, padlevel {params['padlevel']:g}"


@dataclass(frozen=True, eq=False)
class SettingRun:
    """The pipeline's clustering under one SPARC setting.

    ``params``: fc (Hz), amp_th, padlevel; ``features``: :func:`skilllib.features.trial_features` of every
    trial with them; ``sweep``: the silhouette sweep of the selected trials; ``fit``: the k-cluster
    K-means fit and its prototypes (None when the selected trials are too few to cluster)."""

    params: dict[str, float]
    features: pd.DataFrame
    sweep: pt.SilhouetteSweep | None
    fit: pt.PrototypeResult | None

    @property
    def label(self) -> str:
        return setting_label(self.params)

    @property
    def selected(self) -> pd.DataFrame:
        return select(self.features)

    @property
    def n_capped(self) -> int:
        """Selected trials whose band ``fc`` ended (rather than the amplitude threshold)."""
        return int(self.selected["sparc_capped"].sum())

    def prototype_ids(self) -> set[tuple[Any, Any]]:
        if self.fit is None:
            return set()
        return set(self.fit.prototypes[["participant", "trial"]].itertuples(index=False, name=None))


@dataclass(frozen=True, eq=False)
class SparcSensitivity:
    """:func:`sparc_sensitivity`'s result: ``runs[0]`` is the reference, ``k`` the number of clusters.

    Attributes
    ----------
    runs : list of SettingRun
        The clustering under each SPARC setting, the reference first.
    k : int
        The number of clusters (dimensionless).
    features : tuple of str
        The clustering features of every setting (text); ``sparc`` among them.
    """

    runs: list[SettingRun]
    k: int
    features: tuple[str, ...] = pt.FEATURES

    @property
    def reference(self) -> SettingRun:
        return self.runs[0]

    def sparc_table(self) -> pd.DataFrame:
        """The selected trials (rows: participant, trial, pv, duration, n) with their SPARC and ``capped``
        flag under every setting (columns ``sparc | <label>`` and ``capped | <label>``)."""
        base = self.reference.selected[["participant", "trial", "pv", "duration", "n"]].copy()
        for run in self.runs:
            base[f"sparc | {run.label}"] = run.selected["sparc"].to_numpy()
            base[f"capped | {run.label}"] = run.selected["sparc_capped"].to_numpy(dtype=bool)
        return base

    def summary(self) -> pd.DataFrame:
        """One row per setting: selected trials, capped bands among them (count and share), mean and SD of
        SPARC, its correlation with the segment duration, the average silhouette at k and the valid k."""
        rows = {}
        for run in self.runs:
            s = run.selected
            rows[run.label] = {
                "selected": len(s),
                "capped": run.n_capped,
                "capped share": run.n_capped / len(s) if len(s) else np.nan,
                "SPARC mean": s["sparc"].mean(),
                "SPARC SD": s["sparc"].std(),
                "corr(SPARC, duration)": _corr(s["sparc"], s["duration"]),
                f"silhouette, k = {self.k}": run.fit.silhouette if run.fit is not None else np.nan,
                "valid k": run.sweep.valid_ks() if run.sweep is not None else [],
            }
        return pd.DataFrame.from_dict(rows, orient="index").rename_axis("setting")

    def silhouettes(self) -> pd.DataFrame:
        """Average silhouette per k (rows) under every setting (columns)."""
        return pd.DataFrame(
            {
                run.label: pd.Series(dict(zip(run.sweep.ks, run.sweep.scores)))
                for run in self.runs
                if run.sweep is not None
            }
        ).rename_axis("k")

    def comparison(self) -> pd.DataFrame:
        """Every other setting against the reference: trials whose SPARC changes (``changed``, beyond
        :data:`CHANGE_TOL`), the mean and largest absolute change, the reference's SD of SPARC across the
        selected trials (the scale to read the changes on), the ARI of the two k-cluster partitions and
        how many of the setting's k prototypes are prototypes of the reference too."""
        ref = self.reference
        rows = {}
        for run in self.runs[1:]:
            d = run.selected["sparc"].to_numpy() - ref.selected["sparc"].to_numpy()
            both = ref.fit is not None and run.fit is not None
            rows[run.label] = {
                "changed": int(np.sum(np.abs(d) > CHANGE_TOL)),
                "of": len(d),
                "mean |change|": float(np.mean(np.abs(d))) if len(d) else np.nan,
                "max |change|": float(np.max(np.abs(d))) if len(d) else np.nan,
                "reference SD": float(ref.selected["sparc"].std()),
                "ARI": adjusted_rand_score(ref.fit.labels, run.fit.labels) if both else np.nan,
                "prototypes kept": len(run.prototype_ids() & ref.prototype_ids()) if both else 0,
            }
        return pd.DataFrame.from_dict(rows, orient="index").rename_axis(f"vs {ref.label}")

    def prototypes(self) -> pd.DataFrame:
        """The prototypes of every setting (clusters numbered by centre PV, or the first feature; columns
        participant, trial, the features) with ``kept``: the same trial is a prototype of the reference
        too."""
        ref_ids = self.reference.prototype_ids()
        parts = {}
        for run in self.runs:
            if run.fit is not None:
                p = run.fit.prototypes.drop(columns="row")
                p["kept"] = [tuple(x) in ref_ids for x in p[["participant", "trial"]].itertuples(index=False)]
                parts[run.label] = p
        return pd.concat(parts, names=["setting"]) if parts else pd.DataFrame()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``k``, ``settings`` (one per run: ``params``, ``n_selected``, ``n_capped``,
        ``silhouette`` {k: score}, ``prototypes`` [{cluster, participant, trial, pv, sparc, kept}] and, for
        all but the reference, ``vs_reference`` {n_sparc_changed, mean_abs_sparc_change,
        max_abs_sparc_change, ari, prototypes_kept}). With other ``features`` the prototypes hold those
        in place of pv, sparc, in their order."""
        comp = self.comparison()
        protos = self.prototypes()
        out = []
        for run in self.runs:
            entry: dict[str, Any] = {
                "params": dict(run.params),
                "n_selected": len(run.selected),
                "n_capped": run.n_capped,
                "silhouette": run.sweep.to_dict() if run.sweep is not None else {},
            }
            if run.fit is not None:
                p = protos.loc[run.label]
                entry["prototypes"] = [
                    {
                        "cluster": int(c),
                        "participant": json_value(r["participant"]),
                        "trial": json_value(r["trial"]),
                        **{f: float(r[f]) for f in self.features},
                        "kept": bool(r["kept"]),
                    }
                    for c, r in p.iterrows()
                ]
            if run is not self.reference:
                c = comp.loc[run.label]
                entry["vs_reference"] = {
                    "n_sparc_changed": int(c["changed"]),
                    "mean_abs_sparc_change": json_value(c["mean |change|"]),
                    "max_abs_sparc_change": json_value(c["max |change|"]),
                    "ari": json_value(c["ARI"]),
                    "prototypes_kept": int(c["prototypes kept"]),
                }
            out.append(entry)
        return {"k": self.k, "settings": out}


def _corr(a: pd.Series, b: pd.Series) -> float:
    if len(a) < 3 or a.std() == 0 or b.std() == 0:
        return np.nan
    return float(np.corrcoef(a, b)[0, 1])


def complete_params(setting: Mapping[str, float]) -> dict[str, float]:
    """A setting with the book's defaults (:data:`skilllib.smoothness.SPARC_PARAMS`) filled in.

    Parameters
    ----------
    setting : mapping of str to float
        Some of ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless).

    Returns
    -------
    dict of str to float
        All three: ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless).

    Raises
    ------
    ValueError
        For a key that is not a SPARC parameter.
    """
    unknown = set(setting) - set(SPARC_PARAMS)
    if unknown:
        raise ValueError(f"unknown SPARC parameter(s) {sorted(unknown)}; use fc, amp_th, padlevel")
    return {**SPARC_PARAMS, **{key: float(v) if key != "padlevel" else int(v) for key, v in setting.items()}}


def sparc_sensitivity(
    recordings: Recordings,
    settings: Sequence[Mapping[str, float]] = DEFAULT_SETTINGS,
    *,
    k: int = pt.DEFAULT_K,
    scaling: pt.Scaling = "raw",
    random_state: int = 0,
    k_range: tuple[int, int] = pt.K_RANGE,
    reference: tuple[pd.DataFrame, pt.SilhouetteSweep | None] | None = None,
    lowpass: Any = "auto",
    features: Sequence[str] = pt.FEATURES,
    table: Callable[[Mapping[str, float]], pd.DataFrame] | None = None,
) -> SparcSensitivity:
    """The clustering of the paper under each SPARC setting in ``settings``, compared with the first.

    Per setting: :func:`~skilllib.features.trial_features`, the selected trials, the silhouette sweep over
    ``k_range`` and the ``k``-cluster fit (k reduced to the largest the sweep reached; the sweep's own
    shrink warnings are not repeated).

    Parameters
    ----------
    recordings : Recordings or pandas.DataFrame
        The recordings (t in s, positions in m).
    settings : sequence of mapping of str to float
        The SPARC settings: dicts of ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless); missing keys
        take the book's defaults. The first is the reference.
    k : int
        The number of clusters (dimensionless).
    scaling : {"raw", "standard"}
        The clustering space (text), as in :func:`skilllib.prototypes.fit_prototypes`.
    random_state : int
        The seed of the fits (dimensionless), as in :func:`skilllib.prototypes.fit_prototypes`.
    k_range : tuple of int
        (k_min, k_max) of the silhouette sweep (dimensionless).
    reference : tuple or None
        The first setting's features and sweep when the caller has them already (the pipeline), computed
        with the same options; they are not recomputed. None: computed here.
    lowpass : Any
        The positions' filter (:func:`skilllib.features.trial_features`; cut-off in Hz), the same for every
        setting (the pipeline passes the one its run chose).
    features : sequence of str
        The clustering features of every setting (each in its unit: ``pv`` m/s, ``sparc`` and ``ldlj``
        dimensionless, ...), as in :func:`skilllib.prototypes.silhouette_sweep`; must include ``sparc``.
        A ``reference`` sweep must have clustered the same features.
    table : callable or None
        ``table(params)``: the feature table (status set by the run's selection) under the SPARC setting
        ``params`` (fc in Hz), for a run whose segmentation rules or selection are not the paper's (the
        pipeline passes its own); None: :func:`~skilllib.features.trial_features` with the paper's rules
        and contact-speed window.

    Returns
    -------
    SparcSensitivity
        The clustering under each setting (PV in m/s, SPARC dimensionless).

    Raises
    ------
    ValueError
        For no settings, an unknown SPARC parameter, features without ``sparc`` (the clusters would not
        depend on the setting) or a ``reference`` sweep of other features.
    """
    if not settings:
        raise ValueError("no SPARC settings to compare")
    cluster_on = pt._features(features)
    if "sparc" not in cluster_on:
        raise ValueError(
            f"the clustering features {pt._names(cluster_on)} do not include sparc: the clusters cannot depend on "
            "the SPARC setting, there is nothing to compare"
        )
    if reference is not None and reference[1] is not None and tuple(reference[1].features) != cluster_on:
        raise ValueError(
            f"the reference sweep clustered {pt._names(reference[1].features)}, not {pt._names(cluster_on)}"
        )
    params = [complete_params(s) for s in settings]
    runs = []
    k_used = int(k)
    for i, p in enumerate(params):
        if i == 0 and reference is not None:
            feats, sweep = reference
            if sweep is not None:
                k_used = min(k_used, int(sweep.ks[-1]))
            runs.append((p, feats, sweep))
            continue
        feats = trial_features(recordings, sparc_params=p, lowpass=lowpass) if table is None else table(p)
        sel = select(feats)
        missing = [f for f in cluster_on if f not in sel.columns]
        if missing:  # not a too-few-trials case: say so rather than leave fit = None
            raise ValueError(f"the feature table lacks the clustering feature(s) {missing}")
        sweep = None
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", UserWarning)
                sweep = pt.silhouette_sweep(
                    sel, *k_range, scaling=scaling, random_state=random_state, features=cluster_on
                )
        except ValueError:
            pass  # too few (distinct) selected trials to cluster: the run says so through fit = None
        if sweep is not None:
            k_used = min(k_used, int(sweep.ks[-1]))
        runs.append((p, feats, sweep))
    out = []
    for p, feats, sweep in runs:
        fit = None
        if sweep is not None and k_used in sweep.results:
            fit = sweep.results[k_used]
        out.append(SettingRun(p, feats, sweep, fit))
    ids = [tuple(map(tuple, r.selected[["participant", "trial"]].to_numpy())) for r in out]
    if any(i != ids[0] for i in ids[1:]):  # cannot happen: the selection does not use SPARC
        raise RuntimeError("the settings selected different trials")
    return SparcSensitivity(out, k_used, cluster_on)
