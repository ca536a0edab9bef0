"""Large synthetic corpora, quickly: the book's cohort tiled with jittered copies.

The generator (:mod:`skilllib.cohort`) makes about 200 trials/s; a corpus of 10^6 trials would take
well over an hour. Here copy ``c`` of the cohort's 1,500 trials is the cohort with

* participants renamed ``c{c:05d}-{participant}`` (10 new participants per copy),
* every trial's positions scaled about its first sample by a factor drawn uniformly from
  ``1 +- SCALE_JITTER`` (speeds scale with it, so PV and contact speed move and the selection changes;
  SPARC and LDLJ, which do not depend on amplitude, stay) and shifted by up to ``SHIFT_M`` per axis,
* rounded to the recordings format's 0.01 mm.

Copy 0 is the cohort unchanged. Synthetic data, seeded: the same arguments give the same bytes.

    .venv/bin/python benchmarks/corpus.py --copies 100 --out _build/bench/corpus-150k.csv
    .venv/bin/python benchmarks/corpus.py --copies 100 --parquet --per-file 10 --out _build/bench/corpus-150k
"""

from __future__ import annotations

import argparse
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.csv as pacsv
import pyarrow.parquet as pq

from skilllib.datasets import cohort_path
from skilllib.recordings import read_recordings

SCALE_JITTER = 0.05  #: +- relative amplitude change per trial
SHIFT_M = 0.02  #: m, +- shift per axis per trial
SEED = 20201


def _cohort() -> dict[str, np.ndarray]:
    rec = read_recordings(cohort_path())
    f = rec.frame
    keys = f["participant"].astype(str).to_numpy() + "\x00" + f["trial"].astype(str).to_numpy()
    _, first, trial_of_row = np.unique(keys, return_index=True, return_inverse=True)
    order = np.argsort(first)  # trial numbers in order of appearance
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return {
        "participant": f["participant"].astype(str).to_numpy(dtype=object),
        "trial": f["trial"].astype(str).to_numpy(dtype=object),
        "t": f["t"].to_numpy(),
        "pos": f[["x", "y", "z"]].to_numpy(),
        "contact": f["contact"].to_numpy().astype(np.int8),
        "trial_of_row": rank[trial_of_row],
    }


def copies(n_copies: int, seed: int = SEED) -> Iterator[pa.Table]:
    """One Arrow table per copy of the cohort (columns of the recordings format)."""
    base = _cohort()
    n_trials = int(base["trial_of_row"].max()) + 1
    first = np.zeros(n_trials, dtype=np.int64)
    np.minimum.at(first, base["trial_of_row"], np.arange(len(base["t"])))
    first_pos = base["pos"][first][base["trial_of_row"]]
    rng = np.random.default_rng(seed)
    for c in range(n_copies):
        if c == 0:
            scale, shift = np.ones(n_trials), np.zeros((n_trials, 3))
        else:
            scale = 1 + rng.uniform(-SCALE_JITTER, SCALE_JITTER, n_trials)
            shift = rng.uniform(-SHIFT_M, SHIFT_M, (n_trials, 3))
        s = scale[base["trial_of_row"]][:, None]
        pos = np.round(first_pos + s * (base["pos"] - first_pos) + shift[base["trial_of_row"]], 5) + 0.0
        part = base["participant"] if c == 0 else np.char.add(f"c{c:05d}-", base["participant"].astype(str))
        yield pa.table(
            {
                "participant": pa.array(part, pa.string()),
                "trial": pa.array(base["trial"], pa.string()),
                "t": base["t"],
                "x": pos[:, 0],
                "y": pos[:, 1],
                "z": pos[:, 2],
                "contact": base["contact"],
            }
        )


def write_csv(path: Path, n_copies: int, seed: int = SEED) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    options = pacsv.WriteOptions(include_header=False, quoting_style="none")
    with open(path, "wb") as f:
        f.write((",".join(copies_schema().names) + "\n").encode())
        with pacsv.CSVWriter(f, copies_schema(), write_options=options) as w:
            for table in copies(n_copies, seed):
                w.write_table(table)
    return path


def write_parquet(folder: Path, n_copies: int, per_file: int, seed: int = SEED) -> Path:
    """A folder of Parquet files, ``per_file`` copies (15,000 trials for 10) in each: trials never split."""
    folder.mkdir(parents=True, exist_ok=True)
    batch: list[pa.Table] = []
    k = 0
    for i, table in enumerate(copies(n_copies, seed)):
        batch.append(table)
        if len(batch) == per_file or i == n_copies - 1:
            pq.write_table(pa.concat_tables(batch), folder / f"part-{k:05d}.parquet")
            batch, k = [], k + 1
    return folder


def copies_schema() -> pa.Schema:
    return pa.schema(
        [
            ("participant", pa.string()),
            ("trial", pa.string()),
            ("t", pa.float64()),
            ("x", pa.float64()),
            ("y", pa.float64()),
            ("z", pa.float64()),
            ("contact", pa.int8()),
        ]
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--copies", type=int, required=True, help="copies of the 1,500-trial cohort")
    ap.add_argument("--out", type=Path, required=True, help="a .csv file, or a folder with --parquet")
    ap.add_argument("--parquet", action="store_true", help="write a folder of Parquet files")
    ap.add_argument("--per-file", type=int, default=10, help="copies per Parquet file (default 10)")
    ap.add_argument("--seed", type=int, default=SEED)
    args = ap.parse_args()
    if args.parquet:
        write_parquet(args.out, args.copies, args.per_file, args.seed)
    else:
        write_csv(args.out, args.copies, args.seed)
    print(args.out)


if __name__ == "__main__":
    main()
