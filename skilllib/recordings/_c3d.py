"""One trial from a C3D file (Vicon, Qualisys, OptiTrack export): a marker's path and the contact flag.

**Reader: ``c3d``** (0.6.0, pure Python, numpy only; pinned), not ``ezc3d`` (1.7.2, C++ core). Both read
the parameters, points, analog channels and events this module needs, and ``ezc3d`` is faster and
writes files more easily; what decided is what a *damaged* file does. A folder of recordings must
survive one bad file (its trial is reported, the others are read), and ``ezc3d``'s C++ parser does not
fail safely: on copies of a small valid file truncated inside the parameter section it crashed the
interpreter (segmentation fault) or looped without end, and with 3 random bytes changed in the
parameter section it crashed or hung on 6 of 40 copies (measured 2026-11-24 with ezc3d 1.7.2, each
copy read in a subprocess with a 5 s limit). ``c3d`` raised a Python exception on all 40 and on every
truncation, which :func:`read_c3d` turns into a one-line :class:`~skilllib.recordings.DataFormatError`. It
reads frame by frame in Python, fast enough for one-trial files (thousands of frames); it is imported
on first use, so ``import skilllib`` does not pay for it. (Its ``Writer.add_frames`` in 0.6.0 fails when
the point and analog arrays of a frame share a first dimension of 1, as numpy broadcasts them; the
tests pass a prebuilt ``(n_frames, 2)`` object array of ``(points, analog)``.)

Rules of :func:`read_c3d` (one file = one trial):

* **marker**: by name in ``POINT:LABELS`` (and ``LABELS2``, ...); a name matches a label exactly, or
  the part after the last ``:`` of a label (Vicon writes ``Subject:Marker``) when exactly one label has
  it. Points listed as model outputs (``POINT:ANGLES``, ``FORCES``, ``MOMENTS``, ``POWERS``,
  ``SCALARS``, ``REACTIONS``) are not markers. Without a name, the only marker is used; several markers
  without a name, or an unknown name, raise an error listing the markers.
* **units**: ``POINT:UNITS`` (``mm``, ``cm``, ``m``) converted to m; the ``units`` argument overrides
  a missing or wrong header.
* **time**: ``t = (f - 1 + i) / POINT:RATE`` (s) for point frame ``i = 0, 1, ...``, with ``f`` the first
  frame number of the file (counted from 1: ``TRIAL:ACTUAL_START_FIELD`` or the header), so that frame 1
  of the capture is at 0 s and a cropped trial keeps its capture clock, the clock of ``EVENT:TIMES``.
* **gaps**: a sample with a negative residual (the C3D "not seen") or exactly at ``(0, 0, 0)`` (the other
  convention for a missing marker) is NaN in x, y, z, so :mod:`skilllib.recordings` marks the trial invalid
  naming the sample. A file with fewer frames than its header announces is cut short: an error.
* **contact**, from the name ``contact_channel`` (default ``"contact"``; labels compared without case
  or surrounding spaces):

  - an analog channel (``ANALOG:LABELS``) of that name: point frame ``i`` is in contact when any of its
    analog samples (the ``m`` = analog rate / point rate samples recorded during the frame) is above
    the threshold: ``contact_threshold`` in the channel's units (scale and offset of the file applied)
    when given, else the midpoint between the channel's minimum and maximum in this file (a constant
    channel: never in contact);
  - else an event (``EVENT:LABELS``, ``EVENT:TIMES`` = minutes, seconds): contact = 1 from the first
    point frame at or after the earliest such event on (a frame within 1 % of a frame interval before
    the event time counts as at it: the times are stored as 32-bit floats);
  - else, when ``contact_channel`` was not given, ``contact`` is all NaN (:data:`NO_CONTACT`): the
    caller applies the height rule (:func:`skilllib.recordings.map_frame` with
    ``contact_height``); when it was given, an error lists the analog channels and events.
"""

from __future__ import annotations

import io
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from ._errors import DataFormatError, check_file
from ._mapping import unit_factor

NO_CONTACT = np.nan  #: the contact value of every sample when a file has no contact signal
DEFAULT_CONTACT_CHANNEL = "contact"  #: analog channel or event label looked for when none is named
MODEL_OUTPUT_GROUPS = ("ANGLES", "FORCES", "MOMENTS", "POWERS", "SCALARS", "REACTIONS")  #: POINT:<...>
EVENT_TOLERANCE = 0.01  #: fraction of a frame interval by which a frame may precede an event and count


def _texts(reader, name: str) -> list[str]:
    """A text parameter ``GROUP:NAME`` and its continuations (``LABELS2``, ...) as one list of stripped strings."""
    out: list[str] = []
    for key in [name] + [f"{name}{i}" for i in range(2, 100)]:
        param = reader.get(key)
        if param is None:
            break
        out += [str(v).strip() for v in np.ravel(param.string_array)]
    return out


def _read(path: Path):
    """(reader, list of (points, analog) per frame); DataFormatError for anything the parser refuses."""
    check_file(path, "C3D")
    import c3d as c3dlib  # first use only: keeps `import skilllib` and `--help` fast

    raw = path.read_bytes()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # e.g. "No analog data found in file."; counts are checked below
            reader = c3dlib.Reader(io.BytesIO(raw))
            frames = [(p[:, :4].copy(), a.copy()) for _, p, a in reader.read_frames(copy=False)]
            expected = int(reader.frame_count)
    except Exception as e:  # the parser raises AssertionError, struct.error, ValueError, ... on damaged files
        msg = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        raise DataFormatError(f"{path}: not a readable C3D file ({msg[:200]})") from None
    if len(frames) < expected:
        raise DataFormatError(
            f"{path}: file cut short: the header announces {expected} frames, the data hold {len(frames)}"
        )
    if not frames:
        raise DataFormatError(f"{path}: no frames in the file")
    return reader, frames


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
    if name in markers:
        return labels.index(name)
    tails = [lab for lab in markers if lab.rsplit(":", 1)[-1] == name]
    if len(tails) == 1:
        return labels.index(tails[0])
    raise DataFormatError(f"{path}: no marker {marker!r} (markers: {listed})")


def _contact_from_analog(blocks: np.ndarray, threshold: float | None) -> np.ndarray:
    """Per point frame (rows of ``blocks``, its analog samples): 1.0 when any is above the threshold."""
    if threshold is None:
        lo, hi = np.nanmin(blocks), np.nanmax(blocks)
        if not hi > lo:
            return np.zeros(len(blocks))
        threshold = (lo + hi) / 2
    return (blocks > threshold).any(axis=1).astype(float)


def _contact_from_event(t: np.ndarray, t_event: float, rate: float) -> np.ndarray:
    """1.0 from the first point frame at or after ``t_event`` (s) on (tolerance: module docstring)."""
    return (t >= t_event - EVENT_TOLERANCE / rate).astype(float)


def read_c3d(
    path: str | Path,
    *,
    marker: str | None = None,
    contact_channel: str | None = None,
    contact_threshold: float | None = None,
    units: str | None = None,
) -> pd.DataFrame:
    """One marker of a C3D file as one trial: columns ``t`` (s), ``x, y, z`` (m, the file's axes), ``contact``.

    ``contact`` is 0/1 from an analog channel or event named ``contact_channel`` (default ``"contact"``
    when present), else all NaN (:data:`NO_CONTACT`) for the height rule. Positions stay in the lab's
    axes: :func:`skilllib.recordings.map_frame` with ``up_axis`` rotates them. Rules (marker choice,
    units, time origin, gaps, contact threshold) in the module docstring.

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
    units : str or None
        Unit of the file's positions (text: ``"m"``, ``"cm"`` or ``"mm"``), overriding a missing or wrong
        header; None: the file's own.

    Returns
    -------
    pandas.DataFrame
        ``t`` (s), ``x, y, z`` (m, the file's axes), ``contact`` (0/1 or NaN).

    Raises
    ------
    DataFormatError
        One line naming the file, when the file is missing, not a C3D file, damaged or cut short, has no or
        several markers and no ``marker`` (listing them), has no marker ``marker`` (listing them), has no
        usable ``POINT:RATE``, has units other than m, cm, mm, or has no channel or event named by an
        explicit ``contact_channel`` (listing those it has).
    """
    path = Path(path)
    reader, frames = _read(path)
    labels = _texts(reader, "POINT:LABELS")
    outputs = {lab for g in MODEL_OUTPUT_GROUPS for lab in _texts(reader, f"POINT:{g}")}
    markers = [lab for lab in labels if lab and lab not in outputs]
    n_points = frames[0][0].shape[0]
    if n_points != len(labels):
        raise DataFormatError(f"{path}: {n_points} points but {len(labels)} POINT:LABELS")
    k = _choose_marker(labels, markers, marker, path)
    rate = float(reader.point_rate)
    if not rate > 0:
        raise DataFormatError(f"{path}: no sampling rate (POINT:RATE missing or 0)")
    unit_text = units if units is not None else (_texts(reader, "POINT:UNITS") or [""])[0]
    if not unit_text:
        raise DataFormatError(f"{path}: no POINT:UNITS in the file: give the unit with --units m|cm|mm")
    factor = unit_factor(unit_text, f"{path}: POINT:UNITS" if units is None else str(path))
    pts = np.array([p[k] for p, _ in frames], dtype=float)  # (n_frames, 4): x, y, z, residual
    xyz = pts[:, :3]
    xyz[(pts[:, 3] < 0) | np.all(xyz == 0, axis=1)] = np.nan
    xyz *= factor
    t = (int(reader.first_frame) - 1 + np.arange(len(frames))) / rate
    contact = _contact(reader, frames, path, t, rate, contact_channel, contact_threshold)
    return pd.DataFrame({"t": t, "x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2], "contact": contact})


def _contact(
    reader, frames, path: Path, t: np.ndarray, rate: float, contact_channel: str | None, threshold: float | None
) -> np.ndarray:
    name = (contact_channel if contact_channel is not None else DEFAULT_CONTACT_CHANNEL).strip().lower()
    analog_labels = _texts(reader, "ANALOG:LABELS")
    hits = [i for i, lab in enumerate(analog_labels) if lab.lower() == name]
    if hits and frames[0][1].size:
        blocks = np.array([a[hits[0]] for _, a in frames], dtype=float)  # (n_frames, samples per frame)
        return _contact_from_analog(blocks, threshold)
    ev_labels = _texts(reader, "EVENT:LABELS")
    param = reader.get("EVENT:TIMES")
    times = np.asarray(param.float_array, dtype=float).reshape(-1, 2) if param is not None else np.zeros((0, 2))
    ev_times = [
        60 * times[i, 0] + times[i, 1] for i, lab in enumerate(ev_labels) if lab.lower() == name and i < len(times)
    ]
    if ev_times:
        return _contact_from_event(t, min(ev_times), rate)
    if contact_channel is None:
        return np.full(len(t), NO_CONTACT)
    events = ", ".join(sorted(set(ev_labels))) or "none"
    raise DataFormatError(
        f"{path}: no analog channel or event {contact_channel!r} (analog channels: "
        f"{', '.join(analog_labels) or 'none'}; events: {events})"
    )
