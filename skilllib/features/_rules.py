"""Where a movement starts and ends: the task's segmentation rules, stated as data.

The paper's rules are one case: the movement starts at the first sample whose speed exceeds 0.05 m/s and
ends at the first sample in contact (:data:`PAPER_START`, :data:`PAPER_END`). Other discrete movements
need other rules, written as short texts on the command line and in task files (:mod:`skilllib.task`):

===========================  ======================================================================
text                         meaning
===========================  ======================================================================
``speed:0.05``               start: the first sample faster than 0.05 m/s
``speed:5%``                 start: the first sample faster than 5 % of the movement's peak speed
                             for longer than ``hold_s`` (a blip in the rest does not start it)
``event:LABEL``              start / end: at the first frame at or after the event ``LABEL``
``contact``                  end: the first sample in contact (the recording's contact flag)
``offset``                   end: after the onset, the first sample at or below the start's
                             threshold that stays there for ``hold_s`` (s): the first rest
``offset:0.05``              end: the same with 0.05 m/s
``offset:5%``                end: the same with 5 % of the movement's peak speed
``height-above:M``           end: after onset, the first sample at or above M (m) on the up axis
``height-below:M``           end: after onset, the first sample at or below M (m) on the up axis
===========================  ======================================================================

Heights are in metres on the recording's up axis after the unit mapping (``up_axis``; the book's y):
the rule says where the hand goes in the room, not how the robot is placed.

A segment holds the samples from the start sample to the last sample before the end sample, as the
paper's approach holds the samples before contact; its last speed is the ``contact_speed`` column of the
feature table (the speed at the end: before contact, or at offset).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

PAPER_ONSET_SPEED = 0.05  #: m/s, the paper's onset threshold
DEFAULT_HOLD_S = 0.1  #: s, how long the speed must stay below the offset threshold (and a rest between movements)

START_KINDS = ("speed", "event")
END_KINDS = ("contact", "offset", "event", "height-above", "height-below")

_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?"


class RuleError(ValueError):
    """A segmentation rule's text that cannot be read; the message lists the forms allowed."""


@dataclass(frozen=True)
class SpeedThreshold:
    """A speed threshold: absolute (``speed`` in m/s) or relative (``fraction`` of the peak speed).

    Attributes
    ----------
    speed : float or None
        The threshold (m/s), or None when relative.
    fraction : float or None
        The threshold as a fraction of the movement's peak speed (dimensionless, 0 < fraction < 1), or None.
    """

    speed: float | None = PAPER_ONSET_SPEED
    fraction: float | None = None

    def value(self, peak: float) -> float:
        """The threshold in m/s for a movement whose peak speed is ``peak`` (m/s)."""
        return float(self.speed) if self.fraction is None else float(self.fraction) * float(peak)

    def text(self) -> str:
        """``0.05`` or ``5%`` (as written after the colon)."""
        return f"{self.speed:g}" if self.fraction is None else f"{100 * self.fraction:g}%"


@dataclass(frozen=True)
class StartRule:
    """Where a movement starts: ``kind`` ``"speed"`` (the first sample faster than ``threshold``) or
    ``"event"`` (the first frame at or after the first event ``label``).

    Attributes
    ----------
    kind : str
        ``"speed"`` or ``"event"``.
    threshold : SpeedThreshold
        The onset speed (m/s, or a fraction of the peak); also the default offset threshold.
    label : str or None
        The event's label, for ``kind == "event"`` (text).
    """

    kind: str = "speed"
    threshold: SpeedThreshold = SpeedThreshold()
    label: str | None = None

    def text(self) -> str:
        """The rule as written on the command line (``speed:0.05``, ``speed:5%``, ``event:LABEL``)."""
        return f"event:{self.label}" if self.kind == "event" else f"speed:{self.threshold.text()}"

    @property
    def is_paper(self) -> bool:
        """Whether this is the paper's rule (0.05 m/s)."""
        return self == PAPER_START


@dataclass(frozen=True)
class EndRule:
    """Where a movement ends (the first sample not in the segment).

    Attributes
    ----------
    kind : str
        One of :data:`END_KINDS`.
    threshold : SpeedThreshold or None
        For ``offset``: the speed at or below which the movement has ended; None: the start's threshold.
    hold_s : float
        For ``offset``: how long the speed stays at or below the threshold (s).
    label : str or None
        For ``event``: the event's label (text).
    height : float or None
        For ``height-above`` / ``height-below``: the height on the up axis (m).
    """

    kind: str = "contact"
    threshold: SpeedThreshold | None = None
    hold_s: float = DEFAULT_HOLD_S
    label: str | None = None
    height: float | None = None

    def text(self) -> str:
        """The rule as written on the command line (``contact``, ``offset:5%``, ``height-above:0.6``, ...)."""
        if self.kind == "offset":
            return "offset" if self.threshold is None else f"offset:{self.threshold.text()}"
        if self.kind == "event":
            return f"event:{self.label}"
        if self.kind.startswith("height"):
            return f"{self.kind}:{self.height:g}"
        return self.kind

    def offset_threshold(self, start: StartRule) -> SpeedThreshold:
        """The offset threshold: this rule's, or the start's when it states none (and the start is a speed)."""
        return self.threshold if self.threshold is not None else start.threshold

    @property
    def is_paper(self) -> bool:
        """Whether this is the paper's rule (contact)."""
        return self.kind == "contact"


PAPER_START = StartRule()
PAPER_END = EndRule()


def _threshold(text: str, whole: str, what: str) -> SpeedThreshold:
    text = text.strip()
    m = re.fullmatch(rf"({_NUMBER})\s*%", text)
    if m:
        f = float(m.group(1)) / 100
        if not 0 < f < 1:
            raise RuleError(f"{whole!r}: the {what} must be a percentage above 0 and below 100 of the peak speed")
        return SpeedThreshold(speed=None, fraction=f)
    if re.fullmatch(_NUMBER, text):
        v = float(text)
        if not (math.isfinite(v) and v > 0):
            raise RuleError(f"{whole!r}: the {what} must be a speed above 0 m/s")
        return SpeedThreshold(speed=v)
    raise RuleError(f"{whole!r}: the {what} must be a speed in m/s (0.05) or a percentage of the peak (5%)")


START_FORMS = "speed:0.05 (m/s), speed:5% (of the peak speed) or event:LABEL"
END_FORMS = (
    "contact, offset, offset:0.05 (m/s), offset:5% (of the peak speed), event:LABEL, "
    "height-above:M or height-below:M (m)"
)


def parse_start(text: str) -> StartRule:
    """A start rule from its text (module docstring); :class:`RuleError` listing the forms otherwise.

    Parameters
    ----------
    text : str
        ``speed:0.05`` (m/s), ``speed:5%`` or ``event:LABEL``.

    Returns
    -------
    StartRule
        The rule.
    """
    kind, sep, arg = str(text).strip().partition(":")
    kind = kind.strip().lower()
    if kind == "speed" and sep:
        return StartRule("speed", _threshold(arg, text, "start speed"))
    if kind == "event" and arg.strip():
        return StartRule("event", SpeedThreshold(), arg.strip())
    raise RuleError(f"{text!r} is not a start rule: use {START_FORMS}")


def parse_end(text: str, hold_s: float = DEFAULT_HOLD_S) -> EndRule:
    """An end rule from its text (module docstring); :class:`RuleError` listing the forms otherwise.

    Parameters
    ----------
    text : str
        ``contact``, ``offset``, ``offset:0.05`` (m/s), ``offset:5%``, ``event:LABEL``,
        ``height-above:M`` or ``height-below:M`` (m).
    hold_s : float
        For ``offset``: how long the speed stays at or below the threshold (s).

    Returns
    -------
    EndRule
        The rule.
    """
    if not (math.isfinite(hold_s) and hold_s >= 0):
        raise RuleError(f"the offset hold must be a time of at least 0 s, got {hold_s!r}")
    kind, sep, arg = str(text).strip().partition(":")
    kind, arg = kind.strip().lower(), arg.strip()
    if kind == "contact" and not arg:
        return EndRule("contact", hold_s=hold_s)
    if kind == "offset":
        return EndRule("offset", _threshold(arg, text, "offset speed") if arg else None, hold_s)
    if kind == "event" and arg:
        return EndRule("event", hold_s=hold_s, label=arg)
    if kind in ("height-above", "height-below") and arg:
        if not re.fullmatch(_NUMBER, arg) or not math.isfinite(float(arg)):
            raise RuleError(f"{text!r}: the height must be a number in m")
        return EndRule(kind, hold_s=hold_s, height=float(arg))
    raise RuleError(f"{text!r} is not an end rule: use {END_FORMS}")
