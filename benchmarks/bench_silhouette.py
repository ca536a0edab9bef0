"""Benchmark: the silhouette sweep (k = 2..16, K-means n_init = 10) at scale, exact vs subsample estimate.

Run (from the repository root):  .venv/bin/python benchmarks/bench_silhouette.py
Options: --n N [N ...] (default 5000 20000 67000), --compare-exact N (default 20000; 0 skips it),
--k-max K (default 16), --n-init R (default 10), --seed S.

1. For each n: synthetic (PV, SPARC) tuples, :func:`skilllib.prototypes.silhouette_sweep` on them, the
   CPU time of this process (time.process_time: other processes on a shared machine do not count) of the
   whole sweep and of its silhouettes alone, the wall time and the silhouette method used.
2. For n = --compare-exact: the sweep's silhouette per k against the exact one (scikit-learn's
   ``silhouette_samples`` on all points with the sweep's labels; minutes for 20,000 points): the
   difference, the estimate's SD over its repeats and the difference in SDs.
Synthetic data, seeded: 10 Gaussian blobs with centres uniform in PV 0.2-1.5 m/s and SPARC -3 to -1.2,
SD 0.1 m/s and 0.15 (they overlap, like the features). Everything runs on one core (BLAS/OpenMP threads
pinned to 1). Not a test: nothing here is timed by pytest.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from sklearn.metrics import silhouette_samples  # noqa: E402

from skilllib.prototypes import SilhouetteSweep, feature_frame, silhouette_sweep
from skilllib.prototypes import _silhouette as sil

SEED = 20201
N_BLOBS = 10


def features(n: int, seed: int = SEED) -> pd.DataFrame:
    """``n`` synthetic (PV m/s, SPARC) tuples: overlapping Gaussian blobs in the features' ranges."""
    rng = np.random.default_rng(seed)
    centres = np.c_[rng.uniform(0.2, 1.5, N_BLOBS), rng.uniform(-3.0, -1.2, N_BLOBS)]
    x = centres[rng.integers(0, N_BLOBS, n)] + rng.normal(0.0, 1.0, (n, 2)) * [0.1, 0.15]
    return feature_frame(x[:, 0], x[:, 1])


def timed_sweep(df: pd.DataFrame, k_max: int, n_init: int) -> tuple[SilhouetteSweep, dict[str, float]]:
    """The sweep and its CPU seconds (all, silhouettes alone) and wall seconds."""
    inner = sil.silhouette
    spent = [0.0]

    def counting(*args: Any, **kwargs: Any) -> Any:
        t = time.process_time()
        try:
            return inner(*args, **kwargs)
        finally:
            spent[0] += time.process_time() - t

    sil.silhouette = counting  # prototypes calls it through the module
    try:
        t, w = time.process_time(), time.perf_counter()
        sw = silhouette_sweep(df, 2, k_max, n_init=n_init)
        return sw, {"cpu": time.process_time() - t, "silhouette": spent[0], "wall": time.perf_counter() - w}
    finally:
        sil.silhouette = inner


def exact_scores(sw: SilhouetteSweep, progress: Callable[[str], None]) -> dict[int, float]:
    """Exact average silhouette per k with the sweep's labels (O(n^2) per k)."""
    out = {}
    for k in sw.ks:
        r = sw.results[int(k)]
        out[int(k)] = float(silhouette_samples(r.data[["pv", "sparc"]].to_numpy(), r.labels).mean())
        progress(f"exact k = {k}: {out[int(k)]:.4f}")
    return out


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, nargs="+", default=[5_000, 20_000, 67_000], help="points per sweep")
    ap.add_argument("--compare-exact", type=int, default=20_000, help="n for the exact comparison (0: none)")
    ap.add_argument("--k-max", type=int, default=16)
    ap.add_argument("--n-init", type=int, default=10, help="K-means restarts (the book: 10)")
    ap.add_argument("--seed", type=int, default=SEED, help="seed of the synthetic data")
    a = ap.parse_args(argv)
    print(
        f"exact up to {sil.SILHOUETTE_EXACT_MAX} points; above: {sil.SILHOUETTE_REPEATS} subsamples of "
        f"{sil.SILHOUETTE_SAMPLE}; k = 2..{a.k_max}, n_init = {a.n_init}, one thread\n"
    )
    print("| n | method | sweep CPU s | of which silhouettes s | wall s |")
    print("|---:|---|---:|---:|---:|")
    sweeps = {}
    for n in sorted(set(a.n) | ({a.compare_exact} if a.compare_exact else set())):
        sw, t = timed_sweep(features(n, a.seed), a.k_max, a.n_init)
        sweeps[n] = sw
        if n in a.n:
            print(
                f"| {n:,} | {sw.estimate_dict()['method']} | {t['cpu']:.2f} | {t['silhouette']:.2f} | "
                f"{t['wall']:.2f} |",
                flush=True,
            )
    if not a.compare_exact:
        return
    sw = sweeps[a.compare_exact]
    est = sw.estimate_dict()
    if est["method"] == "exact":
        print(f"\n{a.compare_exact} points are computed exactly: nothing to compare")
        return
    exact = exact_scores(sw, lambda s: None)
    print(f"\nn = {a.compare_exact:,}: estimate ({est['repeats']} x {est['sample_size']}) - exact, per k\n")
    print("| k | exact | estimate | difference | SD of repeats | difference / SD | difference / SE |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    diffs = []
    for k, e in exact.items():
        p = est["per_k"][str(k)]
        d = p["mean"] - e
        diffs.append(d)
        print(
            f"| {k} | {e:.4f} | {p['mean']:.4f} | {d:+.4f} | {p['sd']:.4f} | {d / p['sd']:+.2f} | "
            f"{d / (p['sd'] / np.sqrt(est['repeats'])):+.2f} |"
        )
    print(
        f"\nlargest |difference| {max(map(abs, diffs)):.4f}, mean difference {np.mean(diffs):+.4f}; "
        f"best k exact {max(exact, key=exact.get)}, estimate {int(sw.ks[np.argmax(sw.scores)])}"
    )


if __name__ == "__main__":
    main()
