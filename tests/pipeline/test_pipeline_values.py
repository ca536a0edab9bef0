"""What `skilllib.pipeline.run` (and `python -m skilllib run`) computes, not only the shape of it.

Every number of results.json is compared with a direct call of the library on the same recordings file:
:func:`skilllib.recordings.read_recordings` + :func:`skilllib.features.trial_features` for the trials,
:func:`skilllib.prototypes.silhouette_sweep` / :func:`~skilllib.prototypes.fit_prototypes` for the
clustering, :func:`skilllib.robot.transfer` on each prototype's own segment for the transfer and
:func:`skilllib.robot.assess_one` for its dynamics, limits and execution. Then each
option is changed on its own: what depends on it must change as the direct calls say, everything else
must stay identical. Finally the thresholds of the messages are probed at both sides of their edge, with
the library's own constants.

The files are small (at most 80 trials). The module took about 20 s on a quiet 2-core VM before the
transfer gained dynamics and execution (issue 14), and 50 to 60 s on a busy one after: some 35 silhouette
sweeps (0.3 s each; run() always sweeps k = 2..16), one run with figures (5 s), and the direct
assessments the transfer block is checked against.
"""

from __future__ import annotations

import copy
import json
import math
import warnings
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.features import CONTACT_WINDOW, segment, select, trial_features
from skilllib.pipeline import MANIFEST, main
from skilllib.pipeline import _run as pipeline
from skilllib.prototypes import _kmeans as pt
from skilllib.prototypes import sparc_sensitivity
from skilllib.recordings import read_recordings, recordings_from_frame, write_recordings
from skilllib.robot import assess_one, dynamic_limits, get_robot, transfer
from skilllib.smoothness import DEFAULT_AMP_TH, DEFAULT_FC, DEFAULT_PADLEVEL, SPARC_PARAMS

REL = 1e-12  # floats that pass through JSON (repr round-trips exactly; this only allows for rounding)
FEATURES = ("pv", "contact_speed", "duration", "sparc", "sparc_band_end_hz", "ldlj", "peak_acc", "path_length")
TRIAL_KEYS = {
    "participant",
    "trial",
    "status",
    "reason",
    *FEATURES,
    "sparc_capped",
    "resampled",
    "repairs",
    "n_repaired",
}
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
#: The base file: 5 participants x 16 trials at 60 Hz; its 27 selected trials make k = 6 silhouette-valid
#: without shrinking the sweep, and K-means with random_state 1 partitions them differently from 0.
BASE_SEED, BASE_MODEL = 9, CohortModel(n_participants=5, n_trials=16, fs=60.0)


# --- helpers -----------------------------------------------------------------------------------------


def _reject_constant(name: str) -> Any:
    raise AssertionError(f"results.json contains {name}: not JSON, docs/results.md promises null")


def _load(out: Path) -> dict:
    return json.loads((out / "results.json").read_text(), parse_constant=_reject_constant)


def _json(obj: Any) -> Any:
    """``obj`` as it reads back from results.json."""
    return json.loads(json.dumps(obj, allow_nan=False))


def _py(v: Any) -> Any:
    return v.item() if isinstance(v, np.generic) else v


def _missing(v: Any) -> bool:
    return v is None or v is pd.NA or (isinstance(v, float) and math.isnan(v))


def _num(got: Any, want: Any, what: str) -> None:
    """``got`` (from results.json) is the number ``want`` to float round trip, or null when it is missing."""
    if _missing(want):
        assert got is None, f"{what}: expected null, got {got!r}"
        return
    assert isinstance(got, (int, float)) and not isinstance(got, bool), f"{what}: {got!r} is not a number"
    assert got == pytest.approx(float(want), rel=REL, abs=0), f"{what}: {got!r} != {want!r}"


def _same(got: Any, want: Any, what: str = "value") -> None:
    """Deep comparison of JSON-like data: structure and non-floats exact, floats to ``REL``."""
    if isinstance(want, dict):
        assert isinstance(got, dict) and set(got) == set(want), f"{what}: keys {sorted(got)} != {sorted(want)}"
        for key in want:
            _same(got[key], want[key], f"{what}.{key}")
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), f"{what}: {got!r} != {want!r}"
        for i, (g, w) in enumerate(zip(got, want)):
            _same(g, w, f"{what}[{i}]")
    elif isinstance(want, float) and not isinstance(want, bool):
        _num(got, want, what)
    else:
        assert got == want and type(got) is type(want), f"{what}: {got!r} != {want!r}"


def _without(res: dict, *paths: str) -> dict:
    """A deep copy of ``res`` without the keys at the given paths (``"transfer.qd_limits"``,
    ``"transfer.prototypes.*.feasible"``: ``*`` for every item of a list), and without ``task``, the record
    of the options themselves (test_the_task_block_records_each_option)."""
    res = copy.deepcopy(res)
    res.pop("task", None)
    for path in paths:
        _drop(res, path.split("."))
    return res


def _drop(node: Any, parts: list[str]) -> None:
    head, rest = parts[0], parts[1:]
    if head == "*":
        for item in node:
            _drop(item, rest)
    elif not rest:
        node.pop(head, None)
    elif head in node:
        _drop(node[head], rest)


@dataclass
class Direct:
    """The library called directly on a recordings file with one set of options."""

    rec: Any
    params: dict
    feats: pd.DataFrame
    sel: pd.DataFrame
    sweep: pt.SilhouetteSweep | None


def _direct(
    rec, params: dict | None = None, scaling: str = "raw", random_state: int = 0, feats: pd.DataFrame | None = None
) -> Direct:
    params = {**SPARC_PARAMS, **(params or {})}
    feats = trial_features(rec, sparc_params=params) if feats is None else feats
    sel = select(feats)
    sweep = None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)
            sweep = pt.silhouette_sweep(sel, scaling=scaling, random_state=random_state)
    except ValueError:  # too few (distinct) selected trials
        pass
    return Direct(rec, params, feats, sel, sweep)


def _write(df: pd.DataFrame, path: Path) -> Path:
    write_recordings(df, path)
    return path


def _only(df: pd.DataFrame, keys: list[tuple]) -> pd.DataFrame:
    idx = pd.MultiIndex.from_frame(df[["participant", "trial"]])
    return df[idx.isin(keys)]


def _keys(feats: pd.DataFrame, status: str) -> list[tuple]:
    return list(feats.loc[feats["status"] == status, ["participant", "trial"]].itertuples(index=False, name=None))


def _start_in_motion(df: pd.DataFrame, key: tuple, t_onset: float) -> pd.DataFrame:
    """Drop the samples of trial ``key`` up to 50 ms after its onset: the recording starts in motion."""
    mine = (df["participant"] == key[0]) & (df["trial"] == key[1])
    return df[~mine | (df["t"] > t_onset + 0.05)]


# --- the checks: results.json against the direct calls ----------------------------------------------


def check_trials(res: dict, d: Direct) -> None:
    """Every trial's ids, status, reason and features as trial_features gives them; null, never "" or NaN,
    for what is missing; reason null exactly when selected."""
    f = d.feats
    assert len(res["trials"]) == len(f) == res["dataset"]["n_trials"]
    for i, (entry, row) in enumerate(zip(res["trials"], f.to_dict(orient="records"))):
        what = f"trials[{i}] ({row['participant']}, {row['trial']})"
        assert set(entry) == TRIAL_KEYS, what
        assert entry["participant"] == row["participant"] and type(entry["participant"]) is str, what
        assert entry["trial"] == row["trial"] and type(entry["trial"]) is str, what
        assert entry["resampled"] is bool(row["resampled"]), what
        assert entry["repairs"] == row["repairs"] and entry["n_repaired"] == row["n_repaired"], what
        assert entry["status"] == row["status"], what
        if row["status"] == "selected":
            assert entry["reason"] is None, f"{what}: a selected trial's reason must be null"
        else:
            assert isinstance(entry["reason"], str) and entry["reason"] != "", what
            assert entry["reason"] == row["reason"], what
        for c in FEATURES:
            if row["status"] != "invalid":
                assert not _missing(row[c]), what  # valid trials have every feature
            _num(entry[c], row[c], f"{what}.{c}")
        if row["status"] == "invalid":
            assert entry["sparc_capped"] is None, what
        else:
            assert entry["sparc_capped"] is bool(row["sparc_capped"]), what
    assert res["n_selected"] == len(d.sel)
    assert res["sparc_params"] == {key: float(v) for key, v in d.params.items()}
    assert res["contact_speed_window"] == list(CONTACT_WINDOW)
    assert res["dataset"]["n_participants"] == f["participant"].nunique()
    _num(res["dataset"]["fs"], d.rec.fs, "dataset.fs")


def check_clustering(res: dict, d: Direct, k: int, scaling: str = "raw", random_state: int = 0) -> pt.PrototypeResult:
    """silhouette, silhouette_valid_k, k, scaling and clusters as the direct sweep and a direct
    fit_prototypes at that k give them; returns the direct fit."""
    sweep = d.sweep
    assert list(res["silhouette"]) == [str(int(kk)) for kk in sweep.ks]
    for kk, score in zip(sweep.ks, sweep.scores):
        _num(res["silhouette"][str(int(kk))], score, f"silhouette[{kk}]")
    assert res["silhouette_valid_k"] == sweep.valid_ks()
    assert res["k"] == k and res["scaling"] == scaling
    fit = pt.fit_prototypes(d.sel, k, scaling=scaling, random_state=random_state)
    assert np.array_equal(fit.labels, sweep.results[k].labels)
    assert len(res["clusters"]) == k
    by_id = {(t["participant"], t["trial"]): t for t in res["trials"]}
    for c, entry in enumerate(res["clusters"]):
        assert set(entry) == {"id", "size", "centre", "prototype"}
        assert entry["id"] == c
        assert entry["size"] == int(np.sum(fit.labels == c))
        _num(entry["centre"]["pv"], fit.centres.at[c, "pv"], f"clusters[{c}].centre.pv")
        _num(entry["centre"]["sparc"], fit.centres.at[c, "sparc"], f"clusters[{c}].centre.sparc")
        proto = entry["prototype"]
        want_id = (_py(fit.prototypes.at[c, "participant"]), _py(fit.prototypes.at[c, "trial"]))
        assert (proto["participant"], proto["trial"]) == want_id, f"cluster {c}"
        assert type(proto["participant"]) is str and type(proto["trial"]) is str
        _num(proto["pv"], fit.prototypes.at[c, "pv"], f"clusters[{c}].prototype.pv")
        _num(proto["sparc"], fit.prototypes.at[c, "sparc"], f"clusters[{c}].prototype.sparc")
        trial = by_id[want_id]  # the prototype is a selected trial with the features the run reports for it
        assert trial["status"] == "selected"
        assert (proto["pv"], proto["sparc"]) == (trial["pv"], trial["sparc"])
    assert sum(c["size"] for c in res["clusters"]) == res["n_selected"]
    return fit


def check_transfer(
    res: dict,
    d: Direct,
    fit: pt.PrototypeResult,
    robot: str = "simple6",
    qd_limits: Any = None,
    qdd_limits: Any = None,
    tau_limits: Any = None,
) -> None:
    """The transfer block: the robot, its q0, the limits, and per cluster (in cluster order) the summary of
    transfer() on that cluster's own prototype segment, assessed (dynamics, every limit, execution) by
    assess_one with the limits and SPARC parameters of the run."""
    setup = get_robot(robot)
    tr = res["transfer"]
    n = setup.q0.size
    want_lim = setup.qd_limits if qd_limits is None else np.broadcast_to(np.asarray(qd_limits, float), (n,))
    book = dynamic_limits(robot)
    want_qdd = book.qdd_limits if qdd_limits is None else np.broadcast_to(np.asarray(qdd_limits, float), (n,))
    want_tau = book.tau_limits if tau_limits is None else np.broadcast_to(np.asarray(tau_limits, float), (n,))
    assert tr["robot"] == setup.robot.name
    assert tr["q0_deg"] == pytest.approx(np.rad2deg(setup.q0), abs=1e-9)
    assert tr["qd_limits"] == [float(v) for v in want_lim]
    assert tr["qdd_limits"] == (None if want_qdd is None else [float(v) for v in want_qdd])
    assert tr["tau_limits"] == (None if want_tau is None else [float(v) for v in want_tau])
    assert tr["execution"] == {"control_rate_hz": 500.0, "actuator_bandwidth_hz": 100.0}
    limits = get_robot(robot, qdd_max=qdd_limits, tau_max=tau_limits).dynamic_limits
    assert [p["cluster"] for p in tr["prototypes"]] == list(range(fit.k))
    for c, entry in enumerate(tr["prototypes"]):
        seg = segment(d.rec, _py(fit.prototypes.at[c, "participant"]), _py(fit.prototypes.at[c, "trial"]))
        r = transfer(
            setup.robot,
            seg.t - seg.t[0],
            seg.pos,
            seg.vel,
            q0=setup.q0,
            qd_limits=np.asarray(tr["qd_limits"]),
            cluster=c,
        )
        want = assess_one(setup.robot, r, limits, sparc_params=d.params).summary()
        assert len(entry["peak_abs_qd"]) == len(entry["peak_abs_qdd"]) == setup.robot.n
        _same(entry, _json(want), f"transfer.prototypes[{c}]")


MESSAGE_KINDS = {
    "capped": lambda m: "SPARC band ended by fc" in m,
    "shrunk": lambda m: m.startswith("silhouette sweep shrunk"),
    "k reduced": lambda m: "needs more distinct selected trials" in m,
    "not valid": lambda m: "is not silhouette-valid" in m,
    "too few": lambda m: m.startswith("only ") and "clustering needs at least" in m,
    "no rest": lambda m: "'no rest before onset'" in m,
    "unknown rate": lambda m: "sampling rate is unknown" in m,
    "no sensitivity": lambda m: m.startswith("no SPARC sensitivity"),
}


def check_messages(res: dict, d: Direct, k_requested: int, **extra: int) -> None:
    """Each kind of message exactly as often as its condition holds (0 or 1), no other message; the
    capped count that of the direct features. ``extra``: counts of kinds the caller expects beyond those."""
    msgs = res["messages"]
    n_sel = len(d.sel)
    want = {kind: 0 for kind in MESSAGE_KINDS}
    want["capped"] = int(n_sel > 0)
    if d.sweep is not None and n_sel >= pipeline.MIN_SELECTED:
        largest = int(d.sweep.ks[-1])
        want["shrunk"] = int(largest < pt.K_RANGE[1])
        want["k reduced"] = int(k_requested > largest)
        want["not valid"] = int(not d.sweep.results[min(k_requested, largest)].valid)
    want.update(extra)
    got = {kind: sum(map(test, msgs)) for kind, test in MESSAGE_KINDS.items()}
    assert got == want, msgs
    assert len(msgs) == sum(want.values()), msgs
    if n_sel:
        n_capped = int(d.sel["sparc_capped"].sum())
        note = next(m for m in msgs if MESSAGE_KINDS["capped"](m))
        assert note.startswith(
            f"{n_capped} of {n_sel} selected trials have their SPARC band ended by "
            f"fc = {d.params['fc']:g} Hz rather than by the amplitude threshold "
            f"{d.params['amp_th']:g}"
        ), note


def check_all(
    res: dict,
    d: Direct,
    k_requested: int = pt.DEFAULT_K,
    scaling: str = "raw",
    random_state: int = 0,
    robot: str = "simple6",
    qd_limits: Any = None,
    qdd_limits: Any = None,
    tau_limits: Any = None,
) -> pt.PrototypeResult:
    check_trials(res, d)
    k = min(k_requested, int(d.sweep.ks[-1]))
    fit = check_clustering(res, d, k, scaling, random_state)
    check_transfer(res, d, fit, robot, qd_limits, qdd_limits, tau_limits)
    check_messages(res, d, k_requested)
    return fit


# --- fixtures ----------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def cohort_frame() -> pd.DataFrame:
    """The base cohort with string participant ids ("P1".."P5")."""
    fr = generate_cohort(BASE_SEED, BASE_MODEL).frame
    return fr.assign(participant="P" + fr["participant"].astype(str))


@pytest.fixture(scope="module")
def cohort_features(cohort_frame) -> pd.DataFrame:
    return trial_features(recordings_from_frame(cohort_frame))


@pytest.fixture(scope="module")
def base_file(tmp_path_factory, cohort_frame, cohort_features) -> Path:
    """The base cohort with three of its excluded trials made invalid: a gap of NaN positions during the
    approach too long to fill (found by the reader), a recording that starts in motion and one that never
    touches (found by the segmentation)."""
    df = cohort_frame.copy()
    f = cohort_features
    (p1, t1), (p2, t2), (p3, t3) = _keys(f, "excluded")[:3]
    rows = df.index[(df["participant"] == p1) & (df["trial"] == t1)]
    onset = int(
        np.searchsorted(
            df.loc[rows, "t"].to_numpy(), float(f.loc[(f["participant"] == p1) & (f["trial"] == t1), "t_onset"].iloc[0])
        )
    )
    df.loc[rows[onset + 1 : onset + 12], "x"] = np.nan  # 11 samples (0.18 s) in the movement: not filled
    df.loc[(df["participant"] == p3) & (df["trial"] == t3), "contact"] = 0
    t_onset = float(f.loc[(f["participant"] == p2) & (f["trial"] == t2), "t_onset"].iloc[0])
    df = _start_in_motion(df, (p2, t2), t_onset)
    return _write(df.reset_index(drop=True), tmp_path_factory.mktemp("data") / "base.csv")


@pytest.fixture(scope="module")
def base_rec(base_file):
    return read_recordings(base_file)


@pytest.fixture(scope="module")
def direct(base_rec):
    """direct(params=None, scaling="raw", random_state=0): the direct calls on the base file, cached."""
    cache: dict = {}
    features: dict = {}

    def get(params: dict | None = None, scaling: str = "raw", random_state: int = 0) -> Direct:
        p = repr(sorted({**SPARC_PARAMS, **(params or {})}.items()))
        if (p, scaling, random_state) not in cache:
            d = _direct(base_rec, params, scaling, random_state, feats=features.get(p))
            features[p] = d.feats
            cache[(p, scaling, random_state)] = d
        return cache[(p, scaling, random_state)]

    return get


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """runs(path, **options): results.json (as read back), the PipelineRun and the output folder of
    run(path, out, ...) without figures, cached per file and options."""
    cache: dict = {}

    def get(path: Path, **opts: Any) -> tuple[dict, pipeline.PipelineRun, Path]:
        key = (str(path), repr(sorted(opts.items())))
        if key not in cache:
            out = tmp_path_factory.mktemp("run")
            result = pipeline.run(path, out, write_figures=False, **opts)
            cache[key] = (_load(out), result, out)
        return cache[key]

    return get


@pytest.fixture(scope="module")
def base(runs, base_file) -> dict:
    return runs(base_file)[0]


@pytest.fixture(scope="module")
def eight_selected(tmp_path_factory, cohort_frame, cohort_features) -> tuple[Path, Direct]:
    """8 selected and 2 excluded trials of the base cohort: the sweep reaches k = 7 only."""
    f = cohort_features
    keys = _keys(f, "selected")[:8] + _keys(f, "excluded")[:2]
    data = _write(_only(cohort_frame, keys), tmp_path_factory.mktemp("k") / "eight.csv")
    return data, _direct(read_recordings(data))


# --- value tests: the default run against the direct calls -------------------------------------------


def test_the_base_file_is_what_the_tests_need(direct):
    """Preconditions of the tests below (not of the library): invalid trials of both kinds, excluded and
    selected ones, an unshrunk sweep in which the default k is valid, capped bands among the selected and
    among the excluded trials."""
    d = direct()
    reasons = d.feats.loc[d.feats["status"] == "invalid", "reason"].tolist()
    assert len(reasons) == 3
    assert any("missing (NaN)" in r for r in reasons) and any(r.startswith("no rest before onset") for r in reasons)
    assert any(r.startswith("no contact") for r in reasons)
    assert (d.feats["status"] == "excluded").sum() > 10 and len(d.sel) > pt.K_RANGE[1]
    assert not d.sweep.shrunk and d.sweep.results[pt.DEFAULT_K].valid
    capped = d.feats["sparc_capped"].fillna(False).astype(bool)
    assert 0 < d.sel["sparc_capped"].sum() < capped.sum()  # a count over the valid trials would differ


def test_trials_are_those_of_trial_features(base, direct):
    """Catches: a feature computed with other parameters or from another trial, a status or reason that
    differs, "" or NaN instead of null, a reason for a selected trial, ids of another type."""
    check_trials(base, direct())
    assert base["dataset"]["path"].endswith("base.csv")


def test_clusters_are_those_of_the_direct_sweep_and_fit(base, direct):
    """Catches: silhouettes of another k or fit, a wrong valid-k list, clusters out of PV order, a size,
    centre or prototype of another cluster, a prototype's features not those of its trial."""
    fit = check_clustering(base, direct(), pt.DEFAULT_K)
    pvs = [c["centre"]["pv"] for c in base["clusters"]]
    assert pvs == sorted(pvs)
    assert len({(c["prototype"]["participant"], c["prototype"]["trial"]) for c in base["clusters"]}) == fit.k


def test_transfer_is_that_of_each_prototypes_own_segment(base, direct):
    """Catches: a cluster handed another prototype's trajectory (or clusters out of order), the transfer of
    the whole recording instead of the segment, another q0 or limits than reported, a summary value
    computed otherwise."""
    d = direct()
    fit = check_clustering(base, d, pt.DEFAULT_K)
    check_transfer(base, d, fit)
    peaks = [tuple(p["peak_abs_qd"]) for p in base["transfer"]["prototypes"]]
    assert len(set(peaks)) == len(peaks)  # distinct per prototype: a swapped trajectory cannot pass


def test_a_normal_run_has_only_the_capped_note(base, direct):
    """Catches: a spurious "k reduced", "shrunk", "not valid", "too few" or "no rest" message; the capped
    count taken over the wrong trials or repeated."""
    check_messages(base, direct(), pt.DEFAULT_K)
    assert len(base["messages"]) == 1


def test_results_json_is_the_returned_dictionary(runs, base_file, base):
    """Catches: a results.json that differs from what run() returns (e.g. written before a section is set)."""
    assert base == _json(runs(base_file)[1].results)


# --- one option at a time ----------------------------------------------------------------------------

UNCHANGED_BY_CLUSTERING = ("dataset", "sparc_params", "contact_speed_window", "trials", "n_selected")


def test_k_changes_the_clusters_and_their_transfer_only(runs, base_file, base, direct):
    """k = 7 (not silhouette-valid here): trials and silhouettes identical, clusters and transfer those of
    the direct fit at 7, and the not-valid note naming the valid k. Catches: k ignored, the sweep redone
    differently, a missing or spurious note."""
    d = direct()
    assert not d.sweep.results[7].valid
    res = runs(base_file, k=7)[0]
    for key in (*UNCHANGED_BY_CLUSTERING, "silhouette", "silhouette_valid_k", "scaling"):
        assert res[key] == base[key], key
    assert _without(res["transfer"], "prototypes") == _without(base["transfer"], "prototypes")
    check_all(res, d, k_requested=7)
    note = [m for m in res["messages"] if "is not silhouette-valid" in m]
    assert note[0].startswith("k = 7 ") and f"valid k: {', '.join(map(str, d.sweep.valid_ks()))} " in note[0]
    assert [m for m in res["messages"] if m not in note] == base["messages"]


def test_robot_changes_the_transfer_only(runs, base_file, base, direct):
    """The Panda (7 joints, its own q0 and per-joint limits): everything before the transfer identical, the
    transfer that of the Panda. Catches: the robot name reported but Simple6 used, Simple6's q0 or limits."""
    res = runs(base_file, robot="panda")[0]
    assert _without(res, "transfer") == _without(base, "transfer")
    d = direct()
    fit = check_clustering(res, d, pt.DEFAULT_K)
    check_transfer(res, d, fit, robot="panda")
    assert res["transfer"]["qd_limits"] != base["transfer"]["qd_limits"]
    assert all(len(p["peak_abs_qd"]) == 7 for p in res["transfer"]["prototypes"])


def _expected_feasibility(base: dict, lim: np.ndarray) -> tuple[list[bool], list[float]]:
    """Whether the velocity limits ``lim`` (rad/s, per joint) hold, and the stretch they ask for
    (time_scales.velocity), for the base run's prototypes."""
    within, scale = [], []
    for p in base["transfer"]["prototypes"]:
        peak = np.asarray(p["peak_abs_qd"], dtype=float)
        assert np.all(np.abs(peak / lim - 1) > 1e-6)  # no peak at a limit, where tolerances would decide
        within.append(bool(np.all(peak <= lim * (1 + 1e-9))))
        scale.append(float(max(1.0, np.max(peak / lim))))
    return within, scale


def _check_limits_change_only_feasibility(res: dict, base: dict, lim: np.ndarray, d: Direct) -> None:
    """Only what depends on the velocity limits changed: feasible_velocity (the velocity limits' own verdict)
    and time_scales.velocity are peak / limit, time_scale (every limit) the larger of it and the
    (unchanged) acceleration stretch (Simple6 has no torques), feasible exactly when that is 1,
    the binding limit the one that asks for more; the executions are those of the direct calls."""
    varying = (
        "transfer.qd_limits",
        "transfer.prototypes.*.feasible_velocity",
        "transfer.prototypes.*.time_scales.velocity",
        "transfer.prototypes.*.binding_limit",
        "transfer.prototypes.*.feasible",
        "transfer.prototypes.*.time_scale",
        "transfer.prototypes.*.executed",
        "transfer.prototypes.*.executed_time_scaled",
    )
    assert _without(res, *varying) == _without(base, *varying)  # peaks, det J, cond J, flags, clusters, ...
    assert res["transfer"]["qd_limits"] == [float(v) for v in lim]
    within, scale = _expected_feasibility(base, lim)
    for i, (p, p0, s_v, ok) in enumerate(
        zip(res["transfer"]["prototypes"], base["transfer"]["prototypes"], scale, within)
    ):
        _num(p["time_scales"]["velocity"], s_v, f"time_scales.velocity[{i}]")
        assert p["feasible_velocity"] is (not p["flags"] and ok)
        s_a = p0["time_scales"]["acceleration"]
        _num(p["time_scale"], max(s_v, s_a), f"time_scale[{i}]")
        assert p["feasible"] is (not p["flags"] and max(s_v, s_a) == 1.0)
        assert p["binding_limit"] == (None if max(s_v, s_a) == 1.0 else "velocity" if s_v > s_a else "acceleration")
    check_transfer(res, d, check_clustering(res, d, pt.DEFAULT_K), qd_limits=lim)


def test_scalar_qd_max_changes_feasibility_and_time_scale_only(runs, base_file, base, direct):
    """A limit between the prototypes' peaks: those above it need time_scales.velocity = peak / limit, and
    the velocity binds where that exceeds the acceleration's stretch. Catches: qd_max ignored (or reported
    but not used), peaks that depend on the limit, the velocity stretch not combined with the others."""
    peaks = sorted(max(p["peak_abs_qd"]) for p in base["transfer"]["prototypes"])
    qd = (peaks[len(peaks) // 2 - 1] + peaks[len(peaks) // 2]) / 2
    assert all(p["time_scales"]["velocity"] == 1.0 for p in base["transfer"]["prototypes"])
    res = runs(base_file, qd_max=qd)[0]
    lim = np.full(6, qd)
    _check_limits_change_only_feasibility(res, base, lim, direct())
    within = [p["time_scales"]["velocity"] == 1.0 for p in res["transfer"]["prototypes"]]
    assert any(within) and not all(within)
    slow = runs(base_file, qd_max=peaks[0] / 3)[0]  # a third of the smallest peak: s_v >= 3 everywhere
    _check_limits_change_only_feasibility(slow, base, np.full(6, peaks[0] / 3), direct())
    assert {p["binding_limit"] for p in slow["transfer"]["prototypes"]} == {"velocity"}


def test_per_joint_qd_max_applies_each_limit_to_its_joint(runs, base_file, base, direct):
    """Limits that differ per joint (each joint's median peak over the prototypes). Catches: the limits
    applied to the wrong joints (reversed, or the first one for all), the largest or smallest used."""
    peaks = np.array([p["peak_abs_qd"] for p in base["transfer"]["prototypes"]])
    lim = np.median(peaks, axis=0)
    assert np.all(lim > 0) and len(np.unique(lim)) == lim.size
    expected = _expected_feasibility(base, lim)
    for wrong in (lim[::-1], np.full(6, lim[0]), np.full(6, lim.max()), np.full(6, lim.min())):
        assert _expected_feasibility(base, wrong) != expected  # each such defect would be seen
    res = runs(base_file, qd_max=list(lim))[0]
    _check_limits_change_only_feasibility(res, base, lim, direct())


def test_qdd_max_changes_the_acceleration_stretch_only(runs, base_file, base, direct):
    """An acceleration limit between the prototypes' peak accelerations: the acceleration stretch is
    sqrt(peak / limit), everything computed before the limits identical. Catches: qdd_max ignored or
    applied as a velocity limit (no square root), the book's 5 rad/s^2 used anyway."""
    peaks = sorted(max(p["peak_abs_qdd"]) for p in base["transfer"]["prototypes"])
    qdd = (peaks[1] + peaks[2]) / 2
    res = runs(base_file, qdd_max=qdd)[0]
    varying = (
        "transfer.qdd_limits",
        "transfer.prototypes.*.feasible",
        "transfer.prototypes.*.time_scale",
        "transfer.prototypes.*.time_scales.acceleration",
        "transfer.prototypes.*.binding_limit",
        "transfer.prototypes.*.executed",
        "transfer.prototypes.*.executed_time_scaled",
    )
    assert _without(res, *varying) == _without(base, *varying)
    assert res["transfer"]["qdd_limits"] == [qdd] * 6
    for i, p in enumerate(res["transfer"]["prototypes"]):
        _num(p["time_scales"]["acceleration"], max(1.0, np.sqrt(max(p["peak_abs_qdd"]) / qdd)), f"[{i}]")
    assert sum(p["time_scales"]["acceleration"] == 1.0 for p in res["transfer"]["prototypes"]) == 2
    d = direct()
    check_transfer(res, d, check_clustering(res, d, pt.DEFAULT_K), qdd_limits=qdd)


def test_torques_and_tau_max_on_the_puma(runs, base_file, base, direct):
    """The Puma 560 (dynamic parameters): torques, the book's torque limits and no acceleration limit; with
    torque limits below the prototypes' peaks the torque binds, at the stretch assess_one finds. Catches:
    tau_max ignored, torques of another arm, torque limits reported but not applied."""
    d = direct()
    res = runs(base_file, robot="puma560")[0]
    fit = check_clustering(res, d, pt.DEFAULT_K)
    check_transfer(res, d, fit, robot="puma560")
    assert res["transfer"]["qdd_limits"] is None and res["transfer"]["tau_limits"][1] == 186.4
    assert all(len(p["peak_abs_tau"]) == 6 for p in res["transfer"]["prototypes"])
    tau = np.max([p["peak_abs_tau"] for p in res["transfer"]["prototypes"]], axis=0) * 0.8
    low = runs(base_file, robot="puma560", tau_max=list(tau))[0]
    check_transfer(low, d, fit, robot="puma560", tau_limits=tau)
    assert "torque" in {p["binding_limit"] for p in low["transfer"]["prototypes"]}
    assert base["transfer"]["tau_limits"] is None and base["transfer"]["prototypes"][0]["peak_abs_tau"] is None


def test_scaling_changes_the_clustering_as_fit_prototypes_does(runs, base_file, base, direct):
    """scaling = "standard": trials identical, silhouettes, clusters and transfer those of the direct
    standard-scaled sweep (centres still in m/s and SPARC units). Catches: scaling reported but raw used."""
    d = direct(scaling="standard")
    assert d.sweep.to_dict() != direct().sweep.to_dict()
    res = runs(base_file, scaling="standard")[0]
    for key in UNCHANGED_BY_CLUSTERING:
        assert res[key] == base[key], key
    check_all(res, d, scaling="standard")
    assert res["silhouette"] != base["silhouette"]


def test_random_state_changes_the_clustering_as_fit_prototypes_does(runs, base_file, base, direct):
    """random_state = 1: trials identical, silhouettes and clusters those of K-means with that seed, which
    here differ from seed 0's. Catches: the seed ignored (or used for the sweep but not the chosen fit)."""
    d = direct(random_state=1)
    assert not np.array_equal(d.sweep.results[pt.DEFAULT_K].labels, direct().sweep.results[pt.DEFAULT_K].labels)
    res = runs(base_file, random_state=1)[0]
    for key in (*UNCHANGED_BY_CLUSTERING, "k", "scaling"):
        assert res[key] == base[key], key
    check_all(res, d, random_state=1)
    assert res["silhouette"] != base["silhouette"] and res["clusters"] != base["clusters"]


@pytest.mark.parametrize("params", [{"fc": 10.0}, {"amp_th": 0.1}, {"padlevel": 2}], ids=["fc", "amp_th", "padlevel"])
def test_sparc_parameters_reach_the_clustering_and_transfer(runs, base_file, base, direct, params):
    """The clustering and transfer use the SPARC values computed with the given parameter (test_cli checks
    the trials' SPARC). Catches: features recomputed with the defaults for the clustering, a capped note
    with the default parameters, segmentation or selection that changes with SPARC's parameters."""
    d = direct(params)
    assert d.sweep.to_dict() != direct().sweep.to_dict()  # the clustering does depend on it
    res = runs(base_file, **params)[0]
    check_all(res, d)
    same = ("participant", "trial", "status", "reason", "pv", "contact_speed", "duration", "ldlj")
    assert [{c: t[c] for c in same} for t in res["trials"]] == [{c: t[c] for c in same} for t in base["trials"]]
    assert res["silhouette"] != base["silhouette"]


#: Many options at once: the sensitivity setting inherits the run's amp_th and padlevel and its clustering
#: the run's k, scaling and seed; the command line must write the same results.json as run().
UR5_LIMITS = [2.0, 2.5, 3.0, 1.5, 1.0, 3.5]
UR5_TAU = [120.0, 120.0, 100.0, 20.0, 20.0, 20.0]
COMBINED = {
    "k": 4,
    "robot": "ur5",
    "qd_max": UR5_LIMITS,
    "qdd_max": 4.0,
    "tau_max": UR5_TAU,
    "scaling": "standard",
    "random_state": 1,
    "amp_th": 0.08,
    "padlevel": 3,
    "sensitivity": [{"fc": 10.0}],
}
COMBINED_ARGV = [
    "--k",
    "4",
    "--robot",
    "ur5",
    "--qd-max",
    *map(str, UR5_LIMITS),
    "--qdd-max",
    "4",
    "--tau-max",
    *map(str, UR5_TAU),
    "--scaling",
    "standard",
    "--seed",
    "1",
    "--amp-th",
    "0.08",
    "--padlevel",
    "3",
]  # without the sensitivity (time)


def test_sensitivity_uses_the_runs_parameters_k_scaling_and_seed(runs, base_file, base_rec, direct):
    """A run with amp_th 0.08, padlevel 3, k 4, standard scaling, seed 1, UR5 with per-joint limits and the
    setting fc = 10: the section equals sparc_sensitivity called directly; the setting's other parameters
    are the run's (not the book's defaults), its clustering uses the run's k, scaling and seed; everything
    else is what the direct calls give without any sensitivity (and test_cli_writes_what_run_computes
    shows it equal to the same run without it). Catches: any of these not handed on, the run's own results
    altered by the comparison, a comparison against another reference."""
    res = runs(base_file, **COMBINED)[0]
    own = {"fc": DEFAULT_FC, "amp_th": 0.08, "padlevel": 3}
    other = {**own, "fc": 10.0}
    assert [s["params"] for s in res["sparc_sensitivity"]["settings"]] == [own, other]
    d = direct(own, "standard", 1)
    want = _json(
        sparc_sensitivity(
            base_rec, [own, other], k=4, scaling="standard", random_state=1, reference=(d.feats, d.sweep)
        ).to_dict()
    )
    _same(res["sparc_sensitivity"], want, "sparc_sensitivity")
    assert res["sparc_sensitivity"]["settings"][0]["silhouette"] == res["silhouette"]  # the run's own sweep
    other_sel = select(trial_features(base_rec, sparc_params=other))
    for scaling, seed in (("raw", 1), ("standard", 0)):  # scaling or seed not handed on would be seen
        wrong = pt.fit_prototypes(other_sel, 4, scaling=scaling, random_state=seed).silhouette
        assert wrong != pytest.approx(want["settings"][1]["silhouette"]["4"], rel=1e-9)
    check_all(
        res,
        d,
        k_requested=4,
        scaling="standard",
        random_state=1,
        robot="ur5",
        qd_limits=UR5_LIMITS,
        qdd_limits=4.0,
        tau_limits=UR5_TAU,
    )


@pytest.mark.slow
def test_figures_are_written_only_when_asked_and_change_nothing_else(tmp_path, runs, eight_selected):
    """write_figures (on the small file of the k tests, to save time): the figure files listed and
    present; every other key identical to the run without figures, which writes results.json and nothing
    else. Catches: figures missing or unlisted, a figure step that alters results, figures written despite
    write_figures=False."""
    data, d = eight_selected
    k = int(d.sweep.ks[-1])
    out = tmp_path / "fig"
    pipeline.run(data, out, k=k, write_figures=True)
    res = _load(out)
    plain_res, plain, out_plain = runs(data, k=k)
    assert _without(res, "figures") == _without(plain_res) and res["task"] == plain_res["task"]
    want = {f"{n}.{ext}" for n in FIGURES for ext in ("png", "svg")} | {"segmentation-01.png"}  # 10 trials: a page
    assert len(res["figures"]) == len(want) and set(res["figures"]) == want
    assert {p.name for p in out.iterdir()} == want | {"results.json", MANIFEST}
    assert res["dataset"]["synthetic"] is False  # a user's file: no "synthetic data" footer on its figures
    assert not any("Synthetic data" in (out / n).read_text() for n in want if n.endswith(".svg"))
    assert all((out / n).stat().st_size > 0 for n in want)
    assert plain_res.get("figures", []) == [] and plain.results.get("figures", []) == []
    assert {p.name for p in out_plain.iterdir()} == {"results.json", MANIFEST}


# --- the command line: each flag reaches run() as its option -----------------------------------------

NO_READ_OPTIONS = {
    "columns": None,
    "units": None,
    "up_axis": None,
    "marker": None,
    "contact_channel": None,
    "contact_threshold": None,
    "contact_height": None,
    "name_pattern": None,
    "sep": None,
    "time_unit": None,
    "contact_below": None,
}
#: What the command passes when no option is given: None for every setting of the task (run() then takes
#: the task's, the paper's: test_run_takes_the_papers_task_for_every_option_left_out).
CLI_DEFAULTS = {
    "data": None,
    "task": None,
    "start": None,
    "end": None,
    "hold": None,
    "split": None,
    "select": None,
    "features": None,
    "k": None,
    "robot": None,
    "qd_max": None,
    "qdd_max": None,
    "tau_max": None,
    "scaling": None,
    "random_state": None,
    "fc": None,
    "amp_th": None,
    "padlevel": None,
    "sensitivity": None,
    "lowpass": None,
    "read_options": NO_READ_OPTIONS,
    "write_figures": True,
    "workers": None,
    "scheduler": None,
}


CLI_CASES = [
    ([], {}),
    (["--workers", "3"], {"workers": 3}),
    (["--scheduler", "tcp://10.0.0.5:8786"], {"scheduler": "tcp://10.0.0.5:8786"}),
    (["--data", "rec.csv"], {"data": "rec.csv"}),
    (["--k", "4"], {"k": 4}),
    (["--robot", "panda"], {"robot": "panda"}),
    (["--qd-max", "1.5"], {"qd_max": 1.5}),
    (["--qd-max", "1", "2", "3", "4", "5", "6"], {"qd_max": [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]}),
    (["--qdd-max", "2.5"], {"qdd_max": 2.5}),
    (["--qdd-max", "1", "2", "3", "4", "5", "6"], {"qdd_max": [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]}),
    (["--tau-max", "50"], {"tau_max": 50.0}),
    (["--tau-max", "1", "2", "3", "4", "5", "6"], {"tau_max": [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]}),
    (["--scaling", "standard"], {"scaling": "standard"}),
    (["--seed", "5"], {"random_state": 5}),
    (["--fc", "12.5"], {"fc": 12.5}),
    (["--amp-th", "0.1"], {"amp_th": 0.1}),
    (["--padlevel", "2"], {"padlevel": 2}),
    (
        ["--sensitivity", "fc=10", "amp_th=0.1,padlevel=3"],
        {"sensitivity": [{"fc": 10.0}, {"amp_th": 0.1, "padlevel": 3}]},
    ),
    (["--no-figures"], {"write_figures": False}),
    (["--lowpass", "12"], {"lowpass": "12"}),
    (["--lowpass", "none"], {"lowpass": "none"}),
    (
        ["--units", "mm", "--up-axis=-z", "--columns", "time=t,px=x"],
        {"read_options": {**NO_READ_OPTIONS, "units": "mm", "up_axis": "-z", "columns": {"time": "t", "px": "x"}}},
    ),
    (
        ["--sep", "tab", "--time-unit", "ms"],
        {"read_options": {**NO_READ_OPTIONS, "sep": "tab", "time_unit": "ms"}},
    ),
    (
        [
            "--marker",
            "tip",
            "--contact-channel",
            "fz",
            "--contact-height",
            "0.01",
            "--name-pattern",
            "(?P<trial>.*)",
            "--contact-threshold",
            "2.5",
        ],
        {
            "read_options": {
                **NO_READ_OPTIONS,
                "marker": "tip",
                "contact_channel": "fz",
                "contact_height": 0.01,
                "name_pattern": "(?P<trial>.*)",
                "contact_threshold": 2.5,
            }
        },
    ),
]


@pytest.mark.parametrize(
    "option, value, path",
    [
        ("k", 7, ("cluster", "k")),
        ("robot", "panda", ("robot", "name")),
        ("scaling", "standard", ("cluster", "scaling")),
        ("random_state", 5, ("cluster", "seed")),
        ("fc", 12.5, ("sparc", "fc")),
        ("qd_max", 1.5, ("robot", "qd_max")),
        ("lowpass", "none", ("segment", "lowpass")),
    ],
)
def test_the_task_block_records_each_option(runs, base_file, base, option, value, path):
    """results.json's task names the run's options (so that --task results.json runs it again), and its
    name says the paper's task was changed. Catches: an option recorded from the default, not the run."""
    res = runs(base_file, **{option: value})[0]
    assert base["task"]["name"] == "paper" and res["task"]["name"] == "paper + options"
    assert res["task"][path[0]][path[1]] == value
    others = {k: v for k, v in res["task"].items() if k not in ("name", path[0])}
    assert others == {k: v for k, v in base["task"].items() if k not in ("name", path[0])}


def test_run_takes_the_papers_task_for_every_option_left_out():
    """The command passes None for every option not given; run() then resolves the paper's task (the
    defaults that used to be the command's own: k 6, simple6, raw, seed 0, the book's SPARC, auto filter)."""
    import inspect

    from skilllib.pipeline._run import resolve_task
    from skilllib.task import PAPER_TASK

    params = inspect.signature(pipeline.run).parameters
    for key in set(CLI_DEFAULTS) - {"data", "read_options", "write_figures"}:
        if key in params:
            assert params[key].default is None, key
    job = resolve_task(None, **{k: None for k in ("k", "robot", "scaling", "fc", "amp_th", "padlevel", "lowpass")})
    assert job == PAPER_TASK
    assert (job.k, job.robot, job.scaling, job.seed) == (pt.DEFAULT_K, "simple6", "raw", 0)
    assert (job.fc, job.amp_th, job.padlevel, job.lowpass) == (DEFAULT_FC, DEFAULT_AMP_TH, DEFAULT_PADLEVEL, "auto")


@pytest.mark.parametrize("argv, changed", CLI_CASES, ids=[" ".join(a) or "defaults" for a, _ in CLI_CASES])
def test_each_flag_reaches_run_as_its_option_and_no_other(
    monkeypatch, capsys, tmp_path, runs, base_file, argv, changed
):
    """Catches: a flag dropped, handed to another option (e.g. --seed not reaching random_state), one
    --qd-max value passed as a list, the defaults of the CLI different from run()'s."""
    calls = []
    base_run = runs(base_file)[1]

    def spy(data=None, out=None, **kwargs):
        calls.append({"data": data, "out": out, **kwargs})
        return base_run

    monkeypatch.setattr(pipeline, "run", spy)
    assert main(["run", "--quiet", "--out", str(tmp_path / "o"), *argv]) == 0
    capsys.readouterr()
    assert len(calls) == 1
    got = calls[0]
    assert got.pop("out") == str(tmp_path / "o") and callable(got.pop("progress"))
    assert got == {**CLI_DEFAULTS, **changed}
    for key in ("qd_max", "qdd_max", "tau_max"):
        assert type(got[key]) is type({**CLI_DEFAULTS, **changed}[key])


def test_cli_writes_what_run_computes(tmp_path, capsys, runs, base_file):
    """The command end to end with many options at once (per-joint limits among them), without the
    sensitivity: its results.json is run()'s with the same options and the sensitivity, less that section.
    Catches: the CLI post-processing or re-serialising the results, an option lost on the way, a
    sensitivity analysis that changes anything else of the run."""
    code = main(
        ["run", "--quiet", "--data", str(base_file), "--out", str(tmp_path / "o"), "--no-figures", *COMBINED_ARGV]
    )
    out = capsys.readouterr().out
    assert code == 0
    got, want = _load(tmp_path / "o"), runs(base_file, **COMBINED)[0]
    assert _without(got, "sparc_sensitivity") == _without(want, "sparc_sensitivity")
    assert want["task"]["sparc"].pop("sensitivity") == ["fc=10"] and got["task"] == want["task"]
    assert "k = 4 clusters (standard features)" in out and "feasibility on UR5" in out
    assert f"joint velocity limits {', '.join(f'{v:.3g}' for v in UR5_LIMITS)} rad/s" in out


# --- thresholds at both sides of their edge -----------------------------------------------------------


@pytest.fixture(scope="module")
def no_rest_frame() -> tuple[pd.DataFrame, int]:
    """A small cohort of N trials, N a multiple of the denominator of NO_REST_FRACTION (N * fraction whole),
    sampled at 100 Hz (the other files have the cohort's 60 Hz)."""
    frac = Fraction(str(pipeline.NO_REST_FRACTION))
    n = frac.denominator * max(1, -(-10 // frac.denominator))
    assert n * frac == int(n * frac) and int(n * frac) + 3 <= n
    return generate_cohort(3, CohortModel(n_participants=1, n_trials=n, fs=100.0)).frame, n


@pytest.mark.parametrize("extra", [0, 1], ids=["at-fraction", "one-more"])
def test_no_rest_note_only_above_its_fraction(tmp_path, runs, no_rest_frame, extra):
    """Exactly NO_REST_FRACTION of the trials start in motion (plus one trial invalid for another reason):
    no note; one trial more: the note with the count. Catches: >= for >, all invalid trials counted,
    another denominator than all trials."""
    df, n = no_rest_frame
    m_edge = int(Fraction(str(pipeline.NO_REST_FRACTION)) * n)
    f = trial_features(recordings_from_frame(df))
    keys = list(zip(f["participant"], f["trial"]))
    assert (f["status"] != "invalid").all()
    for key in keys[: m_edge + extra]:
        t_on = float(f.loc[(f["participant"] == key[0]) & (f["trial"] == key[1]), "t_onset"].iloc[0])
        df = _start_in_motion(df, key, t_on)
    short = keys[-1]  # invalid for another reason: too few samples
    mine = (df["participant"] == short[0]) & (df["trial"] == short[1])
    df = pd.concat([df[~mine], df[mine].head(3)]).sort_index()
    data = _write(df, tmp_path / "rest.csv")
    res = runs(data)[0]
    check_trials(res, _direct(read_recordings(data)))  # at 100 Hz, with its invalid trials
    reasons = [t["reason"] or "" for t in res["trials"]]
    assert sum(r.startswith("no rest before onset") for r in reasons) == m_edge + extra
    assert sum(t["status"] == "invalid" for t in res["trials"]) == m_edge + extra + 1
    notes = [m for m in res["messages"] if "no rest before onset" in m]
    if extra:
        assert len(notes) == 1 and notes[0].startswith(f"{m_edge + 1} of {n} trials are invalid")
    else:
        assert notes == []


@pytest.mark.parametrize("minus", [0, 1], ids=["MIN_SELECTED", "one-fewer"])
def test_min_selected_is_the_edge_of_clustering(tmp_path, capsys, cohort_frame, cohort_features, minus):
    """Exactly MIN_SELECTED selected trials (and two excluded): clustered as fit_prototypes does, exit 0;
    one fewer: no clusters, the "only" note, the sensitivity skipped with its note, exit 3. MIN_SELECTED
    must be the fewest trials the silhouette sweep accepts. Catches: another minimum, <= for <, clusters
    from excluded trials."""
    f = cohort_features
    keys = _keys(f, "selected")[: pipeline.MIN_SELECTED - minus] + _keys(f, "excluded")[:2]
    data = _write(_only(cohort_frame, keys), tmp_path / "few.csv")
    code = main(
        ["run", "--quiet", "--data", str(data), "--out", str(tmp_path / "o"), "--no-figures", "--sensitivity", "fc=10"]
    )
    err = capsys.readouterr().err
    res = _load(tmp_path / "o")
    d = _direct(read_recordings(data))
    check_trials(res, d)
    assert res["n_selected"] == pipeline.MIN_SELECTED - minus
    if minus:
        assert d.sweep is None  # the edge is the library's own: one fewer trial cannot be swept at all
        assert code == 3, err
        assert not {
            "silhouette",
            "silhouette_valid_k",
            "k",
            "scaling",
            "clusters",
            "sparc_sensitivity",
        } & set(res)
        assert [(e["participant"], e["trial"]) for e in res["transfer"]["selected_trials"]] == list(
            zip(d.sel["participant"], d.sel["trial"])
        )  # too few to cluster: each selected trial transferred as it is
        check_messages(res, d, pt.DEFAULT_K, **{"too few": 1, "no sensitivity": 1})
        assert any(m.startswith(f"only {pipeline.MIN_SELECTED - 1} selected trial(s)") for m in res["messages"])
    else:
        assert code == 0, err
        assert d.sweep is not None and list(d.sweep.ks) == [pt.K_RANGE[0]]  # only the smallest k fits
        fit = check_clustering(res, d, pt.K_RANGE[0])
        check_transfer(res, d, fit)
        check_messages(res, d, pt.DEFAULT_K)
        assert res["sparc_sensitivity"]["k"] == pt.K_RANGE[0]


@pytest.mark.parametrize("above", [0, 1], ids=["largest-k", "one-more"])
def test_k_is_reduced_only_above_the_largest_k_of_the_sweep(runs, eight_selected, above):
    """k equal to the largest k the sweep reached: used as is, no "needs more" note; one more: reduced to
    it with the note. Catches: < for <= in choose_k, the note without the reduction or the reverse."""
    data, d = eight_selected
    largest = int(d.sweep.ks[-1])
    assert largest < pt.K_RANGE[1]
    requested = largest + above
    res = runs(data, k=requested)[0]
    check_all(res, d, k_requested=requested)
    assert res["k"] == largest
    notes = [m for m in res["messages"] if "needs more" in m]
    if above:
        assert notes == [
            (
                f"k = {requested} needs more distinct selected trials than there are; "
                f"using k = {largest}, the largest the data allow"
            )
        ]
    else:
        assert notes == []


def test_a_numpy_integer_k_is_written_as_a_plain_number(tmp_path):
    """k given as numpy.int64 (check_options accepts it) must reach results.json as a JSON number."""
    data = tmp_path / "rec.csv"
    write_recordings(generate_cohort(9, CohortModel(n_participants=5, n_trials=16, fs=60.0)).frame, data)
    run_ = pipeline.run(data, tmp_path / "o", k=np.int64(3), write_figures=False)
    assert type(run_.results["k"]) is int and json.loads((tmp_path / "o" / "results.json").read_text())["k"] == 3
