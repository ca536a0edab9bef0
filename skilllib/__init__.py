"""skilllib: smoothness-based prototypical task executions and their transfer to robot arms.

The companion library of the executable book reproducing Maldonado & Zetzsche (KI 2020).
"""
from .smoothness import sparc

__all__ = ["sparc"]
