"""Scaling of the whole pipeline (no figures) with the number of trials N: wall time and peak memory.

Each run is ``python -m skilllib run --data CORPUS --out DIR --no-figures --quiet`` in a fresh interpreter,

* in memory (``--mode inmemory``): CORPUS is one CSV (``--input csv``, the default) or a folder of
  Parquet files (``--input parquet``; both with ``--input csv parquet``);
* on a local Dask cluster (``--mode dask``): the same command with ``--workers W`` (default 2), CORPUS a
  folder of Parquet files.

The corpora are the book's 1,500-trial cohort tiled C times (``benchmarks/corpus.py``, jittered copies,
N = 1,500 x C), written once into ``_build/bench/`` (``cC.csv``, ``cC-pqK/``) and reused afterwards.

While a run lasts, its process tree is polled every 50 ms with psutil: the peak RSS of the main process
and, separately, the peak RSS of each child process (Dask's workers); the table gives the main process's
peak and the largest child's. Nothing is summed. Each poll reads the RSS and, on Linux, the kernel's
high-water mark VmHWM, so a spike between two polls is counted too. A run that exits non-zero is reported
with its exit code and the last line of its stderr; an option the command line does not know yet (exit 2,
as ``--workers`` before Dask support) ends that series, and the other series go on. The script exits 1
when any run failed.

After the runs: the slope of log(time) against log(N) (least squares over the sizes >= 150,000 trials),
the cost per 10^6 trials (from the two largest sizes) and what both project for 10^8 trials, with the
in-memory path's projected peak memory against this machine's RAM.

    .venv/bin/python benchmarks/bench_scale.py                                   # 1.5k .. ~10^6, both modes
    .venv/bin/python benchmarks/bench_scale.py --sizes 1 10 --mode inmemory      # 1.5k and 15k, a minute
    .venv/bin/python benchmarks/bench_scale.py --mode dask --workers 2 --repeats 3 \\
        --json _build/bench/scale.json --out-md _build/bench/scale.md
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import re
import signal
import statistics
import subprocess
import sys
import threading
import time
from collections.abc import Sequence
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import psutil

ROOT = Path(__file__).resolve().parent.parent
BENCH_DIR = ROOT / "_build" / "bench"
TRIALS_PER_COPY = 1_500  #: trials of the book's cohort, one copy of the corpus
DEFAULT_SIZES = (1, 10, 100, 300, 667)  #: copies: 1.5k, 15k, 150k, 450k, ~10^6 trials
#: the slope is fitted over the sizes with at least this many trials (below, the few seconds of start-up
#: of a run weigh: from 1,500 to 15,000 trials the time grows by 1.6x for 10x the trials)
FIT_MIN_TRIALS = 150_000
TARGET_TRIALS = 10**8  #: the projection's corpus size
POLL_S = 0.05  #: s between two samples of the process tree
MB = 2**20

sys.path.insert(0, str(Path(__file__).resolve().parent))  # benchmarks/corpus.py, whatever the cwd


# ----------------------------------------------------------------------------------------------- corpora


def corpus_path(copies: int, kind: str, bench_dir: Path = BENCH_DIR, per_file: int = 10) -> Path:
    """Where the corpus of ``copies`` copies lives: ``cC.csv`` or the folder ``cC-pqK``."""
    return bench_dir / (f"c{copies}.csv" if kind == "csv" else f"c{copies}-pq{per_file}")


def ensure_corpus(copies: int, kind: str, bench_dir: Path = BENCH_DIR, per_file: int = 10) -> tuple[Path, bool]:
    """The corpus's path, generated unless a file (folder) of that name exists; True when generated.

    It is written under a temporary name and renamed when complete, so an interrupted generation leaves
    no half corpus behind to be reused."""
    import corpus  # benchmarks/corpus.py; imports skilllib, so only when a corpus is needed

    path = corpus_path(copies, kind, bench_dir, per_file)
    if path.exists():
        return path, False
    tmp = path.with_name(f"{path.name}.tmp-{os.getpid()}")
    if kind == "csv":
        corpus.write_csv(tmp, copies)
    else:
        corpus.write_parquet(tmp, copies, per_file)
    os.replace(tmp, path)
    return path, True


# ----------------------------------------------------------------------------------------------- one run


def run_command(data: Path, out: Path, mode: str = "inmemory", workers: int = 2) -> list[str]:
    cmd = [sys.executable, "-m", "skilllib", "run", "--data", str(data), "--out", str(out), "--no-figures", "--quiet"]
    return cmd + (["--workers", str(workers)] if mode == "dask" else [])


def _peak_rss(p: psutil.Process) -> int:
    """Bytes: the process's peak RSS so far (Linux's VmHWM), at least its current RSS."""
    rss = p.memory_info().rss
    try:
        with open(f"/proc/{p.pid}/status", "rb") as f:
            for line in f:
                if line.startswith(b"VmHWM:"):
                    return max(rss, int(line.split()[1]) * 1024)
    except (OSError, ValueError, IndexError):  # not Linux, or the process just ended
        pass
    return rss


def _kill(pid: int) -> None:
    """End the run started as ``pid`` and the processes it started (its own process group)."""
    try:
        os.killpg(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def _unknown_option(stderr: str) -> str | None:
    """The options argparse rejected ('unrecognized arguments: --workers 2'), or None."""
    m = re.search(r"unrecognized arguments: (.*)", stderr)
    return m.group(1).strip() if m else None


def measure(
    data: Path,
    out: Path,
    *,
    mode: str = "inmemory",
    workers: int = 2,
    input_kind: str = "csv",
    n_trials: int | None = None,
    poll_s: float = POLL_S,
    timeout_s: float | None = None,
) -> dict:
    """Run the pipeline once on ``data`` into the folder ``out``; time it and sample its memory.

    The command's stdout and stderr go to ``out.stdout.txt`` and ``out.stderr.txt`` beside ``out``.
    Returns one record: wall time (s), peak RSS of the main process (MB), the largest peak RSS of any
    child process (MB; None when there was none), the exit code (negative: killed by that signal),
    trials/s, and the trials the run says it read."""
    out = Path(out).resolve()
    out.parent.mkdir(parents=True, exist_ok=True)
    cmd = run_command(Path(data).resolve(), out, mode, workers)
    log_out, log_err = out.with_name(out.name + ".stdout.txt"), out.with_name(out.name + ".stderr.txt")
    peak_main = 0
    peak_child: dict[tuple[int, float], int] = {}  # (pid, start time) -> peak RSS in bytes
    child_cmd: dict[tuple[int, float], str] = {}
    ended: dict = {}
    timed_out = False

    with open(log_out, "wb") as fo, open(log_err, "wb") as fe:
        t0 = time.perf_counter()
        proc = subprocess.Popen(
            cmd, stdout=fo, stderr=fe, stdin=subprocess.DEVNULL, cwd=ROOT, start_new_session=True
        )  # its own process group: a timeout ends its workers too

        def reap() -> None:  # blocks until the run ends: its exact end time
            proc.wait()
            ended["t"] = time.perf_counter()

        root = psutil.Process(proc.pid)  # before the waiter can reap it: a zombie, not gone, until then
        waiter = threading.Thread(target=reap, daemon=True)
        waiter.start()
        try:
            while waiter.is_alive():
                try:
                    peak_main = max(peak_main, _peak_rss(root))
                    children = root.children(recursive=True)
                except psutil.Error:  # exited (a zombie until reaped)
                    children = []
                for child in children:
                    try:
                        key = (child.pid, child.create_time())
                        rss = _peak_rss(child)
                        if key not in child_cmd:
                            child_cmd[key] = " ".join(child.cmdline())[:200]
                    except psutil.Error:  # ended between listing and reading
                        continue
                    peak_child[key] = max(peak_child.get(key, 0), rss)
                if timeout_s is not None and time.perf_counter() - t0 > timeout_s and not timed_out:
                    timed_out = True
                    _kill(proc.pid)
                waiter.join(poll_s)
        except BaseException:  # Ctrl-C of the benchmark: do not leave the run (and its workers) behind
            _kill(proc.pid)
            raise
        waiter.join()
    code = proc.returncode
    wall = ended["t"] - t0

    stdout = log_out.read_text(errors="replace")
    stderr = log_err.read_text(errors="replace")
    read = re.search(r"trials read: (\d+)", stdout)
    largest = max(peak_child, key=peak_child.get) if peak_child else None
    return {
        "trials": n_trials,
        "input": input_kind,
        "mode": mode,
        "workers": workers if mode == "dask" else None,
        "exit_code": code,
        "timed_out": timed_out,
        "wall_s": wall,
        "peak_main_mb": peak_main / MB,
        "peak_worker_mb": peak_child[largest] / MB if largest else None,
        "n_children": len(peak_child),
        "largest_child_cmd": child_cmd.get(largest) if largest else None,
        "trials_per_s": n_trials / wall if n_trials and code == 0 else None,
        "trials_read": int(read.group(1)) if read else None,
        "unknown_option": _unknown_option(stderr) if code == 2 else None,
        "stderr_tail": stderr.strip().splitlines()[-1] if stderr.strip() else "",
        "cmd": cmd,
        "data": str(data),
        "out": str(out),
    }


# ----------------------------------------------------------------------------------------------- fits


def fit_scaling(
    ns: Sequence[float], values: Sequence[float], *, min_n: float = FIT_MIN_TRIALS, target: float = TARGET_TRIALS
) -> dict:
    """How ``values`` (times, or memory) grow with ``ns`` (trials), and what that projects for ``target``.

    * ``slope``: least squares of log(value) on log(n) over the sizes >= ``min_n`` (1 = linear); over all
      sizes when fewer than two reach ``min_n`` (``basis`` says which; ``reliable`` is then False: start-up
      weighs on the small runs), None with fewer than two sizes;
    * ``per_million``: (v2 - v1) / (n2 - n1) x 10^6 from the two largest sizes, the cost of 10^6 more trials;
    * ``linear``: the value at ``target`` on that line; ``power``: v_largest x (target / n_largest)^slope.
    """
    pts = sorted((float(n), float(v)) for n, v in zip(ns, values, strict=True) if n > 0 and v is not None and v > 0)
    big = [p for p in pts if p[0] >= min_n]
    out: dict = {
        "target": target,
        "slope": None,
        "basis": None,
        "reliable": False,
        "sizes": [],
        "per_million": None,
        "linear": None,
        "power": None,
    }
    out["reliable"] = len(big) >= 2
    if len(big) >= 2:
        use, out["basis"] = big, f"sizes >= {min_n:,.0f} trials"
    elif len(pts) >= 2:
        use, out["basis"] = pts, f"all sizes (fewer than two reach {min_n:,.0f} trials)"
    else:
        return out
    n, v = np.array(use).T
    out["sizes"] = n.astype(int).tolist()
    out["slope"] = float(np.polyfit(np.log(n), np.log(v), 1)[0])
    (n1, v1), (n2, v2) = pts[-2], pts[-1]
    per_trial = (v2 - v1) / (n2 - n1)
    out["per_million"] = per_trial * 1e6
    out["linear"] = v2 + per_trial * (target - n2)
    out["power"] = v2 * (target / n2) ** out["slope"]
    return out


def _duration(s: float | None) -> str:
    if s is None or not math.isfinite(s):
        return "?"
    if s < 120:
        return f"{s:.0f} s"
    if s < 2 * 3600:
        return f"{s / 60:.0f} min"
    if s < 3 * 86400:
        return f"{s / 3600:.1f} h"
    return f"{s / 86400:.1f} days"


def _gb(mb: float | None) -> str:
    return "?" if mb is None else f"{mb / 1024:.1f} GB"


# ----------------------------------------------------------------------------------------------- report


def _mode_label(mode: str, workers: int | None) -> str:
    return "in-memory" if mode == "inmemory" else f"Dask, {workers} workers"


def _why(r: dict) -> str:
    if r["timed_out"]:
        return "timed out (--timeout)"
    if r["exit_code"] == -signal.SIGKILL:
        return "killed (SIGKILL: out of memory?)"
    return r["stderr_tail"] or "(no stderr)"


def summarize(records: list[dict]) -> list[dict]:
    """One row per (size, input, mode): medians over the repeats; a row fails when any repeat did."""
    groups: dict[tuple, list[dict]] = {}
    for r in records:
        groups.setdefault((r["trials"], r["input"], r["mode"], r["workers"]), []).append(r)
    rows = []
    for (n, kind, mode, workers), rs in groups.items():
        bad = [r for r in rs if r["exit_code"] != 0]
        ok = [r for r in rs if r["exit_code"] == 0]
        workers_mb = [r["peak_worker_mb"] for r in ok if r["peak_worker_mb"] is not None]
        wall = statistics.median(r["wall_s"] for r in ok) if ok else None
        rows.append(
            {
                "trials": n,
                "input": kind,
                "mode": mode,
                "workers": workers,
                "repeats": len(rs),
                "failed": len(bad),
                "exit_code": bad[0]["exit_code"] if bad else 0,
                "error": _why(bad[0]) if bad else None,
                "unknown_option": bad[0]["unknown_option"] if bad else None,
                "wall_s": wall,
                "peak_main_mb": statistics.median(r["peak_main_mb"] for r in ok) if ok else None,
                "peak_worker_mb": statistics.median(workers_mb) if workers_mb else None,
                "trials_per_s": n / wall if wall else None,
            }
        )
    return rows


def markdown_table(rows: list[dict]) -> str:
    lines = [
        "| trials | input | mode | wall time (s) | peak memory (MB) | per worker (MB) | trials/s |",
        "|---:|---|---|---:|---:|---:|---:|",
    ]
    for r in rows:
        mode = _mode_label(r["mode"], r["workers"])
        if r["failed"]:
            why = f"unknown option {r['unknown_option']}" if r["unknown_option"] else r["error"][:80]
            failed = f"**failed: exit {r['exit_code']}** ({r['failed']} of {r['repeats']} runs; {why})"
            if r["wall_s"] is None:
                lines.append(f"| {r['trials']:,} | {r['input']} | {mode} | {failed} | – | – | – |")
                continue
            mode += f"; {failed}"
        worker = "–" if r["peak_worker_mb"] is None else f"{r['peak_worker_mb']:,.0f}"
        lines.append(
            f"| {r['trials']:,} | {r['input']} | {mode} | {r['wall_s']:,.1f} | {r['peak_main_mb']:,.0f} "
            f"| {worker} | {r['trials_per_s']:,.0f} |"
        )
    return "\n".join(lines)


def projections(rows: list[dict], ram_mb: float, target: float = TARGET_TRIALS) -> tuple[list[str], dict]:
    """Lines that say how each series scales and what it projects for ``target`` trials; and the fits."""
    lines: list[str] = []
    fits: dict = {}
    series: dict[tuple, list[dict]] = {}
    for r in rows:
        if not r["failed"]:
            series.setdefault((r["input"], r["mode"], r["workers"]), []).append(r)
    for (kind, mode, workers), rs in series.items():
        name = f"{_mode_label(mode, workers)}, {kind}"
        rs = sorted(rs, key=lambda r: r["trials"])
        ns = [r["trials"] for r in rs]
        ft = fit_scaling(ns, [r["wall_s"] for r in rs], target=target)
        fm = fit_scaling(ns, [r["peak_main_mb"] for r in rs], target=target)
        fw = fit_scaling(ns, [r["peak_worker_mb"] for r in rs], target=target)
        fits[name] = {"time_s": ft, "peak_main_mb": fm, "peak_worker_mb": fw}
        if ft["slope"] is None:
            lines.append(f"- {name}: one successful size only ({ns[0]:,} trials): no slope, no projection.")
            continue
        e = f"10^{round(math.log10(target))}"
        sizes = ", ".join(f"{n:,}" for n in ft["sizes"])
        if ft["reliable"]:
            lines.append(
                f"- {name}: time ~ N^{ft['slope']:.2f} (log-log least squares over {ft['basis']}: "
                f"{sizes}); {ft['per_million']:,.0f} s per 10^6 trials (from the two largest sizes, "
                f"{ns[-2]:,} and {ns[-1]:,})."
            )
            lines.append(
                f"  {e} trials: {_duration(ft['linear'])} at that linear cost, "
                f"{_duration(ft['power'])} on the power law."
            )
        else:
            lines.append(
                f"- {name}: no slope fitted: it needs two sizes >= {FIT_MIN_TRIALS:,} trials (here {sizes}; "
                f"N^{ft['slope']:.2f} between them, start-up dominated). Indicative only: "
                f"{ft['per_million']:,.0f} s per 10^6 trials between the two -> {_duration(ft['linear'])} "
                f"for {e} trials."
            )
        if mode == "inmemory":
            need = fm["linear"] if not fm["reliable"] else max(fm["linear"], fm["power"])
            power = f"; {_gb(fm['power'])} on the power law N^{fm['slope']:.2f}" if fm["reliable"] else ""
            lines.append(
                f"  peak memory of the process: {fm['per_million']:,.0f} MB per 10^6 trials -> "
                f"{_gb(fm['linear'])} for {e} trials (linear{power}"
                f"{'' if fm['reliable'] else '; indicative, from small sizes'})."
            )
            if need > ram_mb:
                lines.append(
                    f"  That exceeds this machine's RAM ({_gb(ram_mb)}): {e} trials do not fit in memory "
                    "here and need the cluster (--workers)."
                )
            else:
                lines.append(f"  That fits in this machine's RAM ({_gb(ram_mb)}), if the growth stays linear.")
        else:
            worker = (
                ""
                if fw["per_million"] is None
                else (f"; largest worker {fw['per_million']:+,.0f} MB per 10^6 trials -> {_gb(fw['linear'])}")
            )
            lines.append(
                f"  peak memory, main process {fm['per_million']:+,.0f} MB per 10^6 trials -> "
                f"{_gb(fm['linear'])} for {e} trials{worker} "
                f"(linear, from the two largest sizes; this machine: {_gb(ram_mb)})."
            )
            if fw["linear"] is not None and fm["linear"] + workers * fw["linear"] > ram_mb:
                lines.append(
                    f"  Main process and {workers} workers together would exceed this machine's RAM at {e} "
                    "trials, if that growth holds."
                )
    return lines, fits


def _git() -> dict:
    def git(*args: str) -> str:
        try:
            return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip()
        except (OSError, subprocess.CalledProcessError):
            return "?"

    return {
        "commit": git("rev-parse", "--short", "HEAD"),
        "skilllib_modified": bool(git("status", "--porcelain", "skilllib")),
    }


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument(
        "--sizes",
        type=int,
        nargs="+",
        default=list(DEFAULT_SIZES),
        metavar="COPIES",
        help="corpus sizes in copies of the 1,500-trial cohort (default: 1 10 100 300 667)",
    )
    ap.add_argument("--mode", choices=["inmemory", "dask", "both"], default="both")
    ap.add_argument(
        "--input",
        nargs="+",
        choices=["csv", "parquet"],
        default=["csv"],
        dest="inputs",
        help="input of the in-memory runs: one CSV and/or a folder of Parquet files (default csv); Dask reads Parquet",
    )
    ap.add_argument("--workers", type=int, default=2, help="Dask workers (default 2)")
    ap.add_argument("--repeats", type=int, default=1, help="runs per size (the median is reported)")
    ap.add_argument("--per-file", type=int, default=10, help="copies per Parquet file (default 10: 15,000 trials)")
    ap.add_argument("--timeout", type=float, default=None, metavar="S", help="kill a run after S seconds")
    ap.add_argument(
        "--bench-dir",
        type=Path,
        default=BENCH_DIR,
        help="corpora (reused when present) and the runs' output folders (default _build/bench)",
    )
    ap.add_argument("--out-md", type=Path, help="append the markdown table and the projection to this file")
    ap.add_argument("--json", type=Path, help="write the raw measurements, the fits and the machine here")
    ap.add_argument(
        "--refit",
        type=Path,
        metavar="JSON",
        help="run nothing: recompute the fits and projections of the measurements stored in JSON "
        "(after a change of the fitting) and write them back into it",
    )
    args = ap.parse_args(argv)
    if args.refit:
        stored = json.loads(args.refit.read_text())
        lines, stored["fits"] = projections(stored["rows"], stored["machine"]["ram_mb"])
        args.refit.write_text(json.dumps(stored, indent=1))
        print("\n".join([markdown_table(stored["rows"]), "", *lines]))
        return 0

    series = ([("inmemory", kind) for kind in args.inputs] if args.mode in ("inmemory", "both") else []) + (
        [("dask", "parquet")] if args.mode in ("dask", "both") else []
    )
    ram_mb = psutil.virtual_memory().total / MB
    machine = {
        "cpus": os.cpu_count(),
        "ram_mb": ram_mb,
        "python": platform.python_version(),
        "platform": platform.platform(),
        "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS"),
        **_git(),
    }
    stopped: dict[tuple, str] = {}  # series ended by an option the command line does not know
    records: list[dict] = []
    runs = len(args.sizes) * len(series) * args.repeats
    i = 0
    for copies in sorted(set(args.sizes)):
        n = TRIALS_PER_COPY * copies
        for mode, kind in series:
            if (mode, kind) in stopped:
                i += args.repeats
                continue
            t0 = time.perf_counter()
            data, made = ensure_corpus(copies, kind, args.bench_dir, args.per_file)
            if made:
                print(
                    f"generated {data.relative_to(ROOT) if data.is_relative_to(ROOT) else data} "
                    f"({n:,} trials) in {time.perf_counter() - t0:.0f} s",
                    file=sys.stderr,
                )
            for rep in range(args.repeats):
                i += 1
                out = args.bench_dir / "runs" / f"{mode}-{kind}-c{copies}"
                r = measure(
                    data, out, mode=mode, workers=args.workers, input_kind=kind, n_trials=n, timeout_s=args.timeout
                )
                r["copies"] = copies
                records.append(r)
                worker = "" if r["peak_worker_mb"] is None else f", largest worker {r['peak_worker_mb']:,.0f} MB"
                print(
                    f"[{i}/{runs}] {n:,} trials, {kind}, {_mode_label(mode, r['workers'])}: exit {r['exit_code']}, "
                    f"{r['wall_s']:.1f} s, main {r['peak_main_mb']:,.0f} MB{worker}",
                    file=sys.stderr,
                )
                if r["exit_code"] != 0:
                    print(
                        f"    FAILED (exit {r['exit_code']}{', timed out' if r['timed_out'] else ''}): "
                        f"{r['stderr_tail'] or '(no stderr)'}   [log: {out}.stderr.txt]",
                        file=sys.stderr,
                    )
                elif r["trials_read"] not in (None, n):
                    print(f"    note: the run read {r['trials_read']:,} trials, not {n:,}", file=sys.stderr)
                if r["unknown_option"]:
                    stopped[(mode, kind)] = r["unknown_option"]
                    print(
                        f"    the command line does not know {r['unknown_option']!r} yet: skipping the other "
                        f"{_mode_label(mode, args.workers)} runs",
                        file=sys.stderr,
                    )
                    i += args.repeats - rep - 1  # this size's other repeats are skipped too
                    break

    rows = summarize(records)
    table = markdown_table(rows)
    lines, fits = projections(rows, ram_mb)
    when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    head = (
        f"Pipeline without figures, {when}, skilllib {machine['commit']}"
        f"{' + local changes' if machine['skilllib_modified'] else ''}; {machine['cpus']} CPUs, "
        f"{_gb(ram_mb)} RAM; peak RSS polled every 50 ms; median of {args.repeats} run(s)."
    )
    notes = [
        f"- {_mode_label(m, args.workers)}, {k}: not run beyond the first size: the command line does not "
        f"know {opt!r} yet (exit 2)."
        for (m, k), opt in stopped.items()
    ]
    report = "\n".join([head, "", table, "", *lines, *notes])
    print(report)
    if args.out_md:
        args.out_md.parent.mkdir(parents=True, exist_ok=True)
        with open(args.out_md, "a") as f:
            f.write(report + "\n\n")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(
            json.dumps(
                {
                    "when": when,
                    "machine": machine,
                    "args": {k: str(v) if isinstance(v, Path) else v for k, v in vars(args).items()},
                    "runs": records,
                    "rows": rows,
                    "fits": fits,
                    "stopped": {f"{m}/{k}": o for (m, k), o in stopped.items()},
                },
                indent=1,
            )
        )
    return 0 if all(r["exit_code"] == 0 for r in records) else 1


if __name__ == "__main__":
    sys.exit(main())
