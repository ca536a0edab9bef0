"""The task as data: a lab's whole setting in one object, one TOML file, one block of results.json.

A :class:`Task` holds how the recordings are read (``[read]``), where each movement starts and ends and
whether a recording holds several (``[segment]``), which trials are clustered (``[select]``), on which
features and how (``[cluster]``), SPARC's parameters (``[sparc]``) and the robot with its limits
(``[robot]``). The paper's task is the default and the shipped preset ``paper``
(``skilllib/task/presets/paper.toml``); :func:`load_task` reads a TOML file, a preset name, or the
``task`` block of a ``results.json`` (so that ``--task results.json`` runs the same analysis again).

A key the task does not know, or a value it cannot use, is refused with the file, its line and the
values allowed (:class:`TaskError`).
"""

from __future__ import annotations

import json
import math
import re
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Any

from ..features import (
    DEFAULT_HOLD_S,
    PAPER_END,
    PAPER_FEATURES,
    PAPER_SELECTION,
    PAPER_START,
    EndRule,
    RuleError,
    SelectionError,
    StartRule,
    Window,
    parse_end,
    parse_features,
    parse_selection,
    parse_start,
)

PRESETS_DIR = Path(__file__).with_name("presets")

#: The keys of each section of a task file and what each takes (the text of the allowed values).
KEYS: dict[str, dict[str, str]] = {
    "read": {
        "columns": "a table of the file's column names and the book's (time = \"t\", ...)",
        "units": "m, cm or mm",
        "time_unit": "s, ms or us",
        "sep": "',', ';' or 'tab'",
        "up_axis": "x, y, z, -x, -y or -z",
        "marker": "a marker name, several separated by commas, or a template like '{hand}FTP'",
        "name_pattern": "a regular expression with groups participant and trial",
        "contact_channel": "an analog channel or event name",
        "contact_threshold": "a number (the channel's unit)",
        "contact_below": "true or false",
        "contact_height": "a height in m",
        "max_gap": "a time in s",
        "fill": "cubic or linear",
    },
    "segment": {
        "start": "speed:0.05, speed:5% or event:LABEL",
        "end": "contact, offset, offset:0.05, offset:5%, event:LABEL, height-above:M or height-below:M",
        "hold": "a time in s (the offset's hold and the shortest rest between movements)",
        "split": "true or false (several movements per recording)",
        "lowpass": "auto, none or a cut-off in Hz",
    },
    "select": {"windows": "'none' or a list of 'FEATURE=LO:HI' (e.g. ['contact_speed=0.3:0.7'])"},
    "cluster": {
        "features": "a list of features, e.g. ['pv', 'sparc']",
        "k": "an integer of at least 2",
        "scaling": "raw or standard",
        "seed": "an integer from 0 to 4294967295",
    },
    "sparc": {
        "fc": "a frequency in Hz",
        "amp_th": "a fraction between 0 and 1",
        "padlevel": "an integer from 0 to 10",
        "sensitivity": "a list of settings like 'fc=10' or 'fc=10,amp_th=0.1'",
    },
    "robot": {
        "name": "simple6, ur5, puma560, panda, ...",
        "qd_max": "joint velocity limits in rad/s: one number or one per joint",
        "qdd_max": "joint acceleration limits in rad/s^2: one number or one per joint",
        "tau_max": "joint torque limits in N m: one number or one per joint",
    },
}
TOP_KEYS = {"name": "a short name of the task (text)", "description": "what the task is (text)"}


class TaskError(ValueError):
    """A task file or task setting that cannot be used: names the file, its line, the key and the values
    allowed."""


def _line_of(text: str, section: str | None, key: str | None) -> int | None:
    """The 1-based line of ``key`` in ``[section]`` of a TOML text (of the section header when key is
    None), or None when it cannot be found (an inline table, a dotted key)."""
    current = None
    for i, line in enumerate(text.splitlines(), start=1):
        s = line.strip()
        m = re.fullmatch(r"\[\s*([A-Za-z0-9_.-]+)\s*\](\s*#.*)?", s)
        if m:
            current = m.group(1)
            if key is None and current == section:
                return i
            continue
        if key is not None and current == section and re.match(rf"[\"']?{re.escape(key)}[\"']?\s*=", s):
            return i
    return None


@dataclass(frozen=True)
class Task:
    """A discrete-movement task: reading, segmentation, selection, features, SPARC, robot and limits.

    The defaults are the paper's (:data:`PAPER_TASK`). Units: ``hold`` in s, ``lowpass`` in Hz (or
    ``"auto"``/``"none"``), ``fc`` in Hz, ``qd_max`` rad/s, ``qdd_max`` rad/s^2, ``tau_max`` N m, heights in
    m (in the rules).

    Attributes
    ----------
    name : str
        A short name (text).
    description : str
        What the task is (text).
    read : dict
        The reading options of :func:`skilllib.recordings.load_recordings` that were set (``max_gap`` in s).
    start : StartRule
        Where a movement starts.
    end : EndRule
        Where it ends (``hold_s`` in s).
    split : bool
        Whether a recording holds several movements (split at rests or events).
    lowpass : str or float
        The positions' low-pass filter: ``"auto"``, ``"none"`` or a cut-off (Hz).
    selection : tuple of Window or None
        The selection windows; ``()`` selects every valid trial; None: the paper's window when the end is
        contact, none otherwise.
    features : tuple of str
        The clustering features (columns of the feature table).
    k : int
        The number of clusters (dimensionless).
    scaling : str
        ``"raw"`` or ``"standard"``.
    seed : int
        K-means' random_state (dimensionless).
    fc, amp_th : float
        SPARC's maximum cut-off (Hz) and amplitude threshold (fraction).
    padlevel : int
        SPARC's zero-padding level (dimensionless).
    sensitivity : tuple of dict
        Other SPARC settings to compare with.
    robot : str
        The arm's name.
    qd_max, qdd_max, tau_max : float, tuple of float or None
        Joint limits (rad/s, rad/s^2, N m); None: the arm's.
    """

    name: str = "paper"
    description: str = ""
    read: Mapping[str, Any] = field(default_factory=dict)
    start: StartRule = PAPER_START
    end: EndRule = PAPER_END
    split: bool = False
    lowpass: str | float = "auto"
    selection: tuple[Window, ...] | None = None
    features: tuple[str, ...] = PAPER_FEATURES
    k: int = 6
    scaling: str = "raw"
    seed: int = 0
    fc: float = 20.0
    amp_th: float = 0.05
    padlevel: int = 4
    sensitivity: tuple[Mapping[str, float], ...] = ()
    robot: str = "simple6"
    qd_max: float | tuple[float, ...] | None = None
    qdd_max: float | tuple[float, ...] | None = None
    tau_max: float | tuple[float, ...] | None = None

    @property
    def hold(self) -> float:
        """The offset's hold and the shortest rest between movements (s)."""
        return self.end.hold_s

    def resolved_selection(self) -> tuple[Window, ...]:
        """The selection windows the run applies: the paper's window when none was set and the end is
        contact; no window (every valid trial) when none was set and the end is something else."""
        if self.selection is not None:
            return self.selection
        return PAPER_SELECTION if self.end.kind == "contact" else ()

    def to_dict(self) -> dict[str, Any]:
        """The task as nested sections (TOML and JSON compatible; unset options left out), as results.json
        records it and :func:`load_task` reads it back."""
        read = {k: (dict(v) if isinstance(v, Mapping) else v) for k, v in self.read.items() if v is not None}
        sel = self.resolved_selection()

        def limit(v):
            return list(v) if isinstance(v, tuple) else v

        robot = {"name": self.robot}
        robot.update({k: limit(getattr(self, k)) for k in ("qd_max", "qdd_max", "tau_max") if getattr(self, k)})
        out: dict[str, Any] = {"name": self.name}
        if self.description:
            out["description"] = self.description
        out |= {
            "read": read,
            "segment": {
                "start": self.start.text(),
                "end": self.end.text(),
                "hold": self.end.hold_s,
                "split": self.split,
                "lowpass": self.lowpass,
            },
            "select": {"windows": [w.text() for w in sel] if sel else "none"},
            "cluster": {"features": list(self.features), "k": self.k, "scaling": self.scaling, "seed": self.seed},
            "sparc": {"fc": self.fc, "amp_th": self.amp_th, "padlevel": self.padlevel},
            "robot": robot,
        }
        if self.sensitivity:
            out["sparc"]["sensitivity"] = [",".join(f"{k}={v:g}" for k, v in s.items()) for s in self.sensitivity]
        return out

    def to_toml(self) -> str:
        """The task as the text of a TOML task file (:meth:`to_dict`)."""
        d = self.to_dict()
        lines = [f"{k} = {_toml_value(d[k])}" for k in TOP_KEYS if k in d]
        for section in KEYS:
            lines += ["", f"[{section}]"]
            for k, v in d.get(section, {}).items():
                lines.append(f"{k} = {_toml_value(v)}")
        return "\n".join(lines) + "\n"

    def with_options(self, **options: Any) -> Task:
        """A copy with the options given (None: unchanged), each checked as in a task file.

        Parameters
        ----------
        \\*\\*options : Any
            Any of the keys of :data:`KEYS` (``start``, ``end``, ``select``/``windows``, ``features``, ``k``,
            ``robot``/``name``, ``read`` keys, ...), as text or values; ``hold`` in s.

        Returns
        -------
        Task
            The task with those options.
        """
        sections: dict[str, dict[str, Any]] = {}
        for key, value in options.items():
            if value is None:
                continue
            key = {"select": "windows", "robot": "name"}.get(key, key)
            section = next((s for s, keys in KEYS.items() if key in keys), None)
            if section is None:
                raise TaskError(f"unknown task option {key!r}")
            sections.setdefault(section, {})[key] = value
        return _apply(self, sections, source="the command line", text="")


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v) if isinstance(v, int) or math.isfinite(v) else json.dumps(str(v))
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, Mapping):
        return "{ " + ", ".join(f"{json.dumps(str(k))} = {_toml_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, Sequence):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {v!r} in TOML")


#: The paper's task (the shipped preset ``paper``).
PAPER_TASK = Task(
    name="paper",
    description="Touch task: onset at 0.05 m/s, end at contact, contact speed 0.3-0.7 m/s, K-means on (PV, SPARC)",
)


def _where(source: str, text: str, section: str | None, key: str | None) -> str:
    line = _line_of(text, section, key) if text else None
    place = f"{source}, line {line}" if line else source
    name = f"[{section}] {key}" if section and key else (key or f"[{section}]")
    return f"{place}: {name}"


def _number(v: Any, where: str, allowed: str, *, integer: bool = False, positive: bool = True) -> Any:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or (integer and not isinstance(v, int)):
        if isinstance(v, str) and not integer:
            try:
                v = float(v)
            except ValueError:
                raise TaskError(f"{where} = {v!r}: use {allowed}") from None
        else:
            raise TaskError(f"{where} = {v!r}: use {allowed}")
    if not math.isfinite(v) or (positive and v <= 0):
        raise TaskError(f"{where} = {v!r}: use {allowed}")
    return v


def _limits(v: Any, where: str, allowed: str) -> float | tuple[float, ...]:
    if isinstance(v, (list, tuple)):
        if not v:
            raise TaskError(f"{where} = []: use {allowed}")
        return tuple(float(_number(x, where, allowed)) for x in v)
    return float(_number(v, where, allowed))


def _apply(task: Task, sections: Mapping[str, Any], *, source: str, text: str) -> Task:
    """``task`` with the values of ``sections`` (a parsed task file or command-line options)."""
    changes: dict[str, Any] = {}
    for k in sections:
        if k in TOP_KEYS:
            if not isinstance(sections[k], str):
                raise TaskError(f"{_where(source, text, None, k)} = {sections[k]!r}: use {TOP_KEYS[k]}")
            changes[k] = sections[k]
        elif k not in KEYS:
            allowed = ", ".join([*TOP_KEYS, *(f"[{s}]" for s in KEYS)])
            raise TaskError(f"{_where(source, text, k, None)}: unknown section {k!r}; the sections are {allowed}")
        elif not isinstance(sections[k], Mapping):
            raise TaskError(f"{_where(source, text, None, k)}: {k} must be a section [{k}]")
    read = dict(task.read)
    start, end = task.start, task.end
    hold = task.end.hold_s
    for section, values in sections.items():
        if section in TOP_KEYS:
            continue
        for key, v in values.items():
            where = _where(source, text, section, key)
            allowed = KEYS[section].get(key)
            if allowed is None:
                raise TaskError(f"{where}: unknown key; [{section}] takes {', '.join(KEYS[section])}")
            changes.update(_value(section, key, v, where, allowed, read))
            if section == "segment" and key == "hold":
                hold = float(_number(v, where, allowed, positive=False))
                if hold < 0:
                    raise TaskError(f"{where} = {v!r}: use {allowed}")
    try:
        if "start" in changes:
            start = parse_start(changes.pop("start"))
        end_text = changes.pop("end", None)
        end = parse_end(end_text, hold) if end_text is not None else replace(end, hold_s=hold)
    except RuleError as e:
        key = "start" if "start" in str(e) and "not a start" in str(e) else "end"
        raise TaskError(f"{_where(source, text, 'segment', key)}: {e}") from None
    if start.kind == "event" and end.kind == "offset" and end.threshold is None:
        raise TaskError(
            f"{_where(source, text, 'segment', 'end')}: 'offset' takes the start's speed threshold, but the start "
            f"is an event: give the offset's threshold (offset:0.05 or offset:5%)"
        )
    changes.pop("hold", None)
    return replace(task, read=read, start=start, end=end, **changes)


def _value(section: str, key: str, v: Any, where: str, allowed: str, read: dict[str, Any]) -> dict[str, Any]:
    """The Task fields one key of a section sets (``read`` keys go into ``read``)."""

    def choice(options: Sequence[str]) -> str:
        if not isinstance(v, str) or v.strip() not in options:
            raise TaskError(f"{where} = {v!r}: use {allowed}")
        return v.strip()

    if section == "read":
        if key in ("units",):
            read[key] = choice(("m", "cm", "mm"))
        elif key == "time_unit":
            read[key] = choice(("s", "ms", "us"))
        elif key == "up_axis":
            read[key] = choice(("x", "y", "z", "-x", "-y", "-z"))
        elif key == "fill":
            read[key] = choice(("cubic", "linear"))
        elif key == "sep":
            s = v if isinstance(v, str) else ""
            s = {"tab": "\t", "\\t": "\t"}.get(s, s)
            if s not in (",", ";", "\t"):
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            read[key] = s
        elif key == "columns":
            if not isinstance(v, Mapping) or not all(isinstance(a, str) and isinstance(b, str) for a, b in v.items()):
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            read[key] = dict(v)
        elif key == "contact_below":
            if not isinstance(v, bool):
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            read[key] = v
        elif key in ("contact_threshold", "contact_height"):
            read[key] = float(_number(v, where, allowed, positive=False))
        elif key == "max_gap":
            read[key] = float(_number(v, where, allowed, positive=False))
            if read[key] < 0:
                raise TaskError(f"{where} = {v!r}: use {allowed}")
        else:  # marker, name_pattern, contact_channel: text
            if not isinstance(v, str) or not v.strip():
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            if key == "name_pattern":
                try:
                    re.compile(v)
                except re.error as e:
                    raise TaskError(f"{where} = {v!r}: not a regular expression ({e})") from None
            read[key] = v
        return {}
    if section == "segment":
        if key in ("start", "end"):
            if not isinstance(v, str):
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            try:
                (parse_start if key == "start" else parse_end)(v)
            except RuleError as e:
                raise TaskError(f"{where}: {e}") from None
            return {key: v}
        if key == "hold":
            return {}
        if key == "split":
            if not isinstance(v, bool):
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            return {"split": v}
        if key == "lowpass":
            if isinstance(v, str) and v.strip().lower() in ("auto", "none"):
                return {"lowpass": v.strip().lower()}
            return {"lowpass": float(_number(v, where, allowed))}
    if section == "select":
        items = v if isinstance(v, (list, tuple)) else [v] if isinstance(v, str) else None
        if items is None or not all(isinstance(x, str) for x in items):
            raise TaskError(f"{where} = {v!r}: use {allowed}")
        try:
            return {"selection": parse_selection(items)}
        except SelectionError as e:
            raise TaskError(f"{where}: {e}") from None
    if section == "cluster":
        if key == "features":
            if not isinstance(v, (str, list, tuple)):
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            try:
                return {"features": parse_features(v)}
            except SelectionError as e:
                raise TaskError(f"{where}: {e}") from None
        if key == "k":
            k = _number(v, where, allowed, integer=True)
            if k < 2:
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            return {"k": int(k)}
        if key == "scaling":
            return {"scaling": choice(("raw", "standard"))}
        if key == "seed":
            s = _number(v, where, allowed, integer=True, positive=False)
            if not 0 <= s <= 2**32 - 1:
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            return {"seed": int(s)}
    if section == "sparc":
        if key == "fc":
            return {"fc": float(_number(v, where, allowed))}
        if key == "amp_th":
            a = float(_number(v, where, allowed))
            if not a < 1:
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            return {"amp_th": a}
        if key == "padlevel":
            p = _number(v, where, allowed, integer=True, positive=False)
            if not 0 <= p <= 10:
                raise TaskError(f"{where} = {v!r}: use {allowed}")
            return {"padlevel": int(p)}
        if key == "sensitivity":
            items = v if isinstance(v, (list, tuple)) else [v]
            try:
                return {"sensitivity": tuple(x if isinstance(x, Mapping) else parse_setting(x) for x in items)}
            except (TypeError, ValueError) as e:
                raise TaskError(f"{where}: {e}") from None
    if section == "robot":
        if key == "name":
            from ..robot import ROBOT_NAMES

            return {"robot": choice(tuple(ROBOT_NAMES))}
        return {key: _limits(v, where, allowed)}
    raise TaskError(f"{where}: unknown key")  # pragma: no cover - KEYS lists every key handled above


def parse_setting(text: str) -> dict[str, float]:
    """``fc=10`` or ``fc=10,amp_th=0.1,padlevel=4`` (a bare number is fc) -> SPARC parameters (fc in Hz).

    Parameters
    ----------
    text : str
        The setting (text).

    Returns
    -------
    dict of str to float
        Some of ``fc`` (Hz), ``amp_th`` and ``padlevel`` (dimensionless).
    """
    if not isinstance(text, str):
        raise TypeError(f"a SPARC setting is a text like 'fc=10', got {text!r}")
    out: dict[str, float] = {}
    for part in text.split(","):
        key, sep, value = part.partition("=")
        key, value = (key.strip(), value.strip()) if sep else ("fc", key.strip())
        key = key.replace("-", "_")
        if key not in ("fc", "amp_th", "padlevel"):
            raise ValueError(f"{text!r}: unknown SPARC parameter {key!r} (use fc, amp_th, padlevel)")
        try:
            out[key] = int(value) if key == "padlevel" else float(value)
        except ValueError:
            raise ValueError(f"{text!r}: {key} = {value!r} is not a number") from None
    return out


def preset_names() -> list[str]:
    """The names of the shipped task presets.

    Returns
    -------
    list of str
        The presets' names (text: ``paper``, ...), for ``--task NAME``.
    """
    return sorted(p.stem for p in PRESETS_DIR.glob("*.toml"))


def load_task(source: str | Path, base: Task = PAPER_TASK) -> Task:
    """A task from a TOML file, a shipped preset's name, or a ``results.json`` (its ``task`` block).

    Keys left out keep ``base``'s values (the paper's); a file without ``name`` is named after itself
    (``lab.toml``: ``lab``). Every problem is a :class:`TaskError` naming the file, the line (for a TOML
    file) and the values allowed.

    Parameters
    ----------
    source : str or pathlib.Path
        A path to a ``.toml`` task file or a ``results.json``, or a preset name (:func:`preset_names`).
    base : Task
        The task whose values the file's keys replace.

    Returns
    -------
    Task
        The task.
    """
    path = Path(source)
    if not path.exists() and str(source) in preset_names():
        path = PRESETS_DIR / f"{source}.toml"
    if not path.is_file():
        raise TaskError(
            f"{source}: no such task file (give a .toml task file, a results.json, or a preset: "
            f"{', '.join(preset_names())})"
        )
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as e:
        raise TaskError(f"{path}: cannot be read ({e})") from None
    if path.suffix.lower() == ".json":
        try:
            data = json.loads(text)
        except json.JSONDecodeError as e:
            raise TaskError(f"{path}, line {e.lineno}: not valid JSON ({e.msg})") from None
        if not isinstance(data, Mapping) or not isinstance(data.get("task"), Mapping):
            raise TaskError(f"{path}: no 'task' block (a results.json of skilllib 0.3 or later has one)")
        return _apply(base, data["task"], source=str(path), text="")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise TaskError(f"{path}: not a valid TOML task file ({e})") from None
    named = data if "name" in data else {"name": path.stem, "description": "", **data}  # not the base's name
    return _apply(base, named, source=str(path), text=text)


def task_fields() -> list[str]:
    """The names of :class:`Task`'s fields (for documentation and tests)."""
    return [f.name for f in fields(Task)]


__all__ = [
    "DEFAULT_HOLD_S",
    "KEYS",
    "PAPER_TASK",
    "Task",
    "TaskError",
    "load_task",
    "parse_setting",
    "preset_names",
]
