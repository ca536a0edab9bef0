"""The default run's results.json is the one of the code before the redesign of issue 21, but for the
renames of schema 2 and the chapters' new numbers: the restructuring changed no number, no trial."""

from __future__ import annotations

import gzip
import json
from pathlib import Path

import pytest

from skilllib.pipeline import run
from skilllib.task import PAPER_TASK

BEFORE = Path(__file__).resolve().parents[1] / "fixtures" / "pipeline" / "results_before_issue21.json.gz"


def schema_2(results: dict, axes: list[float]) -> dict:
    """Schema 1 (before issue 21) in the names of schema 2: ``feasible`` and ``time_scale`` cover every
    limit; the velocity limits' verdict is ``feasible_velocity``."""
    out = {"schema_version": 2, **results}
    # the chapters were renumbered (the sensitivity analysis of chapter 3 is now in chapter 6)
    out["messages"] = [m.replace("--sensitivity, chapter 3)", "--sensitivity, chapter 6)") for m in out["messages"]]
    # real-data defects (stale frames, frozen positions, jumps, gaps) are repaired and reported: keys added,
    # and none fires on the cohort (every count 0, every repairs text empty)
    out["dataset"] = {**out["dataset"], "n_repaired": 0, "n_repaired_samples": 0}
    out["trials"] = [{**t, "repairs": "", "n_repaired": 0} for t in out["trials"]]
    # the noise at rest is measured per axis too (issue 22); the cohort's decision is not borderline
    out["filter"] = {**out["filter"], "position_noise_axes_m": axes, "borderline": False, "alternative_cutoff_hz": None}
    # the task as data (issue 24): the resolved task and the selection's windows are recorded, and two more
    # per-trial features are computed; nothing else changes
    out["selection"] = ["contact_speed=0.3:0.7"]
    out["task"] = PAPER_TASK.to_dict()
    for p in out["transfer"]["prototypes"]:
        p["feasible_velocity"] = p.pop("feasible")
        del p["time_scale"]
        p["time_scale"] = p.pop("time_scale_all_limits")
        p["feasible"] = p.pop("feasible_all_limits")
    return out


@pytest.mark.slow  # the whole default run (about 7 s)
def test_the_default_run_is_unchanged_by_the_redesign(tmp_path):
    run(out=tmp_path / "out", write_figures=False)
    got = json.loads((tmp_path / "out" / "results.json").read_text())
    axes = got["filter"]["position_noise_axes_m"]  # new: the cohort's noise is isotropic, 0.03 mm per axis
    assert len(axes) == 3 and all(abs(a / got["filter"]["position_noise_m"] - 1) < 0.2 for a in axes)
    want = schema_2(json.loads(gzip.decompress(BEFORE.read_bytes())), axes)
    for r in (got, want):
        r.pop("skilllib_version")
    for t in got["trials"]:  # new in issue 24, checked against the per-trial functions in tests/features
        assert (t["peak_acc"] is None) == (t["path_length"] is None) == (t["status"] == "invalid")
        del t["peak_acc"], t["path_length"]
    assert got.keys() == want.keys()
    for key in want:
        assert got[key] == want[key], key
    for g, w in zip(got["transfer"]["prototypes"], want["transfer"]["prototypes"], strict=True):
        assert list(g) == sorted(w, key=list(g).index)  # same keys
    assert sum(p["feasible"] for p in got["transfer"]["prototypes"]) < sum(
        p["feasible_velocity"] for p in got["transfer"]["prototypes"]
    )  # on the cohort acceleration binds: the two verdicts differ, so a swap of the names would show
