"""The book's headline results on many draws of the generative model: write or check replication.csv.

    .venv/bin/python scripts/replicate_draws.py            # seeds 0..23 -> skilllib/cohort/replication.csv
    .venv/bin/python scripts/replicate_draws.py --check    # recompute every row and compare with the file
    .venv/bin/python scripts/replicate_draws.py --seeds 0-3 --out /tmp/r.csv --jobs 2

Each row is :func:`skilllib.cohort.draw_results` of one seed (about 5 s each after the imports, mostly
generating the cohort; the robot part takes under a second). ``--check`` recomputes the rows of the file's
seeds and fails (exit status 1) when a value differs by more than 1e-9 (relative or absolute) or a count
differs at all.
"""

from __future__ import annotations

import argparse
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

from skilllib.cohort import DRAW_QUANTITIES, REPLICATION_CSV, draw_results, read_replication

#: The seeds committed (0..23): at least 20 draws beside the book's seed 9.
DEFAULT_SEEDS = range(24)
TOL = 1e-9


def parse_seeds(text: str) -> list[int]:
    """Seeds from '0-23' or '1,4,9' (or both: '0-3,9')."""
    out: list[int] = []
    for part in text.split(","):
        lo, _, hi = part.strip().partition("-")
        out += list(range(int(lo), int(hi) + 1)) if hi else [int(lo)]
    return out


def compute(seeds: list[int], jobs: int) -> pd.DataFrame:
    """The table of the seeds, in their order, timing each draw on stderr."""
    start = time.perf_counter()
    rows = []
    with ProcessPoolExecutor(jobs) if jobs > 1 else _Serial() as pool:
        for s, (row, took) in zip(seeds, pool.map(_timed, seeds)):
            print(f"seed {s}: {took:.1f} s", file=sys.stderr, flush=True)
            rows.append(row)
    total = time.perf_counter() - start
    print(f"{len(seeds)} draws in {total:.0f} s ({total / max(len(seeds), 1):.1f} s a draw)", file=sys.stderr)
    return pd.DataFrame(rows, columns=["seed", *DRAW_QUANTITIES]).set_index("seed")


def _timed(seed: int) -> tuple[dict, float]:
    t = time.perf_counter()
    row = draw_results(seed)
    return row, time.perf_counter() - t


class _Serial:
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def map(self, fn, items):
        return map(fn, items)


def differences(committed: pd.DataFrame, fresh: pd.DataFrame) -> list[str]:
    """Each cell of ``fresh`` that differs from ``committed`` beyond :data:`TOL` (counts and bools exactly)."""
    out = []
    if list(committed.columns) != list(fresh.columns):
        out.append(f"columns differ: {list(committed.columns)} vs {list(fresh.columns)}")
        return out
    for seed in fresh.index:
        if seed not in committed.index:
            out.append(f"seed {seed} missing from the file")
            continue
        for col in fresh.columns:
            a, b = committed.at[seed, col], fresh.at[seed, col]
            if isinstance(b, float | np.floating) and not float(b).is_integer():
                same = np.isclose(float(a), float(b), rtol=TOL, atol=TOL)
            else:
                same = a == b
            if not same:
                out.append(f"seed {seed}, {col}: file {a!r}, recomputed {b!r}")
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", default=None, help="seeds, e.g. 0-23 or 0-3,9 (default 0-23; --check: the file's)")
    ap.add_argument("--out", type=Path, default=REPLICATION_CSV, help="the CSV file (default the package data)")
    ap.add_argument("--check", action="store_true", help="recompute the file's rows and compare; write nothing")
    ap.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    args = ap.parse_args(argv)
    if args.check:
        committed = read_replication(args.out)
        seeds = parse_seeds(args.seeds) if args.seeds else [int(s) for s in committed.index]
        diff = differences(committed, compute(seeds, args.jobs))
        for line in diff:
            print(line)
        print(f"{args.out}: {'differs' if diff else 'reproduced'} ({len(seeds)} seeds)")
        return 1 if diff else 0
    seeds = parse_seeds(args.seeds) if args.seeds else list(DEFAULT_SEEDS)
    table = compute(seeds, args.jobs)
    table.to_csv(args.out)
    print(f"wrote {args.out} ({len(table)} seeds)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
