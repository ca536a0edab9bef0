"""Every number a chapter's prose states is printed, guarded or cited.

The landing page promises that every number the text states is checked. This test holds each
executed chapter (``BOOK_EXECUTED``, set by ``make test`` after nbmake) to it: every number in its
markdown cells and figure captions must appear

(a) in the chapter's outputs (stdout, ``text/plain``, ``text/html``, ``text/markdown``), or
(b) among the numeric literals of its code cells: the limits its hidden ``remove-cell`` checks assert,
    and the inputs its code sets ("200 noisy copies", "tiled 12 times": a prose number that describes
    an input is held to the code that sets it); comments, strings and assert messages do not count, or
(c) in ``tests/prose_constants.toml``, the cited constants (the paper's values, the device's
    datasheet, the generative model's parameters, unit definitions), each with its reason.

The rules, in the order they are applied:

- **What is prose.** Markdown cells (the text of admonitions such as ``{note}`` included) and the
  ``#| caption:`` lines of figure cells. Not prose: code spans, fenced code, display math
  (``$$ ... $$`` and ``{math}``: equations), link targets, labels ``(name)=``, HTML, citations
  (``[@key, Sect. 5]``, ``@key``).
- **Inline math** (``$...$``) is checked only for numbers written with a decimal point
  (``$-1.40$``, ``$\\sqrt{1 + 0.95^2} = -1.379$``): there, integers are exponents, indices and
  coefficients of formulas (``2^{N+4}``, ``10^{-9}``, ``(2\\pi)^3``).
- **References are not numbers**: "chapter 3", "chapters 3 and 4", "Sect. 5", "Sec. 4.1", "Fig. 1",
  "Eq. (1)", "Table 2", "step 4", "issue 25"; nor is a year after a capitalised name ("KI 2020"),
  nor a digit inside a name (``UR5``, ``3D``, ``Simple6``, ``1st``). A number that stands apart in a
  product's name ("Puma 560", "Phantom Premium 1.5") is a number: it passes where the chapter prints
  the name, as it does wherever it shows that arm's results, or as a cited constant.
- **Numbers written as words** ("ten people", "two thirds") are not extracted. Every number written
  in digits is, small integers included; but a small integer matches almost any output, so this
  test cannot catch a drifted small count (such as a seed): that stays the hidden checks' job.
- **Matching** is by rounding, on absolute values (the sign is usually in the words: "falls by",
  "below"): a prose number with d decimals matches a number that rounds to it at d decimals
  ("0.37" matches 0.3712, not 0.369). "1,500" is 1500. An integer after "about" (or "around",
  "roughly", "nearly", "some", "~") counts to its last non-zero digit: "about 8,000" is 7,500 to
  8,500, "about 45" stays 44.5 to 45.5.
- **Units**: a percentage "12 %" matches 12 (or 12.4) and the fraction 0.12 (or 0.124), and an output
  "12.0%" also counts as 0.12; a number in cm, mm, ms or µs also matches the value in m or s
  ("19 cm" matches 0.19). A range or list shares the unit of its last number ("8 to 19 cm",
  "381 x 267 x 191 mm", "25-75 %").
- A constant may name the ``unit`` that must follow it in the prose ("20" + "Hz" is the paper's
  cut-off; a "20 %" is not covered by it) and the ``context`` its sentence must match (the paper's
  650 trials are cited only in a sentence that names the paper: "the 650 selected trials" of the
  book's cohort must be printed). It is global or per chapter.

What this cannot catch: a number that drifted onto another number the chapter prints (a seed, a
small count: any output has a 1; a one-decimal value), or the paper's value swapped for the book's.
Measured on the chapters of one full run by moving the last digit of each stated number by 3: the
test reports 4 in 5 such drifts of integers above 10, 2 in 3 of numbers with two or more decimals,
1 in 3 of one-decimal numbers and hardly any of integers up to 10. The hidden checks stay the guard
of each claim; this test finds the numbers that have none.
"""

from __future__ import annotations

import ast
import bisect
import html
import json
import math
import os
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

import pytest
from markdown_it import MarkdownIt
from mdit_py_plugins.dollarmath import dollarmath_plugin

ROOT = Path(__file__).resolve().parents[1]
CONSTANTS = Path(__file__).with_name("prose_constants.toml")

# ------------------------------------------------------------------------------------ the prose --

_MD = MarkdownIt("commonmark").enable("table").use(dollarmath_plugin, allow_labels=True, double_inline=True)

# a number in prose: not glued to a word or to another number ("UR5", "v1.2", "3D", "1st")
_PROSE_NUMBER = re.compile(
    r"(?<![\w,^_])(?<!\w\.)(?P<int>\d{1,3}(?:,\d{3})+|\d+)(?:\.(?P<frac>\d+))?"
    r"(?:[eE](?P<exp>[-+−]?\d+))?(?![\w])(?!\.\d)(?P<pct>\s?(?:%|per ?cent\b))?"
)
_UNIT = re.compile(r"\s?(%|[A-Za-zµ°][\w/^*µ°-]*)")
# a range or a list shares the unit of its last number: "8 to 19 cm", "381 x 267 x 191 mm", "25-75 %"
_CONNECTORS = ("", "to", "and", "or", "x", "×")
_SHARED_UNIT = re.compile(r"(?:\s*(?:to|and|or|x|×|–|-|\.\.)\s*\d[\d.,]*(?<![.,]))+\s?(%|[A-Za-zµ°][\w/^*µ°-]*)")
# references: "chapter 3", "chapters 3 and 4", "Sect. 5", "Fig. 1", "Eq. (1)", "issue 25", ...
_REFERENCE = re.compile(
    r"\b(?:chapters?|sections?|secs?\.|sect\.|figs?\.|figures?|eqs?\.|equations?|tables?|steps?|items?"
    r"|parts?|issues?|appendix|lines?|pp?\.)\s*\(?\d+(?:\.\d+)*\)?(?:\s*(?:,|and|or|to|–|-)\s*\(?\d+(?:\.\d+)*\)?)*",
    re.IGNORECASE,
)
_YEAR = re.compile(r"\b[A-Z][\w&]* ((?:19|20)\d\d)\b(?![.,]\d)")  # "KI 2020": a name, then its year
_CITATION = re.compile(r"\[-?@[^\]]*\]|(?<![\w.])-?@[\w:.-]*\w")
_LABEL = re.compile(r"^\s*\([\w:.-]+\)=\s*$", re.MULTILINE)
_DIRECTIVE_OPTION = re.compile(r"^\s*:[\w-]+:.*$", re.MULTILINE)
_MATH_DECIMAL = re.compile(r"(?<![\w.])\d+\.\d+(?![\w.])")
_APPROXIMATE = re.compile(r"(?:\b(?:about|around|roughly|approximately|nearly|almost|some)|[~≈])\s*$", re.I)
_SUBUNITS = {"cm": 100.0, "mm": 1e3, "ms": 1e3, "µs": 1e6, "us": 1e6}
_SENTENCE_END = re.compile(r"(?<=[.!?:])\s+(?=[A-Z(*`$\[-])")
_ABBREVIATION = re.compile(r"(?:\b(?:e\.g|i\.e|cf|vs|al|approx|resp|Eqs?|Figs?|Sect|Ch|No|Ref|[A-Z]))\.$")


@dataclass(frozen=True)
class ProseNumber:
    """One number stated in the prose: its value (absolute), decimals, and where it stands."""

    text: str  # as written, e.g. "1,500", "0.37", "12 %"
    value: float
    decimals: int  # the last significant decimal: "0.37" 2, "3e-15" 15, "about 8,000" -3
    percent: bool
    unit: str  # the word after it ("Hz", "m/s", "trials"), "" when none
    sentence: str
    at: int = 0  # where in the sentence

    def excerpt(self, width: int = 90) -> str:
        """The sentence around the number, at most `width` characters either side."""
        lo, hi = max(0, self.at - width), self.at + len(self.text) + width
        return ("…" if lo else "") + self.sentence[lo:hi] + ("…" if hi < len(self.sentence) else "")

    @property
    def tolerance(self) -> float:
        return 0.5 * 10.0 ** (-self.decimals) * (1 + 1e-9)

    def readings(self) -> list[tuple[float, float]]:
        """(value, tolerance) in each unit an output may print it in: as written, and for a percentage,
        a length in cm or mm, a time in ms or µs, also as a fraction or in metres or seconds."""
        scale = 100.0 if self.percent else _SUBUNITS.get(self.unit)
        out = [(self.value, self.tolerance)]
        return out + [(self.value / scale, self.tolerance / scale)] if scale else out


def _inline_text(children) -> str:
    """An inline token's prose as one string: code spans and links' targets dropped, inline math
    replaced by its decimal numbers (see the module's docstring)."""
    out = []
    for tok in children or []:
        if tok.type == "text":
            out.append(tok.content)
        elif tok.type in ("softbreak", "hardbreak"):
            out.append(" ")
        elif tok.type == "code_inline":
            out.append("`…`")
        elif tok.type == "math_inline" or tok.type == "math_inline_double":
            nums = _MATH_DECIMAL.findall(tok.content)
            out.append("$" + " ".join(nums) + "$" if nums else "$…$")
    return "".join(out)


_FRONT_MATTER = re.compile(r"\A---[ \t]*\n.*?\n---[ \t]*(\n|\Z)", re.S)


def _paragraphs(markdown: str) -> list[str]:
    """The prose of a markdown text, one string per paragraph, heading, table cell or list item; a
    leading front matter block (a chapter's ``numbering``) is not prose."""
    markdown = _FRONT_MATTER.sub("", _LABEL.sub("", markdown), count=1)
    out: list[str] = []
    row: list[str] | None = None  # the cells of a table row, read as one sentence
    for tok in _MD.parse(markdown):
        if tok.type == "tr_open":
            row = []
        elif tok.type == "tr_close" and row is not None:
            out.append(" | ".join(row))
            row = None
        elif tok.type == "inline" and row is not None:
            row.append(_inline_text(tok.children))
        elif tok.type == "inline":
            out.append(_inline_text(tok.children))
        elif tok.type == "fence" and tok.info.startswith("{"):
            name, _, argument = tok.info.partition("}")
            name = name.strip("{ ")
            if name in ("math", "code", "code-block", "code-cell", "eval", "raw", "mermaid", "literalinclude"):
                continue
            if argument.strip() and name not in ("figure", "image", "include", "embed", "glue", "iframe"):
                out += _paragraphs(argument.strip())  # an admonition's title; not a figure's path
            out += _paragraphs(_DIRECTIVE_OPTION.sub("", tok.content))
    return out


def _sentences(paragraph: str) -> list[str]:
    """`paragraph` cut after each full stop that does not end an abbreviation ("Eq.", "e.g.")."""
    out, start = [], 0
    for m in _SENTENCE_END.finditer(paragraph):
        if not _ABBREVIATION.search(paragraph, 0, m.start()):
            out.append(paragraph[start : m.start()])
            start = m.end()
    out.append(paragraph[start:])
    return [s.strip() for s in out if s.strip()]


def prose_numbers(markdown: str) -> list[ProseNumber]:
    """Every number stated in `markdown` (a markdown cell's source), by the module's rules."""
    found = []
    for paragraph in _paragraphs(markdown):
        for sentence in _sentences(paragraph):
            blank = lambda m: " " * len(m.group())  # blanks keep the positions for the excerpt
            text = _REFERENCE.sub(blank, _CITATION.sub(blank, sentence))
            text = _YEAR.sub(lambda m: m.group()[: m.start(1) - m.start()] + "    ", text)
            for m in _PROSE_NUMBER.finditer(text):
                frac, exp = m["frac"] or "", (m["exp"] or "0").replace("−", "-")
                value = abs(float(f"{m['int'].replace(',', '')}.{frac or 0}e{exp}"))
                unit = "%" if m["pct"] else (_UNIT.match(text, m.end()) or [None, ""])[1]
                if unit in _CONNECTORS and (shared := _SHARED_UNIT.match(text, m.end())):
                    unit = shared[1]
                decimals = len(frac) - int(exp)
                digits = m["int"].replace(",", "")
                if not frac and digits != "0" and _APPROXIMATE.search(text, 0, m.start()):
                    decimals += len(digits.rstrip("0")) - len(digits)  # "about 8,000": only the 8 counts
                found.append(
                    ProseNumber(
                        text=m.group().strip() + (" %" if unit == "%" and not m["pct"] else ""),
                        value=value,
                        decimals=decimals,
                        percent=unit == "%",
                        unit=unit.rstrip(".,;:"),
                        sentence=sentence,
                        at=m.start(),
                    )
                )
    return found


def chapter_prose(nb: dict) -> list[ProseNumber]:
    """The numbers of a notebook's markdown cells and of its figures' ``#| caption:`` lines."""
    found = []
    for cell in nb["cells"]:
        source = _source(cell)
        if cell["cell_type"] == "markdown":
            found += prose_numbers(source)
        elif cell["cell_type"] == "code":
            for line in source.splitlines():
                if line.startswith("#| caption:"):
                    found += prose_numbers(line.removeprefix("#| caption:").strip())
    return found


# ------------------------------------------------------------- what the chapter prints and sets --

# in outputs anything that looks like a number counts (a table cell, "UR5", "fig-3", "1,500")
_OUTPUT_NUMBER = re.compile(r"(?<![\d.])\d+(?:\.\d*)?(?:[eE][-+]?\d+)?(?P<pct>\s?%)?")
_THOUSANDS = re.compile(r"(?<![\d.,])\d{1,3}(?:,\d{3})+(?![\d,])")
_TAG = re.compile(r"<[^>]+>")
_TEXT_MIMES = ("text/plain", "text/html", "text/markdown", "text/latex")


def _source(cell) -> str:
    src = cell.get("source", "")
    return "".join(src) if isinstance(src, list) else src


def _numbers_in_text(text: str) -> list[float]:
    values = []
    for m in _OUTPUT_NUMBER.finditer(text):
        try:
            v = abs(float(m.group().rstrip("% ")))
        except ValueError:
            continue
        values.append(v)
        if m["pct"]:
            values.append(v / 100)
    values += [float(m.group().replace(",", "")) for m in _THOUSANDS.finditer(text)]
    return values


def output_numbers(nb: dict) -> list[float]:
    """Every number in the text outputs of a notebook's code cells."""
    values = []
    for cell in nb["cells"]:
        for out in cell.get("outputs", []) if cell["cell_type"] == "code" else []:
            texts = [out.get("text", "")] if out.get("output_type") == "stream" else []
            data = out.get("data", {})
            texts += [data[m] for m in _TEXT_MIMES if m in data]
            for t in texts:
                t = "".join(t) if isinstance(t, list) else t
                if "<" in t:
                    t = html.unescape(_TAG.sub(" ", t))
                values += _numbers_in_text(t)
    return values


def _python(source: str) -> ast.AST | None:
    """A code cell's source as Python (IPython magics and shell lines left out), None if it is not."""
    lines = [line for line in source.splitlines() if not line.lstrip().startswith(("%", "!"))]
    try:
        return ast.parse("\n".join(lines))
    except SyntaxError:
        return None


def code_literals(nb: dict) -> list[float]:
    """The numeric literals of a notebook's code cells; strings, comments and assert messages are not
    literals (a claim's own text in its check's message cannot vouch for it)."""
    values = []
    for cell in nb["cells"]:
        if cell["cell_type"] != "code" or (tree := _python(_source(cell))) is None:
            continue
        messages = {id(n) for a in ast.walk(tree) if isinstance(a, ast.Assert) and a.msg for n in ast.walk(a.msg)}
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Constant)
                and isinstance(node.value, int | float)
                and not isinstance(node.value, bool)
                and id(node) not in messages
            ):
                values.append(abs(float(node.value)))
    return values


# ----------------------------------------------------------------------------------- constants --


@dataclass(frozen=True)
class Constant:
    value: float
    unit: str
    reason: str
    context: str = ""  # a regular expression the sentence must match (case-insensitive), e.g. "paper"


def load_constants(path: Path = CONSTANTS) -> dict[str, list[Constant]]:
    """``prose_constants.toml``: ``[[global]]`` and ``[[chapter.<stem>]]`` entries, each with a
    ``value``, a ``reason``, and optionally the ``unit`` that must follow the number in the prose and
    the ``context`` its sentence must match (the source it cites: "paper")."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    out: dict[str, list[Constant]] = {}

    def entries(rows, where):
        for row in rows:
            assert set(row) <= {"value", "unit", "reason", "context"} and isinstance(row.get("value"), int | float), (
                f"{path.name} [{where}]: each entry has a number `value`, a `reason`, optionally `unit` and"
                f" `context`: {row}"
            )
            assert len(str(row.get("reason", "")).strip()) >= 10, f"{path.name} [{where}]: {row} needs a reason"
            yield Constant(float(row["value"]), row.get("unit", ""), row["reason"], row.get("context", ""))

    out["global"] = list(entries(data.get("global", []), "global"))
    for stem, rows in data.get("chapter", {}).items():
        out[stem] = list(entries(rows, f"chapter.{stem}"))
    return out


# ----------------------------------------------------------------------------------- the check --


class _Values:
    """A sorted multiset of absolute values, asked whether any lies within a prose number's rounding."""

    def __init__(self, values):
        self.sorted = sorted(v for v in values if math.isfinite(v))

    def has(self, lo: float, hi: float) -> bool:
        i = bisect.bisect_left(self.sorted, lo)
        return i < len(self.sorted) and self.sorted[i] <= hi

    def matches(self, n: ProseNumber) -> bool:
        return any(self.has(v - tol, v + tol) for v, tol in n.readings())


def _constant_covers(c: Constant, n: ProseNumber) -> bool:
    if c.unit and c.unit != n.unit:
        return False
    if c.context and not re.search(c.context, n.sentence, re.IGNORECASE):
        return False
    return abs(c.value - n.value) <= n.tolerance


def unsupported_numbers(nb: dict, constants: list[Constant]) -> list[ProseNumber]:
    """The prose numbers of `nb` found neither in its outputs, nor in its code's literals, nor among
    `constants`."""
    values = _Values(output_numbers(nb) + code_literals(nb))
    return [
        n for n in chapter_prose(nb) if not values.matches(n) and not any(_constant_covers(c, n) for c in constants)
    ]


def report(stem: str, missing: list[ProseNumber]) -> str:
    lines = [f"{stem}: {len(missing)} number(s) of the prose neither printed, checked nor cited:"]
    lines += [f"  {n.text!r} in: {n.excerpt()}" for n in missing]
    lines.append(
        "Print each in a cell and guard it in the remove-cell check after it, or, if it is a cited constant"
        " (the paper, a datasheet, a definition), list it with its reason in tests/prose_constants.toml."
    )
    return "\n".join(lines)


# -------------------------------------------------------------------------- the extractor's tests --


def _notebook(markdown: list[str], code: list[tuple[str, str, list[str]]]) -> dict:
    """A notebook dict: markdown cells, then code cells (source, printed stdout, tags)."""
    cells = [{"cell_type": "markdown", "metadata": {}, "source": m} for m in markdown]
    for source, printed, tags in code:
        outputs = [{"output_type": "stream", "name": "stdout", "text": printed}] if printed else []
        cells.append({"cell_type": "code", "metadata": {"tags": tags}, "source": source, "outputs": outputs})
    return {"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}


def test_a_printed_number_passes_and_a_drifted_one_is_reported():
    nb = _notebook(
        ["The silhouette is 0.369, beside the paper's 0.337; 650 trials are kept."],
        [("print(round(s, 3), n_selected)", "0.3712 652\n", [])],
    )
    missing = unsupported_numbers(nb, [Constant(0.337, "", "the paper's silhouette at k = 6")])
    assert [n.text for n in missing] == ["0.369", "650"], "0.3712 rounds to 0.371, 652 is not 650"
    assert missing[0].sentence.startswith("The silhouette is 0.369")
    assert "'0.369' in: The silhouette" in report("04_x", missing)
    # rounded as printed: "0.37" is what 0.3712 rounds to; "1,652" is the printed 1652
    nb["cells"][0]["source"] = "The silhouette is 0.37 and 652 trials are kept."
    assert unsupported_numbers(nb, []) == []
    nb["cells"][1]["outputs"][0]["text"] = "0.3712 1652\n"
    nb["cells"][0]["source"] = "The silhouette is 0.37 and 1,652 trials are kept, not 652."
    assert [n.text for n in unsupported_numbers(nb, [])] == ["652"]
    nb["cells"][0]["source"] = "The silhouette is 0.38."
    assert [n.text for n in unsupported_numbers(nb, [])] == ["0.38"]


def test_a_checked_literal_counts_but_not_the_check_message_or_a_comment():
    check = 'assert abs(s - 0.369) < 1e-3, "text: the silhouette is 0.412"  # 0.5 in a comment\n'
    nb = _notebook(["The silhouette is 0.369, not 0.412 or 0.5."], [(check, "", ["remove-cell"])])
    assert [n.text for n in unsupported_numbers(nb, [])] == ["0.412", "0.5"]


def test_percentages_match_fractions_and_percent_outputs():
    nb = _notebook(["12 % of the trials switch; 0.4 of them are slow; 7 % are capped."], [("x", "0.1187 40.0%\n", [])])
    assert [n.text for n in unsupported_numbers(nb, [])] == ["7 %"]
    assert [(n.value, n.percent) for n in prose_numbers("about 12 % and 12 per cent")] == [(12, True), (12, True)]


def test_what_is_not_a_stated_number():
    md = (
        "(sec-x)=\n## Chapter 3 and Sect. 5\n\n"
        "As chapters 3 and 4 show [@maldonado2020, Sect. 5; @maldonado2019], the KI 2020 paper's Eq. (1) "
        "on the UR5 and Simple6 in 3D, `fc=10`, [see](#fig-3), $2^{N+4}$ and $10^{-9}$, the 1st trial.\n\n"
        "$$\nv = 30 \\tau^2 + 1.875\n$$ (eq-mj)\n\n"
        "```{note}\n:class: dropdown\nThe note states 1,500 trials at $-1.40$ and 3e-15.\n```\n\n"
        "```python\nx = 77\n```\n\n"
        "```{figure} images/01_fig.png\n:width: 80%\nThe caption states 0.5 m/s (Sec. 4.1).\n```\n"
    )
    found = prose_numbers(md)
    assert [(n.text, n.value, n.decimals) for n in found] == [
        ("1,500", 1500, 0),
        ("1.40", 1.40, 2),
        ("3e-15", 3e-15, 15),
        ("0.5", 0.5, 1),
    ]
    assert found[0].unit == "trials" and found[0].sentence.startswith("The note states")
    # a chapter's front matter (its numbering) is not prose; a rule later in the text is not front matter
    md = '---\nnumbering:\n  enumerator: "8.%s"\n---\n# Title\n\nWe saw 12 trials.\n\n---\n\nThen 13.\n'
    assert [n.text for n in prose_numbers(md)] == ["12", "13"]


def test_a_constant_with_a_unit_covers_only_that_unit():
    nb = _notebook(["The cut-off is 20 Hz; 20 % noise; a 20 s wait."], [])
    fc = Constant(20, "Hz", "the paper's maximum cut-off")
    assert [n.text for n in unsupported_numbers(nb, [fc])] == ["20 %", "20"]
    assert unsupported_numbers(nb, [Constant(20, "", "any twenty at all")]) == []


def test_about_units_ranges_and_tables():
    nb = _notebook(
        [
            "About 8,000 points; about 45 s; 8 to 19 cm; a 16.7 ms interval; 25-75 % of peak.",
            "| code | meaning |\n|---|---|\n| 130 | interrupted |\n| 3 | no clusters |\n",
        ],
        [("n = 7_812", "0.19 m, 0.0167 s, 44.2 s, 0.25 and 0.75, 3\n", [])],
    )
    missing = unsupported_numbers(nb, [])
    assert [n.text for n in missing] == ["45", "8", "130"], "44.2 is not about 45; 0.08 m and 130 are printed nowhere"
    assert missing[2].sentence == "130 | interrupted", "a table row is one sentence"
    assert [n.decimals for n in prose_numbers("about 8,000, about 1e-15 and about 0.5")] == [-3, 15, 1]


def test_a_constant_with_a_context_covers_only_sentences_that_cite_it():
    nb = _notebook(["The paper keeps 650 trials.", "The cohort keeps 650 trials [@maldonado2020]."], [])
    paper = Constant(650, "", "the paper's selected trials", context=r"paper|@maldonado2020")
    assert unsupported_numbers(nb, [paper]) == []
    nb["cells"][1]["source"] = "The cohort keeps 650 trials."
    assert [n.sentence for n in unsupported_numbers(nb, [paper])] == ["The cohort keeps 650 trials."]


def test_captions_are_prose():
    nb = _notebook([], [("#| label: fig-x\n#| caption: Synthetic cohort. The 0.3-0.7 m/s window.\nf()", "", [])])
    assert [n.text for n in unsupported_numbers(nb, [])] == ["0.3", "0.7"]


def test_the_constants_file_is_well_formed():
    constants = load_constants()
    assert constants["global"], "the paper's numbers are global constants"
    chapters = {p.stem for p in (ROOT / "notebooks").glob("[0-9][0-9]_*.py")}
    assert set(constants) - {"global"} <= chapters, "a [[chapter.X]] names no chapter"


# ------------------------------------------------------------------------------- the book's test --


def _executed_chapters() -> list[Path]:
    folder = os.environ.get("BOOK_EXECUTED")  # set by `make test` after nbmake
    if not folder:
        return []
    return sorted(Path(folder).glob("[0-9][0-9]_*.ipynb"))


@pytest.mark.book_site
@pytest.mark.parametrize("path", _executed_chapters() or [None], ids=lambda p: p.stem if p else "none")
def test_every_number_of_the_prose_is_printed_checked_or_cited(path):
    if path is None:
        pytest.skip("BOOK_EXECUTED is not set (make test sets it to the chapters nbmake executed)")
    nb = json.loads(path.read_text(encoding="utf-8"))
    assert any(c.get("outputs") for c in nb["cells"] if c["cell_type"] == "code"), f"{path} was not executed"
    constants = load_constants()
    missing = unsupported_numbers(nb, constants["global"] + constants.get(path.stem, []))
    if missing:
        pytest.fail(report(path.stem, missing), pytrace=False)
