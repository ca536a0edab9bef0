"""benchmarks/bench_scale.py: one measured run on the 1,500-trial corpus, and the scaling fit on exact inputs."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

pytest.importorskip("psutil")
pytest.importorskip("pyarrow")

BENCH = Path(__file__).resolve().parent.parent / "benchmarks"


def _load(name: str):
    spec = importlib.util.spec_from_file_location(name, BENCH / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault(name, module)  # bench_scale imports corpus by name
    spec.loader.exec_module(module)
    return module


corpus = _load("corpus")
bench = _load("bench_scale")


@pytest.mark.slow
def test_measure_one_copy_in_memory(tmp_path):
    data = corpus.write_csv(tmp_path / "c1.csv", 1)
    r = bench.measure(data, tmp_path / "out", n_trials=1_500)
    assert r["exit_code"] == 0, r["stderr_tail"]
    assert r["trials_read"] == 1_500  # the corpus holds the trials the table counts
    assert 0 < r["wall_s"] < 120
    assert r["peak_main_mb"] > 50  # the interpreter with numpy, pandas, scikit-learn: well above 50 MB
    assert r["peak_main_mb"] < 10_000
    assert r["trials_per_s"] == pytest.approx(1_500 / r["wall_s"])
    assert (tmp_path / "out" / "results.json").is_file()
    assert r["mode"] == "inmemory" and r["workers"] is None and "--workers" not in r["cmd"]


def test_a_failing_run_is_reported(tmp_path):
    r = bench.measure(tmp_path / "missing.csv", tmp_path / "out", n_trials=1_500)
    assert r["exit_code"] == 2
    assert r["trials_per_s"] is None
    assert r["stderr_tail"].startswith("error:")
    (row,) = bench.summarize([r])
    assert row["failed"] == 1 and row["exit_code"] == 2
    assert "failed: exit 2" in bench.markdown_table([row])


def test_unknown_option_is_recognized():
    msg = (
        "usage: python -m skilllib [-h] [--version] {run} ...\n"
        "python -m skilllib: error: unrecognized arguments: --workers 2\n"
    )
    assert bench._unknown_option(msg) == "--workers 2"
    assert bench._unknown_option("error: data.csv: no such file") is None


def test_dask_command_adds_workers():
    cmd = bench.run_command(Path("/d"), Path("/o"), "dask", 3)
    assert cmd[-2:] == ["--workers", "3"]
    assert cmd[cmd.index("--data") + 1] == "/d" and "--no-figures" in cmd and "--quiet" in cmd


NS = [1_500, 15_000, 150_000, 450_000, 1_000_500]


@pytest.mark.parametrize("power", [1.0, 2.0, 0.5])
def test_slope_of_a_power_law(power):
    fit = bench.fit_scaling(NS, [3e-4 * n**power for n in NS])
    assert fit["slope"] == pytest.approx(power, abs=1e-9)
    assert fit["sizes"] == NS[2:]  # the runs below 150,000 trials (start-up dominated) are left out
    assert fit["power"] == pytest.approx(3e-4 * 1e8**power, rel=1e-9)


def test_linear_cost_and_projection():
    times = [5.0 + 2e-3 * n for n in NS]  # 5 s of start-up, then 2 ms per trial
    fit = bench.fit_scaling(NS, times)
    assert fit["per_million"] == pytest.approx(2_000.0)  # s per 10^6 trials
    assert fit["linear"] == pytest.approx(5.0 + 2e-3 * 1e8)
    assert 0.9 < fit["slope"] < 1.0  # the constant start-up bends the log-log line below 1


def test_slope_uses_the_large_sizes_only():
    # flat (start-up) below 150,000 trials, then exactly linear: the fit must not see the flat points
    fit = bench.fit_scaling(NS, [100.0, 100.0, 100.0, 300.0, 667.0])
    assert fit["slope"] == pytest.approx(1.0, abs=1e-3)
    assert fit["reliable"]
    small = bench.fit_scaling(NS[:2], [1.0, 4.0])  # no size >= 150k: over both, and flagged
    assert small["basis"].startswith("all sizes") and not small["reliable"]
    assert small["slope"] == pytest.approx(0.60206, abs=1e-5)  # log(4) / log(10)
    assert bench.fit_scaling(NS[:1], [1.0])["slope"] is None


def test_projection_says_when_memory_exceeds_ram():
    rows = [
        {
            "trials": n,
            "input": "csv",
            "mode": "inmemory",
            "workers": None,
            "failed": 0,
            "wall_s": 1e-3 * n,
            "peak_main_mb": 0.5 * n,
            "peak_worker_mb": None,
        }
        for n in NS
    ]
    lines, fits = bench.projections(rows, ram_mb=23 * 1024)
    assert fits["in-memory, csv"]["time_s"]["slope"] == pytest.approx(1.0)
    assert any("exceeds this machine's RAM" in line and "need the cluster" in line for line in lines)
    small = [dict(r, peak_main_mb=100.0 + 1e-6 * r["trials"]) for r in rows]
    lines, _ = bench.projections(small, ram_mb=23 * 1024)
    assert not any("exceeds" in line for line in lines)
    lines, _ = bench.projections(rows[:2], ram_mb=23 * 1024)  # 1,500 and 15,000 trials: no fitted slope
    assert lines[0].startswith("- in-memory, csv: no slope fitted")


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="VmHWM is Linux's")
def test_peak_rss_remembers_a_freed_block():
    import psutil

    me = psutil.Process()
    block = bytearray(200 * 2**20)  # touch 200 MB, then let it go: the high-water mark remembers it
    block[::4096] = b"x" * len(block[::4096])
    during = me.memory_info().rss
    del block
    after = me.memory_info().rss
    assert during - after > 150 * 2**20  # the block was returned to the system
    assert bench._peak_rss(me) > during - 4 * 2**20  # the kernel's per-thread RSS counters lag by a little
