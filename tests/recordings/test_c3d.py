"""Tests of skilllib.recordings' C3D reader (``read_c3d``): vendor variants, damaged files, real recordings.

Small files are written at test time by both libraries: ezc3d's writer (the reader's own library) and the
``c3d`` package's ``Writer`` (integer storage, its header conventions); damaged files are made by hand from
them. Every damaged, truncated, garbage or hostile file must give one :class:`DataFormatError` naming the
file, never a crash or a hang of the test process. The real recordings in ``data/real`` (see its
README) are checked against ezc3d read directly.
"""

from __future__ import annotations

import random
import struct
import time
import warnings
from pathlib import Path

import c3d
import ezc3d
import numpy as np
import pandas as pd
import pytest

from skilllib.recordings import (
    UNIT_FACTORS,
    DataFormatError,
    _c3d_safe,
    read_any,
    read_c3d,
    read_folder,
    recordings_from_frame,
)

FS = 100.0
REAL = Path(__file__).resolve().parents[2] / "data" / "real"


def approach(n: int = 80, fs: float = FS, drop: float = 0.12) -> np.ndarray:
    """(n, 3) book-frame path in m: 0.2 s rest, then a minimum-jerk descent of ``drop`` m in y that is cut
    at 80 % of its duration (still moving, as when the tip meets the surface), then at rest below."""
    t = np.arange(n) / fs
    tau = np.clip((t - 0.2) / 0.6, 0, 0.8)
    s = tau**3 * (10 - 15 * tau + 6 * tau**2)
    return np.column_stack([0.02 + 0.01 * s, 0.30 - drop * s, -0.05 + 0.03 * s])


def _pack(labels: list[str]) -> tuple[str, int]:
    width = max(len(s) for s in labels)
    return "".join(s.ljust(width) for s in labels), width


def write_c3d(
    path: Path,
    markers: dict[str, np.ndarray],
    *,
    rate: float = FS,
    units: str = "mm",
    first_frame: int = 1,
    analogs: dict[str, np.ndarray] | None = None,
    events: list[tuple[str, float]] = (),
    missing: dict[str, list[int]] | None = None,
    angles: list[str] = (),
    point_scale: float = -1.0,
) -> Path:
    """A C3D file written with the reader's library: ``markers`` name -> (n, 3) positions in the file's
    ``units`` (``""``: blank POINT:UNITS); ``missing`` frames get a negative residual (the C3D 'not seen');
    ``angles`` are extra points listed as POINT:ANGLES; ``analogs`` name -> (n * m,) samples, m per frame;
    ``events`` (label, time in s) in EVENT:LABELS / EVENT:TIMES; ``first_frame`` counted from 1;
    ``point_scale`` < 0: floats, > 0: integers of that many ``units``."""
    names = list(markers) + list(angles)
    n = len(next(iter(markers.values())))
    m = len(next(iter(analogs.values()))) // n if analogs else 0
    w = c3d.Writer(point_rate=rate, analog_rate=rate * m, point_scale=point_scale, point_units=units.ljust(4))
    w.set_point_labels(names)
    if analogs:
        w.set_analog_labels(list(analogs))
        w.set_analog_scales(np.ones(len(analogs)))  # c3d 0.6.0 leaves them empty otherwise: ezc3d crashes
        w.set_analog_offsets(np.zeros(len(analogs), dtype=int))
    if angles:
        w.point_group.add_str("ANGLES", "model outputs", *_pack(list(angles)), len(angles))
    frames = np.empty((n, 2), dtype=object)  # c3d 0.6.0: add_frames needs a prebuilt object array
    ana = np.stack([np.asarray(a, dtype=float).reshape(n, m) for a in analogs.values()], axis=1) if analogs else None
    for i in range(n):
        pts = np.zeros((len(names), 5))
        for j, name in enumerate(markers):
            pts[j, :3] = markers[name][i]
            if i in (missing or {}).get(name, ()):
                pts[j, 3] = -1
        pts[len(markers) :, :3] = 7.0
        frames[i, 0] = pts
        frames[i, 1] = ana[i] if analogs else np.zeros((0, 0))
    w.add_frames(frames)
    w.set_start_frame(first_frame)
    if events:
        g = w.add_group(50, "EVENT", "events")
        g.add_str("LABELS", "event labels", *_pack([lab for lab, _ in events]), len(events))
        times = np.array([[0.0, tm] for _, tm in events], dtype=np.float32)  # C3D dims [2, n]: minutes, seconds
        g.add_param(
            "TIMES", desc="event times", bytes_per_element=4, bytes=times.tobytes(), dimensions=[2, len(events)]
        )
        g.add("USED", "number of events", 2, "<H", len(events))
    with open(path, "wb") as handle, warnings.catch_warnings():
        warnings.simplefilter("ignore")  # c3d warns "No analog data found in file." for a file without analogs
        w.write(handle)
    return path


def write_ez(
    path: Path,
    markers: dict[str, np.ndarray],
    *,
    rate: float = FS,
    units: str = "mm",
    analogs: dict[str, np.ndarray] | None = None,
    events: list[tuple[str, float]] = (),
    first_frame: int = 1,
) -> Path:
    """A C3D file written by ezc3d (floats, POINT:SCALE -1): ``markers`` name -> (n, 3) positions in the
    file's ``units`` (NaN: not seen); ``analogs`` name -> (n * m,) samples; ``events`` (label, time in s);
    ``first_frame`` is set in the header after writing (0: the OptiTrack Motive numbering)."""
    n = len(next(iter(markers.values())))
    c = ezc3d.c3d()
    c["parameters"]["POINT"]["RATE"]["value"] = [rate]
    c["parameters"]["POINT"]["LABELS"]["value"] = tuple(markers)
    c["parameters"]["POINT"]["UNITS"]["value"] = [units]
    pts = np.ones((4, len(markers), n))
    for j, xyz in enumerate(markers.values()):
        pts[:3, j] = np.asarray(xyz, dtype=float).T
    c["data"]["points"] = pts
    if analogs:
        m = len(next(iter(analogs.values()))) // n
        c["parameters"]["ANALOG"]["RATE"]["value"] = [rate * m]
        c["parameters"]["ANALOG"]["LABELS"]["value"] = tuple(analogs)
        c["data"]["analogs"] = np.stack([np.asarray(a, dtype=float) for a in analogs.values()])[np.newaxis]
    if events:
        c.add_parameter("EVENT", "LABELS", [lab for lab, _ in events])
        c.add_parameter("EVENT", "TIMES", np.array([[0.0 for _ in events], [tm for _, tm in events]]))
    c.write(str(path))
    if first_frame != 1:
        patch(path, {6: struct.pack("<HH", first_frame, first_frame + n - 1)})
    return path


def patch(path: Path, changes: dict[int, bytes]) -> Path:
    """Overwrite bytes of a file in place: offset -> new bytes."""
    raw = bytearray(path.read_bytes())
    for offset, new in changes.items():
        raw[offset : offset + len(new)] = new
    path.write_bytes(bytes(raw))
    return path


def parameter_offset(raw: bytes, group_id: int, name: bytes) -> int:
    """Byte offset of the data of parameter ``name`` of group ``group_id`` (a test-side walk of the records)."""
    pos = (raw[0] - 1) * 512 + 4
    while True:
        nlen, gid = struct.unpack("bb", raw[pos : pos + 2])
        (step,) = struct.unpack("<h", raw[pos + 2 + abs(nlen) : pos + 4 + abs(nlen)])
        if gid == group_id and raw[pos + 2 : pos + 2 + abs(nlen)] == name:
            body = pos + 4 + abs(nlen)
            return body + 2 + raw[body + 1]
        pos += 2 + abs(nlen) + step


def _group_of(raw: bytes, name: bytes) -> int:
    """The id of parameter group ``name`` (a test-side walk of the records)."""
    pos = (raw[0] - 1) * 512 + 4
    while True:
        nlen, gid = struct.unpack("bb", raw[pos : pos + 2])
        (step,) = struct.unpack("<h", raw[pos + 2 + abs(nlen) : pos + 4 + abs(nlen)])
        if gid < 0 and raw[pos + 2 : pos + 2 + abs(nlen)] == name:
            return -gid
        pos += 2 + abs(nlen) + step


def write(writer: str, path: Path, markers: dict[str, np.ndarray], **kw) -> Path:
    """A C3D file by ``writer`` (``"ezc3d"`` or ``"c3d"``)."""
    return write_ez(path, markers, **kw) if writer == "ezc3d" else write_c3d(path, markers, **kw)


WRITERS = ["ezc3d", "c3d"]


# --- C3D -----------------------------------------------------------------------------------------


@pytest.mark.parametrize("units", ["mm", "cm", "m"])
def test_c3d_positions_in_metres_from_the_header_unit_and_time_from_the_rate(tmp_path, units):
    pos = approach()
    path = write_c3d(tmp_path / "a.c3d", {"tip": pos / UNIT_FACTORS[units]}, units=units, rate=FS)
    df = read_c3d(path)
    np.testing.assert_allclose(df[["x", "y", "z"]].to_numpy(), pos, rtol=1e-6, atol=1e-8)  # float32 in the file
    np.testing.assert_allclose(df["t"].to_numpy(), np.arange(len(pos)) / FS, rtol=0, atol=1e-12)
    assert df["contact"].isna().all()  # no channel, no event: left for the height rule
    frame, problems = read_any(path, contact_height=0.2)  # a stem without '_': participant and trial both
    assert frame[["participant", "trial"]].iloc[0].tolist() == ["a", "a"] and problems == []
    assert np.flatnonzero(frame["contact"].to_numpy())[0] == np.flatnonzero(pos[:, 1] <= 0.2)[0]


def test_c3d_time_keeps_the_capture_clock_of_a_cropped_trial(tmp_path):
    path = write_c3d(tmp_path / "a.c3d", {"tip": approach(20) * 1000}, rate=250.0, first_frame=51)
    t = read_c3d(path)["t"].to_numpy()
    assert t[0] == pytest.approx(50 / 250.0) and np.allclose(np.diff(t), 1 / 250.0)


def test_c3d_units_override_and_missing_units(tmp_path):
    pos = approach(20)
    path = write_c3d(tmp_path / "a.c3d", {"tip": pos * 100}, units="")
    with pytest.raises(DataFormatError, match=r"a\.c3d: no POINT:UNITS.*--units"):
        read_c3d(path)
    np.testing.assert_allclose(read_c3d(path, units="cm")[["x", "y", "z"]].to_numpy(), pos, rtol=1e-6)
    bad = write_c3d(tmp_path / "b.c3d", {"tip": pos}, units="in")
    with pytest.raises(DataFormatError, match=r"b\.c3d: POINT:UNITS: unknown length unit 'in' \(known: m, cm, mm\)"):
        read_c3d(bad)


def test_c3d_marker_by_name_and_vicon_subject_prefix(tmp_path):
    a, b = approach(20), approach(20) + 0.5
    path = write_c3d(tmp_path / "a.c3d", {"Sub1:tip": a * 1000, "Sub1:wrist": b * 1000})
    np.testing.assert_allclose(read_c3d(path, marker="Sub1:wrist")["y"], b[:, 1], rtol=1e-6)
    np.testing.assert_allclose(read_c3d(path, marker="tip")["y"], a[:, 1], rtol=1e-6)


def test_c3d_several_markers_without_a_name_or_an_unknown_name_list_the_markers(tmp_path):
    path = write_c3d(tmp_path / "a.c3d", {"tip": approach(20), "wrist": approach(20)})
    with pytest.raises(DataFormatError, match=r"a\.c3d: 2 markers \(tip, wrist\): choose one with --marker NAME"):
        read_c3d(path)
    with pytest.raises(DataFormatError, match=r"a\.c3d: no marker 'elbow' \(markers: tip, wrist\)"):
        read_c3d(path, marker="elbow")


def test_c3d_model_outputs_are_not_markers(tmp_path):
    pos = approach(20)
    path = write_c3d(tmp_path / "a.c3d", {"tip": pos * 1000}, angles=["LElbowAngles"])
    np.testing.assert_allclose(read_c3d(path)["x"], pos[:, 0], rtol=1e-6)


def test_c3d_gaps_are_nan_and_the_trial_is_invalid_with_the_sample(tmp_path):
    pos = approach(30) * 1000
    pos[12] = 0.0  # the all-zero convention
    path = write_c3d(tmp_path / "P1_1.c3d", {"tip": pos}, missing={"tip": [5]}, events=[("contact", 0.25)])
    df = read_c3d(path)
    nan_rows = np.flatnonzero(df[["x", "y", "z"]].isna().any(axis=1).to_numpy())
    assert nan_rows.tolist() == [5, 12] and df[["x", "y", "z"]].iloc[[5, 12]].isna().all().all()
    frame, _ = read_any(path)
    rec = recordings_from_frame(frame)
    trial = rec.trials.iloc[0]  # the gaps reach the checks: an invalid trial, or gaps filled and said
    assert "missing (NaN) at row 5" in trial.reason or "0.050 s" in trial.get("repairs", "")


def test_c3d_contact_from_an_analog_channel_at_the_right_point_frame(tmp_path):
    n, m = 40, 10  # analog at 10 x the point rate
    volts = np.full(n * m, 0.2)
    volts[178:] = 4.8  # first high analog sample in point frame 17 (samples 170..179): "any", not "mean"
    path = write_c3d(
        tmp_path / "a.c3d", {"tip": approach(n) * 1000}, analogs={"force": np.zeros(n * m), "Contact": volts}
    )
    c = read_c3d(path)["contact"].to_numpy()
    assert c.tolist() == [0.0] * 17 + [1.0] * (n - 17)
    # an explicit threshold (the channel's units) above the high level: never in contact
    assert read_c3d(path, contact_threshold=5.0)["contact"].sum() == 0
    # a named channel; a constant channel is never in contact
    assert read_c3d(path, contact_channel="force")["contact"].tolist() == [0.0] * n


def test_c3d_contact_from_an_event_from_the_first_frame_at_or_after_it(tmp_path):
    n = 40
    path = write_c3d(
        tmp_path / "a.c3d",
        {"tip": approach(n) * 1000},
        first_frame=51,
        events=[("Other", 0.51), ("touch", 0.5 + 0.123), ("touch", 0.5 + 0.3)],
    )
    c = read_c3d(path, contact_channel="touch")["contact"].to_numpy()
    assert np.flatnonzero(c)[0] == 13 and c[13:].all()  # t = 0.63 s, the first frame after 0.623 s
    exact = write_c3d(tmp_path / "b.c3d", {"tip": approach(n) * 1000}, events=[("contact", 0.07)])
    c = read_c3d(exact)["contact"].to_numpy()  # 0.07 s is not exact in float32: still frame 7
    assert np.flatnonzero(c)[0] == 7


def test_c3d_named_contact_channel_missing_lists_channels_and_events(tmp_path):
    path = write_c3d(
        tmp_path / "a.c3d", {"tip": approach(20)}, analogs={"Fz": np.zeros(40)}, events=[("Foot Strike", 0.1)]
    )
    with pytest.raises(
        DataFormatError,
        match=r"a\.c3d: no analog channel or event 'touch' "
        r"\(analog channels: Fz; events: Foot Strike\)",
    ):
        read_c3d(path, contact_channel="touch")


def test_c3d_not_a_c3d_file(tmp_path):
    bad = tmp_path / "x.c3d"
    bad.write_bytes(b"not a c3d file at all" * 40)
    with pytest.raises(DataFormatError, match=r"x\.c3d: not a readable C3D file"):
        read_c3d(bad)
    with pytest.raises(DataFormatError, match=r"y\.c3d: file not found"):
        read_c3d(tmp_path / "y.c3d")


def test_c3d_cut_short_or_damaged_raises_a_one_line_error_never_another_exception(tmp_path):
    pos = approach(30) * 1000
    good = write_c3d(
        tmp_path / "good.c3d",
        {"tip": pos},
        analogs={"contact": np.r_[np.zeros(30), np.ones(30)]},
        events=[("Foot Strike", 0.1)],
    )
    raw = good.read_bytes()
    want = read_c3d(good)
    cut = tmp_path / "cut.c3d"
    outcomes = set()
    for n in range(0, len(raw), 32):
        cut.write_bytes(raw[:n])
        try:
            got = read_c3d(cut)
        except DataFormatError as e:
            assert "\n" not in str(e) and str(e).startswith(str(cut))
            outcomes.add(str(e).split(" (")[0].split(":")[1].strip())
        else:  # cut in the padding after the last frame: the data are complete
            pd.testing.assert_frame_equal(got, want)
            outcomes.add("read")
    assert {"not a readable C3D file", "file cut short", "read"} <= outcomes
    rng = random.Random(1)
    bad = tmp_path / "bad.c3d"
    for _ in range(40):  # 3 random bytes changed in the header and parameter section
        b = bytearray(raw)
        for _ in range(3):
            b[rng.randrange(0, 1536)] = rng.randrange(256)
        bad.write_bytes(bytes(b))
        try:
            read_c3d(bad)
        except DataFormatError:
            pass


# --- vendor variants, both writers ----------------------------------------------------------------


@pytest.mark.parametrize("writer", WRITERS)
@pytest.mark.parametrize("first_frame", [0, 1])
def test_first_frame_0_or_1_keeps_every_frame_and_starts_at_0_s(tmp_path, writer, first_frame):
    pos = approach(30)
    path = write(writer, tmp_path / "a.c3d", {"tip": pos * 1000}, rate=FS, first_frame=first_frame)
    if writer == "c3d" and first_frame == 0:  # c3d's Writer has no frame 0: number it as Motive does
        patch(path, {6: struct.pack("<HH", 0, 29)})
    df = read_c3d(path)
    assert len(df) == 30 and df["t"].iloc[0] == 0.0
    np.testing.assert_allclose(df["t"].to_numpy(), np.arange(30) / FS, atol=1e-12)
    np.testing.assert_allclose(df[["x", "y", "z"]].to_numpy(), pos, rtol=1e-6, atol=1e-8)
    assert df.attrs["units"] == "mm" and df.attrs["notes"] == []


@pytest.mark.parametrize("scale", [-1.0, -0.1, 0.1, 0.05])
def test_float_and_integer_storage_either_scale_sign(tmp_path, scale):
    pos = approach(30)
    path = write_c3d(tmp_path / "a.c3d", {"tip": pos * 1000}, point_scale=scale)
    assert (struct.unpack("<f", path.read_bytes()[12:16])[0] < 0) == (scale < 0)
    got = read_c3d(path)[["x", "y", "z"]].to_numpy()
    tol = 1e-8 if scale < 0 else scale / 1000  # an integer file keeps one scale step (mm -> m)
    np.testing.assert_allclose(got, pos, atol=tol)


def test_ezc3d_writes_float_with_a_negative_scale(tmp_path):
    path = write_ez(tmp_path / "a.c3d", {"tip": approach(20)}, units="m")
    assert struct.unpack("<f", path.read_bytes()[12:16])[0] == -1.0
    np.testing.assert_allclose(read_c3d(path)["y"], approach(20)[:, 1], rtol=1e-6)


@pytest.mark.parametrize("writer", WRITERS)
def test_unnamed_markers_are_named_by_their_point_number(tmp_path, writer):
    a, b = approach(20), approach(20) + 0.3
    path = write(writer, tmp_path / "a.c3d", {"": a * 1000, "tip": b * 1000})
    if writer == "c3d":  # its Writer pads labels: blank the first one by hand
        off = parameter_offset(path.read_bytes(), _group_of(path.read_bytes(), b"POINT"), b"LABELS")
        raw = path.read_bytes()
        patch(path, {off: b" " * raw[off - 2]})
    with pytest.raises(DataFormatError, match=r"2 markers \(unnamed_1, tip\)"):
        read_c3d(path)
    np.testing.assert_allclose(read_c3d(path, marker="unnamed_1")["y"], a[:, 1], rtol=1e-6)
    np.testing.assert_allclose(read_c3d(path, marker="tip")["y"], b[:, 1], rtol=1e-6)


def test_ezc3d_gaps_not_seen_and_all_zero_are_nan(tmp_path):
    pos = approach(30) * 1000
    pos[5] = np.nan  # ezc3d writes a negative residual
    pos[12] = 0.0
    df = read_c3d(write_ez(tmp_path / "a.c3d", {"tip": pos}))
    assert np.flatnonzero(df[["x", "y", "z"]].isna().any(axis=1).to_numpy()).tolist() == [5, 12]


def test_ezc3d_analog_at_10x_the_point_rate_and_events(tmp_path):
    n, m = 40, 10
    volts = np.full(n * m, 0.2)
    volts[178:] = 4.8
    path = write_ez(
        tmp_path / "a.c3d",
        {"tip": approach(n) * 1000},
        analogs={"force": np.zeros(n * m), "Contact": volts},
        events=[("Other", 0.05), ("touch", 0.123)],
    )
    assert read_c3d(path)["contact"].tolist() == [0.0] * 17 + [1.0] * (n - 17)
    c = read_c3d(path, contact_channel="touch")["contact"].to_numpy()
    assert np.flatnonzero(c)[0] == 13 and c[13:].all()


def test_header_and_parameter_frame_counts_disagree_the_data_present_are_read(tmp_path):
    pos = approach(30) * 1000
    path = write_ez(tmp_path / "a.c3d", {"tip": pos})
    patch(path, {8: struct.pack("<H", 45)})  # the header announces 45 frames, POINT:FRAMES 30, the data 30
    df = read_c3d(path)
    assert len(df) == 30 and "frame counts disagree (the header 45, POINT:FRAMES 30)" in df.attrs["notes"][0]
    patch(path, {8: struct.pack("<H", 20)})  # the header 20: the data hold 30 (POINT:FRAMES)
    assert len(read_c3d(path)) == 30
    raw = path.read_bytes()
    patch(path, {parameter_offset(raw, _group_of(raw, b"POINT"), b"FRAMES"): struct.pack("<H", 12)})
    assert len(read_c3d(path)) == 20  # the largest count the data hold, not past it


def test_a_huge_announced_frame_count_is_a_file_cut_short(tmp_path):
    path = write_ez(tmp_path / "a.c3d", {"tip": approach(30) * 1000})
    patch(path, {8: struct.pack("<H", 65000)})
    patch(
        path,
        {
            parameter_offset(path.read_bytes(), _group_of(path.read_bytes(), b"POINT"), b"FRAMES"): struct.pack(
                "<H", 65000
            )
        },
    )
    with pytest.raises(DataFormatError, match=r"a\.c3d: file cut short: the header 65000, POINT:FRAMES 65000"):
        read_c3d(path)


# --- damaged files ---------------------------------------------------------------------------------


def _outcome(path: Path, want: pd.DataFrame | None) -> str:
    """``read`` (and equal to ``want`` unless None) or the error's kind; anything but DataFormatError fails."""
    try:
        got = read_c3d(path)
    except DataFormatError as e:
        msg = str(e)
        assert "\n" not in msg and msg.startswith(f"{path}: "), msg
        return msg[len(str(path)) + 2 :].split(" (")[0].split(":")[0]
    if want is not None:
        pd.testing.assert_frame_equal(got, want)
    return "read"


@pytest.mark.parametrize("writer", WRITERS)
def test_truncated_at_many_offsets_or_bytes_changed_in_the_parameters_one_error_each(tmp_path, writer):
    n = 30
    good = write(
        writer, tmp_path / "good.c3d", {"tip": approach(n) * 1000}, analogs={"contact": np.r_[np.zeros(n), np.ones(n)]}
    )
    raw = good.read_bytes()
    want = read_c3d(good)
    bad = tmp_path / "bad.c3d"
    cuts = set()
    for cut in [0, 1, 3, 100, 511, 512, 513, 600, 800, 1000, 1023, 1024, 1100, 1536, 1600, len(raw) - 700]:
        bad.write_bytes(raw[:cut])
        cuts.add(_outcome(bad, want))
    assert {"not a readable C3D file", "file cut short"} <= cuts
    rng = random.Random(1)
    start, end = 512, (raw[0] - 1 + raw[(raw[0] - 1) * 512 + 2]) * 512
    changed = []
    for _ in range(40):  # 3 random bytes changed in the parameter section: the copies that crashed ezc3d
        b = bytearray(raw)
        for _ in range(3):
            b[rng.randrange(start, end)] = rng.randrange(256)
        bad.write_bytes(bytes(b))
        changed.append(_outcome(bad, None))  # a changed label or description reads, differently
    assert "not a readable C3D file" in changed


def test_garbage_empty_and_hostile_headers(tmp_path):
    bad = tmp_path / "x.c3d"
    rng = np.random.default_rng(3)
    for content in [b"", b"\x00" * 5000, rng.bytes(5000), b"\x02\x50" + rng.bytes(5000), b"\x02\x50" + b"\xff" * 3000]:
        bad.write_bytes(content)
        with pytest.raises(DataFormatError, match=r"x\.c3d: "):
            read_c3d(bad)
    good = write_ez(tmp_path / "good.c3d", {"tip": approach(20)})
    raw = good.read_bytes()
    p0 = (raw[0] - 1) * 512
    for offset, new in [
        (0, b"\xff"),  # the parameter section past the end of the file
        (p0 + 2, b"\x00"),  # 0 parameter blocks
        (p0 + 3, b"\x07"),  # unknown processor
        (parameter_offset(raw, _group_of(raw, b"POINT"), b"DATA_START"), struct.pack("<H", 1)),  # in the header
        (parameter_offset(raw, _group_of(raw, b"POINT"), b"SCALE"), struct.pack("<f", np.nan)),
        (parameter_offset(raw, _group_of(raw, b"POINT"), b"RATE"), struct.pack("<f", -5.0)),
        (parameter_offset(raw, _group_of(raw, b"POINT"), b"USED"), struct.pack("<H", 60000)),  # 60000 points: cut short
    ]:
        bad.write_bytes(raw[:offset] + new + raw[offset + len(new) :])
        with pytest.raises(DataFormatError, match=r"x\.c3d: (not a readable C3D file|file cut short)"):
            read_c3d(bad)


def _permissive(path, raw):
    """The Python check switched off (a file it would refuse reaches ezc3d): every frame counted."""
    return _c3d_safe.C3DLayout(params={}, n_frames=20, first_frame=1, is_float=True)


def test_analog_scales_or_offsets_missing_for_a_channel_are_refused(tmp_path):
    path = write_c3d(tmp_path / "a.c3d", {"tip": approach(10) * 1000}, analogs={"a": np.ones(20), "b": np.ones(20)})
    raw = path.read_bytes()
    at = parameter_offset(raw, _group_of(raw, b"ANALOG"), b"SCALE") - 1
    patch(path, {at: b"\x01"})  # ANALOG:SCALE with 1 value for 2 channels (what c3d's Writer leaves: 0)
    with pytest.raises(DataFormatError, match=r"a\.c3d: not a readable C3D file \(ANALOG:SCALE has 1 values for 2"):
        read_c3d(path)


def test_ezc3d_crashing_or_hanging_is_one_error_and_the_next_file_is_read(tmp_path, monkeypatch):
    good = write_ez(tmp_path / "good.c3d", {"tip": approach(20) * 1000}, events=[("x", 0.1)])
    raw = good.read_bytes()
    crash = tmp_path / "crash.c3d"  # FORCE_PLATFORM:CORNERS with 216 dimensions: ezc3d 1.7.2 segfaults
    at = raw.index(b"CORNERS") + len(b"CORNERS") + 3
    crash.write_bytes(raw[:at] + b"\xd8" + raw[at + 1 :])
    hang = tmp_path / "hang.c3d"  # the description of EVENT:LABELS runs over the next record: ezc3d loops
    at = raw.index(b"TIMES") - 3
    hang.write_bytes(raw[:at] + b"\x88" + raw[at + 1 :])
    for path in (crash, hang):  # the Python check refuses both before ezc3d sees them
        with pytest.raises(DataFormatError, match=r"not a readable C3D file \(parameter"):
            read_c3d(path)
    monkeypatch.setattr("skilllib.recordings._c3d.inspect_c3d", _permissive)
    monkeypatch.setattr(_c3d_safe, "PARSE_TIMEOUT", 2.0)
    with pytest.raises(DataFormatError, match=r"crash\.c3d: could not be parsed \(the C3D reader crashed\)"):
        read_c3d(crash)
    t0 = time.perf_counter()
    with pytest.raises(DataFormatError, match=r"hang\.c3d: could not be parsed \(the C3D reader timed out after 2 s"):
        read_c3d(hang)
    assert time.perf_counter() - t0 < 6
    assert len(read_c3d(good)) == 20  # a new worker reads the next file


def test_a_folder_of_c3d_files_with_a_damaged_one(tmp_path):
    pos = approach(30) * 1000
    for k in range(1, 4):
        write(WRITERS[k % 2], tmp_path / f"P1_{k}.c3d", {"tip": pos}, events=[("contact", 0.1)])
    (tmp_path / "P1_4.c3d").write_bytes(good := (tmp_path / "P1_1.c3d").read_bytes()[:1000])
    assert good
    frame, problems = read_folder(tmp_path)
    assert frame["trial"].unique().tolist() == ["1", "2", "3"] and len(frame) == 90
    assert [Path(p.path).name for p in problems] == ["P1_4.c3d"]
    assert problems[0].reason.startswith(("not a readable C3D file", "file cut short"))


# --- real recordings (data/real, README there) ----------------------------------------------


def test_real_vicon_nexus_file_pyomeca():
    path = REAL / "pyomeca_markers_analogs.c3d"
    df = read_c3d(path, marker="INDEX")
    c = ezc3d.c3d(str(path))
    labels = c["parameters"]["POINT"]["LABELS"]["value"]
    tails = [lab.rsplit(":", 1)[-1] for lab in labels]
    assert len(labels) == 51 and {"WRIST", "INDEX"} <= set(tails)
    assert len(df) == 580 and df.attrs["units"] == "mm" and df.attrs["notes"] == []
    np.testing.assert_allclose(np.diff(df["t"]), 0.01, atol=1e-12)
    assert df["t"].iloc[0] == 0.0  # the header's first frame is 1
    k = tails.index("INDEX")
    first = np.flatnonzero(~np.isnan(c["data"]["points"][0, k]))[0]
    np.testing.assert_allclose(df[["x", "y", "z"]].iloc[first], c["data"]["points"][:3, k, first] / 1000)
    assert df["contact"].isna().all()  # no contact channel or event
    assert c["data"]["analogs"].shape == (1, 38, 11600)  # 2000 Hz: 20 samples per point frame
    volts = read_c3d(path, marker="INDEX", contact_channel="Voltage.1")["contact"]
    assert set(volts.unique()) == {0.0, 1.0}


def test_real_wheelchair_propulsion_file_kineticstoolkit():
    path = REAL / "ktk_sample_propulsion.c3d"
    c = ezc3d.c3d(str(path))
    labels = c["parameters"]["POINT"]["LABELS"]["value"]
    assert len(labels) == 41
    with pytest.raises(DataFormatError, match=r"41 markers"):
        read_c3d(path)
    name = labels[-1]
    df = read_c3d(path, marker=name)
    assert len(df) == 700 and df.attrs["units"] == "m"
    assert 1 / np.diff(df["t"]).mean() == pytest.approx(69.9926, abs=1e-3)
    k = labels.index(name)
    first = np.flatnonzero(~np.isnan(c["data"]["points"][0, k]))[0]
    np.testing.assert_allclose(df[["x", "y", "z"]].iloc[first], c["data"]["points"][:3, k, first])
