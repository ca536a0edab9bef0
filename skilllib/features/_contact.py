"""The speed at the instant of contact, estimated from samples that straddle it.

The feature table's ``contact_speed`` (:func:`skilllib.features.trial_features`) is the speed at the last
sample *before* contact: the backward three-point derivative there (at 60 Hz), which lies between 0 and
one sampling interval (16.7 ms) before the touch. On an approach that still decelerates (or accelerates)
into the surface it is therefore the speed up to 16.7 ms too early. The estimators here fit a polynomial
in time to the last positions before contact (least squares, per axis) and evaluate its derivative at an
estimate of the contact instant instead:

* ``"last-sample"``: at the last sample before contact (with ``degree=2, n_fit=3`` exactly the feature
  table's value at 60 Hz, the reference);
* ``"midpoint"``: halfway between the last sample before contact and the first in contact (the instant
  is unknown inside that interval; its middle halves the largest time error);
* ``"crossing"``: where the fitted path reaches the surface, which the samples *after* contact place: the
  median position of the samples in contact within ``rest_s`` s of the first one (the tip resting on the
  surface), crossed along the approach direction at the last sample; the instant is kept inside the
  interval between the last sample before contact and the first in contact, where the contact flag puts
  it. It uses both sides of contact, and assumes the tip stays at the surface after the touch.

The defaults, a cubic fitted to the last 4 samples, are the best of the fits tried on the book's cohort
(chapter 3 measures them against the generator's truth). The fit uses the raw positions (not the run's
low-pass filter): a polynomial fit is itself a smoother. A fit extrapolated beyond its samples amplifies
position noise more than a derivative at a sample does: white position noise of SD s (m) gives a velocity
noise per axis of 2.55 s fs for the last sample (quadratic, 3 samples), 7.7 s fs for the cubic at the
middle of the last interval and 12.7 s fs at its end. At the Phantom's 0.03 mm and 60 Hz that is at most
0.023 m/s, well below the 0.08 m/s SD of the last sample's error on the book's cohort; a noisier device
calls for a lower degree or more samples (``degree``, ``n_fit``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from ..recordings import ID_COLUMNS, Recordings
from ._segmentation import CONTACT_WINDOW

#: The estimators of :func:`contact_speed_at` (text); the feature table's is "last-sample".
CONTACT_ESTIMATORS = ("last-sample", "midpoint", "crossing")
#: Time after the first contact sample whose samples place the surface for ``"crossing"`` (s).
REST_S = 0.25


@dataclass(frozen=True)
class ContactEstimate:
    """One trial's estimated contact instant and contact speed.

    Attributes
    ----------
    speed : float
        The speed at the estimated instant (m/s); NaN when it cannot be estimated.
    t_contact : float
        The estimated contact instant (s, on the recording's clock); NaN when it cannot be estimated.
    reason : str
        Why it cannot be estimated; "" when it can (text).
    """

    speed: float
    t_contact: float
    reason: str = ""


def _check(method: str, degree: int, n_fit: int) -> None:
    if method not in CONTACT_ESTIMATORS:
        raise ValueError(f"unknown contact estimator {method!r}; expected one of {', '.join(CONTACT_ESTIMATORS)}")
    if degree < 1:
        raise ValueError(f"degree must be at least 1 (a velocity needs a slope), got {degree}")
    if n_fit < degree + 1:
        raise ValueError(f"n_fit = {n_fit} samples cannot fit a polynomial of degree {degree}: need {degree + 1}")


def contact_speed_at(
    t: np.ndarray,
    pos: np.ndarray,
    end: int,
    *,
    fs: float | None = None,
    method: str = "crossing",
    degree: int = 3,
    n_fit: int = 4,
    rest_s: float = REST_S,
) -> ContactEstimate:
    """The contact instant and the speed then, from one trial's samples (module docstring).

    Parameters
    ----------
    t : numpy.ndarray, shape (N,)
        The time stamps (s), increasing.
    pos : numpy.ndarray, shape (N, 3)
        The positions (m).
    end : int
        The index of the first sample in contact (samples); the fit uses the ``n_fit`` samples before it.
    fs : float or None
        The sampling rate (Hz): the samples are then taken as 1/fs apart, as the feature table takes them
        (stamps rounded when written, such as the book's 0.1 ms, do not bend the fit); None: the time
        stamps ``t`` as they are.
    method : str
        ``"last-sample"``, ``"midpoint"`` or ``"crossing"`` (:data:`CONTACT_ESTIMATORS`).
    degree : int
        The degree of the polynomial fitted to the positions, per axis (dimensionless, at least 1).
    n_fit : int
        How many samples before contact the fit uses (samples, at least ``degree + 1``).
    rest_s : float
        For ``"crossing"``: the samples in contact up to this long after the first one place the surface (s).

    Returns
    -------
    ContactEstimate
        The speed (m/s) and instant (s), or NaN with the reason when the trial has too few samples before
        contact (or, for ``"crossing"``, none in contact).

    Raises
    ------
    ValueError
        For an unknown method, a degree below 1 or ``n_fit`` below ``degree + 1``.
    """
    _check(method, degree, n_fit)
    t = np.asarray(t, dtype=float)
    pos = np.asarray(pos, dtype=float)
    if end < n_fit:
        return ContactEstimate(np.nan, np.nan, f"{end} samples before contact; the fit needs {n_fit}")
    if method != "last-sample" and end >= len(t):
        return ContactEstimate(np.nan, np.nan, "no sample in contact: the contact instant cannot be bracketed")
    t0 = t[end - 1]
    if fs is None:  # the stamps; dimensionless, last sample at 0: a well-conditioned fit
        dt = t[end - 1] - t[end - 2]  # end >= n_fit >= 2
        tau, x_end = (t[end - n_fit : end] - t0) / dt, ((t[end] - t0) / dt if end < len(t) else 1.0)
    else:  # the grid
        dt, tau, x_end = 1.0 / fs, np.arange(1.0 - n_fit, 1.0), 1.0
    coef = np.polynomial.polynomial.polyfit(tau, pos[end - n_fit : end], degree)  # (degree + 1, 3)
    dcoef = np.polynomial.polynomial.polyder(coef) / dt  # m/s per power of tau

    def vel(x: float) -> np.ndarray:
        return np.polynomial.polynomial.polyval(x, dcoef)

    if method == "last-sample":
        x = 0.0
    else:
        if method == "midpoint":
            x = 0.5 * x_end
        else:
            u = vel(0.0)
            norm = np.linalg.norm(u)
            if norm == 0:
                return ContactEstimate(np.nan, np.nan, "no motion at the last sample before contact")
            u = u / norm
            after = (t >= t[end]) & (t <= t[end] + rest_s)
            after[:end] = False
            surface = np.median(pos[after], axis=0) @ u  # m along the approach direction
            poly = coef @ u  # the fitted path along u (m), coefficients in tau
            poly[0] -= surface
            roots = np.polynomial.polynomial.polyroots(poly) if np.any(poly[1:]) else np.zeros(0)
            real = roots[np.abs(roots.imag) < 1e-9].real
            if np.any(real >= 0):  # the first crossing after the last sample; else: it never gets there
                x = float(np.clip(real[real >= 0].min(), 0.0, x_end))
            else:
                x = x_end
    return ContactEstimate(float(np.linalg.norm(vel(x))), float(t0 + x * dt))


def contact_speed_estimates(
    recordings: Recordings,
    features: pd.DataFrame,
    *,
    method: str = "crossing",
    degree: int = 3,
    n_fit: int = 4,
    rest_s: float = REST_S,
) -> pd.DataFrame:
    """The contact speed of every segmented trial by :func:`contact_speed_at`.

    The end sample of each trial is the feature table's ``t_contact`` (the first contact sample, or the
    end sample of another end rule); invalid trials get NaN and their reason. The samples are taken on
    the recordings' grid (``fs``), as the feature table takes them.

    Parameters
    ----------
    recordings : Recordings
        The recordings the features came from (t in s, positions in m).
    features : pandas.DataFrame
        Their feature table (:func:`skilllib.features.trial_features`; ``t_contact`` in s).
    method : str
        ``"last-sample"``, ``"midpoint"`` or ``"crossing"`` (:data:`CONTACT_ESTIMATORS`).
    degree : int
        The degree of the polynomial fitted to the positions (dimensionless).
    n_fit : int
        How many samples before contact the fit uses (samples).
    rest_s : float
        For ``"crossing"``: how long after the first contact sample the samples place the surface (s).

    Returns
    -------
    pandas.DataFrame
        One row per row of ``features``: ``participant``, ``trial``, ``contact_speed`` (m/s),
        ``t_contact`` (s, the estimated instant) and ``reason`` (text, "" when estimated).
    """
    _check(method, degree, n_fit)
    if not isinstance(recordings, Recordings):
        raise TypeError(f"expected Recordings, got {type(recordings).__name__}")
    rows: list[dict[str, Any]] = []
    for p, tr, status, reason, tc in features[[*ID_COLUMNS, "status", "reason", "t_contact"]].itertuples(index=False):
        row: dict[str, Any] = {"participant": p, "trial": tr}
        if status == "invalid" or not np.isfinite(tc):
            rows.append({**row, "contact_speed": np.nan, "t_contact": np.nan, "reason": reason or "invalid"})
            continue
        trial = recordings.trial(p, tr)
        end = int(np.searchsorted(trial.t, tc - 1e-9))
        est = contact_speed_at(
            trial.t, trial.pos, end, fs=recordings.fs, method=method, degree=degree, n_fit=n_fit, rest_s=rest_s
        )
        rows.append({**row, "contact_speed": est.speed, "t_contact": est.t_contact, "reason": est.reason})
    return pd.DataFrame(rows, columns=[*ID_COLUMNS, "contact_speed", "t_contact", "reason"])


def estimate_errors(
    estimated: np.ndarray | pd.Series,
    true: np.ndarray | pd.Series,
    window: tuple[float, float] | None = CONTACT_WINDOW,
) -> pd.Series:
    """How far estimates lie from the true values, and how many would change a window's selection.

    Parameters
    ----------
    estimated : array-like, shape (N,)
        The estimates (m/s; any unit, the same as ``true``).
    true : array-like, shape (N,)
        The true values (m/s), trial by trial.
    window : tuple of float or None
        The inclusive selection window (m/s); None: no flips counted.

    Returns
    -------
    pandas.Series
        ``trials`` (dimensionless), ``bias`` (mean error), ``SD``, ``RMSE``, ``95th pct |error|``,
        ``max |error|`` (all m/s) and, with a window, ``flips``: the trials inside the window by one and
        outside it by the other (dimensionless).
    """
    e = np.asarray(estimated, dtype=float)
    v = np.asarray(true, dtype=float)
    if e.shape != v.shape:
        raise ValueError(f"estimated and true differ in shape: {e.shape} and {v.shape}")
    ok = np.isfinite(e) & np.isfinite(v)
    err = e[ok] - v[ok]
    out = {
        "trials": int(ok.sum()),
        "bias": float(err.mean()),
        "SD": float(err.std(ddof=1)) if err.size > 1 else np.nan,
        "RMSE": float(np.sqrt(np.mean(err**2))),
        "95th pct |error|": float(np.percentile(np.abs(err), 95)),
        "max |error|": float(np.abs(err).max()),
    }
    if window is not None:
        lo, hi = window
        out["flips"] = int((((e[ok] >= lo) & (e[ok] <= hi)) != ((v[ok] >= lo) & (v[ok] <= hi))).sum())
    return pd.Series(out)
