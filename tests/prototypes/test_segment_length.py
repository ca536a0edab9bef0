"""skilllib.prototypes: partial correlation, explained variance, adjusted SPARC, SPARC by segment length."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.features import trial_features
from skilllib.prototypes import (
    LENGTH_EDGES,
    adjusted_sparc,
    partial_correlation,
    sparc_by_length,
    variance_explained,
    with_covariates,
)


def _frame(seed: int, n: int = 200) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    z = rng.normal(size=n)
    return pd.DataFrame(
        {"z": z, "x": 2 * z + rng.normal(size=n), "y": -z + rng.normal(size=n), "w": rng.normal(size=n)}
    )


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_partial_correlation_is_the_textbook_formula_for_one_covariate(seed):
    d = _frame(seed)
    r = d[["x", "y", "z"]].corr()
    expected = (r.x.y - r.x.z * r.y.z) / np.sqrt((1 - r.x.z**2) * (1 - r.y.z**2))
    assert partial_correlation(d, "x", "y", ["z"]) == pytest.approx(expected, abs=1e-10)
    assert partial_correlation(d, "x", "y", []) == pytest.approx(r.x.y, abs=1e-12)


def test_a_shared_cause_explains_a_correlation_away():
    d = _frame(0, 5000)
    assert partial_correlation(d, "x", "y", []) < -0.5  # both follow z
    assert abs(partial_correlation(d, "x", "y", ["z"])) < 0.05  # and nothing else


def test_variance_explained_alone_and_together():
    d = _frame(1, 500).assign(t=lambda f: 3 * f.z - 2 * f.w)
    r2 = variance_explained(d, "t", ["z", "w"])
    assert r2["all"] == pytest.approx(1.0)
    assert r2["z"] == pytest.approx(np.corrcoef(d.t, d.z)[0, 1] ** 2) and r2["z"] > r2["w"] > 0.2
    with pytest.raises(ValueError, match="constant"):
        variance_explained(d.assign(c=1.0), "c", ["z"])


def test_adjusted_sparc_keeps_the_mean_and_drops_the_covariates_linear_part():
    d = _frame(2, 300).assign(sparc=lambda f: -1.6 + 0.05 * f.z + 0.02 * f.w)
    a = adjusted_sparc(d, ["z"])
    assert a.mean() == pytest.approx(d.sparc.mean())
    assert abs(np.corrcoef(a, d.z)[0, 1]) < 1e-10
    np.testing.assert_allclose(
        a - a.mean(), 0.02 * (d.w - d.w.mean()) - 0.02 * np.polyfit(d.z, d.w, 1)[0] * (d.z - d.z.mean()), atol=1e-12
    )
    assert (a.index == d.index).all()


def test_with_covariates_and_sparc_by_length_on_generated_trials():
    f = trial_features(generate_cohort(5, CohortModel(n_participants=3, n_trials=20)).recordings)
    c = with_covariates(f)
    np.testing.assert_allclose(np.exp(c.log_duration), f.duration)
    np.testing.assert_allclose(c.contact_ratio, f.contact_speed / f.pv)
    assert (c.contact_ratio <= 1 + 1e-12).all()  # the contact speed is one of the segment's speeds
    t = sparc_by_length(f)
    valid = f[f.status != "invalid"]
    assert t["trials"].sum() == len(valid)
    n = valid.n.astype(float)
    first = valid[(n > LENGTH_EDGES[0]) & (n <= LENGTH_EDGES[1])]
    if len(first):
        assert t.iloc[0]["SPARC median"] == pytest.approx(first.sparc.median())
        assert t.iloc[0]["capped share"] == pytest.approx(first.sparc_capped.mean())


def test_missing_or_bad_columns_are_named():
    with pytest.raises(ValueError, match="lacks column"):
        partial_correlation(pd.DataFrame({"x": [1.0]}), "x", "y", [])
    with pytest.raises(ValueError, match="non-finite"):
        adjusted_sparc(pd.DataFrame({"sparc": [-1.5, np.nan], "log_duration": [0.1, 0.2]}))
