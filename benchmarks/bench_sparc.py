"""Benchmark: skilllib.sparc_many against the SPARC authors' per-trial code (monalysa 0.2.1).

Run (from the repository root):  .venv/bin/python benchmarks/bench_sparc.py
Options: --repeats R (default 11), --max-n N (default 1000000; the scaling run goes 10^3 .. N).

1. The experiment's size: 1,500 trials of 30-90 samples at 60 Hz, synthetic touch movements (a minimum-
   jerk submovement, sometimes a corrective one, cut at contact in the deceleration, speed noise).
   monalysa.quality.smoothness.sparc trial by trial against skilllib.sparc_many, interleaved, median of
   R repeats of the CPU time of this process (time.process_time: other processes on a shared machine do
   not count); asserts the largest difference is below 1e-9. The same for LDLJ.
2. Scaling: sparc_many on 10^3 .. 10^6 such trials, each size in a fresh process, giving the time per
   trial, the resident memory before the call (the input included) and the peak of the process (VmHWM).
Everything runs on one core (BLAS threads pinned to 1). Not a test: nothing here is timed by pytest.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from skilllib.smoothness import SPARC_PARAMS, ldlj_many, minimum_jerk_speed, sparc_many

FS = 60.0  # Hz, the Phantom's sampling rate in the experiment


def touch_trials(n: int, seed: int = 0, chunk: int = 20_000) -> list[np.ndarray]:
    """``n`` synthetic speed profiles (m/s) from onset to contact, 30-90 samples at 60 Hz.

    A minimum-jerk submovement cut at contact during its deceleration, a corrective submovement in half
    of the trials, speed noise as from differentiated positions. Generated ``chunk`` trials at a time."""
    rng = np.random.default_rng(seed)
    out: list[np.ndarray] = []
    for m in np.diff(np.r_[0:n:chunk, n]):
        lengths = rng.integers(30, 91, m)
        offsets = np.cumsum(lengths) - lengths
        t = (np.arange(lengths.sum()) - np.repeat(offsets, lengths)) / FS  # s, per trial
        T1 = lengths / FS / rng.uniform(0.6, 0.9, m)  # s; contact at 60-90 % of the submovement
        D1 = rng.uniform(0.1, 0.3, m)  # m
        t2, T2 = T1 * rng.uniform(0.3, 0.6, m), T1 * rng.uniform(0.3, 0.5, m)
        D2 = D1 * rng.uniform(0.1, 0.4, m) * (rng.random(m) < 0.5)
        rep = lambda a: np.repeat(a, lengths)  # noqa: E731, B023  (used at once)
        v = minimum_jerk_speed(t, 0.0, rep(T1), rep(D1)) + minimum_jerk_speed(t, rep(t2), rep(T2), rep(D2))
        v = np.abs(v + rng.normal(0.0, 0.005, v.size))
        out += np.split(v, offsets[1:])
    return out


def compare(authors, ours, trials: list[np.ndarray], repeats: int) -> dict:
    """Median CPU times of the authors' function trial by trial and of ours on all trials, interleaved."""
    ours(trials, FS)  # warm-up (DFT matrices)
    t_ref, t_new = [], []
    for _ in range(repeats):
        t0 = time.process_time()
        ref = np.array([authors(v, FS) for v in trials])
        t1 = time.process_time()
        new = ours(trials, FS)
        t2 = time.process_time()
        t_ref.append(t1 - t0)
        t_new.append(t2 - t1)
    diff = float(np.max(np.abs(new - ref)))
    assert diff < 1e-9, f"{ours.__name__} differs from the authors' code by {diff}"
    return {
        "ref": float(np.median(t_ref)),
        "new": float(np.median(t_new)),
        "diff": diff,
        "range": (float(ref.min()), float(ref.max())),
    }


def _memory_mb() -> dict[str, float]:
    """Current (VmRSS) and peak (VmHWM) resident memory of this process, MB (Linux)."""
    with open("/proc/self/status") as fh:
        fields = dict(line.split(":", 1) for line in fh)
    return {key: int(fields[key].split()[0]) / 1024 for key in ("VmRSS", "VmHWM")}


def scale_point(n: int) -> dict:
    trials = touch_trials(n, seed=1)
    sparc_many(trials[:100], FS)  # warm-up
    before = _memory_mb()["VmRSS"]
    t0 = time.process_time()
    sparc_many(trials, FS)
    seconds = time.process_time() - t0
    return {"n": n, "seconds": seconds, "before_mb": before, "peak_mb": _memory_mb()["VmHWM"]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=11)
    ap.add_argument("--max-n", type=int, default=1_000_000)
    ap.add_argument("--scale-point", type=int, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.scale_point:
        print(json.dumps(scale_point(args.scale_point)))
        return

    from monalysa.quality.smoothness import log_dimensionless_jerk, sparc

    trials = touch_trials(1500)
    print(f"1,500 trials of 30-90 samples at {FS:g} Hz, median CPU time of {args.repeats} repeats, one core")
    print(f"{'':36s}{'time (ms)':>10s}{'per trial (us)':>16s}{'speed-up':>10s}{'max |diff|':>12s}")
    for name, authors, ours in (
        ("sparc", lambda v, fs: sparc(v, fs, **SPARC_PARAMS)[0], sparc_many),
        ("ldlj", log_dimensionless_jerk, ldlj_many),
    ):
        c = compare(authors, ours, trials, args.repeats)
        print(f"{'monalysa ' + name + ', trial by trial':36s}{c['ref'] * 1e3:10.1f}{c['ref'] / 1500 * 1e6:16.1f}")
        print(
            f"{'skilllib.' + ours.__name__:36s}{c['new'] * 1e3:10.2f}{c['new'] / 1500 * 1e6:16.2f}"
            f"{c['ref'] / c['new']:9.0f}x{c['diff']:12.1e}"
        )

    print("\nscaling of sparc_many (each size in a fresh process; CPU time; RSS includes the input)")
    print(f"{'trials':>10s}{'time (s)':>10s}{'per trial (us)':>16s}{'RSS before (MB)':>17s}{'peak RSS (MB)':>15s}")
    n = 1000
    while n <= args.max_n:
        out = subprocess.run(
            [sys.executable, __file__, "--scale-point", str(n)], check=True, capture_output=True, text=True
        ).stdout
        r = json.loads(out)
        print(f"{n:10,d}{r['seconds']:10.2f}{r['seconds'] / n * 1e6:16.2f}{r['before_mb']:17.0f}{r['peak_mb']:15.0f}")
        assert r["peak_mb"] < 2048, f"peak memory {r['peak_mb']:.0f} MB at {n} trials"
        n *= 10


if __name__ == "__main__":
    main()
