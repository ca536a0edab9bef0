"""Tests of the silhouette at scale (skilllib.prototypes): exact up to SILHOUETTE_EXACT_MAX points, a
stratified subsample estimate above it, validity on the pooled subsamples, figures and estimate_dict.

The threshold is patched down (200 points, subsamples of 150) so that the estimate runs on a few hundred
points in milliseconds; expected values come from scikit-learn's silhouette_samples on all points.
"""

from __future__ import annotations

import json

import matplotlib
import numpy as np
import pandas as pd
import pytest
from sklearn.metrics import silhouette_samples

from skilllib.prototypes import (
    SILHOUETTE_EXACT_MAX,
    failing_clusters,
    feature_frame,
    fit_prototypes,
    silhouette_sweep,
)
from skilllib.prototypes import _silhouette as sil

matplotlib.use("Agg")

# well-separated blobs in (PV m/s, SPARC), PV order 0..3
CENTRES = np.array([(0.3, -1.4), (0.7, -2.6), (1.1, -1.6), (1.45, -2.9)])


def blobs(n_per: int, seed: int = 0, sd: float = 0.04) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    x = np.repeat(CENTRES, n_per, axis=0) + rng.normal(0.0, sd, (len(CENTRES) * n_per, 2))
    x = x[rng.permutation(len(x))]
    return feature_frame(x[:, 0], x[:, 1])


@pytest.fixture
def small_threshold(monkeypatch: pytest.MonkeyPatch) -> None:
    """Estimate above 200 points, from 8 subsamples of 150."""
    monkeypatch.setattr(sil, "SILHOUETTE_EXACT_MAX", 200)
    monkeypatch.setattr(sil, "SILHOUETTE_SAMPLE", 150)
    monkeypatch.setattr(sil, "SILHOUETTE_REPEATS", 8)


def test_constants_are_the_documented_ones():
    assert SILHOUETTE_EXACT_MAX == sil.SILHOUETTE_EXACT_MAX == 5_000
    assert (sil.SILHOUETTE_SAMPLE, sil.SILHOUETTE_REPEATS) == (1_000, 10)


@pytest.mark.parametrize("scaling", ["raw", "standard"])
def test_exact_below_threshold_is_silhouette_samples_mean(scaling):
    df = blobs(75)  # 300 points <= 5,000
    r = fit_prototypes(df, 4, scaling=scaling)
    x = df[["pv", "sparc"]].to_numpy()
    z = x if scaling == "raw" else (x - x.mean(axis=0)) / x.std(axis=0)
    s = silhouette_samples(z, r.labels, metric="euclidean")
    assert r.silhouette_method == "exact" and r.silhouette_estimate is None
    np.testing.assert_array_equal(r.silhouette_samples, s)
    assert r.silhouette == float(s.mean())  # bit-identical, not approximately
    np.testing.assert_array_equal(r.silhouette_rows, np.arange(300))
    np.testing.assert_array_equal(r.silhouette_labels, r.labels)


def test_threshold_is_inclusive(monkeypatch):
    df = blobs(50)  # 200 points
    monkeypatch.setattr(sil, "SILHOUETTE_SAMPLE", 150)
    monkeypatch.setattr(sil, "SILHOUETTE_EXACT_MAX", 200)
    assert fit_prototypes(df, 4).silhouette_method == "exact"
    monkeypatch.setattr(sil, "SILHOUETTE_EXACT_MAX", 199)
    r = fit_prototypes(df, 4)
    assert r.silhouette_method == "subsample" and r.silhouette_estimate.exact_max == 199


def test_estimate_is_close_to_exact_and_aligned_with_its_rows(small_threshold):
    df = blobs(150, sd=0.08)  # 600 points
    r = fit_prototypes(df, 4)
    est = r.silhouette_estimate
    assert r.silhouette_method == "subsample"
    assert (est.n_points, est.sample_size, est.repeats, est.exact_max) == (600, 150, 8, 200)
    exact = silhouette_samples(df[["pv", "sparc"]].to_numpy(), r.labels).mean()
    assert est.sd > 0 and abs(r.silhouette - exact) < 3 * est.sd
    assert r.silhouette == est.mean == pytest.approx(np.mean(est.averages))
    # rows: 8 repeats of 150 distinct ascending positions; samples are silhouette_samples on them
    assert len(est.rows) == len(r.silhouette_samples) == 8 * 150
    first = est.rows[:150]
    assert np.all(np.diff(first) > 0)
    x = df[["pv", "sparc"]].to_numpy()
    s0 = silhouette_samples(x[first], r.labels[first])
    np.testing.assert_allclose(r.silhouette_samples[:150], s0, rtol=0, atol=1e-12)
    # the repeat's average weights each cluster's sampled mean by its share of all points
    w = np.bincount(r.labels, minlength=4) / 600
    means = [s0[r.labels[first] == c].mean() for c in range(4)]
    assert est.averages[0] == pytest.approx(float(w @ means), abs=1e-12)
    np.testing.assert_array_equal(r.silhouette_labels, r.labels[est.rows])


def test_estimate_is_deterministic_and_seeded(small_threshold):
    df = blobs(100)
    a, b = fit_prototypes(df, 4, random_state=3), fit_prototypes(df, 4, random_state=3)
    np.testing.assert_array_equal(a.silhouette_estimate.rows, b.silhouette_estimate.rows)
    np.testing.assert_array_equal(a.silhouette_samples, b.silhouette_samples)
    assert a.silhouette == b.silhouette
    c = fit_prototypes(df, 4, random_state=4)
    np.testing.assert_array_equal(c.labels, a.labels)  # same clusters, other subsamples
    assert not np.array_equal(c.silhouette_estimate.rows, a.silhouette_estimate.rows)
    assert c.silhouette != a.silhouette


def test_allocation_is_proportional_with_a_minimum():
    np.testing.assert_array_equal(sil.allocate(np.array([1, 99, 900]), 100), [1, 10, 90])
    # quotas 0.5, 9.5, 90: the one point left goes to the tied remainder of the lower cluster id, which the
    # minimum then raises to 2 anyway (101 points in all)
    np.testing.assert_array_equal(sil.allocate(np.array([5, 95, 900]), 100), [2, 9, 90])
    m = sil.allocate(np.array([333, 333, 334]), 100)
    assert m.sum() == 100 and sorted(m) == [33, 33, 34]


def test_every_cluster_is_sampled_even_a_singleton():
    rng = np.random.default_rng(1)
    z = np.r_[rng.normal(0, 0.1, (999, 2)), [[5.0, 5.0]]]
    labels = np.r_[np.zeros(999, int), 1]
    s, est = sil.subsample_silhouette(z, labels, 0, sample_size=100, repeats=4, exact_max=500)
    assert np.sum(est.rows == 999) == 4  # the outlier in every repeat
    assert np.all(s[est.rows == 999] == 0)  # a singleton's silhouette is 0 (Rousseeuw 1987)
    with pytest.raises(ValueError, match="at least 2"):
        sil.subsample_silhouette(z, labels, 0, sample_size=100, repeats=1, exact_max=500)


def planted(tight_middle: bool, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Two tight blobs 10 apart and a third cluster midway: diffuse (all its silhouettes below the
    average: it fails) or as tight as the others (it does not)."""
    rng = np.random.default_rng(seed)
    sd = 0.1 if tight_middle else 1.5
    z = np.r_[
        rng.normal(0, 0.1, (300, 2)), rng.normal(0, 0.1, (300, 2)) + [10, 0], rng.normal(0, sd, (300, 2)) + [5, 0]
    ]
    return z, np.repeat([0, 1, 2], 300)


@pytest.mark.parametrize("tight_middle, expected", [(False, [2]), (True, [])])
def test_validity_on_pooled_subsamples_finds_a_planted_failing_cluster(tight_middle, expected):
    z, labels = planted(tight_middle)
    full = silhouette_samples(z, labels)
    assert failing_clusters(full, labels) == expected  # the planted truth, on all points
    s, est = sil.subsample_silhouette(z, labels, 0, sample_size=150, repeats=8, exact_max=200)
    assert sil.failing_with_absent(s, labels[est.rows], est.mean, 3) == expected


def test_result_validity_is_judged_on_the_pooled_subsamples(small_threshold):
    z, _ = planted(False)
    df = feature_frame(z[:, 0] / 10 + 0.3, z[:, 1] / 10 - 2)  # PV 0.3-1.3 m/s
    r = fit_prototypes(df, 3)
    assert r.silhouette_method == "subsample"
    exact = silhouette_samples(df[["pv", "sparc"]].to_numpy(), r.labels)
    assert failing_clusters(exact, r.labels) == [1]  # the diffuse middle cluster, numbered by PV
    assert r.failing_clusters() == [1] and not r.valid


def test_result_judges_validity_with_its_own_average_and_sampled_labels(small_threshold):
    import dataclasses

    r = fit_prototypes(blobs(100), 4)
    assert r.failing_clusters() == [] and r.valid
    assert dataclasses.replace(r, silhouette=0.999).failing_clusters() == [0, 1, 2, 3]  # the line it uses
    negative = dataclasses.replace(r, silhouette=-0.5)
    assert negative.failing_clusters() == [] and not negative.valid  # validity also needs average > 0
    est = r.silhouette_estimate
    keep = r.labels[est.rows] != 3  # as if cluster 3 had never been sampled
    r3 = dataclasses.replace(
        r,
        silhouette_samples=r.silhouette_samples[keep],
        silhouette_estimate=dataclasses.replace(est, rows=est.rows[keep]),
    )
    assert r3.failing_clusters() == [3] and not r3.valid


def test_a_cluster_never_sampled_fails():
    s, labels = np.array([0.9, 0.8, 0.7]), np.array([0, 0, 2])
    assert sil.failing_with_absent(s, labels, 0.5, 3) == [1]
    assert sil.failing_with_absent(s, labels, 0.75, 3) == [1, 2]


def test_figures_run_on_a_subsample_result(small_threshold):
    import matplotlib.pyplot as plt
    from matplotlib.container import ErrorbarContainer

    from skilllib.figures import plot_silhouette_sweep, plot_silhouettes

    sw = silhouette_sweep(blobs(75), 2, 4)
    r = sw.results[4]
    assert r.silhouette_method == "subsample" and len(r.silhouette_samples) == 8 * 150 != len(r.data)
    fig = plot_silhouettes(r)
    ax = fig.axes[0]
    gap = max(2, len(r.silhouette_samples) // 60)
    assert ax.get_ylim()[1] == len(r.silhouette_samples) + (r.k + 1) * gap  # every pooled trial drawn
    assert f"estimate, SD {r.silhouette_estimate.sd:.3f}" in ax.get_title()
    plt.close(fig)
    fig = plot_silhouette_sweep(sw, chosen_k=4)
    bars = [c for c in fig.axes[0].containers if isinstance(c, ErrorbarContainer)]
    assert len(bars) == 1
    segs = bars[0].lines[2][0].get_segments()
    sd = [sw.results[k].silhouette_estimate.sd for k in sw.ks]
    np.testing.assert_allclose([s[1, 1] - s[0, 1] for s in segs], 2 * np.array(sd))
    plt.close(fig)


def test_estimate_dict_names_the_method_and_is_json(small_threshold):
    sw = silhouette_sweep(blobs(75), 2, 5)
    d = json.loads(json.dumps(sw.estimate_dict(), allow_nan=False))
    assert {k: d[k] for k in ("method", "exact_max", "n_points", "sample_size", "repeats")} == {
        "method": "subsample",
        "exact_max": 200,
        "n_points": 300,
        "sample_size": 150,
        "repeats": 8,
    }
    assert list(d["per_k"]) == list(sw.to_dict()) == ["2", "3", "4", "5"]
    for k, v in d["per_k"].items():
        a = sw.results[int(k)].silhouette_estimate.averages
        assert v["mean"] == sw.to_dict()[k] == pytest.approx(a.sum() / 8, abs=1e-15)
        assert v["sd"] == pytest.approx(np.sqrt(((a - a.mean()) ** 2).sum() / 7), rel=1e-12)  # ddof 1
        assert (v["min"], v["max"]) == (a.min(), a.max()) and v["min"] < v["mean"] < v["max"]


def test_estimate_dict_of_an_exact_sweep_has_no_spread():
    sw = silhouette_sweep(blobs(25), 2, 4)
    d = json.loads(json.dumps(sw.estimate_dict(), allow_nan=False))
    assert d == {
        "method": "exact",
        "exact_max": 5_000,
        "n_points": 100,
        "sample_size": None,
        "repeats": None,
        "per_k": {k: {"mean": v} for k, v in sw.to_dict().items()},
    }
