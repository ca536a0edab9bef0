"""The paper's chain in one call: recordings -> features -> selection -> K-means prototypes -> segments.

:func:`analyse` is what :func:`skilllib.pipeline.run` computes before the robot, without writing anything
and without the silhouette sweep: the chapters start from it instead of rebuilding the chain by hand.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from ..features import Lowpass, Segment, run_lowpass, segment, select, trial_features
from ..prototypes import DEFAULT_K, PrototypeResult, fit_prototypes
from ..recordings import Recordings, load_recordings
from ._run import DEFAULT_DATA


@dataclass
class Analysis:
    """The paper's procedure on one data set, up to the prototypes' segments.

    Attributes
    ----------
    recordings : Recordings
        The validated recordings.
    features : pandas.DataFrame
        One row per trial (every trial, with its ``status`` and ``reason``; features in m/s, s and
        dimensionless SPARC), as :func:`skilllib.features.trial_features` gives it.
    selected : pandas.DataFrame
        The selected rows of ``features`` (the paper's contact-speed window).
    fit : PrototypeResult
        K-means on the selected trials' (PV, SPARC) tuples; clusters ordered by centre PV (m/s).
    segments : list of Segment
        The prototype of cluster c at index c: onset to the last sample before contact (s, m, m/s).
    """

    recordings: Recordings
    features: pd.DataFrame
    selected: pd.DataFrame
    fit: PrototypeResult
    segments: list[Segment]

    @property
    def fs(self) -> float:
        """The recordings' sampling rate, Hz."""
        return float(self.recordings.fs)


def analyse(
    data: str | Path | pd.DataFrame | Recordings | None = None,
    *,
    k: int = DEFAULT_K,
    scaling: str = "raw",
    random_state: int = 0,
    sparc_params: Mapping[str, float] | None = None,
    lowpass: str | float | Lowpass | None = "auto",
) -> Analysis:
    """Read, segment, select and cluster: the paper's prototypes and their segments in one call.

    Parameters
    ----------
    data : str, pathlib.Path, pandas.DataFrame, Recordings or None
        The recordings (a path as :func:`skilllib.recordings.load_recordings` reads it, a long table, or
        :class:`Recordings`); None for the book's synthetic cohort.
    k : int
        Number of clusters (dimensionless; the paper's 6).
    scaling : str
        ``"raw"`` (the paper: PV in m/s and SPARC as they are) or ``"standard"``.
    random_state : int
        K-means' seed (dimensionless).
    sparc_params : mapping, optional
        SPARC's ``fc`` (Hz), ``amp_th`` (dimensionless) and ``padlevel`` (dimensionless); the book's by default.
    lowpass : str, float, Lowpass or None
        The positions' low-pass filter: ``"auto"``, ``"none"`` or a cut-off in Hz
        (:func:`skilllib.features.run_lowpass`).

    Returns
    -------
    Analysis
        The recordings, every trial's features, the selected trials, the K-means fit and the prototypes'
        segments (cut with the same filter as the features).

    Raises
    ------
    ValueError
        For data that cannot be read (:class:`skilllib.recordings.DataFormatError`) or fewer selected trials
        than ``k``.
    """
    recordings = load_recordings(DEFAULT_DATA if data is None else data)
    filt = run_lowpass(recordings, lowpass)
    features = trial_features(recordings, sparc_params=sparc_params, lowpass=filt)
    selected = select(features)
    fit = fit_prototypes(selected, k, scaling=scaling, random_state=random_state)
    segments = [segment(recordings, p.participant, p.trial, lowpass=filt) for p in fit.prototypes.itertuples()]
    return Analysis(recordings, features, selected, fit, segments)
