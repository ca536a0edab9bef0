"""The output folder of a run: written whole into a fresh folder, then put in place of ``--out`` at once.

A run never writes into ``--out`` directly. It writes into a fresh folder beside it
(``.<name>.partial-<pid>``) and, when everything is written, replaces ``--out`` as a whole by renaming:
old figures never sit beside new results, and a run that fails or is interrupted leaves ``--out`` as it
was (an earlier run's complete results, or nothing) and removes its partial folder. A lock file beside the
folder (``.<name>.lock``, ``fcntl.flock``, released when the process ends, even when it is killed; the
empty file stays) lets one run at a time write a folder: a second run on the same folder is refused with a message.

An existing ``--out`` is replaced only if it is empty or was written by a skilllib run: the run writes a
manifest, :data:`MANIFEST`, listing every file it wrote, and a later run replaces the folder only when
everything in it is on that list. A folder without a manifest (another tool's, a user's own, even one
holding a ``results.json``) is never replaced: a run never deletes a file it did not write.
:func:`check_output` makes these checks, and those of the lock and the permissions, before a run computes
anything; :func:`output_folder` makes them again when it writes.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import shutil
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from .. import __version__

#: Files a run writes besides its figures.
RUN_FILES = ("results.json", "trials.parquet")
#: The manifest a run writes into its output folder: the files it wrote (JSON, with the skilllib version).
MANIFEST = ".skilllib-run.json"


class OutputError(ValueError):
    """The output folder cannot be used: not a folder, holds other files, or another run writes it."""


def _not_written_by_a_run(folder: Path) -> list[str]:
    """Names in ``folder`` that no skilllib run wrote (empty when the folder is empty or a run's output)."""
    names = {p.name for p in folder.iterdir()}
    if not names:
        return []
    try:
        ours = set(json.loads((folder / MANIFEST).read_text())["files"]) | {MANIFEST}
    except (OSError, ValueError, KeyError, TypeError):
        ours = set()  # no manifest (or not ours): nothing in the folder is a run's
    return sorted(names - ours)


def _lock_path(out: Path) -> Path:
    return out.parent / f".{out.name}.lock"


def check_output(out: str | Path, inputs: tuple[str | Path, ...] = ()) -> Path:
    """Check that a run may write ``out`` before it computes anything.

    Parameters
    ----------
    out : str or pathlib.Path
        The output folder (``--out``; text).
    inputs : tuple of str or pathlib.Path
        The run's input files or folders (text): none may lie inside ``out``, which the run replaces.

    Returns
    -------
    pathlib.Path
        ``out`` as an absolute path.

    Raises
    ------
    OutputError
        An empty name; the current folder or one that holds it; a file; a folder holding files no run
        wrote; a folder holding an input; a parent folder the run cannot write into; a folder another run
        is writing. The message says what to do.
    """
    if str(out).strip() == "":
        raise OutputError("--out is empty: name a new or empty folder for the results")
    out = Path(out).absolute()
    cwd = Path.cwd().absolute()
    if out == cwd or out in cwd.parents:
        raise OutputError(
            f"{out}: is the current folder or holds it; a run replaces its --out as a whole, so name a new "
            f"folder for the results (e.g. --out results)"
        )
    if out.exists() and not out.is_dir():
        raise OutputError(f"{out}: exists and is not a folder (--out names the folder for the results)")
    for given in inputs:
        path = Path(given).absolute()
        if path == out or out in path.parents:
            raise OutputError(
                f"{out}: holds the input {given}; a run replaces its --out as a whole, so name another folder"
            )
    if out.is_dir():
        foreign = _not_written_by_a_run(out)
        if foreign:
            shown = ", ".join(foreign[:3]) + (f" and {len(foreign) - 3} more" if len(foreign) > 3 else "")
            raise OutputError(
                f"{out}: holds files a skilllib run did not write ({shown}; a run's folder has its {MANIFEST}); "
                f"a run replaces its folder as a whole, so choose a new or empty folder for --out"
            )
    parent = next((p for p in (out.parent, *out.parent.parents) if p.exists()), None)
    if parent is None or not os.access(parent, os.W_OK | os.X_OK):
        raise OutputError(f"{out}: cannot write into {parent} (permission denied); choose another --out")
    lock_path = _lock_path(out)
    if lock_path.exists():
        with open(lock_path) as lock:
            try:
                fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                who = lock.read().strip() or "another process"
                raise OutputError(
                    f"{out}: another skilllib run ({who}) is writing this folder; wait for it to finish or "
                    f"choose another --out"
                ) from None
            fcntl.flock(lock, fcntl.LOCK_UN)
    return out


@contextlib.contextmanager
def output_folder(out: str | Path) -> Iterator[Path]:
    """Yield a fresh, empty folder to write a run's output into; on normal exit it replaces ``out``
    (module docstring). Raises :class:`OutputError` when ``out`` is a file, holds files no run wrote, or
    another run holds its lock; on an exception inside the block the fresh folder is removed and ``out``
    is left as it was.

    Parameters
    ----------
    out : str or pathlib.Path
        The output folder (``--out``) the run's output replaces as a whole (text).

    Yields
    ------
    pathlib.Path
        The fresh, empty folder ``.<name>.partial-<pid>`` beside ``out`` to write into.

    Raises
    ------
    OutputError
        When ``out`` is a file, holds files no run wrote, or another run holds its lock.
    """
    out = Path(out).absolute()
    if out.exists() and not out.is_dir():
        raise OutputError(f"{out}: exists and is not a folder (--out names the folder for the results)")
    if out.is_dir():
        foreign = _not_written_by_a_run(out)
        if foreign:
            shown = ", ".join(foreign[:3]) + (f" and {len(foreign) - 3} more" if len(foreign) > 3 else "")
            raise OutputError(
                f"{out}: holds files a skilllib run did not write ({shown}; a run's folder has its {MANIFEST}); "
                f"a run replaces its folder as a whole, so choose a new or empty folder for --out"
            )
    out.parent.mkdir(parents=True, exist_ok=True)
    lock_path = _lock_path(out)
    with open(lock_path, "a+") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            lock.seek(0)
            who = lock.read().strip() or "another process"
            raise OutputError(
                f"{out}: another skilllib run ({who}) is writing this folder; wait for it to "
                f"finish or choose another --out"
            ) from None
        lock.seek(0)
        lock.truncate()
        lock.write(f"pid {os.getpid()}")
        lock.flush()
        for stale in out.parent.glob(f".{out.name}.partial-*"):  # left by a run that was killed
            shutil.rmtree(stale, ignore_errors=True)
        partial = out.parent / f".{out.name}.partial-{os.getpid()}"
        partial.mkdir()
        try:
            yield partial
            written = sorted(p.name for p in partial.iterdir())
            (partial / MANIFEST).write_text(json.dumps({"skilllib": __version__, "files": written}, indent=1) + "\n")
        except BaseException:
            shutil.rmtree(partial, ignore_errors=True)
            raise
        if out.exists():
            old = out.parent / f".{out.name}.old-{os.getpid()}"
            out.rename(old)
            partial.rename(out)
            shutil.rmtree(old, ignore_errors=True)
        else:
            partial.rename(out)
        lock.truncate(0)  # the lock file stays (removing it would let two runs lock two different files)


def write_json_atomic(data: Any, path: Path) -> None:
    """Write ``data`` as JSON (indent 1, no NaN) to ``path`` through a temporary file and a rename."""
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(json.dumps(data, indent=1, allow_nan=False) + "\n")
    os.replace(tmp, path)
