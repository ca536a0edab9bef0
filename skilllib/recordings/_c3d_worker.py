"""The child process that parses C3D files with ezc3d for :mod:`skilllib.recordings` (the safety design is in
:mod:`skilllib.recordings._c3d`).

Run by :mod:`skilllib.recordings._c3d_safe` with ``python -c`` executing this file: never imported by the library,
so a crash or an endless loop of ezc3d's C++ parser ends this process only. The protocol on stdin/stdout: an
8-byte little-endian length, then a pickle. The child first sends ``("ready", version)``; each request
``(path, channel)`` gets ``("ok", result)`` or ``("error", message)``; end of stdin ends the child.
"""

import os
import pickle
import struct
import sys

GROUPS = ("POINT", "ANALOG", "EVENT", "TRIAL")  #: parameter groups sent back


def _value(v):
    """A parameter's value as plain lists/arrays (ezc3d gives lists of text or numpy arrays)."""
    return [str(s) for s in v] if isinstance(v, list | tuple) else v


def read(path: str, channel: str | None) -> dict:
    """What :func:`skilllib.recordings.read_c3d` needs from one file: points, residuals, parameters and the
    analog channels labelled ``channel`` (compared stripped, without case)."""
    import ezc3d
    import numpy as np

    c = ezc3d.c3d(path)
    pts = np.asarray(c["data"]["points"], dtype=float)  # (4, n_points, n_frames)
    res = np.asarray(c["data"]["meta_points"]["residuals"], dtype=float)  # (1, n_points, n_frames)
    params = {
        g: {k: _value(p["value"]) for k, p in c["parameters"][g].items() if k != "__METADATA__"}
        for g in GROUPS
        if g in c["parameters"]
    }
    analog = np.asarray(c["data"]["analogs"], dtype=float)  # (1, n_channels, n_samples)
    labels = [str(s).strip().lower() for s in params.get("ANALOG", {}).get("LABELS", [])]
    wanted = {} if channel is None else {i: analog[0, i].copy() for i, s in enumerate(labels) if s == channel}
    return {
        "points": np.ascontiguousarray(pts[:3].transpose(2, 1, 0)),  # (n_frames, n_points, 3)
        "residuals": np.ascontiguousarray(res[0].T),  # (n_frames, n_points)
        "params": params,
        "analogs": wanted,
        "n_analog": analog.shape[2],
    }


def serve() -> None:
    """Answer requests until stdin ends (protocol in the module docstring)."""
    out = os.fdopen(os.dup(1), "wb")  # the protocol's own channel; fd 1 goes to stderr (C++ prints cannot mix in)
    os.dup2(2, 1)
    inp = sys.stdin.buffer

    def send(msg) -> None:
        data = pickle.dumps(msg, protocol=pickle.HIGHEST_PROTOCOL)
        out.write(struct.pack("<Q", len(data)) + data)
        out.flush()

    try:
        import ezc3d
    except Exception as e:  # not installed: one clear message
        send(("error", f"ezc3d cannot be imported ({type(e).__name__}: {e})"))
        return
    send(("ready", getattr(ezc3d, "__version__", "?")))
    while True:
        head = inp.read(8)
        if len(head) < 8:
            return
        path, channel = pickle.loads(inp.read(struct.unpack("<Q", head)[0]))
        try:
            reply = ("ok", read(path, channel))
        except Exception as e:  # ezc3d raises RuntimeError, OSError, ValueError, ... on files it refuses
            text = str(e).strip().splitlines()
            reply = ("error", f"{type(e).__name__}: {text[0] if text else ''}"[:200])
        send(reply)


if __name__ == "__main__":
    serve()
