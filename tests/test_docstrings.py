"""Every public function and class of the sub-packages' public faces has a numpydoc docstring (issue 21):
a ``Parameters`` section listing exactly the signature's parameters, a ``Returns`` section unless it
returns None or is a class, and a unit (or "dimensionless", "samples", "text") for every numeric parameter.

The parser is a small one of numpydoc's sections (numpydoc itself is not a dependency): a section is a
title line underlined by dashes of the same length; an entry is an unindented ``name : type`` line (or a
bare ``name`` / type) followed by its indented description."""

from __future__ import annotations

import importlib
import inspect
import re

import pytest

SUBPACKAGES = [
    "smoothness",
    "recordings",
    "features",
    "prototypes",
    "cohort",
    "task",
    "figures",
    "datasets",
    "robot",
    "pipeline",
]

#: What a numeric parameter's entry must name: its unit, or that it has none.
UNIT = re.compile(
    r"(?<![\w/.^'’-])(m/s\^?2|m/s|rad/s\^?[23]|rad/s|rad|N m|Hz|deg|mm|m|s|dimensionless|samples|text|dots per inch)"
    r"(?![\w/(^])"
)
#: A documented type (or annotation) that is numeric: such a parameter needs a unit.
NUMERIC = re.compile(r"\b(float|int|complex|ndarray|array_like|ArrayLike|array|number)\b")
SECTIONS = ("Parameters", "Attributes", "Returns", "Yields", "Raises", "Warns", "See Also", "Notes", "Examples")


def parse_sections(doc: str) -> dict[str, list[tuple[str, str, str]]]:
    """The numpydoc sections of a docstring: title -> [(name, type, description)] of its entries.

    For ``Returns``/``Raises`` an entry without " : " is a type alone: its name is "" and its type the line."""
    lines = inspect.cleandoc(doc).splitlines()
    sections: dict[str, list[tuple[str, str, str]]] = {}
    current = None
    i = 0
    while i < len(lines):
        line = lines[i]
        underline = lines[i + 1] if i + 1 < len(lines) else ""
        if line.strip() and set(underline.strip()) == {"-"} and len(underline.strip()) == len(line.strip()):
            current = line.strip()
            assert current not in sections, f"section {current!r} twice"
            assert i == 0 or not lines[i - 1].strip(), f"no blank line before section {current!r} (reST needs one)"
            assert underline == "-" * len(line), f"section {current!r}: underline not of the title's length"
            sections[current] = []
            i += 2
            continue
        if current is not None and line and not line[0].isspace():
            head, sep, typ = line.partition(" : ")
            if not sep and current in ("Returns", "Yields", "Raises", "Warns"):
                head, typ = "", line
            sections[current].append((head.strip(), typ.strip(), ""))
        elif current is not None and line.strip() and sections[current]:
            name, typ, desc = sections[current][-1]
            sections[current][-1] = (name, typ, f"{desc} {line.strip()}".strip())
        i += 1
    return sections


def _names(head: str) -> list[str]:
    """``a, b`` documents two parameters; ``\\*\\*kwargs`` (escaped for reST) documents ``kwargs``."""
    return [n.strip().replace("\\", "").lstrip("*") for n in head.split(",") if n.strip()]


def public_callables(sub: str) -> list[tuple[str, object]]:
    """The functions and classes a sub-package's face makes public and the sub-package defines."""
    face = importlib.import_module(f"skilllib.{sub}")
    names = getattr(face, "__all__", None) or [n for n in vars(face) if not n.startswith("_")]
    out = []
    for name in names:
        obj = getattr(face, name)
        if not (inspect.isfunction(obj) or inspect.isclass(obj)):
            continue
        if not getattr(obj, "__module__", "").startswith(f"skilllib.{sub}"):
            continue  # re-exported from elsewhere (pathlib.Path, importlib.resources.files)
        out.append((name, obj))
    return out


def _parameters(obj) -> list[inspect.Parameter]:
    if inspect.isclass(obj) and issubclass(obj, BaseException) and "__init__" not in vars(obj):
        return []  # an exception takes its message
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return []
    return [p for p in sig.parameters.values() if p.name not in ("self", "cls") and not p.name.startswith("_")]


def problems(name: str, obj) -> list[str]:
    """What is wrong with the numpydoc docstring of ``obj`` (empty when nothing is)."""
    doc = inspect.getdoc(obj) if inspect.isclass(obj) else obj.__doc__
    if not doc or not doc.strip():
        return [f"{name}: no docstring"]
    out = []
    summary = inspect.cleandoc(doc).splitlines()[0]
    if not summary.strip():
        out.append(f"{name}: no one-line summary")
    try:
        sections = parse_sections(doc)
    except AssertionError as e:
        return [f"{name}: {e}"]
    params = _parameters(obj)
    # a dataclass documents its fields as Attributes, any class may as Parameters
    section = "Parameters"
    if inspect.isclass(obj) and "Parameters" not in sections and "Attributes" in sections:
        section = "Attributes"
    documented = {}
    for head, typ, desc in sections.get(section, []):
        for n in _names(head):
            documented[n] = (typ, desc)
    if params:
        if section not in sections:
            out.append(f"{name}: no Parameters section")
        expected = [p.name for p in params]
        missing = [p for p in expected if p not in documented]
        # a class's Attributes may list more than its constructor takes (properties, derived fields)
        extra = [] if section == "Attributes" else [d for d in documented if d not in expected]
        if missing:
            out.append(f"{name}: parameters not documented: {missing}")
        if extra:
            out.append(f"{name}: documented but not in the signature: {extra}")
        for p in params:
            if p.name not in documented:
                continue
            typ, desc = documented[p.name]
            if not typ:
                out.append(f"{name}: {p.name} has no type")
            ann = "" if p.annotation is inspect.Parameter.empty else str(p.annotation)
            numeric = NUMERIC.search(typ) or (not typ and NUMERIC.search(ann))
            if numeric and not UNIT.search(f"{typ} {desc}"):
                out.append(f"{name}: {p.name} ({typ}) names no unit nor 'dimensionless'")
            if not desc:
                out.append(f"{name}: {p.name} has no description")
    if not inspect.isclass(obj):
        ret = inspect.signature(obj).return_annotation
        if ret not in (None, "None") and "Returns" not in sections and "Yields" not in sections:
            out.append(f"{name}: no Returns section")
    return out


PARAMS = [pytest.param(sub, id=sub) for sub in SUBPACKAGES]


@pytest.mark.parametrize("sub", PARAMS)
def test_public_docstrings_are_numpydoc_with_units(sub):
    found = public_callables(sub)
    assert found, f"skilllib.{sub}: no public functions or classes found"
    wrong = [p for name, obj in found for p in problems(f"skilllib.{sub}.{name}", obj)]
    assert wrong == [], "\n".join(wrong)


def test_the_check_catches_a_missing_parameter_and_a_missing_unit():
    """The checker itself: a docstring that omits a parameter, and one whose speed has no unit, fail."""

    def f(speed: float, fs: float) -> float:
        """Summary.

        Parameters
        ----------
        speed : float
            The speed (m/s).

        Returns
        -------
        float
            Something (dimensionless).
        """

    def g(speed: float) -> float:
        """Summary.

        Parameters
        ----------
        speed : float
            The speed.

        Returns
        -------
        float
            Something (dimensionless).
        """

    def h(speed: float) -> float:
        """Summary.

        Parameters
        ----------
        speed : float
            The speed (m/s).
        """

    assert problems("f", f) == ["f: parameters not documented: ['fs']"]
    assert problems("g", g) == ["g: speed (float) names no unit nor 'dimensionless'"]
    assert problems("h", h) == ["h: no Returns section"]
