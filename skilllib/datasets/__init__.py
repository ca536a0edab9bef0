"""The data shipped with skilllib: the book's synthetic cohort (:mod:`skilllib.cohort`, seed
:data:`skilllib.cohort.SEED`; documented in the repository's ``data/README.md``).

It is package data, so an installed skilllib (``pip install .``, not only an editable checkout) runs
``python -m skilllib run`` on it from any folder. In the repository ``data/cohort.csv`` links to it.
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path


def cohort_path() -> Path:
    """The synthetic cohort's CSV file.

    10 participants x 150 trials at 60 Hz; format :mod:`skilllib.recordings` (t in s, positions in m).

    Returns
    -------
    pathlib.Path
        The path of ``cohort.csv`` inside the installed package.
    """
    return Path(str(files(__name__) / "cohort.csv"))
