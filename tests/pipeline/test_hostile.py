"""Hostile inputs and options (issue 23): every bad input or option ends with exit 2 and one line naming it,
a trial-level problem with the trial's status and reason; exit 1 ("unexpected ...") is kept for real bugs.

The suite is a table. Each :class:`Case` row says how to build the input in ``tmp_path`` (a function of the
folder returning the ``--data`` path, or None for no ``--data``), the arguments after ``run`` (``{data}``
and ``{out}`` are filled in), the exit status, a fragment of the one line on stderr (or stdout), and the
number of trials results.json must hold (None: no results.json). Rows run in-process through
:func:`skilllib.pipeline.main` (fast); the few that need a real process (signals, a full stdout, the
environment) are in ``PROCESS_CASES`` and run through ``python -m skilllib``.

**Adding a case.** A new input format or option adds rows, not tests: write a builder (a few lines writing
the file) and append a :class:`Case` to ``CASES`` (in-process) or ``PROCESS_CASES`` (a new process), in the
block of its concern. A check beyond the status, the line and the trial count goes into ``check``, a
function of the results dictionary.
"""

from __future__ import annotations

import functools
import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from skilllib.cohort import CohortModel, generate_cohort
from skilllib.pipeline import main
from skilllib.recordings import write_recordings

ROOT = Path(__file__).resolve().parents[2]
C3D = ROOT / "data" / "real" / "pyomeca_markers_analogs.c3d"

Build = Callable[[Path], "Path | str | None"]


@dataclass(frozen=True)
class Case:
    """One row: ``id``; ``build(tmp_path)`` -> the ``--data`` path (None: no ``--data``); ``args`` after
    ``run`` with ``{data}`` and ``{out}``; the exit ``status``; a ``fragment`` of the one line on stderr
    (on stdout for ``on="out"``; ``""`` for a stderr that must be empty); ``n_trials`` in results.json
    (None: no results.json); ``check(results)`` for more."""

    id: str
    build: Build
    args: tuple[str, ...]
    status: int
    fragment: str
    n_trials: int | None = None
    check: Callable[[dict], None] | None = None
    on: str = "err"


# --- inputs ------------------------------------------------------------------------------------------


@functools.cache
def frame() -> pd.DataFrame:
    """2 participants x 6 trials at 60 Hz, 5 of them selected: a run that clusters and transfers, fast."""
    return generate_cohort(0, CohortModel(n_participants=2, n_trials=6)).frame


def csv(df: Callable[[], pd.DataFrame] = frame, name: str = "rec.csv") -> Build:
    return lambda tmp: write_recordings(df(), tmp / name)


def text(name: str, content: str | bytes) -> Build:
    def build(tmp: Path) -> Path:
        path = tmp / name
        path.write_bytes(content if isinstance(content, bytes) else content.encode())
        return path

    return build


def scaled(column: str | tuple[str, ...], factor: float) -> Callable[[], pd.DataFrame]:
    cols = (column,) if isinstance(column, str) else column
    return lambda: frame().assign(**{c: frame()[c] * factor for c in cols})


def jittered() -> pd.DataFrame:
    rng = np.random.default_rng(1)
    return frame().assign(t=frame()["t"] + rng.uniform(-5e-4, 5e-4, len(frame())))


def too_many_fields(tmp: Path) -> Path:
    path = write_recordings(frame(), tmp / "wide.csv")
    lines = path.read_text().splitlines()
    lines[6] += ",0.5"
    path.write_text("\n".join(lines) + "\n")
    return path


def trailing_empty_field(tmp: Path) -> Path:
    """Every data row ends with a comma the header lacks (an exporter's habit): the empty field is ignored."""
    path = write_recordings(frame(), tmp / "trailing.csv")
    lines = path.read_text().splitlines()
    path.write_text("\n".join([lines[0]] + [ln + "," for ln in lines[1:]]) + "\n")
    return path


def tab_separated(tmp: Path) -> Path:
    path = tmp / "rec.tsv"
    frame().to_csv(path, sep="\t", index=False)
    return path


def empty_folder(tmp: Path) -> Path:
    (tmp / "nothing").mkdir()
    (tmp / "nothing" / "notes.txt").write_text("no recordings here\n")
    return tmp / "nothing"


def out_holds_input(tmp: Path) -> Path:
    (tmp / "o").mkdir()
    return write_recordings(frame(), tmp / "o" / "rec.csv")


def damaged_c3d(tmp: Path) -> Path:
    data = C3D.read_bytes()
    (tmp / "damaged.c3d").write_bytes(data[: len(data) // 3])
    return tmp / "damaged.c3d"


def trc_num_markers_inf(tmp: Path) -> Path:
    n, rate = 60, 60.0
    rows = [f"{i + 1}\t{i / rate:.6f}\t{10 + i:.3f}\t{300 - i:.3f}\t{-50:.3f}" for i in range(n)]
    head = [
        "PathFileType\t4\t(X/Y/Z)\tinf.trc",
        "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames",
        f"{rate:g}\t{rate:g}\t{n}\tinf\tmm\t{rate:g}\t1\t{n}",
        "Frame#\tTime\ttip\t\t",
        "\t\tX1\tY1\tZ1",
        "",
    ]
    return text("inf.trc", "\n".join(head + rows) + "\n")(tmp)


def nexus_without_units(tmp: Path) -> Path:
    rows = [f"{i + 1},0,{10 + i:.3f},{300 - i:.3f},-50.000" for i in range(50)]
    lines = ["Trajectories", "100", ",,S:M,,", "Frame,Sub Frame,X,Y,Z", *rows]
    return text("nexus.csv", "\n".join(lines) + "\n")(tmp)


def nan_at(n: int, *, where: str) -> Callable[[], pd.DataFrame]:
    """One trial (participant 1, trial 1) with ``n`` positions missing: in the middle of its approach
    (``where="approach"``)."""

    def make() -> pd.DataFrame:
        df = frame().copy()
        rows = df.index[(df["participant"].astype(str) == "1") & (df["trial"].astype(str) == "1")]
        moving = rows[len(rows) // 3 : len(rows) // 3 + n]  # after the rest, before contact (sample 47 of 61)
        df.loc[moving, ["x", "y", "z"]] = np.nan
        return df

    return make


def trial_folder(tmp: Path, extra: Callable[[Path], None] | None = None) -> Path:
    """A folder of one-trial CSVs (``P<p>_<t>.csv``, the 12 trials of :func:`frame`), then ``extra(folder)``."""
    folder = tmp / "trials"
    folder.mkdir()
    for (p, tr), g in frame().groupby(["participant", "trial"], sort=False):
        g.drop(columns=["participant", "trial"]).to_csv(folder / f"P{p}_{tr}.csv", index=False)
    if extra is not None:
        extra(folder)
    return folder


def with_dangling_link(folder: Path) -> None:
    (folder / "P9_9.csv").symlink_to(folder / "gone.csv")


def with_hidden_and_stray_files(folder: Path) -> None:
    (folder / "._P1_1.csv").write_bytes(b"\0\5\x16\x07 AppleDouble")
    (folder / "notes.txt").write_text("not a recording\n")


def with_an_unreadable_file(folder: Path) -> None:
    (folder / "P1_1.csv").write_bytes(b"\xff\xfe\x00garbage")


def skipped(*reasons: str) -> Callable[[dict], None]:
    def check(results: dict) -> None:
        got = [s["reason"] for s in results["dataset"]["skipped_files"]]
        assert sorted(got) == sorted(reasons) or all(any(r in g for g in got) for r in reasons), got
        assert len(got) == len(reasons), got

    return check


def one_invalid_file(results: dict) -> None:
    bad = [t for t in results["trials"] if t["status"] == "invalid"]
    assert len(bad) == 1 and "P1_1.csv" in bad[0]["reason"], bad


def parquet_mixed_ids(tmp: Path) -> Path:
    """Two Parquet files from different tools: ids stored as int64 in one, as text in the other."""
    folder = tmp / "mixed"
    folder.mkdir()
    df = frame()
    a = df[df["participant"].astype(str) == "1"].astype({"participant": "int64", "trial": "int64"})
    b = df[df["participant"].astype(str) == "2"].astype({"participant": str, "trial": str})
    a.to_parquet(folder / "part-0.parquet", index=False)
    b.to_parquet(folder / "part-1.parquet", index=False)
    return folder


def parquet_with_stray_csv(tmp: Path) -> Path:
    folder = parquet_mixed_ids(tmp)
    write_recordings(frame().head(61), folder / "stray.csv")
    (folder / "._part-0.parquet").write_bytes(b"\0\5\x16\x07 AppleDouble")
    return folder


def ids_are_text(results: dict) -> None:
    assert {t["participant"] for t in results["trials"]} == {"1", "2"}


def noted(*fragments: str) -> Callable[[dict], None]:
    def check(results: dict) -> None:
        for f in fragments:
            assert any(f in m for m in results["messages"]), (f, results["messages"])

    return check


def trial(results: dict, p: str, tr: str) -> dict:
    return next(t for t in results["trials"] if str(t["participant"]) == p and str(t["trial"]) == tr)


def repaired(results: dict) -> None:
    t = trial(results, "1", "1")
    assert t["status"] != "invalid" and t["n_repaired"] >= 1 and t["repairs"], t


def invalid_gap(results: dict) -> None:
    t = trial(results, "1", "1")
    assert t["status"] == "invalid" and "gap" in t["reason"], t


def not_simulated(results: dict) -> None:
    protos = results["transfer"]["prototypes"]
    assert all(p["time_scale"] > 100 and p["executed_time_scaled"] is None for p in protos)
    assert all(p["executed"] is not None for p in protos)
    assert any("not simulated" in m for m in results["messages"])


# --- the table ---------------------------------------------------------------------------------------

OUT = ("--out", "{out}", "--no-figures")

CASES = [
    # the file itself
    Case("missing-file", lambda tmp: tmp / "nope.csv", ("--data", "{data}", *OUT), 2, "nope.csv"),
    Case("empty-file", text("empty.csv", ""), ("--data", "{data}", *OUT), 2, "empty"),
    Case("folder-without-recordings", empty_folder, ("--data", "{data}", *OUT), 2, "nothing"),
    Case("dev-zero", lambda tmp: "/dev/zero", ("--data", "{data}", *OUT), 2, "/dev/zero"),
    # tables
    Case("ms-time-stamps", csv(scaled("t", 1000.0), "ms.csv"), ("--data", "{data}", *OUT), 2, "--time-unit"),
    Case("mm-positions", csv(scaled(("x", "y", "z"), 1000.0), "mm.csv"), ("--data", "{data}", *OUT), 2, "--units"),
    Case("row-with-too-many-fields", too_many_fields, ("--data", "{data}", *OUT), 2, "line 7"),
    Case(
        "trailing-empty-field-ignored",
        trailing_empty_field,
        ("--data", "{data}", *OUT),
        0,
        "the empty last field is ignored",
        12,
        on="out",
    ),  # fmt: skip
    Case("tab-separated-detected", tab_separated, ("--data", "{data}", *OUT), 0, "trials read: 12", 12, on="out"),
    Case("one-sample-nan-repaired", csv(nan_at(1, where="approach")), ("--data", "{data}", *OUT), 0, "", 12, repaired),
    Case("long-gap-in-approach", csv(nan_at(15, where="approach")), ("--data", "{data}", *OUT), 0, "", 12, invalid_gap),
    # C3D, TRC, Vicon Nexus
    Case("c3d-unknown-marker", lambda tmp: C3D, ("--data", "{data}", "--marker", "NOPE", *OUT), 2, "NOPE"),
    Case("c3d-damaged", damaged_c3d, ("--data", "{data}", *OUT), 2, "damaged.c3d"),
    Case("trc-num-markers-inf", trc_num_markers_inf, ("--data", "{data}", *OUT), 2, "NumMarkers"),
    Case("nexus-without-units-row", nexus_without_units, ("--data", "{data}", *OUT), 2, "nexus.csv"),
    # options
    Case("fc-at-nyquist", csv(), ("--data", "{data}", "--fc", "30", *OUT), 2, "Nyquist frequency 30 Hz"),
    Case("fc-at-nyquist-jittered", csv(jittered), ("--data", "{data}", "--fc", "30", *OUT), 2, "fc = 30 Hz"),
    Case("qd-max-below-floor", csv(), ("--data", "{data}", "--qd-max", "1e-13", *OUT), 2, "qd_max must be at least"),
    Case("qd-max-tiny-not-simulated", csv(), ("--data", "{data}", "--qd-max", "1e-6", *OUT), 0, "", 12, not_simulated),
    Case("workers-0", csv(), ("--data", "{data}", "--workers", "0", *OUT), 2, "workers must be"),
    Case("workers-beyond-cores", csv(), ("--data", "{data}", "--workers", "100000", *OUT), 2, "cores"),
    Case("out-empty", csv(), ("--data", "{data}", "--out", "", "--no-figures"), 2, "out"),
    Case("out-holds-input", out_holds_input, ("--data", "{data}", *OUT), 2, "holds"),
    # folders: every file a trial, an invalid trial or a skipped line with its reason
    Case(
        "folder-dangling-link",
        lambda tmp: trial_folder(tmp, with_dangling_link),
        ("--data", "{data}", *OUT),
        0,
        "",
        12,
        skipped("broken link"),
        on="none",
    ),  # fmt: skip
    Case(
        "folder-hidden-and-stray-files",
        lambda tmp: trial_folder(tmp, with_hidden_and_stray_files),
        ("--data", "{data}", *OUT),
        0,
        "",
        12,
        skipped("hidden file", "not a C3D"),
        on="none",
    ),  # fmt: skip
    Case(
        "folder-one-unreadable-file",
        lambda tmp: trial_folder(tmp, with_an_unreadable_file),
        ("--data", "{data}", *OUT),
        0,
        "",
        12,
        one_invalid_file,
        on="none",
    ),  # fmt: skip
    # Parquet datasets as tools write them
    Case("parquet-mixed-id-types", parquet_mixed_ids, ("--data", "{data}", *OUT), 0, "", 12, ids_are_text),
    Case(
        "parquet-stray-csv-and-appledouble",
        parquet_with_stray_csv,
        ("--data", "{data}", *OUT),
        0,
        "",
        12,
        noted("stray.csv", "._part-0.parquet"),
        on="none",
    ),  # fmt: skip
]


def _fill(args: tuple[str, ...], data: Path | str | None, out: Path) -> list[str]:
    return [a.format(data=data, out=out) for a in args]


def _assert_outcome(case: Case, code: int, out: str, err: str, results_dir: Path) -> None:
    assert code == case.status, f"{case.id}: exit {code}, stderr {err!r}"
    assert "Traceback" not in err and "unexpected" not in err, err
    if case.status == 2:
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert len(lines) == 1 and lines[0].startswith("error: "), f"{case.id}: {err!r}"
        assert case.fragment.lower() in lines[0].lower(), f"{case.fragment!r} not in {lines[0]!r}"
    elif case.on == "out":
        assert case.fragment in out, out
    elif case.on == "none":  # nothing required of stderr but one line at most (warnings of skipped files)
        assert len([ln for ln in err.splitlines() if ln.strip()]) <= 1, err
    elif case.fragment == "":
        assert err == "", err
    if case.n_trials is None:
        assert not (results_dir / "results.json").exists()
    else:
        results = json.loads((results_dir / "results.json").read_text())
        assert len(results["trials"]) == case.n_trials
        if case.check is not None:
            case.check(results)


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_hostile_input_in_process(case: Case, tmp_path, capfd):
    data = case.build(tmp_path)
    out = tmp_path / "o"
    code = main(["run", "--quiet", *_fill(case.args, data, out)])
    cap = capfd.readouterr()
    _assert_outcome(case, code, cap.out, cap.err, out)


# --- rows that need a process of their own -----------------------------------------------------------


def parquet_folder(tmp: Path, damaged: bool = False) -> Path:
    folder = tmp / "pq"
    folder.mkdir()
    df = frame().astype({"participant": str, "trial": str})
    for k, p in enumerate(sorted(df["participant"].unique())):
        df[df["participant"] == p].to_parquet(folder / f"part-{k}.parquet", index=False)
    if damaged:
        raw = (folder / "part-1.parquet").read_bytes()
        (folder / "part-1.parquet").write_bytes(raw[: len(raw) // 2] + b"\0" * 64 + raw[-8:])
    return folder


PROCESS_CASES = [
    Case("stdout-full", csv(), ("--data", "{data}", *OUT), 141, "", 12),  # results.json written, summary not
    Case("home-not-writable", csv(), ("--data", "{data}", *OUT), 0, "", 12),
]


def _command(args: list[str], **kw) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "skilllib", "run", "--quiet", *args],
        stderr=subprocess.PIPE,
        text=True,
        **kw,
    )


@pytest.mark.slow  # a new process each
@pytest.mark.parametrize("case", PROCESS_CASES, ids=[c.id for c in PROCESS_CASES])
def test_hostile_environment_in_a_process(case: Case, tmp_path):
    data = case.build(tmp_path)
    out = tmp_path / "o"
    env = {k: v for k, v in os.environ.items() if k not in ("MPLCONFIGDIR", "XDG_CONFIG_HOME", "XDG_CACHE_HOME")}
    if case.id == "home-not-writable":
        env["HOME"] = "/dev/null/home"  # not a folder: nothing can be written under it, even by root
    with open("/dev/full" if case.id == "stdout-full" else os.devnull, "w") as stdout:
        proc = _command(_fill(case.args, data, out), stdout=stdout, env=env)
        _, err = proc.communicate(timeout=300)
    _assert_outcome(case, proc.returncode, "", err, out)


def test_no_figures_imports_no_figure_code(tmp_path):
    """With --no-figures skilllib's figures (and through them matplotlib's font cache) are never imported.
    matplotlib itself is: roboticstoolbox imports it (its trajectory tools, spatialmath's 2-D geometry)."""
    data = csv()(tmp_path)
    code = (
        "import sys\nfrom skilllib.pipeline import main\n"
        f"main(['run', '--quiet', '--data', {str(data)!r}, '--out', {str(tmp_path / 'o')!r}, '--no-figures'])\n"
        "print('FIGURES', 'skilllib.figures' in sys.modules)"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip().splitlines()[-1] == "FIGURES False"


def test_a_damaged_partition_on_a_worker_is_one_line(tmp_path, capfd):
    """The worker's own log ("Compute Failed" and its traceback) is silenced: the one line of the error."""
    data = parquet_folder(tmp_path, damaged=True)
    code = main(["run", "--quiet", "--data", str(data), "--workers", "1", *_fill(OUT, data, tmp_path / "o")])
    err = capfd.readouterr().err
    assert code == 2, err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and "part-1.parquet" in lines[0], err


@pytest.mark.slow  # a process and a local cluster
def test_ctrl_c_during_a_cluster_run_is_one_line(tmp_path):
    """Ctrl-C in a terminal reaches every process of the command (its process group): the client, the
    cluster's worker processes. Exit 130 and one line, no Dask log or traceback."""
    data = parquet_folder(tmp_path)
    proc = _command(
        ["--data", str(data), "--workers", "2", *_fill(OUT, data, tmp_path / "o")],
        stdout=subprocess.DEVNULL,
        start_new_session=True,
    )
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:  # until a worker process runs: the cluster has started
        kids = subprocess.run(["ps", "-o", "cmd=", "--ppid", str(proc.pid)], capture_output=True, text=True).stdout
        if "dask worker" in kids or proc.poll() is not None:
            break
        time.sleep(0.1)
    time.sleep(1.0)  # past the cluster's start-up, during which a Ctrl-C is ignored (skilllib.features)
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    if proc.returncode == 0:  # finished before the signal: nothing to check
        pytest.skip("the run ended before Ctrl-C")
    assert proc.returncode == 130 and err == "error: interrupted\n", err
