"""Every figure of the book fits the page and keeps its text legible (skilllib/figures/_style.py).

The site shows a figure at 1:1 up to 9.2 in (920 CSS px; retina PNGs at 2 x 100 dpi) and scales wider ones
down, their text with them. So every public figure function, called on small inputs (a generated cohort
run through the pipeline with six clusters, and the inputs of the other figure tests), must return figures

- at most :data:`FULL_WIDTH` wide, both as drawn and as saved (the tight crop plus its 0.1 in padding: a
  legend or label outside the axes widens the PNG beyond the figure), and
- whose every visible text (titles, labels, tick labels, legends, annotations) is at least :data:`MIN_FONT`,

whatever the caller's matplotlib settings: each is drawn, and checked, under settings with a 5-pt font
(a figure function that relied on the caller's settings would come out at 5 pt). A static scan keeps
sizes below 8 pt out of the figure code and the chapters.
"""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402
from matplotlib.text import Text  # noqa: E402
from test_limits import _descent  # noqa: E402
from test_measurement import _tables  # noqa: E402

import skilllib as sk  # noqa: E402
import skilllib.figures as skf  # noqa: E402
from skilllib.cohort import CohortModel, generate_cohort  # noqa: E402
from skilllib.figures._style import BOOK_RC, FULL_WIDTH, MIN_FONT, WIDE, grid  # noqa: E402
from skilllib.pipeline import _run as pipeline  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
FS = 60.0
#: The caller's settings every figure is drawn and checked under: a figure function that did not set its own
#: sizes would come out at these.
HOSTILE = {"font.size": 5.0, "xtick.labelsize": 4.0, "ytick.labelsize": 4.0, "legend.fontsize": 4.0}


@pytest.fixture(scope="module")
def run():
    frame = generate_cohort(3, CohortModel(n_participants=4, n_trials=15, fs=FS)).frame
    run_ = pipeline.run(frame, None, k=6, robot="simple6")
    assert run_.prototypes is not None and len(run_.assessments) == 6
    return run_


def _speeds():
    return {
        "one submovement": sk.minimum_jerk_submovements([0.0], FS, T=0.6, D=0.1),
        "two, 0.5 s apart": sk.minimum_jerk_submovements([0.0, 0.5], FS, T=0.6, D=0.1),
    }


def _dynamics(run_):
    return [a.dynamics for a in run_.assessments]


def _by_arm():
    out = {}
    for name in ("simple6", "ur5", "panda", "puma560"):
        arm = sk.get_robot(name)
        out[arm.robot.name] = [
            sk.joint_dynamics(arm.robot, sk.transfer(arm, *_descent(pv)), arm.qdd_limits, arm.tau_limits)
            for pv in (0.3, 0.6, 1.0)
        ]
    return out


def _draws():
    rng = np.random.default_rng(0)
    cols = ["silhouette_k6", "n_valid_k", "r2_contact_ratio", "ari_fc10", "capped_fraction", "centre_sparc_1"]
    return pd.DataFrame(rng.normal(0.5, 0.1, (24, len(cols))), columns=cols, index=pd.Index(range(24), name="seed"))


def _scaling_rows():
    return [
        {
            "trials": n,
            "input": kind,
            "mode": mode,
            "failed": 0,
            "wall_s": n / 1e4,
            "peak_main_mb": 100 + n / 1e3,
            "peak_worker_mb": 50.0 if mode == "dask" else None,
        }
        for n in (1_500, 15_000, 150_000)
        for kind in ("csv", "parquet")
        for mode in ("memory", "dask")
    ]


def _measures():
    rng = np.random.default_rng(0)
    pv = rng.uniform(0.3, 1.6, 120)
    corrected = rng.random(120) < pv / 1.6
    frame = sk.feature_frame(pv, -1.6 + rng.normal(0, 0.1, 120), ldlj=np.where(corrected, -6.0, -3.0))
    fits = {
        "(PV, SPARC)": sk.fit_prototypes(frame, 3),
        "(PV, LDLJ)": sk.fit_prototypes(frame, 3, features=("pv", "ldlj")),
        "(PV, SPARC, LDLJ)": sk.fit_prototypes(frame, 3, features=("pv", "sparc", "ldlj")),
    }
    return fits, corrected


def _phase_spread():
    return sk.phase_spread(_tables())


def _estimator_table():
    rng = np.random.default_rng(1)
    exact = rng.uniform(0.0, 0.05, 80)
    sparc = -1.7 + exact
    return pd.DataFrame(
        {"sparc": sparc, "sparc_gradient": sparc + rng.normal(0, 0.01, 80), "sparc_gradient_trial": sparc - 0.02}
    )


def _sensitivity(run_):
    return sk.sparc_sensitivity(run_.recordings, k=6, k_range=(2, 8))


def _plane():
    data = pd.DataFrame({"pv": [0.5, 0.7, 0.9], "sparc": [-1.6, -1.7, -1.8], "cluster": [0, 1, 2]})
    centres = data.set_index("cluster")[["pv", "sparc"]]
    moved = pd.DataFrame(
        {"pv_a": [0.55], "sparc_a": [-1.8], "pv_b": [0.54], "sparc_b": [-1.81]}, index=pd.Index([2], name="cluster")
    )
    return data, centres, moved


def _stretch():
    s = np.linspace(1, 2, 5)
    tables = [pd.DataFrame({c: v * (s - 1) for c in range(6)}, index=s) for v in (0.0, -0.1, -0.05)]
    return tables


#: name -> draw(run) for every public figure function; several for those whose size depends on the input.
CALLS = {
    "plot_sparc_spectra": lambda r: skf.plot_sparc_spectra({k: sk.sparc_spectrum(v, FS) for k, v in _speeds().items()}),
    "plot_speeds_and_spectra": lambda r: skf.plot_speeds_and_spectra(_speeds(), FS),
    "plot_speed_profiles": lambda r: skf.plot_speed_profiles(_speeds(), FS),
    "plot_spectra_side_by_side": lambda r: skf.plot_spectra_side_by_side(
        {f"fc = {fc:g} Hz": sk.sparc_spectrum(_speeds()["one submovement"], FS, fc=fc) for fc in (10.0, 20.0)}, fmax=30
    ),
    "plot_sparc_against": lambda r: skf.plot_sparc_against([0.1, 0.2, 0.3], {"a": [-1.5, -1.6, -1.8]}, "delay (s)"),
    "plot_padded_spectra": lambda r: skf.plot_padded_spectra(_speeds()["two, 0.5 s apart"], FS, padlevels=(0, 4)),
    "plot_short_segments": lambda r: skf.plot_short_segments(
        np.arange(6, 20),
        {
            (rr, fc): sk.sparc_bands([sk.minimum_jerk_segment(int(n), rr, FS) for n in range(6, 20)], FS, fc=fc)
            for rr in (0.3, 0.7)
            for fc in (20.0, 10.0)
        },
    ),
    "plot_trials_by_participant": lambda r: skf.plot_trials_by_participant(r.recordings, r.features),
    "plot_segmentation": lambda r: skf.plot_segmentation(
        r.recordings, r.features, skf.segmentation_examples(r.features)
    ),
    "plot_segmentation_pages": lambda r: skf.plot_segmentation_pages(r.recordings, r.features),
    "plot_participant_features": lambda r: skf.plot_participant_features(r.features),
    "plot_contact_speeds": lambda r: skf.plot_contact_speeds(r.features),
    "plot_feature_space": lambda r: skf.plot_feature_space(r.features),
    "plot_feature_overview": lambda r: skf.plot_feature_overview(r.features),
    "plot_estimates_vs_truth": lambda r: skf.plot_estimates_vs_truth(
        r.features, r.features.assign(contact_speed=r.features.contact_speed * 0.9), r.features
    ),
    "plot_sparc_vs_length": lambda r: skf.plot_sparc_vs_length(r.features, FS),
    "plot_residual_analysis": lambda r: skf.plot_residual_analysis(
        sk.ResidualAnalysis(np.linspace(2.0, 47.0, 46), np.full(46, 4e-4), 0.0005, -0.0005 / 60, 6.0), 120.0
    ),
    "plot_sparc_against_reference": lambda r: skf.plot_sparc_against_reference(
        {"raw": r.features, "filtered": r.features}, r.features, xlabel="SPARC, reference", ylabel="SPARC"
    ),
    "plot_silhouette_sweep": lambda r: skf.plot_silhouette_sweep(r.sweep, chosen_k=6),
    "plot_silhouettes": lambda r: skf.plot_silhouettes(r.sweep.results[max(r.sweep.results)]),
    "plot_clusters": lambda r: skf.plot_clusters(r.prototypes),
    "plot_prototype_profiles": lambda r: skf.plot_prototype_profiles(r.profiles, r.prototypes.prototypes),
    "plot_stability": lambda r: skf.plot_stability(
        {"seeds, raw": np.array([1.0, 0.9]), "bootstrap, z-scored": np.array([0.5, 0.7, 0.6])}
    ),
    "plot_sparc_sensitivity": lambda r: skf.plot_sparc_sensitivity(_sensitivity(r)),
    "plot_cluster_participants": lambda r: skf.plot_cluster_participants(
        sk.cluster_participant_table(np.arange(60) % 6, np.repeat([f"P{i}" for i in range(16)], 4)[:60])
    ),
    "plot_robot_joints": lambda r: skf.plot_robot_joints(),
    "plot_robot_pose": lambda r: skf.plot_robot_pose(),
    "plot_simple6_figure": lambda r: skf.plot_simple6_figure(),
    "plot_start_poses": lambda r: skf.plot_start_poses(
        [(sk.get_robot(n).robot, sk.transfer(n, *_descent(0.6))) for n in ("ur5", "panda", "puma560")]
    ),
    "plot_joint_velocities": lambda r: skf.plot_joint_velocities(r.transfers),
    "plot_frame_mapping": lambda r: skf.plot_frame_mapping(sk.get_robot("simple6").robot, r.transfers[-1]),
    "plot_sparc_stretch": lambda r: skf.plot_sparc_stretch(
        *_stretch(), time_scales=[1, 1.5, 1.2, 1, 1, 1], capped=[True] + [False] * 5
    ),
    "plot_time_scaled_plane": lambda r: skf.plot_time_scaled_plane(*_plane(), _plane()[1], mark_centre=1),
    "plot_joint_accelerations": lambda r: skf.plot_joint_accelerations(_dynamics(r)),
    "plot_joint_torques": lambda r: skf.plot_joint_torques(_by_arm()["Puma 560"] * 2),
    "plot_executed_speed": lambda r: skf.plot_executed_speed(r.assessments),
    "plot_time_scales": lambda r: skf.plot_time_scales(_by_arm()),
    "dynamics_figures": lambda r: skf.dynamics_figures(r.assessments),
    "plot_limit_sensitivity": lambda r: skf.plot_limit_sensitivity(_by_arm()),
    "plot_draws": lambda r: skf.plot_draws(_draws(), paper={"silhouette_k6": 0.337}),
    "plot_measure_clusters": lambda r: skf.plot_measure_clusters(*_measures()),
    "plot_scaling": lambda r: skf.plot_scaling(_scaling_rows()),
    "plot_phase_spread": lambda r: skf.plot_phase_spread(
        _phase_spread(), sk.fit_prototypes(sk.select(_tables()[0.0]), 3).centres
    ),
    "plot_spread_estimate": lambda r: skf.plot_spread_estimate(_phase_spread(), _phase_spread()),
    "plot_estimator_spread": lambda r: skf.plot_estimator_spread(_estimator_table()),
    "plot_phase_clusters": lambda r: skf.plot_phase_clusters(
        {ph: sk.fit_prototypes(sk.select(t), 3) for ph, t in _tables().items()}
    ),
}


def _public_figure_functions() -> set[str]:
    return {n for n in skf.__all__ if n.startswith("plot_") or n == "dynamics_figures"}


def test_every_public_figure_function_is_checked():
    assert _public_figure_functions() == set(CALLS)


def _figures(out) -> list[plt.Figure]:
    if isinstance(out, plt.Figure):
        return [out]
    return [item[0] if isinstance(item, tuple) else item for item in out]


def _visible_texts(fig: plt.Figure) -> list[Text]:
    """Every text the reader sees: visible, not empty, on a visible axes (tick labels included)."""
    out = []
    for t in fig.findobj(Text):
        if not t.get_visible() or not t.get_text().strip():
            continue
        ax = t.axes
        if ax is not None and not ax.get_visible():
            continue
        out.append(t)
    return out


def saved_width(fig: plt.Figure) -> float:
    """The width (in) of the PNG the inline backend saves: the tight bounding box plus 0.1 in each side."""
    renderer = fig.canvas.get_renderer()
    return fig.get_tightbbox(renderer).width + 0.2


@pytest.mark.parametrize("name", sorted(CALLS))
def test_the_figure_fits_the_page_and_its_text_is_legible(name, run):
    with plt.rc_context(HOSTILE):
        figs = _figures(CALLS[name](run))
        assert figs, name
        for fig in figs:
            fig.canvas.draw()  # drawn under the caller's settings, as the notebook's inline backend does
            width = fig.get_figwidth()
            assert width <= WIDE + 1e-9, f"{name}: drawn {width:.2f} in wide"
            assert saved_width(fig) <= FULL_WIDTH, f"{name}: saved {saved_width(fig):.2f} in wide"
            small = sorted({(round(t.get_fontsize(), 2), t.get_text()[:30]) for t in _visible_texts(fig)})
            assert small and small[0][0] >= MIN_FONT, f"{name}: text below {MIN_FONT} pt: {small[:5]}"
    plt.close("all")


def test_the_book_style_is_not_left_behind():
    """A figure function restores the caller's settings (it draws inside a context)."""
    with plt.rc_context(HOSTILE):
        plt.close(skf.plot_sparc_against([0, 1], {"a": [-1.5, -1.6]}, "x"))
        assert plt.rcParams["font.size"] == HOSTILE["font.size"]
    skf.book_style()
    try:
        assert plt.rcParams["font.size"] == BOOK_RC["font.size"] and plt.rcParams["figure.dpi"] == 100
    finally:
        matplotlib.rcdefaults()


@pytest.mark.parametrize(
    ("n", "max_cols", "panel", "expect"),
    [(6, 3, 3.0, (2, 3, 9.0)), (4, 2, 4.5, (2, 2, 9.0)), (4, 4, 4.6, (4, 1, 4.6)), (2, 3, 2.0, (1, 2, 4.0))],
)
def test_grid_wraps_panels_into_rows_within_the_width(n, max_cols, panel, expect):
    assert grid(n, max_cols, panel) == expect


# ------------------------------------------------------------------------------------ static scan --

#: A font size below 8 pt written in code: a number below 8 after fontsize=/labelsize=/size=, or a relative
#: size that resolves below 8 pt at the book's 10-pt base ("x-small" 6.9 pt, "xx-small" 5.8 pt).
_SMALL = re.compile(
    r"""\b(?:fontsize|labelsize|title_fontsize|size)\s*=\s*(?:(?P<num>\d+(?:\.\d+)?)\b(?!\s*[-*/+])"""
    r"""|["'](?P<rel>x-small|xx-small)["'])"""
)


def _scanned() -> list[Path]:
    return sorted((ROOT / "skilllib" / "figures").glob("*.py")) + sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.py"))


def small_fonts(text: str) -> list[str]:
    out = []
    for m in _SMALL.finditer(text):
        if m["rel"] or float(m["num"]) < MIN_FONT:
            out.append(m[0])
    return out


def test_the_scan_finds_small_sizes():
    assert small_fonts('ax.text(0, 0, "a", fontsize=7)\nax.legend(fontsize="x-small")') == [
        "fontsize=7",
        'fontsize="x-small"',
    ]
    assert small_fonts('fontsize=8, labelsize="small", size=9.5, capsize=2, fontsize=FONT - 1.5') == []


@pytest.mark.parametrize("path", _scanned(), ids=lambda p: p.name)
def test_no_font_below_8_pt_in_the_figure_code_and_chapters(path):
    assert small_fonts(path.read_text(encoding="utf-8")) == []
