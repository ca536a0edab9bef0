"""skilllib.smoothness._profiles, the generated profiles and measurements of the SPARC chapters: each
test says which wrong behaviour it catches; expected values come from the definitions, by hand."""

from __future__ import annotations

import numpy as np
import pytest

from skilllib.smoothness import (
    cut_at_contact,
    minimum_jerk_speed,
    minimum_jerk_submovements,
    noisy_copies,
    sparc_spectrum,
    sparc_squared_integral,
    sparc_squared_sum,
    speed_dip,
    stable_from,
)


def test_submovements_sum_minimum_jerk_bells_up_to_the_end_of_the_last():
    # catches a wrong time grid (length) or a missing submovement
    v = minimum_jerk_submovements([0, 0.5], 60.0, T=0.6, D=0.1)
    assert v.size == 66  # 0 .. 1.1 s at 60 Hz, end exclusive
    t = np.arange(66) / 60
    assert np.allclose(v, minimum_jerk_speed(t, 0, 0.6, 0.1) + minimum_jerk_speed(t, 0.5, 0.6, 0.1))
    assert np.isclose(minimum_jerk_submovements([0], 1000.0, T=1.0, D=2.0).max(), 1.875 * 2, rtol=1e-5)
    with pytest.raises(ValueError):
        minimum_jerk_submovements([], 60.0)


def test_cut_at_contact_ends_before_the_first_falling_sample_below_the_ratio():
    v = np.array([0.0, 0.5, 1.0, 0.8, 0.6, 0.4, 0.1])
    assert cut_at_contact(v, 0.5).tolist() == [0.0, 0.5, 1.0, 0.8, 0.6]  # rising 0.0 and 0.5 kept
    assert cut_at_contact(v, 0.7).tolist() == [0.0, 0.5, 1.0, 0.8]
    with pytest.raises(ValueError):
        cut_at_contact(v, 0.05)  # never below 5 % after the peak
    with pytest.raises(ValueError):
        cut_at_contact(v, 1.5)


def test_noisy_copies_draw_as_separate_calls_and_are_non_negative():
    # catches noise scaled by something other than the peak, or a different draw order
    v = np.array([0.0, 1.0, 2.0, 1.0, 0.0])
    many = noisy_copies(v, 0.1, 3, np.random.default_rng(5))
    rng = np.random.default_rng(5)
    by_hand = [np.abs(v + rng.normal(0, 0.2, v.size)) for _ in range(3)]
    assert many.shape == (3, 5) and np.array_equal(many, np.array(by_hand))
    one = noisy_copies(v, 0.1, rng=np.random.default_rng(5))
    assert one.shape == (5,) and np.array_equal(one, by_hand[0]) and (many >= 0).all()


def test_speed_dip_is_the_lowest_speed_between_the_outer_peaks():
    assert speed_dip([0, 2, 1, 0.5, 3, 0.2, 0.4, 0]) == 0.2
    assert speed_dip([0, 1, 2, 1, 0]) == 2.0  # one peak: no dip


def test_stable_from_is_the_first_x_after_the_last_value_off_by_more_than_tol():
    x = np.arange(5, 10)
    assert stable_from(x, [1.5, 1.2, 1.0, 1.005, 1.0]) == 7
    assert stable_from(x, [1.0, 1.0, 1.3, 1.0, 1.0]) == 8
    assert stable_from(x, np.ones(5)) == 5
    with pytest.raises(ValueError):
        stable_from(x, [1.0])


def test_the_squared_readings_follow_their_formulas():
    v = minimum_jerk_speed(np.arange(0, 0.8, 1 / 60), 0, 0.8)
    s = sparc_spectrum(v, 60.0)
    K = s.f_sel.size - 1
    assert np.isclose(sparc_squared_sum(v, 60.0), -(1 + K * np.sum(np.diff(s.Mf_sel) ** 2)) / K)
    w = 2 * np.pi * s.f_sel
    by_hand = -np.sum(((1 / w[-1]) ** 2 + (np.diff(s.Mf_sel) / np.diff(w)) ** 2) ** 2 * np.diff(w))
    assert np.isclose(sparc_squared_integral(v, 60.0), by_hand)
    ratio = sparc_squared_integral(v, 60.0, "Hz") / sparc_squared_integral(v, 60.0)
    assert np.isclose(ratio, (2 * np.pi) ** 3)  # the integral's units, s^3
    assert sparc_squared_sum([0.3], 1000.0) == 0.0  # a band of one bin
    with pytest.raises(ValueError):
        sparc_squared_integral(v, 60.0, "kHz")
