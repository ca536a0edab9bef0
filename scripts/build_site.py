"""Build the book's static site into _build/html, with no network.

    .venv/bin/python scripts/build_site.py                # execute every chapter, then render
    .venv/bin/python scripts/build_site.py --no-execute   # reuse the chapters executed last time
    .venv/bin/python scripts/build_site.py --executed DIR # take the chapters executed elsewhere (make test:
                                                          # nbmake --overwrite on copies in DIR)

Steps:
1. Stage: copy myst.yml (its `site: template` made absolute), the pages of the toc and the files they
   may refer to into _build/site-src/. Each notebook of the toc is executed there with nbclient (kernel
   python3, cwd = the notebook's own folder, so `../data/...` works); the committed notebooks are
   only read. Chapter k of the toc (the landing page is not counted) numbers its figures, tables and
   equations k.1, k.2, ... unless it sets `numbering` itself.
2. Render: `myst build --html` in the staging folder; myst runs theme/render.mjs (theme/template.yml).
3. Copy the result to _build/html and check that every toc entry has its page.
A failing cell or page stops the build with a non-zero exit and a message naming it.
"""
from __future__ import annotations

import argparse
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
SKIP_DIRS = {".git", ".venv", "_build", "node_modules", "theme", "tests", "__pycache__", ".pytest_cache",
             ".hypothesis", ".ipynb_checkpoints", ".benchmarks", ".ci", "out", "results", "skilllib.egg-info", "_executed", "mutants"}
ANSI = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")


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
    missing = [f for f in files if not (project / f).is_file()]
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
    body = source[m.end():] if m else source
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
    client = NotebookClient(nb, km=km, timeout=timeout, kernel_name="python3",
                            extra_arguments=["--InlineBackend.figure_formats=retina"],
                            resources={"metadata": {"path": str(src.parent)}})
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
    for mine, theirs in zip((c for c in nb.cells if c.cell_type == "code"),
                            (c for c in ran.cells if c.cell_type == "code")):
        mine.outputs, mine.execution_count = theirs.outputs, theirs.execution_count
    return nb  # the chapter's own markdown cells and metadata, the other runner's outputs


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
    """Environment the kernels inherit: the venv first on PATH and inline figures.

    MPLBACKEND=Agg (set by the Makefile for tests) would stop matplotlib from showing figures,
    so the site would have none: the kernels get the inline backend instead.
    """
    bin_dir = str(Path(sys.executable).parent)
    os.environ["PATH"] = bin_dir + os.pathsep + os.environ.get("PATH", "")
    os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")


def find_myst() -> str:
    for cand in (Path(sys.executable).parent / "myst", shutil.which("myst")):
        if cand and Path(cand).exists():
            return str(cand)
    raise BuildError("the myst command was not found (pip install mystmd in the venv)")


def build(project: Path, build_dir: Path, execute: bool, timeout: int, chapter_numbers: bool,
          executed: Path | None = None) -> Path:
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
    for k, rel in enumerate(files):
        src, dst = project / rel, staging / rel
        chapter = k if (chapter_numbers and k > 0) else None
        if rel.endswith(".ipynb"):
            if executed is not None:
                nb = executed_elsewhere(src, rel, executed)
            elif execute:
                t0 = time.perf_counter()
                nb = execute_notebook(src, rel, timeout)
                log(f"executed {rel} in {time.perf_counter() - t0:.1f} s")
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
            if chapter:
                number_notebook(nb, chapter)
            dst.parent.mkdir(parents=True, exist_ok=True)
            nbformat.write(nb, dst)
        elif chapter:
            dst.write_text(set_chapter_numbering(src.read_text(encoding="utf-8"), chapter), encoding="utf-8")
    t_exec = time.perf_counter()

    # 2. Render with myst and the offline theme. CI=1 and no stdin: myst never prompts.
    env = dict(os.environ, CI="1", PWD=str(staging))
    env.pop("BASE_URL", None)
    proc = subprocess.run([find_myst(), "build", "--html"], cwd=staging, env=env, stdin=subprocess.DEVNULL,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=900)
    myst_log = proc.stdout
    (build_dir / "myst-build.log").write_text(myst_log, encoding="utf-8")
    # Show myst's warnings, errors and summary; the whole log is in BUILD_DIR/myst-build.log.
    keep = re.compile(r"\u26a0|\u26d4|error|warn|theme|Built \d+ pages|^\s+-|^\S.*:\s*$", re.I)
    for line in myst_log.splitlines():
        if keep.search(line) and "Myst CLI Versions" not in line:
            print(f"  myst | {line}", flush=True)
    if proc.returncode != 0:
        raise BuildError(f"myst build --html failed (exit {proc.returncode}); the messages above name the page")
    t_myst = time.perf_counter()

    # 3. Copy the site out, then 4. check it.
    rendered = staging / "_build" / "html"
    tmp = build_dir / "html.tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    shutil.copytree(rendered, tmp)
    shutil.rmtree(out, ignore_errors=True)
    tmp.rename(out)
    check_site(out, files)
    t_end = time.perf_counter()
    log(f"timings: stage+execute {t_exec - t_start:.1f} s, myst+render {t_myst - t_exec:.1f} s, "
        f"copy+check {t_end - t_myst:.1f} s, total {t_end - t_start:.1f} s")
    return out


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
    ap.add_argument("--executed", type=Path, metavar="DIR",
                    help="take each chapter's outputs from DIR/<name>.ipynb, executed by another runner")
    ap.add_argument("--timeout", type=int, default=600, help="seconds allowed per cell (default 600)")
    ap.add_argument("--no-chapter-numbers", action="store_true", help="number figures 1, 2, ... on every page")
    args = ap.parse_args(argv)
    project = args.project.resolve()
    build_dir = (args.build_dir or project / "_build").resolve()
    try:
        out = build(project, build_dir, not args.no_execute, args.timeout, not args.no_chapter_numbers,
                    args.executed.resolve() if args.executed else None)
    except BuildError as err:
        print(f"build_site: ERROR: {err}", file=sys.stderr, flush=True)
        return 1
    log(f"the site is in {out} (open {out / 'index.html'})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
