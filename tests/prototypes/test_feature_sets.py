"""skilllib.prototypes on the user's features: ``features=`` through the sweep, the fits and the results."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from sklearn.metrics import adjusted_rand_score, silhouette_score

from skilllib.prototypes import _kmeans as km
from skilllib.prototypes import (
    bootstrap_stability,
    feature_frame,
    fit_prototypes,
    results_section,
    seed_stability,
    silhouette_sweep,
    sparc_sensitivity,
)

THREE = ("pv", "sparc", "ldlj")
# Four blobs in (PV m/s, SPARC, LDLJ): two pairs share (PV, SPARC) and differ only in LDLJ, so no
# clustering of (PV, SPARC) alone can find them.
CENTRES3 = np.array([(0.5, -2.0, -5.0), (0.5, -2.0, -8.0), (1.2, -2.5, -5.0), (1.2, -2.5, -8.0)])
SD3 = np.array([0.03, 0.05, 0.2])


def blobs3(n_per: int = 20, seed: int = 0, centres: np.ndarray = CENTRES3, sd: np.ndarray = SD3):
    """Seeded 3-feature blobs (shuffled) as a features-table slice with extra columns, and the true blob."""
    rng = np.random.default_rng(seed)
    truth = np.repeat(np.arange(len(centres)), n_per)
    x = centres[truth] + rng.normal(0, 1, (len(truth), centres.shape[1])) * sd
    perm = rng.permutation(len(truth))
    x, truth = x[perm], truth[perm]
    n = len(truth)
    df = feature_frame(
        x[:, 0],
        x[:, 1],
        participant=[f"P{i % 7:02d}" for i in range(n)],
        trial=np.arange(n),
        ldlj=x[:, 2],
        duration=rng.uniform(0.4, 1.2, n),
    ).assign(status="selected")
    return df, truth


@pytest.fixture(scope="module")
def data3():
    return blobs3()


# --- the default is the paper's, unchanged ------------------------------------------------------


@pytest.mark.parametrize("method", ["kmeans", "gmm", "agglomerative"])
@pytest.mark.parametrize("scaling", ["raw", "standard"])
def test_default_features_give_exactly_the_explicit_pv_sparc_result(data3, method, scaling):
    df, _ = data3
    a = fit_prototypes(df, 4, method=method, scaling=scaling)
    b = fit_prototypes(df, 4, method=method, scaling=scaling, features=["pv", "sparc"])
    assert a.features == b.features == ("pv", "sparc")
    assert json.dumps(a.to_dict()) == json.dumps(b.to_dict())
    pd.testing.assert_frame_equal(a.data, b.data)
    pd.testing.assert_frame_equal(a.centres, b.centres)
    pd.testing.assert_frame_equal(a.prototypes, b.prototypes)
    np.testing.assert_array_equal(a.silhouette_samples, b.silhouette_samples)
    assert list(a.data.columns) == ["participant", "trial", "pv", "sparc", "cluster"]  # ldlj not taken along


def test_default_dicts_keep_their_keys_and_order(data3):
    df, _ = data3
    sw = silhouette_sweep(df, 2, 5)
    assert sw.features == ("pv", "sparc") and all(r.features == ("pv", "sparc") for r in sw.results.values())
    explicit = silhouette_sweep(df, 2, 5, features=("pv", "sparc"))
    assert sw.to_dict() == explicit.to_dict() and sw.estimate_dict() == explicit.estimate_dict()
    sec = results_section(sw, sw.results[4])
    assert json.dumps(sec) == json.dumps(results_section(explicit, explicit.results[4]))
    assert list(sec) == ["silhouette", "k", "method", "scaling", "average_silhouette", "clusters"]
    assert list(sec["silhouette"]) == ["2", "3", "4", "5"]
    c = sec["clusters"][0]
    assert list(c) == ["id", "size", "centre", "prototype"]
    assert list(c["centre"]) == ["pv", "sparc"]
    assert list(c["prototype"]) == ["participant", "trial", "pv", "sparc"]


def test_default_stability_is_unchanged_by_naming_the_default(data3):
    df, _ = data3
    np.testing.assert_array_equal(
        seed_stability(df, 3, seeds=range(1, 4)), seed_stability(df, 3, seeds=range(1, 4), features=("pv", "sparc"))
    )
    np.testing.assert_array_equal(
        bootstrap_stability(df, 3, n_boot=4), bootstrap_stability(df, 3, n_boot=4, features=("pv", "sparc"))
    )


# --- three features -------------------------------------------------------------------------------


@pytest.mark.parametrize("scaling", ["raw", "standard"])
def test_three_features_recover_blobs_that_two_cannot_separate(data3, scaling):
    df, truth = data3
    r = fit_prototypes(df, 4, features=THREE, scaling=scaling)
    assert r.features == THREE
    assert adjusted_rand_score(truth, r.labels) == 1.0
    assert list(r.centres.columns) == list(THREE)
    assert list(r.prototypes.columns) == ["participant", "trial", *THREE, "row"]
    assert r.sizes.tolist() == [20, 20, 20, 20]
    # the (PV, SPARC) plane sees two groups, not four
    two = fit_prototypes(df, 4, scaling=scaling)
    assert adjusted_rand_score(truth, two.labels) < 0.6
    # numbered by the first feature (PV)
    assert r.centres["pv"].is_monotonic_increasing
    x = df[list(THREE)].to_numpy(float)
    for c in range(4):
        t = truth[r.labels == c][0]
        np.testing.assert_allclose(r.centres.loc[c].to_numpy(), x[truth == t].mean(0), atol=1e-9)
        assert (np.abs(r.centres.loc[c].to_numpy() - CENTRES3[t]) < 5 * SD3 / np.sqrt(20)).all()


@pytest.mark.parametrize("scaling", ["raw", "standard"])
def test_three_feature_centres_are_member_means_and_prototypes_the_nearest_members(data3, scaling):
    df, _ = data3
    r = fit_prototypes(df, 4, features=THREE, scaling=scaling)
    x = df[list(THREE)].to_numpy(float)
    mean, sd = (x.mean(0), x.std(0)) if scaling == "standard" else (np.zeros(3), np.ones(3))
    z = (x - mean) / sd
    for c in range(4):
        mem = np.flatnonzero(r.labels == c)
        np.testing.assert_allclose(r.centres.loc[c].to_numpy(), x[mem].mean(0), atol=1e-9)  # original units
        cz = (r.centres.loc[c].to_numpy() - mean) / sd
        nearest = mem[np.argmin(np.linalg.norm(z[mem] - cz, axis=1))]
        assert r.prototypes.at[c, "row"] == nearest
        assert r.prototypes.at[c, "trial"] == df.at[nearest, "trial"]
        np.testing.assert_array_equal(r.prototypes.loc[c, list(THREE)].to_numpy(float), x[nearest])
    assert r.silhouette == pytest.approx(silhouette_score(z, r.labels), abs=1e-12)


def test_order_follows_the_first_feature_then_the_next(data3):
    df, truth = data3
    r = fit_prototypes(df, 4, features=("ldlj", "pv", "sparc"))
    assert list(r.centres.columns) == ["ldlj", "pv", "sparc"]
    assert r.centres["ldlj"].is_monotonic_increasing
    assert adjusted_rand_score(truth, r.labels) == 1.0
    # a first feature tied exactly in every centre (a constant 0.5 s): the second decides
    tied = fit_prototypes(df.assign(duration=0.5), 4, features=("duration", "ldlj", "pv"))
    assert (tied.centres["duration"] == 0.5).all()
    assert tied.centres["ldlj"].is_monotonic_increasing
    np.testing.assert_array_equal(tied.labels, r.labels)


def test_three_feature_sweep_dict_and_stability(data3):
    df, _ = data3
    sw = silhouette_sweep(df, 2, 6, features=THREE)
    assert sw.features == THREE and all(r.features == THREE for r in sw.results.values())
    assert sw.ks.tolist() == [2, 3, 4, 5, 6]
    direct = fit_prototypes(df, 4, features=THREE)
    np.testing.assert_array_equal(sw.results[4].labels, direct.labels)
    assert sw.results[4].valid  # (k = 2, the two LDLJ groups 3 apart, scores higher in raw units)
    sec = json.loads(json.dumps(results_section(sw, sw.results[4]), allow_nan=False))
    assert list(sec) == ["silhouette", "k", "method", "scaling", "average_silhouette", "clusters"]
    for c, cl in enumerate(sec["clusters"]):
        assert list(cl["centre"]) == list(THREE)
        assert list(cl["prototype"]) == ["participant", "trial", *THREE]
        assert cl["centre"]["ldlj"] == pytest.approx(direct.centres.at[c, "ldlj"])
        assert cl["prototype"]["ldlj"] == pytest.approx(direct.prototypes.at[c, "ldlj"])
    np.testing.assert_array_equal(seed_stability(df, 4, seeds=range(1, 4), features=THREE), 1.0)
    np.testing.assert_array_equal(bootstrap_stability(df, 4, n_boot=5, features=THREE), 1.0)


def test_two_other_features(data3):
    df, truth = data3
    r = fit_prototypes(df, 2, features=("pv", "ldlj"))
    assert r.features == ("pv", "ldlj") and list(r.centres.columns) == ["pv", "ldlj"]
    assert "sparc" not in r.data.columns and "sparc" not in r.prototypes.columns
    assert r.to_dict()["clusters"][0]["centre"].keys() == {"pv", "ldlj"}
    # raw units: the LDLJ gap (3) outweighs the PV gap (0.7 m/s), so k = 2 splits LDLJ -5 from -8
    assert adjusted_rand_score(truth % 2, r.labels) == 1.0
    assert adjusted_rand_score(truth // 2, fit_prototypes(df, 2, features=("pv", "sparc")).labels) == 1.0


# --- scaling on features of very different units ------------------------------------------------


def test_standard_scaling_balances_features_of_very_different_units():
    """Two groups apart in PV (m/s, 0.5 vs 1.5) and a peak acceleration (m/s^2) that is noise of SD 10:
    raw K-means splits along the large numbers of the noise, standardised K-means finds the groups."""
    rng = np.random.default_rng(4)
    truth = np.repeat([0, 1], 60)
    pv = np.where(truth == 0, 0.5, 1.5) + rng.normal(0, 0.05, 120)
    acc = rng.normal(30.0, 10.0, 120)
    df = feature_frame(pv, np.zeros(120), peak_acc=acc)
    raw = fit_prototypes(df, 2, features=("pv", "peak_acc"), scaling="raw")
    std = fit_prototypes(df, 2, features=("pv", "peak_acc"), scaling="standard")
    assert abs(adjusted_rand_score(truth, raw.labels)) < 0.1
    assert adjusted_rand_score(truth, std.labels) == 1.0
    # centres in original units whatever the scaling: the groups' mean PV (m/s) and peak acceleration (m/s^2)
    for r in (raw, std):
        for c in range(2):
            m = r.labels == c
            np.testing.assert_allclose(r.centres.loc[c].to_numpy(), [pv[m].mean(), acc[m].mean()], atol=1e-9)
    np.testing.assert_allclose(std.centres["pv"], [pv[:60].mean(), pv[60:].mean()], atol=1e-9)
    assert std.centres["peak_acc"].between(20, 40).all()


# --- errors name the features -------------------------------------------------------------------


def test_errors_name_the_features_used():
    f = feature_frame(np.repeat([0.5, 1.0, 1.5], 4), np.linspace(-3, -1, 12), ldlj=np.repeat([-5.0, -6.0, -7.0], 4))
    with pytest.raises(ValueError, match=r"^only 3 distinct \(pv, ldlj\) points among 12 trials: cannot form k = 4"):
        fit_prototypes(f, 4, features=("pv", "ldlj"))
    fit_prototypes(f, 4)  # (pv, sparc) has 12 distinct points
    with pytest.warns(UserWarning, match=r"12 trials with 3 distinct \(pv, ldlj\) points allow at most k = 3"):
        silhouette_sweep(f, 2, 6, features=("pv", "ldlj"))
    one = feature_frame([0.5, 0.5, 0.5], [-1.0, -2.0, -3.0], ldlj=[-5.0, -5.0, -5.0])
    with pytest.raises(ValueError, match=r"\(1 distinct \(pv, ldlj\) points\) are too few for a silhouette sweep"):
        silhouette_sweep(one, features=("pv", "ldlj"))
    bad = f.assign(ldlj=np.r_[np.nan, f["ldlj"].to_numpy()[1:]])
    with pytest.raises(ValueError, match=r"^1 trial\(s\) have NaN or infinite pv/sparc/ldlj, e\.g\. "):
        fit_prototypes(bad, 2, features=THREE)
    fit_prototypes(bad, 2)  # NaN in a column not clustered on is no concern
    with pytest.raises(
        ValueError, match=r"lacks column\(s\) \['path_length'\]; needs participant, trial, pv, path_length"
    ):
        fit_prototypes(f, 2, features=("pv", "path_length"))
    with pytest.raises(ValueError, match=r"not numeric"):
        fit_prototypes(f.assign(label="a"), 2, features=("pv", "label"))


@pytest.mark.parametrize(
    ("features", "message"),
    [
        (("pv",), "at least two features"),
        ((), "at least two features"),
        (("pv", "pv"), "named twice"),
        ("pv,sparc", "sequence of column names"),
        (("pv", "trial"), r"\['trial'\] cannot be clustering features"),
        (("pv", "cluster"), r"\['cluster'\] cannot be clustering features"),
        (("pv", 3), "column names"),
    ],
)
def test_bad_feature_sets_are_refused(data3, features, message):
    df, _ = data3
    with pytest.raises(ValueError, match=message):
        fit_prototypes(df, 2, features=features)
    with pytest.raises(ValueError, match=message):
        silhouette_sweep(df, features=features)


def test_results_section_refuses_a_sweep_and_fit_of_different_features(data3):
    df, _ = data3
    sw = silhouette_sweep(df, 2, 4)
    with pytest.raises(ValueError, match=r"the sweep clustered \(pv, sparc\) but the fit \(pv, sparc, ldlj\)"):
        results_section(sw, fit_prototypes(df, 4, features=THREE))


def test_feature_frame_takes_further_columns():
    f = feature_frame([0.5, 0.6], [-1.5, -1.6], trial=["a", "b"], ldlj=[-5, -6], duration=(0.7, 0.8))
    assert list(f.columns) == ["participant", "trial", "pv", "sparc", "ldlj", "duration"]
    assert f["ldlj"].dtype == float
    with pytest.raises(ValueError, match=r"column\(s\) \{'ldlj': 1\} must have 2 values like pv"):
        feature_frame([0.5, 0.6], [-1.5, -1.6], ldlj=[-5])
    with pytest.raises(ValueError, match="clash"):
        feature_frame([0.5, 0.6], [-1.5, -1.6], cluster=[0, 1])


# --- sensitivity ----------------------------------------------------------------------------------


def test_sparc_sensitivity_refuses_features_without_sparc_before_any_work():
    with pytest.raises(ValueError, match=r"\(pv, ldlj\) do not include sparc"):
        sparc_sensitivity(None, features=("pv", "ldlj"))


def test_sparc_sensitivity_refuses_a_reference_of_other_features(data3):
    df, _ = data3
    sw = silhouette_sweep(df, 2, 3)
    with pytest.raises(ValueError, match=r"reference sweep clustered \(pv, sparc\), not \(pv, sparc, ldlj\)"):
        sparc_sensitivity(None, reference=(df, sw), features=THREE)


def test_sparc_sensitivity_clusters_every_setting_on_the_same_three_features():
    from skilllib.cohort import CohortModel, generate_cohort
    from skilllib.features import select, trial_features
    from skilllib.recordings import recordings_from_frame

    rec = recordings_from_frame(generate_cohort(5, CohortModel(n_participants=3, n_trials=30)).frame)
    settings_ = ({"fc": 20.0}, {"fc": 10.0})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        sens = sparc_sensitivity(rec, settings_, k=3, k_range=(2, 4), features=THREE)
        ref_feats = trial_features(rec)
        ref_sweep = silhouette_sweep(select(ref_feats), 2, 4, features=THREE)
    assert sens.features == THREE
    for run in sens.runs:
        assert run.sweep.features == THREE and run.fit.features == THREE
    np.testing.assert_array_equal(sens.reference.fit.labels, ref_sweep.results[sens.k].labels)
    other = sens.runs[1]
    direct = fit_prototypes(other.selected, sens.k, features=THREE)
    np.testing.assert_array_equal(other.fit.labels, direct.labels)
    d = json.loads(json.dumps(sens.to_dict(), allow_nan=False))
    for entry in d["settings"]:
        assert list(entry["prototypes"][0]) == ["cluster", "participant", "trial", *THREE, "kept"]
    # the pipeline's path: the reference handed in, with the same features
    again = sparc_sensitivity(rec, settings_, k=3, k_range=(2, 4), features=THREE, reference=(ref_feats, ref_sweep))
    assert again.to_dict() == sens.to_dict()


# --- invariance -----------------------------------------------------------------------------------


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**16), perm_seed=st.integers(0, 2**16), scaling=st.sampled_from(["raw", "standard"]))
def test_permuting_the_trials_keeps_sizes_centres_and_prototypes_on_separated_blobs(seed, perm_seed, scaling):
    """On well-separated blobs (gaps of many SDs in every feature pair) K-means with restarts finds the
    same partition whatever the row order; the prototype choice breaks exact ties by (participant, trial),
    so the same trials are prototypes. (Not claimed for overlapping data: K-means++ seeding draws rows
    by position, and another local optimum may win.)"""
    df, _ = blobs3(n_per=12, seed=seed)
    perm = np.random.default_rng(perm_seed).permutation(len(df))
    shuffled = df.iloc[perm]
    a = fit_prototypes(df, 4, features=THREE, scaling=scaling, n_init=10)
    b = fit_prototypes(shuffled, 4, features=THREE, scaling=scaling, n_init=10)
    assert a.sizes.tolist() == b.sizes.tolist()
    assert a.prototype_ids == b.prototype_ids
    np.testing.assert_allclose(a.centres.to_numpy(), b.centres.to_numpy(), atol=1e-12)
    np.testing.assert_array_equal(a.labels[perm], b.labels)
    assert a.silhouette == pytest.approx(b.silhouette, abs=1e-12)


def test_features_module_constant_is_the_default():
    assert km.FEATURES == ("pv", "sparc")
