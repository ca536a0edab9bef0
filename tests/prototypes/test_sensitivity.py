"""skilllib.prototypes: the clustering under several SPARC settings, checked against direct computation."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from sklearn.metrics import adjusted_rand_score

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.features import segment, select
from skilllib.prototypes import CHANGE_TOL, complete_params, setting_label, sparc_sensitivity
from skilllib.prototypes import _kmeans as pt
from skilllib.recordings import recordings_from_frame
from skilllib.smoothness import SPARC_PARAMS, sparc_spectrum

SETTINGS = ({"fc": 20.0}, {"fc": 10.0}, {"fc": 20.0, "amp_th": 0.1, "padlevel": 3})
K = 4


@pytest.fixture(scope="module")
def rec():
    return recordings_from_frame(generate_cohort(3, CohortModel(n_participants=4, n_trials=40)).frame)


@pytest.fixture(scope="module")
def sens(rec):
    return sparc_sensitivity(rec, SETTINGS, k=K)


def test_each_setting_measures_every_selected_trial_with_its_own_parameters(rec, sens):
    assert [r.params for r in sens.runs] == [complete_params(s) for s in SETTINGS]
    for run in sens.runs:
        sel = run.selected
        assert len(sel) > 20
        for p, tr, value, end, capped in sel[
            ["participant", "trial", "sparc", "sparc_band_end_hz", "sparc_capped"]
        ].itertuples(index=False):
            s = sparc_spectrum(segment(rec, p, tr).speed, rec.fs, **run.params)
            assert value == pytest.approx(s.sparc, abs=1e-9)
            assert end == pytest.approx(s.cutoff, abs=1e-9) and bool(capped) == s.capped
        assert run.n_capped == sum(
            sparc_spectrum(segment(rec, p, tr).speed, rec.fs, **run.params).capped
            for p, tr in sel[["participant", "trial"]].itertuples(index=False)
        )


def test_comparison_counts_changes_refits_and_shared_prototypes_as_computed_directly(sens):
    comp = sens.comparison()
    ref = sens.reference
    ref_fit = pt.fit_prototypes(ref.selected, K)
    assert list(comp.index) == [r.label for r in sens.runs[1:]]
    for run in sens.runs[1:]:
        d = run.selected["sparc"].to_numpy() - ref.selected["sparc"].to_numpy()
        c = comp.loc[run.label]
        assert c["changed"] == np.sum(np.abs(d) > CHANGE_TOL) and c["of"] == len(d)
        assert c["mean |change|"] == pytest.approx(np.abs(d).mean()) and c["max |change|"] == pytest.approx(
            np.abs(d).max()
        )
        fit = pt.fit_prototypes(run.selected, K)
        assert c["ARI"] == pytest.approx(adjusted_rand_score(ref_fit.labels, fit.labels))
        ids = lambda f: set(f.prototypes[["participant", "trial"]].itertuples(index=False, name=None))  # noqa: E731
        assert c["prototypes kept"] == len(ids(fit) & ids(ref_fit))
    # fc 10 Hz caps more of these short bands than 20 Hz, and changes SPARC of most selected trials
    assert sens.runs[1].n_capped > sens.reference.n_capped
    assert comp.loc[sens.runs[1].label, "changed"] > 0.5 * len(ref.selected)


def test_summary_and_silhouettes_are_the_runs_own(sens):
    summ, sil = sens.summary(), sens.silhouettes()
    for run in sens.runs:
        s = run.selected
        row = summ.loc[run.label]
        assert row["capped"] == run.n_capped and row["capped share"] == pytest.approx(run.n_capped / len(s))
        assert row["SPARC SD"] == pytest.approx(s["sparc"].std())
        assert row["corr(SPARC, duration)"] == pytest.approx(np.corrcoef(s["sparc"], s["duration"])[0, 1])
        assert row[f"silhouette, k = {K}"] == pytest.approx(pt.fit_prototypes(s, K).silhouette)
        assert sil[run.label].to_dict() == pytest.approx(dict(zip(run.sweep.ks, run.sweep.scores)))


def test_the_same_setting_twice_changes_nothing(rec):
    same = sparc_sensitivity(rec, [{"fc": 10.0}, {"fc": 10.0}], k=3, k_range=(2, 4))
    c = same.comparison().iloc[0]
    assert c["changed"] == 0 and c["ARI"] == 1.0 and c["prototypes kept"] == 3
    assert all(same.prototypes()["kept"])


def test_to_dict_is_json_ready_and_matches_the_tables(sens):
    import json

    d = json.loads(json.dumps(sens.to_dict(), allow_nan=False))
    assert d["k"] == K and len(d["settings"]) == len(SETTINGS)
    assert "vs_reference" not in d["settings"][0]
    comp = sens.comparison()
    for entry, run in zip(d["settings"][1:], sens.runs[1:]):
        assert entry["params"] == run.params and entry["n_capped"] == run.n_capped
        assert entry["vs_reference"]["n_sparc_changed"] == comp.loc[run.label, "changed"]
        assert entry["vs_reference"]["ari"] == pytest.approx(comp.loc[run.label, "ARI"])
        kept = [(p["participant"], p["trial"]) for p in entry["prototypes"] if p["kept"]]
        assert len(kept) == entry["vs_reference"]["prototypes_kept"]
        assert [p["cluster"] for p in entry["prototypes"]] == list(range(K))


def test_settings_are_completed_and_checked():
    assert complete_params({"fc": 10}) == {**SPARC_PARAMS, "fc": 10.0}
    assert complete_params({"padlevel": 3.0})["padlevel"] == 3 and isinstance(
        complete_params({"padlevel": 3.0})["padlevel"], int
    )
    with pytest.raises(ValueError, match="unknown SPARC parameter"):
        complete_params({"cutoff": 10})
    with pytest.raises(ValueError, match="no SPARC settings"):
        sparc_sensitivity(pd.DataFrame(), [])
    assert setting_label(complete_params({"fc": 10.0})) == "fc 10 Hz, amp_th 0.05, padlevel 4"


def test_too_few_selected_trials_give_runs_without_fits(rec):
    few = recordings_from_frame(generate_cohort(3, CohortModel(n_participants=1, n_trials=3)).frame)
    s = sparc_sensitivity(few, [{"fc": 20.0}, {"fc": 10.0}])
    assert len(select(s.reference.features)) < 3
    assert all(r.fit is None for r in s.runs)
    assert s.comparison()["prototypes kept"].eq(0).all() and s.prototypes().empty


def test_a_given_reference_is_used_not_recomputed(rec, sens, monkeypatch):
    from skilllib.prototypes import _sensitivity as sensitivity_module

    calls = []
    real = sensitivity_module.trial_features
    monkeypatch.setattr(sensitivity_module, "trial_features", lambda *a, **kw: calls.append(kw) or real(*a, **kw))
    ref = sens.reference
    again = sparc_sensitivity(rec, SETTINGS[:2], k=K, reference=(ref.features, ref.sweep))
    assert len(calls) == 1 and calls[0]["sparc_params"]["fc"] == 10.0  # only the other setting is computed
    assert again.reference.features is ref.features and again.reference.sweep is ref.sweep
    pd.testing.assert_frame_equal(again.comparison(), sens.comparison().iloc[:1])
