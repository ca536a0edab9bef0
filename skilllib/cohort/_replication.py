"""The book's headline results on many draws of the generative model: how much rests on one draw.

Every number of the book comes from one draw of :func:`skilllib.cohort.generate_cohort`, the seed
:data:`skilllib.cohort.SEED`, chosen by the seed survey (:func:`skilllib.cohort.seed_survey`) as the only
one of ten that meets every calibration target. :func:`draw_results` runs the book's headline analysis on
any draw in one call; :func:`replication_table` does so for many seeds (committed for seeds 0..23 as
package data, :data:`REPLICATION_CSV`; ``scripts/replicate_draws.py`` regenerates and checks it);
:func:`replication_summary` places the book's draw among the others, and :func:`within_draws` says
whether a published value lies within the draws' range.

Each quantity is computed as the chapter that reports it computes it (the columns, :data:`DRAW_QUANTITIES`):

* the selection, the silhouette sweep k = 2..16 on the raw (PV, SPARC) of the selected trials and the
  k = 6 fit (chapters 3 and 4: :func:`skilllib.prototypes.silhouette_sweep`,
  :func:`skilllib.cohort.calibration_table`);
* the k = 6 fit with SPARC's cut-off at 10 Hz against 20 Hz (chapter 6:
  :func:`skilllib.prototypes.sparc_sensitivity`, its adjusted Rand index) and the share of selected
  trials whose SPARC band the 20 Hz cap ended (``sparc_capped``);
* the normalised mutual information of the k = 6 clusters with the participants (chapter 7:
  :func:`skilllib.prototypes.participant_dependence`);
* the share of SPARC's variance explained by the contact ratio alone and by the generator's corrections
  alone (chapter 3, "What SPARC measures on these segments": :func:`skilllib.prototypes.with_covariates`,
  :func:`skilllib.prototypes.variance_explained`, corrected = ``truth.n_corrections > 0``);
* the contact speed's estimators against the generator's truth over all trials (chapter 3, "What 60 Hz can
  tell": :func:`skilllib.features.contact_speed_estimates`, :func:`skilllib.features.estimate_errors`): for
  the feature table's last sample and the ``"midpoint"`` and ``"crossing"`` estimates, the bias, SD, RMSE,
  95th percentile and largest absolute error (m/s), the selection flips against the truth, and the trials in
  the selection window by each and by the truth;
* per arm of :data:`skilllib.robot.ROBOT_NAMES`, how many of the six prototypes are feasible as recorded
  under the velocity limits alone and under every limit the arm carries (chapters 5 and 9, the pipeline:
  :func:`skilllib.robot.transfer`, :func:`skilllib.robot.assess`).
"""

from __future__ import annotations

import io
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import pandas as pd

from ..features import (
    CONTACT_WINDOW,
    Lowpass,
    contact_speed_estimates,
    estimate_errors,
    run_lowpass,
    segment,
    select,
    trial_features,
)
from ..prototypes import (
    participant_dependence,
    silhouette_sweep,
    sparc_sensitivity,
    variance_explained,
    with_covariates,
)
from ..recordings import Recordings, format_recordings, recordings_from_frame
from ..robot import ROBOT_NAMES, assess, get_robot, transfer
from ._calibration import calibration_table, calibration_values
from ._model import SEED, CohortModel, generate_cohort

#: :func:`replication_table` of seeds 0..23 with the default model, as committed (``scripts/replicate_draws.py``
#: writes it; ``--check`` recomputes it and compares).
REPLICATION_CSV = Path(__file__).with_name("replication.csv")
#: The number of clusters of the book's headline fit (the paper's k = 6).
K = 6
#: The SPARC cut-off the sensitivity ARI compares with the book's 20 Hz (Hz; chapter 6).
FC_OTHER = 10.0
#: The contact-speed estimators compared with the truth (column prefix: the method of
#: :func:`skilllib.features.contact_speed_estimates`; ``sample`` is the feature table's last sample).
CONTACT_METHODS = {"sample": "last sample", "midpoint": "midpoint", "crossing": "crossing"}
#: The error measures of each estimator (column suffix: what :func:`skilllib.features.estimate_errors` reports).
CONTACT_MEASURES = {
    "bias": "bias",
    "sd": "SD",
    "rmse": "RMSE",
    "p95": "95th pct |error|",
    "max": "max |error|",
    "flips": "flips",
}


def _quantities() -> dict[str, str]:
    q = {
        "n_selected": "trials selected (of 1500)",
        "n_valid_k": "valid k of 2..16",
        "silhouette_k6": "average silhouette, k = 6",
    }
    q.update({f"centre_pv_{i}": f"k = 6 centre {i} PV (m/s)" for i in range(1, K + 1)})
    q.update({f"centre_sparc_{i}": f"k = 6 centre {i} SPARC" for i in range(1, K + 1)})
    q.update(
        {
            "ari_fc10": "ARI, fc 10 vs 20 Hz (k = 6)",
            "capped_fraction": "share of bands ended by the 20 Hz cap",
            "nmi_participants": "NMI(cluster, participant)",
            "r2_contact_ratio": "R² of SPARC, contact ratio alone",
            "r2_corrections": "R² of SPARC, corrections alone",
        }
    )
    names = {"simple6": "Simple6", "ur5": "UR5", "puma560": "Puma 560", "panda": "Panda"}
    q.update({f"feasible_velocity_{a}": f"{names.get(a, a)}: feasible of 6, velocity limits" for a in ROBOT_NAMES})
    q.update({f"feasible_{a}": f"{names.get(a, a)}: feasible of 6, every limit" for a in ROBOT_NAMES})
    for m, label in CONTACT_METHODS.items():
        for k, measure in CONTACT_MEASURES.items():
            unit = "" if k == "flips" else " (m/s)"
            q[f"contact_{m}_{k}"] = f"contact speed, {label}: {measure}{unit}"
        q[f"in_window_{m}"] = f"trials in the 0.3-0.7 m/s window, {label}"
    q["in_window_true"] = "trials in the 0.3-0.7 m/s window, true contact speed"
    q["all_targets"] = "every calibration target met"
    return q


#: The columns of :func:`draw_results` and :func:`replication_table` (besides the seed) and what each is, with
#: its unit: counts of trials, k and prototypes; PV in m/s; SPARC, silhouette, ARI, NMI, R^2 and shares
#: dimensionless; ``all_targets`` a bool (:func:`skilllib.cohort.calibration_table`). Centres are numbered
#: 1..6 from the slowest to the fastest PV.
DRAW_QUANTITIES: dict[str, str] = _quantities()


def draw_recordings(seed: int, model: CohortModel | None = None) -> tuple[Recordings, pd.DataFrame]:
    """One draw of the cohort as the book reads it, and its ground truth.

    The cohort of ``seed`` goes through the CSV writer's rounding (:func:`skilllib.recordings.format_recordings`)
    exactly as :func:`skilllib.cohort.seed_survey` does, so that the book's seed gives ``data/cohort.csv``.

    Parameters
    ----------
    seed : int
        The seed of :func:`skilllib.cohort.generate_cohort` (dimensionless).
    model : CohortModel or None
        The population parameters; None: the defaults.

    Returns
    -------
    tuple of (Recordings, pandas.DataFrame)
        The recordings (t in s, positions in m) and the generator's per-trial truth (times in s, speeds in m/s,
        ``n_corrections`` a count).
    """
    cohort = generate_cohort(int(seed), model)
    text = format_recordings(cohort.frame)
    return recordings_from_frame(pd.read_csv(io.StringIO(text))), cohort.truth


def draw_results(seed: int, model: CohortModel | None = None) -> dict[str, Any]:
    """The book's headline analysis on one draw of the generative model, in one call.

    Generates the cohort of ``seed`` (:func:`draw_recordings`), computes every trial's features with the book's
    SPARC parameters (fc 20 Hz) and the paper's selection, and returns the quantities of
    :data:`DRAW_QUANTITIES`, each computed as its chapter does (module docstring). For
    :data:`skilllib.cohort.SEED` they are the book's printed numbers. About 5 s on a free core, most of it
    generating and reading the cohort; the robot part takes under a second.

    Parameters
    ----------
    seed : int
        The seed of :func:`skilllib.cohort.generate_cohort` (dimensionless).
    model : CohortModel or None
        The population parameters; None: the defaults.

    Returns
    -------
    dict
        ``seed`` and one entry per key of :data:`DRAW_QUANTITIES`: counts (int), PV (m/s), SPARC, silhouette,
        ARI, NMI, R^2 and shares (dimensionless float), ``all_targets`` (bool).

    Raises
    ------
    ValueError
        When the draw selects too few trials for the k = 2..16 sweep.
    """
    rec, truth = draw_recordings(seed, model)
    filt = run_lowpass(rec, "auto")
    feats = trial_features(rec, lowpass=filt)
    sel = select(feats)
    sweep = silhouette_sweep(sel, 2, 16, scaling="raw")
    cal = calibration_values(feats, sweep)
    fit = sweep.results[K]
    centres = fit.centres.sort_values("pv")
    # chapter 6: the k = 6 fit at fc 10 Hz against the book's 20 Hz (the 10 Hz sweep only needs k = 6)
    sens = sparc_sensitivity(
        rec, [{"fc": 20.0}, {"fc": FC_OTHER}], k=K, reference=(feats, sweep), lowpass=filt, k_range=(K, K)
    )
    # chapter 3: SPARC against the contact ratio and the generator's corrections
    cov = with_covariates(sel).merge(truth[["participant", "trial", "n_corrections"]], on=["participant", "trial"])
    cov = cov.assign(corrected=(cov["n_corrections"] > 0).astype(float))
    r2 = variance_explained(cov, "sparc", ["contact_ratio", "corrected"])
    out: dict[str, Any] = {
        "seed": int(seed),
        "n_selected": int(cal["n_selected"]),
        "n_valid_k": len(cal["valid_ks"]),
        "silhouette_k6": float(cal["silhouette_k6"]),
        **{f"centre_pv_{i}": float(v) for i, v in enumerate(centres["pv"], start=1)},
        **{f"centre_sparc_{i}": float(v) for i, v in enumerate(centres["sparc"], start=1)},
        "ari_fc10": float(sens.comparison()["ARI"].iloc[0]),
        "capped_fraction": float(sel["sparc_capped"].astype(bool).mean()),
        "nmi_participants": participant_dependence(fit.labels, sel["participant"], n_permutations=1).nmi,
        "r2_contact_ratio": float(r2["contact_ratio"]),
        "r2_corrections": float(r2["corrected"]),
    }
    out.update(_feasibility(rec, fit.prototypes, filt))
    out.update(_contact_errors(rec, feats, truth))
    out["all_targets"] = bool(calibration_table(feats, sweep)["met"].all())
    return out


def _contact_errors(rec: Recordings, feats: pd.DataFrame, truth: pd.DataFrame) -> dict[str, float]:
    """Per contact-speed estimator, its errors against the truth (m/s; flips and counts of trials)."""
    keys = ["participant", "trial"]
    true = feats[keys].merge(truth[[*keys, "contact_speed"]], on=keys, how="left")["contact_speed"].to_numpy()
    estimates = {"sample": feats["contact_speed"].to_numpy(dtype=float)}
    for m in ("midpoint", "crossing"):
        estimates[m] = contact_speed_estimates(rec, feats, method=m)["contact_speed"].to_numpy(dtype=float)
    lo, hi = CONTACT_WINDOW
    out: dict[str, float] = {}
    for m, est in estimates.items():
        err = estimate_errors(est, true)
        out.update({f"contact_{m}_{k}": float(err[measure]) for k, measure in CONTACT_MEASURES.items()})
        out[f"in_window_{m}"] = int(((est >= lo) & (est <= hi)).sum())
    out["in_window_true"] = int(((true >= lo) & (true <= hi)).sum())
    return out


def _feasibility(rec: Recordings, prototypes: pd.DataFrame, lowpass: Lowpass) -> dict[str, int]:
    """Per arm: prototypes feasible under the velocity limits alone and under every limit (counts)."""
    segs = [segment(rec, p.participant, p.trial, lowpass=lowpass) for p in prototypes.itertuples()]
    velocity, every = {}, {}
    for name in ROBOT_NAMES:
        arm = get_robot(name)
        results = [transfer(arm, s, cluster=c) for c, s in enumerate(segs)]
        verdicts = assess(arm.robot, results, arm.dynamic_limits)
        velocity[f"feasible_velocity_{name}"] = sum(bool(r.feasible) for r in results)
        every[f"feasible_{name}"] = sum(bool(a.dynamics.feasible) for a in verdicts)
    return {**velocity, **every}


def replication_table(
    seeds: Iterable[int],
    model: CohortModel | None = None,
    *,
    progress: Callable[[list[int], str], Iterable[int]] | None = None,
) -> pd.DataFrame:
    """:func:`draw_results` for each seed, one row per seed.

    Parameters
    ----------
    seeds : iterable of int
        The seeds (dimensionless).
    model : CohortModel or None
        The population parameters; None: the defaults.
    progress : callable or None
        ``progress(seeds, description)`` may wrap the loop over seeds (e.g. tqdm).

    Returns
    -------
    pandas.DataFrame
        Index ``seed``; the columns of :data:`DRAW_QUANTITIES` (units there).
    """
    seeds = [int(s) for s in seeds]
    loop = progress(seeds, "draws") if progress is not None else seeds
    rows = [draw_results(s, model) for s in loop]
    out = pd.DataFrame(rows, columns=["seed", *DRAW_QUANTITIES]).set_index("seed")
    return out


def read_replication(path: str | Path = REPLICATION_CSV) -> pd.DataFrame:
    """The committed :func:`replication_table` (or one written by ``scripts/replicate_draws.py``).

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file; default :data:`REPLICATION_CSV`.

    Returns
    -------
    pandas.DataFrame
        Index ``seed``; the columns of :data:`DRAW_QUANTITIES` (units there).
    """
    return pd.read_csv(path, index_col="seed")


def _numeric(table: pd.DataFrame, columns: Sequence[str] | None) -> pd.DataFrame:
    cols = list(columns) if columns is not None else [c for c in table.columns if table[c].dtype != bool]
    missing = [c for c in cols if c not in table.columns]
    if missing:
        raise ValueError(f"no column(s) {missing} in the table")
    return table[cols].astype(float)


def replication_summary(table: pd.DataFrame, seed: int = SEED, columns: Sequence[str] | None = None) -> pd.DataFrame:
    """Each quantity over the draws, and where the book's draw lies among them.

    Percentiles are numpy's linear ones. The rank is 1 for the lowest value and ``draws`` for the highest;
    tied draws share the mean of their ranks (so a quantity equal in every draw ranks (1 + draws) / 2).

    Parameters
    ----------
    table : pandas.DataFrame
        A :func:`replication_table` (index ``seed``), with the row of ``seed``.
    seed : int
        The book's draw (dimensionless); default :data:`skilllib.cohort.SEED`.
    columns : sequence of str or None
        The quantities (text); None: every column that is not boolean.

    Returns
    -------
    pandas.DataFrame
        One row per quantity, in the quantity's unit (:data:`DRAW_QUANTITIES`): ``median``, ``mean``, ``sd``
        (sample SD, ddof 1), ``min``, ``p10``, ``p90``, ``max``, ``book`` (the value of ``seed``), ``rank``
        (dimensionless, 1 = lowest) and ``draws`` (count).

    Raises
    ------
    ValueError
        When ``seed`` is not a row of the table or a column is missing.
    """
    if seed not in table.index:
        raise ValueError(f"seed {seed} is not a row of the table (seeds {list(table.index)})")
    x = _numeric(table, columns)
    ranks = x.rank(method="average")
    out = pd.DataFrame(
        {
            "median": x.median(),
            "mean": x.mean(),
            "sd": x.std(ddof=1),
            "min": x.min(),
            "p10": x.quantile(0.1),
            "p90": x.quantile(0.9),
            "max": x.max(),
            "book": x.loc[seed],
            "rank": ranks.loc[seed],
            "draws": x.notna().sum(),
        }
    )
    out.index.name = "quantity"
    return out


def within_draws(table: pd.DataFrame, paper: Mapping[str, float], seed: int = SEED) -> pd.DataFrame:
    """A published value against the draws: does it lie within the model's spread?

    Parameters
    ----------
    table : pandas.DataFrame
        A :func:`replication_table` (index ``seed``).
    paper : mapping of str to float
        The published value of some quantities, by column name (m/s for speeds, dimensionless otherwise:
        the units of :data:`DRAW_QUANTITIES`).
    seed : int
        The book's draw (dimensionless); default :data:`skilllib.cohort.SEED`.

    Returns
    -------
    pandas.DataFrame
        One row per quantity of ``paper``: ``paper``, ``book`` (the value of ``seed``), ``median``, ``min``,
        ``max`` (the quantity's unit), ``within`` (bool: min <= paper <= max over the draws) and ``sds``
        ((paper - mean) / SD of the draws, dimensionless; NaN when the draws do not vary).
    """
    s = replication_summary(table, seed, columns=list(paper))
    p = pd.Series({k: float(v) for k, v in paper.items()})
    sd = s["sd"].where(s["sd"] > 0)
    return pd.DataFrame(
        {
            "paper": p,
            "book": s["book"],
            "median": s["median"],
            "min": s["min"],
            "max": s["max"],
            "within": (s["min"] <= p) & (p <= s["max"]),
            "sds": (p - s["mean"]) / sd,
        }
    ).rename_axis("quantity")
