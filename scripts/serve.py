"""Build the book, serve it and rebuild it on every save (`make serve`), for authors.

    .venv/bin/python scripts/serve.py                 # http://127.0.0.1:8000
    .venv/bin/python scripts/serve.py --port 8080 --project DIR --build-dir DIR

Watched: myst.yml, the toc's pages, *.bib, notebooks/, images/, data/, skilllib/, scripts/ and theme/
(not node_modules). A chapter's percent script saved in an editor is first synced to its notebook
(`jupytext --sync`). Each rebuild is scripts/build_site.py with its execution cache: an edit of the
prose re-renders in seconds, an edit of a chapter's code executes that chapter again. Open pages reload
themselves after a rebuild (the server adds a small script to each page it serves; the files in
_build/html are not changed). A failed build is reported here and the last good site stays served.
Stop with Ctrl+C.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import threading
import time
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BUILD_SCRIPT = ROOT / "scripts" / "build_site.py"
WATCH_DIRS = ("notebooks", "images", "data", "skilllib", "scripts", "theme")
SKIP = {"node_modules", "__pycache__", ".ipynb_checkpoints", "_build", "_your_data", "_running_the_pipeline", "_out"}
RELOAD = b"""<script>(function () { var id = null; setInterval(function () {
  fetch('/__build').then(function (r) { return r.json(); }).then(function (b) {
    if (id === null) id = b.id; else if (b.id !== id) location.reload(); }).catch(function () {}); }, 1000); })();
</script>"""


def watched_files(project: Path) -> dict[Path, float]:
    """Every watched file with its modification time."""
    files = [project / "myst.yml", project / "index.md", *project.glob("*.md"), *project.glob("*.bib")]
    for name in WATCH_DIRS:
        for base in {project / name, ROOT / name}:
            if base.is_dir():
                files += [p for p in base.rglob("*") if p.is_file() and not SKIP.intersection(p.parts)]
    out = {}
    for p in files:
        try:
            out[p] = p.stat().st_mtime
        except FileNotFoundError:
            pass
    return out


class State:
    def __init__(self) -> None:
        self.build_id = 0
        self.ok = False
        self.lock = threading.Lock()


def make_handler(out: Path, state: State):
    class Handler(SimpleHTTPRequestHandler):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, directory=str(out), **kwargs)

        def log_message(self, fmt, *args):  # quiet: one line per rebuild is enough
            pass

        def do_GET(self):
            if self.path.startswith("/__build"):
                body = json.dumps({"id": state.build_id, "ok": state.ok}).encode()
                self.send_response(200)
                self.send_header("Content-Type", "application/json")
                self.send_header("Cache-Control", "no-store")
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)
                return
            path = Path(self.translate_path(self.path))
            if path.is_dir():
                path = path / "index.html"
            if path.suffix == ".html" and path.is_file():
                html = path.read_bytes()
                html = html.replace(b"</body>", RELOAD + b"</body>", 1)
                self.send_response(200)
                self.send_header("Content-Type", "text/html; charset=utf-8")
                self.send_header("Cache-Control", "no-store")
                self.send_header("Content-Length", str(len(html)))
                self.end_headers()
                self.wfile.write(html)
                return
            super().do_GET()

    return Handler


def sync_scripts(changed: list[Path]) -> None:
    """jupytext --sync each chapter script (notebooks/NN_*.py) that was saved."""
    scripts = [
        p for p in changed if p.suffix == ".py" and p.parent.name == "notebooks" and p.with_suffix(".ipynb").exists()
    ]
    if scripts:
        jupytext = Path(sys.executable).parent / "jupytext"
        subprocess.run([str(jupytext), "--sync", *map(str, scripts)], check=False, stdout=subprocess.DEVNULL)


def build(project: Path, build_dir: Path, state: State) -> None:
    t0 = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, str(BUILD_SCRIPT), "--project", str(project), "--build-dir", str(build_dir)],
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
    )
    took = time.perf_counter() - t0
    with state.lock:
        if proc.returncode == 0:
            state.build_id += 1
            state.ok = True
            print(f"serve: built in {took:.1f} s (build {state.build_id})", flush=True)
        else:
            state.ok = False
            print(
                f"serve: the build failed after {took:.1f} s; still serving the last good site.\n"
                + proc.stderr.strip()[-2000:],
                flush=True,
            )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--project", type=Path, default=ROOT)
    ap.add_argument("--build-dir", type=Path)
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, default=8000)
    ap.add_argument("--interval", type=float, default=1.0, help="seconds between checks for saved files")
    args = ap.parse_args(argv)
    project = args.project.resolve()
    build_dir = (args.build_dir or project / "_build").resolve()
    state = State()
    seen = watched_files(project)  # before the build: a file saved during it is rebuilt next
    build(project, build_dir, state)
    server = ThreadingHTTPServer((args.host, args.port), make_handler(build_dir / "html", state))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    print(f"serve: http://{args.host}:{server.server_address[1]}/ (Ctrl+C stops)", flush=True)
    try:
        while True:
            time.sleep(args.interval)
            now = watched_files(project)
            if now == seen:
                continue
            time.sleep(0.3)  # let an editor finish writing
            now = watched_files(project)
            changed = [p for p in now if seen.get(p) != now[p]] + [p for p in seen if p not in now]
            print(
                "serve: changed "
                + ", ".join(str(p.relative_to(project) if p.is_relative_to(project) else p) for p in changed[:5])
                + (" ..." if len(changed) > 5 else ""),
                flush=True,
            )
            sync_scripts(changed)
            seen = watched_files(project)  # after the sync (it writes the pair), before the build
            build(project, build_dir, state)
    except KeyboardInterrupt:
        print("serve: stopped", flush=True)
    finally:
        server.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
