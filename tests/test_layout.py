"""The package's structure (CONTRIBUTING.md "Layout"): sub-packages along the paper's pipeline, each
importing only those before it, through their public faces, with no private name crossing a border."""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

import skilllib

PACKAGE = Path(skilllib.__file__).parent
#: The sub-packages in their order: each may import only those before it.
LAYERS = [
    "datasets",
    "smoothness",
    "recordings",
    "features",
    "prototypes",
    "robot",
    "cohort",
    "task",
    "figures",
    "pipeline",
]


def _modules() -> list[tuple[str, Path]]:
    out = []
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE.parent).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out.append((".".join(parts), path))
    return out


def _imports(module: str, path: Path) -> list[tuple[str, list[str], int]]:
    """(absolute module imported from, names, line) of every skilllib import of a module, lazy ones too."""
    is_package = path.name == "__init__.py"
    out = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = module.split(".") if is_package else module.split(".")[:-1]
                base = base[: len(base) - node.level + 1]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module or ""
            if source == "skilllib" or source.startswith("skilllib."):
                out.append((source, [a.name for a in node.names], node.lineno))
        elif isinstance(node, ast.Import):
            out += [(a.name, [], node.lineno) for a in node.names if a.name.startswith("skilllib")]
    return out


def _subpackage(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in LAYERS else None


MODULES = _modules()


def test_every_module_lives_in_a_subpackage_of_the_pipeline():
    """No flat top-level module is left beside the sub-packages (the front door and __main__ excepted)."""
    loose = [m for m, p in MODULES if _subpackage(m) is None and m not in ("skilllib", "skilllib.__main__")]
    assert loose == []
    assert sorted({_subpackage(m) for m, _ in MODULES} - {None}) == sorted(LAYERS)


@pytest.mark.parametrize("module,path", MODULES, ids=[m for m, _ in MODULES])
def test_imports_go_down_the_layers_through_public_faces(module, path):
    """A module imports its own sub-package's private modules, or another sub-package before its own by
    that sub-package's public name; never a later sub-package, never a private module or name across."""
    mine = _subpackage(module)
    for source, names, line in _imports(module, path):
        theirs = _subpackage(source)
        where = f"{path.relative_to(PACKAGE.parent)}:{line}"
        if mine is None or theirs is None or theirs == mine:
            if mine is None and theirs is not None:  # the front door and __main__: public faces only
                assert not any(p.startswith("_") for p in source.split(".")[2:]), where
            continue
        assert LAYERS.index(theirs) < LAYERS.index(mine), f"{where}: {mine} imports {theirs}, a later sub-package"
        private = [p for p in source.split(".")[2:] if p.startswith("_")]
        assert not private, f"{where}: imports the private module {source} of {theirs}"
        if source == "skilllib":  # from .. import recordings
            assert all(not n.startswith("_") for n in names if n != "__version__"), where
        assert not [n for n in names if n.startswith("_") and n != "__version__"], (
            f"{where}: a private name of {theirs}"
        )


@pytest.mark.parametrize("sub", LAYERS)
def test_every_name_of_a_public_face_resolves(sub):
    """Each name a sub-package lists in ``__all__`` exists (a face that promises a moved name fails)."""
    package = importlib.import_module(f"skilllib.{sub}")
    for name in getattr(package, "__all__", []):
        assert getattr(package, name) is not None, f"skilllib.{sub}.{name}"


def test_the_front_door_resolves_every_name():
    for name in skilllib.__all__:
        assert hasattr(skilllib, name), name


def test_no_cycle_between_private_modules():
    """Within a sub-package the private modules import each other without a cycle."""
    graph = {m: set() for m, _ in MODULES}
    for module, path in MODULES:
        for source, names, _ in _imports(module, path):
            for target in [source, *(f"{source}.{n}" for n in names)]:
                if target in graph and target != module and _subpackage(target) == _subpackage(module):
                    graph[module].add(target)
    state: dict[str, int] = {}

    def visit(node: str, stack: list[str]) -> None:
        state[node] = 1
        for nxt in graph[node]:
            if state.get(nxt) == 1:
                raise AssertionError("import cycle: " + " -> ".join([*stack, node, nxt]))
            if nxt not in state:
                visit(nxt, [*stack, node])
        state[node] = 2

    for node in graph:
        if node not in state:
            visit(node, [])
