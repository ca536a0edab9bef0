"""Mutation score per module, from the results of `mutmut run` (run `make mutation` or
`make mutation-sample`, not this directly).

    .venv/bin/python scripts/mutation_report.py              # the table of benchmarks/README.md "Mutation testing"
    .venv/bin/python scripts/mutation_report.py --survivors  # also every checked mutant that is not killed
    .venv/bin/python scripts/mutation_report.py --only 'skilllib.*__mutmut_*7'  # the sample only

Reads `mutmut results --all true` (one line per mutant: ``skilllib.module.x_function__mutmut_N: status``)
and tests/mutation_equivalent.toml, the mutants judged equivalent (they change no observable behaviour),
each with the reason. Per module: mutants (all that mutmut generated), checked (those run: all of them
after `make mutation`, the systematic sample of `make mutation-sample` after that), killed (a test failed;
a timeout or a crash of the test process counts as killed: the mutant made the tests hang or die),
equivalent, not killed (survived, or covered by no test), and the score

    killed / (checked - equivalent)

which issue 11 asks to be at least 90 %. When only a sample was checked the score is an estimate of the
whole module's, given with its 95 % Wilson score interval (binomial; the systematic sample treated as a
random one). Exits 1 when an entry of the equivalence list names a mutant that no longer exists or that a
test kills (the list must stay true), 0 otherwise.
"""

from __future__ import annotations

import argparse
import collections
import fnmatch
import math
import re
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EQUIVALENT = ROOT / "tests" / "mutation_equivalent.toml"
KILLED = {"killed", "timeout", "segfault", "caught by type check"}
NOT_RUN = {"not checked"}
LINE = re.compile(r"^\s*(?P<name>[\w.ǁ]+__mutmut_\d+): (?P<status>.+?)\s*$")
Z95 = 1.959964  # two-sided 95 % normal quantile


def mutmut_results(where: Path = ROOT) -> dict[str, str]:
    """Mutant name -> status, from ``mutmut results --all true`` in ``where`` (a checkout that ran mutmut)."""
    out = subprocess.run(
        [sys.executable, "-m", "mutmut", "results", "--all", "true"],
        cwd=where,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    return {m["name"]: m["status"] for m in map(LINE.match, out.splitlines()) if m}


def module_of(name: str) -> str:
    """``skilllib.pipeline._run.x_run__mutmut_3`` -> ``pipeline``: mutants are reported per sub-package."""
    return name.split(".")[1]


def wilson(k: int, n: int, z: float = Z95) -> tuple[float, float]:
    """The Wilson score interval of a binomial proportion k / n (Wilson 1927): (low, high), or (0, 1)
    when n is 0."""
    if n == 0:
        return 0.0, 1.0
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return max(0.0, centre - half), min(1.0, centre + half)


def table(results: dict[str, str], equivalent: dict[str, str], population: dict[str, str] | None = None) -> list[str]:
    """The Markdown table of benchmarks/README.md "Mutation testing", one row per sub-package and one for
    all. ``mutants`` counts the mutants of ``population`` (default: ``results``; all of mutmut's mutants
    when ``results`` is a sample of them), ``checked`` those of ``results`` that were run."""
    rows = collections.defaultdict(collections.Counter)
    for name in population if population is not None else results:
        rows[module_of(name)]["mutants"] += 1
    for name, status in results.items():
        row = rows[module_of(name)]
        if status in NOT_RUN:
            continue
        row["checked"] += 1
        if status in KILLED:
            row["killed"] += 1
        elif name in equivalent:
            row["equivalent"] += 1
        else:
            row["not killed"] += 1
    lines = [
        "| module | mutants | checked | killed | equivalent | not killed | score | 95 % interval |",
        "|---|---|---|---|---|---|---|---|",
    ]
    total = collections.Counter()
    for module in [*sorted(rows), "all"]:
        r = total if module == "all" else rows[module]
        if module != "all":
            total.update(r)
        n = r["checked"] - r["equivalent"]
        score = f"{r['killed'] / n:.1%}" if n else "-"
        low, high = wilson(r["killed"], n)
        interval = "(all checked)" if r["checked"] == r["mutants"] else f"{low:.0%} to {high:.0%}"
        label = "all" if module == "all" else f"`{module}`"
        lines.append(
            f"| {label} | {r['mutants']} | {r['checked']} | {r['killed']} | {r['equivalent']} | "
            f"{r['not killed']} | {score} | {interval} |"
        )
    return lines


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--survivors", action="store_true", help="list every checked mutant that is not killed")
    ap.add_argument(
        "--only",
        metavar="PATTERN",
        help="count only the mutants whose name matches this fnmatch pattern (the sample of "
        "`make mutation-sample`: 'skilllib.*__mutmut_*7')",
    )
    ap.add_argument(
        "--from",
        dest="dirs",
        action="append",
        type=Path,
        metavar="DIR",
        help="read the results of mutmut runs in these checkouts (default: this repository)",
    )
    args = ap.parse_args()
    results: dict[str, str] = {}
    for where in args.dirs or [ROOT]:
        for name, status in mutmut_results(where).items():
            if status not in NOT_RUN or name not in results:
                results[name] = status
    everything = results
    if args.only:
        results = {n: s for n, s in results.items() if fnmatch.fnmatchcase(n, args.only)}
    if not results:
        print("no mutmut results: run `make mutation` or `make mutation-sample` first", file=sys.stderr)
        return 1
    equivalent = (
        tomllib.loads(EQUIVALENT.read_text(encoding="utf-8")).get("equivalent", {}) if EQUIVALENT.exists() else {}
    )
    print("\n".join(table(results, equivalent, everything)))
    if args.survivors:
        print("\nnot killed:")
        for name, status in sorted(results.items()):
            if status not in KILLED | NOT_RUN and name not in equivalent:
                print(f"  {name}: {status}")
    stale = [n for n in equivalent if n not in everything or everything[n] in KILLED]
    if stale:
        print(
            f"\nthe equivalence list names mutants that are gone or killed: {', '.join(sorted(stale))}", file=sys.stderr
        )
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
