"""scripts/mutation_report.py, the table of benchmarks/README.md "Mutation testing": the score counts what it says, and
the interval of a sampled score is the Wilson interval (checked against scipy's)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest
from scipy.stats import binomtest

SPEC = importlib.util.spec_from_file_location(
    "mutation_report", Path(__file__).resolve().parents[1] / "scripts" / "mutation_report.py"
)
report = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(report)


@pytest.mark.parametrize("k, n", [(45, 50), (0, 7), (7, 7), (88, 96), (1, 2)])
def test_wilson_is_scipys_wilson_interval(k, n):
    """Catches a wrong centre or half-width (e.g. the normal-approximation interval, or z on the wrong side)."""
    ci = binomtest(k, n).proportion_ci(confidence_level=0.95, method="wilson")
    assert report.wilson(k, n) == pytest.approx((ci.low, ci.high), abs=1e-6)


def test_score_leaves_out_unchecked_and_equivalent_mutants():
    """A module of 10 mutants, 5 checked: 3 killed (one by a timeout), 1 equivalent, 1 survivor: score 3 / 4.
    Catches counting unchecked mutants as survivors, or equivalent ones as not killed."""
    names = [f"skilllib.smoothness.x_f__mutmut_{i}" for i in range(1, 11)]
    status = ["killed", "timeout", "segfault", "survived", "survived"] + ["not checked"] * 5
    results = dict(zip(names, status))
    rows = report.table(results, {names[3]: "reason"})
    row = [r for r in rows if r.startswith("| `smoothness`")][0]
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[1:7] == ["10", "5", "3", "1", "1", "75.0%"]
    low, high = report.wilson(3, 4)
    assert cells[7] == f"{low:.0%} to {high:.0%}"


def test_split_modules_count_with_their_parent_and_a_full_run_has_no_interval():
    """``_spectral`` is reported with its sub-package ``smoothness``, ``_ik`` with ``robot``; all checked: no
    interval."""
    results = {
        "skilllib.smoothness._spectral.x_a__mutmut_1": "killed",
        "skilllib.smoothness._measures.x_b__mutmut_1": "survived",
        "skilllib.robot._ik.x_c__mutmut_1": "killed",
    }
    rows = {r.split("|")[1].strip(): r for r in report.table(results, {})[2:]}
    assert set(rows) == {"`smoothness`", "`robot`", "all"}
    assert "| 2 | 2 | 1 | 0 | 1 | 50.0% | (all checked) |" in rows["`smoothness`"]
    assert "| 3 | 3 | 2 | 0 | 1 | 66.7% | (all checked) |" in rows["all"]


def test_a_sample_is_scored_against_its_module_with_an_interval():
    """A sample of 2 of a module's 20 mutants: mutants 20, checked 2, and the Wilson interval of 2 / 2
    (catches a sample reported as the whole module, "(all checked)")."""
    population = {f"skilllib.recordings._recordings.x_f__mutmut_{i}": "not checked" for i in range(1, 21)}
    sample = {
        "skilllib.recordings._recordings.x_f__mutmut_7": "killed",
        "skilllib.recordings._recordings.x_f__mutmut_17": "killed",
    }
    row = [r for r in report.table(sample, {}, {**population, **sample}) if r.startswith("| `recordings`")][0]
    low, high = report.wilson(2, 2)
    assert row == f"| `recordings` | 20 | 2 | 2 | 0 | 0 | 100.0% | {low:.0%} to {high:.0%} |"
