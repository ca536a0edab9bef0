"""Edge cases of skilllib.recordings: the unit advice for time stamps not in seconds, the text of what
resampling bridged, and resample_uniform on hand-made trials whose right answer is known exactly.

resample_uniform is checked against its definition: the grid ``t[0] + k dt`` up to the last time stamp,
interpolation (a grid time equal to a time stamp returns that sample), a cubic spline per part (it
reproduces any polynomial of degree <= 3, so a straight approach stays straight and a parabola stays a
parabola), linear interpolation for parts of 2 or 3 samples, a constant for a part of one sample, and
contact from the first grid time at or after the first contact sample. The time stamps sit on multiples of
DT = 1/64 s (exact in binary), so grid times can coincide exactly with time stamps.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from skilllib.recordings import (
    MAX_QUOTE,
    MIN_RATE_HZ,
    TRIM,
    Irregularity,
    gap_after_contact,
    grid_jitter,
    irregularity,
    quote,
    regular_mean_interval,
    resample_uniform,
    time_quantum,
    time_unit_advice,
)

DT = 2.0**-6  # s (64 Hz): multiples are exact
T0 = 3.0  # s: a trial that does not start at 0 (catches t[-1] + t[0] for t[-1] - t[0])
V = 0.25  # m/s: approach speed (straight line)
Y0 = 0.1  # m: height at T0
Y_CONTACT = 0.07  # m: the height in contact, not on the approach line (a velocity and position step)
X_CONST, Z_CONST = 0.01, -0.02  # m


def approach_line(t):
    """(N, 3) positions of a straight approach at speed V along -y."""
    t = np.asarray(t, dtype=float)
    return np.column_stack([np.full_like(t, X_CONST), Y0 - V * (t - T0), np.full_like(t, Z_CONST)])


def jittered_times(n: int, dropped=(), jitter=()) -> np.ndarray:
    """T0 + k DT for k = 0 .. n-1 without the frames in ``dropped``, the frames in ``jitter`` (index ->
    fraction of DT) moved off the grid."""
    k = np.array([i for i in range(n) if i not in dropped], dtype=float)
    for i, f in dict(jitter).items():
        k[k == i] += f
    return T0 + k * DT


def on_grid(t_grid, t):
    """Indices (into t_grid, into t) of grid times that equal a time stamp exactly."""
    _, gi, ti = np.intersect1d(t_grid, t, return_indices=True)
    return gi, ti


# --- time_unit_advice ------------------------------------------------------------------------------


def test_unit_advice_states_the_rate_in_seconds_and_in_the_unit():
    """A median step of 20 (milliseconds at 50 Hz): 1/20 = 0.05 Hz if t were in seconds, 1000/20 = 50 Hz in
    milliseconds (catches 1 * step or 2 / step for 1 / step in the first rate)."""
    step = 20.0
    msg = time_unit_advice(step)
    assert "median time step 20 between samples: 0.05 Hz if t were in seconds" in msg
    assert f"below {MIN_RATE_HZ:g} Hz" in msg
    assert msg.startswith("time stamps look like milliseconds") and "50 Hz in milliseconds" in msg
    assert msg.endswith("divide t by 1000")


def test_unit_advice_at_the_slowest_rate_in_milliseconds_names_milliseconds():
    """A step of 1000 / MIN_RATE_HZ is exactly MIN_RATE_HZ in milliseconds: still milliseconds (catches
    ``<`` for ``<=`` at the lower bound, which would advise microseconds)."""
    step = 1e3 / MIN_RATE_HZ
    msg = time_unit_advice(step)
    assert msg.startswith("time stamps look like milliseconds") and msg.endswith("divide t by 1000")
    assert f"{MIN_RATE_HZ:g} Hz in milliseconds" in msg


def test_unit_advice_for_a_step_too_long_for_any_unit():
    """A step of 1e7 is under MIN_RATE_HZ even in microseconds: no unit is suggested."""
    msg = time_unit_advice(1e7)
    assert msg.startswith("time stamps are not in seconds (median time step 1e+07 between samples")
    assert msg.endswith("; t must be in seconds") and "divide" not in msg


# --- Irregularity.describe -----------------------------------------------------------------------


@pytest.mark.parametrize("dropped, tail", [(0, ""), (1, ", 1 dropped frame"), (2, ", 2 dropped frames")])
def test_describe_names_jitter_in_ms_and_dropped_frames_in_the_right_number(dropped, tail):
    """frame_jitter 0.475 of dt = 4 ms is 1.9 ms; one dropped frame is singular, two plural, none not said
    (catches the jitter not converted by x dt x 1000, a wrong plural threshold and a wrong separator)."""
    irr = Irregularity(max_jitter=1.0, dropped=dropped, max_interval=0.008, at=3, dt=0.004, frame_jitter=0.475)
    assert irr.describe() == "jitter up to 1.9 ms" + tail


def test_describe_rounds_the_jitter_to_two_digits_of_its_true_value():
    """1.949 ms is said as 1.9 ms: a factor slightly off 1000 (1.95 ms and more) would say 2."""
    jitter_ms = 1.949
    dt = 0.004
    irr = Irregularity(
        max_jitter=jitter_ms / (1e3 * dt), dropped=0, max_interval=dt, at=1, dt=dt, frame_jitter=jitter_ms / (1e3 * dt)
    )
    assert irr.describe() == "jitter up to 1.9 ms"


def test_irregularity_counts_dropped_frames_and_finds_the_longest_interval():
    """Frames 5 and 6 dropped (an interval of 3 DT before sample 5 of the kept ones), frame 9 late by DT/4."""
    t = jittered_times(14, dropped=(5, 6), jitter={9: 0.25})
    irr = irregularity(t, DT)
    assert irr.dropped == 2 and irr.max_interval == 3 * DT and irr.at == 5
    assert irr.max_jitter == pytest.approx(2.0) and not irr.regular and not irr.gap
    assert irr.frame_jitter == pytest.approx(0.25)


def test_a_dropped_frame_is_not_reported_as_jitter():
    """An interval of two frames is a dropped frame, not a frame of jitter: describe() says the jitter of
    the late frame only (DT / 4 = 1 ms), where max_jitter counts the dropped frame as 1.0 x DT."""
    t = jittered_times(14, dropped=(5,), jitter={9: 0.25})
    irr = irregularity(t, DT)
    assert irr.max_jitter == pytest.approx(1.0) and irr.frame_jitter == pytest.approx(0.25)
    assert irr.describe() == f"jitter up to {1e3 * DT / 4:.2g} ms, 1 dropped frame"


# --- resample_uniform -------------------------------------------------------------------------------


def parabola(t):
    """(N, 3) positions along a parabola (degree 2: a cubic spline reproduces it, a line does not)."""
    s = np.asarray(t, dtype=float) - T0
    return np.column_stack([0.3 * s**2, Y0 - s + 2.0 * s**2, -0.5 * s])


def trial(n=40, first_contact=20, dropped=(7, 31), jitter=None):
    """Time stamps on the DT grid from T0 except dropped and jittered frames; a straight approach, then
    the tip held at Y_CONTACT from the first contact frame (an index into the full, undropped grid)."""
    if jitter is None:
        jitter = {3: 0.3, 12: -0.25, 26: 0.2, 35: -0.3}
    t = jittered_times(n, dropped, jitter)
    pos = approach_line(t)
    contact = t >= T0 + first_contact * DT
    pos[contact, 1] = Y_CONTACT
    return t, pos, contact


def expected_grid(t):
    """The grid by definition: T0 + k DT up to the last time stamp (all exact here)."""
    n_intervals = int((t[-1] - t[0]) / DT)
    assert n_intervals * DT == t[-1] - t[0]  # the last time stamp is on the grid
    return t[0] + DT * np.arange(n_intervals + 1)


def test_resampled_grid_starts_at_the_first_and_ends_at_the_last_time_stamp():
    """The grid includes the last time stamp when it is on the grid (catches a count rounded down by
    dividing by (1 + 1e-9) or multiplying by (1 - 1e-9), and t[-1] + t[0] for the span)."""
    t, pos, contact = trial()
    grid, _, _ = resample_uniform(t, pos, contact, DT)
    np.testing.assert_array_equal(grid, expected_grid(t))


def test_the_grid_keeps_the_last_time_stamp_when_the_span_divides_just_under_an_integer():
    """At 100 Hz, 29 intervals of 1/100 s divide to 28.999999999999996: the grid still has 30 points (the
    relative margin of 1e-9 in the count; catches (1 - 1e-9))."""
    fs, n = 100.0, 30
    t = np.arange(n) / fs
    assert (t[-1] - t[0]) / (1 / fs) < n - 1  # the float quotient is just under the integer
    t[5] += 0.2 / fs  # one jittered sample
    pos = np.column_stack([t, t**2, np.zeros(n)])
    grid, out, _ = resample_uniform(t, pos, np.zeros(n, bool), 1 / fs)
    assert len(grid) == n and grid[-1] == pytest.approx(t[-1], abs=1e-12)


def test_approach_and_contact_are_interpolated_separately():
    """A straight approach stays exactly straight up to the first contact sample and the contact part
    stays at its constant height: one spline through both would ring across the step (catches the
    approach or contact part taking all samples or the other's)."""
    t, pos, contact = trial()
    grid, out, con = resample_uniform(t, pos, contact, DT)
    tc = t[contact][0]
    before = grid < tc
    assert before.sum() == 20 and (~before).sum() == len(grid) - 20
    np.testing.assert_allclose(out[before], approach_line(grid[before]), rtol=0, atol=1e-12)
    np.testing.assert_allclose(out[~before, 1], Y_CONTACT, rtol=0, atol=1e-12)
    np.testing.assert_allclose(out[:, [0, 2]], np.tile([X_CONST, Z_CONST], (len(grid), 1)), rtol=0, atol=1e-12)


def test_a_grid_time_equal_to_a_time_stamp_returns_that_sample():
    """Interpolation: at every grid time that is a time stamp (the first contact sample included, which
    the approach spline would extrapolate instead: catches ``<=`` for ``<`` in choosing the part)."""
    t, pos, contact = trial()
    grid, out, _ = resample_uniform(t, pos, contact, DT)
    gi, ti = on_grid(grid, t)
    assert len(gi) >= len(t) - 4 and np.flatnonzero(contact)[0] in ti
    np.testing.assert_allclose(out[gi], pos[ti], rtol=0, atol=1e-12)


def test_contact_starts_at_the_grid_time_of_the_first_contact_sample():
    """The first contact sample at T0 + 20 DT, on the grid: contact from grid point 20 on, not 21
    (catches ``>`` for ``>=``)."""
    t, pos, contact = trial()
    grid, _, con = resample_uniform(t, pos, contact, DT)
    np.testing.assert_array_equal(con, np.arange(len(grid)) >= 20)


def test_contact_from_the_first_grid_time_after_the_midpoint_before_the_first_contact_sample():
    """The first contact sample jittered to T0 + 20.3 DT, the last approach sample at T0 + 19 DT: contact
    began at about T0 + 19.65 DT, so from grid point 20 (catches carrying the approach on to the first
    contact sample), and grid point 20 lies on the straight line between samples 19 and 20
    (interpolated, never extrapolated from the approach spline)."""
    t, pos, contact = trial(jitter={20: 0.3})
    grid, out, con = resample_uniform(t, pos, contact, DT)
    np.testing.assert_array_equal(con, np.arange(len(grid)) >= 20)
    c = int(np.flatnonzero(contact)[0])  # frame 20 (frame 7 is dropped)
    w = (grid[20] - t[c - 1]) / (t[c] - t[c - 1])
    assert 0 < w < 1
    np.testing.assert_allclose(out[20], (1 - w) * pos[c - 1] + w * pos[c], rtol=0, atol=1e-12)


def test_no_grid_sample_is_extrapolated_from_the_approach():
    """Whatever the jitter, every grid sample between the last approach and the first contact sample lies
    between their positions (an extrapolated spline overshoots past them: the issue's 2.6-4.1 mm), and
    contact begins at the midpoint between the two samples."""
    rng = np.random.default_rng(3)
    for _ in range(50):
        n = 40
        t = T0 + (np.arange(n) + rng.uniform(-0.3, 0.3, n)) * DT
        y = 0.2 * np.sin(np.minimum(t - T0, 22 * DT) * 9.0)  # decelerating, then still in contact
        pos = np.column_stack([np.zeros(n), y, np.zeros(n)])
        contact = np.arange(n) >= 22
        grid, out, con = resample_uniform(t, pos, contact, DT)
        np.testing.assert_array_equal(con, grid >= 0.5 * (t[21] + t[22]))
        mid = (grid > t[21]) & (grid < t[22])
        lo, hi = sorted((pos[21, 1], pos[22, 1]))
        assert np.all((out[mid, 1] >= lo - 1e-15) & (out[mid, 1] <= hi + 1e-15))


def test_a_trial_without_contact_is_one_spline_with_no_contact():
    """No contact sample: every grid time is approach (catches taking the first contact sample of an
    empty list)."""
    t, _, _ = trial()
    grid, out, con = resample_uniform(t, approach_line(t), np.zeros(len(t), bool), DT)
    np.testing.assert_array_equal(grid, expected_grid(t))
    assert not con.any()
    np.testing.assert_allclose(out, approach_line(grid), rtol=0, atol=1e-12)


def test_a_trial_in_contact_from_its_first_sample():
    """Contact from the first sample (no approach part): every grid time is contact and interpolated
    from the contact samples (catches stopping at the empty approach part, which leaves the output unset)."""
    t, _, _ = trial()
    grid, out, con = resample_uniform(t, parabola(t), np.ones(len(t), bool), DT)
    assert con.all()
    np.testing.assert_allclose(out, parabola(grid), rtol=0, atol=1e-12)


@pytest.mark.parametrize("n_contact", [4, 5])
def test_a_part_of_four_samples_is_a_cubic_spline(n_contact):
    """A contact part of 4 (or 5) jittered samples on a parabola is interpolated by a cubic (exact for a
    parabola), not linearly (catches ``> 4`` or ``>= 5`` for ``>= 4``)."""
    n = 30
    t = jittered_times(n, jitter={n - 3: 0.4, n - 2: -0.3})
    contact = np.arange(n) >= n - n_contact
    grid, out, con = resample_uniform(t, parabola(t), contact, DT)
    assert (~con).sum() == n - n_contact and con.sum() == n_contact
    np.testing.assert_allclose(out, parabola(grid), rtol=0, atol=1e-12)


@pytest.mark.parametrize("n_contact", [2, 3])
def test_a_part_of_two_or_three_samples_is_interpolated_linearly(n_contact):
    """A contact part of 2 or 3 samples, the last ones off the grid, is linear between its samples, and
    contact starts at the first grid time after the last approach sample, linear from that sample to the
    first contact sample: checked per coordinate with numpy.interp (catches the part held constant at its
    first sample and a broken linear branch)."""
    n = 30
    t = jittered_times(n, jitter={n - 1: 0.5, n - 2: 0.4})
    pos = parabola(t)
    contact = np.arange(n) >= n - n_contact
    grid, out, con = resample_uniform(t, pos, contact, DT)
    c = n - n_contact
    tc, pc = t[c - 1 :], pos[c - 1 :]  # the last approach sample and the contact samples
    want = np.column_stack([np.interp(grid[con], tc, pc[:, j]) for j in range(3)])
    np.testing.assert_array_equal(con, grid >= 0.5 * (t[c - 1] + t[c]))
    np.testing.assert_allclose(out[con], want, rtol=0, atol=1e-12)
    assert not np.allclose(out[con], pc[0])  # a constant would not do
    np.testing.assert_allclose(out[~con], parabola(grid[~con]), rtol=0, atol=1e-12)


def test_a_part_of_one_sample_is_that_sample():
    """Contact only at the last sample (on the grid): the last grid point is in contact at that
    sample's position (catches another index than the part's only sample)."""
    n = 30
    t = jittered_times(n, jitter={10: 0.3})
    pos = parabola(t)
    contact = np.arange(n) == n - 1
    pos[-1] = [0.5, 0.6, 0.7]
    grid, out, con = resample_uniform(t, pos, contact, DT)
    np.testing.assert_array_equal(con, np.arange(len(grid)) == len(grid) - 1)
    np.testing.assert_array_equal(out[-1], pos[-1])
    np.testing.assert_allclose(out[:-1], parabola(grid[:-1]), rtol=0, atol=1e-12)


@settings(max_examples=30, deadline=None)
@given(n=st.integers(6, 60), fs=st.sampled_from([60.0, 100.0, 120.0, 250.0]), seed=st.integers(0, 2**16))
def test_float32_time_stamps_resample_as_their_float64_values(n, fs, seed):
    """Time stamps stored in float32 (as C3D files and some loggers store them) are resampled as the same
    values in float64: the grid length is counted in float64, where the margin of 1e-9 applies (counted
    in float32 the last sample can be left out)."""
    rng = np.random.default_rng(seed)
    interior = (np.arange(n) > 0) & (np.arange(n) < n - 1)  # the ends stay on the grid (to float32 rounding)
    t32 = (np.arange(n) / fs + rng.uniform(-0.2, 0.2, n) / fs * interior).astype(np.float32)
    assume(np.all(np.diff(t32) > 0))
    pos = rng.normal(size=(n, 3))
    contact = np.arange(n) >= n // 2
    g32, p32, c32 = resample_uniform(t32, pos, contact, 1 / fs)
    g64, p64, c64 = resample_uniform(t32.astype(np.float64), pos, contact, 1 / fs)
    np.testing.assert_array_equal(g32, g64)
    np.testing.assert_array_equal(p32, p64)
    np.testing.assert_array_equal(c32, c64)


def test_float32_time_stamps_at_60_hz_keep_their_last_sample():
    """8 samples at 60 Hz in float32: counted in float64 the grid has 8 points (float32 arithmetic gives 7)."""
    fs, n = 60.0, 8
    t32 = (np.arange(n) / fs).astype(np.float32)
    grid, _, _ = resample_uniform(t32, np.zeros((n, 3)), np.zeros(n, bool), 1 / fs)
    assert len(grid) == n


# --- csvtable.quote -------------------------------------------------------------------------------


def test_quote_keeps_a_cell_of_max_quote_characters_whole_and_cuts_one_more():
    """A cell of exactly MAX_QUOTE characters is quoted whole; one of MAX_QUOTE + 1 is cut to MAX_QUOTE
    with its length said (catches ``<`` for ``<=``)."""
    whole = "a" * MAX_QUOTE
    assert quote(whole) == repr(whole)
    longer = "b" * (MAX_QUOTE + 1)
    assert quote(longer) == f"{'b' * MAX_QUOTE!r}... ({MAX_QUOTE + 1} characters)"


# --- regular_mean_interval and irregularity ------------------------------------------------------


def test_the_regular_interval_includes_intervals_exactly_at_the_trim_edge():
    """Intervals DT, DT, DT, 1.5 DT: the median DT, and 1.5 DT is exactly TRIM x DT away, inside the
    window (+-TRIM inclusive), so the centre moves to their mean 1.125 DT, where all four stay (catches
    ``<`` for ``<=``, which leaves 1.5 DT out and gives DT)."""
    assert TRIM == 0.5  # the 1.5 DT interval sits exactly on the edge
    d = np.array([1.0, 1.0, 1.0, 1.5]) * DT
    t = T0 + np.concatenate([[0.0], np.cumsum(d)])
    assert np.array_equal(np.diff(t), d)  # exact in binary
    assert regular_mean_interval(t) == np.mean(d) == 1.125 * DT


@settings(max_examples=30, deadline=None)
@given(n=st.integers(6, 60), fs=st.sampled_from([60.0, 100.0, 250.0]), seed=st.integers(0, 2**16))
def test_float32_time_stamps_give_the_interval_and_irregularity_of_their_float64_values(n, fs, seed):
    """The rate and the jitter of float32 time stamps are computed in float64 (float32 intervals lose
    4 digits of a time stamp of a few seconds)."""
    rng = np.random.default_rng(seed)
    t32 = (T0 + np.arange(n) / fs + rng.uniform(-0.3, 0.3, n) / fs).astype(np.float32)
    assume(np.all(np.diff(t32) > 0))
    t64 = t32.astype(np.float64)
    assert regular_mean_interval(t32) == regular_mean_interval(t64)
    assert irregularity(t32, 1 / fs) == irregularity(t64, 1 / fs)


def test_the_mean_shift_stops_after_twenty_steps():
    """60 intervals of DT and a ladder of longer ones, each rung just inside the window (1 + TRIM) x the
    centre the previous rungs lead to: every step takes in one more rung, so the documented limit of 20
    steps leaves the centre at the mean of the 60 intervals and the first 20 rungs (catches another
    number of steps)."""
    steps, n_regular = 20, 60
    rungs, centre = [], 1.0
    for _ in range(steps + 2):
        rungs.append((1 + TRIM) * centre * (1 - 1e-6))
        centre = np.mean([1.0] * n_regular + rungs)
    t = T0 + np.concatenate([[0.0], np.cumsum(np.array([1.0] * n_regular + rungs) * DT)])
    d = np.diff(t)
    assert np.median(d) == pytest.approx(DT, rel=1e-9)  # the mean shift starts at DT
    assert regular_mean_interval(t) == np.mean(d[: n_regular + steps])


# --- regular stamps written imprecisely, gaps after contact ----------------------------------------


def test_time_quantum_finds_the_resolution_stamps_are_written_with():
    """Stamps of 60 Hz written to the millisecond (OpenSim) are multiples of 1 ms; to 0.1 ms, of 0.1 ms;
    exact multiples of 1/64 s or of 1/60 s in binary, of none (catches a finer or coarser quantum)."""
    t = np.arange(200) / 60.0
    assert time_quantum(np.round(t, 3)) == 1e-3
    assert time_quantum(np.round(t, 4)) == 1e-4
    assert time_quantum(np.round(t, 2)) == 1e-2
    assert time_quantum(t) == 0.0
    assert time_quantum(3.0 + np.arange(50) * 2.0**-6 + 1e-7) == 0.0


def test_grid_jitter_measures_stamps_against_their_regular_grid():
    """Rounding to q strays up to q / 2 from the grid; jitter of +-j up to about j; a dropped frame is
    not a stray stamp; a clock a little off the file's rate is absorbed by the fitted slope."""
    dt = 1 / 60
    t = np.arange(300) * dt
    assert grid_jitter(np.round(t, 3), dt) == pytest.approx(1e-3 / 3 / dt, rel=0.02)  # k/60 s: 0, +-1/3 ms off
    assert grid_jitter(np.round(np.arange(300) / 240.0, 3), 1 / 240) == pytest.approx(0.5e-3 * 240, rel=0.03)
    rng = np.random.default_rng(1)
    j = 0.3e-3
    assert grid_jitter(t + rng.uniform(-j, j, len(t)), dt) == pytest.approx(j / dt, rel=0.15)
    assert grid_jitter(np.delete(t, 50), dt) < 1e-9
    assert grid_jitter(t * 1.001, dt) < 1e-9


@pytest.mark.parametrize(
    "fs, stamps, used_as_recorded",
    [
        (60.0, lambda t, rng: np.round(t, 3), True),  # OpenSim: 16/17 ms intervals, 4 % off
        (240.0, lambda t, rng: np.round(t, 3), True),  # 4.17 ms at 240 Hz: intervals of 4 and 5 ms, 20 % off
        (85.0, lambda t, rng: t + rng.uniform(-3e-4, 3e-4, len(t)), True),  # Optotrak: +-0.3 ms
        (60.0, lambda t, rng: t + rng.uniform(-2e-3, 2e-3, len(t)), False),  # a VR log: +-2 ms
    ],
)
def test_stamps_of_a_regular_rate_written_imprecisely_are_not_resampled(fs, stamps, used_as_recorded):
    """The issue's time stamps: rounded to the millisecond, or jittered by much less than a frame, around
    a regular rate: that rate, the samples used as recorded (the trial's timing says so); jitter of an
    eighth of a frame is resampled (catches the old 2 % of an interval)."""
    from skilllib.recordings import recordings_from_frame

    rng = np.random.default_rng(7)
    frames = []
    for k in range(6):
        t = stamps(np.arange(int(1.2 * fs)) / fs, rng)
        y = 0.3 - 0.2 * np.clip(t - 0.2, 0, 0.8)
        frames.append(
            pd.DataFrame(
                {"participant": "P", "trial": str(k), "t": t, "x": 0.0, "y": y, "z": 0.0, "contact": (t >= 0.9) * 1}
            )
        )
    rec = recordings_from_frame(pd.concat(frames, ignore_index=True))
    assert (rec.trials.status == "ok").all()
    assert rec.fs == pytest.approx(fs, rel=2e-3)
    assert rec.trials.timing.str.endswith(": used as recorded").all() == used_as_recorded
    assert rec.trials.timing.str.startswith("resampled:").all() == (not used_as_recorded)
    tr = rec.trial("P", "0")
    assert np.array_equal(tr.t, frames[0].t.to_numpy()) == used_as_recorded


def test_a_gap_after_contact_cuts_the_trial_and_a_gap_before_it_invalidates():
    """A 0.2 s gap in the stamps after the first contact sample lies where the analysis never reads: the
    trial is kept up to it, and says how many samples were left; the same gap during the approach makes
    the trial invalid, naming the gap (catches invalidating both, or cutting both)."""
    from skilllib.recordings import recordings_from_frame

    fs = 100.0
    frames = []
    for k, gap_at in enumerate((0.95, 0.5, None)):
        t = np.arange(120) / fs
        if gap_at is not None:
            t = np.where(t >= gap_at, t + 0.2, t)
        y = 0.3 - 0.2 * np.clip(t - 0.2, 0, 0.7)
        c = (t >= 0.9) * 1
        frames.append(
            pd.DataFrame({"participant": "P", "trial": str(k), "t": t, "x": 0.0, "y": y, "z": 0.0, "contact": c})
        )
    rec = recordings_from_frame(pd.concat(frames, ignore_index=True))
    by = rec.trials.set_index("trial")
    assert by.loc["0", "status"] == "ok" and by.loc["0", "timing"].startswith("cut at a 0.2100 s gap")
    assert "(25 samples after it not used)" in by.loc["0", "timing"]
    assert len(rec.trial("P", "0").t) == 95 and rec.trial("P", "0").contact[-1]
    assert by.loc["1", "status"] == "invalid" and by.loc["1", "reason"].startswith("gap in the time stamps")
    assert gap_after_contact(np.arange(10.0), np.zeros(10, bool), 1.0) is None
