"""The Dask path (skilllib.features) against the in-memory path, on a LocalCluster of two workers.

Issue 15: "Results identical to the in-memory path on the cohort (a test on a LocalCluster)". The
book's cohort is written as a folder of three Parquet files (whole trials in each); the cluster's
feature table must equal, bit for bit, the table of the in-memory path on the cohort's CSV.
"""

from __future__ import annotations

import json

import pandas as pd
import pytest

from skilllib.datasets import cohort_path
from skilllib.features import _dask as partitions
from skilllib.features import trial_features
from skilllib.pipeline import _run as pipeline
from skilllib.recordings import DataFormatError, read_recordings


def write_parts(folder, frame, cuts):
    folder.mkdir()
    for k, (a, b) in enumerate(zip([0, *cuts], [*cuts, len(frame)])):
        part = frame.iloc[a:b].copy()
        for c in ("participant", "trial"):
            part[c] = part[c].astype(str)
        part.to_parquet(folder / f"part-{k}.parquet", index=False)
    return folder


@pytest.fixture(scope="module")
def cohort_frame():
    return read_recordings(cohort_path()).frame


@pytest.fixture(scope="module")
def parts(tmp_path_factory, cohort_frame):
    """The cohort in three files, cut between trials (participants 1-3, 4-7, 8-10)."""
    p = cohort_frame["participant"].astype(str).to_numpy()
    cuts = [int((p == "4").argmax()), int((p == "8").argmax())]
    return write_parts(tmp_path_factory.mktemp("pq") / "cohort", cohort_frame, cuts)


@pytest.fixture(scope="module")
def client():
    c = partitions.client_for(workers=2)
    yield c
    partitions.close_client(c)


def test_the_cluster_gives_the_in_memory_feature_table(parts, client):
    """Every column of every trial, the rate and the filter decision, as trial_features on the CSV."""
    got = partitions.corpus_features(parts, client)
    ref = trial_features(read_recordings(cohort_path()))
    pd.testing.assert_frame_equal(got.features, ref, check_exact=True)
    assert got.features.attrs["lowpass"] == ref.attrs["lowpass"] and got.fs == read_recordings(cohort_path()).fs
    assert sorted(set(got.partition)) == [0, 1, 2] and (got.features["status"] == "selected").sum() > 600


def test_a_trial_split_across_partitions_is_an_error_naming_both_files(tmp_path, cohort_frame, client):
    """A cut inside a trial: the message names the trial and the two files."""
    cut = int((cohort_frame["trial"].astype(str).to_numpy() == "2").argmax()) - 10  # inside trial 1 of "1"
    folder = write_parts(tmp_path / "split", cohort_frame.iloc[:3000], [cut])
    with pytest.raises(
        DataFormatError,
        match=r"trial '1' of participant '1' lies in two partitions, "
        r"part-0.parquet and part-1.parquet",
    ):
        partitions.corpus_features(folder, client)


def test_the_run_on_a_cluster_writes_the_in_memory_results(parts, tmp_path):
    """pipeline.run with workers=2: results.json equal to the in-memory run's on the same folder, key by
    key (prototypes, silhouettes, transfer), apart from nothing."""
    a = pipeline.run(parts, tmp_path / "cluster", workers=2, write_figures=False).results
    b = pipeline.run(parts, tmp_path / "memory", write_figures=False).results
    assert json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)
    with pytest.raises(pipeline.OptionError, match="folder of Parquet files"):
        pipeline.run(cohort_path(), tmp_path / "x", workers=2, write_figures=False)


def test_a_noisy_corpus_gets_the_in_memory_filter_on_the_cluster(tmp_path, client):
    """Tracker noise that makes "auto" filter: the noise at rest is decided over all partitions and the
    residual analysis reads the same 100 approaches, fetched from their partitions; the cut-off and every
    feature are the in-memory ones."""
    from skilllib.cohort import CohortModel, generate_cohort

    frame = generate_cohort(13, CohortModel(n_participants=4, n_trials=40, fs=120.0, noise_sd=0.0005)).frame
    p = frame["participant"].astype(str).to_numpy()
    folder = write_parts(tmp_path / "noisy", frame, [int((p == "2").argmax()), int((p == "4").argmax())])
    got = partitions.corpus_features(folder, client)
    ref = trial_features(read_recordings(folder))
    assert got.lowpass.cutoff_hz is not None and got.lowpass.chosen_by == "winter residual analysis"
    assert got.lowpass == ref.attrs["lowpass"]
    pd.testing.assert_frame_equal(got.features, ref, check_exact=True)


def test_noise_on_one_axis_is_seen_on_the_cluster(tmp_path, client):
    """The foreign 100 Hz data with 0.5 mm of noise on the depth axis only (tests/features/foreign_data.py):
    the partitions' per-axis estimates give the in-memory noise per axis and the same filter (the pooled
    estimate the cluster used before read 0.5 um and left these trials unfiltered)."""
    from foreign_data import foreign_frame

    frame = foreign_frame()
    p = frame["participant"].astype(str).to_numpy()
    folder = write_parts(tmp_path / "foreign", frame, [int((p == p[-1]).argmax())])
    got = partitions.corpus_features(folder, client)
    ref = trial_features(read_recordings(folder))
    lp = ref.attrs["lowpass"]
    assert lp.cutoff_hz is not None and got.lowpass == lp
    assert got.lowpass.noise_axes == pytest.approx(lp.noise_axes, rel=1e-12)
    assert lp.noise_axes[2] > 20 * max(lp.noise_axes[:2])
    pd.testing.assert_frame_equal(got.features, ref, check_exact=True)


def test_partitions_of_different_id_types_and_stray_files_give_the_in_memory_table(tmp_path, cohort_frame, client):
    """Issue 23: ids stored as int64, dictionary-encoded int32 and large text in the three partitions, an
    AppleDouble file and a stray CSV beside them: the cluster's table equals the in-memory one bit for bit,
    the ids are text, and both say the skipped files."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    p = cohort_frame["participant"].astype(str).to_numpy()
    cuts = [0, int((p == "4").argmax()), int((p == "8").argmax()), len(p)]
    folder = tmp_path / "mixed"
    folder.mkdir()
    stored = (lambda c: c.cast(pa.int64()), lambda c: c.cast(pa.int32()).dictionary_encode(), None)
    for k, how in enumerate(stored):
        part = cohort_frame.iloc[cuts[k] : cuts[k + 1]].astype({"participant": str, "trial": str})
        t = pa.Table.from_pandas(part, preserve_index=False)
        for c in ("participant", "trial"):
            col = t.column(c).cast(pa.large_string()) if how is None else how(t.column(c))
            t = t.set_column(t.schema.get_field_index(c), c, col)
        pq.write_table(t, folder / f"part-{k}.parquet")
    (folder / "._part-0.parquet").write_bytes(b"\x00\x05\x16\x07Mac OS X")
    (folder / "stray.csv").write_text("t,x,y,z,contact\n0,0,0,0,0\n")
    got = partitions.corpus_features(folder, client)
    memory = read_recordings(folder)
    ref = trial_features(memory)
    pd.testing.assert_frame_equal(got.features, ref, check_exact=True)
    pd.testing.assert_frame_equal(ref, trial_features(read_recordings(cohort_path())), check_exact=True)
    assert got.notes == memory.notes and "stray.csv: skipped: not a Parquet file in a Parquet dataset" in got.notes
