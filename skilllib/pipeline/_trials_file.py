"""The per-trial table of a run: inline in results.json, or ``trials.parquet`` beside it when the
trials are many.

Rule: up to :data:`TRIALS_IN_JSON_MAX` trials, ``results["trials"]`` lists every trial (ids, status,
reason, features; null when invalid). Above it the list would dominate results.json (41 MB for 150,000
trials) and take seconds to write and to read, so the run writes the whole feature table
(:data:`skilllib.features.FEATURE_COLUMNS`, one row per input trial in input order) to
``trials.parquet`` (Apache Parquet, pyarrow) and results.json says where it is:
``results["trials_file"] = "trials.parquet"``, with the counts per status in ``results["trial_counts"]``.
:func:`read_trials` gives the table of a run's folder either way.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pandas as pd

from ..features import FEATURE_COLUMNS
from ..prototypes import json_value

TRIALS_IN_JSON_MAX = 10_000  #: more trials than this: the table goes to trials.parquet
TRIALS_FILE = "trials.parquet"
#: The keys of each entry of results.json's trials list: the feature table's columns but the segment's
#: bookkeeping (``n``, ``t_onset``, ``t_contact``), in its order.
TRIAL_KEYS = tuple(c for c in FEATURE_COLUMNS if c not in ("n", "t_onset", "t_contact"))


def trials_section(features: pd.DataFrame) -> list[dict[str, Any]]:
    """One results.json entry per input trial: ids, status, reason and features (null when invalid)."""
    cols = list(TRIAL_KEYS)
    out = []
    for rec in features[cols].to_dict(orient="records"):
        entry = {c: json_value(rec[c]) for c in cols}
        if entry["status"] == "selected":
            entry["reason"] = None
        out.append(entry)
    return out


def in_json(features: pd.DataFrame) -> bool:
    """Whether the run lists its trials in results.json (see the module's rule)."""
    return len(features) <= TRIALS_IN_JSON_MAX


def trials_block(features: pd.DataFrame) -> dict[str, Any]:
    """The results.json keys for the trials: ``trials`` (the list) or ``trials_file`` and ``trial_counts``."""
    if in_json(features):
        return {"trials": trials_section(features)}
    counts = features["status"].value_counts()
    return {
        "trials_file": TRIALS_FILE,
        "trial_counts": {s: int(counts.get(s, 0)) for s in ("selected", "excluded", "invalid")},
    }


def write_trials(features: pd.DataFrame, folder: Path) -> Path:
    """The feature table as ``folder/trials.parquet`` (ids and texts as strings, ``n`` nullable integer,
    ``sparc_capped`` nullable boolean)."""
    path = Path(folder) / TRIALS_FILE
    table = features.copy()
    table.attrs = {}
    for c in ("participant", "trial", "status", "reason", "repairs"):
        table[c] = table[c].astype(str)
    table.to_parquet(path, index=False, engine="pyarrow")
    return path


def read_trials(folder: str | Path) -> pd.DataFrame:
    """The per-trial table of a run's output folder, from results.json's list or from trials.parquet.

    Parameters
    ----------
    folder : str or pathlib.Path
        The run's output folder, holding results.json (text).

    Returns
    -------
    pandas.DataFrame
        One row per input trial: ids, status, reason and features (PV in m/s, SPARC dimensionless, ...;
        :data:`skilllib.features.FEATURE_COLUMNS`).

    Raises
    ------
    FileNotFoundError
        When the folder holds no results.json, or not the trials.parquet it names.
    """
    folder = Path(folder)
    results = json.loads((folder / "results.json").read_text())
    if "trials_file" in results:
        return pd.read_parquet(folder / results["trials_file"], engine="pyarrow")
    return pd.DataFrame(results["trials"], columns=list(TRIAL_KEYS))
