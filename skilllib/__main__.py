"""``python -m skilllib``: the command line of :mod:`skilllib.pipeline`."""

import sys

from .pipeline import main

if __name__ == "__main__":
    sys.exit(main())
