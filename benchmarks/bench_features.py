"""The in-memory path's stages on one corpus, side by side with what they replaced.

* reading and validating the CSV: pyarrow's reader (a plain file) against pandas' reader (any other
  file; what every file went through before), both through :func:`skilllib.recordings.recordings_from_frame`;
* the features of every trial: :func:`skilllib.features.trial_features` (vectorised, skilllib.features)
  against the per-trial loop of tests/test_batch.py (``reference_features``) on the first
  ``--reference`` trials, timed in the same process, alternately, ``--repeats`` times (medians).

BLAS and OpenMP are limited to one thread ("features on one core"); pyarrow's reader uses its threads.

    .venv/bin/python benchmarks/corpus.py --copies 100 --out _build/bench/c100.csv
    .venv/bin/python benchmarks/bench_features.py _build/bench/c100.csv --reference 15000
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(var, "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from test_batch import reference_features  # noqa: E402  (the per-trial loop, the tests' reference)

from skilllib.features import trial_features
from skilllib.recordings import read_recordings, read_table, recordings_from_frame


def timed(fn, *args, **kwargs):
    t0 = time.perf_counter()
    out = fn(*args, **kwargs)
    return time.perf_counter() - t0, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", type=Path)
    ap.add_argument("--reference", type=int, default=15_000, help="trials timed with the per-trial loop")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()

    t_fast, rec = [], None
    t_slow = []
    for _ in range(args.repeats):
        dt, rec = timed(read_recordings, args.csv)
        t_fast.append(dt)
        t0 = time.perf_counter()
        df, lines = read_table(args.csv)
        recordings_from_frame(df, str(args.csv), lines=lines)
        t_slow.append(time.perf_counter() - t0)
        del df, lines
    n = len(rec)
    k = min(args.reference, n)
    end = int(rec.runs().start[k - 1] + rec.runs().length[k - 1])  # the rows of the first k trials
    part = recordings_from_frame(rec.frame.iloc[:end])
    t_vec, t_vec_part, t_ref = [], [], []
    for _ in range(args.repeats):
        t_vec.append(timed(trial_features, rec)[0])
        t_vec_part.append(timed(trial_features, part)[0])
        t_ref.append(timed(reference_features, part)[0])
    m = statistics.median
    print(f"corpus: {args.csv} ({args.csv.stat().st_size / 1e6:.0f} MB), {n:,} trials; medians of {args.repeats}")
    print("| stage | trials | time (s) | trials/s |")
    print("|---|---:|---:|---:|")
    for name, k, ts in (
        ("read + validate, pyarrow (plain CSV)", n, t_fast),
        ("read + validate, pandas reader", n, t_slow),
        ("features, vectorised (all trials)", n, t_vec),
        (f"features, vectorised (first {len(part):,})", len(part), t_vec_part),
        (f"features, per-trial loop (first {len(part):,})", len(part), t_ref),
    ):
        print(f"| {name} | {k:,} | {m(ts):.2f} | {k / m(ts):,.0f} |")
    print(
        f"\nspeed-up of the features on the same {len(part):,} trials: {m(t_ref) / m(t_vec_part):.0f}x; "
        f"of reading: {m(t_slow) / m(t_fast):.1f}x"
    )
    assert np.isfinite(m(t_vec))


if __name__ == "__main__":
    main()
