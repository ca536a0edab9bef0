"""Many trials at once: trials as runs of rows of flat arrays, processed in blocks of equal length.

A corpus of 10^5 trials cannot afford a Python loop with pandas indexing per trial (about 1 ms each). Its
trials are instead runs of rows of flat arrays (``t`` (R,), ``pos`` (R, 3), ...): trial ``i`` is rows
``start[i] .. start[i] + length[i] - 1``. Trials of equal length ``n`` are gathered into one block
(``K x n`` rows) and every per-trial computation runs on the block along its second axis.

Why blocks of equal length rather than one pass over the flat arrays: numpy computes a reduction along
the last axis of a block row by row exactly as it computes it on that row alone (``np.sum``'s pairwise
summation, ``np.median``, ``np.percentile``, ``np.linalg.norm``, ``scipy.signal.savgol_filter``'s
convolution), so the block path gives the *same bits* as the per-trial functions of :mod:`skilllib.recordings`
and :mod:`skilllib.features`, which stay the reference (tests compare the two). A sum over the flat array
with ``np.add.reduceat`` would add in another order and differ in the last bits.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Runs:
    """Trial ``i`` is the rows ``start[i] .. start[i] + length[i] - 1`` of flat arrays (int64 arrays).

    Attributes
    ----------
    start : numpy.ndarray of int64
        First row of each trial (samples).
    length : numpy.ndarray of int64
        Number of rows of each trial (samples).
    """

    start: np.ndarray
    length: np.ndarray

    def __post_init__(self) -> None:
        if self.start.shape != self.length.shape:
            raise ValueError(f"start ({self.start.shape}) and length ({self.length.shape}) differ in shape")

    def __len__(self) -> int:
        return len(self.start)

    @classmethod
    def from_codes(cls, codes: np.ndarray) -> Runs:
        """The runs of equal consecutive values of ``codes`` (one per trial when trials are contiguous)."""
        codes = np.asarray(codes)
        if codes.size == 0:
            return cls(np.zeros(0, np.int64), np.zeros(0, np.int64))
        edges = np.flatnonzero(codes[1:] != codes[:-1]) + 1
        start = np.concatenate([[0], edges]).astype(np.int64)
        end = np.concatenate([edges, [codes.size]]).astype(np.int64)
        return cls(start, end - start)

    def blocks(
        self, which: np.ndarray | None = None, length: np.ndarray | None = None, offset: np.ndarray | None = None
    ) -> Iterator[tuple[np.ndarray, np.ndarray]]:
        """For each distinct length n: ``(trials, rows)``, the trial numbers (ascending) and the (K, n)
        row indices of their rows. ``which``: the trials to include (bool mask or indices; default all);
        ``length``: use these lengths instead of the runs' (e.g. the samples before contact);
        ``offset``: start each trial this many rows after its start."""
        idx = np.arange(len(self)) if which is None else np.asarray(which)
        if idx.dtype == bool:
            idx = np.flatnonzero(idx)
        n_of = (self.length if length is None else np.asarray(length))[idx]
        first = self.start[idx] + (0 if offset is None else np.asarray(offset)[idx])
        if idx.size == 0:
            return
        order = np.argsort(n_of, kind="stable")
        n_sorted = n_of[order]
        cuts = np.flatnonzero(np.diff(n_sorted)) + 1
        for part in np.split(order, cuts):
            n = int(n_of[part[0]])
            yield idx[part], first[part][:, None] + np.arange(n)


def first_true(flags: np.ndarray, runs: Runs) -> np.ndarray:
    """Per run, the index (within the run) of its first True value of the flat bool array ``flags``.

    The run's length when it has none (also for an empty run). Runs may lie anywhere in ``flags``.

    Parameters
    ----------
    flags : numpy.ndarray of bool
        The flat flags (dimensionless).
    runs : Runs
        The runs (rows of ``flags``; samples).

    Returns
    -------
    numpy.ndarray of int
        Per run the index of its first True value within the run (samples).
    """
    out = runs.length.copy()
    full = np.flatnonzero(runs.length > 0)
    if full.size == 0:
        return out
    length = runs.length[full]
    offsets = np.cumsum(length) - length
    within = np.arange(int(length.sum()), dtype=np.int64) - np.repeat(offsets, length)
    gathered = np.asarray(flags, bool)[np.repeat(runs.start[full], length) + within]
    where = np.where(gathered, within, np.iinfo(np.int64).max)
    out[full] = np.minimum(np.minimum.reduceat(where, offsets), length)
    return out
