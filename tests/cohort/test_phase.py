"""The sampling phase of the synthetic cohort (``CohortModel.phase``): the same movements sampled later.

Phase 0 is the committed cohort bit for bit; any other phase moves every time stamp by ``phase / fs`` and
nothing else: the same number of samples, the same noise draws, the same ground truth.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import skilllib as sk

SMALL = dict(n_participants=2, n_trials=6)


def _cohort(phase: float | None = None):
    model = sk.CohortModel(**SMALL) if phase is None else sk.CohortModel(**SMALL, phase=phase)
    return sk.generate_cohort(sk.SEED, model)


def test_phase_zero_is_the_default_cohort_bit_for_bit():
    default, zero = _cohort(), _cohort(0.0)
    pd.testing.assert_frame_equal(default.frame, zero.frame, check_exact=True)
    pd.testing.assert_frame_equal(default.truth, zero.truth, check_exact=True)


@pytest.mark.parametrize("phase", [0.25, 0.5, 0.75])
def test_a_phase_moves_the_time_stamps_by_phase_over_fs_and_keeps_the_truth(phase):
    base, moved = _cohort(0.0), _cohort(phase)
    fs = base.model.fs
    assert len(moved.frame) == len(base.frame)  # same samples per trial
    dt = moved.frame["t"].to_numpy() - base.frame["t"].to_numpy()
    np.testing.assert_allclose(dt, phase / fs, rtol=0, atol=1e-12)
    pd.testing.assert_frame_equal(base.truth, moved.truth, check_exact=True)
    pd.testing.assert_frame_equal(base.participants, moved.participants, check_exact=True)
    # the contact flag follows the true contact time on the moved grid
    tc = moved.truth.set_index(["participant", "trial"])["t_contact"]
    f = moved.frame
    expect = f["t"].to_numpy() >= tc.loc[list(zip(f["participant"], f["trial"]))].to_numpy()
    assert np.array_equal(f["contact"].to_numpy() == 1, expect)
    # the positions are those of the same movement at other instants: close, but not the same samples
    d = np.abs(f[["x", "y", "z"]].to_numpy() - base.frame[["x", "y", "z"]].to_numpy())
    assert d.max() > 1e-3  # moving samples moved (m)
    assert np.median(d) < 1e-3


def test_a_phase_shifted_cohort_reads_as_regular_recordings():
    rec = sk.load_recordings(_cohort(0.5).frame)
    f = sk.trial_features(rec)
    assert not f["resampled"].any()
    assert (f["status"] != "invalid").all()


@pytest.mark.parametrize("phase", [-0.1, 1.0, 1.5])
def test_a_phase_outside_one_interval_is_refused(phase):
    with pytest.raises(ValueError, match="phase"):
        sk.CohortModel(phase=phase)


def test_the_model_table_documents_the_phase():
    row = sk.model_table(sk.CohortModel(phase=0.25)).loc["phase"]
    assert row["value"] == "0.25" and "sampling phase" in row["meaning"]
