"""The checks of every trial's samples, for many trials at once (used by :mod:`skilllib.data`).

:func:`trial_problem` is the definition, one trial at a time: the reason why its samples are unusable.
:func:`trial_problems` finds the trials with a problem by flags over the flat arrays and asks
trial_problem for the reason of those only; :func:`trial_stats` computes, in blocks of trials of equal
length (:mod:`skilllib.ragged`), what the sampling-rate, unit and timing checks of :mod:`skilllib.data`
read from every usable trial: the median interval, the regular mean interval
(:func:`skilllib.timing.regular_mean_interval`), the span of the positions, the 95th percentile of the
step between samples and the shortest and longest interval. Every value has the same bits as the
per-trial computation (tests compare them); a trial whose regular mean interval needs more than the
common two steps (dropped frames, jitter of a sizeable fraction of the interval) is computed by
regular_mean_interval itself.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .ragged import Runs
from .timing import TRIM, regular_mean_interval

MIN_SAMPLES = 5  #: fewer samples than this make a trial invalid
POSITION_COLUMNS = ("x", "y", "z")


def trial_problem(t: np.ndarray, pos: np.ndarray, contact: np.ndarray, rows: np.ndarray,
                  line: Callable[[int], int], loc: Callable[[int], str]) -> str:
    """Reason why one trial's samples are unusable ('' when fine); time/units checks come later.
    ``rows``: the trial's rows (kept-row numbers, ascending); ``line(r)``/``loc(r)`` name row r."""
    n = len(rows)
    if rows[-1] - rows[0] + 1 != n:
        gap = int(np.flatnonzero(np.diff(rows) > 1)[0])
        return (f"rows not contiguous: {loc(rows[0])} to {line(rows[gap])} and from {loc(rows[gap + 1])} "
                f"on belong to it, with other rows between")
    if n < MIN_SAMPLES:
        return f"too few samples ({n}; need at least {MIN_SAMPLES})"
    if np.isnan(t).any():
        return f"time stamp missing at {loc(rows[np.flatnonzero(np.isnan(t))[0]])}"
    for j, name in enumerate(POSITION_COLUMNS):
        bad = ~np.isfinite(pos[:, j])
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            what = "missing (NaN)" if np.isnan(pos[k, j]) else "infinite"
            return f"{name} is {what} at {loc(rows[k])}"
    if np.isnan(contact).any():
        return f"contact flag missing at {loc(rows[np.flatnonzero(np.isnan(contact))[0]])}"
    d = np.diff(t)
    if (d < 0).any():
        k = int(np.flatnonzero(d < 0)[0]) + 1
        return f"time goes backwards at {loc(rows[k])} (t = {t[k]:g} s after {t[k - 1]:g} s)"
    if (d == 0).any():
        k = int(np.flatnonzero(d == 0)[0]) + 1
        return f"time stamp repeated at {loc(rows[k])} (t = {t[k]:g} s)"
    return ""


def trial_problems(t: np.ndarray, pos: np.ndarray, contact: np.ndarray, trial_of_row: np.ndarray,
                   rows: list[np.ndarray], line: Callable[[int], int], loc: Callable[[int], str]) -> list[str]:
    """:func:`trial_problem` of every trial: ``trial_of_row`` (R,) the trial number of each row,
    ``rows[i]`` the rows of trial i (ascending). Flags over the flat arrays find the trials with a
    problem; only those are looked at one by one, for their reason."""
    n_trials = len(rows)
    count = np.bincount(trial_of_row, minlength=n_trials)
    first = np.array([r[0] for r in rows], dtype=np.int64)
    last = np.array([r[-1] for r in rows], dtype=np.int64)
    flagged = (last - first + 1 != count) | (count < MIN_SAMPLES)
    bad_row = np.isnan(t) | ~np.isfinite(pos).all(axis=1) | np.isnan(contact)
    same = trial_of_row[1:] == trial_of_row[:-1]
    bad_step = same & ~(np.diff(t) > 0)  # backwards or repeated (NaN is caught above)
    flagged |= np.bincount(trial_of_row[bad_row], minlength=n_trials) > 0
    flagged |= np.bincount(trial_of_row[1:][bad_step], minlength=n_trials) > 0
    reasons = [""] * n_trials
    for i in np.flatnonzero(flagged):
        r = rows[i]
        reasons[i] = trial_problem(t[r], pos[r], contact[r], r, line, loc)
    return reasons


@dataclass(frozen=True)
class TrialStats:
    """Per trial (NaN for trials not looked at): ``med_dt`` and ``mean_dt`` (s, the median and the
    regular mean interval), ``span`` (m, the largest range of x, y or z), ``step95`` (m, the 95th
    percentile of the distance between consecutive samples), ``d_min`` and ``d_max`` (s, the shortest
    and longest interval)."""

    med_dt: np.ndarray
    mean_dt: np.ndarray
    span: np.ndarray
    step95: np.ndarray
    d_min: np.ndarray
    d_max: np.ndarray


def trial_stats(t: np.ndarray, pos: np.ndarray, runs: Runs, which: np.ndarray) -> TrialStats:
    """:class:`TrialStats` of the ``which`` trials (contiguous runs of ``t`` (R,) s and ``pos`` (R, 3) m)."""
    n = len(runs)
    out = {k: np.full(n, np.nan) for k in TrialStats.__dataclass_fields__}
    for trials, rows in runs.blocks(which):
        d = np.diff(t[rows], axis=1)
        med = np.median(d, axis=1)
        mean = d.mean(axis=1)
        # regular_mean_interval's two steps when every interval lies in both windows; else its own loop
        common = (np.abs(d - med[:, None]) <= TRIM * med[:, None]).all(axis=1) & \
                 (np.abs(d - mean[:, None]) <= TRIM * mean[:, None]).all(axis=1)
        for k in np.flatnonzero(~common):
            mean[k] = regular_mean_interval(t[rows[k]])
        p = pos[rows]
        out["med_dt"][trials], out["mean_dt"][trials] = med, mean
        out["span"][trials] = np.ptp(p, axis=1).max(axis=1)
        out["step95"][trials] = np.percentile(np.linalg.norm(np.diff(p, axis=1), axis=2), 95, axis=1)
        out["d_min"][trials], out["d_max"][trials] = d.min(axis=1), d.max(axis=1)
    return TrialStats(**out)
