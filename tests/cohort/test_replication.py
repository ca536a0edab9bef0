"""Tests of skilllib.cohort._replication: the book's headline results on many draws of the model.

The committed table's row of the book's seed is recomputed from scratch and compared with the file, and
then with the book's numbers computed independently from the committed cohort file by the functions the
chapters call (or by plain scikit-learn / numpy where the replication calls a library function). The
summary and the paper-vs-draws helper are tested on small hand-made tables whose medians, ranks and
ranges are known.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from sklearn.metrics import adjusted_rand_score, normalized_mutual_info_score

from skilllib.cohort import _replication as rep
from skilllib.cohort._calibration import SURVEY_CSV
from skilllib.cohort._model import SEED, generate_cohort
from skilllib.datasets import cohort_path
from skilllib.features import segment, select, trial_features
from skilllib.prototypes import fit_prototypes, silhouette_sweep
from skilllib.recordings import read_recordings
from skilllib.robot import ROBOT_NAMES, get_robot, joint_dynamics, transfer

TOL = 1e-9


@pytest.fixture(scope="module")
def committed():
    return rep.read_replication()


@pytest.fixture(scope="module")
def fresh():
    """The book's row, recomputed from scratch (generator, CSV rounding, features, ...)."""
    return rep.draw_results(SEED)


@pytest.fixture(scope="module")
def book():
    """The committed cohort file's features, selection and k = 6 fit, as chapters 3 and 4 compute them."""
    rec = read_recordings(cohort_path())
    feats = trial_features(rec)
    sel = select(feats)
    return rec, feats, sel, fit_prototypes(sel, 6)


def test_committed_table_covers_seeds_0_to_23_with_every_quantity(committed):
    assert list(committed.index) == list(range(24))
    assert list(committed.columns) == list(rep.DRAW_QUANTITIES)
    assert committed.notna().all().all()


def test_committed_table_agrees_with_the_seed_survey(committed):
    """Two committed tables from two code paths: the survey's seeds 0..9 must give the same counts,
    silhouettes and verdict on the targets (seed 9 the only one meeting all)."""
    survey = pd.read_csv(SURVEY_CSV, index_col="seed")
    both = committed.loc[survey.index]
    assert both["n_selected"].tolist() == survey["selected"].tolist()
    assert both["n_valid_k"].tolist() == survey["valid_k"].tolist()
    assert both["silhouette_k6"].round(3).tolist() == survey["silhouette_k6"].tolist()
    assert both["all_targets"].tolist() == survey["all"].tolist()


@pytest.mark.slow
def test_book_row_recomputed_from_scratch_equals_the_file(committed, fresh):
    row = committed.loc[SEED]
    assert fresh["seed"] == SEED
    for col in rep.DRAW_QUANTITIES:
        a, b = row[col], fresh[col]
        if isinstance(b, bool | int):
            assert a == b, col
        else:
            assert b == pytest.approx(float(a), rel=TOL, abs=TOL), col


@pytest.mark.slow
def test_book_row_equals_the_book_computed_independently(fresh, book):
    rec, feats, sel, fit = book
    assert fresh["n_selected"] == len(sel)
    sweep = silhouette_sweep(sel, 2, 16, scaling="raw")
    assert fresh["n_valid_k"] == len(sweep.valid_ks())
    assert fresh["silhouette_k6"] == pytest.approx(fit.silhouette, abs=TOL)
    order = np.argsort(fit.centres["pv"].to_numpy())
    assert [fresh[f"centre_pv_{i}"] for i in range(1, 7)] == pytest.approx(fit.centres["pv"].to_numpy()[order])
    assert [fresh[f"centre_sparc_{i}"] for i in range(1, 7)] == pytest.approx(fit.centres["sparc"].to_numpy()[order])
    # chapter 6's comparison: K-means k = 6 on the selected trials' features at fc 10 Hz
    sel10 = select(trial_features(rec, sparc_params={"fc": 10.0}))
    fit10 = fit_prototypes(sel10, 6)
    assert fresh["ari_fc10"] == pytest.approx(adjusted_rand_score(fit.labels, fit10.labels), abs=TOL)
    assert fresh["capped_fraction"] == pytest.approx(sel["sparc_capped"].sum() / len(sel), abs=TOL)
    assert fresh["nmi_participants"] == pytest.approx(normalized_mutual_info_score(sel["participant"], fit.labels))
    # R^2 of a one-predictor least-squares line is the squared correlation
    truth = generate_cohort(SEED).truth[["participant", "trial", "n_corrections"]]
    d = sel.merge(truth, on=["participant", "trial"])
    ratio = d["contact_speed"] / d["pv"]
    assert fresh["r2_contact_ratio"] == pytest.approx(np.corrcoef(ratio, d["sparc"])[0, 1] ** 2, abs=TOL)
    corrected = (d["n_corrections"] > 0).astype(float)
    assert fresh["r2_corrections"] == pytest.approx(np.corrcoef(corrected, d["sparc"])[0, 1] ** 2, abs=TOL)
    # chapters 5 and 9: each prototype's transfer and joint dynamics with the arm's own limits
    segs = [segment(rec, p.participant, p.trial) for p in fit.prototypes.itertuples()]
    for name in ROBOT_NAMES:
        arm = get_robot(name)
        results = [transfer(arm, s, cluster=c) for c, s in enumerate(segs)]
        dyn = [joint_dynamics(arm.robot, r, arm.qdd_limits, arm.tau_limits) for r in results]
        assert fresh[f"feasible_velocity_{name}"] == sum(r.feasible for r in results), name
        assert fresh[f"feasible_{name}"] == sum(d.feasible for d in dyn), name


def test_feasible_under_every_limit_never_exceeds_the_velocity_only_count(committed):
    for name in ROBOT_NAMES:
        assert (committed[f"feasible_{name}"] <= committed[f"feasible_velocity_{name}"]).all(), name
        assert committed[f"feasible_velocity_{name}"].between(0, 6).all(), name


# ------------------------------------------------------------------------------ the summary --


@pytest.fixture
def small():
    """Five draws: ``up`` rises with the seed order, ``down`` falls, ``flat`` is equal, ``tie`` ties the book."""
    return pd.DataFrame(
        {
            "up": [5.0, 1.0, 3.0, 2.0, 4.0],
            "down": [10.0, 50.0, 30.0, 40.0, 20.0],
            "flat": [6, 6, 6, 6, 6],
            "tie": [1, 2, 2, 3, 0],
            "ok": [True, False, True, True, True],
        },
        index=pd.Index([10, 11, 12, 13, 14], name="seed"),
    )


def test_summary_median_range_percentiles_and_rank(small):
    s = rep.replication_summary(small, seed=12)
    assert list(s.index) == ["up", "down", "flat", "tie"]  # the boolean column is left out
    up, down = s.loc["up"], s.loc["down"]
    assert (up["median"], up["min"], up["max"], up["book"], up["rank"], up["draws"]) == (3, 1, 5, 3, 3, 5)
    assert up["p10"] == pytest.approx(1.4) and up["p90"] == pytest.approx(4.6)
    assert (down["min"], down["max"]) == (10, 50)
    assert down["rank"] == 3  # 30 among 10..50
    assert rep.replication_summary(small, seed=11).loc["up", "rank"] == 1  # the lowest value ranks 1
    assert rep.replication_summary(small, seed=11).loc["down", "rank"] == 5
    assert s.loc["flat", "rank"] == 3 and s.loc["flat", "sd"] == 0  # all tied: the mean rank (1 + 5) / 2
    assert s.loc["tie", "rank"] == 3.5  # tied with seed 11 on ranks 3 and 4
    assert up["sd"] == pytest.approx(np.std([1, 2, 3, 4, 5], ddof=1))


def test_summary_refuses_a_seed_that_is_not_a_draw(small):
    with pytest.raises(ValueError, match="seed 9"):
        rep.replication_summary(small, seed=9)
    with pytest.raises(ValueError, match="nope"):
        rep.replication_summary(small, seed=12, columns=["nope"])


def test_within_draws_says_inside_on_the_bounds_and_outside_beyond(small):
    w = rep.within_draws(small, {"up": 5.0, "down": 9.0, "flat": 6.0}, seed=12)
    assert w.loc["up", "within"] and not w.loc["down", "within"]
    assert w.loc["flat", "within"] and np.isnan(w.loc["flat", "sds"])  # no spread: no SDs
    assert w.loc["up", "sds"] == pytest.approx((5.0 - 3.0) / np.std([1, 2, 3, 4, 5], ddof=1))
    assert w.loc["down", "sds"] < 0  # below the draws
    assert (w.loc["up", "book"], w.loc["up", "median"], w.loc["up", "paper"]) == (3, 3, 5)
    assert not rep.within_draws(small, {"up": 0.99}, seed=12).loc["up", "within"]


@pytest.mark.slow
def test_book_row_contact_errors_equal_a_direct_computation(fresh, book):
    """The last sample's errors against the truth, computed here with numpy alone: a swapped estimate
    and truth flips the bias's sign; a window test on the wrong column changes the counts."""
    rec, feats, sel, fit = book
    truth = generate_cohort(SEED).truth[["participant", "trial", "contact_speed"]]
    m = feats.merge(truth, on=["participant", "trial"], suffixes=("", "_true"))
    err = m["contact_speed"] - m["contact_speed_true"]
    assert fresh["contact_sample_bias"] == pytest.approx(err.mean(), abs=TOL)
    assert fresh["contact_sample_max"] == pytest.approx(err.abs().max(), abs=TOL)
    inside = m["contact_speed"].between(0.3, 0.7)
    inside_true = m["contact_speed_true"].between(0.3, 0.7)
    assert fresh["contact_sample_flips"] == (inside != inside_true).sum()
    assert fresh["in_window_sample"] == len(sel) == inside.sum()
    assert fresh["in_window_true"] == inside_true.sum()
    # the new estimates are estimates: their errors are finite and they select other trials
    for method in ("midpoint", "crossing"):
        assert 0 < fresh[f"contact_{method}_rmse"] < 1
        assert fresh[f"in_window_{method}"] != fresh["in_window_sample"]
