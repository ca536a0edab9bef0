"""Values for results.json: the one coercion of numpy and pandas values into JSON values.

It lives here because the prototypes are the first step whose results go into results.json as they are
(``PrototypeResult.to_dict``, ``SparcSensitivity.to_dict``); the robot's summaries and the pipeline's
trial entries use it too. results.json is written with ``allow_nan=False``: NaN and infinities must
have become null before.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd


def json_value(v: Any) -> Any:
    """``v`` as a JSON value.

    A numpy scalar as the Python number (or bool, str) it holds, NaN, +-inf, None and pandas' NA as None
    (null); an array, list or tuple as a list and a mapping as a dict, their items converted alike;
    anything else unchanged (a Python int stays an int, a float a float).

    Parameters
    ----------
    v : Any
        The value (its unit is kept: the number is unchanged).

    Returns
    -------
    Any
        The JSON value.
    """
    if v is None or v is pd.NA:
        return None
    if isinstance(v, np.ndarray):
        v = v.tolist()
    if isinstance(v, (list, tuple)):
        return [json_value(x) for x in v]
    if isinstance(v, Mapping):
        return {k: json_value(x) for k, x in v.items()}
    if isinstance(v, np.generic):
        v = v.item()
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v
