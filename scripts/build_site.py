"""Build the book's static site into _build/html, with no network.

    .venv/bin/python scripts/build_site.py                # execute the chapters whose code changed, render
    .venv/bin/python scripts/build_site.py --no-cache     # execute every chapter again
    .venv/bin/python scripts/build_site.py --no-execute   # reuse the chapters executed last time
    .venv/bin/python scripts/build_site.py --executed DIR # take the chapters executed elsewhere (make test:
                                                          # nbmake --overwrite on copies in DIR)

Steps:
1. Stage: copy myst.yml (its `site: template` made absolute), the pages of the toc and the files they
   may refer to into _build/site-src/. Each notebook of the toc is executed there with nbclient (kernel
   python3, cwd = the notebook's own folder, so `../data/...` works); the committed notebooks are
   only read. The k-th notebook of the toc (markdown pages are not counted) numbers its figures, tables and
   equations k.1, k.2, ... unless it sets `numbering` itself. A notebook paired with a percent script
   (NN_slug.py beside it) offers both for download.
   Executed notebooks are cached in BUILD_DIR/cache/, keyed on the chapter's code cells, the kernel
   settings and every file of CACHE_INPUTS (skilllib/, data/, images/, environment.txt, pyproject.toml):
   an edit of the prose only re-executes nothing. Pages in GENERATED_PAGES (api.md: the API reference,
   scripts/api_page.py) are written into the staging folder, cached on the package's sources.
2. Render: `myst build --html` in the staging folder; myst runs theme/render.mjs (theme/template.yml)
   with BOOK_VERSION, BOOK_COMMIT and BOOK_BUILD_DATE for the page footer.
3. Copy the result to _build/html and check that every toc entry has its page.
4. Lighten it: the figures' PNGs become lossless WebP (about 40 % of the bytes; cached in
   BUILD_DIR/cache/webp), and the site's size and each page's weight (HTML + images + scripts + CSS) are
   printed.
A failing cell or page stops the build with a non-zero exit and a message naming it.

Links to the repository ("View source", the licence) use BOOK_SOURCE_URL when it is set (the base URL of
the repository's files, e.g. https://github.com/org/repo/blob/main/), else a path relative to the site
(../../ from _build/html), so that they work from file:// in a checkout. Last, the PDF of the whole book
(scripts/build_pdf.py) is written into the site as book.pdf, which every page links (--no-pdf: neither).
"""

from __future__ import annotations

import argparse
import datetime
import hashlib
import json
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
# Never staged: tooling, caches and the build itself. Everything else is, so that pages can refer to
# images, bibliographies and data files next to them.
SKIP_DIRS = {
    ".git",
    ".venv",
    "_build",
    "node_modules",
    "theme",
    "tests",
    "__pycache__",
    ".pytest_cache",
    ".hypothesis",
    ".ipynb_checkpoints",
    ".benchmarks",
    ".ci",
    "out",
    "results",
    "skilllib.egg-info",
    "_executed",
    "mutants",
}
ANSI = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")
# What an executed chapter's outputs depend on besides its code cells (paths relative to the project;
# missing ones are skipped). A change to any of them executes the chapters again.
CACHE_INPUTS = ("skilllib", "data", "images", "environment.txt", "pyproject.toml")
# The kernel of the site build: figures inline as retina PNGs; MPLBACKEND=Agg in its environment so that
# a subprocess a chapter starts (python -m skilllib run) does not print `Figure(650x600)` for each figure.
KERNEL_ARGS = ["--matplotlib=inline", "--InlineBackend.figure_formats=retina"]
# myst only warns about these; the build stops on them.
FATAL_MYST = re.compile(
    r"Could not link citation|Error reading file|No target for internal reference|"
    r"Duplicate identifier"
)
# Toc entries written at build time: file -> package whose API reference it is part of (scripts/api_page.py
# writes api.md, the index, and api-<sub-package>.md per public sub-package; myst.yml lists the same pages).
GENERATED_PAGES = {"api.md": "skilllib"} | {
    f"api-{sub}.md": "skilllib"
    for sub in "cohort datasets features figures pipeline prototypes recordings robot smoothness task".split()
}


class BuildError(Exception):
    """A step failed; the message says which page and why."""


def log(msg: str) -> None:
    print(f"[build_site] {msg}", flush=True)


def toc_files(entries) -> list[str]:
    files: list[str] = []
    for e in entries or []:
        if isinstance(e, dict):
            if e.get("file"):
                files.append(str(e["file"]).removeprefix("./"))
            files += toc_files(e.get("children"))
    return files


def read_config(project: Path) -> tuple[dict, list[str]]:
    cfg_file = project / "myst.yml"
    if not cfg_file.exists():
        raise BuildError(f"no myst.yml in {project}")
    cfg = yaml.safe_load(cfg_file.read_text(encoding="utf-8"))
    files = toc_files((cfg.get("project") or {}).get("toc"))
    if not files:
        raise BuildError("myst.yml has no project.toc with files")
    missing = [f for f in files if not (project / f).is_file() and f not in GENERATED_PAGES]
    if missing:
        raise BuildError("myst.yml lists pages that do not exist: " + ", ".join(missing))
    if not (cfg.get("site") or {}).get("template"):
        raise BuildError("myst.yml needs `site: template: ./theme` (the offline theme); without it myst downloads one")
    return cfg, files


def sync_tree(src: Path, dst: Path, skip_files: set[Path]) -> None:
    """Copy src into dst (files that changed only), leaving out SKIP_DIRS and skip_files."""
    for dirpath, dirnames, filenames in os.walk(src):
        d = Path(dirpath)
        dirnames[:] = [n for n in dirnames if n not in SKIP_DIRS and not (d / n).samefile(dst.parent)]
        for name in filenames:
            s = d / name
            if s in skip_files:
                continue
            t = dst / s.relative_to(src)
            st = s.stat()
            if t.exists() and t.stat().st_size == st.st_size and t.stat().st_mtime >= st.st_mtime:
                continue
            t.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(s, t)


def set_chapter_numbering(source: str, chapter: int) -> str:
    """Add `numbering: enumerator: "k.%s"` to a page's front matter unless it has `numbering`."""
    m = re.match(r"---\s*\n(.*?\n)---\s*(\n|$)", source, re.S)
    meta = (yaml.safe_load(m.group(1)) if m else None) or {}
    if "numbering" in meta:
        return source
    meta["numbering"] = {"enumerator": f"{chapter}.%s"}
    body = source[m.end() :] if m else source
    return "---\n" + yaml.safe_dump(meta, sort_keys=False, allow_unicode=True) + "---\n" + body


def read_notebook(path: Path, rel: str):
    try:
        return nbformat.read(path, as_version=4)
    except Exception as err:  # not JSON, not a notebook, unreadable
        raise BuildError(f"{rel}: cannot be read as a notebook: {type(err).__name__}: {str(err)[:300]}") from None


def number_notebook(nb, chapter: int) -> None:
    """Same as set_chapter_numbering, in the notebook metadata (myst reads page front matter there)."""
    first = next((c for c in nb.cells if c.cell_type == "markdown"), None)
    if "numbering" in nb.metadata or (first is not None and re.match(r"---\s*\n.*?numbering:", first.source, re.S)):
        return
    nb.metadata["numbering"] = {"enumerator": f"{chapter}.%s"}


def execute_notebook(src: Path, rel: str, timeout: int):
    """Execute a copy of the notebook at src (cwd: its folder); return it with its outputs."""
    from jupyter_client.manager import KernelManager
    from nbclient import NotebookClient

    nb = read_notebook(src, rel)
    # IPC transport: a local kernel needs no TCP ports (and ipykernel then does not warn about them).
    tmp = Path(tempfile.mkdtemp(prefix="book-kernel-"))
    km = KernelManager(kernel_name="python3", transport="ipc", connection_file=str(tmp / "kernel.json"))
    # Retina PNGs: twice the pixels, shown at the figure's size (the theme reads the width metadata).
    client = NotebookClient(
        nb,
        km=km,
        timeout=timeout,
        kernel_name="python3",
        extra_arguments=KERNEL_ARGS,
        resources={"metadata": {"path": str(src.parent)}},
    )
    try:
        run_cells(client, nb, rel, timeout)
    finally:  # the client does not stop a kernel it was given
        if km.has_kernel:
            km.shutdown_kernel(now=False)
        shutil.rmtree(tmp, ignore_errors=True)
    return nb


def executed_elsewhere(src: Path, rel: str, folder: Path):
    """The notebook ``folder/<name>`` executed by another runner (``make test`` runs nbmake with
    ``--overwrite`` on copies), after checking that it holds the chapter's own code cells and that every
    code cell ran without an error."""
    done = folder / src.name
    if not done.is_file():
        raise BuildError(f"{rel}: no executed copy {done} (--executed)")
    nb, ran = read_notebook(src, rel), read_notebook(done, rel)
    code = [(c.source, c.metadata.get("tags", [])) for c in nb.cells if c.cell_type == "code"]
    if code != [(c.source, c.metadata.get("tags", [])) for c in ran.cells if c.cell_type == "code"]:
        raise BuildError(f"{rel}: the executed copy {done} has other code than the chapter: execute it again")
    for i, cell in enumerate(c for c in ran.cells if c.cell_type == "code"):
        if cell.get("execution_count") is None or any(o.get("output_type") == "error" for o in cell.outputs):
            raise BuildError(f"{rel}: code cell {i + 1} of {done} did not run, or raised an error")
    return with_outputs_of(nb, ran)  # the chapter's own markdown cells and metadata, the other runner's outputs


def run_cells(client, nb, rel: str, timeout: int) -> None:
    from nbclient.exceptions import CellExecutionError, CellTimeoutError

    code_cells = 0
    with client.setup_kernel():
        for index, cell in enumerate(nb.cells):
            if cell.cell_type != "code":
                continue
            code_cells += 1
            where = f"cell {index + 1} (code cell {code_cells})"
            try:
                client.execute_cell(cell, index)
            except CellTimeoutError:
                raise BuildError(f"{rel}: {where} did not finish within {timeout} s") from None
            except CellExecutionError as err:
                first_line = next((ln for ln in cell.source.splitlines() if ln.strip() and not ln.startswith("#|")), "")
                tail = "\n".join(ANSI.sub("", str(err.traceback or "")).strip().splitlines()[-6:])
                raise BuildError(
                    f"{rel}: {where} raised {err.ename}: {err.evalue}\n"
                    f"    the cell begins: {first_line[:100]}\n"
                    f"    end of the traceback:\n" + "\n".join("      " + ln for ln in tail.splitlines())
                ) from None


def kernel_environment() -> None:
    """Environment the kernels inherit: the venv first on PATH, and MPLBACKEND=Agg.

    The kernel itself shows figures inline (KERNEL_ARGS: --matplotlib=inline); MPLBACKEND is what the
    processes a chapter starts inherit. With the inline backend there (ipykernel's default), a
    `python -m skilllib run` would print `Figure(650x600)` for every figure roboticstoolbox shows.
    """
    bin_dir = str(Path(sys.executable).parent)
    os.environ["PATH"] = bin_dir + os.pathsep + os.environ.get("PATH", "")
    os.environ["MPLBACKEND"] = "Agg"
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")


# ------------------------------------------------------------------------------ the execution cache --


def _file_digest(path: Path) -> str:
    h = hashlib.sha256()
    with path.open("rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def inputs_digest(project: Path, names=CACHE_INPUTS) -> str:
    """One digest of every file under `names` (relative to project), by path and content."""
    h = hashlib.sha256()
    for name in names:
        root = project / name
        files = [root] if root.is_file() else sorted(p for p in root.rglob("*") if p.is_file()) if root.is_dir() else []
        for p in files:
            if "__pycache__" in p.parts or p.suffix == ".pyc":
                continue
            h.update(f"{p.relative_to(project).as_posix()}\0{_file_digest(p)}\0".encode())
    return h.hexdigest()


def cache_key(nb, inputs: str) -> str:
    """The key of a notebook's executed outputs: its code cells (in order), the kernel settings, the
    Python version and the digest of CACHE_INPUTS. Markdown cells, tags and metadata are not in it."""
    h = hashlib.sha256()
    h.update(f"{sys.version}\0{' '.join(KERNEL_ARGS)}\0{inputs}\0".encode())
    for cell in nb.cells:
        if cell.cell_type == "code":
            h.update(b"\0code\0" + cell.source.encode())
    return h.hexdigest()[:24]


class ExecutionCache:
    """Executed notebooks in BUILD_DIR/cache/exec/<name>-<key>.ipynb (one kept per notebook)."""

    def __init__(self, folder: Path, inputs: str):
        self.folder = folder
        self.inputs = inputs

    def path(self, rel: str, nb) -> Path:
        return self.folder / f"{rel.replace('/', '__').removesuffix('.ipynb')}-{cache_key(nb, self.inputs)}.ipynb"

    def get(self, src: Path, rel: str):
        """The chapter with the cached outputs of its code, or None when its code (or an input) changed."""
        nb = read_notebook(src, rel)
        hit = self.path(rel, nb)
        if not hit.is_file():
            return None
        try:
            return with_outputs_of(nb, nbformat.read(hit, as_version=4))
        except Exception:  # a damaged cache file or other code under the same key: execute again
            return None

    def put(self, rel: str, nb) -> None:
        self.folder.mkdir(parents=True, exist_ok=True)
        target = self.path(rel, nb)
        for old in self.folder.glob(f"{rel.replace('/', '__').removesuffix('.ipynb')}-*.ipynb"):
            if old != target:
                old.unlink()
        tmp = target.with_suffix(".tmp")
        nbformat.write(nb, tmp)
        tmp.replace(target)


def with_outputs_of(nb, ran):
    """`nb` (the chapter: its markdown, tags and metadata) with the outputs of `ran`'s code cells, which
    must be the same code; ValueError otherwise."""
    mine = [c for c in nb.cells if c.cell_type == "code"]
    theirs = [c for c in ran.cells if c.cell_type == "code"]
    if [c.source for c in mine] != [c.source for c in theirs]:
        raise ValueError("other code")
    for m, t in zip(mine, theirs):
        m.outputs, m.execution_count = t.outputs, t.execution_count
    return nb


# ------------------------------------------------------------------------------ build information --


def build_info(project: Path) -> dict[str, str]:
    """Version, commit and date for the footer: version from myst.yml `project: version`, or else
    pyproject.toml's `project.version`, or, when that is dynamic, the `__version__` of the package that
    `tool.setuptools.dynamic.version.attr` names (read from its source, not imported); the commit (with "+
    local changes" when the work tree differs from it); the date
    (UTC, or SOURCE_DATE_EPOCH when set, for reproducible builds)."""
    version = "unversioned"
    try:
        cfg = yaml.safe_load((project / "myst.yml").read_text(encoding="utf-8")) or {}
        version = str((cfg.get("project") or {}).get("version") or "") or version
    except (OSError, yaml.YAMLError):
        pass
    if version == "unversioned" and (project / "pyproject.toml").is_file():
        import tomllib

        try:
            meta = tomllib.loads((project / "pyproject.toml").read_text(encoding="utf-8"))
            version = str(meta["project"].get("version") or "") or version
            attr = meta.get("tool", {}).get("setuptools", {}).get("dynamic", {}).get("version", {}).get("attr")
            if version == "unversioned" and attr:
                module, name = attr.rsplit(".", 1)
                src = project / (module.replace(".", "/") + ".py")
                if not src.is_file():
                    src = project / module.replace(".", "/") / "__init__.py"
                m = re.search(rf"^{re.escape(name)}\s*=\s*['\"]([^'\"]+)['\"]", src.read_text(encoding="utf-8"), re.M)
                version = m.group(1) if m else version
        except (KeyError, OSError, tomllib.TOMLDecodeError):
            pass
    commit = "not a git checkout"
    try:
        rev = subprocess.run(
            ["git", "rev-parse", "--short=12", "HEAD"], cwd=project, capture_output=True, text=True, timeout=30
        )
        if rev.returncode == 0:
            commit = rev.stdout.strip()
            dirty = subprocess.run(
                ["git", "status", "--porcelain", "--untracked-files=no"],
                cwd=project,
                capture_output=True,
                text=True,
                timeout=30,
            )
            if dirty.returncode == 0 and dirty.stdout.strip():
                commit += " + local changes"
    except (OSError, subprocess.TimeoutExpired):
        pass
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    when = (
        datetime.datetime.fromtimestamp(int(epoch), datetime.UTC)
        if epoch and epoch.isdigit()
        else datetime.datetime.now(datetime.UTC)
    )
    return {"BOOK_VERSION": version, "BOOK_COMMIT": commit, "BOOK_BUILD_DATE": when.strftime("%Y-%m-%d %H:%M UTC")}


# ------------------------------------------------------------------------------ generated pages --


def generate_page(project: Path, rel: str, dst: Path, cache_dir: Path) -> None:
    """Write the generated page `rel` (GENERATED_PAGES) to dst. scripts/api_page.py writes every page of
    the package's reference at once into the cache, kept while the package's sources and the generator
    are unchanged; the pages it writes must be those GENERATED_PAGES lists for the package."""
    package = GENERATED_PAGES[rel]
    generator = Path(__file__).resolve().parent / "api_page.py"
    h = hashlib.sha256(f"{sys.version}\0{_file_digest(generator)}\0".encode())
    h.update(inputs_digest(project, (package,)).encode())
    cached = cache_dir / f"api-{package}-{h.hexdigest()[:24]}"
    if not cached.is_dir():
        t0 = time.perf_counter()
        partial = cached.with_name(cached.name + ".partial")
        shutil.rmtree(partial, ignore_errors=True)
        proc = subprocess.run(
            [sys.executable, str(generator), "--package", package, "--out-dir", str(partial)],
            cwd=project,
            capture_output=True,
            text=True,
            stdin=subprocess.DEVNULL,
            timeout=600,
        )
        if proc.returncode != 0:
            shutil.rmtree(partial, ignore_errors=True)
            raise BuildError(
                f"{rel} (the API reference of {package}) could not be generated:\n"
                + (proc.stderr.strip() or proc.stdout.strip())[-3000:]
            )
        written = {p.name for p in partial.glob("*.md")}
        listed = {Path(f).name for f, p in GENERATED_PAGES.items() if p == package}
        if written != listed:
            shutil.rmtree(partial, ignore_errors=True)
            raise BuildError(
                f"scripts/api_page.py writes the pages {sorted(written)} for {package}, but GENERATED_PAGES "
                f"(scripts/build_site.py) lists {sorted(listed)}: list the same pages there and in myst.yml"
            )
        partial.rename(cached)
        for old in cache_dir.glob(f"api-{package}-*"):
            if old != cached:
                shutil.rmtree(old, ignore_errors=True)
        log(f"generated the API reference of {package} ({len(written)} pages) in {time.perf_counter() - t0:.1f} s")
    dst.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(cached / Path(rel).name, dst)


def add_downloads(nb, src: Path) -> None:
    """Offer the chapter's percent script (NN_slug.py beside the notebook) for download as well."""
    script = src.with_suffix(".py")
    if script.is_file():
        nb.metadata["downloads"] = [{"file": script.name, "title": f"Python script {script.name}"}]


def find_myst() -> str:
    for cand in (Path(sys.executable).parent / "myst", shutil.which("myst")):
        if cand and Path(cand).exists():
            return str(cand)
    raise BuildError("the myst command was not found (pip install mystmd in the venv)")


def build(
    project: Path,
    build_dir: Path,
    execute: bool,
    timeout: int,
    chapter_numbers: bool,
    executed: Path | None = None,
    use_cache: bool = True,
    pdf: bool = True,
) -> Path:
    t_start = time.perf_counter()
    cfg, files = read_config(project)
    theme = (project / cfg["site"]["template"]).resolve()
    if not (theme / "template.yml").is_file():
        raise BuildError(f"site.template {cfg['site']['template']!r} has no template.yml ({theme})")
    if not (theme / "node_modules").is_dir():
        raise BuildError(f"{theme}/node_modules is missing: run `npm ci --prefix {os.path.relpath(theme)}`")

    staging = build_dir / "site-src"
    out = build_dir / "html"
    staging.mkdir(parents=True, exist_ok=True)
    shutil.rmtree(out, ignore_errors=True)  # a failed build leaves no stale site behind

    # 1. Stage. myst only accepts a real folder (not a symlink) as template: give it the absolute path.
    notebooks = [f for f in files if f.endswith(".ipynb")]
    sync_tree(project, staging, {project / f for f in notebooks} | {project / "myst.yml"})
    cfg["site"]["template"] = str(theme)
    (staging / "myst.yml").write_text(yaml.safe_dump(cfg, sort_keys=False, allow_unicode=True), encoding="utf-8")

    kernel_environment()
    cache = ExecutionCache(build_dir / "cache" / "exec", inputs_digest(project)) if (execute or executed) else None
    reused = []
    n_chapters = 0  # the notebooks are the numbered chapters; the landing and reference pages are not
    for rel in files:
        src, dst = project / rel, staging / rel
        is_chapter = chapter_numbers and rel.endswith(".ipynb")
        n_chapters += is_chapter
        chapter = n_chapters if is_chapter else None
        if rel in GENERATED_PAGES and not src.is_file():
            generate_page(project, rel, dst, build_dir / "cache")
            continue
        if rel.endswith(".ipynb"):
            if executed is not None:
                nb = executed_elsewhere(src, rel, executed)
                cache.put(rel, nb)
            elif execute and use_cache and (hit := cache.get(src, rel)) is not None:
                nb = hit
                reused.append(rel)
            elif execute:
                t0 = time.perf_counter()
                nb = execute_notebook(src, rel, timeout)
                log(f"executed {rel} in {time.perf_counter() - t0:.1f} s")
                cache.put(rel, nb)
            elif dst.exists():
                nb = read_notebook(dst, rel)
                if src.stat().st_mtime > dst.stat().st_mtime:
                    log(f"warning: {rel} changed since it was last executed (--no-execute)")
            else:
                log(f"warning: {rel} was never executed; staging it without outputs (--no-execute)")
                nb = read_notebook(src, rel)
            # Jupytext's pairing settings mean nothing to myst (it warns about them) or to a reader who
            # downloads the notebook: the staged copy leaves them out.
            nb.metadata.pop("jupytext", None)
            add_downloads(nb, src)
            if chapter:
                number_notebook(nb, chapter)
            dst.parent.mkdir(parents=True, exist_ok=True)
            nbformat.write(nb, dst)
        elif chapter:
            dst.write_text(set_chapter_numbering(src.read_text(encoding="utf-8"), chapter), encoding="utf-8")
    if reused:
        log(f"code unchanged, outputs reused from {os.path.relpath(build_dir / 'cache', project)}: {', '.join(reused)}")
    t_exec = time.perf_counter()

    # 2. Render with myst and the offline theme. CI=1 and no stdin: myst never prompts.
    env = dict(os.environ, CI="1", PWD=str(staging), **build_info(project), **source_env(project, out))
    env.pop("BASE_URL", None)
    if pdf:
        env["BOOK_PDF"] = PDF_NAME
    else:
        env.pop("BOOK_PDF", None)
    proc = subprocess.run(
        [find_myst(), "build", "--html"],
        cwd=staging,
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        timeout=900,
    )
    myst_log = proc.stdout
    (build_dir / "myst-build.log").write_text(myst_log, encoding="utf-8")
    # Show myst's warnings, errors and summary; the whole log is in BUILD_DIR/myst-build.log.
    keep = re.compile(r"\u26a0|\u26d4|error|warn|theme|Built \d+ pages|^\s+-|^\S.*:\s*$", re.I)
    for line in myst_log.splitlines():
        if keep.search(line) and "Myst CLI Versions" not in line:
            print(f"  myst | {line}", flush=True)
    if proc.returncode != 0:
        raise BuildError(f"myst build --html failed (exit {proc.returncode}); the messages above name the page")
    fatal = sorted({ln.strip() for ln in myst_log.splitlines() if FATAL_MYST.search(ln)})
    if fatal:
        raise BuildError(
            "myst reported problems the site must not have (a citation without its entry in the "
            "bibliography, an unreadable .bib, a cross-reference without target, a duplicate "
            "label):\n  " + "\n  ".join(fatal)
        )
    t_myst = time.perf_counter()

    # 3. Copy the site out, then 4. check it.
    rendered = staging / "_build" / "html"
    tmp = build_dir / "html.tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    shutil.copytree(rendered, tmp)
    shutil.rmtree(out, ignore_errors=True)
    tmp.rename(out)
    check_site(out, files)
    t_check = time.perf_counter()
    images_to_webp(out, build_dir / "cache" / "webp")
    t_images = time.perf_counter()
    if pdf:
        book_pdf(staging, out / PDF_NAME, build_dir / "cache" / "pdf", build_info(project))
    t_end = time.perf_counter()
    log(
        f"timings: stage+execute {t_exec - t_start:.1f} s, myst+render {t_myst - t_exec:.1f} s, "
        f"copy+check {t_check - t_myst:.1f} s, images {t_images - t_check:.1f} s, "
        f"pdf {t_end - t_images:.1f} s, total {t_end - t_start:.1f} s"
    )
    report_weight(out)
    return out


# ------------------------------------------------------------------------------ source links, weight --

PDF_NAME = "book.pdf"  # written into the site by the PDF step (scripts/build_pdf.py); linked from every page


def book_pdf(staging: Path, dst: Path, cache: Path, info: dict[str, str]) -> None:
    """The PDF of the staged book (scripts/build_pdf.py: mystmd's Typst export, compiled offline) at dst,
    cached on the staged files, the PDF step's own files and the title page's build information."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import build_pdf

    cache.mkdir(parents=True, exist_ok=True)
    # the build date is left out of the key: a PDF says when its content was last built
    h = hashlib.sha256(json.dumps({k: v for k, v in info.items() if "DATE" not in k}, sort_keys=True).encode())
    sources = [p for p in sorted(staging.rglob("*")) if p.is_file() and "_build" not in p.relative_to(staging).parts]
    sources += [Path(build_pdf.__file__), *sorted((ROOT / "theme" / "typst").rglob("*"))]
    for path in sources:
        if path.is_file():
            h.update(str(path).encode() + b"\0" + _file_digest(path).encode())
    cached = cache / f"{h.hexdigest()[:24]}.pdf"
    if cached.is_file():
        log(f"PDF unchanged, taken from {cached.parent.name}/")
    else:
        try:
            build_pdf.build_pdf(staging, cached.with_suffix(".tmp.pdf"), build_info=info)
        except build_pdf.PdfError as err:
            raise BuildError(f"the book's PDF: {err}") from None
        cached.with_suffix(".tmp.pdf").rename(cached)
        for old in cache.glob("*.pdf"):  # one PDF is kept: the latest
            if old != cached:
                old.unlink()
    shutil.copyfile(cached, dst)


def source_env(project: Path, out: Path) -> dict[str, str]:
    """What the theme needs to link the repository's files: the checkout (only files that exist there
    are linked) and its path relative to the site. BOOK_SOURCE_URL, when set, is passed through as is."""
    rel = Path(os.path.relpath(project, out)).as_posix()
    return {"BOOK_SOURCE_ROOT": str(project), "BOOK_SOURCE_RELATIVE": rel.rstrip("/") + "/"}


def images_to_webp(out: Path, cache: Path) -> None:
    """Every PNG of assets/ becomes a lossless WebP (the same pixels in about 40 % of the bytes; every
    browser of the last five years shows it), and the pages refer to it."""
    from PIL import Image

    pngs = sorted((out / "assets").glob("*.png"))
    if not pngs:
        return
    cache.mkdir(parents=True, exist_ok=True)
    renamed, before, after = {}, 0, 0
    for png in pngs:
        data = png.read_bytes()
        cached = cache / f"{hashlib.sha256(data).hexdigest()[:32]}.webp"
        if not cached.is_file():
            with Image.open(png) as im:
                tmp = cached.with_suffix(".tmp")
                im.save(tmp, "WEBP", lossless=True, quality=100, method=4, exact=True)
            tmp.replace(cached)
        webp = png.with_suffix(".webp")
        if cached.stat().st_size >= len(data):  # never heavier
            continue
        shutil.copyfile(cached, webp)
        png.unlink()
        renamed[f"assets/{png.name}"] = f"assets/{webp.name}"
        before, after = before + len(data), after + webp.stat().st_size
    if not renamed:
        return
    pattern = re.compile("|".join(re.escape(k) for k in renamed))
    for page in out.glob("*.html"):
        html = page.read_text(encoding="utf-8")
        new = pattern.sub(lambda m: renamed[m.group(0)], html)
        if new != html:
            page.write_text(new, encoding="utf-8")
    log(f"images: {len(renamed)} PNGs as lossless WebP, {before / 1e6:.1f} MB -> {after / 1e6:.1f} MB")


def page_weights(out: Path) -> dict[str, dict[str, int]]:
    """Bytes each page loads when opened: its HTML, the images, scripts and stylesheets it refers to
    (files of the site; fonts and what scripts load later not counted)."""
    from html.parser import HTMLParser

    class Refs(HTMLParser):
        def __init__(self) -> None:
            super().__init__()
            self.refs: dict[str, set[str]] = {"img": set(), "script": set(), "css": set()}
            self.in_template = 0

        def handle_starttag(self, tag, attrs):
            a = dict(attrs)
            if tag == "template":
                self.in_template += 1
            elif tag == "img" and a.get("src") and not self.in_template:
                self.refs["img"].add(a["src"])
            elif tag == "script" and a.get("src"):
                self.refs["script"].add(a["src"])
            elif tag == "link" and a.get("rel") in ("stylesheet", "icon") and a.get("href"):
                self.refs["css"].add(a["href"])

        def handle_endtag(self, tag):
            if tag == "template":
                self.in_template -= 1

    weights = {}
    for page in sorted(out.glob("*.html")):
        parser = Refs()
        parser.feed(page.read_text(encoding="utf-8"))
        w = {"html": page.stat().st_size}
        for kind, refs in parser.refs.items():
            files = [out / r.split("#")[0] for r in refs if not re.match(r"^[a-z]+:", r)]
            w[kind] = sum(f.stat().st_size for f in files if f.is_file())
        w["total"] = sum(w.values())
        weights[page.name] = w
    return weights


def report_weight(out: Path) -> None:
    total = sum(f.stat().st_size for f in out.rglob("*") if f.is_file())
    log(f"site size: {total / 1e6:.1f} MB in {sum(1 for f in out.rglob('*') if f.is_file())} files ({out})")
    log("page weights (kB: total = html + images + scripts + css and icon, loaded when the page opens):")
    for name, w in sorted(page_weights(out).items(), key=lambda kv: -kv[1]["total"]):
        log(
            f"  {name:32s} {w['total'] / 1e3:7.0f} = {w['html'] / 1e3:5.0f} + {w['img'] / 1e3:5.0f} "
            f"+ {w['script'] / 1e3:4.0f} + {w['css'] / 1e3:4.0f}"
        )


def check_site(out: Path, files: list[str]) -> None:
    """Every toc entry has its HTML page (the theme writes _static/pages.json: file -> url)."""
    manifest = out / "_static" / "pages.json"
    if not (out / "index.html").is_file() or not manifest.is_file():
        raise BuildError(f"{out} has no index.html or _static/pages.json: the theme did not run")
    pages = {p["file"]: p for p in json.loads(manifest.read_text(encoding="utf-8"))["pages"]}
    problems = []
    for rel in files:
        page = pages.get(rel)
        if page is None:
            problems.append(f"{rel}: no page in the site")
        elif not (out / page["url"]).is_file() or (out / page["url"]).stat().st_size < 500:
            problems.append(f"{rel}: {page['url']} is missing or empty")
        elif rel.endswith(".ipynb") and not (out / page["download"]).is_file():
            problems.append(f"{rel}: its notebook download {page['download']} is missing")
    if problems:
        raise BuildError("the site is incomplete:\n  " + "\n  ".join(problems))
    log(f"checked {len(files)} pages in {out}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--project", type=Path, default=ROOT, help="folder with myst.yml (default: the repository)")
    ap.add_argument("--build-dir", type=Path, help="default: PROJECT/_build (the site goes to BUILD_DIR/html)")
    ap.add_argument("--no-execute", action="store_true", help="reuse the notebooks executed by the last build")
    ap.add_argument("--no-cache", action="store_true", help="execute every chapter, even those whose code is unchanged")
    ap.add_argument(
        "--executed",
        type=Path,
        metavar="DIR",
        help="take each chapter's outputs from DIR/<name>.ipynb, executed by another runner",
    )
    ap.add_argument("--timeout", type=int, default=600, help="seconds allowed per cell (default 600)")
    ap.add_argument("--no-chapter-numbers", action="store_true", help="number figures 1, 2, ... on every page")
    ap.add_argument("--no-pdf", action="store_true", help=f"no PDF of the book ({PDF_NAME}) and no link to it")
    args = ap.parse_args(argv)
    project = args.project.resolve()
    build_dir = (args.build_dir or project / "_build").resolve()
    try:
        out = build(
            project,
            build_dir,
            not args.no_execute,
            args.timeout,
            not args.no_chapter_numbers,
            args.executed.resolve() if args.executed else None,
            use_cache=not args.no_cache,
            pdf=not args.no_pdf,
        )
    except BuildError as err:
        print(f"build_site: ERROR: {err}", file=sys.stderr, flush=True)
        return 1
    log(f"the site is in {out} (open {out / 'index.html'})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
