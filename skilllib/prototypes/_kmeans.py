"""Prototypical task executions: silhouette sweep and K-means prototypes (paper Sect. 6, Fig. 2).

The paper clusters the selected trials' (PV, SPARC) tuples -- peak speed PV in m/s and the
dimensionless SPARC -- with K-means from scikit-learn (Pedregosa et al. 2011, JMLR 12:2825), checks the
number of clusters k = 2..16 by silhouette analysis (Rousseeuw 1987, J Comput Appl Math 20:53; as in
scikit-learn's example "Selecting the number of clusters with silhouette analysis on KMeans
clustering"), uses k = 6 (average silhouette 0.337) and takes as each cluster's prototype the real
trial nearest its centre.

Input everywhere: a pandas DataFrame, one row per selected trial, with at least the columns
``participant``, ``trial`` and the clustering features, by default the paper's ``pv`` (m/s) and
``sparc``; other columns (``status``, ``duration``, ...) are ignored, rows are not filtered (pass the
selected rows). :func:`feature_frame` builds one from arrays. ``features=`` clusters on any two or more
numeric columns instead (e.g. ``("pv", "ldlj")``, or three features; names and units in
:data:`skilllib.features.FEATURE_UNITS`); the results keep the set (``PrototypeResult.features``,
``SilhouetteSweep.features``) and report centres and prototypes under those names. Clusters are
numbered by their centre's first feature ascending (ties by the next), with the default features by
centre PV (cluster 0 = slowest), so the numbers do not depend on the seed or the method (the paper's
cluster numbers are K-means' arbitrary ones).

Silhouettes are exact up to ``SILHOUETTE_EXACT_MAX`` trials, above it estimated from random subsamples
(:mod:`skilllib.prototypes`). Results for ``results.json``: ``{"silhouette": sweep.to_dict(),
**result.to_dict()}``, see :func:`results_section`; ``sweep.estimate_dict()`` says how they were computed.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import pandas as pd
from sklearn.cluster import AgglomerativeClustering, KMeans
from sklearn.metrics import adjusted_rand_score
from sklearn.mixture import GaussianMixture

from ..recordings import ID_COLUMNS
from ..smoothness import single_threaded
from . import _silhouette as _sil
from ._json import json_value
from ._settings import DEFAULT_K
from ._silhouette import SilhouetteEstimate

Scaling = Literal["raw", "standard"]
Method = Literal["kmeans", "gmm", "agglomerative"]
FEATURES = ("pv", "sparc")  #: the paper's clustering features: PV (m/s) and SPARC (dimensionless)
#: Columns the clustering adds or keeps next to the features: not allowed as feature names.
_RESERVED = (*ID_COLUMNS, "cluster", "row")
K_RANGE = (2, 16)  #: the paper's silhouette sweep


def feature_frame(pv: Any, sparc: Any, participant: Any = None, trial: Any = None, **columns: Any) -> pd.DataFrame:
    """A DataFrame in the module's input format from arrays: PV, SPARC, trial ids and other features.

    Missing ``participant`` defaults to 0 for every row and missing ``trial`` to 0..n-1. Further
    features (to cluster on with ``features=``) are given by name: ``feature_frame(pv, sparc,
    ldlj=ldlj)``.

    Parameters
    ----------
    pv : array_like
        The peak speeds (m/s).
    sparc : array_like
        The SPARC values (dimensionless).
    participant : array_like or None
        The participant ids (text); None: 0 for every row.
    trial : array_like or None
        The trial ids (text); None: 0..n-1.
    \\*\\*columns : array_like
        Further feature columns by name (e.g. ``ldlj``, dimensionless; ``duration``, s), n values each.

    Returns
    -------
    pandas.DataFrame
        Columns ``participant``, ``trial``, ``pv`` (m/s), ``sparc`` (dimensionless), then ``columns`` in
        the order given.
    """
    pv_a, sp_a = np.asarray(pv, dtype=float).ravel(), np.asarray(sparc, dtype=float).ravel()
    if pv_a.shape != sp_a.shape:
        raise ValueError(f"pv has {pv_a.size} values but sparc has {sp_a.size}")
    n = pv_a.size
    part = np.zeros(n, dtype=int) if participant is None else np.asarray(participant).ravel()
    tri = np.arange(n) if trial is None else np.asarray(trial).ravel()
    if part.size != n or tri.size != n:
        raise ValueError(f"participant ({part.size}) and trial ({tri.size}) must have {n} values like pv")
    extra = {name: np.asarray(v, dtype=float).ravel() for name, v in columns.items()}
    clash = [name for name in extra if name in (*_RESERVED, "pv", "sparc")]
    if clash:
        raise ValueError(f"feature column(s) {clash} clash with the frame's own columns")
    wrong = {name: v.size for name, v in extra.items() if v.size != n}
    if wrong:
        raise ValueError(f"column(s) {wrong} must have {n} values like pv")
    return pd.DataFrame({"participant": part, "trial": tri, "pv": pv_a, "sparc": sp_a, **extra})


def _features(features: Sequence[str]) -> tuple[str, ...]:
    """The clustering features as a tuple of column names; ValueError unless >= 2 distinct names."""
    if isinstance(features, str):
        raise ValueError(f"features must be a sequence of column names such as ('pv', 'sparc'), not {features!r}")
    names = tuple(features)
    if not all(isinstance(f, str) for f in names):
        raise ValueError(f"features must be column names (text), got {names!r}")
    if len(names) < 2:
        raise ValueError(f"cluster on at least two features, got {names!r}")
    if len(set(names)) < len(names):
        raise ValueError(f"a feature is named twice in {names!r}")
    reserved = [f for f in names if f in _RESERVED]
    if reserved:
        raise ValueError(f"{reserved} cannot be clustering features: the clustering uses these columns itself")
    return names


def _names(features: Sequence[str]) -> str:
    """``"(pv, sparc)"``: the features for a message."""
    return f"({', '.join(features)})"


def _validate(data: pd.DataFrame, features: tuple[str, ...] = FEATURES) -> pd.DataFrame:
    """The id and feature columns, positionally indexed, features as float; ValueError on missing or
    non-numeric columns, NaN or duplicate ids (messages name ``features``)."""
    if not isinstance(data, pd.DataFrame):
        raise ValueError(f"expected a pandas DataFrame, got {type(data).__name__}; see feature_frame()")
    cols = [*ID_COLUMNS, *features]
    missing = [c for c in cols if c not in data.columns]
    if missing:
        raise ValueError(f"data lacks column(s) {missing}; needs {', '.join(cols)}")
    df = data.loc[:, cols].reset_index(drop=True)
    try:
        x = df[list(features)].to_numpy(dtype=float)
    except (TypeError, ValueError) as e:
        bad_cols = [f for f in features if not pd.api.types.is_numeric_dtype(df[f])]
        raise ValueError(f"feature column(s) {bad_cols or list(features)} are not numeric: {e}") from None
    bad = ~np.isfinite(x).all(axis=1)
    if bad.any():
        ex = list(df.loc[bad, list(ID_COLUMNS)].head(3).itertuples(index=False, name=None))
        raise ValueError(
            f"{int(bad.sum())} trial(s) have NaN or infinite {'/'.join(features)}, e.g. (participant, "
            f"trial) {ex}; drop or deselect them before clustering"
        )
    dup = df.duplicated(list(ID_COLUMNS))
    if dup.any():
        ex = list(df.loc[dup, list(ID_COLUMNS)].head(3).itertuples(index=False, name=None))
        raise ValueError(f"{int(dup.sum())} duplicate (participant, trial) id(s), e.g. {ex}")
    df[list(features)] = x
    return df


def _n_distinct(x: np.ndarray) -> int:
    """Distinct rows of ``x``, as ``len(np.unique(x, axis=0))`` (-0.0 == 0.0) but 3x faster on 68,000 rows."""
    s = x[np.lexsort(x.T[::-1])]
    return min(len(x), 1 + int(np.any(s[1:] != s[:-1], axis=1).sum()))


def _check_k(x: np.ndarray, k: int, features: Sequence[str] = FEATURES) -> int:
    """ValueError unless 2 <= k <= n - 1 and there are at least k distinct points (named by ``features``)."""
    if isinstance(k, bool) or int(k) != k:
        raise ValueError(f"k must be an integer, got {k!r}")
    k, n = int(k), len(x)
    if k < 2:
        raise ValueError(f"k = {k}: need at least 2 clusters (silhouettes need 2 <= k <= n - 1)")
    if n < k + 1:
        raise ValueError(
            f"{n} trials are too few for k = {k} clusters: need at least k + 1 = {k + 1} "
            "(the silhouette is defined for 2 <= k <= n - 1, Rousseeuw 1987)"
        )
    distinct = _n_distinct(x)
    if distinct < k:
        raise ValueError(
            f"only {distinct} distinct {_names(features)} points among {n} trials: cannot form k = {k} clusters"
        )
    return k


def _scale(x: np.ndarray, scaling: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Clustering space ``z = (x - mean) / scale``; returns (z, mean, scale).

    "raw" is the paper's space (the features in their units: PV in m/s, SPARC); "standard" are z-scores as
    ``sklearn.preprocessing.StandardScaler`` (population SD; a constant feature is left unscaled).
    """
    if scaling == "raw":
        return x.copy(), np.zeros(x.shape[1]), np.ones(x.shape[1])
    if scaling == "standard":
        mean, sd = x.mean(axis=0), x.std(axis=0)
        sd[sd == 0] = 1.0
        return (x - mean) / sd, mean, sd
    raise ValueError(f"scaling must be 'raw' or 'standard', got {scaling!r}")


@dataclass(frozen=True)
class _Fit:
    """A fit in clustering space, clusters already ordered by the centres' first feature (PV)."""

    labels: np.ndarray  # (n,) 0..k-1
    centres_z: np.ndarray  # (k, d) in clustering space, d features
    typ_dist: np.ndarray  # (n,) distance of each point to its own cluster's centre (prototype choice)
    z: np.ndarray
    mean: np.ndarray
    scale: np.ndarray


def _fit_arrays(
    x: np.ndarray,
    k: int,
    method: str,
    scaling: str,
    random_state: int,
    n_init: int,
    features: Sequence[str] = FEATURES,
) -> _Fit:
    """Cluster the (n, d) feature values ``x`` (columns ``features``, named in messages) in their space."""
    k = _check_k(x, k, features)
    z, mean, scale = _scale(x, scaling)
    if method == "kmeans":
        km = KMeans(n_clusters=k, init="k-means++", n_init=n_init, random_state=random_state).fit(z)
        raw, cz = km.labels_, km.cluster_centers_
    elif method == "gmm":
        gm = GaussianMixture(n_components=k, covariance_type="full", n_init=n_init, random_state=random_state).fit(z)
        raw, cz = gm.predict(z), gm.means_
    elif method == "agglomerative":
        raw = AgglomerativeClustering(n_clusters=k, linkage="ward").fit_predict(z)
        cz = np.array([z[raw == c].mean(axis=0) for c in range(k)])
    else:
        raise ValueError(f"method must be 'kmeans', 'gmm' or 'agglomerative', got {method!r}")
    empty = sorted(set(range(k)) - set(np.unique(raw).tolist()))
    if empty:
        raise ValueError(
            f"{method} left component(s) {empty} of k = {k} without trials; choose a smaller k or another method"
        )
    if method == "gmm":  # Mahalanobis distance under the point's own component
        y = np.einsum("ni,nij->nj", z - cz[raw], gm.precisions_cholesky_[raw])
        dist = np.linalg.norm(y, axis=1)
    else:
        dist = np.linalg.norm(z - cz[raw], axis=1)
    c_orig = cz * scale + mean
    order = np.lexsort(c_orig.T[::-1])  # first feature (PV) ascending, ties by the next (SPARC), ...
    remap = np.empty(k, dtype=int)
    remap[order] = np.arange(k)
    return _Fit(remap[raw], cz[order], dist, z, mean, scale)


@dataclass(frozen=True, eq=False)
class PrototypeResult:
    """Clusters of the feature tuples (the paper: PV, SPARC) and their prototypes, clusters ordered by
    the centres' first feature (PV).

    Prototypes: K-means and agglomerative: the member nearest the centre (Euclidean, in the clustering
    space); GMM: the member with the smallest Mahalanobis distance to its component mean (highest component
    density). Silhouette: average silhouette (Rousseeuw 1987; ``sklearn.metrics.silhouette_score``),
    Euclidean, in the clustering space: exact up to ``SILHOUETTE_EXACT_MAX`` trials, above it an estimate
    from subsamples (:mod:`skilllib.prototypes`).

    Attributes
    ----------
    k : int
        The number of clusters (dimensionless).
    method : str
        The clustering method (text).
    scaling : str
        The clustering space, ``"raw"`` or ``"standard"`` (text).
    random_state : int
        The seed of the fit (dimensionless).
    n_init : int
        The restarts (dimensionless).
    data : pandas.DataFrame
        The input's participant, trial, the features (by default pv in m/s, sparc dimensionless) and the
        ``cluster`` label, in input row order (positional index 0..n-1).
    centres : pandas.DataFrame
        Per cluster (index 0..k-1) one column per feature (``pv`` in m/s, ``sparc`` dimensionless, ...) in
        ORIGINAL units, whatever the scaling.
    prototypes : pandas.DataFrame
        Per cluster the prototype trial: ``participant``, ``trial``, its features (``pv`` in m/s,
        ``sparc`` dimensionless, ...) and ``row`` (its position in ``data``).
    sizes : numpy.ndarray of int
        Trials per cluster (dimensionless).
    silhouette : float
        The average silhouette (dimensionless).
    silhouette_samples : numpy.ndarray
        Per-trial silhouettes of the trials ``silhouette_rows`` (exact: all, input order; dimensionless).
    silhouette_method : str
        ``"exact"`` or ``"subsample"`` (text).
    silhouette_estimate : SilhouetteEstimate or None
        None when exact; else the :class:`~skilllib.prototypes.SilhouetteEstimate` (n, sample size,
        repeats, averages, spread, rows).
    features : tuple of str
        The clustering features, in order (text); the columns of ``centres``.
    """

    k: int
    method: str
    scaling: str
    random_state: int
    n_init: int
    data: pd.DataFrame
    centres: pd.DataFrame
    prototypes: pd.DataFrame
    sizes: np.ndarray
    silhouette: float
    silhouette_samples: np.ndarray
    silhouette_method: str = "exact"
    silhouette_estimate: SilhouetteEstimate | None = None
    features: tuple[str, ...] = FEATURES

    @property
    def prototype_ids(self) -> set[tuple[str, str]]:
        """The prototypes' (participant, trial) ids (text): compare two fits' prototypes with ``&``."""
        return set(self.prototypes[["participant", "trial"]].itertuples(index=False, name=None))

    @property
    def labels(self) -> np.ndarray:
        """Cluster of each trial (0 = lowest centre PV, or first feature), input row order."""
        return self.data["cluster"].to_numpy()

    @property
    def silhouette_rows(self) -> np.ndarray:
        """Positions in ``data`` of the trials whose silhouettes ``silhouette_samples`` holds."""
        return np.arange(len(self.data)) if self.silhouette_estimate is None else self.silhouette_estimate.rows

    @property
    def silhouette_labels(self) -> np.ndarray:
        """Clusters of the trials in ``silhouette_samples`` (``labels[silhouette_rows]``)."""
        return self.labels[self.silhouette_rows]

    def failing_clusters(self) -> list[int]:
        """Clusters with no trial above the average silhouette (:func:`failing_clusters`); an estimate's
        on the pooled subsamples, a cluster never sampled failing too (``failing_with_absent``)."""
        return _sil.failing_with_absent(self.silhouette_samples, self.silhouette_labels, self.silhouette, self.k)

    @property
    def valid(self) -> bool:
        """The sweep's validity criterion for this k (see :func:`is_valid`)."""
        return self.silhouette > 0 and not self.failing_clusters()

    def to_dict(self) -> dict[str, Any]:
        """``k``, ``method``, ``scaling``, ``average_silhouette`` and ``clusters`` (ordered by centre PV,
        each with ``id``, ``size``, ``centre`` {pv, sparc}, ``prototype`` {participant, trial, pv, sparc});
        plain Python ints/floats/strings, JSON-ready. With other ``features`` the centre and prototype
        hold those, keyed by name in the order of ``features`` (units of the feature); there is no
        separate list of the features, the centre's keys are it."""
        clusters = []
        for c in range(self.k):
            p = {col: self.prototypes.at[c, col] for col in self.prototypes.columns}  # keeps each dtype
            clusters.append(
                {
                    "id": c,
                    "size": int(self.sizes[c]),
                    "centre": {f: float(self.centres.at[c, f]) for f in self.features},
                    "prototype": {
                        "participant": json_value(p["participant"]),
                        "trial": json_value(p["trial"]),
                        **{f: float(p[f]) for f in self.features},
                    },
                }
            )
        return {
            "k": self.k,
            "method": self.method,
            "scaling": self.scaling,
            "average_silhouette": float(self.silhouette),
            "clusters": clusters,
        }


@single_threaded()
def fit_prototypes(
    data: pd.DataFrame,
    k: int = DEFAULT_K,
    *,
    method: Method = "kmeans",
    scaling: Scaling = "raw",
    random_state: int = 0,
    n_init: int = 10,
    features: Sequence[str] = FEATURES,
) -> PrototypeResult:
    """Cluster the (PV, SPARC) tuples, or those of ``features``, into ``k`` clusters and pick each
    cluster's prototype trial.

    ``method="kmeans"`` is the paper's: ``sklearn.cluster.KMeans`` (Lloyd, k-means++ seeding) with
    ``n_init`` restarts (best inertia kept) and ``random_state``; same inputs give identical labels and
    centres. ``"gmm"`` (``sklearn.mixture.GaussianMixture``, full covariances, ``n_init`` restarts) and
    ``"agglomerative"`` (Ward linkage, deterministic; ``random_state`` unused) are alternatives with the
    same result. ``scaling``: "raw" (the paper: PV in m/s and SPARC as they are; any features in their
    units) or "standard" (z-scores of each feature); clustering, prototype distances and silhouettes use
    that space, centres are reported in original units. Clusters are numbered by the centres' first
    feature ascending (the default: PV), ties by the next.
    Silhouettes: exact up to ``SILHOUETTE_EXACT_MAX`` trials, above a subsample estimate seeded by
    ``random_state`` (:func:`skilllib.prototypes.silhouette`; see ``silhouette_method``).

    Parameters
    ----------
    data : pandas.DataFrame
        The trials: ``participant``, ``trial`` (ids) and the ``features`` columns, by default ``pv`` (m/s)
        and ``sparc`` (dimensionless), as :func:`feature_frame` makes them.
    k : int
        The number of clusters (dimensionless), >= 2.
    method : {"kmeans", "gmm", "agglomerative"}
        The clustering method (text), as :func:`fit_prototypes`.
    scaling : {"raw", "standard"}
        The clustering space (text): the features in their units (the paper: PV in m/s, SPARC), or the
        z-scores of each feature.
    random_state : int
        The seed of the fit (dimensionless).
    n_init : int
        Restarts of K-means and GMM, the best kept (dimensionless).
    features : sequence of str
        The columns to cluster on, two or more (each in its own unit, e.g. ``pv`` m/s, ``ldlj``
        dimensionless, ``duration`` s); default the paper's ``("pv", "sparc")``.

    Returns
    -------
    PrototypeResult
        The clusters, their centres (in the features' units: PV m/s, SPARC dimensionless), prototypes and
        silhouettes.

    Raises
    ------
    ValueError
        On fewer than two or repeated features, missing or non-numeric columns, NaN/inf features,
        duplicate ids, k < 2, fewer than k + 1 trials, fewer than k distinct points, or a GMM component
        left empty; the messages name the features.
    """
    feats = _features(features)
    df = _validate(data, feats)
    x = df[list(feats)].to_numpy()
    fit = _fit_arrays(x, k, method, scaling, random_state, n_init, feats)
    k = len(fit.centres_z)
    labels = fit.labels
    df["cluster"] = labels
    centres = pd.DataFrame(fit.centres_z * fit.scale + fit.mean, columns=list(feats))
    centres.index.name = "cluster"
    rows = []
    for c in range(k):  # nearest member; exact ties broken by (participant, trial) for order independence
        mem = df.loc[labels == c, list(ID_COLUMNS)].assign(_d=fit.typ_dist[labels == c])
        rows.append(mem.sort_values(["_d", *ID_COLUMNS], kind="mergesort").index[0])
    prototypes = df.loc[rows, [*ID_COLUMNS, *feats]].assign(row=rows).reset_index(drop=True)
    prototypes.index.name = "cluster"
    s, average, est = _sil.silhouette(fit.z, labels, random_state)
    return PrototypeResult(
        k=k,
        method=method,
        scaling=scaling,
        random_state=random_state,
        n_init=n_init,
        data=df,
        centres=centres,
        prototypes=prototypes,
        sizes=np.bincount(labels, minlength=k),
        silhouette=average,
        silhouette_samples=s,
        silhouette_method="exact" if est is None else "subsample",
        silhouette_estimate=est,
        features=feats,
    )


@dataclass(frozen=True, eq=False)
class SilhouetteSweep:
    """Average and per-trial silhouettes for each k.

    ``results[k]`` equals ``fit_prototypes(data, k, ...)`` with the same options. ``requested`` is the
    asked-for (k_min, k_max), which may exceed ``ks``.

    Attributes
    ----------
    results : dict of int to PrototypeResult
        The fit for each number of clusters k (dimensionless).
    requested : tuple of int
        The asked-for (k_min, k_max) (dimensionless).
    features : tuple of str
        The clustering features (text), those of every result.
    """

    results: dict[int, PrototypeResult]
    requested: tuple[int, int]
    features: tuple[str, ...] = FEATURES

    @property
    def ks(self) -> np.ndarray:
        return np.array(sorted(self.results), dtype=int)

    @property
    def scores(self) -> np.ndarray:
        """Average silhouette per k, aligned with ``ks``."""
        return np.array([self.results[k].silhouette for k in self.ks])

    @property
    def shrunk(self) -> bool:
        """True when the k range was cut short for lack of (distinct) trials."""
        return int(self.ks[-1]) < self.requested[1]

    def valid_ks(self) -> list[int]:
        """The k (dimensionless) whose clustering is valid, ascending."""
        return [int(k) for k in self.ks if self.results[k].valid]

    def valid_k_ranges(self) -> str:
        """The valid k as runs, for a reader: ``"2-4, 7"`` (``"none"`` when no k is valid)."""
        ks, runs = self.valid_ks(), []
        for k in ks:
            if runs and k == runs[-1][1] + 1:
                runs[-1][1] = k
            else:
                runs.append([k, k])
        return ", ".join(f"{a}-{b}" if b > a else f"{a}" for a, b in runs) or "none"

    def table(self) -> pd.DataFrame:
        """One row per k: ``silhouette``, ``valid``, ``failing`` (cluster ids below the average)."""
        return pd.DataFrame(
            {
                "k": self.ks,
                "silhouette": self.scores,
                "valid": [self.results[k].valid for k in self.ks],
                "failing": [self.results[k].failing_clusters() for k in self.ks],
            }
        ).set_index("k")

    def to_dict(self) -> dict[str, float]:
        """``{"2": score, ..., "16": score}`` for results.json."""
        return {str(int(k)): float(s) for k, s in zip(self.ks, self.scores)}

    def estimate_dict(self) -> dict[str, Any]:
        """How the scores were computed, JSON-ready (:func:`skilllib.prototypes.sweep_estimate`)."""
        return _sil.sweep_estimate(self.results, _sil.SILHOUETTE_EXACT_MAX)


def silhouette_sweep(
    data: pd.DataFrame,
    k_min: int = K_RANGE[0],
    k_max: int = K_RANGE[1],
    *,
    method: Method = "kmeans",
    scaling: Scaling = "raw",
    random_state: int = 0,
    n_init: int = 10,
    features: Sequence[str] = FEATURES,
    progress: Callable[[list[int], str], Iterable[int]] | None = None,
) -> SilhouetteSweep:
    """Fit k = k_min..k_max clusters and compute silhouettes (Rousseeuw 1987) as the paper does (2..16).

    The silhouette needs k <= n - 1, and k clusters need k distinct points: when the data allow fewer
    clusters than ``k_max`` the range is shrunk to min(n - 1, distinct points) with a ``UserWarning``.

    Parameters
    ----------
    data : pandas.DataFrame
        The trials: ``participant``, ``trial`` (ids) and the ``features`` columns, by default ``pv`` (m/s)
        and ``sparc`` (dimensionless), as :func:`feature_frame` makes them.
    k_min : int
        The fewest clusters (dimensionless), >= 2.
    k_max : int
        The most clusters (dimensionless), >= ``k_min``.
    method : {"kmeans", "gmm", "agglomerative"}
        The clustering method (text), as :func:`fit_prototypes`.
    scaling : {"raw", "standard"}
        The clustering space (text): the features in their units (the paper: PV in m/s, SPARC), or the
        z-scores of each feature.
    random_state : int
        The seed of the fit (dimensionless).
    n_init : int
        Restarts of K-means and GMM, the best kept (dimensionless).
    features : sequence of str
        The columns to cluster on, two or more (each in its own unit, e.g. ``pv`` m/s, ``ldlj``
        dimensionless, ``duration`` s); default the paper's ``("pv", "sparc")``.
    progress : callable or None
        ``progress(ks, "silhouette")`` may wrap the loop over k (e.g. a tqdm progress bar).

    Returns
    -------
    SilhouetteSweep
        The fit and silhouettes (dimensionless) for each k.

    Raises
    ------
    ValueError
        When not even ``k_min`` is possible, or ``k_min`` < 2, or ``k_max`` < ``k_min``.
    """
    feats = _features(features)
    df = _validate(data, feats)
    if k_min < 2 or k_max < k_min:
        raise ValueError(f"need 2 <= k_min <= k_max, got k_min = {k_min}, k_max = {k_max}")
    x = df[list(feats)].to_numpy()
    n, distinct = len(x), _n_distinct(x)
    hi = min(k_max, n - 1, distinct)
    if hi < k_min:
        raise ValueError(
            f"{n} trials ({distinct} distinct {_names(feats)} points) are too few for a silhouette "
            f"sweep from k = {k_min}: need at least {k_min + 1} trials and {k_min} distinct points"
        )
    if hi < k_max:
        warnings.warn(
            f"silhouette sweep shrunk from k = {k_min}..{k_max} to {k_min}..{hi}: {n} trials with "
            f"{distinct} distinct {_names(feats)} points allow at most k = {hi}",
            UserWarning,
            stacklevel=2,
        )
    ks = list(range(k_min, hi + 1))
    results = {
        k: fit_prototypes(
            df, k, method=method, scaling=scaling, random_state=random_state, n_init=n_init, features=feats
        )
        for k in (progress(ks, "silhouette") if progress else ks)
    }
    return SilhouetteSweep(results=results, requested=(int(k_min), int(k_max)), features=feats)


def seed_stability(
    data: pd.DataFrame,
    k: int = DEFAULT_K,
    *,
    seeds: Iterable[int] = range(1, 11),
    method: Method = "kmeans",
    scaling: Scaling = "raw",
    random_state: int = 0,
    n_init: int = 10,
    features: Sequence[str] = FEATURES,
) -> np.ndarray:
    """Adjusted Rand index of the labels fitted with each of ``seeds`` against the reference fit.

    Adjusted Rand index (Hubert & Arabie 1985; ``sklearn.metrics.adjusted_rand_score``) against the fit
    with ``random_state``; one value per seed. 1 means the same partition; about 0 is chance agreement.
    Use ``n_init=1`` to see single-start variability of K-means.

    Parameters
    ----------
    data : pandas.DataFrame
        The trials: ``participant``, ``trial`` (ids) and the ``features`` columns, by default ``pv`` (m/s)
        and ``sparc`` (dimensionless), as :func:`feature_frame` makes them.
    k : int
        The number of clusters (dimensionless), >= 2.
    seeds : iterable of int
        The seeds to refit with (dimensionless).
    method : {"kmeans", "gmm", "agglomerative"}
        The clustering method (text), as :func:`fit_prototypes`.
    scaling : {"raw", "standard"}
        The clustering space (text): the features in their units (the paper: PV in m/s, SPARC), or the
        z-scores of each feature.
    random_state : int
        The seed of the fit (dimensionless).
    n_init : int
        Restarts of K-means and GMM, the best kept (dimensionless).
    features : sequence of str
        The columns to cluster on, two or more (each in its own unit, e.g. ``pv`` m/s, ``ldlj``
        dimensionless, ``duration`` s); default the paper's ``("pv", "sparc")``.

    Returns
    -------
    numpy.ndarray
        The adjusted Rand index of each seed (dimensionless).
    """
    opts = {"method": method, "scaling": scaling, "n_init": n_init, "features": features}
    ref = fit_prototypes(data, k, random_state=random_state, **opts)
    return np.array(
        [
            adjusted_rand_score(ref.labels, fit_prototypes(ref.data, k, random_state=int(s), **opts).labels)
            for s in seeds
        ]
    )


@single_threaded()
def bootstrap_stability(
    data: pd.DataFrame,
    k: int = DEFAULT_K,
    *,
    n_boot: int = 50,
    method: Method = "kmeans",
    scaling: Scaling = "raw",
    random_state: int = 0,
    n_init: int = 10,
    features: Sequence[str] = FEATURES,
) -> np.ndarray:
    """Adjusted Rand index of bootstrap refits against the full-data labels; one value per resample.

    Each resample draws n trials with replacement (``numpy.random.default_rng(random_state)``), refits the
    whole procedure on it (scaling included), assigns every original trial to the nearest refitted
    centre (in the resample's clustering space; for ``"gmm"`` this approximates its own assignment) and
    compares with the full-data fit's labels.

    Parameters
    ----------
    data : pandas.DataFrame
        The trials: ``participant``, ``trial`` (ids) and the ``features`` columns, by default ``pv`` (m/s)
        and ``sparc`` (dimensionless), as :func:`feature_frame` makes them.
    k : int
        The number of clusters (dimensionless), >= 2.
    n_boot : int
        The number of resamples (dimensionless).
    method : {"kmeans", "gmm", "agglomerative"}
        The clustering method (text), as :func:`fit_prototypes`.
    scaling : {"raw", "standard"}
        The clustering space (text): the features in their units (the paper: PV in m/s, SPARC), or the
        z-scores of each feature.
    random_state : int
        The seed of the fit (dimensionless).
    n_init : int
        Restarts of K-means and GMM, the best kept (dimensionless).
    features : sequence of str
        The columns to cluster on, two or more (each in its own unit, e.g. ``pv`` m/s, ``ldlj``
        dimensionless, ``duration`` s); default the paper's ``("pv", "sparc")``.

    Returns
    -------
    numpy.ndarray, shape (n_boot,)
        The adjusted Rand index of each resample (dimensionless, 1 = the same partition).
    """
    ref = fit_prototypes(
        data, k, method=method, scaling=scaling, random_state=random_state, n_init=n_init, features=features
    )
    x = ref.data[list(ref.features)].to_numpy()
    rng = np.random.default_rng(random_state)
    out = np.empty(n_boot)
    for b in range(n_boot):
        idx = rng.integers(0, len(x), len(x))
        fit = _fit_arrays(x[idx], k, method, scaling, int(rng.integers(2**31 - 1)), n_init, ref.features)
        z = (x - fit.mean) / fit.scale
        pred = np.argmin(((z[:, None, :] - fit.centres_z[None]) ** 2).sum(axis=2), axis=1)
        out[b] = adjusted_rand_score(ref.labels, pred)
    return out


def results_section(sweep: SilhouetteSweep, result: PrototypeResult) -> dict[str, Any]:
    """The clustering part of results.json: ``{"silhouette": {"2": ..}, "k": .., "clusters": [..], ..}``.

    Parameters
    ----------
    sweep : SilhouetteSweep
        The silhouette sweep.
    result : PrototypeResult
        The chosen fit.

    Returns
    -------
    dict of str to Any
        The section as JSON values (PV in m/s, SPARC and silhouettes dimensionless; other features in
        their units).

    Raises
    ------
    ValueError
        When the sweep and the fit clustered different features.
    """
    if tuple(sweep.features) != tuple(result.features):
        raise ValueError(
            f"the sweep clustered {_names(sweep.features)} but the fit {_names(result.features)}: "
            "pass results of the same features"
        )
    return {"silhouette": sweep.to_dict(), **result.to_dict()}
