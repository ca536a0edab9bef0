"""skilllib.prototypes: clusters against the participants who made the trials, on hand-made labels."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from sklearn.metrics import normalized_mutual_info_score

from skilllib.prototypes import (
    between_participant_share,
    cluster_composition,
    cluster_participant_table,
    participant_dependence,
    participant_spread,
)

# participant A: 4 trials, all in cluster 0; B: 2 in cluster 0, 2 in cluster 1; C: 3 in cluster 1
PARTS = ["A"] * 4 + ["B"] * 4 + ["C"] * 3
LABELS = [0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1]


def test_table_counts_trials_per_cluster_and_participant():
    t = cluster_participant_table(LABELS, PARTS)
    assert t.loc[0, "A"] == 4 and t.loc[0, "B"] == 2 and t.loc[1, "B"] == 2 and t.loc[1, "C"] == 3
    assert t.loc[0, "C"] == 0 and t.loc[1, "A"] == 0
    assert t.loc["all", "all"] == 11 and t.loc[0, "all"] == 6 and t.loc["all", "C"] == 3


def test_composition_names_the_largest_participant_and_its_share():
    c = cluster_composition(LABELS, PARTS)
    assert c.loc[0].tolist() == [6, 2, "A", pytest.approx(4 / 6)]
    assert c.loc[1].tolist() == [5, 2, "C", pytest.approx(3 / 5)]


def test_spread_of_each_participant_over_the_clusters():
    s = participant_spread(LABELS, PARTS)
    assert s.loc["A", "clusters"] == 1 and s.loc["A", "main share"] == 1.0 and s.loc["A", "entropy"] == 0.0
    assert s.loc["B", "clusters"] == 2 and s.loc["B", "main share"] == 0.5
    assert s.loc["B", "entropy"] == pytest.approx(1.0)  # evenly over both of k = 2 clusters
    assert s.loc["C", "main cluster"] == 1 and s["trials"].sum() == 11


def test_clusters_that_are_the_participants_have_nmi_1_and_beat_every_permutation():
    parts = np.repeat(np.arange(5), 20)
    d = participant_dependence(parts + 10, parts, n_permutations=199, seed=1)
    assert d.nmi == pytest.approx(1.0)
    assert d.p_value == pytest.approx(1 / 200) and d.baseline_q95 < 0.2 and d.excess > 0.8


def test_clusters_independent_of_the_participants_have_nmi_0_and_a_large_p_value():
    parts = np.repeat(np.arange(4), 12)
    labels = np.tile(np.arange(3), 16)  # every participant has 4 trials in each cluster
    d = participant_dependence(labels, parts, n_permutations=199, seed=2)
    assert d.nmi == pytest.approx(0.0, abs=1e-12)
    assert d.p_value == 1.0 and d.baseline_mean > 0  # chance alone gives a positive NMI on 48 trials


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 10_000), n=st.integers(10, 60))
def test_nmi_is_sklearns_and_the_baseline_is_seeded(seed, n):
    rng = np.random.default_rng(seed)
    labels, parts = rng.integers(0, 3, n), rng.integers(0, 4, n)
    d = participant_dependence(labels, parts, n_permutations=30, seed=seed)
    assert d.nmi == pytest.approx(normalized_mutual_info_score(parts, labels))
    assert d == participant_dependence(labels, parts, n_permutations=30, seed=seed)
    assert 1 / 31 <= d.p_value <= 1


def test_between_participant_share():
    df = pd.DataFrame(
        {
            "participant": PARTS,
            "pv": [1.0] * 4 + [2.0] * 4 + [3.0] * 3,  # constant per person
            "sparc": [1.0, -1.0] * 5 + [0.0],
        }
    )  # every participant's mean is about 0
    share = between_participant_share(df, ["pv", "sparc"])
    assert share["pv"] == pytest.approx(1.0)
    x = df["sparc"]
    expected = ((x.groupby(df["participant"]).transform("mean") - x.mean()) ** 2).sum() / ((x - x.mean()) ** 2).sum()
    assert share["sparc"] == pytest.approx(expected) and share["sparc"] < 0.1


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="3 cluster labels but 2 participant ids"):
        cluster_participant_table([0, 1, 0], ["a", "b"])
    with pytest.raises(ValueError, match="no trials"):
        participant_dependence([], [])
    with pytest.raises(ValueError, match="participant column"):
        between_participant_share(pd.DataFrame({"pv": [1.0]}))
