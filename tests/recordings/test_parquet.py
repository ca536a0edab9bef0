"""Columnar data in and out (issue 15): Parquet files and folders as --data, with the CSV's checks and
messages that name the file and row; the per-trial table as trials.parquet above 10,000 trials."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.pipeline import _run as pipeline
from skilllib.pipeline import _trials_file as trialtable
from skilllib.recordings import DataFormatError, read_recordings, write_recordings


@pytest.fixture(scope="module")
def frame():
    f = generate_cohort(4, CohortModel(n_participants=3, n_trials=10)).frame.copy()
    for c in ("participant", "trial"):
        f[c] = f[c].astype(str)
    return f


def test_a_parquet_folder_reads_as_the_csv(tmp_path, frame):
    """Two Parquet files (cut between trials) and the CSV of the same table: the same recordings."""
    (tmp_path / "pq").mkdir()
    cut = int((frame["participant"] == "2").to_numpy().argmax())
    frame.iloc[:cut].to_parquet(tmp_path / "pq" / "part-1.parquet", index=False)
    frame.iloc[cut:].to_parquet(tmp_path / "pq" / "part-2.parquet", index=False)
    a = read_recordings(write_recordings(frame, tmp_path / "r.csv"))
    b = read_recordings(tmp_path / "pq")
    cols = ["participant", "trial", "n_samples", "status", "reason", "timing"]
    pd.testing.assert_frame_equal(a.trials[cols], b.trials[cols], check_exact=True)
    assert a.fs == b.fs and len(a) == 30


def test_parquet_integer_ids_are_text_and_problems_name_the_file_and_row(tmp_path, frame):
    """Integer ids read as text ("1"); a missing column names the file; NaN in x names file and row."""
    f = frame.copy()
    f["participant"] = f["participant"].astype(int)
    f.loc[5, "x"] = np.nan
    f.to_parquet(tmp_path / "one.parquet", index=False)
    rec = read_recordings(tmp_path / "one.parquet")
    assert set(rec.trials["participant"]) == {"1", "2", "3"}
    assert rec.trials["repairs"].iloc[0].endswith("one.parquet, row 6)")  # the one-sample gap, filled
    f.drop(columns="contact").to_parquet(tmp_path / "nocontact.parquet", index=False)
    with pytest.raises(DataFormatError, match=r"nocontact.parquet: required column 'contact' missing"):
        read_recordings(tmp_path / "nocontact.parquet")
    f.assign(t=f["t"].astype(str).where(f.index != 9, "soon")).to_parquet(tmp_path / "text.parquet", index=False)
    with pytest.raises(DataFormatError, match=r"text.parquet, row 10, column 't': 'soon' is not a number"):
        read_recordings(tmp_path / "text.parquet")


def test_many_trials_go_to_trials_parquet(tmp_path, frame, monkeypatch):
    """Above the threshold results.json names trials.parquet and counts the statuses; read_trials gives
    the same table either way."""
    inline = pipeline.run(frame, tmp_path / "inline", write_figures=False)
    monkeypatch.setattr(trialtable, "TRIALS_IN_JSON_MAX", 20)
    many = pipeline.run(frame, tmp_path / "many", write_figures=False)
    res = json.loads((tmp_path / "many" / "results.json").read_text())
    assert "trials" not in res and res["trials_file"] == "trials.parquet"
    counts = inline.features["status"].value_counts()
    assert res["trial_counts"] == {s: int(counts.get(s, 0)) for s in ("selected", "excluded", "invalid")}
    table = trialtable.read_trials(tmp_path / "many")
    pd.testing.assert_frame_equal(
        table, many.features.astype({c: str for c in ("participant", "trial", "status", "reason")}), check_dtype=False
    )
    short = trialtable.read_trials(tmp_path / "inline")
    assert list(short["trial"]) == list(table["trial"]) and np.allclose(short["sparc"], table["sparc"], equal_nan=True)
    assert (tmp_path / "many" / "trials.parquet").exists() and not (tmp_path / "inline" / "trials.parquet").exists()
