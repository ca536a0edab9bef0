"""Recordings in other formats through the pipeline (issue 12): a folder of C3D files, a TRC file, a CSV
with other column names, millimetres and z up, a DataFrame; unreadable files kept as invalid trials."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from test_formats import write_c3d, write_trc

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.features import trial_features
from skilllib.pipeline import _run as pipeline
from skilllib.pipeline import main
from skilllib.recordings import UP_AXIS_ROTATIONS, load_recordings, recordings_from_frame

MODEL = CohortModel(n_participants=3, n_trials=8, fs=100.0)


@pytest.fixture(scope="module")
def cohort():
    return generate_cohort(5, MODEL)


@pytest.fixture(scope="module")
def reference(cohort):
    """The trial table of the cohort read from the book's own CSV format (positions to 0.01 mm)."""
    return trial_features(recordings_from_frame(cohort.frame), lowpass="none")


def _lab(pos_book: np.ndarray, up: str) -> np.ndarray:
    """Book-frame positions in a lab frame whose vertical axis is ``up`` (inverse of the reader's rotation)."""
    return pos_book @ UP_AXIS_ROTATIONS[up]  # R is orthogonal: book = lab R^T -> lab = book R


def _same_features(got: pd.DataFrame, want: pd.DataFrame, atol: float) -> None:
    cols = ["pv", "contact_speed", "duration", "sparc"]
    assert got.status.tolist() == want.status.tolist()
    ok = want.status != "invalid"
    np.testing.assert_allclose(got.loc[ok, cols].to_numpy(float), want.loc[ok, cols].to_numpy(float), atol=atol)


def test_a_folder_of_c3d_files_in_mm_z_up_with_an_analog_contact_runs_end_to_end(tmp_path, cohort, reference, capsys):
    """participant/<trial>.c3d, millimetres in the header, z up, contact from an analog channel sampled at
    four times the point rate: the same trials, statuses and features as the CSV of the same movements."""
    root = tmp_path / "lab"
    for (p, tr), g in cohort.frame.groupby(["participant", "trial"], sort=False):
        (root / f"P{p}").mkdir(parents=True, exist_ok=True)
        pos = _lab(g[["x", "y", "z"]].to_numpy(), "z") * 1000
        write_c3d(
            root / f"P{p}" / f"{tr}.c3d",
            {"tip": pos},
            rate=MODEL.fs,
            units="mm",
            analogs={"contact": np.repeat(g["contact"].to_numpy() * 5.0, 4)},
        )
    out = tmp_path / "out"
    code = main(["run", "--data", str(root), "--out", str(out), "--up-axis", "z", "--no-figures", "--lowpass", "none"])
    assert code in (0, 3), capsys.readouterr().err
    res = json.loads((out / "results.json").read_text())
    got = pd.DataFrame(res["trials"])
    assert got.participant.tolist() == ["P" + p for p in reference.participant]
    assert got.trial.tolist() == reference.trial.tolist()
    _same_features(got, reference, atol=2e-4)  # float32 in the file


def test_a_trc_file_is_one_trial_named_by_its_file(tmp_path, cohort, reference):
    g = cohort.frame[(cohort.frame.participant == "2") & (cohort.frame.trial == "3")]
    path = write_trc(tmp_path / "S07_walk12.trc", {"spoon": g[["x", "y", "z"]].to_numpy() * 1000}, rate=MODEL.fs)
    contact_y = float(g.loc[g.contact == 1, "y"].iloc[0])  # the surface: the height at the first contact sample
    rec = load_recordings(path, contact_height=contact_y + 1e-6)
    assert rec.keys() == [("S07", "walk12")]
    f = trial_features(rec, lowpass="none")
    want = reference[(reference.participant == "2") & (reference.trial == "3")]
    _same_features(f, want.reset_index(drop=True), atol=1e-5)


def test_a_csv_with_other_names_millimetres_and_z_up(tmp_path, cohort, reference):
    df = cohort.frame.copy()
    df[["x", "y", "z"]] = _lab(df[["x", "y", "z"]].to_numpy(), "-z") * 1000
    path = tmp_path / "vr.csv.gz"
    df.rename(columns={"participant": "subject", "t": "time", "contact": "touch"}).to_csv(path, index=False)
    rec = load_recordings(path, columns="subject=participant,time=t,touch=contact", units="mm", up_axis="-z")
    _same_features(trial_features(rec, lowpass="none"), reference, atol=1e-9)


def test_a_folder_keeps_unreadable_files_as_invalid_trials(tmp_path, cohort):
    root = tmp_path / "lab"
    root.mkdir()
    for (p, tr), g in list(cohort.frame.groupby(["participant", "trial"], sort=False))[:3]:
        write_trc(root / f"{p}_{tr}.trc", {"tip": g[["x", "y", "z"]].to_numpy()}, rate=MODEL.fs, units="m")
    (root / "1_99.c3d").write_bytes(b"not a c3d file at all")
    rec = load_recordings(root, contact_height=-0.09)
    st = rec.trials.set_index(["participant", "trial"])
    assert len(rec) == 4 and st.loc[("1", "99"), "status"] == "invalid"
    assert st.loc[("1", "99"), "reason"].startswith("file 1_99.c3d: ")
    f = trial_features(rec, lowpass="none")
    assert f.set_index(["participant", "trial"]).loc[("1", "99"), "status"] == "invalid" and len(f) == 4


def test_a_bad_sample_of_a_folder_file_names_the_file_and_the_sample(tmp_path, cohort):
    root = tmp_path / "lab" / "A"
    root.mkdir(parents=True)
    g = cohort.frame[(cohort.frame.participant == "1") & (cohort.frame.trial == "1")]
    cells = {(6, 2): ""}  # row 6 (sample 7), column 2 (x of the first marker): a gap, as TRC writes one
    write_trc(root / "t1.trc", {"tip": g[["x", "y", "z"]].to_numpy()}, rate=MODEL.fs, units="m", cells=cells)
    rec = load_recordings(root.parent, contact_height=-0.09)
    assert rec.trials.reason.iloc[0] == "" and rec.trials.repairs.iloc[0].endswith("(A/t1.trc, sample 7)")


def test_pipeline_run_takes_a_dataframe(cohort, reference):
    res = pipeline.run(cohort.frame, None, lowpass="none").results
    assert res["dataset"]["path"] == "<DataFrame>" and res["dataset"]["n_trials"] == len(reference)
    assert [t["sparc"] for t in res["trials"]] == pytest.approx(reference.sparc.tolist(), nan_ok=True)


def test_what_a_reader_notes_reaches_the_recordings_and_the_run(tmp_path, capsys):
    """A TRC header announcing 652 frames over 120 rows is read (the data present are believed) and the
    note names the file, read alone or in a folder, and is printed by run (issue 22: a header frame count
    that disagrees passed silently)."""
    from skilllib.recordings import load_recordings
    from skilllib.recordings import write_trc as write_trc_file

    t = np.arange(120) / 100
    y = 0.3 - 0.2 * np.clip(t - 0.3, 0, 0.5)
    p = write_trc_file(tmp_path / "lab" / "P1_1.trc", {"tip": np.column_stack([0 * t, y, 0 * t])}, t)
    lines = p.read_text().splitlines()
    lines[2] = lines[2].replace("\t120\t", "\t652\t", 1)
    p.write_text("\n".join(lines) + "\n")
    alone = load_recordings(p, contact_height=0.2)
    assert alone.notes == (f"{p}: header announces 652 frames, file has 120",)
    assert len(alone.trial("P1", "1").t) == 120
    folder = load_recordings(p.parent, contact_height=0.2)
    assert folder.notes == ("P1_1.trc: header announces 652 frames, file has 120",)
    main(["run", "--data", str(p), "--contact-height", "0.2", "--out", str(tmp_path / "o"), "--no-figures"])
    assert f"note: {p}: header announces 652 frames, file has 120" in capsys.readouterr().out
