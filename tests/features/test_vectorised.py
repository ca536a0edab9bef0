"""The vectorised paths against their per-trial references (issue 15: "one implementation must be the
reference of the other in a test").

* :func:`skilllib.features.trial_features` (segmentation and features of all trials at once,
  :mod:`skilllib.features`) against :func:`reference_features`, the per-trial loop it replaced:
  :func:`skilllib.features.segment_arrays`, :func:`skilllib.smoothness.ldlj` and
  :func:`skilllib.smoothness.sparc_bands` one trial after another. Bit for bit at 60 and 120 Hz; at
  250 Hz (a 9-sample differentiating window) to 1e-13 relative (skilllib.features's docstring says why).
* :func:`skilllib.recordings.recordings_from_frame` (flags over the flat arrays, statistics in blocks,
  :mod:`skilllib.recordings`) against :func:`reference_validation`, the per-trial checks.
* :func:`skilllib.recordings.read_recordings` through pyarrow (a plain file) against the pandas reader
  (:func:`skilllib.recordings.read_table`), which every other file goes to.

The recordings are a "zoo": generated trials plus every way a trial can fail segmentation or validation.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given
from hypothesis import strategies as st

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.datasets import cohort_path
from skilllib.features import (
    CONTACT_WINDOW,
    FEATURE_COLUMNS,
    SPARC_PARAMS,
    Lowpass,
    path_length,
    peak_acceleration,
    run_lowpass,
    segment_arrays,
    trial_features,
)
from skilllib.recordings import Runs, first_true, read_recordings, read_table, recordings_from_frame
from skilllib.recordings import _checks as checks
from skilllib.recordings import _timing as timing
from skilllib.smoothness import _measures as smoothness


def reference_features(rec, lowpass="auto", window=CONTACT_WINDOW) -> pd.DataFrame:
    """The per-trial loop: segment each usable trial, its features, SPARC of all segments, the status."""
    filt = run_lowpass(rec, lowpass)
    rows, speeds = [], []
    for (p, tr), status, reason, note in zip(
        rec.keys(), rec.trials["status"], rec.trials["reason"], rec.trials["timing"]
    ):
        row = {"participant": p, "trial": tr, "status": "invalid", "reason": reason, "resampled": bool(note)}
        row.update(rec.trials.set_index(["participant", "trial"]).loc[(p, tr), ["repairs", "n_repaired"]].to_dict())
        if status == "ok":
            d = rec.trial(p, tr)
            seg = segment_arrays(d.t, d.pos, d.contact, rec.fs, lowpass=filt)
            if isinstance(seg, str):
                row["reason"] = seg
            else:
                v = seg.speed
                lo, hi = window
                cs = float(v[-1])
                why = (
                    f"contact speed {cs:.3f} m/s below {lo:g} m/s"
                    if cs < lo
                    else f"contact speed {cs:.3f} m/s above {hi:g} m/s"
                    if cs > hi
                    else ""
                )
                row.update(
                    status="excluded" if why else "selected",
                    reason=why,
                    pv=float(v.max()),
                    contact_speed=cs,
                    duration=seg.duration,
                    ldlj=smoothness.ldlj(v, rec.fs),
                    peak_acc=peak_acceleration(v, rec.fs),
                    path_length=path_length(v, rec.fs),
                    n=len(v),
                    t_onset=float(d.t[seg.onset]),
                    t_contact=float(d.t[seg.contact]),
                    _k=len(speeds),
                )
                speeds.append(v)
        rows.append(row)
    bands = smoothness.sparc_bands(speeds, rec.fs, **SPARC_PARAMS) if speeds else None
    for row in rows:
        if "_k" in row:
            k = row.pop("_k")
            row.update(
                sparc=float(bands.sparc[k]),
                sparc_band_end_hz=float(bands.band_end_hz[k]),
                sparc_capped=bool(bands.capped[k]),
            )
    out = pd.DataFrame(rows, columns=list(FEATURE_COLUMNS))
    out["n"] = out["n"].astype("Int64")
    out["sparc_capped"] = out["sparc_capped"].astype("boolean")
    out["resampled"] = out["resampled"].astype(bool)
    return out


def zoo(fs: float, seed: int = 5) -> pd.DataFrame:
    """Generated trials at ``fs`` plus trials that fail in every way (each named by its trial id)."""
    f = generate_cohort(seed, CohortModel(n_participants=3, n_trials=12, fs=fs)).frame.copy()
    f["participant"], f["trial"] = f["participant"].astype(str), f["trial"].astype(str)
    one = f[(f.participant == f.participant.iloc[0]) & (f.trial == f.trial.iloc[0])]
    dt = 1 / fs

    def variant(name, **change):
        g = one.copy()
        g["participant"], g["trial"] = "zoo", name
        for col, fn in change.items():
            g[col] = fn(g)
        return g

    seg = segment_arrays(one["t"].to_numpy(), one[["x", "y", "z"]].to_numpy(), one["contact"].to_numpy() == 1, fs)
    extra = [
        variant("no-contact", contact=lambda g: 0),
        variant("contact-at-start", contact=lambda g: 1),
        variant("contact-at-second", contact=lambda g: (np.arange(len(g)) >= 1).astype(int)),
        variant("short-approach", contact=lambda g: (np.arange(len(g)) >= 2).astype(int)),
        variant("no-onset", y=lambda g: g["y"].iloc[0] + 0 * g["y"]),
        variant("moving-at-start", y=lambda g: g["y"] - 0.2 * g["t"]),
        variant("too-short", contact=lambda g: (np.arange(len(g)) >= seg.onset + 3).astype(int)),
        variant("jitter", t=lambda g: g["t"] + np.where(np.arange(len(g)) % 3 == 1, 0.2 * dt, 0.0)),
        variant("dropped", t=lambda g: g["t"] + np.where(np.arange(len(g)) >= 10, dt, 0.0)),
        variant("gap", t=lambda g: g["t"] + np.where(np.arange(len(g)) >= 10, 5 * dt, 0.0)),
        variant("nan-x", x=lambda g: g["x"].where(np.arange(len(g)) != 7)),
        variant("backwards", t=lambda g: g["t"].where(np.arange(len(g)) != 7, g["t"].iloc[5])),
        variant("off-rate", t=lambda g: g["t"] * 1.5),
        variant("huge", z=lambda g: g["z"] + np.where(np.arange(len(g)) == 3, 5.0, 0.0)),
    ]
    return pd.concat([f, *extra, one.iloc[:3].assign(participant="zoo", trial="few")], ignore_index=True)


def assert_same(got: pd.DataFrame, ref: pd.DataFrame, exact: bool) -> None:
    if exact:
        pd.testing.assert_frame_equal(got, ref, check_exact=True)
        return
    floats = [c for c in ref.columns if ref[c].dtype == float]
    pd.testing.assert_frame_equal(got.drop(columns=floats), ref.drop(columns=floats), check_exact=True)
    for c in floats:
        np.testing.assert_allclose(got[c], ref[c], rtol=1e-13, atol=0, err_msg=c)


@pytest.mark.parametrize("fs, exact", [(60.0, True), (120.0, True), (250.0, False)])
def test_features_equal_the_per_trial_loop_on_the_zoo(fs, exact):
    """Every status, reason, id, count and feature as the per-trial loop gives them. Catches an off-by-one
    in the onset or contact index, a reason in another order, a segment's speeds cut differently, LDLJ
    or SPARC of other samples, a trial's features in another trial's row."""
    rec = recordings_from_frame(zoo(fs))
    got = trial_features(rec)
    assert_same(got, reference_features(rec), exact)
    reasons = dict(zip(got["trial"], got["reason"]))
    assert reasons["no-contact"].startswith("no contact")
    assert reasons["contact-at-start"].startswith("in contact from sample 1")
    assert reasons["moving-at-start"].startswith("no rest before onset")
    assert reasons["too-short"].startswith("too short")
    assert reasons["gap"].startswith("gap in the time stamps")
    assert got.loc[got["trial"] == "jitter", "resampled"].item()
    assert (got["status"] == "selected").sum() > 5 and (got["status"] == "excluded").sum() > 5


def test_features_equal_the_per_trial_loop_on_the_cohort_bit_for_bit():
    """The book's 1,500 trials: the table of the vectorised path is the per-trial loop's, every bit."""
    rec = read_recordings(cohort_path())
    assert_same(trial_features(rec), reference_features(rec), exact=True)


@pytest.mark.parametrize("cutoff", [8.0, None])
def test_filtered_runs_equal_the_per_trial_loop(cutoff):
    """A run with a low-pass filter (one trial at a time in skilllib.features) and one without."""
    rec = recordings_from_frame(zoo(120.0, seed=9))
    filt = Lowpass(cutoff, "given", fs=rec.fs) if cutoff else Lowpass(None, "none")
    assert_same(trial_features(rec, lowpass=filt), reference_features(rec, lowpass=filt), exact=True)


def reference_validation(frame: pd.DataFrame) -> tuple[list[str], float]:
    """The per-trial checks: trial_problem, then the rate from each trial's intervals, units, timing."""
    keys = list(dict.fromkeys(zip(frame["participant"], frame["trial"])))
    t, pos, c = frame["t"].to_numpy(float), frame[["x", "y", "z"]].to_numpy(float), frame["contact"].to_numpy(float)
    rows = [
        np.flatnonzero((frame["participant"] == p).to_numpy() & (frame["trial"] == tr).to_numpy()) for p, tr in keys
    ]
    reasons = [checks.trial_problem(t[r], pos[r], c[r], r, int, lambda i: f"row {i}") for r in rows]
    ok = [i for i, r in enumerate(reasons) if not r]
    med = np.array([np.median(np.diff(t[rows[i]])) for i in ok])
    mean = np.array([timing.regular_mean_interval(t[rows[i]]) for i in ok])
    ref = np.median(med)
    off = np.abs(med / ref - 1) > timing.RATE_TOLERANCE
    dt = float(np.median(mean[~off]))
    for j, i in enumerate(ok):
        if off[j]:
            reasons[i] = "off-rate"
        elif np.ptp(pos[rows[i]], axis=0).max() > 2.0:
            reasons[i] = "span"
        elif timing.irregularity(t[rows[i]], dt).gap:
            reasons[i] = "gap"
    return reasons, dt


@pytest.mark.parametrize("fs", [60.0, 250.0])
def test_validation_equals_the_per_trial_checks(fs):
    """Which trials are invalid, and the sampling rate to the last bit, as the per-trial checks find them."""
    frame = zoo(fs)
    rec = recordings_from_frame(frame)
    reasons, dt = reference_validation(frame)
    assert rec.fs == 1.0 / dt
    assert [bool(r) for r in reasons] == list(rec.trials["status"] == "invalid")
    flagged = {k: r for k, r in zip(rec.keys(), rec.trials["reason"]) if r}
    assert flagged[("zoo", "gap")].startswith("gap") and flagged[("zoo", "off-rate")].startswith("sampled at")
    assert flagged[("zoo", "huge")].startswith("positions span") and ("zoo", "nan-x") not in flagged
    repairs = rec.trials.set_index("trial")["repairs"]
    row = int(np.flatnonzero(((frame["participant"] == "zoo") & (frame["trial"] == "nan-x")).to_numpy())[7])
    assert repairs["nan-x"].startswith("1 missing sample replaced") and repairs["nan-x"].endswith(f"(row {row})")


def test_plain_files_are_read_by_pyarrow_with_the_same_result(tmp_path):
    """A plain file (pyarrow) and the same file with one quoted id (pandas' reader) give the same
    recordings: ids as text (01, NA), values to the last bit, line numbers in the reasons."""
    frame = zoo(60.0)
    frame.loc[frame["participant"] == "zoo", "participant"] = "01"
    frame.loc[frame["trial"] == "few", "participant"] = "NA"
    text = frame.to_csv(index=False, lineterminator="\n", float_format="%.6f")
    plain, quoted = tmp_path / "plain.csv", tmp_path / "quoted.csv"
    plain.write_text(text)
    quoted.write_text(text.replace("\n01,", '\n"01",', 1))
    a, b = read_recordings(plain), read_recordings(quoted)
    pd.testing.assert_frame_equal(a.trials, b.trials, check_exact=True)
    assert a.fs == b.fs and "NA" in set(a.trials["participant"]) and "01" in set(a.trials["participant"])
    for col in ("t", "x", "y", "z", "contact"):
        np.testing.assert_array_equal(a.frame[col].to_numpy(), b.frame[col].to_numpy())
    df, _ = read_table(plain)
    assert (df["participant"].to_numpy() == a.frame["participant"].astype(str).to_numpy()).all()


def test_a_blank_line_goes_to_the_reader_that_counts_lines(tmp_path):
    """pyarrow skips blank lines, which would shift every line number after them: such a file is read
    by pandas' reader, and a sample below the blank line is named by its physical line (here the repair
    of a missing sample)."""
    frame = zoo(60.0)
    lines = frame.to_csv(index=False, lineterminator="\n").splitlines()
    bad = next(i for i, ln in enumerate(lines) if ln.startswith("zoo,nan-x,")) + 7  # row 7 of that trial
    path = tmp_path / "blank.csv"
    path.write_text("\n".join(lines[:3] + [""] + lines[3:]) + "\n")
    rec = read_recordings(path)
    repairs = rec.trials.set_index("trial").loc["nan-x", "repairs"]
    assert f"line {bad + 2})" in repairs, repairs  # +1 for 1-based lines, +1 for the blank line


@given(st.lists(st.lists(st.booleans(), min_size=0, max_size=6), min_size=1, max_size=8), st.randoms())
def test_first_true_and_blocks_agree_with_a_loop(runs_flags, rnd):
    """first_true: the first True of each run wherever the runs lie (shuffled order, empty runs);
    Runs.blocks: every included trial exactly once, with its own rows."""
    order = list(range(len(runs_flags)))
    rnd.shuffle(order)
    flat, start = [], [0] * len(runs_flags)
    for i in order:
        start[i] = len(flat)
        flat += runs_flags[i]
    runs = Runs(np.array(start, dtype=np.int64), np.array([len(f) for f in runs_flags], dtype=np.int64))
    got = first_true(np.array(flat, dtype=bool), runs)
    want = [f.index(True) if True in f else len(f) for f in runs_flags]
    assert got.tolist() == want
    seen = []
    for trials, rows in runs.blocks(runs.length > 0):
        for k, i in enumerate(trials):
            assert rows[k].tolist() == list(range(start[i], start[i] + len(runs_flags[i])))
            seen.append(int(i))
    assert sorted(seen) == [i for i, f in enumerate(runs_flags) if f]
