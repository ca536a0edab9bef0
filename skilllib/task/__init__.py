"""The task as data: reading, segmentation, selection, features, SPARC, robot and limits in one object.

:class:`Task` (the paper's task by default, :data:`PAPER_TASK`), :func:`load_task` (a TOML task file,
a shipped preset such as ``paper``, or the ``task`` block of a results.json) and
:meth:`Task.with_options` (command-line options over a task file). The rules' texts
(``speed:5%``, ``offset``, ``height-above:0.6``, ...) are those of :mod:`skilllib.features`.
"""

import lazy_loader as _lazy

__getattr__, __dir__, __all__ = _lazy.attach(
    __name__,
    submod_attrs={
        "_task": ["KEYS", "load_task", "PAPER_TASK", "parse_setting", "preset_names", "Task", "TaskError"],
    },
)
