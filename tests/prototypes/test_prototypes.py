"""Tests of skilllib.prototypes (silhouette sweep, K-means prototypes) and its figures."""

from __future__ import annotations

import json
import warnings

import matplotlib
import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from sklearn.cluster import KMeans
from sklearn.metrics import adjusted_rand_score, silhouette_score
from threadpoolctl import threadpool_limits

from skilllib.prototypes import (
    PrototypeResult,
    bootstrap_stability,
    failing_clusters,
    feature_frame,
    fit_prototypes,
    is_valid,
    results_section,
    seed_stability,
    silhouette_sweep,
)

matplotlib.use("Agg")

# Six well-separated blobs in (PV m/s, SPARC), listed in PV order but NOT in SPARC order,
# so that ordering by PV is distinguishable from ordering by anything else.
CENTRES = np.array([(0.4, -1.5), (0.65, -2.4), (0.9, -1.7), (1.15, -2.8), (1.4, -2.0), (1.65, -2.6)])


def blobs(
    n_per: int = 25,
    seed: int = 0,
    sd: tuple[float, float] = (0.02, 0.05),
    centres: np.ndarray = CENTRES,
    shuffle: bool = True,
) -> tuple[pd.DataFrame, np.ndarray]:
    """Seeded Gaussian blobs as a features-table slice (with extra columns) and the true blob of each row."""
    rng = np.random.default_rng(seed)
    truth = np.repeat(np.arange(len(centres)), n_per)
    x = centres[truth] + rng.normal(0, 1, (len(truth), 2)) * np.asarray(sd)
    if shuffle:
        perm = rng.permutation(len(truth))
        x, truth = x[perm], truth[perm]
    n = len(truth)
    df = pd.DataFrame(
        {
            "participant": [f"P{i % 10:02d}" for i in range(n)],
            "trial": np.arange(n) // 10,
            "status": "selected",
            "reason": "",
            "pv": x[:, 0],
            "contact_speed": 0.5,
            "duration": 0.6,
            "sparc": x[:, 1],
            "ldlj": -6.0,
        }
    )
    return df, truth


@pytest.fixture(scope="module")
def data() -> tuple[pd.DataFrame, np.ndarray]:
    return blobs()


def zspace(df: pd.DataFrame, scaling: str) -> np.ndarray:
    x = df[["pv", "sparc"]].to_numpy(float)
    return x if scaling == "raw" else (x - x.mean(0)) / x.std(0)


# --- K-means prototypes -----------------------------------------------------------------------


@pytest.mark.parametrize("method", ["kmeans", "gmm", "agglomerative"])
def test_deterministic(method):
    df, _ = blobs(n_per=30, seed=4, sd=(0.15, 0.4))  # overlapping: the seed matters
    a = fit_prototypes(df, 9, method=method, random_state=3, n_init=2)
    b = fit_prototypes(df, 9, method=method, random_state=3, n_init=2)
    np.testing.assert_array_equal(a.labels, b.labels)
    np.testing.assert_array_equal(a.centres.to_numpy(), b.centres.to_numpy())
    pd.testing.assert_frame_equal(a.prototypes, b.prototypes)


@pytest.mark.parametrize("method", ["kmeans", "gmm", "agglomerative"])
@pytest.mark.parametrize("scaling", ["raw", "standard"])
def test_recovers_blobs_ordered_by_pv(data, method, scaling):
    df, truth = data
    r = fit_prototypes(df, 6, method=method, scaling=scaling)
    assert np.all(np.diff(r.centres["pv"].to_numpy()) > 0)
    # blobs are numbered in PV order, so the PV-ordered labels equal the truth exactly
    np.testing.assert_array_equal(r.labels, truth)
    np.testing.assert_array_equal(r.sizes, np.bincount(truth))
    np.testing.assert_allclose(r.centres.to_numpy(), CENTRES, atol=0.03)


@pytest.mark.parametrize("scaling", ["raw", "standard"])
@pytest.mark.parametrize("method", ["kmeans", "agglomerative"])
def test_prototypes_are_members_nearest_their_centre(method, scaling):
    df, _ = blobs(n_per=30, seed=5, sd=(0.12, 0.3))  # overlapping, so "nearest" is not trivial
    r = fit_prototypes(df, 6, method=method, scaling=scaling)
    z = zspace(df, scaling)
    x = df[["pv", "sparc"]].to_numpy(float)
    cz = r.centres.to_numpy() if scaling == "raw" else (r.centres.to_numpy() - x.mean(0)) / x.std(0)
    for c, p in r.prototypes.iterrows():
        row = int(p["row"])
        assert r.labels[row] == c
        assert (df.at[row, "participant"], df.at[row, "trial"]) == (p["participant"], p["trial"])
        assert (df.at[row, "pv"], df.at[row, "sparc"]) == (p["pv"], p["sparc"])
        members = np.flatnonzero(r.labels == c)
        d = np.linalg.norm(z[members] - cz[c], axis=1)
        assert members[np.argmin(d)] == row


def test_gmm_prototype_is_most_typical_member():
    from sklearn.mixture import GaussianMixture

    df, _ = blobs(n_per=30, seed=5, sd=(0.12, 0.3))
    r = fit_prototypes(df, 4, method="gmm", scaling="standard", random_state=2)
    z = zspace(df, "standard")
    gm = GaussianMixture(4, covariance_type="full", n_init=10, random_state=2).fit(z)
    comp = gm.predict(z)
    for c, p in r.prototypes.iterrows():
        row = int(p["row"])
        assert r.labels[row] == c
        j = comp[row]
        members = np.flatnonzero(r.labels == c)
        np.testing.assert_array_equal(comp[members], j)  # cluster c is component j
        diff = z[members] - gm.means_[j]
        maha = np.einsum("ni,ij,nj->n", diff, np.linalg.inv(gm.covariances_[j]), diff)
        assert members[np.argmin(maha)] == row


@pytest.mark.parametrize("method", ["kmeans", "gmm", "agglomerative"])
def test_centres_in_original_units_under_standard_scaling(method):
    df, _ = blobs(n_per=30, seed=2, sd=(0.1, 0.25))
    r = fit_prototypes(df, 5, method=method, scaling="standard")
    assert r.centres["pv"].between(0.3, 1.8).all() and r.centres["sparc"].between(-3.0, -1.3).all()
    if method != "gmm":  # K-means and Ward centres are the members' means, in m/s and SPARC
        means = df[["pv", "sparc"]].groupby(r.labels).mean().to_numpy()
        np.testing.assert_allclose(r.centres.to_numpy(), means, atol=1e-9)


def test_silhouette_matches_sklearn_in_clustering_space(data):
    df, _ = blobs(n_per=30, seed=5, sd=(0.12, 0.3))
    for scaling in ("raw", "standard"):
        r = fit_prototypes(df, 6, scaling=scaling)
        assert r.silhouette == pytest.approx(silhouette_score(zspace(df, scaling), r.labels), abs=1e-12)


def test_input_index_and_extra_columns(data):
    df, _ = data
    sub = df.iloc[::2].copy()  # gaps in the index, as a selection from the features table
    sub.index = sub.index * 7 + 3
    r = fit_prototypes(sub, 6)
    assert list(r.data.columns) == ["participant", "trial", "pv", "sparc", "cluster"]
    assert list(r.data.index) == list(range(len(sub)))
    p = r.prototypes.iloc[0]
    assert sub.iloc[int(p["row"])]["trial"] == p["trial"]


def test_feature_frame_arrays():
    df = feature_frame([0.5, 0.6, 1.2, 1.3], [-1.5, -1.6, -2.5, -2.4])
    assert list(df.columns) == ["participant", "trial", "pv", "sparc"]
    r = fit_prototypes(df, 2)
    np.testing.assert_array_equal(r.labels, [0, 0, 1, 1])
    with pytest.raises(ValueError, match="pv has 2 values but sparc has 1"):
        feature_frame([1, 2], [3])


# --- errors -----------------------------------------------------------------------------------


def test_errors(data):
    df, _ = data
    bad = df.copy()
    bad.loc[3, "sparc"] = np.nan
    with pytest.raises(ValueError, match="1 trial.*NaN"):
        fit_prototypes(bad, 6)
    with pytest.raises(ValueError, match="NaN"):
        silhouette_sweep(bad)
    with pytest.raises(ValueError, match=r"lacks column.*'sparc'"):
        fit_prototypes(df.drop(columns="sparc"), 6)
    with pytest.raises(ValueError, match="duplicate"):
        fit_prototypes(pd.concat([df, df.iloc[:1]]), 6)
    with pytest.raises(ValueError, match="at least 2 clusters"):
        fit_prototypes(df, 1)
    with pytest.raises(ValueError, match="integer"):
        fit_prototypes(df, 2.5)
    with pytest.raises(ValueError, match="scaling"):
        fit_prototypes(df, 6, scaling="minmax")
    with pytest.raises(ValueError, match="method"):
        fit_prototypes(df, 6, method="dbscan")
    with pytest.raises(ValueError, match="DataFrame"):
        fit_prototypes(df[["pv", "sparc"]].to_numpy(), 6)


def test_too_few_trials():
    df = feature_frame([0.5, 0.7, 0.9, 1.1, 1.3], [-1.5, -2.0, -1.7, -2.2, -1.9])
    with pytest.raises(ValueError, match="5 trials are too few for k = 6"):
        fit_prototypes(df, 6)
    with pytest.raises(ValueError, match="too few for k = 5"):  # silhouette needs k <= n - 1
        fit_prototypes(df, 5)
    assert fit_prototypes(df, 4).k == 4


def test_duplicate_only_data():
    df = feature_frame(np.repeat([0.5, 1.0, 1.5], 10), np.repeat([-1.5, -2.0, -2.5], 10))
    with pytest.raises(ValueError, match="only 3 distinct"):
        fit_prototypes(df, 4)
    r = fit_prototypes(df, 3)
    np.testing.assert_array_equal(r.sizes, [10, 10, 10])
    with pytest.warns(UserWarning, match="2..3"):
        sw = silhouette_sweep(df)
    assert list(sw.ks) == [2, 3]
    with pytest.raises(ValueError, match="only 1 distinct"):
        fit_prototypes(feature_frame(np.ones(10), -2 * np.ones(10)), 2)
    with pytest.raises(ValueError, match="too few for a silhouette sweep"):
        silhouette_sweep(feature_frame(np.ones(10), -2 * np.ones(10)))


# --- silhouette sweep -------------------------------------------------------------------------


def test_sweep_range_and_contract(data):
    df, _ = data
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # 150 trials: no shrinking, no warning
        sw = silhouette_sweep(df)
    assert list(sw.ks) == list(range(2, 17)) and not sw.shrunk
    d = sw.to_dict()
    assert list(d) == [str(k) for k in range(2, 17)] and all(type(v) is float for v in d.values())
    assert int(sw.ks[np.argmax(sw.scores)]) == 6  # six blobs
    r6 = fit_prototypes(df, 6)
    np.testing.assert_array_equal(sw.results[6].labels, r6.labels)
    assert sw.results[6].silhouette == r6.silhouette
    assert 6 in sw.valid_ks()
    t = sw.table()
    assert list(t.columns) == ["silhouette", "valid", "failing"] and list(t.index) == list(range(2, 17))


def test_sweep_shrinks_with_few_trials():
    df, _ = blobs(n_per=2, seed=1)  # 12 trials
    with pytest.warns(UserWarning, match=r"shrunk from k = 2..16 to 2..11"):
        sw = silhouette_sweep(df)
    assert list(sw.ks) == list(range(2, 12)) and sw.shrunk
    with pytest.raises(ValueError, match="too few"):
        silhouette_sweep(df.iloc[:2])
    with pytest.raises(ValueError, match="k_min"):
        silhouette_sweep(df, k_min=5, k_max=3)


def test_failing_clusters_and_validity():
    labels = np.array([0, 0, 0, 1, 1, 1, 2])
    s = np.array([0.8, 0.7, 0.6, 0.3, 0.2, 0.1, 0.0])  # average 0.386: cluster 1 and singleton 2 fail
    assert failing_clusters(s, labels) == [1, 2]
    assert not is_valid(s, labels)
    s_ok = np.array([0.8, 0.7, 0.6, 0.6, 0.2, 0.1, 0.9])  # average 0.557
    assert failing_clusters(s_ok, labels) == [] and is_valid(s_ok, labels)
    assert not is_valid(s_ok - 1.0, labels)  # every cluster above its average, but average < 0
    # a cluster whose best trial equals the average exactly does not reach ABOVE it
    assert failing_clusters(np.array([0.9, 0.1, 0.5, 0.5]), np.array([0, 0, 1, 1])) == [1]


# --- stability --------------------------------------------------------------------------------


def test_ari_is_one_on_separated_blobs(data):
    df, _ = data
    np.testing.assert_array_equal(seed_stability(df, 6, seeds=range(1, 6)), 1.0)
    np.testing.assert_array_equal(bootstrap_stability(df, 6, n_boot=10), 1.0)
    np.testing.assert_array_equal(bootstrap_stability(df, 6, n_boot=5, scaling="standard"), 1.0)


def test_ari_below_one_when_k_is_wrong():
    """Each bootstrap ARI equals one recomputed with scikit-learn alone by the documented procedure:
    resample with default_rng(random_state), refit K-means (seeded from the same generator), assign
    every trial to the nearest refitted centre, compare with the full-data fit."""
    df, _ = blobs(n_per=30, seed=4, sd=(0.15, 0.4))  # blobs overlap; k = 9 splits them arbitrarily
    b = bootstrap_stability(df, 9, n_boot=10, random_state=1)
    x = df[["pv", "sparc"]].to_numpy(float)
    rng = np.random.default_rng(1)
    expected = []
    with threadpool_limits(1):  # a few hundred points: threads only cost time
        ref = KMeans(9, n_init=10, random_state=1).fit(x).labels_
        for _ in range(10):
            idx = rng.integers(0, len(x), len(x))
            km = KMeans(9, n_init=10, random_state=int(rng.integers(2**31 - 1))).fit(x[idx])
            expected.append(adjusted_rand_score(ref, km.predict(x)))
    assert b.shape == (10,)
    np.testing.assert_allclose(b, expected, rtol=0, atol=1e-12)
    assert b.min() < 0.95  # k = 9 on overlapping blobs is not stable


# --- results.json -----------------------------------------------------------------------------


def test_results_section_json(data):
    """Sizes, centres, prototypes and average silhouette against the known blobs (sizes 25, 22, .., 10,
    so that a permutation of the clusters shows), computed without skilllib."""
    df, truth = data
    keep = np.sort(np.concatenate([np.flatnonzero(truth == c)[: 25 - 3 * c] for c in range(6)]))
    df, truth = df.iloc[keep].reset_index(drop=True), truth[keep]
    sw = silhouette_sweep(df, 2, 8)
    out = results_section(sw, sw.results[6])
    text = json.dumps(out, allow_nan=False)
    back = json.loads(text)
    assert back["k"] == 6 and list(back["silhouette"]) == [str(k) for k in range(2, 9)]
    cl = back["clusters"]
    assert [c["id"] for c in cl] == list(range(6))
    assert [c["size"] for c in cl] == [25, 22, 19, 16, 13, 10]  # the blobs, numbered in PV order
    x = df[["pv", "sparc"]].to_numpy(float)
    means = [x[truth == c].mean(axis=0) for c in range(6)]
    np.testing.assert_allclose([[c["centre"]["pv"], c["centre"]["sparc"]] for c in cl], means, rtol=1e-12)
    assert back["average_silhouette"] == pytest.approx(silhouette_score(x, truth), abs=1e-12)
    for c in cl:  # the prototype is the blob member nearest the blob's mean
        members = np.flatnonzero(truth == c["id"])
        row = members[np.argmin(np.linalg.norm(x[members] - means[c["id"]], axis=1))]
        assert c["prototype"] == {
            "participant": df.at[row, "participant"],
            "trial": int(df.at[row, "trial"]),
            "pv": x[row, 0],
            "sparc": x[row, 1],
        }
    assert type(cl[0]["prototype"]["trial"]) is int and type(cl[0]["prototype"]["participant"]) is str


# --- invariances (hypothesis) -----------------------------------------------------------------

_BLOBS, _ = blobs(n_per=12, seed=7)
_RELAXED = settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@_RELAXED
@given(perm_seed=st.integers(0, 2**32 - 1), fit_seed=st.integers(0, 1000))
def test_row_permutation_keeps_prototypes(perm_seed, fit_seed):
    ref = fit_prototypes(_BLOBS, 6, random_state=fit_seed)
    perm = np.random.default_rng(perm_seed).permutation(len(_BLOBS))
    r = fit_prototypes(_BLOBS.iloc[perm], 6, random_state=fit_seed)
    key = ["participant", "trial"]
    pd.testing.assert_frame_equal(r.prototypes[key], ref.prototypes[key])
    np.testing.assert_allclose(r.centres.to_numpy(), ref.centres.to_numpy(), atol=1e-12)
    np.testing.assert_array_equal(r.labels, ref.labels[perm])


@_RELAXED
@given(factor=st.floats(0.01, 100.0), shift=st.floats(-5.0, 5.0))
def test_standard_scaling_ignores_pv_units(factor, shift):
    ref = fit_prototypes(_BLOBS, 6, scaling="standard")
    scaled = _BLOBS.assign(pv=_BLOBS["pv"] * factor + shift)
    r = fit_prototypes(scaled, 6, scaling="standard")
    np.testing.assert_array_equal(r.labels, ref.labels)
    np.testing.assert_allclose(r.centres["pv"], ref.centres["pv"] * factor + shift, rtol=1e-9, atol=1e-9)


def test_raw_scaling_does_depend_on_units():
    # the same fit in cm/s weighs PV 100x: the partition collapses onto PV, unlike the m/s one
    df, _ = blobs(n_per=30, seed=5, sd=(0.12, 0.3))
    a = fit_prototypes(df, 6, scaling="raw")
    b = fit_prototypes(df.assign(pv=df["pv"] * 100), 6, scaling="raw")
    assert not np.array_equal(a.labels, b.labels)


# --- figures ----------------------------------------------------------------------------------


def test_figures(tmp_path, data):
    import matplotlib.pyplot as plt

    from skilllib import figures as F

    df, _ = data
    sw = silhouette_sweep(df, 2, 10)
    r: PrototypeResult = sw.results[6]
    ax = F.plot_clusters(r).axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("peak speed PV (m/s)", "SPARC")
    ax = F.plot_silhouette_sweep(sw, chosen_k=6).axes[0]
    assert ax.get_ylabel() == "average silhouette"
    assert "silhouette" in F.plot_silhouettes(sw.results[3]).axes[0].get_xlabel()
    prof = [(np.linspace(0, 0.5, 30), p * np.sin(np.linspace(0, np.pi, 30))) for p in r.prototypes["pv"]]
    fig = F.plot_prototype_profiles(prof, r.prototypes)
    assert fig.axes[0].get_ylabel() == "speed (m/s)" and len(fig.axes[0].lines) == 6
    with pytest.raises(ValueError, match="5 speed profiles for 6 prototypes"):
        F.plot_prototype_profiles(prof[:5], r.prototypes)
    paths = F.save(fig, tmp_path, "profiles")
    assert all(p.stat().st_size > 0 for p in paths)
    from skilllib.figures import plot_stability

    ax = plot_stability({"seeds, raw": np.array([1.0, 0.9]), "bootstrap": np.array([0.5, 0.7, 0.6])}).axes[0]
    assert ax.get_ylabel() == "adjusted Rand index" and len(ax.collections) == 4  # 2 strips + 2 medians
    assert [t.get_text() for t in ax.get_xticklabels()] == ["seeds\nraw", "bootstrap"]
    with pytest.raises(ValueError, match="no ARI"):
        plot_stability({})
    plt.close("all")


# --- threads ----------------------------------------------------------------------------------


def test_fits_run_single_threaded_and_restore_limits():
    from threadpoolctl import threadpool_info

    from skilllib.smoothness import single_threaded

    before = [(i["internal_api"], i["num_threads"]) for i in threadpool_info()]
    inside = single_threaded()(lambda: [i["num_threads"] for i in threadpool_info()])()
    assert inside and all(n == 1 for n in inside)
    fit_prototypes(blobs(n_per=5)[0], 3)
    assert [(i["internal_api"], i["num_threads"]) for i in threadpool_info()] == before


@pytest.mark.parametrize(
    "ks, text", [([2, 3, 4, 7], "2-4, 7"), ([5], "5"), ([], "none"), ([2, 4, 6], "2, 4, 6"), ([3, 4], "3-4")]
)
def test_valid_k_ranges_reads_as_runs(ks, text):
    """The chapters print the valid k as runs; a run cut short or a lone k merged would misreport them."""
    from types import SimpleNamespace

    from skilllib.prototypes import SilhouetteSweep

    assert SilhouetteSweep.valid_k_ranges(SimpleNamespace(valid_ks=lambda: ks)) == text
