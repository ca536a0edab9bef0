"""Clusters or people? How the (PV, SPARC) clusters relate to the participants who made the trials.

The paper reads its clusters as "the different motor strategies with which the task was executed"
(Sect. 3). A strategy is something several people use, and one person may switch between; a cluster
that holds mostly one person's trials says more about that person's habitual speed than about a
strategy. This module measures which it is:

* :func:`cluster_participant_table`: trials per cluster and participant (a contingency table);
* :func:`participant_dependence`: normalised mutual information (NMI, scikit-learn's
  ``normalized_mutual_info_score``, arithmetic mean normalisation) between cluster and participant, with a
  permutation baseline: the participant labels shuffled across the same trials, which keeps every
  participant's and every cluster's size and destroys only their association;
* :func:`cluster_composition` and :func:`participant_spread`: how many people make up each cluster and
  how many clusters each person's trials fall in;
* :func:`between_participant_share`: the share of a feature's variance between participants' means
  (eta squared of a one-way layout), i.e. how much of PV or SPARC is a property of the person.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
from sklearn.metrics import normalized_mutual_info_score

from ..recordings import sort_ids

#: Permutations of the baseline in :func:`participant_dependence`.
N_PERMUTATIONS = 999


def _pair(labels: Any, participants: Any) -> tuple[np.ndarray, np.ndarray]:
    lab, par = np.asarray(labels).ravel(), np.asarray(participants).ravel()
    if lab.size != par.size:
        raise ValueError(f"{lab.size} cluster labels but {par.size} participant ids: one of each per trial")
    if lab.size == 0:
        raise ValueError("no trials")
    return lab, par


def cluster_participant_table(labels: Any, participants: Any) -> pd.DataFrame:
    """Trials per cluster (rows) and participant (columns), with row and column totals (``all``).

    Parameters
    ----------
    labels : array_like
        The cluster label of each trial (dimensionless).
    participants : array_like
        The participant id of each trial, aligned with ``labels`` (text).

    Returns
    -------
    pandas.DataFrame
        The counts of trials (dimensionless).
    """
    lab, par = _pair(labels, participants)
    t = pd.crosstab(
        pd.Series(lab, name="cluster"), pd.Series(par, name="participant"), margins=True, margins_name="all"
    )
    return t.reindex(columns=[*sort_ids(c for c in t.columns if c != "all"), "all"])


@dataclass(frozen=True)
class ParticipantDependence:
    """NMI between cluster and participant (0: independent, 1: each participant is one cluster) and its
    permutation baseline: the mean and 95th percentile of the NMI with participants shuffled, and the
    permutation p-value (1 + #{baseline >= observed}) / (1 + n_permutations)."""

    nmi: float
    baseline_mean: float
    baseline_q95: float
    p_value: float
    n_permutations: int

    @property
    def excess(self) -> float:
        """NMI above the chance level of the baseline mean."""
        return self.nmi - self.baseline_mean


def participant_dependence(
    labels: Any, participants: Any, *, n_permutations: int = N_PERMUTATIONS, seed: int = 0
) -> ParticipantDependence:
    """NMI between the clusters and the participants with a permutation baseline.

    The permutations use ``numpy.random.default_rng(seed)``; see :class:`ParticipantDependence`.

    Parameters
    ----------
    labels : array_like
        The cluster label of each trial (dimensionless).
    participants : array_like
        The participant id of each trial, aligned with ``labels`` (text).
    n_permutations : int
        The number of permutations of the baseline (dimensionless).
    seed : int
        The seed of the permutations (dimensionless).

    Returns
    -------
    ParticipantDependence
        The normalised mutual information and its permutation baseline (dimensionless).
    """
    lab, par = _pair(labels, participants)
    if n_permutations < 1:
        raise ValueError(f"n_permutations must be at least 1, got {n_permutations}")
    observed = normalized_mutual_info_score(par, lab)
    rng = np.random.default_rng(seed)
    base = np.array([normalized_mutual_info_score(rng.permutation(par), lab) for _ in range(n_permutations)])
    return ParticipantDependence(
        float(observed),
        float(base.mean()),
        float(np.quantile(base, 0.95)),
        float((1 + np.sum(base >= observed)) / (1 + n_permutations)),
        int(n_permutations),
    )


def cluster_composition(labels: Any, participants: Any) -> pd.DataFrame:
    """Per cluster: its trials, how many participants contribute, and the largest contributor.

    Columns ``trials``, ``participants`` (how many contribute), ``largest`` (the participant with most
    trials in it) and ``largest share`` (that participant's share of the cluster).

    Parameters
    ----------
    labels : array_like
        The cluster label of each trial (dimensionless).
    participants : array_like
        The participant id of each trial, aligned with ``labels`` (text).

    Returns
    -------
    pandas.DataFrame
        One row per cluster: counts (dimensionless), the participant (text) and the share (dimensionless).
    """
    t = cluster_participant_table(labels, participants).drop(index="all", columns="all")
    return pd.DataFrame(
        {
            "trials": t.sum(axis=1),
            "participants": (t > 0).sum(axis=1),
            "largest": t.idxmax(axis=1),
            "largest share": t.max(axis=1) / t.sum(axis=1),
        }
    )


def participant_spread(labels: Any, participants: Any) -> pd.DataFrame:
    """Per participant: how their trials spread over the clusters.

    Columns ``trials``, ``clusters`` (how many of their trials' clusters), ``main cluster``, ``main share``
    (share of their trials in it) and ``entropy`` (of their trials over the clusters, divided by log k:
    0 = all in one cluster, 1 = spread evenly over all k).

    Parameters
    ----------
    labels : array_like
        The cluster label of each trial (dimensionless).
    participants : array_like
        The participant id of each trial, aligned with ``labels`` (text).

    Returns
    -------
    pandas.DataFrame
        One row per participant (counts, shares and entropy dimensionless).
    """
    t = cluster_participant_table(labels, participants).drop(index="all", columns="all").T
    p = t.to_numpy(dtype=float) / t.sum(axis=1).to_numpy()[:, None]
    k = t.shape[1]
    with np.errstate(divide="ignore", invalid="ignore"):
        h = -np.nansum(np.where(p > 0, p * np.log(p), 0.0), axis=1) / np.log(k) if k > 1 else np.zeros(len(t))
    return pd.DataFrame(
        {
            "trials": t.sum(axis=1),
            "clusters": (t > 0).sum(axis=1),
            "main cluster": t.idxmax(axis=1),
            "main share": p.max(axis=1),
            "entropy": h,
        },
        index=t.index,
    )


def between_participant_share(data: pd.DataFrame, columns: Sequence[str] = ("pv", "sparc")) -> pd.Series:
    """Share of each column's variance that lies between the participants' means.

    Eta squared of a one-way layout: sum over trials of (participant mean - grand mean)**2 over the total
    sum of squares; 0 when participants do not differ on average, 1 when every participant's trials are
    identical.

    Parameters
    ----------
    data : pandas.DataFrame
        The trials, with ``participant`` and the columns (e.g. ``pv`` in m/s, ``sparc`` dimensionless).
    columns : sequence of str
        The columns (text).

    Returns
    -------
    pandas.Series
        The share of each column (dimensionless, 0 to 1).
    """
    if "participant" not in data.columns:
        raise ValueError("data needs a participant column")
    out = {}
    for c in columns:
        x = data[c].astype(float)
        total = float(((x - x.mean()) ** 2).sum())
        between = float(((x.groupby(data["participant"]).transform("mean") - x.mean()) ** 2).sum())
        out[c] = between / total if total > 0 else np.nan
    return pd.Series(out, name="between-participant share of variance")
