"""Start-up of the command line: wall time of `python -m skilllib --help` and `run --help`, beside the
import of the libraries a run needs (what --help used to import), interleaved, median of R repeats.

    .venv/bin/python benchmarks/bench_cli.py [--repeats R]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

CASES = {
    "python -m skilllib --help": [sys.executable, "-m", "skilllib", "--help"],
    "python -m skilllib run --help": [sys.executable, "-m", "skilllib", "run", "--help"],
    "python -m skilllib --version": [sys.executable, "-m", "skilllib", "--version"],
    "python -c pass (the interpreter alone)": [sys.executable, "-c", "pass"],
    "import pandas, sklearn, roboticstoolbox, matplotlib": [
        sys.executable,
        "-c",
        "import pandas, sklearn.cluster, roboticstoolbox, matplotlib.pyplot",
    ],
}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=11)
    args = ap.parse_args()
    times: dict[str, list[float]] = {name: [] for name in CASES}
    for _ in range(args.repeats):
        for name, cmd in CASES.items():
            t0 = time.perf_counter()
            subprocess.run(cmd, check=True, capture_output=True)
            times[name].append(time.perf_counter() - t0)
    print("| command | median wall time (s) | min (s) |")
    print("|---|---|---|")
    for name, ts in times.items():
        print(f"| `{name}` | {statistics.median(ts):.3f} | {min(ts):.3f} |")


if __name__ == "__main__":
    main()
