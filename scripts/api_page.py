"""The API reference of a package (the book's: skilllib), written as MyST pages from its docstrings.

    .venv/bin/python scripts/api_page.py                       # list the pages it writes for skilllib
    .venv/bin/python scripts/api_page.py --out-dir DIR         # write them (scripts/build_site.py does)
    .venv/bin/python scripts/api_page.py --page api-robot.md   # print one page

The pages: ``api.md``, the index (what each sub-package is for, one line each, and every name of the
package's front door), and ``api-<sub>.md``, one per public sub-package (``api-smoothness.md``,
``api-robot.md``, ...): every public module directly below the package; a deeper public module
(``skilllib.figures.clusters``) is a section of its sub-package's page. The toc (myst.yml) and
``GENERATED_PAGES`` in scripts/build_site.py list the same pages; the build stops when they differ.

What is listed: in each public module (no leading underscore, not ``__main__``) its public functions and
classes (``__all__`` when the module has one, otherwise the public names it defines; a name defined in a
private module ``skilllib.robot._velocity`` is documented in ``skilllib.robot``), with the public methods
and properties of each class. Every entry has a label ``<module>.<name>`` (e.g.
``skilllib.smoothness.sparc``) that chapters cross-reference with ``[`sk.sparc`](#skilllib.smoothness.sparc)``
on whichever page it is; a sub-package's page has the sub-package's label (``skilllib.robot``). An entry
shows its signature (``inspect``), a link ``source:<file>#L<line>`` to the line of its ``def`` or
``class``, which the site's theme resolves (under the base URL ``BOOK_SOURCE_URL`` when set, otherwise
relative to the built site in a checkout: ``_build/html`` -> ``../../skilllib/...``), and its docstring.

The page outline stays short: a sub-package page's headings are its functions and classes (h2; in a
deeper module's section, h3). A class's methods and properties are no headings (mystmd would make an
h4 below an h2 an h3, which the outline lists): each is its signature, a code block that carries its
label, under the class. A docstring never adds a heading: the numpydoc sections Parameters, Other
Parameters, Returns, Yields, Attributes (tables: name, type, unit, description; the unit is what the
row's text states: m, s, m/s, rad/s, Hz, ...) and Raises, Warns (exception, when) become tables, any
other section a bold label.

The docstrings are reStructuredText (``code``, ``:func:`name```, simple tables, nested lists). docutils,
the reference reST implementation, turns each part into HTML; mystmd turns that HTML into MyST nodes,
so the theme renders, searches and previews it like any page. The Python roles (``:func:``, ``:class:``,
``:mod:``, ``:meth:``, ``:attr:``, ``:data:``, ``:exc:``, ``:obj:``) become cross-references to the entries.
A docstring that docutils reports a problem with (level WARNING or above) stops the pages with the object
and the line named: the docstrings render without markup errors or not at all.
"""

from __future__ import annotations

import argparse
import html
import importlib
import inspect
import pkgutil
import re
import sys
import textwrap
from dataclasses import dataclass, field
from pathlib import Path

from docutils import nodes
from docutils.core import publish_doctree, publish_from_doctree
from docutils.parsers.rst import roles
from docutils.writers import html5_polyglot

# The units a docstring can state (SI as the book writes them). `s` and `m` only as whole words that are
# not followed by "(" (``s(t)`` is a function) so that variable names are not taken for units.
UNIT = re.compile(
    r"(?<![\w/.^'’-])(m/s\^?[23]|m/s[²³]|rad/s\^?2|rad/s²|m/s|rad/s|rad|deg|kHz|Hz|ms|mm|cm|N m|kg|s|m|dimensionless)"
    r"(?![\w/(²³^])"
)
PY_ROLES = ("func", "class", "mod", "meth", "attr", "data", "exc", "obj")
# numpydoc sections shown as tables: (first column's header, whether the rows have types and units)
TABLE_SECTIONS = {
    "Parameters": ("Parameter", True),
    "Other Parameters": ("Parameter", True),
    "Attributes": ("Attribute", True),
    "Returns": ("Returns", True),
    "Yields": ("Yields", True),
    "Raises": ("Raises", False),
    "Warns": ("Warns", False),
}
SECTION_HEAD = re.compile(r"^([A-Z][A-Za-z ]*)\n(-{3,}|={3,}|~{3,})(?:\n|$)", re.M)
# Headings of a sub-package page: its functions and classes h2; a deeper module's section h2 and its
# entries h3. A class's methods and properties are no headings (see _member).
ENTRY_LEVEL = 2


class DocstringError(Exception):
    """A docstring has a reST problem; the message names the object and the line."""


@dataclass
class Entry:
    label: str  # module.name (or module.Class.name)
    name: str
    kind: str  # "function", "class", "method", "property"
    obj: object
    children: list[Entry] = field(default_factory=list)

    @property
    def code(self):
        """The function the entry's source and docstring are those of (a property's getter)."""
        return self.obj.fget if self.kind == "property" else self.obj


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


def page_of(module: str, package: str) -> str:
    """The page that documents `module`: api.md for the package itself, else api-<sub-package>.md."""
    if module == package:
        return "api.md"
    return f"api-{module.removeprefix(package + '.').split('.')[0]}.md"


# ------------------------------------------------------------------------------------ signatures --


def _annotation(ann) -> str:
    if ann is inspect.Parameter.empty:
        return ""
    text = ann if isinstance(ann, str) else inspect.formatannotation(ann)
    return re.sub(r"ForwardRef\('([^']*)'\)", r"\1", text.replace("NoneType", "None"))


def signature(entry: Entry) -> str | None:
    """``name(param: type = default, ...) -> type``, one parameter a line when it is long."""
    try:
        sig = inspect.signature(entry.code)
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


# ------------------------------------------------------------------------------------ source links --


def source_location(obj) -> tuple[Path, int] | None:
    """The file that defines `obj` and the line of its ``def`` or ``class`` (after any decorator)."""
    try:
        obj = inspect.unwrap(obj)
        path = inspect.getsourcefile(obj)
        lines, start = inspect.getsourcelines(obj)
    except (TypeError, OSError):
        return None
    if path is None:
        return None
    keyword = re.compile(r"\s*(async\s+def|def|class)\s")
    offset = next((i for i, line in enumerate(lines) if keyword.match(line)), 0)
    return Path(path).resolve(), start + offset


def source_url(path: Path, line: int, root: Path) -> str:
    """The link to `path` (a file under the repository `root`) at `line`, as ``source:<path>#L<line>``:
    the site's theme resolves it as it does its "View source" links (under BOOK_SOURCE_URL when it is
    set, else relative to the built site in a checkout: _build/html -> ../../). A plain relative link
    would not do: myst copies a linked file that exists into the site's assets."""
    return f"source:{path.relative_to(root).as_posix()}#L{line}"


# ------------------------------------------------------------------------------------ docstrings --


class _Translator(html5_polyglot.HTMLTranslator):
    """HTML that mystmd maps to MyST nodes: ``<code>`` for literals, plain ``<pre>`` blocks, and a
    section title as a bold label, never a heading (the page's outline is the entries only)."""

    def visit_literal(self, node):
        self.body.append(f"<code>{self.encode(node.astext().replace(chr(10), ' '))}</code>")
        raise nodes.SkipNode

    def visit_literal_block(self, node):
        self.body.append(f"<pre>{self.encode(node.astext())}</pre>\n")
        raise nodes.SkipNode

    def visit_section(self, node):
        pass

    def depart_section(self, node):
        pass

    def visit_title(self, node):
        if isinstance(node.parent, nodes.section):
            self.body.append(f"<p><strong>{self.encode(node.astext())}</strong></p>\n")
            raise nodes.SkipNode
        super().visit_title(node)


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

    def doctree(self, doc: str, where: str, first_line: int = 1):
        """The doctree of `doc`, the part of a docstring that starts at its line `first_line`."""
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

            def line(m):
                return f"docstring line {int(m.group(1)) + first_line - 1}:"

            lines = "; ".join(re.sub(r"^<string>:(\d+):", line, p).splitlines()[0] for p in problems)
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

    def rst(self, text: str, where: str, first_line: int = 1, inline: bool = False) -> str:
        """reST to HTML; `inline`: a single paragraph without its <p> (for a table cell)."""
        if not text.strip():
            return ""
        out = self.html(self.doctree(text, where, first_line))
        if inline:
            m = re.fullmatch(r"<p>(.*)</p>", out, re.S)
            if m and "<p>" not in m.group(1):
                return m.group(1).replace("\n", " ")
        return out


def _no_blank_lines(html_text: str) -> str:
    """CommonMark ends an HTML block at a blank line: keep the block in one piece (a blank line inside
    <pre> becomes an empty span, which shows as the same empty line)."""
    out, in_pre = [], False
    for line in html_text.splitlines():
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
        u = u.replace("²", "^2").replace("³", "^3")
        u = re.sub(r"/s([23])$", r"/s^\1", u)
        if u not in seen:
            seen.append(u)
    return seen


def _shown_unit(unit: str) -> str:
    return unit.replace("^2", "²").replace("^3", "³")


@dataclass
class Section:
    title: str | None  # None: the text before the first section
    text: str
    first_line: int  # the docstring's line (1-based) the text starts on


def sections(doc: str) -> list[Section]:
    """A numpydoc docstring cut at its section headings (a title underlined with ---, === or ~~~)."""
    out, pos, title = [], 0, None
    for m in SECTION_HEAD.finditer(doc):
        if len(m.group(2)) < len(m.group(1).rstrip()):
            continue
        out.append(Section(title, doc[pos : m.start()], doc.count("\n", 0, pos) + 1))
        title, pos = m.group(1).strip(), m.end()
    out.append(Section(title, doc[pos:], doc.count("\n", 0, pos) + 1))
    return [s for s in out if s.title or s.text.strip()]


@dataclass
class Item:
    name: str
    type: str
    text: str  # the description, dedented
    first_line: int  # of the description in the docstring


def items(section: Section, typed: bool) -> list[Item]:
    """The rows of a numpydoc list section: ``name : type`` (or a type alone) at the left margin, the
    description indented below it."""
    rows: list[Item] = []
    lines = section.text.split("\n")
    i = 0
    while i < len(lines):
        head = lines[i]
        if not head.strip() or head[0].isspace():
            i += 1
            continue
        j = i + 1
        while j < len(lines) and (not lines[j].strip() or lines[j][0].isspace()):
            j += 1
        body = textwrap.dedent("\n".join(lines[i + 1 : j])).strip("\n")
        name, sep, kind = head.partition(" : ")
        if not sep:
            name, kind = ("", head) if typed else (head, "")
        rows.append(Item(name.strip().replace("\\", ""), kind.strip(), body, section.first_line + i + 1))
        i = j
    return rows


def section_table(r: Renderer, section: Section, where: str) -> str:
    header, typed = TABLE_SECTIONS[section.title]
    rows = items(section, typed)
    named = any(row.name for row in rows) or not typed
    cols = ([header] if named else []) + (["Type"] if typed else []) + (["Unit"] if typed else [])
    cols += ["Description" if typed else "When"]
    if not named:
        cols[0] = header  # a list of return types: the type is the first column
    head = "".join(f"<th>{c}</th>" for c in cols)
    out = ["<table>", f"<thead><tr>{head}</tr></thead>", "<tbody>"]
    for row in rows:
        desc = r.rst(row.text, where, row.first_line, inline=True)
        cells = [f"<code>{html.escape(row.name)}</code>" if row.name else ""] if named else []
        if typed:
            cells.append(html.escape(row.type))
            units = units_of(f"{row.type}\n{row.text}")
            cells.append(", ".join(html.escape(_shown_unit(u)) for u in units))
        cells.append(desc)
        out.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
    out += ["</tbody>", "</table>"]
    return _no_blank_lines("\n".join(out))


def docstring_blocks(r: Renderer, doc: str, where: str, cls: str = "docstring") -> list[str]:
    """A docstring as Markdown blocks: its text in ``<div class="docstring">``, each numpydoc table a
    block of its own beside it (a table of the page, which the theme lets use the margin's width)."""
    blocks: list[str] = []
    text: list[str] = []

    def flush():
        if any(text):
            blocks.append(f'<div class="{cls}">\n' + "\n".join(p for p in text if p) + "\n</div>")
        text.clear()

    for s in sections(doc):
        if s.title in TABLE_SECTIONS:
            flush()
            blocks.append(section_table(r, s, where))
            continue
        if s.title:
            text.append(f"<p><strong>{html.escape(s.title)}</strong></p>")
        text.append(r.rst(s.text, where, s.first_line))
    flush()
    return [line for b in blocks for line in (b, "")]


def _docstring(obj) -> str:
    return inspect.getdoc(obj) or ""


def summary(doc: str) -> str:
    """The first paragraph of a docstring (its summary line), as Markdown for a table cell."""
    first = doc.strip().split("\n\n")[0].replace("\n", " ")
    text = re.sub(r":\w+:`~?([^`]+)`", r"`\1`", first).replace("``", "`")
    return text.rstrip(".")


# ------------------------------------------------------------------------------------ the pages --


def render_pages(package: str = "skilllib") -> dict[str, str]:
    """Every page of the API reference of `package`: file name -> MyST text."""
    docs = collect(package)
    labels = (
        {m.name for m in docs}
        | {e.label for m in docs for e in m.entries}
        | {c.label for m in docs for e in m.entries for c in e.children}
    )
    r = Renderer(labels)
    pkg = importlib.import_module(package)
    root = Path(pkg.__file__).resolve().parent.parent  # the checkout (the package's parent folder)
    by_page: dict[str, list[ModuleDoc]] = {}
    for mod in docs:
        by_page.setdefault(page_of(mod.name, package), []).append(mod)
    pages = {"api.md": _index_page(r, package, docs, by_page)}
    for name, mods in by_page.items():
        if name != "api.md":
            pages[name] = _sub_package_page(r, package, mods, labels, root)
    if r.errors:
        raise DocstringError(f"{len(r.errors)} docstring(s):\n  " + "\n  ".join(r.errors))
    return pages


def _version(package: str) -> str | None:
    version = getattr(importlib.import_module(package), "__version__", None)
    try:
        from importlib.metadata import version as dist_version

        version = version or dist_version(package)
    except Exception:
        pass
    return version


def _index_page(r: Renderer, package: str, docs: list[ModuleDoc], by_page: dict[str, list[ModuleDoc]]) -> str:
    version = _version(package)
    n_functions = sum(e.kind == "function" for m in docs for e in m.entries)
    n_classes = sum(e.kind == "class" for m in docs for e in m.entries)
    subs = [mods for name, mods in by_page.items() if name != "api.md"]
    out = [
        "---",
        "title: API reference",
        f"subtitle: Every public function and class of {package}{f' {version}' if version else ''}, "
        "one page per sub-package",
        f"label: {package}",
        "---",
        "",
        f"These pages are generated at build time from the docstrings of `{package}` (`scripts/api_page.py`): "
        f"{len(subs)} sub-packages, {n_functions} functions and {n_classes} classes. Each entry gives the "
        "signature, a link to its source line, its parameters and return values in a table with the unit "
        "each one's description states (m, s, m/s, rad/s, Hz, ...), and the docstring. The chapters link to "
        "the entries where they call a function.",
        "",
        "| Sub-package | What it is for | Functions | Classes |",
        "|---|---|---:|---:|",
    ]
    for mods in subs:
        face = mods[0]
        entries = [e for m in mods for e in m.entries]
        what = summary(_docstring(face.module)) or "(no docstring)"
        n_f = sum(e.kind == "function" for e in entries)
        n_c = sum(e.kind == "class" for e in entries)
        out.append(f"| [`{face.name}`](#{face.name}) | {_cell(what)} | {n_f} | {n_c} |")
    out.append("")
    front = next((m for m in docs if m.name == package), None)
    if front is not None:
        if front.reexports:
            links = ", ".join(
                f"[`{n}`](#{lab})" if lab in r.labels else f"`{n}`"
                for n, lab in sorted(front.reexports, key=lambda x: x[0].lower())
            )
            out += [
                f"`import {package}` offers every public name of its sub-packages as `{package}.NAME`, A–Z: {links}.",
                "",
            ]
    return "\n".join(out).rstrip() + "\n"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _sub_package_page(r: Renderer, package: str, mods: list[ModuleDoc], labels: set[str], root: Path) -> str:
    face = mods[0]
    doc = _docstring(face.module)
    first, _, rest = doc.partition("\n\n")
    short = face.name.removeprefix(package + ".")
    out = [
        "---",
        f"title: {face.name}",
        f"short_title: {short}",
        f"label: {face.name}",
    ]
    if first:
        out.append(f"subtitle: {_yaml_str(_plain(first))}")
    out += ["---", ""]
    r.module, r.owner = face.name, ""
    if rest.strip():
        out += docstring_blocks(r, rest, face.name, "docstring module-doc")
    # at a glance: every entry of the page with its first sentence (a table, not in the outline)
    rows = []
    for mod in mods:
        prefix = mod.name.removeprefix(face.name + ".") + "." if mod is not face else ""
        for e in mod.entries:
            rows.append(f"| [`{prefix}{e.name}`](#{e.label}) | {e.kind} | {_cell(summary(_docstring(e.code)))} |")
    if rows:
        out += ["| Name | Kind | What it does |", "|---|---|---|", *rows, ""]
    for mod in mods:
        r.module, r.owner = mod.name, ""
        level = ENTRY_LEVEL
        if mod is not face:
            out += [f"({mod.name})=", f"{'#' * ENTRY_LEVEL} `{mod.name}`", ""]
            mdoc = _docstring(mod.module)
            if mdoc:
                out += docstring_blocks(r, mdoc, mod.name, "docstring module-doc")
            level += 1
        if mod.reexports:
            links = ", ".join(f"[`{n}`](#{lab})" if lab in labels else f"`{n}`" for n, lab in mod.reexports)
            out += [f"Names available from `{mod.name}`: {links}.", ""]
        for e in mod.entries:
            out += _entry(r, e, level, root)
    return "\n".join(out).rstrip() + "\n"


def _plain(rst: str) -> str:
    """reST inline markup as plain text (a subtitle or a table cell of the summary)."""
    text = re.sub(r":\w+:`~?([^`]+)`", r"\1", rst.replace("\n", " "))
    return re.sub(r"``([^`]+)``", r"\1", text)


def _yaml_str(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _entry(r: Renderer, e: Entry, level: int, root: Path) -> list[str]:
    """A function or class: a heading with its label, then the kind and source line, the signature and
    the docstring; a class's methods and properties follow it (_member)."""
    doc = _docstring(e.code)
    sig = signature(e)
    lines = [f"({e.label})=", f"{'#' * level} `{e.name}`", ""]
    lines += [f'<div class="api-kind">{_meta(e, root)}</div>', ""]
    if sig:
        lines += ["```python", sig, "```", ""]
    if e.kind == "class":
        r.owner = e.label
    lines += _docstring_block(r, e, doc)
    if e.children:
        lines += [f"**Methods and properties of `{e.name}`**", ""]
    for child in e.children:
        lines += _member(r, child, root)
    if e.kind == "class":
        r.owner = ""
    return lines


def _member(r: Renderer, e: Entry, root: Path) -> list[str]:
    """A method or property: no heading (the page's outline lists functions and classes only); its label
    is on its signature, the block a link to it scrolls to."""
    sig = signature(e) or e.name
    fence = "`" * max(3, 1 + max((len(m) for m in re.findall(r"`+", sig)), default=0))
    lines = [f"{fence}{{code}} python", f":label: {e.label}", sig, fence, ""]
    lines += [f'<div class="api-kind">{_meta(e, root)}</div>', ""]
    return lines + _docstring_block(r, e, _docstring(e.code))


def _meta(e: Entry, root: Path) -> str:
    """``function skilllib.x.name · source: file, line N`` (the link to the line of its def or class)."""
    tag = {"class": "class", "property": "property", "method": "method"}.get(e.kind, "function")
    meta = f"{tag} <code>{e.label}</code>"
    loc = source_location(e.code)
    if loc is not None:
        path, line = loc
        try:
            url, rel = source_url(path, line, root), path.relative_to(root).as_posix()
        except ValueError:  # defined outside the checkout
            return meta
        meta += f' · <a href="{html.escape(url)}">source: <code>{rel}</code>, line {line}</a>'
    return meta


def _docstring_block(r: Renderer, e: Entry, doc: str) -> list[str]:
    if not doc:
        return ["*No docstring.*", ""]
    where = f"{e.label} ({inspect.getsourcefile(e.code) or '?'})"
    return docstring_blocks(r, doc, where)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--package", default="skilllib")
    ap.add_argument("--out-dir", type=Path, help="write every page into this folder")
    ap.add_argument("--page", help="print this page (e.g. api.md, api-robot.md)")
    args = ap.parse_args(argv)
    try:
        pages = render_pages(args.package)
    except DocstringError as err:
        print(f"api_page: a docstring has a markup error: {err}", file=sys.stderr)
        return 1
    if args.out_dir:
        args.out_dir.mkdir(parents=True, exist_ok=True)
        for name, text in pages.items():
            (args.out_dir / name).write_text(text, encoding="utf-8")
    if args.page:
        if args.page not in pages:
            print(f"api_page: no page {args.page}; the pages are {', '.join(pages)}", file=sys.stderr)
            return 2
        sys.stdout.write(pages[args.page])
    elif not args.out_dir:
        sys.stdout.write("".join(f"{name}\n" for name in pages))
    return 0


if __name__ == "__main__":
    sys.exit(main())
