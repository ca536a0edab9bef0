"""The example trials of the segmentation figure (skilllib.figures.segmentation_examples)."""

from __future__ import annotations

import pandas as pd

from skilllib.figures import segmentation_examples


def test_the_examples_are_the_median_and_least_smooth_selected_and_the_nearest_excluded():
    f = pd.DataFrame(
        {
            "participant": ["01", "01", "1", "2", "2", "3"],
            "trial": ["1", "2", "1", "1", "2", "1"],
            "status": ["selected", "selected", "selected", "excluded", "excluded", "invalid"],
            "sparc": [-1.5, -1.6, -2.0, -1.4, -1.7, float("nan")],
            "contact_speed": [0.5, 0.4, 0.6, 0.95, 0.25, float("nan")],
        }
    )
    got = segmentation_examples(f, speeds=(1.0, 0.2))
    # median SPARC of the selected (-1.6), the lowest (-2.0), then nearest 1.0 and 0.2 m/s
    assert got == [("01", "2"), ("1", "1"), ("2", "1"), ("2", "2")]
    assert all(isinstance(p, str) and isinstance(t, str) for p, t in got)  # ids stay text
