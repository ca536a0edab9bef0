"""The figures of the pipeline; the chapters draw the same ones.

Every function takes data (arrays, DataFrames, result objects) and returns a matplotlib Figure;
``save`` writes it as PNG and SVG. Axes carry units. This module may import the other skilllib
modules; none of them imports it.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib


import matplotlib.pyplot as plt  # noqa: E402

#: Colours of the clusters, in cluster order (ordered by centre PV).
CLUSTER_COLORS = plt.get_cmap("tab10").colors


def save(fig: plt.Figure, out_dir: str | Path, name: str, dpi: int = 150) -> list[Path]:
    """Write ``fig`` as ``out_dir/name.png`` and ``out_dir/name.svg``; return both paths."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / f"{name}.png", out / f"{name}.svg"]
    fig.savefig(paths[0], dpi=dpi, bbox_inches="tight")
    fig.savefig(paths[1], bbox_inches="tight", metadata={"Date": None})
    return paths


# --- smoothness (issue 3) --------------------------------------------------------------------
from collections.abc import Mapping, Sequence  # noqa: E402

import numpy as np  # noqa: E402

from .smoothness import SPARC_PARAMS, SparcSpectrum, sparc_spectrum  # noqa: E402


def plot_sparc_spectra(spectra: Mapping[str, SparcSpectrum], ax: plt.Axes | None = None,
                       fmax: float | None = None) -> plt.Figure:
    """Normalised Fourier magnitude spectra |V(f)|/V(0) against frequency (Hz): the band whose arc length
    SPARC measures drawn thick, the rest thin; the amplitude threshold (dashed), the maximum cut-off fc
    (dotted) and each adaptive cut-off (dot). Labels carry the SPARC values."""
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(5.5, 3.4))
    first = next(iter(spectra.values()))
    fmax = fmax if fmax is not None else 1.5 * max(first.fc, max(s.cutoff for s in spectra.values()))
    for i, (label, s) in enumerate(spectra.items()):
        color = CLUSTER_COLORS[i % len(CLUSTER_COLORS)]
        shown = s.f <= fmax
        ax.plot(s.f[shown], s.Mf[shown], color=color, lw=0.8, alpha=0.5)
        ax.plot(s.f_sel, s.Mf_sel, color=color, lw=2, label=f"{label}: SPARC {s.sparc:.3f}")
        ax.plot(s.cutoff, s.Mf_sel[-1], "o", color=color, ms=4)
    ax.axhline(first.amp_th, color="0.3", ls="--", lw=0.8)
    ax.text(fmax, first.amp_th, f"amp_th = {first.amp_th:g}", ha="right", va="bottom", fontsize="small")
    if first.fc <= fmax:
        ax.axvline(first.fc, color="0.3", ls=":", lw=1)
        ax.text(first.fc, 1.02, f"fc = {first.fc:g} Hz", ha="center", va="bottom", fontsize="small")
    ax.set_xlim(0, fmax)
    ax.set_ylim(0, 1.08)
    ax.set_xlabel("frequency f (Hz)")
    ax.set_ylabel(r"normalised magnitude $|V(f)|\,/\,V(0)$")
    ax.legend(fontsize="small", frameon=False, loc="upper right", bbox_to_anchor=(1, 0.93))
    return fig


def plot_speeds_and_spectra(speeds: Mapping[str, np.ndarray], fs: float, fmax: float | None = None,
                            **sparc_params: float) -> plt.Figure:
    """Speed profiles (m/s against s, sampled at ``fs`` Hz) beside their normalised spectra and SPARC
    bands (:func:`plot_sparc_spectra`); ``sparc_params`` default to ``SPARC_PARAMS``."""
    params = {**SPARC_PARAMS, **sparc_params}
    fig, (ax_v, ax_f) = plt.subplots(1, 2, figsize=(10, 3.4), layout="constrained")
    spectra = {}
    for i, (label, v) in enumerate(speeds.items()):
        v = np.asarray(v, dtype=float)
        ax_v.plot(np.arange(v.size) / fs, v, ".-", ms=2.5, lw=1, color=CLUSTER_COLORS[i % 10], label=label)
        spectra[label] = sparc_spectrum(v, fs, **params)
    ax_v.set_xlabel("time t (s)")
    ax_v.set_ylabel("speed v (m/s)")
    ax_v.set_ylim(bottom=0)
    plot_sparc_spectra(spectra, ax=ax_f, fmax=fmax)
    return fig


def plot_sparc_against(x: Sequence[float], curves: Mapping[str, Sequence[float]], xlabel: str,
                       ylabel: str = "SPARC", ax: plt.Axes | None = None) -> plt.Figure:
    """One or more smoothness values against a parameter of the movement (e.g. delay, noise level)."""
    fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(5.5, 3.4))
    for i, (label, y) in enumerate(curves.items()):
        ax.plot(x, y, "o-", ms=3, color=CLUSTER_COLORS[i % 10], label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if len(curves) > 1:
        ax.legend(fontsize="small", frameon=False)
    return fig


# --- the experiment and its data (issue 4) ---------------------------------------------------
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

from .data import Recordings  # noqa: E402
from .features import CONTACT_WINDOW, ONSET_SPEED, velocity  # noqa: E402

#: Colours of the participants (in sorted participant order): tab10 with its grey replaced by black,
#: because grey marks excluded trials.
PARTICIPANT_COLORS = tuple((0.0, 0.0, 0.0) if i == 7 else c for i, c in enumerate(plt.get_cmap("tab10").colors))


def _pcolor(participants: list, p) -> tuple[float, float, float]:
    return PARTICIPANT_COLORS[list(participants).index(p) % len(PARTICIPANT_COLORS)]


def _approach(rec: Recordings, p, tr) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """t (s), y (m) of the whole trial, speed (m/s) before contact (as the features), contact index."""
    d = rec.trial(p, tr)
    c = int(np.flatnonzero(d.contact)[0])
    return d.t, d.pos[:, 1], np.linalg.norm(velocity(d.pos[:c], rec.fs), axis=1), c


def plot_trials_by_participant(recordings: Recordings, features: pd.DataFrame,
                               window: tuple[float, float] = (-0.9, 0.3)) -> plt.Figure:
    """The paper's Fig. 1b redrawn: vertical position y (m) and speed (m/s, approach only) of every valid
    trial against time from contact (s), one column per participant (two rows of participants).
    Selected trials in the participant's colour, excluded ones in grey."""
    f = features[features["status"] != "invalid"]
    parts = sorted(f["participant"].unique())
    ncol = int(np.ceil(len(parts) / 2))
    fig, axs = plt.subplots(4, ncol, figsize=(2.1 * ncol, 7.2), sharex=True, sharey="row", squeeze=False)
    for i, p in enumerate(parts):
        ay, av = axs[2 * (i // ncol), i % ncol], axs[2 * (i // ncol) + 1, i % ncol]
        lines = {"y": {True: [], False: []}, "v": {True: [], False: []}}
        for tr, status in f.loc[f["participant"] == p, ["trial", "status"]].itertuples(index=False):
            t, y, v, c = _approach(recordings, p, tr)
            tt = t - t[c]
            keep = (tt >= window[0]) & (tt <= window[1])
            sel = status == "selected"
            lines["y"][sel].append(np.column_stack([tt[keep], y[keep]]))
            kv = keep[:c]
            lines["v"][sel].append(np.column_stack([tt[:c][kv], v[kv]]))
        for ax, key in ((ay, "y"), (av, "v")):
            ax.add_collection(LineCollection(lines[key][False], colors="0.75", lw=0.4))
            ax.add_collection(LineCollection(lines[key][True], colors=[_pcolor(parts, p)], lw=0.5, alpha=0.6))
            ax.autoscale_view()
            ax.axvline(0, color="k", lw=0.5, ls=":")
        ay.set_title(f"participant {p}", fontsize=9)
    for r in (1, 3):
        axs[r, 0].set_ylim(0, None)
    for r in range(4):
        axs[r, 0].set_ylabel("y (m)" if r % 2 == 0 else "speed (m/s)")
    for ax in axs[-1]:
        ax.set_xlabel("time from contact (s)")
    for i in range(len(parts), 2 * ncol):  # odd number of participants: hide the spare column
        axs[2 * (i // ncol), i % ncol].axis("off")
        axs[2 * (i // ncol) + 1, i % ncol].axis("off")
    fig.tight_layout()
    return fig


def plot_segmentation(recordings: Recordings, features: pd.DataFrame, keys: list[tuple]) -> plt.Figure:
    """Onset/contact segmentation of example trials: y (m) and approach speed (m/s) against time (s); the
    onset threshold, the onset sample, the first contact sample and the segment (shaded)."""
    fig, axs = plt.subplots(2, len(keys), figsize=(3.2 * len(keys), 4.6), sharex="col", squeeze=False)
    idx = features.set_index(["participant", "trial"])
    for j, (p, tr) in enumerate(keys):
        row = idx.loc[(p, tr)]
        t, y, v, c = _approach(recordings, p, tr)
        ay, av = axs[0, j], axs[1, j]
        ay.plot(t, y, ".-", ms=3, lw=0.8, color="0.3")
        av.plot(t[:c], v, ".-", ms=3, lw=0.8, color="0.3")
        av.axhline(ONSET_SPEED, color="tab:orange", lw=0.8, ls="--", label=f"onset threshold {ONSET_SPEED:g} m/s")
        if row["status"] != "invalid":
            o = int(round((row["t_onset"] - t[0]) * recordings.fs))
            for ax in (ay, av):
                ax.axvspan(t[o], t[c - 1], color="tab:blue", alpha=0.12, lw=0)
            av.plot(t[o], v[o], "o", color="tab:orange", ms=5, label="onset")
            av.plot(t[c - 1], v[c - 1], "s", color="tab:red", ms=5,
                    label=f"contact speed {row['contact_speed']:.2f} m/s")
        for ax in (ay, av):
            ax.axvline(t[c], color="tab:red", lw=0.8, ls=":")
        ay.set_title(f"P{p} T{tr}: {row['status']}", fontsize=9)
        av.set_xlabel("time (s)")
        av.legend(fontsize=6.5, frameon=False, loc="upper left")
    axs[0, 0].set_ylabel("y (m)")
    axs[1, 0].set_ylabel("speed (m/s)")
    fig.tight_layout()
    return fig


def plot_participant_features(features: pd.DataFrame) -> plt.Figure:
    """Per participant, peak speed (m/s), contact speed (m/s, the selection window shaded), duration (s)
    and SPARC of every valid trial (box: quartiles; points: trials, selected in colour)."""
    f = features[features["status"] != "invalid"]
    parts = sorted(f["participant"].unique())
    cols = [("pv", "peak speed PV (m/s)"), ("contact_speed", "contact speed (m/s)"),
            ("duration", "duration onset-contact (s)"), ("sparc", "SPARC")]
    fig, axs = plt.subplots(len(cols), 1, figsize=(7.5, 8), sharex=True)
    rng = np.random.default_rng(0)  # horizontal jitter of the points only
    for ax, (c, label) in zip(axs, cols):
        data = [f.loc[f["participant"] == p, c].to_numpy() for p in parts]
        ax.boxplot(data, positions=range(len(parts)), widths=0.5, showfliers=False,
                   medianprops={"color": "k"})
        for i, p in enumerate(parts):
            g = f[f["participant"] == p]
            x = i + rng.uniform(-0.18, 0.18, len(g))
            sel = (g["status"] == "selected").to_numpy()
            ax.scatter(x[~sel], g[c].to_numpy()[~sel], s=3, color="0.7", zorder=2)
            ax.scatter(x[sel], g[c].to_numpy()[sel], s=3, color=_pcolor(parts, p), zorder=3)
        ax.set_ylabel(label, fontsize=8)
        if c == "contact_speed":
            ax.axhspan(*CONTACT_WINDOW, color="tab:green", alpha=0.12, lw=0)
    axs[-1].set_xticks(range(len(parts)), [str(p) for p in parts])
    axs[-1].set_xlabel("participant")
    fig.tight_layout()
    return fig


def plot_contact_speeds(features: pd.DataFrame, bin_width: float = 0.05, ax: plt.Axes | None = None) -> plt.Figure:
    """Histogram of contact speeds (m/s) of the valid trials; the selection window shaded."""
    v = features.loc[features["status"] != "invalid", "contact_speed"].to_numpy()
    n_sel = int((features["status"] == "selected").sum())
    fig, ax = plt.subplots(figsize=(5.5, 3.2)) if ax is None else (ax.figure, ax)
    ax.hist(v, bins=np.arange(0, v.max() + bin_width, bin_width), color="0.55")
    ax.axvspan(*CONTACT_WINDOW, color="tab:green", alpha=0.15, lw=0,
               label=f"selected: {CONTACT_WINDOW[0]:g}-{CONTACT_WINDOW[1]:g} m/s ({n_sel} trials)")
    ax.set_xlabel("contact speed (m/s)")
    ax.set_ylabel("trials")
    ax.legend(frameon=False, fontsize=8)
    return fig


def plot_feature_space(features: pd.DataFrame, ax: plt.Axes | None = None) -> plt.Figure:
    """Peak speed PV (m/s) against SPARC: selected trials coloured by participant, excluded in grey."""
    f = features[features["status"] != "invalid"]
    parts = sorted(f["participant"].unique())
    fig, ax = plt.subplots(figsize=(6, 4)) if ax is None else (ax.figure, ax)
    ex = f[f["status"] == "excluded"]
    ax.scatter(ex["pv"], ex["sparc"], s=4, color="0.8", label="excluded")
    for p in parts:
        g = f[(f["participant"] == p) & (f["status"] == "selected")]
        ax.scatter(g["pv"], g["sparc"], s=6, color=_pcolor(parts, p), label=f"P{p}")
    ax.set_xlabel("peak speed PV (m/s)")
    ax.set_ylabel("SPARC")
    ax.legend(fontsize=6.5, frameon=False, ncol=2, loc="lower right", markerscale=2)
    return fig


def plot_feature_overview(features: pd.DataFrame) -> plt.Figure:
    """The pipeline's features figure: contact-speed histogram with the selection window (m/s) and
    PV (m/s) against SPARC of the valid trials."""
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 3.8))
    plot_contact_speeds(features, ax=a)
    plot_feature_space(features, ax=b)
    fig.tight_layout()
    return fig


def plot_estimates_vs_truth(features: pd.DataFrame, truth: pd.DataFrame) -> plt.Figure:
    """Features estimated from the 60 Hz samples against the generator's noise-free truth: peak speed,
    contact speed (m/s) and duration (s); the identity line dashed."""
    m = features[features["status"] != "invalid"].merge(truth, on=["participant", "trial"], suffixes=("", "_true"))
    m = m.assign(duration_true=m["t_contact_true"] - m["t_onset_true"])
    fig, axs = plt.subplots(1, 3, figsize=(10, 3.3))
    for ax, (c, label) in zip(axs, [("pv", "PV (m/s)"), ("contact_speed", "contact speed (m/s)"),
                                    ("duration", "duration (s)")]):
        ax.scatter(m[f"{c}_true"], m[c], s=3, color="0.35")
        lim = [0, max(m[c].max(), m[f"{c}_true"].max()) * 1.05]
        ax.plot(lim, lim, "--", color="tab:red", lw=0.8)
        ax.set(xlim=lim, ylim=lim, xlabel=f"true {label}", ylabel=f"estimated {label}")
    fig.tight_layout()
    return fig


# --- clusters and prototypes (issue 5) -------------------------------------------------------
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from .prototypes import PrototypeResult, SilhouetteSweep  # noqa: E402


def _cluster_color(c: int) -> tuple[float, float, float]:
    """Colour of cluster ``c``; CLUSTER_COLORS repeats beyond its length (k > 10)."""
    return CLUSTER_COLORS[int(c) % len(CLUSTER_COLORS)]


def plot_silhouette_sweep(sweep: SilhouetteSweep, chosen_k: int | None = None) -> plt.Figure:
    """Average silhouette (Rousseeuw 1987) against k; filled markers = valid k (average > 0 and every
    cluster has a trial above the average, as in scikit-learn's silhouette example), open = not valid."""
    ks, scores = sweep.ks, sweep.scores
    valid = np.array([sweep.results[k].valid for k in ks])
    fig, ax = plt.subplots(figsize=(5.5, 3.4))
    ax.plot(ks, scores, color="0.6", lw=1, zorder=1)
    ax.scatter(ks[valid], scores[valid], color="k", zorder=2, label="valid")
    ax.scatter(ks[~valid], scores[~valid], facecolor="white", edgecolor="k", zorder=2,
               label="not valid: a cluster lies wholly below the average")
    if chosen_k is not None and chosen_k in sweep.results:
        ax.axvline(chosen_k, color=CLUSTER_COLORS[3], ls="--", lw=1,
                   label=f"k = {chosen_k} (average {sweep.results[chosen_k].silhouette:.3f})")
    ax.set_xticks(ks)
    ax.set_xlabel("number of clusters k")
    ax.set_ylabel("average silhouette")
    ax.legend(fontsize="small", frameon=False)
    return fig


def plot_silhouettes(result: PrototypeResult) -> plt.Figure:
    """Silhouette plot ("knife plot", as in scikit-learn's example) of one clustering: each cluster's
    trial silhouettes sorted, the average as a dashed line; clusters marked * lie wholly below it."""
    s, labels, avg = result.silhouette_samples, result.labels, result.silhouette
    failing = set(result.failing_clusters())
    gap = max(2, len(s) // 60)
    fig, ax = plt.subplots(figsize=(5, 3 + 0.1 * result.k))
    y0 = gap
    for c in range(result.k):
        sc = np.sort(s[labels == c])
        ax.fill_betweenx(np.arange(y0, y0 + len(sc)), 0, sc, color=_cluster_color(c), lw=0)
        ax.text(-0.02, y0 + len(sc) / 2, f"{c}*" if c in failing else str(c), ha="right", va="center",
                fontsize="small" if result.k <= 10 else "x-small")
        y0 += len(sc) + gap
    ax.axvline(avg, color="k", ls="--", lw=1)
    ax.axvline(0, color="0.5", lw=0.5)
    ax.set_xlim(min(-0.1, float(s.min()) - 0.05), 1)
    ax.set_ylim(0, y0)
    ax.set_yticks([])
    ax.set_xlabel("silhouette coefficient")
    ax.set_ylabel("trials, by cluster (0 = lowest PV)")
    note = "; * no trial above it" if failing else ""
    ax.set_title(f"k = {result.k} ({result.method}, {result.scaling} features): "
                 f"average {avg:.3f} (dashed){note}", fontsize="small")
    return fig


def plot_clusters(result: PrototypeResult) -> plt.Figure:
    """PV-SPARC tuples coloured by cluster, with the centres (x) and the prototype trials (circled):
    the paper's Fig. 2a, clusters numbered by centre PV."""
    d = result.data
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for c in range(result.k):
        m = d["cluster"].to_numpy() == c
        ax.scatter(d.loc[m, "pv"], d.loc[m, "sparc"], s=10, alpha=0.6, color=_cluster_color(c), lw=0,
                   label=f"cluster {c} (n = {int(result.sizes[c])})")
    ax.scatter(result.centres["pv"], result.centres["sparc"], marker="X", s=90, color="k",
               edgecolor="white", lw=0.8, label="centre", zorder=3)
    ax.scatter(result.prototypes["pv"], result.prototypes["sparc"], marker="o", s=110, facecolor="none",
               edgecolor="k", lw=1.5, label="prototype (trial nearest the centre)", zorder=4)
    ax.set_xlabel("peak speed PV (m/s)")
    ax.set_ylabel("SPARC")
    ax.legend(fontsize="x-small", frameon=False, loc="center left", bbox_to_anchor=(1.01, 0.5))
    return fig


def plot_prototype_profiles(profiles: list[tuple[np.ndarray, np.ndarray]], prototypes: pd.DataFrame,
                            ) -> plt.Figure:
    """Speed profiles of the prototypes labelled with their PV and SPARC: the paper's Fig. 2b.

    ``profiles[i]`` is (t in s, speed in m/s) of the prototype of cluster i, in the row order of
    ``prototypes`` (``PrototypeResult.prototypes``: columns pv, sparc; index = cluster id).
    """
    if len(profiles) != len(prototypes):
        raise ValueError(f"{len(profiles)} speed profiles for {len(prototypes)} prototypes")
    fig, ax = plt.subplots(figsize=(5.5, 3.6))
    for (c, p), (t, v) in zip(prototypes.iterrows(), profiles):
        ax.plot(np.asarray(t), np.asarray(v), color=_cluster_color(c), lw=1.6,
                label=f"cluster {c}: PV = {p['pv']:.2f} m/s, SPARC = {p['sparc']:.2f}")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("speed (m/s)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize="x-small", frameon=False)
    return fig


# --- transfer to the robot (issue 6) ---------------------------------------------------------
import numpy as np  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

import roboticstoolbox as rtb  # noqa: E402

with plt.rc_context():  # roboticstoolbox's PyPlot backend sets the ggplot style globally on import;
    import roboticstoolbox.backends.PyPlot.PyPlot  # noqa: E402, F401  the context undoes that.

from .robots import DEFAULT_POSE_DEG, default_pose, joint_origins, simple6  # noqa: E402
from .transfer import EXP_TO_BASE, TransferResult  # noqa: E402

#: Colours of the joints q1..q7 in the transfer figures.
JOINT_COLORS = plt.get_cmap("Dark2").colors


def _auto_limits(points: np.ndarray, margin: float) -> list[float]:
    """Cubic 3-D limits [x0, x1, y0, y1, z0, z1] (m) around ``points`` plus ``margin`` m."""
    lo, hi = points.min(axis=0) - margin, points.max(axis=0) + margin
    half = float((hi - lo).max()) / 2
    mid = (lo + hi) / 2
    return [float(v) for m in mid for v in (m - half, m + half)]


def _metre_labels(ax: plt.Axes) -> None:
    """Axis labels in m (roboticstoolbox writes X, Y, Z on every ``plot``)."""
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")


def _draw_robot(ax: plt.Axes, robot: rtb.DHRobot, q: np.ndarray, limits: list[float], **plot_kwargs) -> None:
    """Draw ``robot`` at ``q`` on the 3-D axes ``ax`` with roboticstoolbox's PyPlot backend."""
    kw = dict(jointaxes=False, eeframe=True, shadow=False, name=False,
              options={"eelength": 0.15 * (limits[1] - limits[0]), "eex": {"linewidth": 2.5},
                       "eey": {"linewidth": 2.5}, "eez": {"linewidth": 2.5}})
    kw.update(plot_kwargs)
    robot.plot(np.asarray(q, dtype=float), backend="pyplot", block=False, ax=ax, limits=limits, **kw)
    _metre_labels(ax)
    base = robot.base.t
    ax.scatter(*base, marker="^", s=60, color="k", zorder=10)
    ax.set_box_aspect((1, 1, 1))
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(5))
    ax.tick_params(labelsize="small", pad=0)


def _label_joints(ax: plt.Axes, robot: rtb.DHRobot, q: np.ndarray, length: float) -> None:
    """Arrows along the joint axes of a standard-DH arm, labelled q1..qn beyond their tips."""
    pos, axes = joint_origins(robot, q)
    for j, (p, a) in enumerate(zip(pos, axes)):
        c = JOINT_COLORS[j % len(JOINT_COLORS)]
        ax.quiver(*p, *(a * length), color=c, lw=2, arrow_length_ratio=0.2)
        ax.text(*(p + a * length * 1.3), f"$q_{j + 1}$", color=c, fontsize=13, ha="center", va="center")


def plot_robot_joints(robot: rtb.DHRobot | None = None, q: np.ndarray | None = None, ax: plt.Axes | None = None,
                      view: tuple[float, float] = (22.0, -35.0)) -> plt.Figure:
    """An arm (default: Simple6 at the paper's default pose) with its joint axes labelled q1..qn:
    paper Fig. 3a.

    Joint j turns about the arrow labelled q_j (the z axis of DH frame j-1; Corke 2017, sec. 7.1);
    the arm is drawn by roboticstoolbox's PyPlot backend; ``view`` = (elevation, azimuth) deg.
    """
    robot = simple6() if robot is None else robot
    q = default_pose() if q is None else np.asarray(q, dtype=float)
    pos, _ = joint_origins(robot, q)
    reach = float(robot.reach)
    pts = np.vstack([pos, robot.fkine(q).t, np.zeros(3)])
    limits = _auto_limits(pts, 0.3 * reach)
    fig = plt.figure(figsize=(5.5, 5.5)) if ax is None else ax.figure
    ax = ax or fig.add_subplot(111, projection="3d", proj_type="ortho")
    _draw_robot(ax, robot, q, limits, eeframe=False)
    _label_joints(ax, robot, q, 0.2 * reach)
    ax.view_init(elev=view[0], azim=view[1])
    ax.set_title(f"{robot.name}: joint axes", fontsize="medium")
    return fig


def plot_robot_pose(robot: rtb.DHRobot | None = None, q: np.ndarray | None = None, ax: plt.Axes | None = None,
                    view: tuple[float, float] = (18.0, -70.0)) -> plt.Figure:
    """An arm in a pose (default: Simple6 at the paper's default pose ``DEFAULT_POSE_DEG``):
    paper Fig. 3b. The tool frame is drawn (x red, y green, z blue); the tool point (m) and the
    joint angles (deg) are written on the figure. Axes in m."""
    robot = simple6() if robot is None else robot
    q = default_pose() if q is None else np.asarray(q, dtype=float)
    pos, _ = joint_origins(robot, q)
    tool = robot.fkine(q).t
    reach = float(robot.reach)
    limits = _auto_limits(np.vstack([pos, tool, np.zeros(3)]), 0.3 * reach)
    fig = plt.figure(figsize=(5.5, 5.5)) if ax is None else ax.figure
    ax = ax or fig.add_subplot(111, projection="3d", proj_type="ortho")
    _draw_robot(ax, robot, q, limits)
    ax.scatter(*tool, color="k", s=20, zorder=10)
    ax.text(*(tool + np.array([0.0, 0.0, 0.12]) * reach), f"tool ({tool[0]:.2f}, {tool[1]:.2f}, {tool[2]:.2f}) m",
            fontsize="small", ha="center")
    ax.text2D(0.02, 0.97, "tool frame: x red, y green, z blue; base ▲", transform=ax.transAxes,
              fontsize="small", va="top")
    ax.view_init(elev=view[0], azim=view[1])
    deg = ", ".join(f"{v:g}" for v in np.round(np.rad2deg(q), 1))
    ax.set_title(f"{robot.name} at q = ({deg}) deg", fontsize="medium")
    return fig


def plot_simple6_figure() -> plt.Figure:
    """The paper's Fig. 3: (a) Simple6's joint labels, (b) its default pose, both at
    ``DEFAULT_POSE_DEG``; axes in m."""
    fig = plt.figure(figsize=(10, 5))
    robot, q = simple6(), default_pose()
    a = fig.add_subplot(121, projection="3d", proj_type="ortho")
    b = fig.add_subplot(122, projection="3d", proj_type="ortho")
    plot_robot_joints(robot, q, ax=a)
    plot_robot_pose(robot, q, ax=b)
    a.set_title("(a) joint labels", fontsize="medium")
    b.set_title("(b) default pose q = (" + ", ".join(f"{v:g}" for v in DEFAULT_POSE_DEG) + ") deg",
                fontsize="medium")
    return fig


def plot_joint_velocities(results: list[TransferResult], qd_limits: float | np.ndarray | None = None,
                          titles: list[str] | None = None, ncols: int = 3) -> plt.Figure:
    """Joint velocities qd_j(t) (rad/s) against time (s from movement start), one panel per
    transfer result (prototype/cluster): the paper's Fig. 4.

    Dashed lines: +-the joint velocity limits (``qd_limits`` rad/s, scalar or per joint; default
    each result's own). Samples with a flag are marked with a red x on the time axis. Panels share
    the y axis so the prototypes can be compared.
    """
    if not results:
        raise ValueError("plot_joint_velocities needs at least one TransferResult")
    n_panels = len(results)
    ncols = min(ncols, n_panels)
    nrows = -(-n_panels // ncols)
    width, height = max(3.6 * ncols, 7.5), 2.8 * nrows + 0.8
    fig, axs = plt.subplots(nrows, ncols, figsize=(width, height), sharex=True, sharey=True,
                            squeeze=False)
    for i, (ax, r) in enumerate(zip(axs.flat, results)):
        n = r.qd.shape[1]
        lim = r.qd_limits if qd_limits is None else np.broadcast_to(np.asarray(qd_limits, float), (n,))
        t = r.t - r.t[0]
        for j in range(n):
            ax.plot(t, r.qd[:, j], color=JOINT_COLORS[j % len(JOINT_COLORS)], lw=1.5, label=f"$q_{j + 1}$")
        for g, value in enumerate(np.unique(lim)):
            joints = np.nonzero(lim == value)[0] + 1
            who = "" if joints.size == n else " ($q_{" + ",".join(str(j) for j in joints) + "}$)"
            for sgn in (1, -1):
                ax.axhline(sgn * value, color=("k", "0.45", "0.7")[g % 3], ls=("--", "-.", ":")[g % 3], lw=0.9,
                           label=f"limit ±{value:.3g} rad/s{who}" if sgn > 0 else None)
        bad = sorted({f["sample"] for f in r.flags})
        if bad:
            ax.plot(t[bad], np.zeros(len(bad)), "x", color="r", ms=6, label="flagged sample")
        ax.axhline(0, color="0.7", lw=0.5)
        title = titles[i] if titles else (f"cluster {r.cluster}" if r.cluster is not None else f"trajectory {i}")
        peak = r.peak_abs_qd
        state = "within limits" if r.feasible else (
            f"time scale {r.time_scale:.2f}" if not r.flags else f"{len(r.flags)} flagged samples")
        peak_txt = f"{np.nanmax(peak):.2f}" if np.isfinite(peak).any() else "n/a"
        ax.set_title(f"{title}: max " + r"$|\dot{q}_j|$" + f" {peak_txt} rad/s, {state}", fontsize="small")
        ax.grid(alpha=0.3)
    for ax in axs.flat[n_panels:]:
        ax.set_visible(False)
    for ax in axs[-1]:
        ax.set_xlabel("time from start (s)")
    for ax in axs[:, 0]:
        ax.set_ylabel("joint velocity (rad/s)")
    handles, labels = axs.flat[0].get_legend_handles_labels()
    per_row = min(len(labels), int(width / 0.95))
    fig.legend(handles, labels, loc="upper center", ncol=per_row, frameon=False,
               bbox_to_anchor=(0.5, 1 - 0.3 / height), fontsize="small")
    law = r"$\dot{q} = J(q)^{-1} v$" if results[0].qd.shape[1] == 6 else r"$\dot{q} = J(q)^{+} v$"
    fig.suptitle(f"{results[0].robot}: joint velocities {law}", y=0.995, fontsize="medium")
    legend_rows = -(-len(labels) // per_row)
    fig.tight_layout(rect=(0, 0, 1, 1 - (0.3 + 0.2 * legend_rows) / height))
    return fig


def plot_frame_mapping(robot: rtb.DHRobot, result: TransferResult, rotation: np.ndarray = EXP_TO_BASE,
                       view: tuple[float, float] = (20.0, -55.0)) -> plt.Figure:
    """The experiment frame and the robot base frame, with the mapped path and the arm.

    The arm is drawn at its start pose ``result.q0`` and (grey) at the last solved sample; the
    target path ``result.x_base`` (m, base frame) in black. Arrows: the base frame at the origin
    (x, y, z) and, at the path's start, the experiment axes x_e (mediolateral), y_e (up) and z_e
    (anteroposterior) as seen in the base frame, i.e. the columns of ``rotation``
    (``p_base = rotation @ p_exp``).
    """
    R = np.asarray(rotation, dtype=float)
    reach = float(robot.reach)
    pos0, _ = joint_origins(robot, result.q0)
    pts = np.vstack([pos0, result.x_base, np.zeros(3)])
    limits = _auto_limits(pts, 0.25 * reach)
    fig = plt.figure(figsize=(6.5, 6))
    ax = fig.add_subplot(111, projection="3d", proj_type="ortho")
    _draw_robot(ax, robot, result.q0, limits, eeframe=False)
    ok = np.nonzero(np.all(np.isfinite(result.q), axis=1))[0]
    if ok.size and ok[-1] > 0:
        robot.plot(result.q[ok[-1]], backend="pyplot", block=False, ax=ax, limits=limits, jointaxes=False,
                   eeframe=False, shadow=False, name=False, color="0.6")
        _metre_labels(ax)
    x = result.x_base
    ax.plot(x[:, 0], x[:, 1], x[:, 2], color="k", lw=2.5, label="hand path (base frame)", zorder=20)
    ax.scatter(*x[-1], color="k", marker="v", s=40, zorder=21)
    L = 0.35 * reach
    for k, name in enumerate(("x", "y", "z")):
        e = np.eye(3)[k] * L
        ax.quiver(0, 0, 0, *e, color="0.3", lw=1.5, arrow_length_ratio=0.15)
        ax.text(*(e * 1.15), f"${name}_0$", color="0.3", fontsize=11, ha="center", va="center")
    exp_names = ("$x_e$ mediolateral", "$y_e$ up", "$z_e$ anteroposterior")
    for k in range(3):
        e = R[:, k] * L * 0.8
        c = JOINT_COLORS[k]
        ax.quiver(*x[0], *e, color=c, lw=2, arrow_length_ratio=0.15)
        ax.text(*(x[0] + e * 1.2), exp_names[k], color=c, fontsize=9, ha="center", va="center")
    ax.plot([], [], color="#E16F6D", lw=4, label="arm at the start pose q0")
    ax.plot([], [], color="0.6", lw=4, label="arm at the last sample")
    ax.view_init(elev=view[0], azim=view[1])
    ax.set_title(f"{result.robot}: experiment frame (coloured) in the base frame (grey)", fontsize="medium")
    ax.legend(loc="upper left", fontsize="small", frameon=False)
    return fig
