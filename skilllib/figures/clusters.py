"""Figures of the clustering chapter: silhouette sweep, silhouette plots, clusters, prototypes."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from ..features import FEATURE_UNITS, feature_label
from ..prototypes import PrototypeResult, SilhouetteSweep, SparcSensitivity
from ._common import CLUSTER_COLORS
from ._style import SINGLE, WIDE, book_figure

#: The paper's clustering features: the figures' wording for them is the book's (``"0 = lowest PV"``).
_PAPER = ("pv", "sparc")
#: Columns of ``PrototypeResult.prototypes`` that are not features.
_NOT_FEATURES = ("participant", "trial", "row")


def _cluster_color(c: int) -> tuple[float, float, float]:
    """Colour of cluster ``c``; CLUSTER_COLORS repeats beyond its length (k > 10)."""
    return CLUSTER_COLORS[int(c) % len(CLUSTER_COLORS)]


def _short(name: str) -> str:
    """A feature's short name for text: ``PV``, ``SPARC``, ``LDLJ``, ``duration`` (unknown: the column)."""
    return {"pv": "PV"}.get(name, FEATURE_UNITS.get(name, (name, ""))[0])


def _value_text(name: str, value: float) -> str:
    """``"PV = 0.52 m/s"``, ``"SPARC = -1.80"``: a feature's value with its unit."""
    unit = FEATURE_UNITS.get(name, (name, ""))[1]
    return f"{_short(name)} = {value:.2f}" + (f" {unit}" if unit else "")


@book_figure
def plot_silhouette_sweep(sweep: SilhouetteSweep, chosen_k: int | None = None) -> plt.Figure:
    """Average silhouette (Rousseeuw 1987) against k, valid k filled.

    Filled markers = valid k (average > 0 and every cluster has a trial above the average, as in
    scikit-learn's silhouette example), open = not valid. Subsample estimates (more trials than
    ``SILHOUETTE_EXACT_MAX``) get bars of +- 1 SD over the repeats.

    Parameters
    ----------
    sweep : SilhouetteSweep
        The sweep of :func:`skilllib.prototypes.silhouette_sweep`.
    chosen_k : int or None
        The k to mark (dimensionless); None: none.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; silhouette (dimensionless) against k.
    """
    ks, scores = sweep.ks, sweep.scores
    valid = np.array([sweep.results[k].valid for k in ks])
    fig, ax = plt.subplots(figsize=(SINGLE, 3.8), layout="constrained")
    ax.plot(ks, scores, color="0.6", lw=1, zorder=1)
    est = [sweep.results[k].silhouette_estimate for k in ks]
    if all(e is not None for e in est):
        ax.errorbar(
            ks,
            scores,
            yerr=[e.sd for e in est],
            fmt="none",
            ecolor="0.4",
            lw=1,
            capsize=2,
            zorder=1,
            label=f"estimate: ± 1 SD over {est[0].repeats} subsamples of {est[0].sample_size} trials",
        )
    ax.scatter(ks[valid], scores[valid], color="k", zorder=2, label="valid")
    ax.scatter(
        ks[~valid],
        scores[~valid],
        facecolor="white",
        edgecolor="k",
        zorder=2,
        label="not valid: a cluster lies wholly below the average",
    )
    if chosen_k is not None and chosen_k in sweep.results:
        ax.axvline(
            chosen_k,
            color=CLUSTER_COLORS[3],
            ls="--",
            lw=1,
            label=f"k = {chosen_k} (average {sweep.results[chosen_k].silhouette:.3f})",
        )
    ax.set_xticks(ks)
    ax.set_xlabel("number of clusters k")
    ax.set_ylabel("average silhouette")
    ax.legend(fontsize="small", frameon=False)
    return fig


@book_figure
def plot_silhouettes(result: PrototypeResult) -> plt.Figure:
    """Silhouette plot ("knife plot", as in scikit-learn's example) of one clustering.

    Each cluster's trial silhouettes sorted, the average as a dashed line; clusters marked * lie wholly
    below it. For a subsample estimate (``result.silhouette_method == "subsample"``) the pooled subsamples'
    trials.

    Parameters
    ----------
    result : PrototypeResult
        The clustering of :func:`skilllib.prototypes.fit_prototypes`.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; silhouettes (dimensionless) by cluster.
    """
    s, labels, avg = result.silhouette_samples, result.silhouette_labels, result.silhouette
    est = result.silhouette_estimate
    failing = set(result.failing_clusters())
    gap = max(2, len(s) // 60)
    fig, ax = plt.subplots(figsize=(SINGLE, 3 + 0.12 * result.k), layout="constrained")
    y0 = gap
    for c in range(result.k):
        sc = np.sort(s[labels == c])
        ax.fill_betweenx(np.arange(y0, y0 + len(sc)), 0, sc, color=_cluster_color(c), lw=0)
        ax.text(
            -0.02,
            y0 + len(sc) / 2,
            f"{c}*" if c in failing else str(c),
            ha="right",
            va="center",
            fontsize="small",
        )
        y0 += len(sc) + gap
    ax.axvline(avg, color="k", ls="--", lw=1)
    ax.axvline(0, color="0.5", lw=0.5)
    ax.set_xlim(min(-0.1, float(s.min()) - 0.05), 1)
    ax.set_ylim(0, y0)
    ax.set_yticks([])
    ax.set_xlabel("silhouette coefficient")
    features = tuple(result.features)
    ax.set_ylabel(
        f"trials, by cluster (0 = lowest {_short(features[0])})"
        if est is None
        else f"sampled trials ({est.repeats} x {est.sample_size} of {est.n_points}), by cluster"
    )
    note = "; * no trial above it" if failing else ""
    how = "dashed" if est is None else f"dashed; estimate, SD {est.sd:.3f}"
    space = f"{result.scaling} features" if features == _PAPER else f"{result.scaling} {', '.join(features)}"
    ax.set_title(
        f"k = {result.k} ({result.method}, {space}): average {avg:.3f} ({how}){note}",
        fontsize="small",
    )
    return fig


@book_figure
def plot_clusters(result: PrototypeResult) -> plt.Figure:
    """PV-SPARC tuples coloured by cluster, with the centres (x) and the prototype trials (circled).

    The paper's Fig. 2a, clusters numbered by centre PV. The axes are the result's first two features
    (``result.features``; the paper's PV and SPARC), labelled with
    :func:`skilllib.features.feature_label`. With more than two features the plane shows a projection:
    the title says which two of how many are shown, and the prototypes -- the trials nearest their
    centre in all features (in the clustering space) -- need not look nearest in it.

    Parameters
    ----------
    result : PrototypeResult
        The clustering of :func:`skilllib.prototypes.fit_prototypes`.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; the second feature against the first, each in its unit (the paper: SPARC,
        dimensionless, against PV in m/s).
    """
    d = result.data
    features = tuple(result.features)
    fx, fy = features[:2]
    fig, ax = plt.subplots(figsize=(7.6, 4.4), layout="constrained")
    for c in range(result.k):
        m = d["cluster"].to_numpy() == c
        ax.scatter(
            d.loc[m, fx],
            d.loc[m, fy],
            s=10,
            alpha=0.6,
            color=_cluster_color(c),
            lw=0,
            label=f"cluster {c} (n = {int(result.sizes[c])})",
        )
    ax.scatter(
        result.centres[fx],
        result.centres[fy],
        marker="X",
        s=90,
        color="k",
        edgecolor="white",
        lw=0.8,
        label="centre",
        zorder=3,
    )
    ax.scatter(
        result.prototypes[fx],
        result.prototypes[fy],
        marker="o",
        s=110,
        facecolor="none",
        edgecolor="k",
        lw=1.5,
        label="prototype (trial nearest the centre)",
        zorder=4,
    )
    ax.set_xlabel(feature_label(fx))
    ax.set_ylabel(feature_label(fy))
    if len(features) > 2:
        rest = ", ".join(_short(f) for f in features[2:])
        ax.set_title(
            f"{_short(fx)} and {_short(fy)}: 2 of {len(features)} clustering features shown (not shown: {rest});\n"
            f"clusters, centres and prototypes in all {len(features)} ({result.scaling} scaling)",
            fontsize="small",
        )
    ax.legend(fontsize="small", frameon=False, loc="center left", bbox_to_anchor=(1.01, 0.5))
    return fig


@book_figure
def plot_prototype_profiles(
    profiles: list[tuple[np.ndarray, np.ndarray]],
    prototypes: pd.DataFrame,
) -> plt.Figure:
    """Speed profiles of the prototypes labelled with their PV and SPARC: the paper's Fig. 2b.

    The labels give every clustering feature the prototypes hold (the columns of ``prototypes`` other
    than participant, trial and row), in their order.

    Parameters
    ----------
    profiles : list of tuple of numpy.ndarray
        ``profiles[i]`` is (t in s, speed in m/s) of the prototype of cluster i, in the row order of
        ``prototypes``.
    prototypes : pandas.DataFrame
        ``PrototypeResult.prototypes``: the features, e.g. pv (m/s), sparc (dimensionless); index =
        cluster id.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; speed (m/s) against time (s).
    """
    if len(profiles) != len(prototypes):
        raise ValueError(f"{len(profiles)} speed profiles for {len(prototypes)} prototypes")
    features = [col for col in prototypes.columns if col not in _NOT_FEATURES]
    fig, ax = plt.subplots(figsize=(8.0, 3.8), layout="constrained")
    for (c, p), (t, v) in zip(prototypes.iterrows(), profiles):
        ax.plot(
            np.asarray(t),
            np.asarray(v),
            color=_cluster_color(c),
            lw=1.6,
            label=f"cluster {c}: " + ", ".join(_value_text(f, p[f]) for f in features),
        )
    ax.set_xlabel("time (s)")
    ax.set_ylabel("speed (m/s)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize="small", frameon=False, loc="center left", bbox_to_anchor=(1.01, 0.5))
    return fig


@book_figure
def plot_stability(ari: dict[str, np.ndarray], seed: int = 0) -> plt.Figure:
    """Adjusted Rand indices as one jittered strip per entry of ``ari``, each with its median.

    ARI is dimensionless, 1 = same partition; entries are e.g. refits with other seeds or on bootstrap
    resamples, see :func:`skilllib.prototypes.seed_stability` and
    :func:`~skilllib.prototypes.bootstrap_stability`; the median is a black bar. ``", "`` in a name becomes
    a line break.

    Parameters
    ----------
    ari : dict of str to numpy.ndarray
        Name (text) -> adjusted Rand indices (dimensionless).
    seed : int
        The seed of the jitter (dimensionless).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; ARI (dimensionless) per entry.
    """
    if not ari:
        raise ValueError("no ARI series to plot")
    fig, ax = plt.subplots(figsize=(7, 3.4), layout="constrained")
    jitter = np.random.default_rng(seed)
    for i, a in enumerate(np.asarray(v, dtype=float) for v in ari.values()):
        ax.scatter(i + jitter.uniform(-0.15, 0.15, a.size), a, s=14, alpha=0.7, color="C0")
        ax.hlines(np.median(a), i - 0.3, i + 0.3, color="k", lw=1.5)
    ax.set_xticks(range(len(ari)), [n.replace(", ", "\n") for n in ari], fontsize="small")
    ax.set_ylabel("adjusted Rand index")
    ax.set_ylim(top=1.02)
    return fig


@book_figure
def plot_sparc_sensitivity(sens: SparcSensitivity) -> plt.Figure:
    """SPARC and silhouettes under every SPARC setting against the reference setting.

    Left: each selected trial's SPARC under every other setting against the reference setting (identity
    dashed; trials whose band that setting's fc ended drawn as rings). Right: average silhouette against k
    under every setting.

    Parameters
    ----------
    sens : SparcSensitivity
        The result of :func:`skilllib.prototypes.sparc_sensitivity`.

    Returns
    -------
    matplotlib.figure.Figure
        The figure; SPARC and silhouettes (dimensionless).
    """
    fig, (a, b) = plt.subplots(1, 2, figsize=(WIDE, 4.0), layout="constrained")
    ref = sens.reference.selected["sparc"].to_numpy()
    for i, run in enumerate(sens.runs[1:], start=1):
        y = run.selected["sparc"].to_numpy()
        cap = run.selected["sparc_capped"].to_numpy(dtype=bool)
        a.scatter(ref[~cap], y[~cap], s=6, color=_cluster_color(i), label=f"{run.label}: band ended by amp_th")
        a.scatter(
            ref[cap],
            y[cap],
            s=12,
            facecolor="none",
            edgecolor=_cluster_color(i),
            lw=0.7,
            label=f"{run.label}: band ended by fc ({int(cap.sum())})",
        )
    lo = min(ref.min(), *(r.selected["sparc"].min() for r in sens.runs))
    hi = max(ref.max(), *(r.selected["sparc"].max() for r in sens.runs))
    a.plot([lo, hi], [lo, hi], "--", color="0.4", lw=0.8)
    a.set_xlabel(f"SPARC, {sens.reference.label}")
    a.set_ylabel("SPARC, other setting")
    a.legend(fontsize="small", frameon=False, loc="lower right")
    for i, run in enumerate(sens.runs):
        if run.sweep is not None:
            b.plot(run.sweep.ks, run.sweep.scores, "o-", ms=3, color=_cluster_color(i), label=run.label)
    b.axvline(sens.k, color="0.5", ls=":", lw=1)
    b.set_xlabel("number of clusters k")
    b.set_ylabel("average silhouette")
    b.legend(fontsize="small", frameon=False)
    return fig


@book_figure
def plot_cluster_participants(table: pd.DataFrame) -> plt.Figure:
    """Trials per cluster and participant as a heat map with the counts written in.

    Rows are clusters (0 = lowest centre PV), columns participants.

    Parameters
    ----------
    table : pandas.DataFrame
        As :func:`skilllib.prototypes.cluster_participant_table` (counts, dimensionless; its ``all``
        totals are left out).

    Returns
    -------
    matplotlib.figure.Figure
        The figure; the heat map of counts (dimensionless).
    """
    t = table.drop(index="all", columns="all", errors="ignore")
    fig, ax = plt.subplots(figsize=(min(WIDE, 1.6 + 0.46 * t.shape[1]), 0.9 + 0.45 * t.shape[0]), layout="constrained")
    im = ax.imshow(t.to_numpy(), cmap="Greys", aspect="auto")
    vmax = t.to_numpy().max()
    for (i, j), n in np.ndenumerate(t.to_numpy()):
        ax.text(j, i, str(n), ha="center", va="center", fontsize=8, color="white" if n > 0.6 * vmax else "black")
    ax.set_xticks(range(t.shape[1]), [str(c) for c in t.columns])
    ax.set_yticks(range(t.shape[0]), [str(r) for r in t.index])
    ax.set_xlabel("participant")
    ax.set_ylabel("cluster (0 = lowest centre PV)")
    fig.colorbar(im, ax=ax, label="trials", shrink=0.8)
    return fig
