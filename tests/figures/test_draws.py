"""Tests of skilllib.figures.draws: one strip per quantity, the book's draw placed among the draws."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

import skilllib.figures as skf  # noqa: E402


@pytest.fixture
def table():
    return pd.DataFrame(
        {
            "silhouette_k6": [0.40, 0.38, 0.42, 0.36, 0.44],
            "n_valid_k": [15, 15, 15, 15, 15],
            "all_targets": [False, True, False, False, False],
        },
        index=pd.Index([0, 1, 2, 3, 4], name="seed"),
    )


def _offsets(ax, marker_color):
    return [
        np.asarray(c.get_offsets()) for c in ax.collections if np.allclose(c.get_facecolor()[0][:3], marker_color[:3])
    ]


def test_book_and_paper_drawn_at_their_sds_from_the_draws_mean(table):
    fig = skf.plot_draws(table, seed=1, paper={"silhouette_k6": 0.337})
    ax = fig.axes[0]
    sd = np.std([0.40, 0.38, 0.42, 0.36, 0.44], ddof=1)
    book = _offsets(ax, matplotlib.colors.to_rgba(skf.draws.BOOK_COLOR))
    assert list(book[0][0]) == pytest.approx([(0.38 - 0.40) / sd, 0.0])  # first strip at y = 0
    assert list(book[1][0]) == pytest.approx([0.0, -1.0])  # a quantity equal in every draw sits at 0
    paper = _offsets(ax, matplotlib.colors.to_rgba(skf.draws.PAPER_COLOR))
    assert len(paper) == 1 and list(paper[0][0]) == pytest.approx([(0.337 - 0.40) / sd, 0.0])
    draws = _offsets(ax, matplotlib.colors.to_rgba(skf.draws.DRAW_COLOR))
    assert len(draws) == 2 and all(len(d) == 5 for d in draws)
    assert np.all(np.abs(draws[0][:, 1]) < 0.5) and np.all(np.abs(draws[1][:, 1] + 1) < 0.5)  # in their strips
    texts = [t.get_text() for t in ax.texts]
    assert texts == [
        "0.360 to 0.440  (book 0.380)",
        "15 to 15  (book 15)",
        "range over the draws (book)",
    ]  # min before max, in the unit
    assert [t.get_text() for t in ax.get_yticklabels()][0] == "average silhouette, k = 6"
    plt.close(fig)


def test_boolean_columns_left_out_and_bad_input_refused(table):
    fig = skf.plot_draws(table, seed=1)
    assert len(fig.axes[0].texts) == 3
    plt.close(fig)
    with pytest.raises(ValueError, match="seed 9"):
        skf.plot_draws(table, seed=9)
    with pytest.raises(ValueError, match="nope"):
        skf.plot_draws(table, seed=1, columns=["nope"])
