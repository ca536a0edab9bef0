"""Average silhouette of a clustering: exact up to :data:`SILHOUETTE_EXACT_MAX` points, an estimate above.

The silhouette of point i (Rousseeuw 1987, J Comput Appl Math 20:53) is s(i) = (b - a) / max(a, b) with
a the mean distance to the other members of its own cluster and b the smallest mean distance to the
members of another cluster; dimensionless, in [-1, 1]. Distances here are Euclidean in the clustering
space (PV in m/s and SPARC for "raw" features, z-scores for "standard"). The average silhouette of all n
points costs O(n^2) time: scikit-learn's ``silhouette_samples`` (Pedregosa et al. 2011) takes 0.3 s
for 5,000 points, 1.7 s for 10,000, 4.6 s for 20,000 and about 40 s for 67,000 (one core), and a sweep
repeats it for every k (15 times for k = 2..16: 9.5 min at 66,800 points).

* n <= :data:`SILHOUETTE_EXACT_MAX`: ``silhouette_samples`` on all points (``method = "exact"``).
* n above it: an ESTIMATE (``method = "subsample"``). Each of :data:`SILHOUETTE_REPEATS` repeats draws
  a stratified random subsample of about :data:`SILHOUETTE_SAMPLE` points -- per cluster c of n_c
  points, m_c = m n_c / n points (largest-remainder rounding; at least :data:`SILHOUETTE_MIN_PER_CLUSTER`,
  or all n_c if fewer), without replacement (Cochran 1977, Sampling Techniques, 3rd ed., ch. 5) -- and
  runs ``silhouette_samples`` on it: a and b of a sampled point are its mean distances to the SAMPLED
  members of each cluster (unbiased for the full-data means). The repeat's average weights each
  cluster's mean sampled silhouette by n_c / n (with proportional allocation this is the plain mean
  of the sample up to rounding). Stratifying keeps every cluster, even a singleton outlier, in every
  sample: a simple random sample of 1,000 out of 67,000 misses a singleton with probability 0.985,
  and then b and the validity rule of :func:`failing_clusters` cannot be evaluated for it.

  The estimate is the mean of the repeats' averages; its spread is reported as their SD (ddof 1; the
  standard error of the estimate is SD / sqrt(repeats)), minimum and maximum, in
  :class:`SilhouetteEstimate`. The draws use ``numpy.random.default_rng(random_state)``: the same data,
  labels and seed give identical values (for a given numpy version). The subsample's b is a minimum of
  noisy means, so the estimate is biased slightly low, more so for larger k: on 20,000 synthetic points
  (``benchmarks/bench_silhouette.py``; 200 repeats) +0.001 at k = 2, -0.001 at k = 6, -0.0015 at k = 10
  and -0.003 at k = 16, against an SD per repeat of 0.008 (standard error of the estimate 0.0026).

Validity (:func:`is_valid`, :func:`failing_clusters`) of a subsample estimate is judged on the pooled
silhouettes of all repeats with their clusters' labels and the estimate as the average line.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from sklearn.metrics import silhouette_samples

from ..smoothness import single_threaded

SILHOUETTE_EXACT_MAX = 5_000  #: points; above: the estimate (exact sweep k = 2..16 at 5,000: 4.8 s CPU)
SILHOUETTE_SAMPLE = 1_000  #: points per subsample (``silhouette_samples`` on 1,000 points: 0.011 s)
SILHOUETTE_REPEATS = 10  #: subsamples per estimate (SD of one repeat ~0.008, of their mean ~0.0026)
SILHOUETTE_MIN_PER_CLUSTER = 2  #: sampled points per cluster at least (a needs a second member)


def failing_clusters(samples: np.ndarray, labels: np.ndarray, average: float | None = None) -> list[int]:
    """Clusters none of whose trials has a silhouette above the average.

    Such a cluster lies entirely below the average line of the silhouette plot, which scikit-learn's
    silhouette example reads as a bad choice of k. A singleton cluster has silhouette 0 (Rousseeuw 1987)
    and so fails whenever the average is positive.

    Parameters
    ----------
    samples : numpy.ndarray
        Per-trial silhouettes (dimensionless, -1 to 1).
    labels : numpy.ndarray
        The cluster label of each trial (dimensionless).
    average : float or None
        The average silhouette to compare with (dimensionless); None: the mean of ``samples``.

    Returns
    -------
    list of int
        The failing clusters' labels (dimensionless).
    """
    samples, labels = np.asarray(samples, dtype=float), np.asarray(labels)
    avg = float(samples.mean()) if average is None else float(average)
    return [int(c) for c in np.unique(labels) if not (samples[labels == c] > avg).any()]


def is_valid(samples: np.ndarray, labels: np.ndarray, average: float | None = None) -> bool:
    """Validity of a clustering for the sweep: average silhouette > 0 and no failing cluster.

    Operationalises the paper's "2 <= n clusters <= 16 produces valid clusters" with scikit-learn's
    example criterion (every cluster reaches above the average silhouette). That example also weighs the
    spread of cluster sizes; this criterion does not.

    Parameters
    ----------
    samples : numpy.ndarray
        Per-trial silhouettes (dimensionless, -1 to 1).
    labels : numpy.ndarray
        The cluster label of each trial (dimensionless).
    average : float or None
        The average silhouette to compare with (dimensionless); None: the mean of ``samples``.

    Returns
    -------
    bool
        True when the clustering is valid.
    """
    samples = np.asarray(samples, dtype=float)  # averaged in float64, as failing_clusters does
    avg = float(samples.mean()) if average is None else float(average)
    return avg > 0 and not failing_clusters(samples, labels, avg)


@dataclass(frozen=True, eq=False)
class SilhouetteEstimate:
    """A subsample estimate of the average silhouette (dimensionless) and its spread over the repeats.

    :n_points: points clustered (n). :sample_size: points asked per subsample (m; a repeat may hold a
        few more when clusters are raised to the minimum per cluster). :repeats: subsamples drawn.
    :exact_max: the threshold in force: n was above it.
    :averages: (repeats,) each subsample's cluster-weighted average silhouette.
    :rows: positions (0..n-1) of the sampled points, repeat after repeat, ascending within a repeat; a
        point drawn in two repeats appears twice. The pooled per-point silhouettes align with it.
    """

    n_points: int
    sample_size: int
    repeats: int
    exact_max: int
    averages: np.ndarray
    rows: np.ndarray

    @property
    def mean(self) -> float:
        """The estimate: mean of the repeats' averages."""
        return float(np.mean(self.averages))

    @property
    def sd(self) -> float:
        """SD (ddof 1) of the repeats' averages; the estimate's standard error is sd / sqrt(repeats)."""
        return float(np.std(self.averages, ddof=1))

    def to_dict(self) -> dict[str, float]:
        """``{"mean", "sd", "min", "max"}`` as plain floats."""
        return {
            "mean": self.mean,
            "sd": self.sd,
            "min": float(np.min(self.averages)),
            "max": float(np.max(self.averages)),
        }


def allocate(sizes: np.ndarray, sample_size: int, minimum: int = SILHOUETTE_MIN_PER_CLUSTER) -> np.ndarray:
    """Points to draw per cluster: ``sample_size * size / n`` by largest remainder (sums to
    ``sample_size``), raised to ``minimum``, capped at the cluster's size."""
    sizes = np.asarray(sizes, dtype=np.int64)
    quota = sample_size * sizes / sizes.sum()
    m = np.floor(quota).astype(np.int64)
    short = int(sample_size - m.sum())
    m[np.argsort(-(quota - m), kind="stable")[:short]] += 1  # largest remainders, ties by cluster id
    return np.minimum(np.maximum(m, minimum), sizes)


def subsample_silhouette(
    z: np.ndarray, labels: np.ndarray, random_state: int | None, *, sample_size: int, repeats: int, exact_max: int
) -> tuple[np.ndarray, SilhouetteEstimate]:
    """Pooled per-point silhouettes of ``repeats`` stratified subsamples and the estimate (module doc).

    ``z``: (n, d) points in the clustering space; ``labels``: (n,) clusters 0..k-1, each non-empty.
    Returns the pooled silhouettes, aligned with ``estimate.rows``, and the :class:`SilhouetteEstimate`.
    """
    if repeats < 2:
        raise ValueError(f"repeats = {repeats}: the spread of the estimate needs at least 2 subsamples")
    labels = np.asarray(labels)
    k = int(labels.max()) + 1
    members = [np.flatnonzero(labels == c) for c in range(k)]
    sizes = np.array([len(m) for m in members])
    per = allocate(sizes, sample_size)
    weight = sizes / sizes.sum()
    rng = np.random.default_rng(random_state)
    rows, pooled, averages = [], [], np.empty(repeats)
    for r in range(repeats):
        idx = np.sort(np.concatenate([mem[rng.choice(len(mem), m, replace=False)] for mem, m in zip(members, per)]))
        lab = labels[idx]
        s = silhouette_samples(z[idx], lab, metric="euclidean")
        averages[r] = float(weight @ (np.bincount(lab, weights=s, minlength=k) / np.maximum(per, 1)))
        rows.append(idx)
        pooled.append(s)
    est = SilhouetteEstimate(
        n_points=len(labels),
        sample_size=int(sample_size),
        repeats=int(repeats),
        exact_max=int(exact_max),
        averages=averages,
        rows=np.concatenate(rows),
    )
    return np.concatenate(pooled), est


@single_threaded()  # OpenMP and BLAS on one thread: faster on busy cores, reproducible
def silhouette(
    z: np.ndarray,
    labels: np.ndarray,
    random_state: int | None = 0,
) -> tuple[np.ndarray, float, SilhouetteEstimate | None]:
    """Per-point silhouettes, the average silhouette and, above the threshold, the estimate's details.

    n <= :data:`SILHOUETTE_EXACT_MAX` (or n <= :data:`SILHOUETTE_SAMPLE`): ``silhouette_samples`` on all
    points, their mean and None. Otherwise :func:`subsample_silhouette` with the module's constants,
    read at call time (tests may patch them here): the pooled samples, the estimate and its details.
    Runs with OpenMP and BLAS limited to one thread, like the K-means fits.
    """
    n = len(z)
    if n <= SILHOUETTE_EXACT_MAX or n <= SILHOUETTE_SAMPLE:
        s = silhouette_samples(z, labels, metric="euclidean")
        return s, float(s.mean()), None
    s, est = subsample_silhouette(
        z,
        labels,
        random_state,
        sample_size=SILHOUETTE_SAMPLE,
        repeats=SILHOUETTE_REPEATS,
        exact_max=SILHOUETTE_EXACT_MAX,
    )
    return s, est.mean, est


def failing_with_absent(samples: np.ndarray, labels: np.ndarray, average: float, k: int) -> list[int]:
    """:func:`failing_clusters` over clusters 0..k-1; a cluster with no point in ``labels`` (never
    sampled) fails too: none of its trials is shown above the average."""
    absent = set(range(k)) - {int(c) for c in np.unique(labels)}
    return sorted(set(failing_clusters(samples, labels, average)) | absent)


def sweep_estimate(results: Mapping[int, Any], exact_max: int) -> dict[str, Any]:
    """How a sweep's silhouettes were computed (``SilhouetteSweep.estimate_dict``), JSON-ready.

    ``results``: k -> ``PrototypeResult`` (its ``data``, ``silhouette``, ``silhouette_estimate``). Returns
    ``{"method": "exact"|"subsample", "exact_max", "n_points", "sample_size", "repeats", "per_k": {"2":
    {"mean", "sd", "min", "max"}, ...}}``; exact: ``sample_size`` and ``repeats`` None, ``per_k`` means only
    (no spread). ``exact_max``: the threshold stored in the estimates, for exact results the given one.
    """
    ks = sorted(int(k) for k in results)
    est = {k: results[k].silhouette_estimate for k in ks}
    if all(e is None for e in est.values()):
        return {
            "method": "exact",
            "exact_max": int(exact_max),
            "n_points": len(results[ks[0]].data),
            "sample_size": None,
            "repeats": None,
            "per_k": {str(k): {"mean": float(results[k].silhouette)} for k in ks},
        }
    e0 = next(e for e in est.values() if e is not None)
    return {
        "method": "subsample",
        "exact_max": e0.exact_max,
        "n_points": e0.n_points,
        "sample_size": e0.sample_size,
        "repeats": e0.repeats,
        "per_k": {str(k): e.to_dict() for k, e in est.items() if e is not None},
    }
