"""The output folder of a run: written whole into a fresh folder, then put in place of ``--out`` at once.

A run never writes into ``--out`` directly. It writes into a fresh folder beside it
(``.<name>.partial-<pid>``) and, when everything is written, replaces ``--out`` as a whole by renaming:
old figures never sit beside new results, and a run that fails or is interrupted leaves ``--out`` as it
was (an earlier run's complete results, or nothing) and removes its partial folder. A lock file beside the
folder (``.<name>.lock``, ``fcntl.flock``, released when the process ends, even when it is killed; the
empty file stays) lets one run at a time write a folder: a second run on the same folder is refused with a message.

An existing ``--out`` is replaced only if it is empty or holds nothing but what a run writes (the files
its results.json lists, results.json itself and the trial table): a run never deletes a user's own files.
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

#: Files a run writes besides the figures that its results.json lists.
RUN_FILES = ("results.json", "trials.parquet")


class OutputError(ValueError):
    """The output folder cannot be used: not a folder, holds other files, or another run writes it."""


def _written_by_a_run(folder: Path) -> list[str]:
    """Names in ``folder`` that no run wrote (empty when the folder is empty or a run's output)."""
    names = {p.name for p in folder.iterdir()}
    ours = set(RUN_FILES)
    try:
        ours |= set(json.loads((folder / "results.json").read_text()).get("figures", []))
    except (OSError, ValueError, AttributeError):
        pass
    return sorted(names - ours)


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
        foreign = _written_by_a_run(out)
        if foreign:
            shown = ", ".join(foreign[:3]) + (f" and {len(foreign) - 3} more" if len(foreign) > 3 else "")
            raise OutputError(
                f"{out}: holds files a skilllib run did not write ({shown}); a run replaces its "
                f"folder as a whole, so choose a new or empty folder for --out"
            )
    out.parent.mkdir(parents=True, exist_ok=True)
    lock_path = out.parent / f".{out.name}.lock"
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
