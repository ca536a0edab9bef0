"""The figure of two clusterings side by side (issue 25): a panel per fit, corrected trials filled, each
centre labelled with its cluster's share of corrected trials."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from skilllib.figures import plot_measure_clusters, plt  # noqa: E402
from skilllib.prototypes import feature_frame, fit_prototypes  # noqa: E402


@pytest.fixture(scope="module")
def fits():
    rng = np.random.default_rng(0)
    n = 120
    pv = rng.uniform(0.3, 1.6, n)
    corrected = rng.random(n) < pv / 1.6
    ldlj = np.where(corrected, -6.0, -3.0) + rng.normal(0, 0.3, n)
    frame = feature_frame(pv, -1.6 + rng.normal(0, 0.1, n), ldlj=ldlj)
    both = {
        "(PV, SPARC)": fit_prototypes(frame, 3),
        "(PV, LDLJ)": fit_prototypes(frame, 3, features=("pv", "ldlj")),
    }
    return both, corrected


def test_one_panel_per_fit_with_its_features_and_silhouette(fits):
    both, corrected = fits
    fig = plot_measure_clusters(both, corrected, labels={"ldlj": "LDLJ (dimensionless)"})
    assert len(fig.axes) == 2
    (a, b) = fig.axes
    assert a.get_xlabel() == "peak speed PV (m/s)" and a.get_ylabel() == "SPARC (dimensionless)"
    assert b.get_ylabel() == "LDLJ (dimensionless)"
    assert f"{both['(PV, LDLJ)'].silhouette:.2f}" in b.get_title() and "(PV, LDLJ)" in b.get_title()
    plt.close(fig)


def test_each_centre_carries_its_clusters_share_of_corrected_trials(fits):
    both, corrected = fits
    fig = plot_measure_clusters(both, corrected)
    for ax, fit in zip(fig.axes, both.values()):
        lab = fit.data["cluster"].to_numpy()
        want = sorted(f"{corrected[lab == c].mean():.0%}" for c in range(fit.k))
        assert sorted(t.get_text() for t in ax.texts) == want
        # filled points are exactly the corrected trials
        filled = sum(
            len(col.get_offsets())
            for col in ax.collections
            if col.get_gid() != "centre" and len(col.get_facecolor()) and col.get_facecolor()[0][3] > 0
        )
        assert filled == corrected.sum()
    plt.close(fig)


def test_flags_of_another_length_are_refused(fits):
    both, corrected = fits
    with pytest.raises(ValueError, match="corrected flags"):
        plot_measure_clusters(both, corrected[:-1])
