"""Figures of SPARC's measurement uncertainty (skilllib/figures/measurement.py), on small seeded tables."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pandas as pd
import pytest

import skilllib as sk
import skilllib.figures as skf

PHASES = (0.0, 0.25, 0.5, 0.75)


def _tables(n: int = 120, seed: int = 0) -> dict[float, pd.DataFrame]:
    rng = np.random.default_rng(seed)
    pv = rng.uniform(0.4, 1.4, n)
    base = -1.8 + 0.2 * pv + rng.normal(0, 0.04, n)
    out = {}
    for ph in PHASES:
        out[ph] = pd.DataFrame(
            {
                "participant": "1",
                "trial": [str(i) for i in range(n)],
                "status": "selected",
                "pv": pv + rng.normal(0, 0.002, n),
                "sparc": base + rng.normal(0, 0.01 + 0.02 * (pv > 1), n),
                "t_contact": 1.0,
            }
        )
    return out


@pytest.fixture(scope="module")
def tables():
    return _tables()


@pytest.fixture(scope="module")
def fits(tables):
    return {ph: sk.fit_prototypes(sk.select(t), 3) for ph, t in tables.items()}


def test_phase_spread_figure_draws_every_later_phase_and_every_centre_gap(tables, fits):
    spread = sk.phase_spread(tables)
    fig = skf.plot_phase_spread(spread, fits[0.0].centres)
    ax, bx = fig.axes
    assert len(ax.collections) == len(PHASES) - 1  # one scatter per later phase
    assert [len(c.get_offsets()) for c in ax.collections] == [len(spread)] * 3
    gaps = np.abs(np.diff(fits[0.0].centres.sort_values("pv")["sparc"]))
    drawn = sorted(line.get_xdata()[0] for line in bx.lines if line.get_linestyle() == "-")
    np.testing.assert_allclose(drawn, np.sort(gaps))  # k - 1 gaps, at their values
    assert "SPARC" in ax.get_xlabel() and bx.get_ylabel() == "trials"
    assert sum(p.get_height() for p in bx.patches) == len(spread)  # every trial in the histogram
    skf.plt.close(fig)


def test_spread_estimate_figure_pairs_the_same_trials(tables):
    exact = sk.phase_spread(tables)
    est = exact.assign(sparc_sd=exact["sparc_sd"] * 2).iloc[::-1]  # another order: paired by id
    fig = skf.plot_spread_estimate(exact, est)
    ax = fig.axes[0]
    xy = ax.collections[0].get_offsets()
    assert len(xy) == len(exact)
    np.testing.assert_allclose(np.asarray(xy)[:, 1], np.maximum(2 * np.asarray(xy)[:, 0], 1e-4), rtol=1e-9)
    assert ax.get_xscale() == ax.get_yscale() == "log"
    skf.plt.close(fig)


def test_estimator_figure_states_the_correlation_it_draws():
    rng = np.random.default_rng(1)
    a = rng.normal(-1.6, 0.1, 200)
    table = pd.DataFrame({"sparc": a, "sparc_gradient": a + rng.normal(0, 0.02, 200), "sparc_gradient_trial": a})
    fig = skf.plot_estimator_spread(table)
    r = np.corrcoef(table["sparc"], table["sparc_gradient"])[0, 1]
    assert f"r = {r:.3f}" in fig.axes[0].get_title()
    assert "r = 1.000" in fig.axes[1].get_title() and "difference 0.000" in fig.axes[1].get_title()
    skf.plt.close(fig)


def test_phase_clusters_figure_marks_every_fit(fits):
    fig = skf.plot_phase_clusters(fits)
    ax = fig.axes[0]
    k = fits[0.0].k
    # the reference's trials by cluster, then centres and prototypes of every phase
    assert len(ax.collections) == k + 2 * len(fits)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels.count("centres, phase 0.5") == 1 and len(labels) == 2 * len(fits)
    skf.plt.close(fig)
