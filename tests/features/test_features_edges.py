"""Edge cases of skilllib.features that tests/test_features.py leaves open: the noise floor at rest
(rest_speed), the tables status_counts and participant_summary (their columns, zero counts, medians and
IQRs against numpy), and small details of segmentation and trial_features.

The tables are checked on hand-made feature tables (their values are then known), rest_speed and the
segmentation on a few synthetic minimum-jerk approaches.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from skilllib.features import (
    CONTACT_WINDOW,
    ONSET_SPEED,
    Lowpass,
    participant_summary,
    rest_speed,
    status_counts,
    trial_features,
)
from skilllib.features import _table as features
from skilllib.recordings import recordings_from_frame

FS = 60.0
STATUSES = ["selected", "excluded", "invalid"]
SUMMARY_FEATURES = {
    "pv": "PV (m/s)",
    "contact_speed": "contact speed (m/s)",
    "duration": "duration (s)",
    "sparc": "SPARC",
}
NOISE_SD = 0.03e-3  #: m, the Phantom's position resolution (module docstring of skilllib.features)


def approach(amp=0.15, dur=0.5, surface=0.12, rest=0.6, after=0.3, fs=FS, seed=None):
    """Rest, a minimum-jerk drop of ``amp`` m in ``dur`` s cut by a surface ``surface`` m below the start,
    sampled at ``fs``; with ``seed``, white position noise of NOISE_SD. Returns t, pos (N, 3), contact."""
    t = np.arange(int((rest + dur + after) * fs)) / fs
    tau = np.clip((t - rest) / dur, 0, 1)
    drop = amp * tau**3 * (10 - 15 * tau + 6 * tau**2)
    contact = np.cumsum(drop >= surface) > 0
    pos = np.column_stack([np.full_like(t, 0.01), 0.2 - np.minimum(drop, surface), np.full_like(t, -0.03)])
    if seed is not None:
        pos = pos + np.random.default_rng(seed).normal(0, NOISE_SD, pos.shape)
    return t, pos, contact


def frame_of(trials: dict) -> pd.DataFrame:
    """Long table from {(participant, trial): (t, pos, contact)}."""
    return pd.concat(
        [
            pd.DataFrame(
                {
                    "participant": p,
                    "trial": tr,
                    "t": t,
                    "x": pos[:, 0],
                    "y": pos[:, 1],
                    "z": pos[:, 2],
                    "contact": c.astype(int),
                }
            )
            for (p, tr), (t, pos, c) in trials.items()
        ],
        ignore_index=True,
    )


def central_speeds(pos: np.ndarray, fs: float) -> np.ndarray:
    """|(p[i+1] - p[i-1]) * fs / 2| at the interior samples i = 1 .. N-2 (the definition)."""
    return np.linalg.norm((pos[2:] - pos[:-2]) * fs / 2, axis=1)


# --- rest_speed ----------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def noisy():
    """Two noisy valid trials of participant 1, a third that never touches (invalid), their features."""
    trials = {
        ("1", "1"): approach(seed=1),
        ("1", "2"): approach(amp=0.2, rest=0.8, seed=2),
        ("1", "3"): approach(amp=0.10, surface=0.2, seed=3),
    }
    rec = recordings_from_frame(frame_of(trials))
    return trials, rec, trial_features(rec)


def test_rest_speed_is_the_central_difference_speed_before_the_margin(noisy):
    """Per valid trial (in table order), the central-difference speeds at samples 1 .. o-2, where o is
    the first sample at or after t_onset - margin; the invalid trial adds nothing. Catches a margin
    added instead of subtracted, another slice of the interior, invalid trials taken instead of valid
    ones, a norm over the wrong axis."""
    trials, rec, f = noisy
    assert f.status.tolist()[:2] != ["invalid", "invalid"] and f.status[2] == "invalid"
    for margin in (0.2, 0.35):
        want = []
        for (_key, (t, pos, _)), row in zip(trials.items(), f.itertuples()):
            if row.status == "invalid":
                continue
            o = int(np.flatnonzero(t >= row.t_onset - margin)[0])
            want.append(central_speeds(pos[:o], FS))
        got = rest_speed(rec, f, margin=margin)
        np.testing.assert_allclose(got, np.concatenate(want), rtol=1e-9, atol=1e-12)
    # the default margin is 0.2 s
    np.testing.assert_array_equal(rest_speed(rec, f), rest_speed(rec, f, margin=0.2))


def test_rest_speed_is_the_noise_floor(noisy):
    """White position noise of SD s gives a per-axis speed SD of s * fs / sqrt(2) (module docstring):
    the 3-D speed's RMS is sqrt(3) times that. Accepts the recordings as a DataFrame too."""
    trials, rec, f = noisy
    got = rest_speed(recordings_from_frame(frame_of(trials)), f)
    rms = np.sqrt(np.mean(got**2))
    assert rms == pytest.approx(np.sqrt(3) * NOISE_SD * FS / np.sqrt(2), rel=0.25)
    assert got.max() < ONSET_SPEED


@pytest.mark.parametrize("o", [2, 3, 4])
def test_rest_speed_needs_three_samples_before_the_margin(noisy, o):
    """With t_onset - margin at sample o, o samples are differentiated and o - 2 interior speeds kept:
    none for o = 2 (an empty float array), one for o = 3. Catches ``o > 3`` / ``o >= 4`` for ``o >= 3``
    and an empty result that is not an empty array."""
    trials, rec, f = noisy
    t, pos, _ = trials[("1", "1")]
    one = f.iloc[:1].copy()
    one["t_onset"] = t[o]
    got = rest_speed(rec, one, margin=0.0)
    assert isinstance(got, np.ndarray) and got.shape == (o - 2,)
    np.testing.assert_allclose(got, central_speeds(pos[:o], FS), rtol=1e-9, atol=1e-12)


def test_rest_speed_without_valid_trials_is_empty(noisy):
    _, rec, f = noisy
    got = rest_speed(rec, f[f.status == "invalid"])
    assert isinstance(got, np.ndarray) and got.shape == (0,)


# --- status_counts --------------------------------------------------------------------------------------


def table(rows: list[tuple]) -> pd.DataFrame:
    """A features table from (participant, status, pv, contact_speed, duration, sparc) rows."""
    f = pd.DataFrame(rows, columns=["participant", "status", "pv", "contact_speed", "duration", "sparc"])
    f.insert(1, "trial", [str(i) for i in range(len(f))])
    return f


def test_status_counts_has_every_status_column_even_when_none_occurs():
    """Columns selected, excluded, invalid, total in that order, with integer zeros for a status no trial
    has (here: no invalid trial). Catches columns left to the crosstab and a missing fill value (NaN)."""
    f = table(
        [
            ("2", "selected", 1, 0.5, 0.4, -1.5),
            ("2", "excluded", 1, 0.8, 0.3, -1.6),
            ("10", "selected", 1, 0.4, 0.5, -1.4),
        ]
    )
    t = status_counts(f)
    assert t.columns.tolist() == [*STATUSES, "total"]
    assert t.index.tolist() == ["2", "10", "all"]
    assert t["invalid"].tolist() == [0, 0, 0]
    assert all(pd.api.types.is_integer_dtype(t[c]) for c in t.columns)
    assert t.loc["2"].tolist() == [1, 1, 0, 2] and t.loc["all"].tolist() == [2, 1, 0, 3]


def test_status_counts_counts_invalid_trials():
    """Catches a misspelt 'invalid' column (its counts lost as zeros)."""
    f = table(
        [
            ("1", "invalid", np.nan, np.nan, np.nan, np.nan),
            ("1", "invalid", np.nan, np.nan, np.nan, np.nan),
            ("1", "selected", 1, 0.5, 0.4, -1.5),
            ("3", "invalid", np.nan, np.nan, np.nan, np.nan),
        ]
    )
    t = status_counts(f)
    assert t.loc["1"].tolist() == [1, 0, 2, 3] and t.loc["3"].tolist() == [0, 0, 1, 1]
    assert t.loc["all"].tolist() == [1, 0, 3, 4]


# --- participant_summary --------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def summary_table() -> pd.DataFrame:
    """Participant 'P2' with 5 valid trials and 2 invalid ones (NaN features), 'P10' with 3 valid ones;
    the features are distinct random numbers, so medians and IQRs of wrong subsets differ."""
    rng = np.random.default_rng(7)
    rows = []
    for p, statuses in (
        ("P10", ["selected", "excluded", "selected"]),
        ("P2", ["invalid", "selected", "excluded", "excluded", "invalid", "selected", "selected"]),
    ):
        for s in statuses:
            vals = [np.nan] * 4 if s == "invalid" else list(rng.uniform(0.1, 2.0, 4))
            rows.append((p, s, *vals))
    return table(rows)


def test_participant_summary_columns_are_named_for_the_reader(summary_table):
    """The table's headers, in order (shown in the book's chapter 3). Catches a changed name."""
    s = participant_summary(summary_table)
    want = ["valid trials", "selected"]
    for name in SUMMARY_FEATURES.values():
        want += [f"{name} median", f"{name} IQR"]
    assert s.columns.tolist() == want
    assert s.index.tolist() == ["P2", "P10"]


def test_participant_summary_counts_valid_trials_and_their_medians_and_iqrs(summary_table):
    """Over the valid trials only: their number, the selected ones, and per feature the median and the
    interquartile range (numpy's linear percentiles). Catches invalid trials counted, a median or IQR
    left out, and q75 + q25 for the IQR."""
    s = participant_summary(summary_table)
    for p, g in summary_table.groupby("participant"):
        valid = g[g.status != "invalid"]
        assert s.loc[p, "valid trials"] == len(valid)
        assert s.loc[p, "selected"] == (g.status == "selected").sum()
        for col, name in SUMMARY_FEATURES.items():
            q25, q50, q75 = np.percentile(valid[col].to_numpy(), [25, 50, 75])
            assert s.loc[p, f"{name} median"] == pytest.approx(q50, rel=1e-12)
            assert s.loc[p, f"{name} IQR"] == pytest.approx(q75 - q25, rel=1e-12)
    assert s.loc["P2", "valid trials"] == 5  # two invalid trials left out


# --- trial_features details ----------------------------------------------------------------------------


def test_default_window_and_onset_are_the_constants():
    """trial_features(window=..., onset_speed=...) defaults equal the module constants."""
    df = frame_of({("1", "1"): approach(), ("1", "2"): approach(amp=0.30, dur=0.3)})
    a = trial_features(recordings_from_frame(df))
    b = trial_features(recordings_from_frame(df), window=CONTACT_WINDOW, onset_speed=ONSET_SPEED)
    pd.testing.assert_frame_equal(a, b)


# --- the low-pass filter in segmentation ----------------------------------------------------------------

CUTOFF_HZ = 6.0


def test_a_lowpass_filters_the_approach_before_differentiating():
    """With a cut-off, the approach's positions (samples before contact only) are filtered by the given
    filter and then differentiated: the segment's pos are the filtered positions, its speed their
    second-order difference. Catches the filter skipped (or applied only without a cut-off)."""
    t, pos, c = approach(seed=4)
    lp = Lowpass(CUTOFF_HZ, "given")
    ci = int(np.flatnonzero(c)[0])
    filtered = lp.apply(pos[:ci], FS)
    assert np.abs(filtered - pos[:ci]).max() > 1e-6  # the filter changes these positions
    speed = np.linalg.norm(np.gradient(filtered, 1 / FS, axis=0, edge_order=2), axis=1)
    o = int(np.flatnonzero(speed > ONSET_SPEED)[0])
    seg = features.segment_arrays(t, pos, c, FS, lowpass=lp)
    assert (seg.onset, seg.contact) == (o, ci)
    np.testing.assert_allclose(seg.pos, filtered[o:], rtol=0, atol=1e-12)
    np.testing.assert_allclose(seg.speed, speed[o:], rtol=1e-9, atol=1e-12)
    unfiltered = features.segment_arrays(t, pos, c, FS, lowpass=Lowpass(None, "none"))
    np.testing.assert_array_equal(unfiltered.pos, pos[unfiltered.onset : ci])


# --- segment and segment_arrays details -----------------------------------------------------------------


def test_no_rest_reason_gives_the_speed_at_the_first_sample():
    """A recording that starts in motion, accelerating (y = -(v0 t + a t^2 / 2), exact for the three-point
    difference): the reason names the first sample's speed v0, not the second's v0 + a / fs."""
    v0, a, n = 0.3, 6.0, 30
    t = np.arange(n) / FS
    pos = np.column_stack([np.zeros(n), -(v0 * t + a * t**2 / 2), np.zeros(n)])
    out = features.segment_arrays(t, pos, np.arange(n) >= 20, FS)
    assert out == (
        f"no rest before onset: speed {v0:.2f} m/s > {ONSET_SPEED:g} m/s at the first sample "
        f"(the movement started before the recording)"
    )


def test_segment_arrays_returns_float_arrays_and_the_given_ids():
    """Integer time stamps and positions (1 Hz, 1 m steps) give a segment of float arrays holding the
    samples from onset to contact, with the participant and trial given."""
    n, start, contact_at = 20, 5, 15
    t = np.arange(n)
    pos = np.column_stack([np.zeros(n, int), np.maximum(np.arange(n) - start, 0), np.zeros(n, int)])
    seg = features.segment_arrays(t, pos, np.arange(n) >= contact_at, 1.0, participant="P7", trial="12")
    assert (seg.participant, seg.trial) == ("P7", "12")
    assert seg.t.dtype == float and seg.pos.dtype == float
    np.testing.assert_array_equal(seg.t, t[seg.onset : contact_at])
    np.testing.assert_array_equal(seg.pos, pos[seg.onset : contact_at])
    assert seg.onset == start  # the central difference between the rest and the first step: 0.5 m/s


@pytest.fixture(scope="module")
def mixed_rec():
    """Participant 1: trial 1 with an infinite position (invalid data; a NaN would be a gap, filled),
    trial 2 good."""
    df = frame_of({("1", "1"): approach(), ("1", "2"): approach(amp=0.16)})
    df.loc[3, "y"] = np.inf
    return recordings_from_frame(df)


def test_segment_looks_up_the_status_of_its_own_trial(mixed_rec):
    """segment(rec, 1, 2) of a good trial beside an invalid trial 1 of the same participant returns its
    segment with its ids (catches the status row matched by participant *or* trial)."""
    seg = features.segment(mixed_rec, 1, 2)
    assert (seg.participant, seg.trial) == ("1", "2")
    t, pos, c = approach(amp=0.16)
    np.testing.assert_array_equal(seg.t, t[seg.onset : seg.contact])


def test_segment_of_a_trial_with_bad_data_names_the_reason(mixed_rec):
    with pytest.raises(ValueError, match=r"^trial '1' of participant '1' is invalid: y is infinite at row"):
        features.segment(mixed_rec, 1, 1)


def test_segment_passes_its_options_on(mixed_rec):
    """segment() segments like segment_arrays with the same onset speed, minimum length and filter.
    Catches an option dropped on the way."""
    tr = mixed_rec.trial("1", "2")
    for opts in ({"onset_speed": 4 * ONSET_SPEED}, {"lowpass": Lowpass(CUTOFF_HZ, "given")}):
        seg = features.segment(mixed_rec, "1", "2", **opts)
        want = features.segment_arrays(tr.t, tr.pos, tr.contact, mixed_rec.fs, **opts)
        assert (seg.onset, seg.contact) == (want.onset, want.contact)
        np.testing.assert_array_equal(seg.speed, want.speed)
        np.testing.assert_array_equal(seg.pos, want.pos)
    assert (
        features.segment(mixed_rec, "1", "2", onset_speed=4 * ONSET_SPEED).onset
        > features.segment(mixed_rec, "1", "2").onset
    )
    n = len(features.segment(mixed_rec, "1", "2").speed)
    with pytest.raises(ValueError, match=f"cannot be segmented: too short: {n} samples"):
        features.segment(mixed_rec, "1", "2", min_samples=n + 1)


# --- approaches and run_lowpass -------------------------------------------------------------------------


def test_approaches_are_the_positions_before_contact_of_usable_trials(mixed_rec):
    """In trial order, each usable trial's positions before its first contact sample, a trial that never
    touches whole, and nothing of a trial with bad data. Catches the status test inverted or misspelt
    and the cut at another contact sample."""
    df = frame_of({("1", "1"): approach(), ("1", "2"): approach(amp=0.16), ("2", "1"): approach(amp=0.10, surface=0.2)})
    df.loc[3, "y"] = np.inf  # trial (1, 1): bad data
    out = features.approaches(recordings_from_frame(df))
    t2, pos2, c2 = approach(amp=0.16)
    _, pos3, c3 = approach(amp=0.10, surface=0.2)
    assert not c3.any() and len(out) == 2
    np.testing.assert_array_equal(out[0], pos2[: int(np.flatnonzero(c2)[0])])
    np.testing.assert_array_equal(out[1], pos3)


def test_run_lowpass_defaults_to_auto(noisy):
    """run_lowpass(rec) is the 'auto' choice (the noise here is below the limit: not needed)."""
    _, rec, _ = noisy
    assert features.run_lowpass(rec) == features.run_lowpass(rec, "auto")
    assert features.run_lowpass(rec).chosen_by.startswith("auto")


def test_select_keeps_the_feature_columns_and_renumbers_the_rows():
    """select(): the selected rows, the same columns (no old index added as a column), index 0..n-1."""
    from skilllib.features import select

    f = pd.DataFrame(
        {
            "participant": ["1", "1", "2"],
            "trial": ["1", "2", "1"],
            "status": ["excluded", "selected", "selected"],
            "pv": [0.1, 0.2, 0.3],
        }
    )
    s = select(f)
    assert list(s.columns) == list(f.columns)
    assert list(s.index) == [0, 1] and list(s["pv"]) == [0.2, 0.3]


def test_auto_lowpass_estimates_the_noise_with_the_rates_own_derivative_window():
    """At 1 kHz the derivative window is wider than its minimum; run_lowpass("auto") must estimate the
    speed noise with the window of the recordings' rate. Catches the minimum window used at every rate."""
    from skilllib.cohort import CohortModel, generate_cohort
    from skilllib.features import MIN_DIFF_WINDOW, approaches, choose_lowpass, diff_window, run_lowpass
    from skilllib.recordings import load_recordings

    fs = 1000.0
    rec = load_recordings(generate_cohort(1, CohortModel(n_participants=1, n_trials=3, fs=fs)).frame)
    assert rec.fs == pytest.approx(fs) and diff_window(rec.fs) != MIN_DIFF_WINDOW
    got = run_lowpass(rec, "auto")
    want = choose_lowpass("auto", approaches(rec), rec.fs, diff_window(rec.fs))
    other = choose_lowpass("auto", approaches(rec), rec.fs, MIN_DIFF_WINDOW)
    assert got.speed_noise == want.speed_noise and got.speed_noise != other.speed_noise
