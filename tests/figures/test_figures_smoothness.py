"""Figures of the SPARC chapters: each draws what it is given, with labelled axes."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402

import skilllib as sk  # noqa: E402
from skilllib.figures import plot_padded_spectra, plot_short_segments, plt  # noqa: E402


def test_padded_spectra_draw_one_polygon_per_padlevel():
    v = sk.minimum_jerk_submovements([0, 0.5], 60.0, T=0.6, D=0.1)
    fig = plot_padded_spectra(v, 60.0, padlevels=(0, 4))
    (ax,) = fig.axes
    assert [len(line.get_xdata()) for line in ax.lines][1] > 8 * len(ax.lines[0].get_xdata())
    assert "Hz" in ax.get_xlabel() and ax.get_legend() is not None
    plt.close(fig)


def test_short_segments_mark_capped_bands_open_and_draw_the_bound():
    n = np.arange(6, 20)
    bands = {
        (r, fc): sk.sparc_bands([sk.minimum_jerk_segment(int(k), r, 60.0) for k in n], 60.0, fc=fc)
        for r in (0.3, 0.7)
        for fc in (20.0, 10.0)
    }
    fig = plot_short_segments(n, bands)
    ax, ax_end = fig.axes
    assert len(ax.lines) == 4 + 1 and ax.lines[-1].get_ydata()[0] == sk.figures.threshold_bound()
    assert [line.get_linestyle() for line in ax.lines[:2]] == ["-", "--"]
    n_capped = sum(int(b.capped.sum()) for b in bands.values())
    open_markers = sum(len(c.get_offsets()) for c in ax.collections[1::2])
    assert n_capped > 0 and open_markers == n_capped
    assert "samples" in ax.get_xlabel() and "Hz" in ax_end.get_ylabel()
    plt.close(fig)
