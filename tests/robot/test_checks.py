"""The checks of a transfer the chapters print: joint limits, J qd = v, the next band frequency."""

from __future__ import annotations

import numpy as np
import pytest
from robot_paths import minimum_jerk_descent

import skilllib as sk


def test_within_joint_limits_takes_an_arm_or_its_model():
    puma = sk.get_robot("puma560")
    assert sk.within_joint_limits(puma, puma.q0)
    assert sk.within_joint_limits(puma.robot, puma.q0)
    outside = puma.q0.copy()
    outside[1] = puma.robot.qlim[1, 1] + 0.1
    assert not sk.within_joint_limits(puma, outside)


def test_tool_velocity_error_is_rounding_error_for_a_transfer_and_skips_unsolved_samples():
    arm = sk.get_robot("simple6")
    t, pos, vel = minimum_jerk_descent(amplitude=0.2, peak_speed=0.8)
    r = sk.transfer(arm, t, pos, vel)
    assert sk.tool_velocity_error(arm, r) < 1e-12
    r.qd[2] += 0.1  # a wrong joint velocity shows
    assert sk.tool_velocity_error(arm.robot, r) > 1e-3
    r.q[:] = np.nan
    assert np.isnan(sk.tool_velocity_error(arm, r))


def test_tool_velocity_error_needs_the_commanded_velocities():
    arm = sk.get_robot("simple6")
    r = sk.transfer(arm, *minimum_jerk_descent())
    r.v_base = None
    with pytest.raises(ValueError, match="v_base"):
        sk.tool_velocity_error(arm, r)


def test_next_band_frequency_is_inf_for_a_smooth_profile_and_finite_for_a_capped_one():
    fs = 60.0
    t = np.arange(0, 0.5, 1 / fs)
    bell = np.sin(np.pi * t / t[-1]) ** 2
    assert np.isinf(sk.next_band_frequency(bell, fs))
    rng = np.random.default_rng(0)
    rough = bell + 0.3 * rng.standard_normal(t.size)
    f = sk.next_band_frequency(rough, fs, fc=5.0)
    assert 5.0 < f <= fs / 2
    assert sk.sparc_spectrum(rough, fs, fc=5.0).capped
