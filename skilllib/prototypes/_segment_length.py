"""SPARC and the length of the segment it is measured on.

SPARC is built to ignore a movement's duration (the frequency axis is normalised by the band,
Balasubramanian et al. 2015), and on complete, finely sampled movements it does. The experiment's
segments are different: they run from onset to a contact that cuts the movement at speed, and at 60 Hz
they hold only one or a few dozen samples. A segment of T seconds resolves its spectrum only every
1/T Hz, so a band up to f_c holds about f_c T independent spectral values (a 0.2 s segment: 4 below
20 Hz), and the cut at contact spreads the spectrum over many of them; short segments therefore reach
the cap f_c more often, and their SPARC tracks their length (chapters 1-4 show it on the cohort).

The functions here measure that dependence and offer ways to look past it:

* :func:`sparc_by_length`: SPARC, its spread and the share of capped bands per range of segment samples;
* :func:`partial_correlation`: the correlation of two features with covariates (e.g. the duration)
  regressed out of both, so that "SPARC relates to X" can be told from "both relate to duration";
* :func:`variance_explained`: R^2 of a feature on each predictor alone and on all together
  (ordinary least squares), e.g. how much of SPARC the duration explains;
* :func:`with_covariates`: the covariates these functions are used with, added to a feature table:
  ``log_duration`` (log of the segment duration in s) and ``contact_ratio`` (contact speed / PV: how much
  of the bell the contact cuts off; 1 = contact at peak speed);
* :func:`adjusted_sparc`: SPARC with its least-squares dependence on covariates removed (the residual
  plus the mean), a smoothness feature uncorrelated with them across the given trials.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd

#: Bin edges (segment samples) of :func:`sparc_by_length`.
LENGTH_EDGES = (0, 12, 16, 20, 25, 1000)


def _design(data: pd.DataFrame, columns: Sequence[str]) -> np.ndarray:
    """[1, columns...] as a float matrix; ValueError on a missing column or a non-finite value."""
    missing = [c for c in columns if c not in data.columns]
    if missing:
        raise ValueError(f"data lacks column(s) {missing}")
    X = np.column_stack([np.ones(len(data)), *(data[c].to_numpy(dtype=float) for c in columns)])
    if not np.isfinite(X).all():
        raise ValueError(f"non-finite values in {list(columns)}: use valid trials only")
    return X


def _residual(y: np.ndarray, X: np.ndarray) -> np.ndarray:
    return y - X @ np.linalg.lstsq(X, y, rcond=None)[0]


def partial_correlation(data: pd.DataFrame, x: str, y: str, covariates: Sequence[str]) -> float:
    """Pearson correlation of columns ``x`` and ``y`` after regressing each on ``covariates``.

    Each is regressed with an intercept (ordinary least squares) and the residuals are kept. With no
    covariates it is the plain correlation. NaN when a residual is constant.

    Parameters
    ----------
    data : pandas.DataFrame
        The trials, with the columns.
    x : str
        The first column (text).
    y : str
        The second column (text).
    covariates : sequence of str
        The covariate columns (text).

    Returns
    -------
    float
        The partial correlation (dimensionless, -1 to 1), or NaN.
    """
    X = _design(data, covariates)
    rx, ry = (_residual(_design(data, [c])[:, 1], X) for c in (x, y))
    if np.std(rx) == 0 or np.std(ry) == 0:
        return float("nan")
    return float(np.corrcoef(rx, ry)[0, 1])


def variance_explained(data: pd.DataFrame, target: str, predictors: Sequence[str]) -> pd.Series:
    """R^2 of ``target`` on each predictor alone (linear, with an intercept) and on ``all`` of them.

    Parameters
    ----------
    data : pandas.DataFrame
        The trials, with the columns.
    target : str
        The target column (text).
    predictors : sequence of str
        The predictor columns (text).

    Returns
    -------
    pandas.Series
        R^2 per predictor and ``all`` (dimensionless, 0 to 1).
    """
    y = _design(data, [target])[:, 1]
    total = float(np.sum((y - y.mean()) ** 2))
    if total == 0:
        raise ValueError(f"{target} is constant: nothing to explain")
    r2 = {p: 1 - float(np.sum(_residual(y, _design(data, [p])) ** 2)) / total for p in predictors}
    r2["all"] = 1 - float(np.sum(_residual(y, _design(data, predictors)) ** 2)) / total
    return pd.Series(r2, name=f"R^2 of {target}")


def with_covariates(features: pd.DataFrame) -> pd.DataFrame:
    """A copy of a feature table (valid trials) with ``log_duration`` and ``contact_ratio`` added.

    ``log_duration`` is ln of the duration in s; ``contact_ratio`` the contact speed / PV (dimensionless).

    Parameters
    ----------
    features : pandas.DataFrame
        The feature table of :func:`skilllib.features.trial_features` (m/s, s).

    Returns
    -------
    pandas.DataFrame
        The valid trials with the two columns added (dimensionless).
    """
    out = features.copy()
    out["log_duration"] = np.log(out["duration"].astype(float))
    out["contact_ratio"] = out["contact_speed"].astype(float) / out["pv"].astype(float)
    return out


def adjusted_sparc(data: pd.DataFrame, covariates: Sequence[str] = ("log_duration",)) -> pd.Series:
    """SPARC minus its least-squares fit on ``covariates`` across the given trials, plus the mean SPARC.

    The fit has an intercept; see :func:`with_covariates` for ``log_duration`` and ``contact_ratio``.
    Keeps SPARC's scale and mean and removes the part the covariates predict linearly, so the result is
    uncorrelated with each of them over these trials. A descriptive adjustment of this data set (the fit
    is made on it), not a property of one movement.

    Parameters
    ----------
    data : pandas.DataFrame
        The trials, with ``sparc`` (dimensionless) and the covariates.
    covariates : sequence of str
        The covariate columns (text).

    Returns
    -------
    pandas.Series
        The adjusted SPARC of each trial (dimensionless).
    """
    y = _design(data, ["sparc"])[:, 1]
    return pd.Series(_residual(y, _design(data, covariates)) + y.mean(), index=data.index, name="sparc_adjusted")


def sparc_by_length(features: pd.DataFrame, edges: Sequence[int] = LENGTH_EDGES) -> pd.DataFrame:
    """SPARC per range of segment samples ``n`` (bins (a, b]) of the valid trials.

    Columns ``trials``, median and SD of SPARC and the share of bands capped by fc (``capped share``).

    Parameters
    ----------
    features : pandas.DataFrame
        The feature table of :func:`skilllib.features.trial_features` (``n`` in samples, ``sparc``
        dimensionless).
    edges : sequence of int
        The bin edges of ``n`` (samples).

    Returns
    -------
    pandas.DataFrame
        One row per bin: counts, SPARC median and SD, and the capped share (dimensionless).
    """
    f = features[features["status"] != "invalid"]
    bins = pd.cut(f["n"].astype(float), list(edges))
    g = f.groupby(bins, observed=True)
    out = pd.DataFrame(
        {
            "trials": g.size(),
            "SPARC median": g["sparc"].median(),
            "SPARC SD": g["sparc"].std(),
            "capped share": g["sparc_capped"].mean(),
        }
    )
    out.index = out.index.astype(str)
    return out.rename_axis("segment samples")
