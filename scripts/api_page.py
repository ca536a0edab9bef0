"""The API reference page of a package (the book's: skilllib), written as a MyST page from its docstrings.

    .venv/bin/python scripts/api_page.py                  # print the page for skilllib
    .venv/bin/python scripts/api_page.py --out api.md     # write it (scripts/build_site.py does, at build time)

What is listed: every public module of the package (no leading underscore, not ``__main__``): its
sub-packages, each the public face of its private modules, and in each its public functions and classes
(``__all__`` when the module has one, otherwise the public names it defines; a name defined in a private
module ``skilllib.robot._velocity`` is documented in ``skilllib.robot``), with the public methods and
properties of each class. Every entry has a label
``<module>.<name>`` (e.g. ``skilllib.smoothness.sparc``) that chapters cross-reference with
``[`skilllib.sparc`](#skilllib.smoothness.sparc)``, its signature (``inspect``), the units its docstring
states, and the docstring itself.

The docstrings are reStructuredText (``code``, ``:func:`name```, simple tables, nested lists). docutils,
the reference reST implementation, turns each one into HTML; mystmd turns that HTML into MyST nodes,
so the theme renders, searches and previews it like any page. The Python roles (``:func:``, ``:class:``,
``:mod:``, ``:meth:``, ``:attr:``, ``:data:``, ``:exc:``, ``:obj:``) become cross-references to the entries.
A docstring that docutils reports a problem with (level WARNING or above) stops the page with the object
and the line named: the docstrings render without markup errors or not at all.
"""

from __future__ import annotations

import argparse
import importlib
import inspect
import pkgutil
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

from docutils import nodes
from docutils.core import publish_doctree, publish_from_doctree
from docutils.parsers.rst import roles
from docutils.writers import html5_polyglot

# The units a docstring can state (SI as the book writes them). `s` and `m` only as whole words that are
# not followed by "(" (``s(t)`` is a function) so that variable names are not taken for units.
UNIT = re.compile(r"(?<![\w/.^'’-])(m/s\^?2|m/s²|m/s|rad/s|rad|deg|Hz|kHz|ms|mm|cm|s|m|dimensionless)(?![\w/(²^])")
PY_ROLES = ("func", "class", "mod", "meth", "attr", "data", "exc", "obj")


class DocstringError(Exception):
    """A docstring has a reST problem; the message names the object and the line."""


@dataclass
class Entry:
    label: str  # module.name (or module.Class.name)
    name: str
    kind: str  # "function", "class", "method", "property"
    obj: object
    children: list[Entry] = field(default_factory=list)


@dataclass
class ModuleDoc:
    name: str
    module: object
    entries: list[Entry]
    reexports: list[tuple[str, str]]  # (name, label of its entry) for names defined elsewhere


# ------------------------------------------------------------------------------------ what is public --


def public_modules(package: str) -> list[str]:
    pkg = importlib.import_module(package)
    names = [package]
    for info in pkgutil.walk_packages(pkg.__path__, prefix=f"{package}."):
        parts = info.name.split(".")
        if any(p.startswith("_") for p in parts[1:]):
            continue
        names.append(info.name)
    return sorted(names, key=lambda n: (n != package, n.count("."), n))


def home(obj) -> str | None:
    """The public module that documents ``obj``: its defining module without the private part
    (``skilllib.recordings._csv`` -> ``skilllib.recordings``, a sub-package's public face)."""
    module = getattr(obj, "__module__", None)
    if module is None:
        return None
    parts = module.split(".")
    cut = next((i for i, p in enumerate(parts) if p.startswith("_")), len(parts))
    return ".".join(parts[:cut])


def _is_member(obj) -> bool:
    return inspect.isfunction(obj) or inspect.isclass(obj)


def collect(package: str) -> list[ModuleDoc]:
    docs: list[ModuleDoc] = []
    defined: dict[int, str] = {}
    for modname in public_modules(package):
        module = importlib.import_module(modname)
        names = list(getattr(module, "__all__", None) or [n for n in vars(module) if not n.startswith("_")])
        entries, reexports = [], []
        for name in names:
            obj = getattr(module, name, None)
            if not _is_member(obj):
                continue
            if home(obj) != modname:
                if modname == package or name in (getattr(module, "__all__", None) or ()):
                    reexports.append((name, obj))
                continue
            label = f"{modname}.{name}"
            if inspect.isclass(obj) and any(n.lower() == name.lower() and n != name for n in names):
                label += "-class"  # MyST labels ignore case: class Segment and function segment differ here
            entry = Entry(label, name, "class" if inspect.isclass(obj) else "function", obj)
            if inspect.isclass(obj):
                entry.children = _class_members(entry)
            defined[id(obj)] = entry.label
            entries.append(entry)
        docs.append(ModuleDoc(modname, module, entries, reexports))
    for doc in docs:  # names re-exported from another module link to where they are documented
        doc.reexports = [(n, defined.get(id(o), f"{home(o)}.{n}")) for n, o in doc.reexports]
    return docs


def _class_members(cls_entry: Entry) -> list[Entry]:
    cls = cls_entry.obj
    out = []
    for name, value in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(value, property):
            out.append(Entry(f"{cls_entry.label}.{name}", name, "property", value))
        elif inspect.isfunction(value) or isinstance(value, (staticmethod, classmethod)):
            func = value.__func__ if isinstance(value, (staticmethod, classmethod)) else value
            out.append(Entry(f"{cls_entry.label}.{name}", name, "method", func))
    return out


# ------------------------------------------------------------------------------------ signatures --


def _annotation(ann) -> str:
    if ann is inspect.Parameter.empty:
        return ""
    text = ann if isinstance(ann, str) else inspect.formatannotation(ann)
    return text.replace("NoneType", "None")


def signature(entry: Entry) -> str | None:
    """``name(param: type = default, ...) -> type``, one parameter a line when it is long."""
    obj = entry.obj.fget if entry.kind == "property" else entry.obj
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):  # e.g. an exception class without its own __init__
        return None
    params = []
    for p in sig.parameters.values():
        if entry.kind == "method" and p.name in ("self", "cls") and not params:
            continue
        text = p.name
        if p.kind is p.VAR_POSITIONAL:
            text = "*" + text
        elif p.kind is p.VAR_KEYWORD:
            text = "**" + text
        ann = _annotation(p.annotation)
        if ann:
            text += f": {ann}"
        if p.default is not inspect.Parameter.empty:
            text += f" = {p.default!r}" if ann else f"={p.default!r}"
        params.append(text)
    if any(p.kind is p.KEYWORD_ONLY for p in sig.parameters.values()):
        first_kw = next(
            i
            for i, p in enumerate(
                [q for q in sig.parameters.values() if not (entry.kind == "method" and q.name in ("self", "cls"))]
            )
            if p.kind is p.KEYWORD_ONLY
        )
        if not any(p.kind is p.VAR_POSITIONAL for p in sig.parameters.values()):
            params.insert(first_kw, "*")
    ret = _annotation(sig.return_annotation)
    if entry.kind == "property":
        return f"{entry.name}" + (f" -> {ret}" if ret else "")
    tail = f" -> {ret}" if ret else ""
    one_line = f"{entry.name}({', '.join(params)}){tail}"
    if len(one_line) <= 88:
        return one_line
    return f"{entry.name}(\n" + "".join(f"    {p},\n" for p in params) + f"){tail}"


# ------------------------------------------------------------------------------------ docstrings --


class _Translator(html5_polyglot.HTMLTranslator):
    """HTML that mystmd maps to MyST nodes: ``<code>`` for literals, plain ``<pre>`` blocks."""

    def visit_literal(self, node):
        self.body.append(f"<code>{self.encode(node.astext().replace(chr(10), ' '))}</code>")
        raise nodes.SkipNode

    def visit_literal_block(self, node):
        self.body.append(f"<pre>{self.encode(node.astext())}</pre>\n")
        raise nodes.SkipNode


class _Writer(html5_polyglot.Writer):
    def __init__(self):
        super().__init__()
        self.translator_class = _Translator


class Renderer:
    """Docstrings to HTML with the Python roles resolved against the documented labels."""

    def __init__(self, labels: set[str]):
        self.labels = labels
        self.module = ""
        self.owner = ""  # the class whose members are being rendered
        self.errors: list[str] = []  # every docstring problem, reported together

        def role(*args, **kwargs):
            return self._role(*args, **kwargs)

        for name in PY_ROLES:
            roles.register_local_role(name, role)

    def resolve(self, target: str) -> str | None:
        target = target.lstrip("~.")
        for cand in (
            target,
            f"{self.owner}.{target}" if self.owner else None,
            f"{self.module}.{target}",
            f"{self.module.rsplit('.', 1)[0]}.{target}",
        ):
            if cand and cand in self.labels:
                return cand
        return None

    def _role(self, name, rawtext, text, lineno, inliner, options=None, content=None):
        shown = text[1:].rsplit(".", 1)[-1] if text.startswith("~") else text
        if name in ("func", "meth") and not shown.endswith(")"):
            shown += "()"
        label = self.resolve(text)
        code = nodes.literal(shown, shown)
        if label is None:
            return [code], []
        return [nodes.reference("", "", code, refuri=f"#{label}")], []

    def doctree(self, doc: str, where: str):
        messages: list[str] = []

        class Stream:
            def write(self, s):
                messages.append(s.strip())

        tree = publish_doctree(
            doc,
            settings_overrides={
                "report_level": 2,
                "halt_level": 5,
                "warning_stream": Stream(),
                "doctitle_xform": False,
                "file_insertion_enabled": False,
                "raw_enabled": False,
                "syntax_highlight": "none",
                "input_encoding": "unicode",
            },
        )
        problems = [m for m in messages if m]
        if problems:
            lines = "; ".join(re.sub(r"^<string>:(\d+):", r"docstring line \1:", p).splitlines()[0] for p in problems)
            self.errors.append(f"{where}: {lines}")
        return tree

    def html(self, tree) -> str:
        writer = _Writer()
        publish_from_doctree(
            tree,
            writer=writer,
            settings_overrides={"initial_header_level": 4, "output_encoding": "unicode", "doctitle_xform": False},
        )
        return _no_blank_lines(writer.parts["body"].strip())


def _no_blank_lines(html: str) -> str:
    """CommonMark ends an HTML block at a blank line: keep the block in one piece (a blank line inside
    <pre> becomes an empty span, which shows as the same empty line)."""
    out, in_pre = [], False
    for line in html.splitlines():
        if not line.strip():
            if in_pre:
                out.append("<span></span>")
            continue
        out.append(line)
        opened, closed = line.rfind("<pre"), line.rfind("</pre>")
        if opened > closed:
            in_pre = True
        elif closed > opened:
            in_pre = False
    return "\n".join(out)


def units_of(text: str) -> list[str]:
    seen: list[str] = []
    for u in UNIT.findall(text):
        u = {"m/s²": "m/s^2", "m/s2": "m/s^2"}.get(u, u)
        if u not in seen:
            seen.append(u)
    return seen


# ------------------------------------------------------------------------------------ the page --


def _docstring(obj) -> str:
    return inspect.getdoc(obj) or ""


def render_page(package: str = "skilllib") -> str:
    docs = collect(package)
    labels = (
        {m.name for m in docs}
        | {e.label for m in docs for e in m.entries}
        | {c.label for m in docs for e in m.entries for c in e.children}
    )
    r = Renderer(labels)
    version = getattr(importlib.import_module(package), "__version__", None)
    try:
        from importlib.metadata import version as dist_version

        version = version or dist_version(package)
    except Exception:
        pass
    n_functions = sum(e.kind == "function" for m in docs for e in m.entries)
    n_classes = sum(e.kind == "class" for m in docs for e in m.entries)
    out = [
        "---",
        "title: API reference",
        f"subtitle: Every public function and class of {package}{f' {version}' if version else ''}, "
        "from its docstrings",
        "---",
        "",
        f"This page is generated at build time from the docstrings of `{package}` (`scripts/api_page.py`): "
        f"{len(docs)} modules, {n_functions} functions and {n_classes} classes. Each entry gives the signature, "
        "the units its docstring states (m, s, m/s, rad/s, Hz, deg; *none stated* where the docstring names none) "
        "and the docstring. The chapters link here where they call a function.",
        "",
    ]
    for mod in docs:
        r.module, r.owner = mod.name, ""
        out += [f"({mod.name})=", f"## `{mod.name}`", ""]
        doc = _docstring(mod.module)
        if doc:
            out += [_html_block(r, doc, mod.name, "module-doc"), ""]
        if mod.reexports:
            links = ", ".join(f"[`{n}`](#{lab})" if lab in labels else f"`{n}`" for n, lab in mod.reexports)
            out += [f"Names available from `{mod.name}`: {links}.", ""]
        for e in mod.entries:
            out += _entry(r, e, level=3)
    if r.errors:
        raise DocstringError(f"{len(r.errors)} docstring(s):\n  " + "\n  ".join(r.errors))
    return "\n".join(out).rstrip() + "\n"


def _entry(r: Renderer, e: Entry, level: int) -> list[str]:
    doc = _docstring(e.obj.fget if e.kind == "property" else e.obj)
    where = f"{e.label} ({inspect.getsourcefile(e.obj.fget if e.kind == 'property' else e.obj) or '?'})"
    tree = r.doctree(doc, where) if doc else None
    units = units_of(tree.astext() if tree is not None else "")
    sig = signature(e)
    lines = [f"({e.label})=", f"{'#' * level} `{e.name}`", ""]
    tag = {"class": "class", "property": "property", "method": "method"}.get(e.kind, "function")
    lines += [f'<div class="api-kind">{tag} <code>{e.label}</code></div>', ""]
    if sig:
        lines += ["```python", sig, "```", ""]
    unit_text = ", ".join(f"`{u}`" for u in units) if units else "*none stated*"
    lines += [f"**Units:** {unit_text}", ""]
    if tree is not None:
        if e.kind == "class":
            r.owner = e.label
        lines += [f'<div class="docstring">\n{r.html(tree)}\n</div>', ""]
    else:
        lines += ["*No docstring.*", ""]
    for child in e.children:
        lines += _entry(r, child, level + 1)
    if e.kind == "class":
        r.owner = ""
    return lines


def _html_block(r: Renderer, doc: str, where: str, cls: str) -> str:
    return f'<div class="docstring {cls}">\n{r.html(r.doctree(doc, where))}\n</div>'


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--package", default="skilllib")
    ap.add_argument("--out", type=Path, help="write the page here (default: print it)")
    args = ap.parse_args(argv)
    try:
        page = render_page(args.package)
    except DocstringError as err:
        print(f"api_page: a docstring has a markup error: {err}", file=sys.stderr)
        return 1
    if args.out:
        args.out.write_text(page, encoding="utf-8")
    else:
        sys.stdout.write(page)
    return 0


if __name__ == "__main__":
    sys.exit(main())
