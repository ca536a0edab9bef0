"""Edge cases of skilllib.pipeline that tests/test_pipeline_values.py and tests/test_cli.py leave open:
the figures a run writes (names, what the data figures show, the synthetic-data note, every figure
closed), the low-pass filter's message, and the printed summary (skilllib.pipeline).

The figures are drawn from one small run (3 participants x 8 trials, k = 2, a low-pass filter and a
non-default amp_th) with ``skilllib.figures.save`` replaced by a recorder (nothing is rendered or
written) and the costliest figure functions by stubs that record their arguments: this module checks
what _write_figures does with the figures, which keeps it fast; the figures themselves are drawn and
written by the slow figure tests and tests/test_cli.py.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")

import matplotlib.colors as mcolors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402

from skilllib import figures as fg
from skilllib.cohort import CohortModel, generate_cohort
from skilllib.features import NO_FILTER, Lowpass
from skilllib.pipeline import _run as pipeline
from skilllib.pipeline import _summary as summary
from skilllib.recordings import MAX_RANGE_M
from skilllib.robot import get_robot

FS = 60.0
AMP_TH = 0.1  #: not the default 0.05: the figures must show the run's own threshold
CUTOFF_HZ = 8.0
DATA_FIGURES = ["features", "trials_by_participant", "participant_features", "sparc_vs_length"]
SEGMENTATION_PAGES = ["segmentation-01"]  #: 24 trials: one page (PNG only, skilllib.figures.save_page)
CLUSTER_FIGURES = [
    "silhouette_sweep",
    "silhouettes_k",
    "clusters_pv_sparc",
    "prototype_speed_profiles",
    "joint_velocities",
    "frame_mapping",
]
ROBOT = "simple6"


@pytest.fixture(scope="module")
def small_run() -> pipeline.PipelineRun:
    frame = generate_cohort(3, CohortModel(n_participants=3, n_trials=8, fs=FS)).frame
    run_ = pipeline.run(frame, None, k=2, amp_th=AMP_TH, lowpass=CUTOFF_HZ, robot=ROBOT)
    assert run_.prototypes is not None and len(run_.transfers) == 2
    return run_


#: Figure functions replaced by stubs (each ~1 s to draw); their (name, args) are recorded.
STUBBED = (
    "plot_trials_by_participant",
    "plot_participant_features",
    "plot_joint_velocities",
    "plot_frame_mapping",
    "plot_sparc_sensitivity",
)
STUB_DYNAMICS = ("dynamics_a", "dynamics_b", "dynamics_c")  #: names the dynamics_figures stub returns
SENSITIVITY = object()  #: stands for a SparcSensitivity: only passed on to its figure


def _draw(run_: pipeline.PipelineRun, mp: pytest.MonkeyPatch, synthetic: bool) -> dict:
    """_write_figures of ``run_`` with its dataset marked (not) synthetic; save() records (fig, name)
    without rendering, the costly figure functions are stubs that record their arguments."""
    saved, calls = [], []

    def record(fig, out_dir, name, dpi=150):
        saved.append((fig, name))
        return [Path(out_dir) / f"{name}.png", Path(out_dir) / f"{name}.svg"]

    def record_page(fig, out_dir, name, dpi=110):
        saved.append((fig, name))
        return [Path(out_dir) / f"{name}.png"]

    def stub(fname):
        def draw(*args, **kwargs):  # keywords: the task's end and selection window (test_tasks.py)
            calls.append((fname, args))
            return plt.figure()

        return draw

    def dynamics(assessments):
        calls.append(("dynamics_figures", (assessments,)))
        return [(plt.figure(), n) for n in STUB_DYNAMICS]  # all drawn before the first is saved

    mp.setattr(fg, "save", record)
    mp.setattr(fg, "save_page", record_page)
    for fname in STUBBED:
        mp.setattr(fg, fname, stub(fname))
    mp.setattr(fg, "dynamics_figures", dynamics)
    results = {**run_.results, "dataset": {**run_.results["dataset"], "synthetic": synthetic}}
    robot = get_robot(ROBOT).robot
    written = pipeline._write_figures(dataclasses.replace(run_, results=results), Path("unused"), robot)
    return {"written": written, "saved": saved, "calls": calls, "robot": robot}


def _data_only(run_: pipeline.PipelineRun) -> pipeline.PipelineRun:
    """``run_`` without its clustering and transfer: only the data figures are drawn."""
    return dataclasses.replace(run_, prototypes=None, sweep=None, sensitivity=None, transfers=[], assessments=[])


@pytest.fixture(scope="module")
def drawn(small_run):
    """Every figure of the small run (with a stand-in sensitivity) as if it were the shipped cohort (the
    note drawn), and its data figures as it is (a DataFrame: no note)."""
    with pytest.MonkeyPatch.context() as mp:
        synthetic = _draw(dataclasses.replace(small_run, sensitivity=SENSITIVITY), mp, True)
    with pytest.MonkeyPatch.context() as mp:
        plain = _draw(_data_only(small_run), mp, False)
    return {"synthetic": synthetic, "plain": plain}


def _names(saved: list[tuple]) -> list[str]:
    return [name for _, name in saved]


def test_every_figure_is_written_under_its_name_png_and_svg(drawn):
    """The data figures, the clustering and transfer figures, the dynamics figures and the sensitivity
    figure, in that order; the returned list names both files of each. Catches a figure written under a
    wrong (or no) name."""
    d = drawn["synthetic"]
    names = _names(d["saved"])
    assert names == [*DATA_FIGURES, *SEGMENTATION_PAGES, *CLUSTER_FIGURES, *STUB_DYNAMICS, "sparc_sensitivity"]
    exts = {n: ("png",) if n in SEGMENTATION_PAGES else ("png", "svg") for n in names}
    assert d["written"] == [f"{n}.{ext}" for n in names for ext in exts[n]]
    # without clustering, only the data figures and the segmentation pages
    assert _names(drawn["plain"]["saved"]) == [*DATA_FIGURES, *SEGMENTATION_PAGES]


def test_transfers_without_clusters_get_the_transfer_figures_only(small_run):
    """Too few selected trials to cluster, each transferred as it is: the data figures, then the transfer
    and dynamics figures, no cluster figure (there is no clustering to draw)."""
    alone = dataclasses.replace(small_run, prototypes=None, sweep=None, sensitivity=None)
    with pytest.MonkeyPatch.context() as mp:
        d = _draw(alone, mp, False)
    transfer_figures = [n for n in CLUSTER_FIGURES if n in ("joint_velocities", "frame_mapping")]
    assert _names(d["saved"]) == [*DATA_FIGURES, *SEGMENTATION_PAGES, *transfer_figures, *STUB_DYNAMICS]


def test_figures_are_drawn_from_the_runs_own_objects(drawn, small_run):
    """Each figure function gets the run's recordings, features, transfers (the frame mapping: the
    last, fastest prototype's), assessments and sensitivity."""
    d = drawn["synthetic"]
    calls = dict(d["calls"])
    assert calls["plot_trials_by_participant"][0] is small_run.recordings
    assert calls["plot_trials_by_participant"][1] is small_run.features
    assert calls["plot_participant_features"] == (small_run.features,)
    assert calls["plot_joint_velocities"] == (small_run.transfers,)
    assert calls["plot_frame_mapping"] == (d["robot"], small_run.transfers[-1])
    assert calls["dynamics_figures"] == (small_run.assessments,)
    assert calls["plot_sparc_sensitivity"] == (SENSITIVITY,)


def test_every_figure_is_closed(drawn):
    """A run draws a dozen figures: each is closed once saved (a batch of runs would otherwise keep them
    all in memory). Catches a figure left open."""
    for key in drawn:
        for fig, name in drawn[key]["saved"]:
            assert not plt.fignum_exists(fig.number), name


def _legend_labels(fig) -> list[str]:
    return [line.get_label() for ax in fig.axes for line in ax.get_lines()]


def test_data_figures_show_the_runs_amp_th_and_sampling_rate(drawn):
    """The threshold-ended SPARC bound of the features and sparc_vs_length figures is drawn for the
    run's amp_th (not the default), and sparc_vs_length's length axis names the recordings' rate."""
    figs = {name: fig for fig, name in drawn["plain"]["saved"]}
    want = f"amp_th = {AMP_TH:g}"
    for name in ("features", "sparc_vs_length"):
        assert any(want in label for label in _legend_labels(figs[name])), name
    xlabels = [ax.get_xlabel() for ax in figs["sparc_vs_length"].axes]
    assert any(f"samples at {FS:g} Hz" in x for x in xlabels), xlabels


def _notes(fig) -> list:
    return [t for t in fig.texts if t.get_text() == pipeline.SYNTHETIC_NOTE]


def test_synthetic_note_on_every_figure_of_the_shipped_cohort_only(drawn):
    """Every figure of a run on the shipped cohort carries the note once, none of a run on other data."""
    for fig, name in drawn["synthetic"]["saved"]:
        assert len(_notes(fig)) == 1, name
    for fig, name in drawn["plain"]["saved"]:
        assert _notes(fig) == [], name


def test_synthetic_note_is_small_grey_and_in_the_bottom_right_corner(drawn):
    """The note sits in the figure's bottom right corner (right-aligned to the right edge, bottom-aligned
    at the bottom: its text never runs off the right or the bottom), in grey and smaller than the default
    text. Catches moved coordinates, another alignment, the default size or colour."""
    for fig, name in drawn["synthetic"]["saved"]:
        (note,) = _notes(fig)
        assert (note.get_horizontalalignment(), note.get_verticalalignment()) == ("right", "bottom"), name
        x, y = note.get_position()
        assert 0.95 < x <= 1 and 0 <= y < 0.05, (name, x, y)
        assert note.get_fontsize() < plt.rcParams["font.size"], name
        r, g, b, _ = mcolors.to_rgba(note.get_color())
        assert r == g == b and 0.2 < r < 0.8, (name, note.get_color())  # grey, neither black nor white
        box = note.get_window_extent(FigureCanvasAgg(fig).get_renderer())  # the figure's canvas is closed
        # ends at the right edge, above the bottom one (saved with a tight box, a long note widens a
        # narrow figure to the left)
        assert fig.bbox.width * 0.95 < box.x1 <= fig.bbox.width + 0.5 and box.y0 >= -0.5, (name, box)
        assert box.y1 < fig.bbox.height / 10, (name, box)


def test_without_valid_trials_no_data_figure_is_drawn(small_run):
    """Only invalid trials (and no clustering): no data figure, only the segmentation pages (why each
    trial is invalid)."""
    bare = dataclasses.replace(_data_only(small_run), features=small_run.features.assign(status="invalid"))
    with pytest.MonkeyPatch.context() as mp:
        d = _draw(bare, mp, True)
    assert d["written"] == [f"{n}.png" for n in SEGMENTATION_PAGES] and d["calls"] == []
    assert _names(d["saved"]) == SEGMENTATION_PAGES


# --- filter_message ------------------------------------------------------------------------------------


def test_filter_message_counts_bands_strictly_above_the_cutoff():
    """'SPARC's band reaches above that cut-off in N of M': bands ending exactly at the cut-off do not
    reach above it. Catches ``>=`` and a wrong column."""
    band_ends = [CUTOFF_HZ / 2, CUTOFF_HZ, np.nextafter(CUTOFF_HZ, np.inf), 2 * CUTOFF_HZ, CUTOFF_HZ]
    selected = pd.DataFrame({"sparc_band_end_hz": band_ends})
    beyond = sum(e > CUTOFF_HZ for e in band_ends)
    msg = pipeline.filter_message(selected, Lowpass(CUTOFF_HZ, "given"))
    assert f"above that cut-off in {beyond} of {len(band_ends)} selected trials" in msg
    assert msg.startswith(f"positions were low-pass filtered at {CUTOFF_HZ:.3g} Hz (given;")


def test_a_filtered_run_says_so_in_its_messages(small_run):
    """The run's filter message counts its own selected trials' bands above the cut-off."""
    sel = small_run.features[small_run.features.status == "selected"]
    beyond = int((sel["sparc_band_end_hz"] > CUTOFF_HZ).sum())
    assert f"above that cut-off in {beyond} of {len(sel)} selected trials" in small_run.messages[0]


# --- summary: the lines `python -m skilllib run` prints -------------------------------------------------


@pytest.mark.parametrize(
    "reason, kind",
    [
        ("contact speed 0.812 m/s above 0.7 m/s", "contact speed above 0.7 m/s"),
        ("contact speed 0.125 m/s below 0.3 m/s", "contact speed below 0.3 m/s"),
        ("sampled at 100 Hz, not at the file's 60 Hz", "sampled at another rate than the file"),
        ("positions span 3.2 m (more than the device)", f"positions span more than {MAX_RANGE_M:g} m"),
        (
            "in contact from sample 2: no approach recorded before contact",
            "in contact from the start: no approach recorded",
        ),
        ("too short: 3 samples from onset to contact (need at least 5)", "too short"),
        ("time goes backwards at line 12 (t = 0.5 after 0.6)", "time goes backwards"),
        ("x is missing (NaN) at row 17", "x is missing (NaN)"),
        ("only 12 samples of -1.5e-3 m", "only N samples of N m"),
    ],
)
def test_reason_kind_drops_what_differs_from_trial_to_trial(reason, kind):
    """Reasons that differ only in their numbers, line numbers or details after a colon count as one kind
    (the rule of each pattern of summary._REASON_KINDS and of the fallback)."""
    assert summary.reason_kind(reason) == kind


def test_reason_kind_counts_like_reasons_together():
    kinds = {summary.reason_kind(f"too short: {n} samples from onset to contact (need at least 5)") for n in range(5)}
    assert kinds == {"too short"}


@pytest.fixture(scope="module")
def lines(small_run) -> list[str]:
    return summary.summary_lines(small_run)


def test_summary_counts_trials_participants_and_statuses(small_run, lines):
    """The first two lines: trials, participants and rate; selected / excluded / invalid counts (0 for
    a status no trial has)."""
    f = small_run.features
    assert lines[0] == (
        f"trials read: {len(f)} from {f.participant.nunique()} participant(s) at {FS:.4g} Hz (from the time stamps)"
    )
    n = {s: int((f.status == s).sum()) for s in ("selected", "excluded", "invalid")}
    assert lines[1] == f"selected: {n['selected']}, excluded: {n['excluded']}, invalid: {n['invalid']}"


def test_summary_names_the_commonest_reasons_with_their_counts(small_run):
    """Up to three commonest reason kinds per status, most common first, as 'n x kind'; none for a
    status without trials."""
    f = small_run.features.copy()
    reasons = (
        ["no contact: the contact flag is never 1"] * 3
        + ["no onset: speed stays below 0.05 m/s"] * 2
        + ["x is missing (NaN) at row 4", "y is missing (NaN) at row 9", "z is missing (NaN) at row 2"]
    )
    f.loc[: len(reasons) - 1, "status"] = "invalid"
    f.loc[: len(reasons) - 1, "reason"] = reasons
    f.loc[f.status != "invalid", "status"] = "selected"
    run_ = dataclasses.replace(small_run, features=f, prototypes=None, sensitivity=None, messages=[])
    got = summary.summary_lines(run_)
    top = [ln for ln in got if ln.startswith("  commonest")]
    assert top == ["  commonest invalid reasons: 3 x no contact; 2 x no onset; 1 x x is missing (NaN)"]
    assert got[1] == f"selected: {len(f) - len(reasons)}, excluded: 0, invalid: {len(reasons)}"


def test_summary_of_the_clustering_and_each_prototype(small_run, lines):
    """k, scaling and silhouette; per cluster its size, prototype, peak |qd| and verdict (feasible, the
    time scaling and binding limit, or the transfer's flags); how many prototypes are feasible."""
    fit = small_run.prototypes
    assert f"k = {fit.k} clusters ({fit.scaling} features), average silhouette {fit.silhouette:.3f}" in lines
    clusters = [ln for ln in lines if ln.startswith("  cluster ")]
    assert len(clusters) == fit.k
    for c, (line, tr, a) in enumerate(zip(clusters, small_run.transfers, small_run.assessments)):
        p = fit.prototypes.loc[c]
        assert line.startswith(
            f"  cluster {c}: size {fit.sizes[c]}, prototype participant {p['participant']} "
            f"trial {p['trial']} (PV {p['pv']:.2f} m/s, SPARC {p['sparc']:.2f}); "
        )
        assert f"peak |qd| {np.nanmax(tr.peak_abs_qd):.2f} rad/s" in line
        d = a.dynamics
        if d.feasible:
            assert line.endswith(", feasible")
        elif not tr.flags:
            assert line.endswith(f"needs time scaling x{d.time_scale:.2f} ({d.binding_limit} binds)")
        else:
            assert line.endswith(f"{len(tr.flags)} flag(s)")
    n_ok = sum(a.dynamics.feasible for a in small_run.assessments)
    feas = [ln for ln in lines if ln.startswith("feasibility on ")]
    assert len(feas) == 1 and feas[0].startswith(f"feasibility on {small_run.transfers[0].robot} (joint velocity")
    assert feas[0].endswith(f"): {n_ok} of {fit.k} prototypes feasible as recorded")


def test_summary_ends_with_every_message_as_a_note(small_run, lines):
    assert small_run.messages and lines[-len(small_run.messages) :] == [f"note: {m}" for m in small_run.messages]


def test_summary_of_an_unknown_sampling_rate(small_run):
    run_ = dataclasses.replace(small_run, recordings=SimpleNamespace(fs=float("nan")), prototypes=None)
    assert summary.summary_lines(run_)[0].endswith("participant(s) at an unknown sampling rate")


# --- the run's options reach every step -----------------------------------------------------------


def test_the_prototypes_trajectory_is_filtered_as_the_trials_were(small_run):
    """The transfer gets the prototype's segment low-pass filtered at the run's cut-off, the trajectory
    its features came from. Catches the filter dropped for the prototype's segment (auto or none used)."""
    from skilllib.features import segment

    lowpass = small_run.features.attrs["lowpass"]
    assert lowpass.cutoff_hz == CUTOFF_HZ
    protos = small_run.prototypes.prototypes
    for c, (_t, speed) in enumerate(small_run.profiles):
        p, tr = protos.at[c, "participant"], protos.at[c, "trial"]
        filtered = segment(small_run.recordings, p, tr, lowpass=lowpass)
        raw = segment(small_run.recordings, p, tr, lowpass=NO_FILTER)
        np.testing.assert_array_equal(speed, filtered.speed)
        assert raw.speed.shape != speed.shape or not np.allclose(raw.speed, speed, rtol=0, atol=1e-6)


def test_progress_wraps_each_stage_with_its_name():
    """``progress(items, description)`` wraps the features, the silhouette sweep and the transfer loop.
    Catches a stage run without it (a terminal would show no bar) or under another name."""
    seen = []

    def progress(items, desc):
        seen.append((desc, len(items)))
        return items

    frame = generate_cohort(3, CohortModel(n_participants=3, n_trials=8, fs=FS)).frame
    run_ = pipeline.run(
        frame, None, k=2, amp_th=AMP_TH, lowpass=CUTOFF_HZ, robot=ROBOT, progress=progress, write_figures=False
    )
    names = [d for d, _ in seen]
    assert names[0] == "features" and "silhouette" in names and ("transfer", 2) in seen
    assert names.index("silhouette") < names.index("transfer")
    assert len(run_.transfers) == 2


@pytest.mark.parametrize("fc, ok", [(FS / 2 * (1 - 1e-9), True), (FS / 2, False), (FS / 2.5, True)])
def test_fc_below_the_nyquist_frequency_is_accepted(fc, ok):
    """fc just below fs / 2 is accepted; fc = fs / 2 is an option error naming both (issue 23: SPARC's
    band must end below the Nyquist frequency). Catches a bound of fs / 3 (rejects fc = fs / 2.5) or a
    comparison that lets fc = fs / 2 through."""
    params = {"fc": fc, "amp_th": 0.05, "padlevel": 4}
    if ok:
        pipeline._check_nyquist(params, FS)
    else:
        with pytest.raises(pipeline.OptionError, match=rf"Nyquist frequency {FS / 2:g} Hz"):
            pipeline._check_nyquist(params, FS)
    pipeline._check_nyquist({**params, "fc": 1e6}, float("nan"))  # rate unknown: nothing to check against


@pytest.fixture(scope="module")
def started_late() -> pd.DataFrame:
    """8 trials whose recording starts half-way through the approach: no rest before the onset."""
    frame = generate_cohort(3, CohortModel(n_participants=2, n_trials=4, fs=FS)).frame
    g = frame.groupby(["participant", "trial"], sort=False)
    return frame[g.cumcount() >= g["t"].transform("size") // 2]


@pytest.mark.parametrize(
    "lowpass, hint",
    [
        ("none", "then try a low-pass filter (--lowpass auto or HZ) (chapter 13)"),
        (CUTOFF_HZ, "then try a stronger low-pass filter (--lowpass HZ) (chapter 13)"),
        ("auto", "then try a low-pass filter (--lowpass HZ) (chapter 13)"),
    ],
)
def test_many_trials_without_rest_get_the_hint_that_fits_the_filter(started_late, lowpass, hint):
    """More than NO_REST_FRACTION of the trials without rest: the message counts them and suggests the
    next step for the filter in use (none: a filter; auto that did not filter: a cut-off; a cut-off: a
    stronger one). Catches the three hints confused or garbled."""
    run_ = pipeline.run(started_late, None, k=2, lowpass=lowpass, write_figures=False)
    no_rest = int(run_.features["reason"].astype(str).str.startswith("no rest before onset").sum())
    assert no_rest > pipeline.NO_REST_FRACTION * len(run_.features)
    msgs = [m for m in run_.messages if "no rest before onset" in m]
    assert len(msgs) == 1
    assert msgs[0].startswith(f"{no_rest} of {len(run_.features)} trials are invalid") and msgs[0].endswith(hint)
