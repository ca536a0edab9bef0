"""The time-scaling figures of the transfer chapter and the notebook-safe 3-D robot figures."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import skilllib as sk
import skilllib.figures as skf


def test_plot_sparc_stretch_one_panel_per_cluster_with_units():
    s = np.linspace(1, 2, 5)
    tables = [pd.DataFrame({c: v * (s - 1) for c in range(4)}, index=s) for v in (0.0, -0.1, -0.05)]
    fig = skf.plot_sparc_stretch(*tables, time_scales=[1, 1.5, 1.2, 1], capped=[True, False, False, False])
    shown = [ax for ax in fig.axes if ax.get_visible()]
    assert len(shown) == 4
    assert shown[0].get_title() == "cluster 0, capped band"
    assert [ln.get_xdata()[0] for ln in shown[1].lines if ln.get_linestyle() == ":"] == [1.5]
    assert any("time scale s" in ax.get_xlabel() for ax in shown)
    plt.close(fig)


def test_plot_time_scaled_plane_draws_both_panels_and_zooms():
    data = pd.DataFrame({"pv": [0.5, 0.7, 0.9], "sparc": [-1.6, -1.7, -1.8], "cluster": [0, 1, 2]})
    centres = data.set_index("cluster")[["pv", "sparc"]]
    moved = pd.DataFrame(
        {"pv_a": [0.55], "sparc_a": [-1.8], "pv_b": [0.54], "sparc_b": [-1.81]}, index=pd.Index([2], name="cluster")
    )
    fig = skf.plot_time_scaled_plane(data, centres, moved, centres, zoom=((0.5, 0.6), (-1.9, -1.7)), mark_centre=1)
    left, right = fig.axes
    assert right.get_xlim() == (0.5, 0.6) and right.get_ylim() == (-1.9, -1.7)
    assert left.get_xlabel() == "peak speed PV (m/s)"
    auto = skf.plot_time_scaled_plane(data, centres, moved, centres)
    lo, hi = auto.axes[1].get_xlim()
    assert lo < 0.54 and hi > 0.55
    plt.close("all")


def test_robot_figures_restore_matplotlibs_interactive_mode():
    plt.ion()
    try:
        fig = skf.plot_simple6_figure()
        assert plt.isinteractive()
    finally:
        plt.ioff()
    fig = skf.plot_robot_pose()
    assert not plt.isinteractive()
    plt.close("all")
    assert isinstance(fig, plt.Figure) and sk.get_robot("simple6").name == "simple6"
