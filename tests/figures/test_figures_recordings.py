"""The recordings chapter's figures (skilllib/figures/recordings.py): Winter's residual analysis and
SPARC after a filter against a reference."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import skilllib as sk  # noqa: E402
from skilllib.figures import plot_residual_analysis, plot_sparc_against_reference, plt  # noqa: E402


def _analysis() -> sk.ResidualAnalysis:
    cutoffs = np.linspace(2.0, 47.0, 46)  # Hz
    residual = np.where(cutoffs < 6, 0.01 / cutoffs, 0.0005 - 0.0005 * cutoffs / 60)  # m
    return sk.ResidualAnalysis(cutoffs, residual, 0.0005, -0.0005 / 60, 6.0)


def test_the_residual_figure_draws_the_residual_in_mm_the_noise_line_and_the_cut_off():
    ra = _analysis()
    fig = plot_residual_analysis(ra, fs=120.0)
    (ax,) = fig.axes
    assert "mm" in ax.get_ylabel() and "Hz" in ax.get_xlabel()
    assert ax.get_ylim()[1] == 4 * ra.noise_m * 1e3  # the axis ends at four times the noise
    dots = ax.lines[0]
    assert dots.get_label() == "residual R(f)" and np.all(dots.get_ydata() <= 2.0)
    above = ax.lines[1]  # residuals above the scale: triangles at its top
    assert above.get_marker() == "^" and np.all(above.get_ydata() == 2.0)
    assert any("above the scale" in t.get_text() for t in ax.texts)
    labels = [line.get_label() for line in ax.lines]
    assert "line fitted to the noise" in labels and "cut-off 6.0 Hz" in labels
    plt.close(fig)


def test_the_sparc_figure_draws_one_panel_per_table_with_the_trials_valid_in_both():
    ids = {"participant": ["1", "1", "2", "2"], "trial": ["1", "2", "1", "2"]}
    reference = pd.DataFrame({**ids, "status": "selected", "sparc": [-1.5, -1.6, -1.7, -1.8]})
    noisy = reference.assign(sparc=reference.sparc - 0.05, status=["selected", "invalid", "excluded", "selected"])
    fig = plot_sparc_against_reference({"a": reference, "b": noisy}, reference, xlabel="x", ylabel="y")
    left, right = fig.axes
    assert len(left.collections[0].get_offsets()) == 4 and len(right.collections[0].get_offsets()) == 3
    assert left.get_title() == "a: 4 trials, rank correlation 1.00"
    assert right.get_title().startswith("b: 3 trials") and left.get_ylabel() == "y"
    plt.close(fig)
