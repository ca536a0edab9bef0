"""`python -m skilllib run`: the whole pipeline, its results.json and its handling of broken input.

Each broken-input case writes its own small file; file-level problems must stop the run with exit
status 2 and one line on stderr (no traceback), trial-level problems must mark just that trial invalid.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.features import segment, select, trial_features
from skilllib.pipeline import main
from skilllib.prototypes import _kmeans as pt
from skilllib.recordings import read_recordings, recordings_from_frame, write_recordings
from skilllib.smoothness import SPARC_PARAMS, sparc_spectrum

ROOT = Path(__file__).resolve().parents[2]


def _schema_keys() -> set[str]:
    """The top-level keys of results.json as the schema table of docs/results.md (the book's reference page)
    names them (first column, in backticks)."""
    text = (ROOT / "docs" / "results.md").read_text()
    rows = [line.split("|")[1] for line in text.splitlines() if line.startswith("| `")]
    return {key for cell in rows for key in re.findall(r"`([a-z_]+)`", cell)}


SCHEMA_KEYS = _schema_keys()
FIGURES = (
    "features",
    "trials_by_participant",
    "participant_features",
    "sparc_vs_length",
    "silhouette_sweep",
    "silhouettes_k",
    "clusters_pv_sparc",
    "prototype_speed_profiles",
    "joint_velocities",
    "frame_mapping",
    "joint_accelerations",
    "executed_speed",
    "time_scales",
)
TRIAL_KEYS = {
    "peak_acc",
    "path_length",
    "repairs",
    "n_repaired",
    "participant",
    "trial",
    "status",
    "reason",
    "pv",
    "contact_speed",
    "duration",
    "sparc",
    "sparc_band_end_hz",
    "sparc_capped",
    "ldlj",
    "resampled",
}


@pytest.fixture(scope="module")
def small_frame() -> pd.DataFrame:
    """4 participants x 12 trials sampled at 100 Hz (not the cohort's 60 Hz)."""
    return generate_cohort(7, CohortModel(n_participants=4, n_trials=12, fs=100.0)).frame


def _write(df: pd.DataFrame, path: Path) -> Path:
    write_recordings(df, path)
    return path


def _run(capsys, *args: str) -> tuple[int, str, str]:
    code = main(["run", "--quiet", *args])
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def _results(out: Path) -> dict:
    return json.loads((out / "results.json").read_text())


def _one_line_error(err: str, *needles: str) -> None:
    lines = [ln for ln in err.strip().splitlines() if ln]
    assert len(lines) == 1, f"expected one error line, got: {err!r}"
    assert lines[0].startswith("error: ")
    assert "Traceback" not in err
    for n in needles:
        assert n.lower() in lines[0].lower(), f"{n!r} not in {lines[0]!r}"


# --- a good small file at another sampling rate ------------------------------------------------------


def test_small_file_at_100_hz(tmp_path, capsys, small_frame):
    data = _write(small_frame, tmp_path / "rec.csv")
    code, out, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), "--no-figures")
    assert code == 0, err
    res = _results(tmp_path / "o")
    assert res["dataset"]["fs"] == pytest.approx(100.0, rel=1e-6)
    assert res["dataset"]["n_trials"] == 48 and res["dataset"]["n_participants"] == 4
    assert res["dataset"]["path"] == str(data)
    assert len(res["trials"]) == 48
    assert all(set(t) == TRIAL_KEYS for t in res["trials"])
    n_sel = sum(t["status"] == "selected" for t in res["trials"])
    assert res["n_selected"] == n_sel
    assert sum(c["size"] for c in res["clusters"]) == n_sel
    assert "trials read: 48" in out and "selected:" in out


def _selected_keys(df: pd.DataFrame) -> list[tuple]:
    f = trial_features(recordings_from_frame(df))
    return list(f.loc[f["status"] == "selected", ["participant", "trial"]].itertuples(index=False, name=None))


def _only(df: pd.DataFrame, keys: list[tuple]) -> pd.DataFrame:
    idx = pd.MultiIndex.from_frame(df[["participant", "trial"]])
    return df[idx.isin(keys)]


def test_small_data_shrink_the_sweep_and_k_with_messages(tmp_path, capsys, small_frame):
    keys = _selected_keys(small_frame)[:5]  # 5 selected trials: silhouettes allow k = 2..4
    data = _write(_only(small_frame, keys), tmp_path / "five.csv")
    code, out, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), "--no-figures")
    assert code == 0, err
    res = _results(tmp_path / "o")
    assert res["n_selected"] == 5
    assert sorted(int(k) for k in res["silhouette"]) == [2, 3, 4]
    assert res["k"] == 4 and len(res["clusters"]) == 4 and len(res["transfer"]["prototypes"]) == 4
    assert any("shrunk" in m and "2..4" in m for m in res["messages"])
    assert any("k = 6" in m and "k = 4" in m for m in res["messages"])
    assert "note: silhouette sweep shrunk" in out


@pytest.mark.parametrize("n", [0, 1, 2])
def test_fewer_than_three_selected_trials_exit_3_with_every_trial(tmp_path, capsys, small_frame, n):
    f = trial_features(recordings_from_frame(small_frame))
    excluded = list(f.loc[f["status"] == "excluded", ["participant", "trial"]].itertuples(index=False, name=None))
    keys = _selected_keys(small_frame)[:n] + excluded[:2]
    data = _write(_only(small_frame, keys), tmp_path / "few.csv")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"))
    assert code == 3, err
    res = _results(tmp_path / "o")
    assert res["n_selected"] == n and len(res["trials"]) == n + 2
    assert not {"clusters", "silhouette", "k"} & set(res)
    assert any(f"only {n} selected" in m for m in res["messages"])
    assert "features.png" in res["figures"] and "clusters_pv_sparc.png" not in res["figures"]
    if n == 0:
        assert "transfer" not in res and "joint_velocities.png" not in res["figures"]
    else:  # too few to cluster: each selected trial is transferred as it is, in trial order
        selected = [(t["participant"], t["trial"]) for t in res["trials"] if t["status"] == "selected"]
        got = [(e["participant"], e["trial"]) for e in res["transfer"]["selected_trials"]]
        assert got == selected and len(res["transfer"]["prototypes"]) == n
        assert "joint_velocities.png" in res["figures"]


def test_identical_trials_cannot_be_clustered_exit_3(tmp_path, capsys, small_frame):
    one = _only(small_frame, _selected_keys(small_frame)[:1])
    data = _write(pd.concat([one.assign(trial=i) for i in range(1, 5)]), tmp_path / "same.csv")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), "--no-figures")
    assert code == 3, err
    res = _results(tmp_path / "o")
    assert res["n_selected"] == 4 and "clusters" not in res
    assert any("1 distinct" in m for m in res["messages"])


def test_every_trial_invalid_still_writes_results(tmp_path, capsys, small_frame):
    few = small_frame.groupby(["participant", "trial"], sort=False).head(3)  # 3 samples per trial
    data = _write(few, tmp_path / "short.csv")
    code, out, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"))
    assert code == 3, err
    res = _results(tmp_path / "o")
    assert res["dataset"]["fs"] is None and len(res["trials"]) == 48
    assert {t["status"] for t in res["trials"]} == {"invalid"}  # no data figure, the segmentation pages only
    assert res["figures"] == ["segmentation-01.png", "segmentation-02.png"]  # 48 trials, 24 a page
    assert "48 x too few samples" in out


def test_recordings_that_start_in_motion_get_a_hint(tmp_path, capsys, small_frame):
    f = trial_features(recordings_from_frame(small_frame)).set_index(["participant", "trial"])["t_onset"]
    onset = small_frame.set_index(["participant", "trial"]).index.map(f).to_numpy()
    late = small_frame[small_frame["t"].to_numpy() > onset + 0.05]  # every recording starts after onset
    data = _write(late, tmp_path / "late.csv")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), "--no-figures")
    assert code == 3, err
    res = _results(tmp_path / "o")
    assert all(t["reason"].startswith("no rest before onset") for t in res["trials"])
    assert any("48 of 48 trials" in m and "low-pass filter" in m for m in res["messages"])


def test_jittered_time_stamps_give_the_nominal_rate(tmp_path, capsys, small_frame):
    rng = np.random.default_rng(1)
    jit = small_frame.assign(t=small_frame["t"] + rng.uniform(-1e-3, 1e-3, len(small_frame)))  # +-1 ms at 100 Hz
    data = _write(jit, tmp_path / "jitter.csv")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), "--no-figures")
    assert code == 0, err
    res = _results(tmp_path / "o")
    assert res["dataset"]["fs"] == pytest.approx(100.0, rel=1e-3)
    assert not any(t["status"] == "invalid" for t in res["trials"])


def test_the_silhouette_sweep_reports_progress(small_frame):
    selected = select(trial_features(recordings_from_frame(small_frame)))
    seen = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        sweep = pt.silhouette_sweep(selected, progress=lambda items, desc: seen.append((desc, items)) or items)
        ref = pt.silhouette_sweep(selected)
    assert seen == [("silhouette", list(sweep.ks))]
    np.testing.assert_allclose(sweep.scores, ref.scores)


# --- file-level problems: exit 2, one line naming the problem ----------------------------------------


def test_missing_file(tmp_path, capsys):
    code, _, err = _run(capsys, "--data", str(tmp_path / "nope.csv"), "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "nope.csv")
    assert not (tmp_path / "o" / "results.json").exists()


def test_empty_file(tmp_path, capsys):
    (tmp_path / "empty.csv").write_text("")
    code, _, err = _run(capsys, "--data", str(tmp_path / "empty.csv"), "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "empty.csv", "empty")


def test_missing_column_is_named(tmp_path, capsys, small_frame):
    data = tmp_path / "nocontact.csv"
    small_frame.drop(columns=["contact"]).to_csv(data, index=False)
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "nocontact.csv", "contact")


def test_cell_that_is_not_a_number_names_line_and_column(tmp_path, capsys, small_frame):
    data = _write(small_frame, tmp_path / "bad.csv")
    lines = data.read_text().splitlines()
    header = lines[0].split(",")
    row = lines[10].split(",")
    row[header.index("y")] = "abc"
    lines[10] = ",".join(row)
    data.write_text("\n".join(lines) + "\n")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "bad.csv", "line 11", "'y'", "abc")


def test_millimetres_are_recognised(tmp_path, capsys, small_frame):
    mm = small_frame.assign(**{c: small_frame[c] * 1000 for c in ("x", "y", "z")})
    data = tmp_path / "mm.csv"
    mm.to_csv(data, index=False)
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "mm.csv", "millimet", "1000")


def test_centimetres_are_recognised(tmp_path, capsys, small_frame):
    data = _write(small_frame.assign(**{c: small_frame[c] * 100 for c in ("x", "y", "z")}), tmp_path / "cm.csv")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "cm.csv", "centimetres", "100")


def test_header_only_file(tmp_path, capsys):
    (tmp_path / "header.csv").write_text("participant,trial,t,x,y,z,contact\n")
    code, _, err = _run(capsys, "--data", str(tmp_path / "header.csv"), "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "header.csv", "no data rows")


def test_milliseconds_are_recognised(tmp_path, capsys, small_frame):
    data = _write(small_frame.assign(t=small_frame["t"] * 1000), tmp_path / "ms.csv")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "ms.csv", "milliseconds", "1000")


def test_participants_at_different_rates_stop_the_run(tmp_path, capsys, small_frame):
    other = generate_cohort(8, CohortModel(n_participants=2, n_trials=12, fs=120.0)).frame
    data = _write(
        pd.concat([small_frame, other.assign(participant="x" + other["participant"])]), tmp_path / "mixed.csv"
    )
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "mixed.csv", "mixed sampling rates", "100 Hz", "120 Hz")


def test_semicolon_separated_file_gets_a_hint(tmp_path, capsys, small_frame):
    """A semicolon file is read (the separator detected); forced to commas with --sep, one line says how
    the line was split and which separator the file seems to use."""
    small_frame.to_csv(tmp_path / "semi.csv", sep=";", index=False)
    code, _, err = _run(capsys, "--data", str(tmp_path / "semi.csv"), "--out", str(tmp_path / "o"), "--sep", ",")
    assert code == 2
    _one_line_error(err, "semi.csv", "participant", "split at commas", "--sep")


def test_bad_options_are_one_line(tmp_path, capsys, small_frame):
    data = _write(small_frame, tmp_path / "rec.csv")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), "--qd-max", "1", "2")
    assert code == 2
    _one_line_error(err, "qd_max", "6 joints")
    for bad in (["--qd-max", "-1"], ["--k", "1"]):
        code, _, err = _run(capsys, "--data", str(tmp_path / "missing.csv"), "--out", str(tmp_path / "o"), *bad)
        assert code == 2  # options are checked before the file is read
        _one_line_error(err, "qd_max" if "--qd-max" in bad else "k must")
    with pytest.raises(SystemExit) as e:  # argparse names the valid robots
        main(["run", "--data", str(data), "--out", str(tmp_path / "o"), "--robot", "r2d2"])
    assert e.value.code == 2
    assert "simple6" in capsys.readouterr().err


# --- the SPARC parameters: used as given, reported as used -----------------------------------------


@pytest.mark.parametrize(
    "opts, params",
    [
        ([], dict(SPARC_PARAMS)),
        (["--fc", "10"], {**SPARC_PARAMS, "fc": 10.0}),
        (["--fc", "15", "--amp-th", "0.1", "--padlevel", "3"], {"fc": 15.0, "amp_th": 0.1, "padlevel": 3}),
    ],
    ids=["default", "fc10", "all-three"],
)
def test_sparc_options_are_used_for_every_trial_and_reported(tmp_path, capsys, small_frame, opts, params):
    """Each valid trial's SPARC, band end and capped flag equal sparc_spectrum of its own segment with the
    parameters the run reports; the capped count in messages is that of the selected trials."""
    data = _write(small_frame, tmp_path / "rec.csv")
    code, out, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), "--no-figures", *opts)
    assert code == 0, err
    res = _results(tmp_path / "o")
    assert res["sparc_params"] == {k: float(v) for k, v in params.items()}
    rec = read_recordings(data)  # as the run read it (positions rounded to 0.01 mm by the writer)
    n_checked = n_capped = 0
    for t in res["trials"]:
        if t["status"] == "invalid":
            assert t["sparc"] is None and t["sparc_band_end_hz"] is None and t["sparc_capped"] is None
            continue
        s = sparc_spectrum(segment(rec, t["participant"], t["trial"]).speed, rec.fs, **params)
        assert t["sparc"] == pytest.approx(s.sparc, abs=1e-9)
        assert t["sparc_band_end_hz"] == pytest.approx(s.cutoff, abs=1e-9) and t["sparc_capped"] is s.capped
        assert t["sparc_band_end_hz"] <= params["fc"]
        n_checked += 1
        n_capped += s.capped and t["status"] == "selected"
    assert n_checked == int((trial_features(rec).status != "invalid").sum()) > 20
    note = [m for m in res["messages"] if "SPARC band ended by fc" in m]
    assert len(note) == 1 and note[0].startswith(f"{n_capped} of {res['n_selected']} selected trials")
    assert f"fc = {params['fc']:g} Hz" in note[0] and "note: " + note[0] in out


def test_sparc_settings_change_the_values_that_depend_on_them_only(tmp_path, capsys, small_frame):
    data = _write(small_frame, tmp_path / "rec.csv")
    runs = {}
    for fc in ("20", "10"):
        assert _run(capsys, "--data", str(data), "--out", str(tmp_path / fc), "--no-figures", "--fc", fc)[0] == 0
        runs[fc] = _results(tmp_path / fc)
    a, b = (pd.DataFrame(runs[fc]["trials"]) for fc in ("20", "10"))
    same = ["participant", "trial", "status", "reason", "pv", "contact_speed", "duration", "ldlj"]
    pd.testing.assert_frame_equal(a[same], b[same])  # segmentation and selection do not use SPARC
    valid = a.status != "invalid"
    assert (a.sparc[valid] != b.sparc[valid]).any() and b.sparc_capped[valid].sum() >= a.sparc_capped[valid].sum()


@pytest.mark.slow
def test_sensitivity_compares_with_the_runs_own_setting(tmp_path, capsys, small_frame):
    data = _write(small_frame, tmp_path / "rec.csv")
    code, out, err = _run(
        capsys,
        "--data",
        str(data),
        "--out",
        str(tmp_path / "o"),
        "--k",
        "3",
        "--sensitivity",
        "fc=10",
        "fc=20,amp_th=0.1",
    )
    assert code == 0, err
    res = _results(tmp_path / "o")
    sens = res["sparc_sensitivity"]
    assert sens["k"] == res["k"] == 3
    assert [s["params"] for s in sens["settings"]] == [
        {"fc": 20.0, "amp_th": 0.05, "padlevel": 4},
        {"fc": 10.0, "amp_th": 0.05, "padlevel": 4},
        {"fc": 20.0, "amp_th": 0.1, "padlevel": 4},
    ]
    ref = sens["settings"][0]
    assert [(p["participant"], p["trial"]) for p in ref["prototypes"]] == [
        (c["prototype"]["participant"], c["prototype"]["trial"]) for c in res["clusters"]
    ]  # the run's own fit
    selected = [t for t in res["trials"] if t["status"] == "selected"]
    rec = read_recordings(data)
    for entry in sens["settings"][1:]:
        changed = sum(
            abs(
                t["sparc"]
                - sparc_spectrum(segment(rec, t["participant"], t["trial"]).speed, rec.fs, **entry["params"]).sparc
            )
            > 1e-9
            for t in selected
        )
        assert entry["vs_reference"]["n_sparc_changed"] == changed
    assert "SPARC sensitivity, against this run's fc 20 Hz" in out and "fc 10 Hz, amp_th 0.05, padlevel 4:" in out
    assert {"sparc_sensitivity.png", "sparc_sensitivity.svg"} <= set(res["figures"])


@pytest.mark.parametrize(
    "opts, words",
    [
        (["--fc", "60"], ("Nyquist", "50 Hz")),
        (["--sensitivity", "fc=80"], ("Nyquist", "fc = 80")),
        (["--fc", "0"], ("fc must",)),
        (["--amp-th", "1.5"], ("amp_th", "between 0 and 1")),
        (["--padlevel", "-1"], ("padlevel", "0 to 10")),
    ],
)
def test_bad_sparc_options_are_one_line(tmp_path, capsys, small_frame, opts, words):
    data = _write(small_frame, tmp_path / "rec.csv")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), *opts)
    assert code == 2
    _one_line_error(err, *words)
    assert not (tmp_path / "o" / "results.json").exists()


def test_bad_sensitivity_settings_are_option_errors(tmp_path, capsys):
    for bad in ("fq=10", "fc=ten"):
        with pytest.raises(SystemExit) as e:
            main(["run", "--out", str(tmp_path / "o"), "--sensitivity", bad])
        assert e.value.code == 2
        assert bad.split("=")[0] in capsys.readouterr().err


# --- trial-level problems: that trial invalid with a reason, the rest processed ----------------------


def _rows(df: pd.DataFrame, p, tr) -> pd.Index:
    return df.index[(df["participant"] == p) & (df["trial"] == tr)]


def test_broken_trials_are_marked_and_the_rest_goes_on(tmp_path, capsys, small_frame):
    df = small_frame.copy()
    keys = df[["participant", "trial"]].drop_duplicates().itertuples(index=False, name=None)
    keys = list(keys)
    (p_back, t_back), (p_nan, t_nan), (p_noc, t_noc), (p_few, t_few), (p_rep, t_rep) = keys[:5]
    i = _rows(df, p_back, t_back)
    df.loc[i[20], "t"] = df.loc[i[18], "t"]  # time goes backwards
    df.loc[_rows(df, p_nan, t_nan)[30:60], "x"] = np.nan  # NaN positions (empty cells): 0.3 s, too long to fill
    df.loc[_rows(df, p_noc, t_noc), "contact"] = 0  # never touches the box
    few = _rows(df, p_few, t_few)
    df = df.drop(few[3:])  # only 3 samples left
    i = _rows(df, p_rep, t_rep)
    df.loc[i[15], "t"] = df.loc[i[14], "t"]  # a repeated time stamp
    (p_inf, t_inf), (p_non, t_non), (p_irr, t_irr), (p_off, t_off) = keys[5:9]
    df.loc[_rows(df, p_inf, t_inf)[25], "z"] = np.inf  # infinite position
    i = _rows(df, p_non, t_non)  # no onset: at rest until contact (a still hand with 0.03 mm tracker noise;
    c = int(np.flatnonzero(df.loc[i, "contact"].to_numpy())[0])  # exact repeats then a step: a frozen marker)
    still = np.random.default_rng(5).normal(0, 3e-5, (c, 3))
    df.loc[i[:c], ["x", "y", "z"]] = df.loc[i[0], ["x", "y", "z"]].to_numpy(dtype=float) + still
    df = df.drop(_rows(df, p_irr, t_irr)[12:16])  # four samples missing in a row: a gap
    i = _rows(df, p_off, t_off)
    df.loc[i, "t"] = df.loc[i[0], "t"] + 2 * (df.loc[i, "t"] - df.loc[i[0], "t"])  # this trial at 50 Hz
    # rows of one trial not contiguous: move the last trial's first row to the top of the file
    p_last, t_last = keys[-1]
    first = _rows(df, p_last, t_last)[0]
    df = pd.concat([df.loc[[first]], df.drop(first)])
    data = _write(df.reset_index(drop=True), tmp_path / "broken.csv")

    code, out, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), "--no-figures")
    assert code == 0, err
    res = _results(tmp_path / "o")
    assert len(res["trials"]) == len(keys), "every input trial appears in results.json"
    by_key = {(t["participant"], t["trial"]): t for t in res["trials"]}
    expected = {
        (p_back, t_back): "backwards",
        (p_nan, t_nan): "nan",
        (p_noc, t_noc): "contact",
        (p_few, t_few): "samples",
        (p_rep, t_rep): "repeat",
        (p_last, t_last): "contiguous",
        (p_inf, t_inf): "infinite",
        (p_non, t_non): "no onset",
        (p_irr, t_irr): "gap in the time stamps",
        (p_off, t_off): "50.0 hz",
    }
    for key, word in expected.items():
        t = by_key[(str(key[0]), str(key[1]))]
        assert t["status"] == "invalid", (key, t)
        assert word in t["reason"].lower(), (key, t["reason"])
        assert t["sparc"] is None and t["pv"] is None
    others = [t for k, t in by_key.items() if k not in {(str(a), str(b)) for a, b in expected}]
    assert any(t["status"] == "selected" for t in others)
    assert "commonest invalid reasons" in out and "invalid: 10" in out


def _plain(v):
    return v.item() if isinstance(v, np.generic) else v


# --- the default run on the committed cohort, with figures --------------------------------------------


@pytest.mark.slow
def test_default_run_writes_results_and_figures(tmp_path):
    out = tmp_path / "cohort"
    proc = subprocess.run(
        [sys.executable, "-m", "skilllib", "run", "--out", str(out), "--quiet"],
        check=False,
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    res = _results(out)
    assert res["dataset"] == {
        "path": "skilllib/datasets/cohort.csv",
        "synthetic": True,
        "n_trials": 1500,
        "n_participants": 10,
        "fs": 60.0,
        "n_resampled": 0,
        "n_repaired": 0,
        "n_repaired_samples": 0,
    }
    svgs = [(out / f).read_text() for f in res["figures"] if f.endswith(".svg")]
    assert all("Synthetic data: the book" in svg for svg in svgs), "every figure of the cohort says it is synthetic"
    assert res["filter"]["cutoff_hz"] is None and res["filter"]["chosen_by"] == "auto: not needed"
    assert res["sparc_params"] == {"fc": 20.0, "amp_th": 0.05, "padlevel": 4.0}
    assert len(res["trials"]) == 1500
    statuses = {t["status"] for t in res["trials"]}
    assert statuses <= {"selected", "excluded", "invalid"}
    assert res["k"] == 6 and set(res["silhouette"]) == {str(k) for k in range(2, 17)}
    ids = {(t["participant"], t["trial"]) for t in res["trials"] if t["status"] == "selected"}
    for c in res["clusters"]:  # prototypes are selected trials, with ids as text, as written in the file
        proto = c["prototype"]
        assert type(proto["participant"]) is str and type(proto["trial"]) is str
        assert (proto["participant"], proto["trial"]) in ids
    pvs = [c["centre"]["pv"] for c in res["clusters"]]
    assert pvs == sorted(pvs) and [c["id"] for c in res["clusters"]] == list(range(6))
    tr = res["transfer"]
    assert tr["robot"] == "Simple6" and tr["q0_deg"] == pytest.approx([0, -60, 120, 90, -90, 30])
    assert len(tr["prototypes"]) == 6
    for p in tr["prototypes"]:
        assert len(p["peak_abs_qd"]) == 6 and p["ik_max_residual_m"] <= 1e-6
        assert p["time_scale"] >= 1
        assert not (p["feasible"] and p["time_scale"] > 1)
        assert p["feasible"] or p["time_scale"] > 1 or p["flags"]
    # the schema table of docs/results.md (sensitivity: an option; trials_file and trial_counts: above 10,000 trials)
    assert set(res) == SCHEMA_KEYS - {"sparc_sensitivity", "trials_file", "trial_counts"}
    assert not any("shrunk" in m or "needs more" in m for m in res["messages"])  # the cohort allows k = 6
    pages = {f"segmentation-{i:02d}.png" for i in range(1, 4)}  # 72 of the 1,500 trials, PNG only
    assert set(res["figures"]) == {f"{n}.{ext}" for n in FIGURES for ext in ("png", "svg")} | pages
    for name in res["figures"]:
        assert (out / name).stat().st_size > 0


@pytest.mark.parametrize("workers", ["0", "-1", "100000"])
def test_workers_out_of_range_are_an_option_error(tmp_path, capsys, small_frame, workers):
    """Issue 23: --workers 0 was accepted and --workers 100000 ran for minutes; both are exit 2 at once,
    before the data are read or the output folder made."""
    data = _write(small_frame, tmp_path / "rec.csv")
    code, _, err = _run(capsys, "--data", str(data), "--out", str(tmp_path / "o"), "--workers", workers)
    assert code == 2
    _one_line_error(err, "workers must be an integer from 1 to")
    assert not (tmp_path / "o").exists()


def test_a_device_is_refused_before_it_is_read(tmp_path, capsys):
    """Issue 23: --data /dev/zero was read into memory until MemoryError (exit 1)."""
    code, _, err = _run(capsys, "--data", "/dev/zero", "--out", str(tmp_path / "o"))
    assert code == 2
    _one_line_error(err, "/dev/zero", "not a regular file")


@pytest.mark.slow  # a subprocess
def test_run_command_runs_the_command_line_in_a_new_process(tmp_path):
    """sk.run_command is what the chapters use to show the command as a user types it."""
    from skilllib.pipeline import run_command

    proc = run_command("--data", str(tmp_path / "missing.csv"), "--out", str(tmp_path / "o"))
    assert proc.returncode == 2 and proc.stderr.startswith("error: ") and "missing.csv" in proc.stderr
