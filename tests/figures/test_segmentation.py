"""The segmentation pages (skilllib/figures/segmentation.py), the window of plot_trials_by_participant
(skilllib/figures/experiment.py), and the pages a run writes (skilllib/pipeline/_run.py _write_figures).

Drawn from a small generated cohort (3 participants x 10 trials at 60 Hz) in which one trial never
touches (contact flag 0: "no contact") and one starts in motion ("no rest before onset", a long reason).
"""

from __future__ import annotations

import dataclasses
import json

import matplotlib

matplotlib.use("Agg")

import matplotlib.colors as mcolors  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from skilllib import figures as fg  # noqa: E402
from skilllib.cohort import CohortModel, generate_cohort  # noqa: E402
from skilllib.features import trial_features  # noqa: E402
from skilllib.figures.segmentation import STATUS_COLORS  # noqa: E402
from skilllib.pipeline import _run as pipeline  # noqa: E402
from skilllib.recordings import recordings_from_frame  # noqa: E402

NO_CONTACT = ("1", "2")  #: its contact flag zeroed
IN_MOTION = ("2", "3")  #: its samples before (and just after) the onset dropped


def _frame() -> pd.DataFrame:
    frame = generate_cohort(5, CohortModel(n_participants=3, n_trials=10, fs=60.0)).frame
    frame = frame.assign(participant=frame["participant"].astype(str), trial=frame["trial"].astype(str))
    key = (frame["participant"] == NO_CONTACT[0]) & (frame["trial"] == NO_CONTACT[1])
    frame.loc[key, "contact"] = 0
    rec = recordings_from_frame(frame)
    t_on = trial_features(rec).set_index(["participant", "trial"]).loc[IN_MOTION, "t_onset"]
    key = (frame["participant"] == IN_MOTION[0]) & (frame["trial"] == IN_MOTION[1])
    return frame[~key | (frame["t"] > t_on + 0.02)].reset_index(drop=True)


@pytest.fixture(scope="module")
def data():
    rec = recordings_from_frame(_frame())
    feats = trial_features(rec)
    assert feats.set_index(["participant", "trial"]).loc[NO_CONTACT, "status"] == "invalid"
    assert feats.set_index(["participant", "trial"]).loc[IN_MOTION, "reason"].startswith("no rest before onset")
    return rec, feats


def _panel(fig, p: str, tr: str):
    """The axes of trial ``tr`` of participant ``p`` (its title starts "P<p> T<tr> ·")."""
    (ax,) = [ax for ax in fig.axes if ax.get_title(loc="left").startswith(f"P{p} T{tr} ·")]
    return ax


def _vlines(ax) -> dict[str, float]:
    """The vertical lines of a panel by colour: {colour: x} (an axvline's x data is [x, x])."""
    out = {}
    for line in ax.lines:
        x = np.asarray(line.get_xdata(), dtype=float)
        if len(x) == 2 and x[0] == x[1] and tuple(line.get_ydata()) == (0, 1):
            out[mcolors.to_hex(line.get_color())] = float(x[0])
    return out


def test_pages_hold_rows_x_cols_trials_the_last_one_partly(data):
    rec, feats = data
    figs = fg.plot_segmentation_pages(rec, feats, rows=2, cols=4)  # 30 trials, 8 a page
    assert len(figs) == 4
    shown = [[ax for ax in fig.axes if ax.axison] for fig in figs]
    assert [len(a) for a in shown] == [8, 8, 8, 6]
    assert len(fg.plot_segmentation_pages(rec, feats, rows=2, cols=4, max_pages=2)) == 2
    assert len(fg.plot_segmentation_pages(rec, feats)) == 2  # 24 a page by default
    fg.plt.close("all")


def test_trials_are_in_natural_order_of_participant_and_trial(data):
    rec, feats = data
    (fig,) = fg.plot_segmentation_pages(rec, feats, keys=[("1", "10"), ("1", "2"), ("1", "1")], rows=1, cols=3)
    titles = [ax.get_title(loc="left").split(" ·")[0] for ax in fig.axes]
    assert titles == ["P1 T10", "P1 T2", "P1 T1"]  # keys given: drawn as given
    keys, note = fg.segmentation_keys(feats)
    assert note == "" and keys[:3] == [("1", "1"), ("1", "2"), ("1", "3")] and keys[9] == ("1", "10")
    fg.plt.close("all")


def test_an_invalid_trials_reason_is_in_its_panel_red_and_shortened(data):
    rec, feats = data
    figs = fg.plot_segmentation_pages(rec, feats)
    fig = figs[0]
    ax = _panel(fig, *NO_CONTACT)
    title = ax.get_title(loc="left")
    assert "invalid" in title and "no contact: the contact flag is never 1" in title.replace("\n", " ")
    assert ax._left_title.get_color() == STATUS_COLORS["invalid"]  # the title of loc="left"
    reason = feats.set_index(["participant", "trial"]).loc[IN_MOTION, "reason"]
    long = _panel(fig, *IN_MOTION).get_title(loc="left")
    assert long.endswith("…") and len(long.split("\n")) == 3  # ids and status, two lines of the reason
    assert reason.startswith(long.split("\n", 1)[1].replace("\n", " ").removesuffix(" …").rstrip())
    ok = _panel(fig, "1", "1")
    assert ok._left_title.get_color() in (STATUS_COLORS["selected"], STATUS_COLORS["excluded"])
    fg.plt.close("all")


def test_onset_and_contact_lines_stand_at_the_features_times_and_the_segment_is_shaded(data):
    rec, feats = data
    (fig,) = fg.plot_segmentation_pages(rec, feats, keys=[("1", "1"), ("2", "5")], rows=1, cols=2)
    for ax, (p, tr) in zip(fig.axes, [("1", "1"), ("2", "5")]):
        row = feats.set_index(["participant", "trial"]).loc[(p, tr)]
        lines = _vlines(ax)
        assert lines[mcolors.to_hex("tab:blue")] == row["t_onset"]
        assert lines[mcolors.to_hex("tab:purple")] == row["t_contact"]
        t = rec.trial(p, tr).t
        c = int(np.flatnonzero(rec.trial(p, tr).contact)[0])
        (span,) = ax.patches
        x = span.get_patch_transform().transform(span.get_path().vertices)[:, 0]  # Rectangle or Polygon
        assert x.min() == pytest.approx(row["t_onset"]) and x.max() == pytest.approx(t[c - 1])
        assert ax.get_xlim() == (t[0], t[-1])  # the whole recording
    labels = [h.get_text() for h in fig.legends[0].get_texts()]
    assert {"onset", "first contact sample", "analysed segment"} <= set(labels)
    fg.plt.close("all")


def test_the_approach_speed_is_the_analysed_one(data):
    """The black line up to contact is the speed :func:`skilllib.features.segment` computes, with the
    run's filter (features.attrs["lowpass"]) applied."""
    from skilllib.features import segment

    rec, _ = data
    feats = trial_features(rec, lowpass=8.0)
    (fig,) = fg.plot_segmentation_pages(rec, feats, keys=[("1", "1")], rows=1, cols=1)
    seg = segment(rec, "1", "1", lowpass=feats.attrs["lowpass"])
    (black,) = [line for line in fig.axes[0].lines if line.get_color() == "k"]
    x, y = black.get_xydata().T
    np.testing.assert_allclose(y[seg.onset : seg.contact], seg.speed, rtol=1e-12)
    np.testing.assert_array_equal(x[seg.onset : seg.contact], seg.t)
    fg.plt.close("all")


class _Repaired:
    """Recordings with a repaired_mask: samples 5..7 of every trial repaired."""

    def __init__(self, rec):
        self._rec = rec

    def __getattr__(self, name):
        return getattr(self._rec, name)

    def repaired_mask(self, participant, trial) -> np.ndarray:
        mask = np.zeros(len(self._rec.trial(participant, trial).t), dtype=bool)
        mask[5:8] = True
        return mask


def _crosses(ax) -> list[Line2D]:
    return [line for line in ax.lines if line.get_marker() == "x"]


def test_repaired_samples_are_crossed_when_the_recordings_say_which(data):
    rec, feats = data
    (fig,) = fg.plot_segmentation_pages(_Repaired(rec), feats, keys=[("1", "1")], rows=1, cols=1)
    (cross,) = _crosses(fig.axes[0])
    np.testing.assert_array_equal(cross.get_xdata(), rec.trial("1", "1").t[5:8])
    assert "repaired sample" in [h.get_text() for h in fig.legends[0].get_texts()]
    (plain,) = fg.plot_segmentation_pages(rec, feats, keys=[("1", "1")], rows=1, cols=1)
    assert not _crosses(plain.axes[0]) and "repaired sample" not in [h.get_text() for h in plain.legends[0].get_texts()]
    fg.plt.close("all")


def test_a_resampled_trial_says_so(data):
    rec, feats = data
    f = feats.copy()
    f.loc[(f["participant"] == "1") & (f["trial"] == "1"), "resampled"] = True
    (fig,) = fg.plot_segmentation_pages(rec, f, keys=[("1", "1"), ("1", "3")], rows=1, cols=2)
    assert "resampled" in fig.axes[0].get_title(loc="left") and "resampled" not in fig.axes[1].get_title(loc="left")
    fg.plt.close("all")


def test_segmentation_keys_put_every_invalid_trial_in_a_capped_sample(data):
    _, feats = data
    keys, note = fg.segmentation_keys(feats, 6)
    assert len(keys) == 6 and {NO_CONTACT, IN_MOTION} <= set(keys)
    assert {k[0] for k in keys} == {"1", "2", "3"}  # the valid ones spread over the participants
    assert "6 of 30 trials" in note and "all 2 invalid" in note
    keys, note = fg.segmentation_keys(feats, 1)
    assert keys == [NO_CONTACT] and "the first 1 of 2 invalid" in note


def test_one_participant_gets_a_time_axis_and_the_window_shows_every_onset(data):
    rec, feats = data
    one = feats[feats["participant"] == "1"]
    fig = fg.plot_trials_by_participant(rec, one)
    visible = [ax for ax in fig.axes if ax.axison]
    assert len(visible) == 2  # y and speed of the one participant
    speed = visible[-1]
    assert speed.get_xlabel() == "time from contact (s)"
    fig.canvas.draw()
    assert any(t.get_text() for t in speed.get_xticklabels())
    lo, hi = speed.get_xlim()
    lead = (one["t_onset"] - one["t_contact"]).dropna()
    assert lo < lead.min() and lo == pytest.approx(lead.min() - 0.2) and 0 < hi <= 0.3
    fg.plt.close("all")


def test_three_participants_every_column_has_a_time_axis(data):
    rec, feats = data
    fig = fg.plot_trials_by_participant(rec, feats, window=(-0.9, 0.3))
    labelled = [ax for ax in fig.axes if ax.axison and ax.get_xlabel() == "time from contact (s)"]
    assert len(labelled) == 2  # columns: participants 1 and 3 below, 2 above the hidden spare
    assert fig.axes[0].get_xlim() == (-0.9, 0.3)  # a window given is kept
    fg.plt.close("all")


def test_a_run_writes_the_segmentation_pages_png_with_the_note(data, tmp_path, monkeypatch):
    """_write_figures on a small run (its clustering and transfer left out): the pages segmentation-01.png, ... are
    written and listed; the synthetic-data note and the "Shown" note on them when capped. The other
    figures are not rendered (save replaced by a recorder)."""
    frame = _frame()
    run_ = pipeline.run(frame, None, k=2, write_figures=False)
    run_ = dataclasses.replace(run_, prototypes=None, sweep=None, sensitivity=None, transfers=[], assessments=[])
    monkeypatch.setattr(fg, "save", lambda fig, out, name, dpi=150: [tmp_path / f"{name}.png"])
    texts = []
    real = fg.save_page

    def page(fig, out, name):
        texts.append([t.get_text() for t in fig.texts])
        return real(fig, out, name)

    monkeypatch.setattr(fg, "save_page", page)
    monkeypatch.setattr(fg, "MAX_SEGMENTATION_TRIALS", 24)
    results = {**run_.results, "dataset": {**run_.results["dataset"], "synthetic": True}}
    written = pipeline._write_figures(dataclasses.replace(run_, results=results), tmp_path, None)
    assert [n for n in written if n.startswith("segmentation")] == ["segmentation-01.png"]
    assert (tmp_path / "segmentation-01.png").stat().st_size > 0
    assert any(t.startswith("Synthetic data") for t in texts[0])
    assert any(t.startswith("Shown: the segmentation of 24 of 30 trials: all 2 invalid") for t in texts[0])
    assert not fg.plt.get_fignums()


@pytest.mark.slow
def test_the_command_writes_the_pages_and_lists_them(data, tmp_path):
    """A real run of the command's function on the small cohort, figures included: two pages (30
    trials), PNG only, listed in results.json."""
    out = tmp_path / "o"
    pipeline.run(_frame(), out, k=2)
    figures = json.loads((out / "results.json").read_text())["figures"]
    pages = sorted(n for n in figures if n.startswith("segmentation"))
    assert pages == ["segmentation-01.png", "segmentation-02.png"]
    assert all((out / n).stat().st_size > 0 for n in pages)


def test_a_trial_with_a_gap_too_long_to_fill_is_drawn_around_the_gap():
    """An invalid trial keeps its missing samples (a gap too long to fill): its panel shows the speed on
    either side of the gap and nothing across it (catches velocity() refusing NaN, which stopped the run's
    figures)."""
    import skilllib as sk

    c = sk.generate_cohort(9, sk.CohortModel(n_participants=1, n_trials=3))
    df = c.frame.copy()
    rows = df.index[df.trial == "2"]
    df.loc[rows[5:40], "x"] = np.nan  # 0.58 s: not filled, invalid
    rec = sk.load_recordings(df)
    f = sk.trial_features(rec)
    assert f.set_index("trial").loc["2", "status"] == "invalid"
    fig = fg.plot_segmentation_pages(rec, f)[0]
    panel = fig.axes[1]
    speed = panel.lines[0].get_ydata()
    assert np.isnan(speed[5:40]).all() and np.isfinite(speed[:4]).all() and np.isfinite(speed[41:]).any()
    matplotlib.pyplot.close(fig)
