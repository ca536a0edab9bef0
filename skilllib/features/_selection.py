"""Which trials are clustered: windows on the per-trial features, and the features clustering reads.

The paper selects the trials whose contact speed lies in 0.3-0.7 m/s (:data:`PAPER_SELECTION`) and
clusters them on (PV, SPARC) (:data:`PAPER_FEATURES`). Both are the user's: a selection is a tuple of
:class:`Window` (every window must hold; an empty tuple selects every valid trial), written
``contact_speed=0.3:0.7`` (``FEATURE=LO:HI``, either end may be left open: ``pv=0.5:``); the clustering
features are any of :data:`FEATURE_UNITS`.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
import pandas as pd

#: The per-trial features one may select on or cluster with: column -> (label, unit).
FEATURE_UNITS: dict[str, tuple[str, str]] = {
    "pv": ("peak speed PV", "m/s"),
    "sparc": ("SPARC", ""),
    "ldlj": ("LDLJ", ""),
    "duration": ("duration", "s"),
    "contact_speed": ("end speed", "m/s"),
    "peak_acc": ("peak acceleration", "m/s^2"),
    "path_length": ("path length", "m"),
    "sparc_band_end_hz": ("SPARC band end", "Hz"),
}
#: Other names accepted for a feature (``end_speed``: the speed at the segment's end, whatever ends it).
FEATURE_ALIASES = {"end_speed": "contact_speed", "peak_speed": "pv", "peak_acceleration": "peak_acc"}

PAPER_FEATURES = ("pv", "sparc")


class SelectionError(ValueError):
    """A selection window or a feature list that cannot be read; the message lists what is allowed."""


def feature_name(name: str) -> str:
    """The feature column a name means (aliases resolved); :class:`SelectionError` for an unknown one.

    Parameters
    ----------
    name : str
        A column of :data:`FEATURE_UNITS` or an alias of :data:`FEATURE_ALIASES` (text).

    Returns
    -------
    str
        The column (text).
    """
    key = str(name).strip().lower().replace("-", "_")
    key = FEATURE_ALIASES.get(key, key)
    if key not in FEATURE_UNITS:
        known = ", ".join([*FEATURE_UNITS, *FEATURE_ALIASES])
        raise SelectionError(f"unknown feature {name!r}: use one of {known}")
    return key


def feature_label(name: str) -> str:
    """An axis label for a feature column: ``"peak speed PV (m/s)"``, ``"SPARC"``.

    Parameters
    ----------
    name : str
        A column of :data:`FEATURE_UNITS` (text; another name is used as it is).

    Returns
    -------
    str
        The label, with the unit in brackets when it has one (text).
    """
    label, unit = FEATURE_UNITS.get(name, (name, ""))
    return f"{label} ({unit})" if unit else label


@dataclass(frozen=True)
class Window:
    """Trials whose ``feature`` lies in ``lo <= value <= hi`` (units of the feature; None: open).

    Attributes
    ----------
    feature : str
        A column of :data:`FEATURE_UNITS` (text).
    lo, hi : float or None
        The inclusive bounds (the feature's unit: m/s, s, m, ...), None for an open end.
    """

    feature: str
    lo: float | None
    hi: float | None

    def text(self) -> str:
        """``contact_speed=0.3:0.7`` (as written on the command line)."""
        lo = "" if self.lo is None else f"{self.lo:g}"
        hi = "" if self.hi is None else f"{self.hi:g}"
        return f"{self.feature}={lo}:{hi}"

    def reason(self, value: float) -> str:
        """Why a trial with ``value`` is outside (empty when inside)."""
        label, unit = FEATURE_UNITS[self.feature]
        if self.feature == "contact_speed":
            label = "contact speed"  # the paper's reason text, unchanged
        u = f" {unit}" if unit else ""
        if np.isnan(value):
            return f"{label} not computed for this trial: outside the window {self.text()}"
        if self.lo is not None and value < self.lo:
            return f"{label} {value:.3f}{u} below {self.lo:g}{u}"
        if self.hi is not None and value > self.hi:
            return f"{label} {value:.3f}{u} above {self.hi:g}{u}"
        return ""


#: The paper's selection: contact speed 0.3-0.7 m/s, inclusive.
PAPER_SELECTION = (Window("contact_speed", 0.3, 0.7),)


def parse_window(text: str) -> Window:
    """A window from ``FEATURE=LO:HI`` (either bound may be empty); :class:`SelectionError` otherwise.

    Parameters
    ----------
    text : str
        E.g. ``contact_speed=0.3:0.7`` (the feature's unit: m/s), ``duration=:1.5`` (s).

    Returns
    -------
    Window
        The window.
    """
    name, sep, bounds = str(text).partition("=")
    lo_text, colon, hi_text = bounds.partition(":")
    if not sep or not colon:
        raise SelectionError(f"{text!r}: write a window as FEATURE=LO:HI (e.g. contact_speed=0.3:0.7), or 'none'")
    feature = feature_name(name)

    def bound(v: str) -> float | None:
        v = v.strip()
        if not v:
            return None
        if not re.fullmatch(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?", v) or not math.isfinite(float(v)):
            raise SelectionError(f"{text!r}: {v!r} is not a number")
        return float(v)

    lo, hi = bound(lo_text), bound(hi_text)
    if lo is None and hi is None:
        raise SelectionError(f"{text!r}: give at least one bound (LO:, :HI or LO:HI)")
    if lo is not None and hi is not None and lo > hi:
        raise SelectionError(f"{text!r}: the lower bound {lo:g} is above the upper bound {hi:g}")
    return Window(feature, lo, hi)


def parse_selection(texts: str | Iterable[str]) -> tuple[Window, ...]:
    """Windows from texts (``none`` alone: no window, every valid trial is selected).

    Parameters
    ----------
    texts : str or iterable of str
        ``none``, or one or more ``FEATURE=LO:HI``.

    Returns
    -------
    tuple of Window
        The windows (empty for ``none``).
    """
    items = [texts] if isinstance(texts, str) else list(texts)
    if any(str(t).strip().lower() == "none" for t in items):
        if len(items) > 1:
            raise SelectionError("'none' selects every valid trial: it cannot be combined with windows")
        return ()
    return tuple(parse_window(t) for t in items)


def parse_features(text: str | Sequence[str]) -> tuple[str, ...]:
    """The clustering features from ``pv,sparc`` (or a list); at least two, no repeats.

    Parameters
    ----------
    text : str or sequence of str
        Feature names of :data:`FEATURE_UNITS` (or aliases), comma-separated.

    Returns
    -------
    tuple of str
        The feature columns.
    """
    items = [s for s in (text.split(",") if isinstance(text, str) else text) if str(s).strip()]
    names = tuple(feature_name(s) for s in items)
    if len(names) < 2:
        raise SelectionError(f"cluster on at least two features (e.g. pv,sparc), got {','.join(names) or 'none'}")
    if len(set(names)) < len(names):
        raise SelectionError(f"a feature is named twice in {','.join(names)}")
    return names


def apply_selection(features: pd.DataFrame, windows: Sequence[Window]) -> pd.DataFrame:
    """The feature table with ``status`` and ``reason`` of its valid trials set by ``windows``.

    A valid trial (``selected`` or ``excluded``) is ``selected`` when every window holds, else
    ``excluded`` with the first failing window's reason; ``invalid`` trials are left as they are.

    Parameters
    ----------
    features : pandas.DataFrame
        The feature table of :func:`skilllib.features.trial_features` (speeds m/s, durations s, ...).
    windows : sequence of Window
        The windows (empty: every valid trial selected).

    Returns
    -------
    pandas.DataFrame
        A copy with ``status`` and ``reason`` updated (attrs kept).
    """
    out = features.copy()
    valid = (out["status"] != "invalid").to_numpy()
    reason = np.where(valid, "", out["reason"].to_numpy(dtype=object)).astype(object)
    for w in reversed(list(windows)):  # the first failing window's reason is the one kept
        values = out[w.feature].to_numpy(dtype=float)
        low = values < w.lo if w.lo is not None else np.zeros(len(values), bool)
        high = values > w.hi if w.hi is not None else np.zeros(len(values), bool)
        for i in np.flatnonzero(valid & (low | high | np.isnan(values))):  # reasons for the failing only
            reason[i] = w.reason(values[i])
    out["reason"] = reason
    out["status"] = np.where(valid, np.where(reason == "", "selected", "excluded"), "invalid").astype(object)
    out.attrs = dict(features.attrs)
    return out
