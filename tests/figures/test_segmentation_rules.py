"""The segmentation pages under other start and end rules (skilllib/figures/segmentation.py): the run's onset
threshold (absolute or from each trial's peak) and the end sample labelled by what ended it."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.colors as mcolors  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from skilllib import figures as fg  # noqa: E402
from skilllib.features import parse_end, parse_start, trial_features  # noqa: E402
from skilllib.recordings import recordings_from_frame  # noqa: E402

FS = 100.0


def _reaches() -> pd.DataFrame:
    """Three minimum-jerk reaches up y at 100 Hz, 1 s of rest before and after, no contact."""
    rows = []
    for k, amp in enumerate((0.2, 0.3, 0.4), 1):
        n = 301
        t = np.arange(n) / FS
        tau = np.clip(t - 1.0, 0, 1)
        y = 0.5 + amp * (10 * tau**3 - 15 * tau**4 + 6 * tau**5)
        y = y + np.random.default_rng(k).normal(0, 2e-5, n)
        rows.append(pd.DataFrame({"participant": "1", "trial": str(k), "t": t, "x": 0.1, "y": y, "z": -0.2}))
    return pd.concat(rows, ignore_index=True).assign(contact=0)


@pytest.fixture(scope="module")
def run():
    rec = recordings_from_frame(_reaches())
    start, end = parse_start("speed:5%"), parse_end("offset:5%")
    return rec, trial_features(rec, start=start, end=end), start, end


def _hlines(ax) -> list[float]:
    return [
        float(line.get_ydata()[0])
        for line in ax.lines
        if tuple(line.get_xdata()) == (0, 1) and line.get_ydata()[0] == line.get_ydata()[1]
    ]


def test_offset_pages_draw_the_relative_threshold_and_label_the_end(run):
    rec, feats, _, _ = run
    assert (feats["status"] != "invalid").all()
    (fig,) = fg.plot_segmentation_pages(rec, feats, rows=1, cols=3)  # the rules from feats.attrs
    for ax, (_, row) in zip(fig.axes, feats.iterrows()):
        ends = [
            float(line.get_xdata()[0])
            for line in ax.lines
            if mcolors.to_hex(line.get_color()) == mcolors.to_hex("tab:purple")
        ]
        assert ends == [row["t_contact"]]
        (black,) = [line for line in ax.lines if line.get_color() == "k"]
        peak = np.nanmax(black.get_ydata())
        assert _hlines(ax) == [pytest.approx(0.05 * peak)]  # onset and offset share the threshold
        assert "offset" in [t.get_text().strip() for t in ax.texts]
    labels = [h.get_text() for h in fig.legends[0].get_texts()]
    assert "offset (end)" in labels and "onset and offset threshold 5% of the peak" in labels
    assert any("Rules: start speed:5%, end offset:5%." in t.get_text().replace("\n", " ") for t in fig.texts)
    fg.plt.close("all")


def test_a_different_absolute_offset_threshold_gets_its_own_line(run):
    rec, _, _, _ = run
    start, end = parse_start("speed:0.05"), parse_end("offset:0.02")
    feats = trial_features(rec, start=start, end=end)
    (fig,) = fg.plot_segmentation_pages(rec, feats, keys=[("1", "2")], rows=1, cols=1)
    assert sorted(_hlines(fig.axes[0])) == [0.02, 0.05]
    labels = [h.get_text() for h in fig.legends[0].get_texts()]
    assert {"onset threshold 0.05 m/s", "offset threshold 0.02 m/s"} <= set(labels)
    fg.plt.close("all")


def test_a_height_end_is_labelled_and_the_paper_default_is_unchanged(run):
    rec, _, _, _ = run
    end = parse_end("height-above:0.6")
    feats = trial_features(rec, end=end)
    (fig,) = fg.plot_segmentation_pages(rec, feats, keys=[("1", "3")], rows=1, cols=1, end=end)
    assert "height above 0.6 m (end)" in [h.get_text() for h in fig.legends[0].get_texts()]
    assert "height" in [t.get_text().strip() for t in fig.axes[0].texts]
    paper = trial_features(rec)  # no contact: every trial invalid, the paper's legend
    (fig,) = fg.plot_segmentation_pages(rec, paper, keys=[("1", "1")], rows=1, cols=1)
    labels = [h.get_text() for h in fig.legends[0].get_texts()]
    assert "onset threshold 0.05 m/s" in labels and "speed before contact (as analysed)" in labels
    fg.plt.close("all")
