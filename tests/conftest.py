"""Test-wide settings.

Hypothesis draws its examples from a fixed seed (``derandomize``) and keeps no example database, so
the same commit runs the same examples on every machine: a property test fails reproducibly or not at
all. Set ``HYPOTHESIS_PROFILE=explore`` to draw fresh random examples while developing.
"""

from __future__ import annotations

import os

from hypothesis import settings

settings.register_profile("repro", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repro"))
