"""SPARC's measurement uncertainty (skilllib/features/_uncertainty.py): the sub-sample shift spread, the
exact phase spread, the share of variance, the speed estimators, two clusterings compared.

Movements are minimum-jerk drops (Flash & Hogan 1985) sampled at 60 Hz: one that ends at rest before the
contact flag (its whole bell is in the segment) and ones cut at contact while still fast (the contact
ratio is high), whose end depends on where the sampling grid falls.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import skilllib as sk

FS = 60.0
REST = 0.4  # s before onset
DUR = 0.6  # s, minimum-jerk duration
DROP = 0.15  # m


def _mj(s):
    s = np.clip(s, 0.0, 1.0)
    return s**3 * (10 - 15 * s + 6 * s**2)


def _trial(t: np.ndarray, t_contact: float, scale: float = 1.0) -> pd.DataFrame:
    y = -scale * DROP * _mj((t - REST) / DUR)
    x = 0.2 * y  # a tilt: 3-D, not one axis
    return pd.DataFrame({"t": t, "x": x, "y": y, "z": 0.0 * t, "contact": (t >= t_contact).astype(int)})


def _frame(trials: dict[str, tuple[float, float]], scale: float = 1.0, n: int = 80) -> pd.DataFrame:
    """trial id -> (contact time s, phase); one participant."""
    parts = []
    for tr, (tc, phase) in trials.items():
        t = (np.arange(n) + phase) / FS
        parts.append(_trial(t, tc, scale).assign(participant="1", trial=tr))
    return pd.concat(parts, ignore_index=True)[list(sk.COLUMNS)]


# contact after the movement has ended (the bell whole) against contact at 70 % of its duration (fast)
WHOLE = {f"w{i}": (REST + DUR + 0.1, ph) for i, ph in enumerate((0.0, 0.3, 0.6, 0.9))}
CUT = {f"c{i}": (REST + 0.7 * DUR, ph) for i, ph in enumerate((0.0, 0.3, 0.6, 0.9))}


def _features(frame: pd.DataFrame, **kw):
    rec = sk.load_recordings(frame)
    return rec, sk.trial_features(rec, window=None, lowpass="none", **kw)


def test_a_whole_bell_spreads_far_less_than_a_movement_cut_while_fast():
    rec, f = _features(_frame({**WHOLE, **CUT}))
    s = sk.sparc_shift_spread(rec, f).set_index("trial")
    whole, cut = s.loc[list(WHOLE), "sparc_sd"], s.loc[list(CUT), "sparc_sd"]
    assert whole.max() < 0.2 * cut.median(), (whole, cut)
    assert cut.min() > 0.003  # a cut movement's SPARC moves with the grid
    assert list(s.columns[1:5]) == ["sparc_0", "sparc_0.25", "sparc_0.5", "sparc_0.75"]
    assert s.attrs["shifts"] == (0.0, 0.25, 0.5, 0.75)
    v = s[["sparc_0", "sparc_0.25", "sparc_0.5", "sparc_0.75"]].to_numpy()
    np.testing.assert_allclose(s["sparc_sd"], v.std(axis=1), rtol=1e-12)
    np.testing.assert_allclose(s["sparc_range"], v.max(axis=1) - v.min(axis=1), rtol=1e-12)


def test_shift_zero_is_the_recording_and_a_vanishing_shift_changes_nothing():
    rec, f = _features(_frame(CUT))
    s = sk.sparc_shift_spread(rec, f, shifts=(1e-9,))
    np.testing.assert_allclose(s["sparc_0"], f["sparc"], rtol=0, atol=1e-12)  # the table's SPARC
    assert s["sparc_sd"].max() < 1e-6


@pytest.mark.parametrize("shift", [0.25, 0.5, 0.75])
def test_a_shifted_approach_is_the_movement_sampled_at_t_plus_shift_over_fs(shift):
    """The spline's re-sampling against the movement truly sampled ``shift`` of an interval later, ending at
    the last shifted sample inside the recorded approach: the same SPARC to spline accuracy."""
    tc = REST + 0.7 * DUR
    rec, f = _features(_frame({"c": (tc, 0.0)}))
    got = sk.sparc_shift_spread(rec, f, shifts=(shift,))[f"sparc_{shift:g}"].iloc[0]
    t = (np.arange(80) + shift) / FS
    last = np.flatnonzero(t <= f["t_contact"].iloc[0] - 1 / FS + 1e-12)[-1]  # inside the recorded approach
    truth = _trial(t, t[last + 1]).assign(participant="1", trial="c")[list(sk.COLUMNS)]
    _, ft = _features(truth)
    assert abs(got - ft["sparc"].iloc[0]) < 2e-3, (got, ft["sparc"].iloc[0])
    assert abs(got - f["sparc"].iloc[0]) > 5 * abs(got - ft["sparc"].iloc[0])  # and not the unshifted value


@settings(max_examples=15, deadline=None)
@given(scale=st.floats(0.3, 4.0))
def test_the_spread_does_not_depend_on_the_movement_amplitude(scale):
    """SPARC ignores the amplitude; with an onset relative to the peak speed the segments do too."""
    start = sk.parse_start("speed:10%")
    rec1, f1 = _features(_frame(CUT), start=start)
    recs, fs_ = _features(_frame(CUT, scale=scale), start=start)
    a, b = sk.sparc_shift_spread(rec1, f1), sk.sparc_shift_spread(recs, fs_)
    np.testing.assert_allclose(a["sparc_sd"], b["sparc_sd"], rtol=1e-6, atol=1e-9)


def test_shifts_outside_one_interval_are_refused():
    rec, f = _features(_frame(CUT))
    for bad in [(0.0,), (1.0,), (-0.5,)]:
        with pytest.raises(ValueError, match="shifts"):
            sk.sparc_shift_spread(rec, f, shifts=bad)


def _table(values: np.ndarray, status: str = "selected") -> pd.DataFrame:
    n = len(values)
    return pd.DataFrame(
        {"participant": ["1"] * n, "trial": [str(i) for i in range(n)], "status": status, "sparc": values, "pv": 1.0}
    ).assign(t_contact=1.0)


def test_phase_spread_and_its_share_of_the_variance():
    rng = np.random.default_rng(3)
    base = rng.normal(-1.6, 0.1, 200)
    noise = [rng.normal(0, 0.03, 200) for _ in range(4)]
    tables = {ph: _table(base + e) for ph, e in zip((0.0, 0.25, 0.5, 0.75), noise)}
    s = sk.phase_spread(tables)
    v = np.column_stack([base + e for e in noise])
    np.testing.assert_allclose(s["sparc_sd"], v.std(axis=1), rtol=1e-12)
    share = sk.spread_share(s)
    np.testing.assert_allclose(share, v.var(axis=1).mean() / v.var(), rtol=1e-12)
    assert 0.05 < share < 0.1  # about 0.03^2 * 3/4 / (0.1^2 + 0.03^2)
    same = sk.phase_spread({ph: _table(base) for ph in (0.0, 0.5)})
    assert same["sparc_sd"].max() == 0 and sk.spread_share(same) == 0


def test_phase_spread_keeps_the_reference_selection_and_blanks_invalid_trials():
    ref = _table(np.array([-1.5, -1.6, -1.7]))
    ref.loc[2, "status"] = "excluded"
    other = _table(np.array([-1.55, -1.6, -1.7]))
    other.loc[1, "status"] = "invalid"
    s = sk.phase_spread({0.0: ref, 0.5: other})
    assert list(s["trial"]) == ["0", "1"]
    assert np.isnan(s.loc[1, "sparc_0.5"]) and s.loc[1, "sparc_sd"] == 0
    np.testing.assert_allclose(s.loc[0, "sparc_range"], 0.05)
    pv = sk.phase_spread({0.0: ref, 0.5: other}, column="pv")
    assert "pv_sd" in pv and pv.attrs["column"] == "pv"


def test_the_book_speed_and_central_differences():
    rec, f = _features(_frame({**WHOLE, **CUT}))
    e = sk.sparc_by_estimator(rec, f).set_index("trial")
    np.testing.assert_allclose(e["sparc"], f.set_index("trial")["sparc"], rtol=0, atol=1e-12)
    # interior samples agree at 60 Hz: a bell that ends at rest gives the same SPARC every way
    for col in ("sparc_gradient", "sparc_gradient_trial"):
        np.testing.assert_allclose(e.loc[list(WHOLE), col], e.loc[list(WHOLE), "sparc"], atol=1e-12)
    # cut while fast (and decelerating), the last sample's difference decides: the estimators part
    for col in ("sparc_gradient", "sparc_gradient_trial"):
        assert (e.loc[list(CUT), col] - e.loc[list(CUT), "sparc"]).abs().min() > 3e-5


def _fit(df: pd.DataFrame, k: int = 3):
    return sk.fit_prototypes(df, k)


def _points(seed: int = 0) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    centres = np.array([[0.5, -1.7], [0.9, -1.6], [1.3, -1.5]])
    x = np.vstack([c + rng.normal(0, [0.05, 0.02], (40, 2)) for c in centres])
    return sk.feature_frame(x[:, 0], x[:, 1], ["1"] * len(x), [str(i) for i in range(len(x))])


def test_cluster_agreement_of_a_fit_with_itself_and_with_a_perturbed_one():
    df = _points()
    a = sk.cluster_agreement(_fit(df), _fit(df.sample(frac=1, random_state=1)))  # rows shuffled
    assert a.ari == 1 and a.prototypes_kept == 3 and a.n_common == 120
    assert (a.clusters["prototype_distance"] == 0).all()
    moved = df.iloc[5:].copy()  # 5 trials fewer, the rest nudged
    moved["sparc"] += np.random.default_rng(2).normal(0, 0.004, len(moved))
    b = sk.cluster_agreement(_fit(df), _fit(moved))
    assert b.n_common == 115 and b.n_reference == 120 and b.n_other == 115
    assert 0.8 < b.ari <= 1
    assert list(b.clusters["matched"]) == [0, 1, 2]
    np.testing.assert_allclose(b.clusters["pv_ref"], b.clusters["pv_other"], atol=0.02)


def test_cluster_agreement_matches_centres_not_labels():
    df = _points()
    ref = _fit(df)
    flipped = df.assign(pv=-df["pv"])  # PV order reversed: cluster 0 is now the fastest
    other = _fit(flipped)
    other.centres["pv"] *= -1  # back to the reference's frame: the same clusters, numbered backwards
    a = sk.cluster_agreement(ref, other)
    assert list(a.clusters["matched"]) == [2, 1, 0] and a.ari == 1


def test_cluster_agreement_refuses_different_k():
    df = _points()
    with pytest.raises(ValueError, match="same k"):
        sk.cluster_agreement(_fit(df, 3), _fit(df, 4))
