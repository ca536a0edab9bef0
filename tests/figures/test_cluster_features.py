"""skilllib.figures.clusters on the user's clustering features: axes, labels and the pairs note."""

from __future__ import annotations

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest

from skilllib import figures as F
from skilllib.features import feature_label
from skilllib.prototypes import feature_frame, fit_prototypes

matplotlib.use("Agg")

CENTRES = np.array([(0.5, -2.0, -5.0), (0.5, -2.0, -8.0), (1.2, -2.5, -5.0), (1.2, -2.5, -8.0)])


@pytest.fixture(scope="module")
def df():
    rng = np.random.default_rng(2)
    truth = np.repeat(np.arange(4), 15)
    x = CENTRES[truth] + rng.normal(0, 1, (60, 3)) * [0.03, 0.05, 0.2]
    return feature_frame(x[:, 0], x[:, 1], ldlj=x[:, 2], duration=rng.uniform(0.4, 1.2, 60))


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def _offsets(ax, i):
    return np.asarray(ax.collections[i].get_offsets())


def test_default_scatter_is_the_papers_pv_sparc_without_a_title(df):
    r = fit_prototypes(df, 4)
    ax = F.plot_clusters(r).axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("peak speed PV (m/s)", "SPARC")
    assert ax.get_title() == ""
    np.testing.assert_array_equal(_offsets(ax, 4), r.centres[["pv", "sparc"]].to_numpy())  # after 4 clusters


def test_scatter_of_two_other_features_uses_them_and_their_labels(df):
    r = fit_prototypes(df, 4, features=("pv", "ldlj"))
    ax = F.plot_clusters(r).axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == (feature_label("pv"), feature_label("ldlj"))
    assert ax.get_ylabel() == "LDLJ"
    assert ax.get_title() == ""
    pts = np.vstack([_offsets(ax, c) for c in range(4)])
    np.testing.assert_array_equal(np.sort(pts, axis=0), np.sort(df[["pv", "ldlj"]].to_numpy(), axis=0))
    np.testing.assert_array_equal(_offsets(ax, 4), r.centres[["pv", "ldlj"]].to_numpy())
    np.testing.assert_array_equal(_offsets(ax, 5), r.prototypes[["pv", "ldlj"]].to_numpy())


def test_scatter_of_three_features_shows_the_first_two_and_says_so(df):
    r = fit_prototypes(df, 4, features=("duration", "pv", "ldlj"), scaling="standard")
    ax = F.plot_clusters(r).axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("duration (s)", "peak speed PV (m/s)")
    title = ax.get_title()
    assert "2 of 3 clustering features shown (not shown: LDLJ)" in title
    assert "duration and PV" in title and "standard scaling" in title
    np.testing.assert_array_equal(_offsets(ax, 4), r.centres[["duration", "pv"]].to_numpy())


def test_silhouette_plot_names_the_features_and_the_order(df):
    default = F.plot_silhouettes(fit_prototypes(df, 4)).axes[0]
    assert default.get_ylabel() == "trials, by cluster (0 = lowest PV)"
    assert "(kmeans, raw features)" in default.get_title()
    ax = F.plot_silhouettes(fit_prototypes(df, 4, features=("ldlj", "pv", "sparc"))).axes[0]
    assert ax.get_ylabel() == "trials, by cluster (0 = lowest LDLJ)"
    assert "(kmeans, raw ldlj, pv, sparc)" in ax.get_title()


def test_prototype_profiles_are_labelled_with_the_features_clustered(df):
    r = fit_prototypes(df, 4)
    prof = [(np.linspace(0, 0.5, 20), np.sin(np.linspace(0, np.pi, 20))) for _ in range(4)]
    labels = [ln.get_label() for ln in F.plot_prototype_profiles(prof, r.prototypes).axes[0].lines]
    p = r.prototypes.loc[0]
    assert labels[0] == f"cluster 0: PV = {p['pv']:.2f} m/s, SPARC = {p['sparc']:.2f}"
    r3 = fit_prototypes(df, 4, features=("pv", "ldlj", "duration"))
    labels = [ln.get_label() for ln in F.plot_prototype_profiles(prof, r3.prototypes).axes[0].lines]
    p = r3.prototypes.loc[2]
    assert labels[2] == f"cluster 2: PV = {p['pv']:.2f} m/s, LDLJ = {p['ldlj']:.2f}, duration = {p['duration']:.2f} s"
