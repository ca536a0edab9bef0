"""The checks of every trial's samples, for many trials at once, and of a corpus's sampling rate and
units (used by :mod:`skilllib.recordings` and :mod:`skilllib.features`).

:func:`trial_problem` is the definition, one trial at a time: the reason why its samples are unusable.
:func:`trial_problems` finds the trials with a problem by flags over the flat arrays and asks
trial_problem for the reason of those only; :func:`trial_stats` computes, in blocks of trials of equal
length (:mod:`skilllib.recordings`), what the sampling-rate, unit and timing checks of :mod:`skilllib.recordings`
read from every usable trial: the median interval, the regular mean interval
(:func:`skilllib.recordings.regular_mean_interval`), the span of the positions, the 95th percentile of the
step between samples and the shortest and longest interval. Every value has the same bits as the
per-trial computation (tests compare them); a trial whose regular mean interval needs more than the
common two steps (dropped frames, jitter of a sizeable fraction of the interval) is computed by
regular_mean_interval itself.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import _timing as timing
from ._columns import POSITION_COLUMNS
from ._errors import DataFormatError
from ._runs import Runs
from ._timing import MIN_RATE_HZ, MIXED_FRACTION, RATE_TOLERANCE, TRIM, regular_mean_interval

MIN_SAMPLES = 5  #: fewer samples than this make a trial invalid
MAX_RANGE_M = 2.0  #: a trial spanning more than this (m) has wrong units or a glitch (device: 0.38 m)
#: with the unit stated (header, --units): only a span beyond this (m) is a glitch (a lab's capture volume
#: is rarely over 15 m across; overground gait spans a few metres and must be read)
MAX_KNOWN_RANGE_M = 20.0
MAX_TYPICAL_SPEED = 20.0  #: m/s; a typical (median over trials of the 95th percentile) speed above it: wrong units


def trial_problem(
    t: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray,
    rows: np.ndarray,
    line: Callable[[int], int],
    loc: Callable[[int], str],
) -> str:
    """Reason why one trial's samples are unusable ('' when fine); time/units checks come later.
    Missing (NaN) positions are not a problem here: they are gaps, filled or judged by
    :func:`skilllib.recordings.repair_trial`. ``rows``: the trial's rows (kept-row numbers, ascending);
    ``line(r)``/``loc(r)`` name row r."""
    n = len(rows)
    if rows[-1] - rows[0] + 1 != n:
        gap = int(np.flatnonzero(np.diff(rows) > 1)[0])
        return (
            f"rows not contiguous: {loc(rows[0])} to {line(rows[gap])} and from {loc(rows[gap + 1])} "
            f"on belong to it, with other rows between"
        )
    if n < MIN_SAMPLES:
        return f"too few samples ({n}; need at least {MIN_SAMPLES})"
    if np.isnan(t).any():
        return f"time stamp missing at {loc(rows[np.flatnonzero(np.isnan(t))[0]])}"
    for j, name in enumerate(POSITION_COLUMNS):  # NaN (missing) positions are gaps (skilllib.recordings)
        bad = np.isinf(pos[:, j])
        if bad.any():
            return f"{name} is infinite at {loc(rows[int(np.flatnonzero(bad)[0])])}"
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


def trial_problems(
    t: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray,
    trial_of_row: np.ndarray,
    rows: list[np.ndarray],
    line: Callable[[int], int],
    loc: Callable[[int], str],
) -> list[str]:
    """:func:`trial_problem` of every trial: ``trial_of_row`` (R,) the trial number of each row,
    ``rows[i]`` the rows of trial i (ascending). Flags over the flat arrays find the trials with a
    problem; only those are looked at one by one, for their reason."""
    n_trials = len(rows)
    count = np.bincount(trial_of_row, minlength=n_trials)
    first = np.array([r[0] for r in rows], dtype=np.int64)
    last = np.array([r[-1] for r in rows], dtype=np.int64)
    flagged = (last - first + 1 != count) | (count < MIN_SAMPLES)
    bad_row = np.isnan(t) | np.isinf(pos).any(axis=1) | np.isnan(contact)  # NaN positions: gaps, repaired later
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
        common = (np.abs(d - med[:, None]) <= TRIM * med[:, None]).all(axis=1) & (
            np.abs(d - mean[:, None]) <= TRIM * mean[:, None]
        ).all(axis=1)
        for k in np.flatnonzero(~common):
            mean[k] = regular_mean_interval(t[rows[k]])
        p = pos[rows]
        out["med_dt"][trials], out["mean_dt"][trials] = med, mean
        out["span"][trials] = np.ptp(p, axis=1).max(axis=1)
        out["step95"][trials] = np.percentile(np.linalg.norm(np.diff(p, axis=1), axis=2), 95, axis=1)
        out["d_min"][trials], out["d_max"][trials] = d.min(axis=1), d.max(axis=1)
    return TrialStats(**out)


def corpus_rate(source: str, med_dt: np.ndarray, mean_dt: np.ndarray) -> tuple[float, float]:
    """``(ref, dt)`` of a corpus from its usable trials' median and regular mean intervals.

    The median of the medians and the file's interval (see :mod:`skilllib.recordings`).

    Parameters
    ----------
    source : str
        The file, for messages (text).
    med_dt : numpy.ndarray
        Each trial's median interval (s), NaN for trials not usable.
    mean_dt : numpy.ndarray
        Each trial's regular mean interval (s), NaN for trials not usable.

    Returns
    -------
    ref : float
        The median of the trials' median intervals (s).
    dt : float
        The file's sampling interval (s).

    Raises
    ------
    DataFormatError
        For time stamps not in seconds and for mixed rates.
    """
    ok = ~np.isnan(med_dt)
    ref = float(np.median(med_dt[ok]))
    if ref > 1 / MIN_RATE_HZ:
        advice = timing.time_unit_advice(ref)
        option = next(
            (o for word, o in (("like milliseconds", "ms"), ("like microseconds", "us")) if word in advice), ""
        )
        hint = f", or give the unit: --time-unit {option}" if option else ""
        raise DataFormatError(f"{source}: {advice}{hint}")
    off = np.abs(med_dt / ref - 1) > RATE_TOLERANCE  # NaN compares False
    if off.sum() > MIXED_FRACTION * ok.sum():
        rates = pd.Series(np.round(1 / mean_dt[ok], 1)).value_counts()
        desc = ", ".join(f"{n} trials at {hz:g} Hz" for hz, n in rates.head(4).items())
        raise DataFormatError(
            f"{source}: mixed sampling rates ({desc}); split the file by rate or resample every trial to one rate"
        )
    return ref, float(np.median(mean_dt[ok & ~off]))


def _check_rates(source: str, stats: TrialStats, reasons: list[str], rate: tuple[float, float] | None = None) -> float:
    """Time units and mixed rates (errors, unless ``rate`` is given), single off-rate trials (invalid);
    returns the sampling interval in s. ``stats``: NaN for the trials not usable."""
    med_dt, mean_dt = stats.med_dt, stats.mean_dt
    ref, dt = corpus_rate(source, med_dt, mean_dt) if rate is None else rate
    off = np.abs(med_dt / ref - 1) > RATE_TOLERANCE  # NaN compares False
    for i in np.flatnonzero(off):
        reasons[i] = (
            f"sampled at {1 / mean_dt[i]:.1f} Hz, the file at {1 / dt:.1f} Hz "
            f"(mean interval {mean_dt[i]:.4f} s vs {dt:.4f} s)"
        )
    return dt


def _check_units(
    source: str,
    stats: TrialStats,
    reasons: list[str],
    dt: float,
    corpus_checked: bool = False,
    units_known: bool = False,
) -> None:
    """Positions in millimetres (or centimetres) raise (unless ``corpus_checked``: the caller checked the
    whole corpus, :func:`check_corpus_units`); a single trial with a huge span is invalid. When the unit is
    stated (``units_known``: a file header's or ``--units``) it is believed: no "not metres" check, and only
    a span beyond :data:`MAX_KNOWN_RANGE_M` (a glitch, not a movement) makes a trial invalid."""
    idx = np.array([i for i in range(len(reasons)) if not reasons[i]], dtype=np.int64)
    if not idx.size:
        return
    span = stats.span[idx]
    if not corpus_checked and not units_known:
        check_corpus_units(source, span, stats.step95[idx] / dt)
    limit = MAX_KNOWN_RANGE_M if units_known else MAX_RANGE_M
    for j, i in enumerate(idx):
        if span[j] > limit:
            reasons[i] = (
                f"positions span {span[j]:.3g} m (more than {limit:g} m, with the unit stated): a glitch"
                if units_known
                else f"positions span {span[j]:.3g} m (more than {limit:g} m): a glitch or wrong units"
            )


def check_corpus_units(source: str, span: np.ndarray, speed95: np.ndarray) -> None:
    """DataFormatError when the typical trial says the positions are not in metres.

    The typical trial: the median over trials of the span (m) and of the 95th percentile speed (m/s).

    Parameters
    ----------
    source : str
        The file, for the message (text).
    span : numpy.ndarray
        Each trial's span of positions (m, if the positions are in metres).
    speed95 : numpy.ndarray
        Each trial's 95th percentile speed (m/s, if the positions are in metres).

    Raises
    ------
    DataFormatError
        When the typical span or speed is too large for metres.
    """
    if np.median(span) > MAX_RANGE_M or np.median(speed95) > MAX_TYPICAL_SPEED:
        raise DataFormatError(
            f"{source}: positions look like millimetres or centimetres, not metres (a typical trial spans "
            f"{np.median(span):.3g} and moves at up to {np.median(speed95):.3g} per s; a hand-held device spans "
            f"well under {MAX_RANGE_M:g} m): write x, y, z in metres (divide millimetres by 1000, centimetres by "
            f"100), or give the unit: --units mm"
        )
