"""Figures of a run on a corpus (issue 15): per-participant figures draw the first 12 participants and
say so; dense plots are rasterized inside the SVG; the scaling figure draws every series it is given."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from skilllib.figures import MAX_FIGURE_PARTICIPANTS, few_participants, plot_scaling, plt, save


def test_few_participants_keeps_the_first_by_natural_order_and_says_so():
    ids = [f"P{i}" for i in range(30, 0, -1)]
    f = pd.DataFrame({"participant": np.repeat(ids, 2), "trial": ["1", "2"] * 30})
    kept, note = few_participants(f)
    assert sorted(kept["participant"].unique(), key=lambda p: int(p[1:])) == [f"P{i}" for i in range(1, 13)]
    assert len(kept) == 2 * MAX_FIGURE_PARTICIPANTS and note == "the first 12 of 30 participants (by id)"
    same, none = few_participants(f[f["participant"].isin(["P1", "P2"])])
    assert len(same) == 4 and none == ""


def test_a_dense_plot_is_an_image_in_the_svg_and_a_sparse_one_stays_vectors(tmp_path):
    rng = np.random.default_rng(0)
    for n, name in ((30_000, "dense"), (300, "sparse")):
        fig, ax = plt.subplots()
        ax.scatter(rng.random(n), rng.random(n), s=2)
        ax.axhline(0.5)
        save(fig, tmp_path, name)
        plt.close(fig)
    dense, sparse = (tmp_path / "dense.svg").read_text(), (tmp_path / "sparse.svg").read_text()
    assert "<image" in dense and dense.count("<use") < 100
    assert "<image" not in sparse and sparse.count("<use") >= 300


def test_the_scaling_figure_draws_each_series_and_leaves_out_failed_runs():
    rows = [
        {
            "trials": n,
            "input": kind,
            "mode": mode,
            "failed": int(fail),
            "wall_s": n / 1e4,
            "peak_main_mb": 100 + n / 1e3,
            "peak_worker_mb": 50.0 if mode == "dask" else None,
        }
        for n in (1_500, 15_000, 150_000)
        for mode, kind, fail in (
            ("inmemory", "csv", False),
            ("inmemory", "parquet", False),
            ("dask", "parquet", n == 150_000),
        )
    ]
    fig = plot_scaling(rows)
    top, bottom = fig.axes
    labels = [line.get_label() for line in top.lines]
    assert labels[:2] == ["in memory, one CSV file", "slope 1 (time proportional to N)"]
    dask = next(line for line in top.lines if line.get_label().startswith("Dask"))
    assert list(dask.get_xdata()) == [1_500, 15_000]  # the failed 150,000 run is not drawn
    assert any(line.get_label() == "largest Dask worker" for line in bottom.lines)
    plt.close(fig)
