"""One trial from a C3D file (Vicon, Qualisys, OptiTrack, Optotrak export): a marker's path and the contact flag.

**Reader: ``ezc3d``** (1.7.2, pyomeca's maintained C++ reader; pinned), behind two safety layers. The
pure-Python ``c3d`` package (0.6.0), used before, failed on what vendors write: an OptiTrack Motive file
that numbers its first frame 0 lost a frame ("file cut short"), an Optotrak export's last frame was
misread, a wheelchair-propulsion file did not parse (``SCALE: cannot get value as numpy.float32``), and an
ezc3d-written file was refused for its scale factor's sign; ``ezc3d`` reads them all. But its parser does
not fail safely: on copies of a small valid file truncated inside the parameter section it crashed the
interpreter (segmentation fault) or looped without end, and with 3 random bytes changed in the parameter
section it crashed or hung on 6 of 40 copies (measured 2026-11-24, each copy in a subprocess with a 5 s
limit; again 4 of 40 on another file). A folder of recordings must survive one bad file, so:

1. **Checked in Python first** (:func:`~skilllib.recordings._c3d_safe.inspect_c3d`): the header, every
   record of the parameter section (names are text, each record and its data inside the section, types
   known, the chain moves forward), POINT:SCALE and POINT:RATE usable, the data start after the
   parameters, ``ANALOG:SCALE``/``OFFSET`` with a value per channel (ezc3d crashes on the empty ones
   ``c3d``'s ``Writer`` leaves, and reads memory it does not own on too few), and the frame counts against
   the bytes the data hold. Most damage is caught here with a precise message, before any C++ code reads
   the file (measured 2026-11-27: of 40 copies of a small ezc3d-written file with 3 random bytes changed
   in the parameter section, 34 refused here, among them all 4 on which ezc3d crashed or hung; 5 read,
   1 refused by ezc3d).
2. **Parsed by ezc3d in a worker process** (:mod:`~skilllib.recordings._c3d_worker`), started on the first
   C3D file and reused for every later one (measured: 0.35-0.55 s to start; then 2.5-7 ms per small
   file, against 1.3-3 ms for ezc3d in the caller; 50 files of 300 frames: 0.13-0.34 s): a parser
   that crashes or runs past its time limit (10 s + 1 s per MB) ends the worker, not the caller, and the
   file gets ``could not be parsed (the C3D reader crashed/timed out): the file is damaged``; the next
   file starts a new worker.

Every failure is one line, a :class:`~skilllib.recordings.DataFormatError` naming the file (the command
line exits 2); nothing is written before the whole file is read.

Rules of :func:`read_c3d` (one file = one trial):

* **marker**: by name in ``POINT:LABELS`` (and ``LABELS2``, ...); a name matches a label exactly, or
  the part after the last ``:`` of a label (Vicon writes ``Subject:Marker``) when exactly one label has
  it. An empty label is named ``unnamed_K``, K the point's number in the file (from 1). Points listed as
  model outputs (``POINT:ANGLES``, ``FORCES``, ``MOMENTS``, ``POWERS``, ``SCALARS``, ``REACTIONS``) are not
  markers. Without a name, the only marker is used; several markers without a name, or an unknown name,
  raise an error listing the markers.
* **units**: ``POINT:UNITS`` (``mm``, ``cm``, ``m``) converted to m; the ``units`` argument overrides
  a missing or wrong header. ``attrs["units"]`` of the result is the unit the file states (``"mm"``,
  ``"cm"``, ``"m"``), or None when it states none (or one not known).
* **storage**: POINT:SCALE < 0 means floats, > 0 scaled integers (ezc3d applies the scale); either sign
  is read.
* **frames**: the header (first and last frame), ``POINT:FRAMES`` and ``TRIAL:ACTUAL_START/END_FIELD``
  may disagree (vendors write them differently): the largest announced count the data hold is read
  (frames past a smaller count that are all zero bytes are the block padding, not frames), and the
  disagreement is a note in ``attrs["notes"]``. When every announced count is more than the data
  hold, the file is cut short: an error.
* **time**: ``t = (f - 1 + i) / POINT:RATE`` (s) for point frame ``i = 0, 1, ...``, with ``f`` the first
  frame number of the file (``TRIAL:ACTUAL_START_FIELD`` or the header), so that frame 1 of the capture
  is at 0 s and a cropped trial keeps its capture clock, the clock of ``EVENT:TIMES``. A file that numbers
  its first frame 0 (OptiTrack Motive) counts from 0: its frame 0 is at 0 s (``t = i / POINT:RATE``).
* **gaps**: a sample with a negative residual (the C3D "not seen"; ezc3d gives it as NaN) or exactly at
  ``(0, 0, 0)`` (the other convention for a missing marker) is NaN in x, y, z, so
  :mod:`skilllib.recordings` marks the trial invalid naming the sample.
* **contact**, from the name ``contact_channel`` (default ``"contact"``; labels compared without case
  or surrounding spaces):

  - an analog channel (``ANALOG:LABELS``) of that name: point frame ``i`` is in contact when any of its
    analog samples (the ``m`` = analog rate / point rate samples recorded during the frame) is above
    the threshold (with ``contact_below``: below it, for a load cell whose channel goes negative under
    load): ``contact_threshold`` in the channel's units (scale and offset of the file applied)
    when given, else the midpoint between the channel's minimum and maximum in this file (a constant
    channel: never in contact);
  - else an event of that name (:func:`c3d_events`, with its combined ``CONTEXT LABEL`` too): contact = 1
    from the first point frame at or after the earliest such event on (a frame within 1 % of a frame
    interval before the event time counts as at it: the times are stored as 32-bit floats);
  - else, when ``contact_channel`` was not given, ``contact`` is all NaN (:data:`NO_CONTACT`): the
    caller applies the height rule (:func:`skilllib.recordings.map_frame` with
    ``contact_height``); when it was given, an error lists the analog channels and events.
* **events** (:func:`c3d_events`): every event of ``EVENT:LABELS``, ``EVENT:CONTEXTS`` and ``EVENT:TIMES``
  (minutes, seconds) is kept in ``attrs["events"]`` as ``(label, time in s)``, on the clock of ``t``
  (the capture clock: an event at 1.5 s is at the sample whose ``t`` is 1.5 s). The label is kept as
  written; an event with a context (``Left``, ``Right``, ``General``) is listed a second time under the
  combined label ``"CONTEXT LABEL"`` (``Left`` + ``Foot Strike``: ``"Left Foot Strike"``), unless the
  label already starts with its context, so that a rule can name either. Events without a label are
  left out (a note says how many).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from ._c3d_safe import inspect_c3d, parse_c3d
from ._errors import DataFormatError, check_file
from ._mapping import UNIT_FACTORS, unit_factor

NO_CONTACT = np.nan  #: the contact value of every sample when a file has no contact signal
DEFAULT_CONTACT_CHANNEL = "contact"  #: analog channel or event label looked for when none is named
MODEL_OUTPUT_GROUPS = ("ANGLES", "FORCES", "MOMENTS", "POWERS", "SCALARS", "REACTIONS")  #: POINT:<...>
EVENT_TOLERANCE = 0.01  #: fraction of a frame interval by which a frame may precede an event and count


def _texts(group: dict, name: str) -> list[str]:
    """A text parameter ``NAME`` of a group and its continuations (``LABELS2``, ...) as one list, stripped."""
    out: list[str] = []
    for key in [name] + [f"{name}{i}" for i in range(2, 100)]:
        if key not in group:
            break
        value = group[key]
        out += [str(v).strip() for v in (value if isinstance(value, list) else np.ravel(value))]
    return out


def _number(group: dict, name: str) -> float | None:
    """The first value of a numeric parameter, or None."""
    value = np.ravel(np.asarray(group.get(name, []), dtype=object))
    try:
        return float(value[0]) if value.size else None
    except (TypeError, ValueError):
        return None


def _choose_marker(labels: list[str], markers: list[str], marker: str | None, path: Path) -> int:
    """Index into ``labels`` of the chosen marker (rules in the module docstring)."""
    listed = ", ".join(markers) if markers else "none"
    if marker is None:
        if len(markers) == 1:
            return labels.index(markers[0])
        if not markers:
            raise DataFormatError(f"{path}: no marker in POINT:LABELS")
        raise DataFormatError(f"{path}: {len(markers)} markers ({listed}): choose one with --marker NAME")
    name = marker.strip()
    if markers.count(name) > 1:
        raise DataFormatError(f"{path}: {markers.count(name)} points are labelled {name!r}")
    if name in markers:
        return labels.index(name)
    tails = [lab for lab in markers if lab.rsplit(":", 1)[-1] == name]
    if len(tails) == 1:
        return labels.index(tails[0])
    raise DataFormatError(f"{path}: no marker {marker!r} (markers: {listed})")


def _contact_from_analog(blocks: np.ndarray, threshold: float | None, below: bool = False) -> np.ndarray:
    """Per point frame (rows of ``blocks``, its analog samples): 1.0 when any is above the threshold
    (``below``: below it)."""
    if threshold is None:
        lo, hi = np.nanmin(blocks), np.nanmax(blocks)
        if not hi > lo:
            return np.zeros(len(blocks))
        threshold = (lo + hi) / 2
    return ((blocks < threshold) if below else (blocks > threshold)).any(axis=1).astype(float)


def c3d_events(params: dict) -> tuple[list[tuple[str, float]], int]:
    """The events of a C3D file's parameters (rules: module docstring, events).

    Parameters
    ----------
    params : dict
        The file's parameter groups (``{group: {name: value}}``, as the reader gives them; text and numbers).

    Returns
    -------
    events : list of tuple of (str, float)
        ``(label, time)`` (text, s on the capture clock), ordered by time, then label; an event with a
        context also under ``"CONTEXT LABEL"``.
    n_unlabelled : int
        Events left out because they have no label (dimensionless).
    """
    event = params.get("EVENT", {})
    labels = _texts(event, "LABELS")
    contexts = _texts(event, "CONTEXTS")
    times = np.asarray(event.get("TIMES", np.zeros((2, 0))), dtype=float)
    times = times.T if times.ndim == 2 and times.shape[0] == 2 else times.reshape(-1, 2)
    n = min(len(labels), len(times))
    used = _number(event, "USED")
    if used is not None and 0 < used < n:
        n = int(used)
    out: list[tuple[str, float]] = []
    unlabelled = 0
    for i in range(n):
        label = labels[i]
        t = float(60 * times[i, 0] + times[i, 1])
        if not label:
            unlabelled += 1
            continue
        out.append((label, t))
        context = contexts[i] if i < len(contexts) else ""
        if context and not label.lower().startswith(context.lower()):
            out.append((f"{context} {label}", t))
    out.sort(key=lambda e: (e[1], e[0]))
    return out, unlabelled


def _contact_from_event(t: np.ndarray, t_event: float, rate: float) -> np.ndarray:
    """1.0 from the first point frame at or after ``t_event`` (s) on (tolerance: module docstring)."""
    return (t >= t_event - EVENT_TOLERANCE / rate).astype(float)


def _file_units(text: str) -> str | None:
    """The length unit a C3D file states, normalised (``"m"``, ``"cm"``, ``"mm"``), or None.

    Parameters
    ----------
    text : str
        ``POINT:UNITS`` as written (text; case and surrounding spaces ignored).

    Returns
    -------
    str or None
        The known unit (text), or None when the text is empty or not a known unit.
    """
    key = str(text).strip().lower()
    return key if key in UNIT_FACTORS else None


def read_c3d(
    path: str | Path,
    *,
    marker: str | None = None,
    contact_channel: str | None = None,
    contact_threshold: float | None = None,
    contact_below: bool = False,
    units: str | None = None,
) -> pd.DataFrame:
    """One marker of a C3D file as one trial: columns ``t`` (s), ``x, y, z`` (m, the file's axes), ``contact``.

    ``contact`` is 0/1 from an analog channel or event named ``contact_channel`` (default ``"contact"``
    when present), else all NaN (:data:`NO_CONTACT`) for the height rule. Positions stay in the lab's
    axes: :func:`skilllib.recordings.map_frame` with ``up_axis`` rotates them. Rules (marker choice,
    units, frames, time origin, gaps, contact threshold) and the safety design (a damaged file never
    crashes or hangs the caller) in the module docstring.

    Parameters
    ----------
    path : str or pathlib.Path
        The C3D file (text).
    marker : str or None
        Name of the marker to read (text); None: the file's only marker.
    contact_channel : str or None
        Name of the analog channel or event that gives contact in a C3D file (text); None: ``"contact"``
        when the file has it, else contact is left NaN for the height rule.
    contact_threshold : float or None
        Analog level above which a C3D frame is in contact, in the channel's own unit (V, N, ...; taken as
        dimensionless here); None: midway between the channel's minimum and maximum in the file.
    contact_below : bool
        Whether a frame is in contact when the analog channel is *below* the threshold (a load cell whose
        channel goes negative under load; dimensionless); False: above it.
    units : str or None
        Unit of the file's positions (text: ``"m"``, ``"cm"`` or ``"mm"``), overriding a missing or wrong
        header; None: the file's own.

    Returns
    -------
    pandas.DataFrame
        ``t`` (s), ``x, y, z`` (m, the file's axes), ``contact`` (0/1 or NaN). ``attrs["units"]``: the unit
        the file states (text: ``"m"``, ``"cm"``, ``"mm"``) or None; ``attrs["notes"]``: disagreements in
        the file that were resolved (list of text, e.g. frame counts); ``attrs["events"]``: the file's
        events, ``(label, time)`` pairs (text, s on the clock of ``t``; :func:`c3d_events`).

    Raises
    ------
    DataFormatError
        One line naming the file, when the file is missing, not a C3D file, damaged (the reader crashed or
        timed out on it) or cut short, has no or several markers and no ``marker`` (listing them), has no
        marker ``marker`` (listing them), has no usable ``POINT:RATE``, has units other than m, cm, mm, or
        has no channel or event named by an explicit ``contact_channel`` (listing those it has).
    """
    path = Path(path)
    check_file(path, "C3D")
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise DataFormatError(f"{path}: cannot be read ({e.strerror or e})") from None
    layout = inspect_c3d(path, raw)
    name = (contact_channel if contact_channel is not None else DEFAULT_CONTACT_CHANNEL).strip().lower()
    if layout.patches:  # frame counts that disagree: ezc3d reads a copy that says the count the data hold
        with tempfile.TemporaryDirectory(prefix="skilllib-c3d-") as tmp:
            fixed = bytearray(raw)
            for offset, new in layout.patches.items():
                fixed[offset : offset + len(new)] = new
            copy = Path(tmp) / "copy.c3d"
            copy.write_bytes(bytes(fixed))
            try:
                got = parse_c3d(copy, name, len(raw))
            except DataFormatError as e:
                raise DataFormatError(str(e).replace(str(copy), str(path), 1)) from None
    else:
        got = parse_c3d(path, name, len(raw))
    try:
        return _trial(path, layout, got, marker, contact_channel, (contact_threshold, contact_below), units)
    except DataFormatError:
        raise
    except (ValueError, TypeError, IndexError, KeyError) as e:  # parameters of unexpected shape or type
        raise DataFormatError(f"{path}: not a readable C3D file ({type(e).__name__}: {e})"[:300]) from None


def _trial(path, layout, got, marker, contact_channel, threshold, units) -> pd.DataFrame:
    """The trial's table from the checked layout and ezc3d's values (rules: module docstring);
    ``threshold`` is ``(contact_threshold, contact_below)``."""
    params = got["params"]
    point = params.get("POINT", {})
    notes = list(layout.notes)
    pts, res = got["points"], got["residuals"]
    n_ez, n_points = pts.shape[0], pts.shape[1]
    n = layout.n_frames
    if n_ez < n:
        notes.append(f"the C3D reader read {n_ez} of the {n} frames the data hold")
        n = n_ez
    if n == 0:
        raise DataFormatError(f"{path}: no frames in the file")
    labels = _texts(point, "LABELS")[:n_points]
    if len(labels) < n_points:
        notes.append(f"{n_points} points but {len(labels)} POINT:LABELS: the others are unnamed")
        labels += [""] * (n_points - len(labels))
    labels = [lab or f"unnamed_{k}" for k, lab in enumerate(labels, start=1)]
    outputs = {lab for g in MODEL_OUTPUT_GROUPS for lab in _texts(point, g)}
    markers = [lab for lab in labels if lab not in outputs]
    k = _choose_marker(labels, markers, marker, path)
    rate = _number(point, "RATE")
    if rate is None or not rate > 0:
        raise DataFormatError(f"{path}: no sampling rate (POINT:RATE missing or 0)")
    stated = (_texts(point, "UNITS") or [""])[0]
    unit_text = units if units is not None else stated
    if not unit_text:
        raise DataFormatError(f"{path}: no POINT:UNITS in the file: give the unit with --units m|cm|mm")
    factor = unit_factor(unit_text, f"{path}: POINT:UNITS" if units is None else str(path))
    xyz = np.array(pts[:n, k, :], dtype=float)
    xyz[(res[:n, k] < 0) | np.all(xyz == 0, axis=1) | np.isnan(xyz).any(axis=1)] = np.nan
    xyz *= factor
    first = layout.first_frame
    t = ((first - 1 if first >= 1 else 0) + np.arange(n)) / rate
    events, unlabelled = c3d_events(params)
    if unlabelled:
        notes.append(f"{unlabelled} event(s) without a label left out")
    contact = _contact(params, got, n_ez, path, t, rate, contact_channel, threshold, events)
    frame = pd.DataFrame({"t": t, "x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2], "contact": contact})
    frame.attrs["units"] = _file_units(stated)
    frame.attrs["notes"] = notes
    frame.attrs["events"] = events
    return frame


def _contact(
    params: dict,
    got: dict,
    n_ez: int,
    path: Path,
    t: np.ndarray,
    rate: float,
    contact_channel: str | None,
    threshold: tuple[float | None, bool],
    events: list[tuple[str, float]],
) -> np.ndarray:
    n = len(t)
    analog_labels = _texts(params.get("ANALOG", {}), "LABELS")
    m = got["n_analog"] // n_ez if n_ez else 0
    if got["analogs"] and m > 0:
        samples = got["analogs"][min(got["analogs"])]
        blocks = np.asarray(samples[: n * m], dtype=float).reshape(n, m)  # (n_frames, samples per frame)
        return _contact_from_analog(blocks, *threshold)
    name = (contact_channel if contact_channel is not None else DEFAULT_CONTACT_CHANNEL).strip().lower()
    ev_labels = [lab for lab, _ in events]
    ev_times = [tm for lab, tm in events if lab.lower() == name]
    if ev_times:
        return _contact_from_event(t, min(ev_times), rate)
    if contact_channel is None:
        return np.full(n, NO_CONTACT)
    events = ", ".join(sorted(set(ev_labels))) or "none"
    raise DataFormatError(
        f"{path}: no analog channel or event {contact_channel!r} (analog channels: "
        f"{', '.join(analog_labels) or 'none'}; events: {events})"
    )
