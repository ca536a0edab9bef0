"""Mutation score per module, from the results of `mutmut run` (run `make mutation`, not this directly).

    .venv/bin/python scripts/mutation_report.py            # the table of README "Mutation testing"
    .venv/bin/python scripts/mutation_report.py --survivors  # also every mutant that is not killed

Reads `mutmut results --all true` (one line per mutant: ``skilllib.module.x_function__mutmut_N: status``)
and tests/mutation_equivalent.toml, the mutants judged equivalent (they change no observable behaviour),
each with the reason. Per module: mutants, killed (a test failed; a timeout counts as killed: the mutant
made a test hang), equivalent, not killed (survived or covered by no test), and the score

    killed / (mutants - equivalent)

which the issue asks to be at least 90 %. Exits 1 when an entry of the equivalence list names a mutant
that no longer exists or that a test kills (the list must stay true), 0 otherwise.
"""
from __future__ import annotations

import argparse
import collections
import re
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EQUIVALENT = ROOT / "tests" / "mutation_equivalent.toml"
KILLED = {"killed", "timeout", "caught by type check"}
LINE = re.compile(r"^\s*(?P<name>[\w.]+__mutmut_\d+): (?P<status>.+?)\s*$")


def mutmut_results(where: Path = ROOT) -> dict[str, str]:
    """Mutant name -> status, from ``mutmut results --all true`` in ``where`` (a checkout that ran mutmut)."""
    out = subprocess.run([sys.executable, "-m", "mutmut", "results", "--all", "true"], cwd=where,
                         capture_output=True, text=True, check=True).stdout
    return {m["name"]: m["status"] for m in map(LINE.match, out.splitlines()) if m}


#: Modules split from one of issue 11's six since it was filed, reported with it.
PARENT = {"_spectral": "smoothness", "csvtable": "data", "timing": "data", "ik": "transfer", "summary": "pipeline",
          "output": "pipeline"}


def module_of(name: str) -> str:
    """``skilllib.pipeline.x_run__mutmut_3`` -> ``pipeline`` (split-off modules with their parent: PARENT)."""
    module = name.split(".")[1]
    return PARENT.get(module, module)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--survivors", action="store_true", help="list every mutant that is not killed")
    ap.add_argument("--from", dest="dirs", action="append", type=Path, metavar="DIR",
                    help="read the results of mutmut runs in these checkouts (several runs that each mutated "
                         "some modules; default: this repository)")
    args = ap.parse_args()
    results = {}
    for where in args.dirs or [ROOT]:
        results.update(mutmut_results(where))
    if not results:
        print("no mutmut results: run `make mutation` first", file=sys.stderr)
        return 1
    equivalent = tomllib.loads(EQUIVALENT.read_text(encoding="utf-8")).get("equivalent", {}) if EQUIVALENT.exists() else {}
    stale = [n for n in equivalent if n not in results or results[n] in KILLED]
    rows = collections.defaultdict(collections.Counter)
    for name, status in results.items():
        row = rows[module_of(name)]
        row["mutants"] += 1
        if status in KILLED:
            row["killed"] += 1
        elif name in equivalent:
            row["equivalent"] += 1
        else:
            row["not killed"] += 1
    print("| module | mutants | killed | equivalent | not killed | score |")
    print("|---|---|---|---|---|---|")
    total = collections.Counter()
    for module in sorted(rows):
        r = rows[module]
        total.update(r)
        score = r["killed"] / max(r["mutants"] - r["equivalent"], 1)
        print(f"| `{module}` | {r['mutants']} | {r['killed']} | {r['equivalent']} | {r['not killed']} | {score:.1%} |")
    score = total["killed"] / max(total["mutants"] - total["equivalent"], 1)
    print(f"| all | {total['mutants']} | {total['killed']} | {total['equivalent']} | {total['not killed']} | {score:.1%} |")
    if args.survivors:
        print("\nnot killed:")
        for name, status in sorted(results.items()):
            if status not in KILLED and name not in equivalent:
                print(f"  {name}: {status}")
    if stale:
        print(f"\nthe equivalence list names mutants that are gone or killed: {', '.join(sorted(stale))}",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
