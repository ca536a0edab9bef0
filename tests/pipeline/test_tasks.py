"""The task as data through the command line (issue 24): --start/--end/--split/--select/--features/--task,
the task recorded in results.json and run again from it, and the errors of rules that cannot apply."""

from __future__ import annotations

import functools
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.pipeline import main
from skilllib.recordings import write_recordings

ROOT = Path(__file__).resolve().parents[2]
ADL = ROOT / "data" / "real" / "ue-adl-forward-reach"


@functools.cache
def cohort_frame() -> pd.DataFrame:
    return generate_cohort(0, CohortModel(n_participants=3, n_trials=12)).frame


@pytest.fixture
def cohort_csv(tmp_path) -> Path:
    return write_recordings(cohort_frame(), tmp_path / "rec.csv")


def run_cli(capsys, *args: str) -> tuple[int, dict | None, str, str]:
    code = main(["run", "--quiet", "--no-figures", *map(str, args)])
    out, err = capsys.readouterr()
    idx = list(args).index("--out") + 1 if "--out" in args else None
    path = Path(args[idx]) / "results.json" if idx else None
    res = json.loads(path.read_text()) if path and path.exists() and code in (0, 3) else None
    return code, res, out, err


def test_select_none_clusters_every_valid_trial(capsys, tmp_path, cohort_csv):
    code, res, out, _ = run_cli(capsys, "--data", cohort_csv, "--out", tmp_path / "o", "--select", "none", "--k", "3")
    assert code == 0
    status = [t["status"] for t in res["trials"]]
    assert "excluded" not in status and status.count("selected") == res["n_selected"] > 0
    assert res["selection"] == [] and res["contact_speed_window"] is None
    assert res["task"]["select"]["windows"] == "none"
    assert "selected: every valid trial" in out


def test_several_windows_must_all_hold_and_name_the_failing_feature(capsys, tmp_path, cohort_csv):
    code, res, _, _ = run_cli(
        capsys, "--data", cohort_csv, "--out", tmp_path / "o", "--k", "2",
        "--select", "contact_speed=0.3:0.7", "--select", "pv=0.9:",
    )  # fmt: skip
    assert code in (0, 3)
    trials = [t for t in res["trials"] if t["status"] != "invalid"]
    for t in trials:
        inside = 0.3 <= t["contact_speed"] <= 0.7 and t["pv"] >= 0.9
        assert (t["status"] == "selected") == inside
        if not 0.3 <= t["contact_speed"] <= 0.7:
            assert t["reason"].startswith("contact speed ")
        elif not inside:
            assert t["reason"] == f"peak speed PV {t['pv']:.3f} m/s below 0.9 m/s"
    assert res["selection"] == ["contact_speed=0.3:0.7", "pv=0.9:"]
    assert any(t["reason"] and t["reason"].startswith("peak speed PV") for t in trials)


def test_clustering_features_are_the_users(capsys, tmp_path, cohort_csv):
    code, res, out, _ = run_cli(
        capsys, "--data", cohort_csv, "--out", tmp_path / "o", "--k", "3", "--features", "pv,ldlj,duration"
    )
    assert code == 0
    assert res["task"]["cluster"]["features"] == ["pv", "ldlj", "duration"]
    for c in res["clusters"]:
        assert set(c["centre"]) == {"pv", "ldlj", "duration"}
    sel = [t for t in res["trials"] if t["status"] == "selected"]
    for c in res["clusters"]:  # the prototype is a selected trial, described by the same features
        p = c["prototype"]
        row = next(t for t in sel if (t["participant"], t["trial"]) == (p["participant"], p["trial"]))
        assert row["ldlj"] == pytest.approx(p["ldlj"]) and row["duration"] == pytest.approx(p["duration"])
    assert sum(c["size"] for c in res["clusters"]) == len(sel) and "clustered on pv, ldlj, duration" in out


def test_results_json_runs_the_same_analysis_again(capsys, tmp_path, cohort_csv):
    first = tmp_path / "first"
    code, res, _, _ = run_cli(
        capsys, "--data", cohort_csv, "--out", first, "--k", "3", "--features", "pv,sparc,ldlj",
        "--select", "pv=0.5:", "--scaling", "standard", "--seed", "5", "--fc", "12",
    )  # fmt: skip
    assert code == 0
    again = tmp_path / "again"
    code2, res2, _, _ = run_cli(capsys, "--data", cohort_csv, "--out", again, "--task", first / "results.json")
    assert code2 == 0
    for r in (res, res2):
        r.pop("skilllib_version")
    assert res2 == res


def test_a_task_file_and_the_command_line_over_it(capsys, tmp_path, cohort_csv):
    task = tmp_path / "lab.toml"
    task.write_text('name = "lab"\n[cluster]\nk = 4\nfeatures = ["pv", "ldlj"]\n[select]\nwindows = "none"\n')
    code, res, _, _ = run_cli(capsys, "--data", cohort_csv, "--out", tmp_path / "o", "--task", task, "--k", "2")
    assert code == 0
    assert (
        res["k"] == 2
        and res["task"]["name"] == "lab + options"
        and res["task"]["cluster"]["features"] == ["pv", "ldlj"]
    )
    assert res["selection"] == []


@pytest.mark.parametrize(
    "args, fragment",
    [
        (("--select", "speed=0.3:0.7"), "unknown feature 'speed'"),
        (("--select", "none", "--select", "pv=0.3:"), "'none' selects every valid trial"),
        (("--features", "pv"), "cluster on at least two features"),
        (("--start", "speed:-1"), "the start speed must be a speed above 0 m/s"),
        (("--end", "offset:120%"), "percentage above 0 and below 100"),
        (("--end", "height:0.5"), "is not an end rule: use contact, offset"),
        (("--start", "event:go", "--end", "offset"), "give the offset's threshold"),
        (("--hold", "-1", "--end", "offset"), "hold must be a time of at least 0 s"),
        (("--task", "nosuch"), "no such task file"),
        (("--workers", "1", "--end", "offset"), "computes the paper's segmentation only"),
    ],
)
def test_bad_task_options_exit_2_with_one_line(capsys, tmp_path, cohort_csv, args, fragment):
    code, _, _, err = run_cli(capsys, "--data", cohort_csv, "--out", tmp_path / "o", *args)
    assert code == 2
    assert fragment in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_a_bad_task_file_names_its_line(capsys, tmp_path, cohort_csv):
    task = tmp_path / "bad.toml"
    task.write_text('[segment]\nstart = "speed:5%"\nend = "offset"\nsplitt = true\n')
    code, _, _, err = run_cli(capsys, "--data", cohort_csv, "--out", tmp_path / "o", "--task", task)
    assert code == 2
    assert f"{task}, line 4: [segment] splitt: unknown key; [segment] takes start, end, hold, split" in err


def test_a_rule_that_cannot_apply_is_each_trials_reason(capsys, tmp_path, cohort_csv):
    code, res, _, _ = run_cli(capsys, "--data", cohort_csv, "--out", tmp_path / "o", "--end", "event:touch")
    assert code == 3
    reasons = {t["reason"] for t in res["trials"]}
    assert len(reasons) == 1 and "no event 'touch'" in reasons.pop()


def test_height_rules_on_the_cohorts_own_axis(capsys, tmp_path, cohort_csv):
    """The cohort's reaches go down from y near 0 to a surface at y = -0.094 to -0.119 m: ending them where
    the tip crosses -0.08 m (height-below:-0.08) ends the segments at or before contact: never longer than
    the paper's, and shorter unless the last approach sample is above -0.08 m."""
    code, res, _, _ = run_cli(
        capsys, "--data", cohort_csv, "--out", tmp_path / "o", "--end", "height-below:-0.08", "--select", "none"
    )
    assert code == 0
    code, paper, _, _ = run_cli(capsys, "--data", cohort_csv, "--out", tmp_path / "p", "--select", "none")
    both = [
        (a, b)
        for a, b in zip(res["trials"], paper["trials"], strict=True)
        if a["status"] != "invalid" and b["status"] != "invalid"
    ]
    assert len(both) > 20
    assert all(a["duration"] <= b["duration"] + 1e-12 for a, b in both)
    assert sum(a["duration"] < b["duration"] for a, b in both) > 0.8 * len(both)  # a fast one may cross at contact


@pytest.mark.skipif(not ADL.is_dir(), reason="the real forward reaches are not in data/real")
def test_real_forward_reaches_go_through_in_one_command(capsys, tmp_path):
    """The 160 forward reaches of 16 people (Vicon Nexus exports, no contact signal): the moving hand by the
    marker template, onset and offset at 3 % of the peak, every trial clustered, prototypes, a verdict."""
    code, res, out, err = run_cli(
        capsys, "--data", ADL, "--out", tmp_path / "o", "--marker", "{hand}FTP", "--up-axis", "z",
        "--name-pattern", r"(?P<participant>ADL\d{3})F(?P<trial>(?P<hand>[LR])\d)",
        "--start", "speed:3%", "--end", "offset:3%",
    )  # fmt: skip
    assert code == 0, err
    trials = res["trials"]
    assert len(trials) == 160 and res["dataset"]["n_participants"] == 16
    assert all(t["status"] == "selected" for t in trials) and res["n_selected"] == 160
    assert all(0.4 < t["duration"] < 2.5 and t["contact_speed"] < 0.1 * t["pv"] for t in trials)
    assert res["task"]["segment"] == {
        "start": "speed:3%", "end": "offset:3%", "hold": 0.1, "split": False, "lowpass": "auto"
    }  # fmt: skip
    assert res["task"]["read"]["marker"] == "{hand}FTP" and res["selection"] == []
    assert len(res["transfer"]["prototypes"]) == res["k"] == 6
    assert res["task"]["name"] == "paper + options" and "task paper + options: start speed:3%, end offset:3%" in out


def test_an_upward_reach_stays_upward_on_the_robot(capsys, tmp_path):
    """Segmentation is stated in the recording's own axes, the mapping to the robot apart (issue 24, item 6):
    a lab file with z up holds reaches that rise 0.25 m to a shelf; --up-axis z (the truth) and
    --end height-above:M end them at the shelf, and the tool of the arm rises too (base z up). Before, only
    --up-axis=-y made a height rule fire on an upward reach, and it turned the robot's motion upside down."""
    fs, rows = 100.0, []
    for p in ("A", "B"):
        for k in range(6):
            dur = 0.8 + 0.05 * k + (0.03 if p == "B" else 0.0)
            t = np.arange(int((0.5 + dur + 0.5) * fs)) / fs
            tau = np.clip((t - 0.5) / dur, 0, 1)
            s = 10 * tau**3 - 15 * tau**4 + 6 * tau**5
            z = 0.9 + 0.25 * s  # up, in the lab's z (m)
            x = 0.05 * s  # a little forward
            rows.append(pd.DataFrame({"participant": p, "trial": str(k + 1), "t": t, "x": x, "y": 0.0, "z": z}))
    data = pd.concat(rows)
    data.to_csv(tmp_path / "shelf.csv", index=False)
    code, res, _, err = run_cli(
        capsys, "--data", tmp_path / "shelf.csv", "--out", tmp_path / "o", "--up-axis", "z",
        "--end", "height-above:1.1", "--select", "none", "--k", "2",
    )  # fmt: skip
    assert code == 0, err
    assert all(t["status"] == "selected" for t in res["trials"])
    from skilllib.pipeline import run

    got = run(tmp_path / "shelf.csv", None, end="height-above:1.1", select="none", k=2, read_options={"up_axis": "z"})
    for tr in got.transfers:
        rise = tr.x_base[-1, 2] - tr.x_base[0, 2]
        assert rise > 0.1  # up on the robot (base z), by most of the 0.2 m climbed to 1.1 m
        assert abs(tr.x_base[-1, 2] - tr.x_base[0, 2]) > abs(tr.x_base[-1, 1] - tr.x_base[0, 1])


def test_the_sparc_sensitivity_follows_the_tasks_selection_and_features(capsys, tmp_path, cohort_csv):
    """--sensitivity re-derives each setting's trials with the run's own selection (not the paper's window)
    and clusters the run's features; without sparc among them there is nothing to compare, and it says so."""
    args = ("--data", cohort_csv, "--k", "3", "--select", "pv=0.6:", "--sensitivity", "fc=10")
    code, res, _, err = run_cli(capsys, *args, "--out", tmp_path / "a", "--features", "pv,sparc,ldlj")
    assert code == 0, err
    sens = res["sparc_sensitivity"]
    n_sel = sum(t["status"] == "selected" for t in res["trials"])
    assert [s["n_selected"] for s in sens["settings"]] == [n_sel, n_sel]  # the pv window does not read SPARC
    assert set(sens["settings"][0]["prototypes"][0]) >= {"pv", "sparc", "ldlj"}
    code, res, _, err = run_cli(capsys, *args, "--out", tmp_path / "b", "--features", "pv,ldlj")
    assert code == 0, err
    assert "sparc_sensitivity" not in res
    assert any(
        m.startswith("no SPARC sensitivity analysis: the clustering features (pv, ldlj)") for m in res["messages"]
    )


@pytest.mark.skipif(not (ROOT / "data" / "real" / "pyomeca_markers_analogs.c3d").is_file(), reason="no real C3D")
def test_one_real_reach_to_a_box_gets_a_verdict_without_clusters(capsys, tmp_path):
    """The Vicon reach to a box (pyomeca): the load cell's channel goes negative under load
    (--contact-below); one trial cannot be clustered (exit 3), but it is transferred as it is, with the
    verdict the library gives its segment."""
    import skilllib as sk

    c3d = ROOT / "data" / "real" / "pyomeca_markers_analogs.c3d"
    read = {"marker": "INDEX", "up_axis": "z", "contact_channel": "Voltage.2", "contact_below": True}
    code, res, out, err = run_cli(
        capsys, "--data", c3d, "--out", tmp_path / "o", "--marker", "INDEX", "--up-axis", "z",
        "--contact-channel", "Voltage.2", "--contact-below", "--start", "speed:5%", "--select", "none",
    )  # fmt: skip
    assert code == 3, err
    (trial,) = res["trials"]
    assert trial["status"] == "selected" and trial["contact_speed"] < 0.1 * trial["pv"]  # slowed at the box
    assert "clusters" not in res and res["transfer"]["selected_trials"] == [
        {"participant": trial["participant"], "trial": trial["trial"]}
    ]
    rec = sk.load_recordings(c3d, **read)
    seg = sk.segment(rec, *rec.keys()[0], start=sk.parse_start("speed:5%"), lowpass=sk.run_lowpass(rec))
    arm = sk.get_robot("simple6")
    want = sk.assess(arm.robot, [sk.transfer(arm, seg, cluster=0)], arm.dynamic_limits)[0].summary()
    got = res["transfer"]["prototypes"][0]
    assert got["peak_abs_qd"] == pytest.approx(want["peak_abs_qd"]) and got["feasible"] == want["feasible"]
    assert "selected trial 0: participant pyomeca_markers trial analogs" in out
