"""Parquet datasets as tools write them (issue 23): files whose ids are stored in different types, files of
different schemas, damaged files, stray, hidden and AppleDouble files beside the parts, reading options."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from skilllib.datasets import cohort_path
from skilllib.recordings import DataFormatError, is_parquet, load_recordings, read_recordings


@pytest.fixture(scope="module")
def frame():
    """Six trials of the cohort (participants 1 and 2, trials 1-3), ids as text."""
    f = read_recordings(cohort_path()).frame
    f = pd.DataFrame({c: f[c].astype(str) if c in ("participant", "trial") else f[c] for c in f.columns})
    keep = f["participant"].isin(["1", "2"]) & f["trial"].isin(["1", "2", "3"])
    return f[keep].reset_index(drop=True)


@pytest.fixture(scope="module")
def cut(frame):
    """The first row of participant 2: the files are cut between trials."""
    return int((frame["participant"] == "2").to_numpy().argmax())


@pytest.fixture(scope="module")
def reference(tmp_path_factory, frame):
    """The recordings of the six trials as one combined file with text ids."""
    path = tmp_path_factory.mktemp("one") / "all.parquet"
    pq.write_table(pa.Table.from_pandas(frame, preserve_index=False), path)
    return read_recordings(path)


def table(df: pd.DataFrame, id_type: pa.DataType | None = None, dictionary: bool = False) -> pa.Table:
    """``df`` as an Arrow table, ids stored as ``id_type`` (None: text), dictionary-encoded or not."""
    t = pa.Table.from_pandas(df, preserve_index=False)
    for c in ("participant", "trial"):
        col = t.column(c)
        if id_type is not None:
            col = col.cast(pa.int64()).cast(id_type) if pa.types.is_integer(id_type) else col.cast(id_type)
        if dictionary:
            col = col.dictionary_encode()
        t = t.set_column(t.schema.get_field_index(c), c, col)
    return t


def write_dataset(folder, frame, cut, first: pa.Table | None = None, second: pa.Table | None = None):
    folder.mkdir()
    pq.write_table(first if first is not None else table(frame.iloc[:cut]), folder / "part-0.parquet")
    pq.write_table(second if second is not None else table(frame.iloc[cut:]), folder / "part-1.parquet")
    return folder


def assert_same(a, b):
    """The same recordings: trials (ids, counts, statuses, reasons, timing), samples and rate."""
    cols = ["participant", "trial", "n_samples", "first_line", "status", "reason", "timing", "repairs"]
    pd.testing.assert_frame_equal(a.trials[cols], b.trials[cols], check_exact=True)
    pd.testing.assert_frame_equal(a.frame, b.frame, check_exact=True)
    assert a.fs == b.fs


VARIANTS = {
    "int64 and text": (pa.int64(), False, None, False),
    "int32 and int64": (pa.int32(), False, pa.int64(), False),
    "dictionary and plain": (None, True, None, False),
    "large_string and string": (pa.large_string(), False, None, False),
    "float and uint16 dictionary": (pa.float64(), False, pa.uint16(), True),
}


@pytest.mark.parametrize("variant", VARIANTS)
def test_ids_stored_in_different_types_are_the_same_text(tmp_path, frame, cut, reference, variant):
    """Ids are unified to text across files whatever their Arrow type: the same recordings as one file."""
    t0, d0, t1, d1 = VARIANTS[variant]
    folder = write_dataset(
        tmp_path / "ds", frame, cut, table(frame.iloc[:cut], t0, d0), table(frame.iloc[cut:], t1, d1)
    )
    rec = read_recordings(folder)
    assert list(rec.trials["participant"]) == ["1"] * 3 + ["2"] * 3
    assert all(isinstance(v, str) for v in [*rec.trials["participant"], *rec.trials["trial"]])
    assert_same(rec, reference)
    assert_same(load_recordings(folder), reference)
    assert rec.notes == ()


def test_integer_ids_in_one_file_keep_the_existing_rule(tmp_path, frame):
    """A single file of integer (or integer-valued float) ids reads them as the API does: 1 is "1", 1.0 is
    "1", 2.5 is "2.5"; a dataset of the same ids in two types gives those texts too."""
    f = frame.assign(participant=frame["participant"].astype(float))
    f.loc[f["participant"] == 2.0, "participant"] = 2.5
    f.to_parquet(tmp_path / "floats.parquet", index=False)
    assert list(dict.fromkeys(read_recordings(tmp_path / "floats.parquet").trials["participant"])) == ["1", "2.5"]


def test_a_missing_column_or_a_column_that_cannot_be_unified_names_the_file(tmp_path, frame, cut):
    """One line naming the file and the column."""
    second = table(frame.iloc[cut:].drop(columns="contact"))
    folder = write_dataset(tmp_path / "missing", frame, cut, second=second)
    with pytest.raises(DataFormatError, match=r"part-1.parquet: required column 'contact' missing") as e:
        read_recordings(folder)
    assert "\n" not in str(e.value)
    second = table(frame.iloc[cut:].assign(t=frame["t"].iloc[cut:].astype(str)))
    folder = write_dataset(tmp_path / "text", frame, cut, second=second)
    with pytest.raises(
        DataFormatError, match=r"part-1.parquet: column 't' is (large_)?string here but double in part-0"
    ) as e:
        read_recordings(folder)
    assert "\n" not in str(e.value)
    second = table(frame.iloc[cut:].assign(x=pd.Timestamp("2024-01-01")))
    folder = write_dataset(tmp_path / "date", frame, cut, second=second)
    with pytest.raises(DataFormatError, match=r"part-1.parquet: column 'x' is timestamp"):
        read_recordings(folder)


def test_numbers_of_different_types_are_unified(tmp_path, frame, cut, reference):
    """contact as booleans in one file and int64 in another, t as float32-free doubles: read as numbers."""
    first = frame.iloc[:cut].assign(contact=frame["contact"].iloc[:cut].astype(bool))
    second = frame.iloc[cut:].assign(contact=frame["contact"].iloc[cut:].astype(np.int64))
    folder = write_dataset(tmp_path / "ds", frame, cut, table(first), table(second))
    assert_same(read_recordings(folder), reference)


def damaged(raw: bytes, at: int, n: int = 64) -> bytes:
    out = bytearray(raw)
    out[at : at + n] = b"\x07" * n
    return bytes(out)


def test_a_damaged_file_is_one_line_naming_it(tmp_path, frame, cut):
    """Bytes overwritten in the middle (page checksums written), or the file truncated: one line naming the
    file; overwritten anywhere without checksums, never another exception nor more than one line."""
    folder = write_dataset(tmp_path / "ds", frame, cut)
    part = folder / "part-1.parquet"
    pq.write_table(table(frame.iloc[cut:]), part, compression="none", write_page_checksum=True)
    raw = part.read_bytes()
    part.write_bytes(damaged(raw, len(raw) // 3))
    with pytest.raises(DataFormatError, match=r"part-1.parquet: ") as e:
        read_recordings(folder)
    assert "\n" not in str(e.value)
    part.write_bytes(raw[: len(raw) // 2])
    with pytest.raises(DataFormatError, match=r"part-1.parquet: not a readable Parquet file") as e:
        read_recordings(folder)
    assert "\n" not in str(e.value)
    pq.write_table(table(frame.iloc[cut:]), part)
    raw = part.read_bytes()
    for k in range(1, 40):
        part.write_bytes(damaged(raw, len(raw) * k // 40))
        try:
            read_recordings(folder)
        except DataFormatError as err:
            assert "part-1.parquet" in str(err) and "\n" not in str(err), str(err)


def test_stray_hidden_and_appledouble_files_are_skipped_and_said(tmp_path, frame, cut, reference):
    """A stray one-trial CSV, .DS_Store, AppleDouble ._part-0.parquet, Spark's _SUCCESS and a sub-folder
    beside the parts: the parts are read, each other entry skipped with a note naming it."""
    folder = write_dataset(tmp_path / "ds", frame, cut)
    frame.iloc[:200][["t", "x", "y", "z", "contact"]].to_csv(folder / "stray.csv", index=False)
    (folder / ".DS_Store").write_bytes(b"\x00\x00\x00\x01Bud1")
    (folder / "._part-0.parquet").write_bytes(b"\x00\x05\x16\x07\x00\x02\x00\x00Mac OS X")
    (folder / "_SUCCESS").write_bytes(b"")
    (folder / "old").mkdir()
    assert is_parquet(folder)
    for rec in (read_recordings(folder), load_recordings(folder)):
        assert_same(rec, reference)
        notes = "\n".join(rec.notes)
        assert "stray.csv: skipped: not a Parquet file in a Parquet dataset" in rec.notes
        for name in (".DS_Store: skipped: a hidden file", "._part-0.parquet: skipped: an AppleDouble", "_SUCCESS"):
            assert name in notes
        assert "old: skipped: a folder inside a Parquet dataset" in notes


def test_a_folder_of_trial_files_with_a_stray_parquet_file_is_not_a_dataset(tmp_path, frame):
    """More one-trial CSVs than Parquet files: a folder of trials (its reader reports the Parquet file)."""
    folder = tmp_path / "trials"
    folder.mkdir()
    for k in range(3):
        frame.iloc[:200][["t", "x", "y", "z", "contact"]].to_csv(folder / f"P1_{k}.csv", index=False)
    frame.to_parquet(folder / "summary.parquet", index=False)
    assert not is_parquet(folder)
    (folder / "more.parquet").write_bytes((folder / "summary.parquet").read_bytes())
    (folder / "more2.parquet").write_bytes((folder / "summary.parquet").read_bytes())
    assert is_parquet(folder)


def test_reading_options_apply_or_are_refused(tmp_path, frame, cut, reference):
    """--columns renames the files' columns, --units converts, --contact-height gives contact; --marker
    and the other formats' options are refused with one line saying what applies."""
    mm = frame.assign(**{c: frame[c] * 1000 for c in ("x", "y", "z")}).rename(columns={"participant": "subject"})
    folder = tmp_path / "ds"
    folder.mkdir()
    mm.iloc[:cut].rename(columns={"subject": "participant"}).to_parquet(folder / "part-0.parquet", index=False)
    mm.iloc[cut:].to_parquet(folder / "part-1.parquet", index=False)
    with pytest.raises(DataFormatError, match=r"part-0.parquet: --columns names column 'subject', which the file"):
        load_recordings(folder, units="mm", columns="subject=participant")
    single = tmp_path / "mm.parquet"
    mm.to_parquet(single, index=False)
    rec = load_recordings(single, units="mm", columns="subject=participant")
    cols = ["participant", "trial", "n_samples", "status", "reason"]
    pd.testing.assert_frame_equal(rec.trials[cols], reference.trials[cols])
    assert np.allclose(rec.frame[["x", "y", "z"]], reference.frame[["x", "y", "z"]], rtol=1e-12, atol=0)
    nocontact = tmp_path / "nocontact.parquet"
    frame.drop(columns="contact").to_parquet(nocontact, index=False)
    got = load_recordings(nocontact, contact_height=float(frame["y"].min()) + 0.002)
    assert set(np.unique(got.frame["contact"])) <= {0.0, 1.0} and got.frame["contact"].sum() > 0
    for opts, flag in (({"marker": "RFTP"}, "--marker"), ({"sep": ";"}, "--sep")):
        with pytest.raises(DataFormatError, match=rf"{flag} does not apply to Parquet input") as e:
            load_recordings(single, **opts)
        assert "\n" not in str(e.value) and "--units" in str(e.value)
