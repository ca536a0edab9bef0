"""Build a PDF of the whole book from the staged, executed project, with no network.

    .venv/bin/python scripts/build_pdf.py --site-src _build/site-src --out _build/html/book.pdf

SITE_SRC is the folder scripts/build_site.py stages and renders (myst.yml, index.md, the executed
notebooks/*.ipynb, docs/, api.md ...). scripts/build_site.py calls build_pdf(site_src, out) after the
HTML render.

Steps:
1. Copy SITE_SRC (without its _build) into a work folder and give its myst.yml one export: format typst,
   the local template theme/typst (an absolute path, so myst downloads no template), and the pages of the
   toc in order: the landing page (as "Introduction" when its title is the book's), each part as a
   level-1 heading, each chapter and reference page at level 2.
2. `myst build --typst` there writes book.typ and one book-<slug>.typ per page. myst then runs a `typst`
   command, which is a no-op here (a stand-in first on PATH): step 4 compiles.
3. Rewrite the .typ files: the Typst packages myst imports (@preview/subpar, @preview/tablex) point to
   the offline stand-ins in theme/typst/shims/; figure and equation numbers read k.1, k.2 ... as on the
   site (myst's pattern "10.1" would not); chapter headings carry their number and every page's heading
   a label <page-slug>, to which links between pages (site URLs "/slug") are turned; images are shown
   at their drawn size, smaller only when wider than the text; a link whose target myst left without a
   label (a labelled code block) is shown as its text, and reported.
4. Compile with the typst package (PyPI `typst`), the compiler's embedded fonts only and no date in the
   file: the same inputs give the same bytes.
A page that myst or Typst cannot convert stops the build with a non-zero exit and a message naming it.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import nbformat
import yaml

ROOT = Path(__file__).resolve().parents[1]
TEMPLATE = ROOT / "theme" / "typst"
# The Typst packages myst's export imports, and the local files that stand in for them.
SHIMS = {"subpar": "shims/subpar.typ", "tablex": "shims/tablex.typ"}
OUT_NAME = "book"  # myst writes book.typ and book-<slug>.typ


class PdfError(Exception):
    """A step failed; the message says which page and why."""


def log(msg: str) -> None:
    print(f"[build_pdf] {msg}", flush=True)


# ------------------------------------------------------------------------------ the pages in order --


def front_matter_title(path: Path) -> str | None:
    """The `title` of a Markdown page's front matter, or of a notebook's first cell's / its metadata."""
    if path.suffix == ".ipynb":
        nb = nbformat.read(path, as_version=4)
        title = nb.metadata.get("title")
        first = next((c.source for c in nb.cells if c.cell_type == "markdown"), "")
    else:
        title, first = None, path.read_text(encoding="utf-8")
    m = re.match(r"---\s*\n(.*?\n)---\s*(\n|$)", first, re.S)
    meta = (yaml.safe_load(m.group(1)) if m else None) or {}
    return meta.get("title") or title


def articles(cfg: dict, site_src: Path) -> list[dict]:
    """myst export `articles` from the toc: files and part titles, each with its heading level."""
    project = cfg.get("project") or {}
    book_title = project.get("title")

    def walk(entries, level):
        out = []
        for e in entries or []:
            if not isinstance(e, dict):
                continue
            if e.get("file"):
                rel = str(e["file"]).removeprefix("./")
                item = {"file": rel, "level": level}
                if not out and level == 1 and front_matter_title(site_src / rel) == book_title:
                    item["title"] = "Introduction"  # the landing page repeats the book's title (as on the site)
                out.append(item)
                out += walk(e.get("children"), level + 1)
            elif e.get("title"):
                out.append({"title": str(e["title"]), "level": level})
                out += walk(e.get("children"), level + 1)
        return out

    found = walk(project.get("toc"), 1)
    if not any("file" in a for a in found):
        raise PdfError("myst.yml has no project.toc with files")
    return found


def chapter_number(path: Path) -> str | None:
    """The chapter's number from its `numbering: enumerator: "k.%s"`: the front matter of its first
    markdown cell (scripts/notebook_front_matter.py), else its metadata (set by scripts/build_site.py)."""
    if path.suffix != ".ipynb":
        return None
    nb = nbformat.read(path, as_version=4)
    first = next((c.source for c in nb.cells if c.cell_type == "markdown"), "")
    m = re.match(r"---\s*\n(.*?\n)---\s*(\n|$)", first, re.S)
    own = ((yaml.safe_load(m.group(1)) if m else None) or {}).get("numbering") or {}
    enumerator = own.get("enumerator") or (nb.metadata.get("numbering") or {}).get("enumerator") or ""
    m = re.fullmatch(r"(\w+)\.%s", str(enumerator))
    return m.group(1) if m else None


# ------------------------------------------------------------------------------ 1.-2. myst's export --


def stage(site_src: Path, work: Path, items: list[dict], cfg: dict) -> Path:
    src = work / "src"
    shutil.copytree(
        site_src, src, ignore=shutil.ignore_patterns("_build", ".ipynb_checkpoints", "__pycache__"), symlinks=True
    )
    cfg = dict(cfg)
    cfg.pop("site", None)  # the HTML theme plays no part here
    project = dict(cfg.get("project") or {})
    project["exports"] = [
        {
            "id": "book-pdf",
            "format": "typst",
            "template": str(TEMPLATE),
            "output": f"_pdf/{OUT_NAME}.typ",
            "articles": items,
        }
    ]
    cfg["project"] = project
    (src / "myst.yml").write_text(yaml.safe_dump(cfg, sort_keys=False, allow_unicode=True), encoding="utf-8")
    return src


def find_myst() -> str:
    for cand in (Path(sys.executable).parent / "myst", shutil.which("myst")):
        if cand and Path(cand).exists():
            return str(cand)
    raise PdfError("the myst command was not found (pip install mystmd in the venv)")


def run_myst(src: Path, work: Path, items: list[dict]) -> Path:
    # myst runs `typst compile book.typ` after writing it; this stand-in does nothing (step 4 compiles).
    shim_bin = work / "bin"
    shim_bin.mkdir()
    (shim_bin / "typst").write_text("#!/bin/sh\nexit 0\n", encoding="utf-8")
    (shim_bin / "typst").chmod(0o755)
    # CI: myst never prompts. npm_config_registry: myst asks npm for its latest version in the background
    # (an update notice); a closed local port makes that fail at once instead of reaching the network.
    env = dict(os.environ, CI="1", PWD=str(src), npm_config_registry="http://127.0.0.1:9/")
    env["PATH"] = str(shim_bin) + os.pathsep + env.get("PATH", "")
    proc = subprocess.run(
        [find_myst(), "build", "--typst", "--ci"],
        cwd=src,
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        timeout=600,
    )
    myst_log = proc.stdout
    (work / "myst-typst.log").write_text(myst_log, encoding="utf-8")
    if "Fetching template" in myst_log:  # myst's message before it downloads a template
        raise PdfError(f"myst tried to download a template instead of using {TEMPLATE}:\n" + myst_log[-2000:])
    # myst marks errors with ⛔ (and a failed command with a line "Error: ..."); warnings (⚠) are shown
    problems = [ln.strip() for ln in myst_log.splitlines() if "\u26d4" in ln or ln.lstrip().startswith("Error")]
    out = src / "_pdf" / f"{OUT_NAME}.typ"
    if proc.returncode != 0 or problems or not out.is_file():
        pages = sorted({a["file"] for a in items if "file" in a and any(a["file"] in p for p in problems)})
        raise PdfError(
            "myst could not convert the book to Typst"
            + (f" ({', '.join(pages)})" if pages else "")
            + ":\n  "
            + "\n  ".join(problems or myst_log.strip().splitlines()[-15:])
        )
    for ln in myst_log.splitlines():
        if "\u26a0" in ln or "warn" in ln.lower():
            log(f"myst | {ln.strip()}")
    return out


# ------------------------------------------------------------------------------ 3. the .typ files --

PACKAGE_IMPORT = re.compile(r'#import "@preview/([\w-]+):[\d.]+"')
NUMBERING = re.compile(r'#set (figure|math\.equation)\(numbering: "(\(?)(\w+)\.1(\)?)"\)')
PAGE_LINK = re.compile(r'#link\("/([\w-]*)(?:#([\w.-]+))?"\)')
# tex-to-typst writes `\\pm\\pi` as `plus.minuspi`: a symbol with modifiers run into the next name.
TEX_SYMBOL_RUN = re.compile(r"\b((?:plus\.minus|minus\.plus|dot\.op|dots\.h|arrow\.r|lt\.eq|gt\.eq|eq\.not)(?=[a-z]))")
IMAGE = re.compile(r'image\("(files/[^"]+)", width: [\d.]+%\)')


def chapter_numbering(text: str) -> str:
    """myst numbers the k-th chapter's figures and equations with the Typst pattern "k.1" / "(k.1)":
    Typst reads each "1" in it as a counter, so for k = 10, 11, ... the numbers come out wrong. A
    function gives k.n for every k, as on the site."""
    return NUMBERING.sub(lambda m: f'#set {m[1]}(numbering: n => "{m[2]}{m[3]}." + str(n) + "{m[4]}")', text)


def included_pages(book_typ: Path, items: list[dict]) -> dict[str, str]:
    """book-<slug>.typ -> the toc file it was written from (myst includes them in toc order)."""
    includes = re.findall(r'#include "([^"]+)"', book_typ.read_text(encoding="utf-8"))
    files = [a["file"] for a in items if "file" in a]
    if len(includes) != len(files):
        raise PdfError(f"myst wrote {len(includes)} pages for the {len(files)} files of the toc")
    return dict(zip(includes, files))


def rewrite(folder: Path, pages: dict[str, str], site_src: Path) -> None:
    for name in SHIMS.values():
        target = folder / name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(TEMPLATE / name, target)
    shutil.copyfile(TEMPLATE / "style.typ", folder / "style.typ")

    landing = next(iter(pages)).removeprefix(f"{OUT_NAME}-").removesuffix(".typ")  # "/" is the landing page
    for typ in sorted(folder.glob("*.typ")):
        if typ.name == "style.typ":
            continue
        text = typ.read_text(encoding="utf-8")
        page = pages.get(typ.name, typ.name)

        def local_package(m, page=page):
            if m.group(1) not in SHIMS:
                raise PdfError(
                    f"{page}: myst's Typst needs the package {m.group(0)[8:]}, which has no offline stand-in"
                )
            return f'#import "{SHIMS[m.group(1)]}"'

        text = PACKAGE_IMPORT.sub(local_package, text)
        text = chapter_numbering(text)
        if IMAGE.search(text):
            text = '#import "style.typ": book-image\n' + IMAGE.sub(r'book-image("\1")', text)
        # Links to other pages are site URLs ("/slug", "/slug#id"): in the PDF they go to the page's
        # heading (labelled <page-slug> below) or to the target's own label.
        text = PAGE_LINK.sub(lambda m: f"#link(<{m[2] or 'page-' + (m[1] or landing)}>)", text)
        text = TEX_SYMBOL_RUN.sub(r"\1 ", text)
        if typ.name in pages:
            number = chapter_number(site_src / page)
            slug = typ.stem.removeprefix(f"{OUT_NAME}-")
            prefix = f"{number} " if number else ""
            text, n = re.subn(r"^(=+) (.*)$", rf"\1 {prefix}\2 <page-{slug}>", text, count=1, flags=re.M)
            if not n:
                raise PdfError(f"{page}: myst's Typst has no heading for the page's title")
        typ.write_text(text, encoding="utf-8")


# ------------------------------------------------------------------------------ 4. compile --


def title_inputs(cfg: dict, site_src: Path, items: list[dict], info: dict[str, str] | None = None) -> dict[str, str]:
    project = cfg.get("project") or {}
    inputs = {"title": str(project.get("title") or "Untitled")}
    landing = next((a["file"] for a in items if "file" in a), None)
    if landing and (site_src / landing).suffix == ".md":
        m = re.match(r"---\s*\n(.*?\n)---", (site_src / landing).read_text(encoding="utf-8"), re.S)
        meta = (yaml.safe_load(m.group(1)) if m else None) or {}
        if meta.get("subtitle"):
            inputs["subtitle"] = str(meta["subtitle"])
    if project.get("description"):
        inputs["description"] = " ".join(str(project["description"]).split())
    authors = [a.get("name") if isinstance(a, dict) else str(a) for a in project.get("authors") or []]
    if any(authors):
        inputs["authors"] = ", ".join(a for a in authors if a)
    lic = project.get("license")
    if lic:
        inputs["license"] = str(lic.get("content") if isinstance(lic, dict) else lic)
    info = {**os.environ, **(info or {})}
    build = [
        f"{label} {info[key]}"
        for key, label in (("BOOK_VERSION", "Version"), ("BOOK_COMMIT", "commit"), ("BOOK_BUILD_DATE", "built"))
        if info.get(key)
    ]
    if build:
        inputs["build"] = ", ".join(build)
    return inputs


LINK_TO_LABEL = re.compile(r"#link\(<([^<>\s]+)>\)")
LABEL_USE = re.compile(r"(?:#link\(|#cite\(|#ref\()<[^<>\s]+>")
LABEL = re.compile(r"<([\w.:/-]+)>")


def unlink_missing_targets(folder: Path, pages: dict[str, str]) -> None:
    """A link whose target myst's Typst does not label (a labelled code block, such as the API pages'
    signatures) would stop Typst; it is shown as its text instead, and reported."""
    texts = {typ: typ.read_text(encoding="utf-8") for typ in sorted(folder.glob("*.typ"))}
    defined = {m for text in texts.values() for m in LABEL.findall(LABEL_USE.sub("", text))}
    dropped: dict[str, int] = {}
    for typ, text in texts.items():
        new, n = LINK_TO_LABEL.subn(lambda m: m[0] if m[1] in defined else "#", text)
        if n and new != text:
            dropped[pages.get(typ.name, typ.name)] = sum(1 for x in LINK_TO_LABEL.findall(text) if x not in defined)
            typ.write_text(new, encoding="utf-8")
    if dropped:
        log(
            "links shown as text, their targets have no label in myst's Typst (labelled code blocks?): "
            + ", ".join(f"{page} {n}" for page, n in dropped.items())
        )


def compile_typst(book_typ: Path, pages: dict[str, str], inputs: dict[str, str]) -> bytes:
    import typst

    epoch = os.environ.get("SOURCE_DATE_EPOCH", "")
    try:
        pdf, warnings = typst.compile_with_warnings(
            str(book_typ),
            root=str(book_typ.parent),
            font_paths=[],
            ignore_system_fonts=True,  # the compiler's embedded fonts only: the same PDF everywhere
            sys_inputs=inputs,
            timestamp=int(epoch) if epoch.isdigit() else 0,
            format="pdf",
        )
    except typst.TypstError as err:
        # The diagnostic shows the failing line of book-<slug>.typ; the trace, the include it came from.
        text = "\n".join([str(getattr(err, "diagnostic", "") or err), *map(str, getattr(err, "trace", []) or [])])
        named = sorted({page for name, page in pages.items() if re.search(rf"\b{re.escape(name)}\b", text)})
        where = ", ".join(named) if named else "the book"
        raise PdfError(f"{where}: Typst could not typeset the page:\n  " + text.strip()[:3000]) from None
    for w in warnings:
        msg = str(getattr(w, "message", w))
        if "unknown font family" not in msg:
            log(f"typst warning | {msg[:300]}")
    return pdf


def build_pdf(site_src: Path, out: Path, work: Path | None = None, build_info: dict[str, str] | None = None) -> Path:
    """Write the PDF of the book staged in site_src to out; PdfError names the page that failed.

    work: keep the intermediate files there (default: a temporary folder, removed). build_info:
    BOOK_VERSION, BOOK_COMMIT, BOOK_BUILD_DATE for the title page (scripts/build_site.py's build_info;
    default: those environment variables, or nothing)."""
    t0 = time.perf_counter()
    site_src, out = Path(site_src).resolve(), Path(out).resolve()
    cfg_file = site_src / "myst.yml"
    if not cfg_file.is_file():
        raise PdfError(f"no myst.yml in {site_src} (give the folder scripts/build_site.py stages: BUILD_DIR/site-src)")
    cfg = yaml.safe_load(cfg_file.read_text(encoding="utf-8")) or {}
    items = articles(cfg, site_src)
    missing = [a["file"] for a in items if "file" in a and not (site_src / a["file"]).is_file()]
    if missing:
        raise PdfError("the toc lists pages that are not in the staged folder: " + ", ".join(missing))

    keep = work is not None
    work = Path(work).resolve() if keep else Path(tempfile.mkdtemp(prefix="book-pdf-"))
    if keep:
        # cleared before use, so only an empty folder or one this script made before
        if work.is_dir() and any(work.iterdir()) and not (work / "src" / "myst.yml").is_file():
            raise PdfError(f"--work {work} is neither empty nor a work folder of build_pdf.py: not clearing it")
        shutil.rmtree(work, ignore_errors=True)
        work.mkdir(parents=True)
    try:
        src = stage(site_src, work, items, cfg)
        book_typ = run_myst(src, work, items)
        t_myst = time.perf_counter()
        pages = included_pages(book_typ, items)
        rewrite(book_typ.parent, pages, site_src)
        unlink_missing_targets(book_typ.parent, pages)
        pdf = compile_typst(book_typ, pages, title_inputs(cfg, site_src, items, build_info))
    finally:
        if not keep:
            shutil.rmtree(work, ignore_errors=True)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_suffix(".pdf.tmp")
    tmp.write_bytes(pdf)
    tmp.replace(out)
    t_end = time.perf_counter()
    log(
        f"{out} ({len(pdf) / 1e6:.1f} MB, {len(pages)} pages of the toc): myst {t_myst - t0:.1f} s, "
        f"typst {t_end - t_myst:.1f} s"
    )
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--site-src", type=Path, required=True, help="the staged project (BUILD_DIR/site-src)")
    ap.add_argument("--out", type=Path, required=True, help="the PDF to write")
    ap.add_argument("--work", type=Path, help="keep the intermediate files (myst's .typ, its log) in this folder")
    args = ap.parse_args(argv)
    try:
        build_pdf(args.site_src, args.out, args.work)
    except PdfError as err:
        print(f"build_pdf: ERROR: {err}", file=sys.stderr, flush=True)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
