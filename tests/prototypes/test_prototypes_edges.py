"""skilllib.prototypes at its edges: feature_frame's types and ids, the validity rule's boundaries, the
options the sweep and the seed-stability check pass on, and the words of their errors and warnings.

Each test says which wrong behaviour it catches. Expected values come from scikit-learn called
directly (KMeans, silhouette_samples, adjusted_rand_score, StandardScaler) or from the rule's
definition, never from skilllib's own output.
"""

from __future__ import annotations

import json
import warnings

import numpy as np
import pandas as pd
import pytest
from sklearn.cluster import AgglomerativeClustering, KMeans
from sklearn.metrics import adjusted_rand_score, silhouette_samples
from sklearn.preprocessing import StandardScaler
from threadpoolctl import threadpool_limits

from skilllib.prototypes import (
    DEFAULT_K,
    failing_clusters,
    feature_frame,
    fit_prototypes,
    is_valid,
    seed_stability,
    silhouette_sweep,
)
from skilllib.prototypes import _kmeans as prototypes

# Six blobs in (PV m/s, SPARC), listed in PV order, overlapping at sd = (0.15, 0.4): the partition
# depends on the seed, on n_init and on the scaling, so a dropped option shows in the result.
CENTRES = np.array([(0.4, -1.5), (0.65, -2.4), (0.9, -1.7), (1.15, -2.8), (1.4, -2.0), (1.65, -2.6)])


def overlapping(n_per: int = 15, seed: int = 4) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    truth = np.repeat(np.arange(len(CENTRES)), n_per)
    x = CENTRES[truth] + rng.normal(0, 1, (len(truth), 2)) * np.array([0.15, 0.4])
    x = x[rng.permutation(len(truth))]
    n = len(truth)
    return pd.DataFrame(
        {
            "participant": [f"P{i % 10:02d}" for i in range(n)],
            "trial": np.arange(n) // 10,
            "pv": x[:, 0],
            "sparc": x[:, 1],
        }
    )


@pytest.fixture(scope="module")
def df() -> pd.DataFrame:
    return overlapping()


def space(df: pd.DataFrame, scaling: str) -> np.ndarray:
    x = df[["pv", "sparc"]].to_numpy(float)
    return x if scaling == "raw" else StandardScaler().fit_transform(x)


def kmeans_labels(z: np.ndarray, k: int, random_state: int, n_init: int) -> np.ndarray:
    with threadpool_limits(1):
        return KMeans(k, init="k-means++", n_init=n_init, random_state=random_state).fit(z).labels_


# --- feature_frame -----------------------------------------------------------------------------


def test_feature_frame_keeps_the_given_ids():
    """Given participant and trial ids are the frame's (and so the prototypes'). Catches ids replaced
    by the defaults."""
    f = feature_frame([0.5, 0.6, 1.2], [-1.5, -1.6, -2.5], participant=["P01", "P01", "P07"], trial=[3, 4, 9])
    assert f["participant"].tolist() == ["P01", "P01", "P07"] and f["trial"].tolist() == [3, 4, 9]


def test_feature_frame_features_are_floats_and_default_ids_integers():
    """PV and SPARC given as whole numbers become floats (m/s, dimensionless); the default participant
    is the integer 0 and trials 0..n-1, so results.json writes ``"participant": 0``, not ``0.0``.
    Catches integer feature columns and float default ids."""
    f = feature_frame([1, 2, 3, 4], [-2, -3, -2, -3])
    assert f["pv"].dtype == np.float64 and f["sparc"].dtype == np.float64
    assert f["participant"].dtype.kind == "i" and f["trial"].dtype.kind == "i"
    proto = fit_prototypes(f, 2).to_dict()["clusters"][0]["prototype"]
    assert json.dumps(proto["participant"]) == "0" and type(proto["pv"]) is float


@pytest.mark.parametrize("participant, trial", [([1, 2], None), (None, [1, 2, 3, 4]), ([1], [1, 2])])
def test_feature_frame_names_ids_of_the_wrong_length(participant, trial):
    """Either id array of another length than pv is refused with both lengths named. Catches a check
    that needs both to be wrong (pandas would then refuse with its own, less helpful message)."""
    p_size = 3 if participant is None else len(participant)
    t_size = 3 if trial is None else len(trial)
    with pytest.raises(
        ValueError, match=rf"^participant \({p_size}\) and trial \({t_size}\) must have 3 values like pv$"
    ):
        feature_frame([0.5, 0.6, 1.2], [-1.5, -1.6, -2.5], participant=participant, trial=trial)


# --- errors and warnings ---------------------------------------------------------------------------


def test_too_few_trials_message_states_the_rule():
    """The message gives the minimum (k + 1 trials) and why (Rousseeuw's 2 <= k <= n - 1). Catches a
    wrong number or altered reference in it."""
    f = feature_frame([0.5, 0.7, 0.9, 1.1, 1.3], [-1.5, -2.0, -1.7, -2.2, -1.9])
    with pytest.raises(
        ValueError,
        match=r"^5 trials are too few for k = 6 clusters: need at least k \+ 1 = 7 "
        r"\(the silhouette is defined for 2 <= k <= n - 1, Rousseeuw 1987\)$",
    ):
        fit_prototypes(f, 6)


def test_sweep_too_few_message_states_the_minimum():
    """Two trials cannot start a sweep at k = 2: the message asks for k_min + 1 = 3 trials and 2
    distinct points. Catches a wrong count."""
    f = feature_frame([0.5, 0.7], [-1.5, -2.0])
    with pytest.raises(
        ValueError,
        match=r"^2 trials \(2 distinct \(pv, sparc\) points\) are too few for a "
        r"silhouette sweep from k = 2: need at least 3 trials and 2 distinct points$",
    ):
        silhouette_sweep(f)


def test_sweep_shrink_warning_points_at_the_caller():
    """The UserWarning that the k range was shrunk names the caller's line (stacklevel 2), where the
    user can act, not a line inside skilllib. Catches the warning attributed to prototypes.py.
    (Under mutmut the function runs inside its trampoline, two frames deeper: the caller frame is then
    mutmut's; it is still not prototypes.py.)"""
    f = overlapping(n_per=2)  # 12 trials: k at most 11
    with pytest.warns(UserWarning, match=r"^silhouette sweep shrunk from k = 2..16 to 2..11: 12 trials") as rec:
        silhouette_sweep(f, n_init=1)
    assert len(rec) == 1 and rec[0].category is UserWarning
    where = rec[0].filename
    instrumented = hasattr(silhouette_sweep, "__wrapped__")  # mutmut's trampoline
    assert where != prototypes.__file__
    assert where == __file__ or (instrumented and "mutmut" in where)


# --- the validity rule ---------------------------------------------------------------------------


def test_failing_clusters_and_is_valid_use_the_given_average():
    """Both take the average line from ``average`` when given (the plot's line may be another run's).
    Cluster 1's best trial (0.5) is not above the samples' own mean 0.5 but is above 0.4. Catches the
    given average ignored."""
    s, labels = np.array([0.9, 0.1, 0.5, 0.5]), np.array([0, 0, 1, 1])
    assert failing_clusters(s, labels) == [1] and not is_valid(s, labels)
    assert failing_clusters(s, labels, average=0.4) == [] and is_valid(s, labels, average=0.4)
    assert failing_clusters(s, labels, average=0.95) == [0, 1]
    assert not is_valid(s, labels, average=-0.4)  # no cluster fails, but the average is not > 0


def test_an_average_silhouette_of_exactly_zero_is_not_valid():
    """The rule asks for an average > 0: exactly 0 fails even when every cluster has a trial above it.
    Catches >= 0."""
    s, labels = np.array([0.5, -0.5, 0.25, -0.25]), np.array([0, 0, 1, 1])
    assert s.mean() == 0.0 and failing_clusters(s, labels) == []
    assert not is_valid(s, labels) and not is_valid(s, labels, average=0.0)


def test_failing_clusters_averages_in_double_precision():
    """Silhouettes handed over as float32 are averaged in float64: the mean of float32 0.9, 0.1, 0.5,
    0.5 is 0.49999999441..., so cluster 1's 0.5 lies above it. Catches the average taken in float32,
    which rounds it to 0.5 and fails cluster 1."""
    s32, labels = np.array([0.9, 0.1, 0.5, 0.5], dtype=np.float32), np.array([0, 0, 1, 1])
    exact = sum(float(x) for x in s32) / 4
    assert exact < 0.5 and np.float32(s32.mean(dtype=np.float32)) == 0.5  # float32 would round it up
    assert failing_clusters(s32, labels) == []


def test_is_valid_agrees_with_failing_clusters_on_float32():
    """is_valid is "average > 0 and no failing cluster": on the float32 silhouettes above no cluster
    fails and the average is positive, so they are valid. Catches is_valid averaging in float32 (0.5
    exactly, so that cluster 1 fails there and not in failing_clusters); that was a bug."""
    s32, labels = np.array([0.9, 0.1, 0.5, 0.5], dtype=np.float32), np.array([0, 0, 1, 1])
    assert failing_clusters(s32, labels) == [] and is_valid(s32, labels)
    assert is_valid(s32.astype(np.float64), labels) and is_valid(list(s32), labels)


def test_result_failing_clusters_are_computed_from_its_silhouettes(df):
    """PrototypeResult.failing_clusters() and .valid apply the rule to the fit's own silhouettes:
    recomputed here with sklearn's silhouette_samples on the fit's labels. k = 9 on six overlapping
    blobs leaves clusters below the average, k = 2 none. Catches the wrong array passed on."""
    x = df[["pv", "sparc"]].to_numpy(float)
    seen = set()
    for k in (2, 3, 9):
        r = fit_prototypes(df, k)
        s = silhouette_samples(x, r.labels)
        expected = [c for c in range(k) if not (s[r.labels == c] > s.mean()).any()]
        assert r.failing_clusters() == expected and r.valid == (s.mean() > 0 and not expected)
        seen.add(bool(expected))
    assert seen == {True, False}  # both outcomes occur


def test_to_dict_names_method_and_scaling(df):
    """results.json's clustering section carries how it was made: ``method`` and ``scaling`` (README).
    Catches renamed or missing keys."""
    d = fit_prototypes(df, 3, method="agglomerative", scaling="standard").to_dict()
    assert list(d) == ["k", "method", "scaling", "average_silhouette", "clusters"]
    assert (d["k"], d["method"], d["scaling"]) == (3, "agglomerative", "standard")


# --- the sweep passes its options on -------------------------------------------------------------


def same_fit(a, b) -> bool:
    return (
        (a.k, a.method, a.scaling, a.random_state, a.n_init) == (b.k, b.method, b.scaling, b.random_state, b.n_init)
        and np.array_equal(a.labels, b.labels)
        and a.silhouette == b.silhouette
        and a.prototypes.equals(b.prototypes)
    )


def test_sweep_results_are_fit_prototypes_with_the_same_options(df):
    """``results[k]`` equals ``fit_prototypes(data, k, ...)`` with the same options, defaults included
    (random_state 0, n_init 10). Catches an option not passed on or a default that differs."""
    sw = silhouette_sweep(df, 8, 9)
    assert all(same_fit(sw.results[k], fit_prototypes(df, k)) for k in (8, 9))
    sw = silhouette_sweep(df, 9, 9, method="agglomerative", scaling="standard")
    assert same_fit(sw.results[9], fit_prototypes(df, 9, method="agglomerative", scaling="standard"))
    sw = silhouette_sweep(df, 9, 9, random_state=3, n_init=1)
    assert same_fit(sw.results[9], fit_prototypes(df, 9, random_state=3, n_init=1))
    # the options matter on these data: n_init 1 and 10 give other partitions
    assert not np.array_equal(kmeans_labels(space(df, "raw"), 9, 3, 1), kmeans_labels(space(df, "raw"), 9, 3, 10))


def test_sweep_of_one_k_and_within_k_max():
    """k_min == k_max is a sweep of one k; k_max bounds the range even when the data allow more.
    Catches k_min == k_max refused and k_max ignored."""
    f = overlapping(n_per=4)  # 24 trials: the data allow k up to 23
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert silhouette_sweep(f, 3, 3, n_init=1).ks.tolist() == [3]
        assert silhouette_sweep(f, 2, 4, n_init=1).ks.tolist() == [2, 3, 4]


# --- seed stability: against scikit-learn ---------------------------------------------------------


def ari_oracle(df, k, seeds, scaling="raw", random_state=0, n_init=10) -> list[float]:
    """The documented procedure with scikit-learn alone: K-means with random_state (the reference) and
    with each seed, in the scaling's space, compared by the adjusted Rand index."""
    z = space(df, scaling)
    ref = kmeans_labels(z, k, random_state, n_init)
    return [adjusted_rand_score(ref, kmeans_labels(z, k, s, n_init)) for s in seeds]


def test_seed_stability_defaults(df):
    """Defaults: reference random_state 0 and n_init 10, as fit_prototypes. On these data n_init 10 and
    11 give other ARIs, and so do reference seeds 0 and 1. Catches another default."""
    seeds = [1, 2, 3]
    got = seed_stability(df, 9, seeds=seeds)
    np.testing.assert_allclose(got, ari_oracle(df, 9, seeds), rtol=0, atol=1e-12)
    assert not np.allclose(got, ari_oracle(df, 9, seeds, n_init=11))
    assert not np.allclose(got, ari_oracle(df, 9, seeds, random_state=1))


def test_seed_stability_passes_every_option_on(df):
    """k, scaling, random_state and n_init reach both the reference and each refit: the ARIs equal those
    of scikit-learn run with the same options (here not the defaults). Catches an option dropped on
    either side (a dropped seed gives a constant or random ARI)."""
    seeds = [1, 2, 3, 4]
    got = seed_stability(df, 7, seeds=seeds, scaling="standard", random_state=5, n_init=1)
    expected = ari_oracle(df, 7, seeds, scaling="standard", random_state=5, n_init=1)
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-12)
    assert len(set(np.round(expected, 9))) > 1 and max(expected) < 1  # the seeds matter here
    for other in (
        dict(scaling="raw", random_state=5, n_init=1),
        dict(scaling="standard", random_state=0, n_init=1),
        dict(scaling="standard", random_state=5, n_init=10),
    ):
        assert not np.allclose(got, ari_oracle(df, 7, seeds, **other))  # each option changes the answer
    assert DEFAULT_K != 7 and not np.allclose(got, ari_oracle(df, DEFAULT_K, seeds, "standard", 5, 1))


def test_seed_stability_of_a_deterministic_method_is_one(df):
    """Ward clustering ignores the seed: every refit is the same partition, ARI exactly 1. K-means on
    these data gives another partition than Ward. Catches the method not passed to the reference or to
    the refits."""
    np.testing.assert_array_equal(seed_stability(df, 9, seeds=[1, 2], method="agglomerative"), 1.0)
    ward = AgglomerativeClustering(n_clusters=9, linkage="ward").fit_predict(space(df, "raw"))
    assert adjusted_rand_score(ward, kmeans_labels(space(df, "raw"), 9, 0, 10)) < 0.99


def test_standard_scaling_leaves_a_constant_feature_unscaled():
    """Every trial at the same PV (a paced task): standard scaling z-scores SPARC and leaves PV, whose SD
    is 0, unscaled, as sklearn's StandardScaler does; the clusters are K-means' on StandardScaler's
    output and the centres are reported in original units (PV exactly 0.5 m/s). Catches a division by
    the zero SD (NaN or inf in the clustering space)."""
    rng = np.random.default_rng(2)
    f = feature_frame(np.full(30, 0.5), np.r_[rng.normal(-1.5, 0.05, 15), rng.normal(-2.5, 0.05, 15)])
    r = fit_prototypes(f, 2, scaling="standard")
    z = space(f, "standard")
    assert np.all(z[:, 0] == 0.0)  # sklearn: a constant feature stays at 0 after centring
    assert adjusted_rand_score(r.labels, kmeans_labels(z, 2, 0, 10)) == 1.0
    np.testing.assert_array_equal(r.centres["pv"], [0.5, 0.5])
    sparc = f["sparc"].to_numpy()
    np.testing.assert_allclose(sorted(r.centres["sparc"]), sorted([sparc[:15].mean(), sparc[15:].mean()]), rtol=1e-12)


def test_duplicate_ids_are_counted_and_three_are_shown():
    """Five repeated (participant, trial) ids: the error counts all five and shows the first three (a
    message that lists every duplicate of a large table would be unreadable)."""
    from skilllib.prototypes import fit_prototypes

    n = 12
    df = pd.DataFrame(
        {
            "participant": ["p"] * n,
            "trial": [str(i % 7) for i in range(n)],
            "pv": np.linspace(0.3, 1.4, n),
            "sparc": np.linspace(-2.0, -1.4, n),
        }
    )
    with pytest.raises(ValueError, match=r"^5 duplicate \(participant, trial\) id\(s\), e\.g\. ") as e:
        fit_prototypes(df, 2)
    assert str(e.value).endswith("[('p', '0'), ('p', '1'), ('p', '2')]")
