"""C3D files read safely: the header and parameter section checked in Python, then parsed by ezc3d in a child.

Two layers (why: :mod:`skilllib.recordings._c3d`). :func:`inspect_c3d` walks the 512-byte header and every
record of the parameter section in pure Python, bounds-checked, and decides how many frames the file really
holds; a damaged file gets a precise :class:`DataFormatError` here, before any C++ code sees it.
:func:`parse_c3d` then hands the file to ezc3d in a long-lived worker process
(:mod:`skilllib.recordings._c3d_worker`, started on first use, reused for every later file, restarted when
it dies): a crash or a hang of the parser ends the worker, never the caller, and gives one
:class:`DataFormatError`.
"""

from __future__ import annotations

import atexit
import math
import os
import pickle
import queue
import struct
import subprocess
import sys
import threading
from dataclasses import dataclass, field
from pathlib import Path

from ._errors import DataFormatError

BLOCK = 512  #: bytes of a C3D block
PROCESSORS = {84: "Intel", 85: "DEC", 86: "MIPS"}  #: parameter-section processor byte -> byte order / float kind
PARSE_TIMEOUT = 10.0  #: s a worker may take for one file, plus :data:`PARSE_TIMEOUT_PER_MB`
PARSE_TIMEOUT_PER_MB = 1.0  #: s per MB of file added to :data:`PARSE_TIMEOUT`
START_TIMEOUT = 60.0  #: s the worker may take to start (import numpy and ezc3d) on a loaded machine
MAX_RECORDS = 20_000  #: parameter records walked at most (a loop guard; real files have a few hundred)
MAX_SCALE = 1e6  #: largest |POINT:SCALE| believed
MAX_RATE = 1e6  #: largest POINT:RATE (Hz) believed


@dataclass
class C3DLayout:
    """What the Python check learnt of a file: its parameters (raw) and the frames the data hold.

    Attributes
    ----------
    params : dict
        ``"GROUP:NAME"`` -> (type, dims, raw bytes): type -1 text, 1 byte, 2 int16, 4 float (dimensionless).
    n_frames : int
        Point frames the reader believes (count).
    first_frame : int
        Number of the first frame (count; 0 when the writer numbers from 0).
    is_float : bool
        Data stored as floats (POINT:SCALE < 0), else as scaled integers.
    notes : list of str
        Disagreements the reader resolved (text).
    patches : dict
        Byte offset -> bytes that make the header's last frame and POINT:FRAMES say ``n_frames`` (empty when
        they already agree): ezc3d reads the count they give.
    """

    params: dict[str, tuple[int, tuple[int, ...], bytes]]
    n_frames: int
    first_frame: int
    is_float: bool
    notes: list[str] = field(default_factory=list)
    patches: dict[int, bytes] = field(default_factory=dict)


class _Decoder:
    """Integers and floats in the byte order and float format of the file's processor."""

    def __init__(self, processor: int) -> None:
        self.order = ">" if processor == 86 else "<"
        self.dec = processor == 85

    def int16(self, raw: bytes, signed: bool = True) -> list[int]:
        n = len(raw) // 2
        return list(struct.unpack(f"{self.order}{n}{'h' if signed else 'H'}", raw[: 2 * n]))

    def float32(self, raw: bytes) -> list[float]:
        n = len(raw) // 4
        if not self.dec:
            return list(struct.unpack(f"{self.order}{n}f", raw[: 4 * n]))
        swapped = b"".join(raw[i + 2 : i + 4] + raw[i : i + 2] for i in range(0, 4 * n, 4))
        return [v / 4 for v in struct.unpack(f"<{n}f", swapped)]  # DEC F: words swapped, exponent bias 2 off


def _fail(path: Path, why: str) -> DataFormatError:
    return DataFormatError(f"{path}: not a readable C3D file ({why})")


def _walk_parameters(raw: bytes, start: int, end: int, dec: _Decoder, path: Path) -> tuple[dict, dict]:
    """Every parameter record between ``start`` and ``end`` (bytes), each record's bounds checked; and the byte
    offset of each parameter's data."""
    groups: dict[int, str] = {}
    found: list[tuple[int, str, int, tuple[int, ...], bytes]] = []
    offsets: dict[str, int] = {}
    pos = start + 4
    for _ in range(MAX_RECORDS):
        if pos + 2 > end:
            break  # the section ends without a terminating record: tolerated, as readers do
        nlen, gid = struct.unpack("bb", raw[pos : pos + 2])
        if nlen == 0 or gid == 0:
            break
        name_end = pos + 2 + abs(nlen)
        if name_end + 2 > end:
            raise _fail(path, f"parameter record at byte {pos} runs past the parameter section")
        name = raw[pos + 2 : name_end]
        if not all(31 < ch < 127 for ch in name):
            raise _fail(path, f"parameter record at byte {pos} has a name that is not text")
        (step,) = dec.int16(raw[name_end : name_end + 2])
        nxt = name_end + step if step > 0 else end
        if step < 0 or nxt > end:
            raise _fail(path, f"parameter record {name.decode()!r} points outside the parameter section")
        body = name_end + 2
        if gid < 0:
            if body + 1 > nxt or body + 1 + raw[body] > nxt:
                raise _fail(path, f"parameter group {name.decode()!r} is longer than its record")
            groups[-gid] = name.decode().upper()
        else:
            if body + 2 > nxt:
                raise _fail(path, f"parameter {name.decode()!r} is longer than its record")
            kind, ndims = struct.unpack("bB", raw[body : body + 2])
            if kind not in (-1, 1, 2, 4):
                raise _fail(path, f"parameter {name.decode()!r} has an unknown type {kind}")
            dims = tuple(raw[body + 2 : body + 2 + ndims])
            data = body + 2 + ndims
            size = abs(kind) * math.prod(dims)
            if data + size + 1 > nxt or data + size + 1 + raw[data + size] > nxt:
                raise _fail(path, f"parameter {name.decode()!r} is longer than its record")
            found.append((gid, name.decode().upper(), kind, dims, raw[data : data + size]))
            offsets[f"{gid}:{name.decode().upper()}"] = data
        if step == 0:
            break
        pos = nxt
    else:
        raise _fail(path, f"more than {MAX_RECORDS} parameter records")
    by_name = {f"{groups[g]}:{n}": (k, d, b) for g, n, k, d, b in found if g in groups}
    at = {f"{groups[int(g)]}:{n}": o for key, o in offsets.items() for g, n in [key.split(":", 1)] if int(g) in groups}
    return by_name, at


def inspect_c3d(path: Path, raw: bytes) -> C3DLayout:
    """Check a C3D file's header and parameter section in Python and count the frames its data hold.

    Parameters
    ----------
    path : pathlib.Path
        The file, for messages.
    raw : bytes
        Its content.

    Returns
    -------
    C3DLayout
        The raw parameters, the number of point frames believed (count), the first frame number, the
        storage and notes on disagreements resolved.

    Raises
    ------
    DataFormatError
        Naming the file and what is wrong, for anything inconsistent in the header, the parameter section or
        the sizes, and for data cut short.
    """
    size = len(raw)
    if size < BLOCK:
        raise _fail(path, f"{size} bytes, shorter than the 512-byte header" if size else "the file is empty")
    if raw[1] != 0x50:
        raise _fail(path, "no C3D key in the header")
    start = (raw[0] - 1) * BLOCK
    if raw[0] < 2 or start + 4 > size:
        raise _fail(path, "the parameter section is missing or outside the file: the file is cut short")
    if raw[start + 3] not in PROCESSORS:
        raise _fail(path, f"unknown processor type {raw[start + 3]} in the parameter section")
    dec = _Decoder(raw[start + 3])
    n_blocks = raw[start + 2]
    end = min(start + n_blocks * BLOCK, size)
    if n_blocks == 0:
        raise _fail(path, "the parameter section has 0 blocks")
    params, data_at = _walk_parameters(raw, start, end, dec, path)
    words = dec.int16(raw[:BLOCK], signed=False)
    h_points, h_analog, h_first, h_last, data_start = words[1], words[2], words[3], words[4], words[8]
    h_scale, h_rate = dec.float32(raw[12:16])[0], dec.float32(raw[20:24])[0]

    def number(key: str, default: float | None = None) -> float | None:
        if key not in params:
            return default
        kind, _, b = params[key]
        vals = dec.float32(b) if kind == 4 else dec.int16(b) if kind == 2 else list(b) if kind == 1 else []
        return vals[0] if vals else default

    def unsigned(v: float | None) -> int | None:
        return None if v is None else int(v) & 0xFFFF

    n_points = unsigned(number("POINT:USED", h_points))
    scale, rate = number("POINT:SCALE", h_scale), number("POINT:RATE", h_rate)
    if not (math.isfinite(scale) and 0 < abs(scale) <= MAX_SCALE):
        raise _fail(path, f"POINT:SCALE {scale:g} is not a usable scale factor")
    if not (math.isfinite(rate) and 0 < rate <= MAX_RATE):
        raise _fail(path, f"POINT:RATE {rate:g} is not a usable rate")
    if n_points == 0:
        raise DataFormatError(f"{path}: no points in the file (POINT:USED is 0)")
    analog_used = unsigned(number("ANALOG:USED", 0)) or 0
    for key in ("ANALOG:SCALE", "ANALOG:OFFSET") if analog_used else ():  # ezc3d reads one per channel
        count = math.prod(params[key][1]) if key in params and params[key][0] != -1 else 0
        if count < analog_used:  # ezc3d 1.7.2 crashes on 0 values, reads memory it does not own on fewer
            raise _fail(path, f"{key} has {count} values for {analog_used} analog channels")
    if analog_used and h_analog % analog_used:
        raise _fail(path, f"{h_analog} analog values per frame in the header for {analog_used} channels")
    notes = []
    if n_points != h_points:
        notes.append(f"the header announces {h_points} points, POINT:USED {n_points}: POINT:USED believed")
    is_float = scale < 0
    width = 4 if is_float else 2
    frame_bytes = (4 * n_points + h_analog) * width
    ds = unsigned(number("POINT:DATA_START", data_start)) or data_start
    offset = (ds - 1) * BLOCK
    if ds < 2 or offset < start + BLOCK:
        raise _fail(path, f"the data start (block {ds}) is inside the header or parameter section")
    if offset > size:
        raise DataFormatError(f"{path}: file cut short: the data start (block {ds}) is past the end of the file")
    present = (size - offset) // frame_bytes
    announced = {}
    if h_last >= h_first:
        announced["the header"] = h_last - h_first + 1
    frames = unsigned(number("POINT:FRAMES"))
    if frames:
        announced["POINT:FRAMES"] = frames
    if "TRIAL:ACTUAL_START_FIELD" in params and "TRIAL:ACTUAL_END_FIELD" in params:
        s = dec.int16(params["TRIAL:ACTUAL_START_FIELD"][2], signed=False) + [0, 0]
        e = dec.int16(params["TRIAL:ACTUAL_END_FIELD"][2], signed=False) + [0, 0]
        s_n, e_n = s[0] + 65536 * s[1], e[0] + 65536 * e[1]
        if e_n >= s_n:
            announced["TRIAL:ACTUAL_END_FIELD"] = e_n - s_n + 1
        first = s_n
    else:
        first = h_first
    if not announced:
        raise DataFormatError(f"{path}: no frame count in the header or POINT:FRAMES")
    fit = [n for n in announced.values() if n <= present]
    if not fit:
        told = ", ".join(f"{k} {v}" for k, v in announced.items())
        raise DataFormatError(f"{path}: file cut short: {told} frames announced, the data hold {present}")
    n_frames = max(fit)
    if n_frames > min(announced.values()):  # frames past the smaller count that are all zero bytes are padding
        low = min(announced.values())
        while n_frames > low and not any(raw[offset + (n_frames - 1) * frame_bytes : offset + n_frames * frame_bytes]):
            n_frames -= 1
    if len(set(announced.values())) > 1:
        told = ", ".join(f"{k} {v}" for k, v in announced.items())
        notes.append(f"frame counts disagree ({told}): the {n_frames} frames the data hold are read")
    if n_frames == 0:
        raise DataFormatError(f"{path}: no frames in the file")
    patches = {}
    if len(set(announced.values())) > 1 and h_first + n_frames - 1 <= 0xFFFF:
        patches[8] = struct.pack(f"{dec.order}H", h_first + n_frames - 1)
        if "POINT:FRAMES" in data_at and params["POINT:FRAMES"][0] == 2 and n_frames <= 0xFFFF:
            patches[data_at["POINT:FRAMES"]] = struct.pack(f"{dec.order}H", n_frames)
    return C3DLayout(params, n_frames, first, is_float, notes, patches)


class _Worker:
    """One child process running :mod:`skilllib.recordings._c3d_worker`; replies read by a thread (timeouts)."""

    def __init__(self) -> None:
        worker = str(Path(__file__).with_name("_c3d_worker.py"))
        run = "import sys; exec(compile(open(sys.argv[1]).read(), sys.argv[1], 'exec'))"  # not run as a script:
        # its folder is not put first on sys.path (where _csv.py would hide the standard library's)
        self.pid = os.getpid()  # a forked copy of this process must start its own worker
        self.proc = subprocess.Popen(
            [sys.executable, "-c", run, worker],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
        )
        self.replies: queue.Queue = queue.Queue()
        threading.Thread(target=self._listen, daemon=True).start()
        self.ready = self.receive(START_TIMEOUT)

    def _listen(self) -> None:
        out = self.proc.stdout
        while True:
            head = out.read(8)
            if len(head) < 8:
                self.replies.put(None)  # the child ended (crash, kill or end of input)
                return
            n = struct.unpack("<Q", head)[0]
            body = out.read(n)
            if len(body) < n:
                self.replies.put(None)
                return
            self.replies.put(pickle.loads(body))

    def receive(self, timeout: float):
        """The next reply; ``("crashed", code)`` or ``("timeout", s)`` (and the child killed) when none comes."""
        try:
            reply = self.replies.get(timeout=timeout)
        except queue.Empty:
            self.stop()
            return ("timeout", timeout)
        if reply is None:
            self.stop()
            return ("crashed", self.proc.returncode)
        return reply

    def ask(self, request, timeout: float):
        data = pickle.dumps(request)
        try:
            self.proc.stdin.write(struct.pack("<Q", len(data)) + data)
            self.proc.stdin.flush()
        except OSError:
            self.stop()
            return ("crashed", self.proc.returncode)
        return self.receive(timeout)

    def alive(self) -> bool:
        return self.pid == os.getpid() and self.proc.poll() is None

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        for handle in (self.proc.stdin, self.proc.stdout):
            try:
                handle.close()
            except OSError:
                pass


_worker: _Worker | None = None
_lock = threading.Lock()


def _stop_worker() -> None:
    if _worker is not None and _worker.pid == os.getpid():
        _worker.stop()


atexit.register(_stop_worker)


def parse_c3d(path: Path, channel: str | None, size: int) -> dict:
    """Parse a C3D file with ezc3d in the worker process, started on first use and reused.

    Parameters
    ----------
    path : pathlib.Path
        The file (already checked by :func:`inspect_c3d`).
    channel : str or None
        Analog channel label to return (lower case, stripped text); None: none.
    size : int
        The file's size (bytes): the time limit grows with it.

    Returns
    -------
    dict
        ``points`` (n_frames, n_points, 3) in the file's unit, ``residuals`` (n_frames, n_points), ``params``
        (``{group: {name: value}}``), ``analogs`` (``{channel index: samples}``, scaled by ezc3d), ``n_analog``.

    Raises
    ------
    DataFormatError
        Naming the file when ezc3d refuses it, crashes or takes longer than the time limit.
    """
    global _worker
    timeout = PARSE_TIMEOUT + PARSE_TIMEOUT_PER_MB * size / 1e6
    with _lock:
        if _worker is None or not _worker.alive():
            _worker = _Worker()
            if _worker.ready[0] != "ready":
                why = _worker.ready[1]
                _worker.stop()
                _worker = None
                raise DataFormatError(f"{path}: could not be parsed: the C3D reader did not start ({why})")
        kind, value = _worker.ask((str(Path(path).resolve()), channel), timeout)
    if kind == "ok":
        return value
    if kind == "error":
        raise DataFormatError(f"{path}: not a readable C3D file ({value})")
    what = "crashed" if kind == "crashed" else f"timed out after {value:.0f} s"
    raise DataFormatError(f"{path}: could not be parsed (the C3D reader {what}): the file is damaged")
