"""Selection windows on the per-trial features (issue 24): parsing, every window must hold, the first
failing window's reason, invalid trials untouched, a feature that is not a number never selected."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from skilllib.features import (
    PAPER_SELECTION,
    SelectionError,
    Window,
    apply_selection,
    parse_features,
    parse_selection,
    parse_window,
)


def table(pv, cs, status=None) -> pd.DataFrame:
    n = len(pv)
    return pd.DataFrame(
        {
            "participant": ["1"] * n,
            "trial": [str(i) for i in range(n)],
            "status": status or ["excluded"] * n,
            "reason": [""] * n,
            "pv": pv,
            "contact_speed": cs,
        }
    )


def test_the_papers_window_gives_the_papers_reasons():
    f = apply_selection(table([1.0, 1.0, 1.0, 1.0], [0.3, 0.7, 0.2999, 0.812]), PAPER_SELECTION)
    assert f["status"].tolist() == ["selected", "selected", "excluded", "excluded"]  # inclusive bounds
    assert f["reason"].tolist()[2:] == [
        "contact speed 0.300 m/s below 0.3 m/s",
        "contact speed 0.812 m/s above 0.7 m/s",
    ]


def test_every_window_holds_and_the_first_failing_one_is_the_reason():
    w = parse_selection(["contact_speed=0.3:0.7", "pv=0.9:"])
    f = apply_selection(table([1.0, 0.5, 0.5], [0.5, 0.5, 0.9]), w)
    assert f["status"].tolist() == ["selected", "excluded", "excluded"]
    assert f["reason"].tolist() == [
        "",
        "peak speed PV 0.500 m/s below 0.9 m/s",
        "contact speed 0.900 m/s above 0.7 m/s",
    ]


def test_invalid_trials_keep_their_reason_and_nan_is_never_selected():
    f = table([1.0, np.nan, np.nan], [0.5, 0.5, np.nan], status=["selected", "selected", "invalid"])
    f.loc[2, "reason"] = "no contact: the contact flag is never 1"
    got = apply_selection(f, (Window("pv", 0.1, None),))
    assert got["status"].tolist() == ["selected", "excluded", "invalid"]
    assert got["reason"].tolist()[1:] == [
        "peak speed PV not computed for this trial: outside the window pv=0.1:",
        "no contact: the contact flag is never 1",
    ]
    assert apply_selection(f, ())["status"].tolist() == ["selected", "selected", "invalid"]  # none: all valid


@pytest.mark.parametrize(
    "text, message",
    [
        ("pv", "write a window as FEATURE=LO:HI"),
        ("pv=1", "write a window as FEATURE=LO:HI"),
        ("pv=:", "give at least one bound"),
        ("pv=0.5:0.2", "the lower bound 0.5 is above the upper bound 0.2"),
        ("pv=a:1", "'a' is not a number"),
        ("speed=0:1", "unknown feature 'speed'"),
    ],
)
def test_bad_windows_say_what_is_wrong(text, message):
    with pytest.raises(SelectionError, match=message):
        parse_window(text)


def test_aliases_and_feature_lists():
    assert parse_window("end_speed=0.3:0.7") == PAPER_SELECTION[0]
    assert parse_features("pv, sparc,peak_acceleration") == ("pv", "sparc", "peak_acc")
    with pytest.raises(SelectionError, match="named twice"):
        parse_features("pv,peak_speed")


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(0, 2), min_size=1, max_size=20),
    st.floats(0, 2),
    st.floats(0, 2),
)
def test_a_window_selects_exactly_the_trials_inside_it(values, a, b):
    lo, hi = min(a, b), max(a, b)
    got = apply_selection(table(values, values), (Window("pv", lo, hi),))
    inside = [lo <= v <= hi for v in values]
    assert (got["status"] == "selected").tolist() == inside
    assert parse_window(Window("pv", lo, hi).text()) == Window("pv", float(f"{lo:g}"), float(f"{hi:g}"))


def test_trial_features_without_a_window_selects_every_valid_trial():
    from skilllib.datasets import cohort_path
    from skilllib.features import trial_features
    from skilllib.recordings import load_recordings

    rec = load_recordings(cohort_path())
    paper, none = trial_features(rec), trial_features(rec, window=None)
    valid = paper["status"] != "invalid"
    assert (none.loc[valid, "status"] == "selected").all()
    pd.testing.assert_frame_equal(none[~valid], paper[~valid])  # invalid trials as they were
    assert (paper["status"] == "excluded").sum() > 0  # the paper's window excludes some: None changes them
    pd.testing.assert_frame_equal(apply_selection(none, PAPER_SELECTION), paper)
