"""The estimates-against-truth figure with a second contact-speed estimate (skilllib.figures.experiment)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from skilllib.figures import plot_estimates_vs_truth  # noqa: E402


@pytest.fixture
def tables():
    ids = {"participant": ["1", "1", "2", "2"], "trial": ["1", "2", "1", "2"]}
    features = pd.DataFrame(
        {
            **ids,
            "status": ["selected", "excluded", "selected", "invalid"],
            "pv": [1.0, 1.2, 0.8, np.nan],
            "contact_speed": [0.5, 0.9, 0.35, np.nan],
            "duration": [0.3, 0.25, 0.4, np.nan],
            "t_onset": [0.32, 0.32, 0.3, np.nan],
            "t_contact": [0.633, 0.583, 0.717, np.nan],
        }
    )
    truth = pd.DataFrame(
        {
            **ids,
            "pv": [1.01, 1.19, 0.82, 0.9],
            "contact_speed": [0.45, 0.6, 0.25, 0.5],
            "t_onset": [0.3, 0.3, 0.3, 0.3],
            "t_contact": [0.62, 0.57, 0.71, 0.7],
        }
    )
    est = pd.DataFrame({**ids, "contact_speed": [0.47, 0.72, 0.29, np.nan]})
    return features, truth, est


def test_without_estimates_one_row_of_three_panels(tables):
    features, truth, _ = tables
    fig = plot_estimates_vs_truth(features, truth)
    assert len(fig.axes) == 3
    plt.close(fig)


def test_the_second_row_shows_both_estimates_their_errors_and_the_window(tables):
    features, truth, est = tables
    fig = plot_estimates_vs_truth(features, truth, est, label="crossing")
    assert len(fig.axes) == 6
    _, errors, hist = fig.axes[3:]
    old, new = (c.get_offsets() for c in errors.collections[:2])
    # valid trials only (the invalid one left out), error = estimate - truth, per trial
    np.testing.assert_allclose(old[:, 0], [0.45, 0.6, 0.25])
    np.testing.assert_allclose(old[:, 1], [0.05, 0.3, 0.1])
    np.testing.assert_allclose(new[:, 1], [0.02, 0.12, 0.04])
    bounds = sorted(ln.get_xdata()[0] for ln in errors.get_lines() if ln.get_linestyle() == ":")
    assert bounds == [0.3, 0.7]
    labels = [t.get_text() for t in hist.get_legend().get_texts()]
    rmse_new = np.sqrt(np.mean(np.square([0.02, 0.12, 0.04])))
    assert labels[1].startswith("crossing") and f"RMSE {rmse_new:.3f} m/s" in labels[1]
    plt.close(fig)


def test_no_window_draws_no_bounds(tables):
    features, truth, est = tables
    fig = plot_estimates_vs_truth(features, truth, est, window=None)
    assert not [ln for ln in fig.axes[4].get_lines() if ln.get_linestyle() == ":"]
    plt.close(fig)
