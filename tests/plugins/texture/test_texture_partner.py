"""Tests of reading the second border off the grey levels beside the first."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_texture.borders import cable_strip, fit_borders
from trackbench_texture.partner import partner_line

LIMITS = dict(min_width_px=5.0, max_width_px=120.0, max_skew=math.radians(10.0), min_rows=30.0, min_strength=0.3, widest_share=1.0)


def _band(left: float, right: float, inside: float, outside: float, shape=(120, 160), slope: float = 0.0) -> np.ndarray:
    """``float32`` scan image ``[along, across]``: grey ``inside`` between two parallel lines, ``outside`` elsewhere."""
    along, across = np.mgrid[0 : shape[0], 0 : shape[1]].astype(np.float32)
    shifted = across - slope * along
    return np.where((shifted >= left) & (shifted < right), inside, outside).astype(np.float32)


@settings(max_examples=30, deadline=None)
@given(
    left=st.integers(10, 60),
    width=st.integers(8, 80),
    bright=st.booleans(),
    from_left=st.booleans(),
    slope=st.floats(-0.1, 0.1),
)
def test_the_partner_of_either_border_is_the_other(left, width, bright, from_left, slope):
    right = left + width
    grey = _band(left, right, 160.0 if bright else 40.0, 90.0, slope=slope)
    start, other = (left, right) if from_left else (right, left)
    # The step between pixels start - 1 and start lies at start - 0.5.
    found = partner_line(grey, slope, start - 0.5, **LIMITS)
    assert found is not None
    found_slope, found_intercept = found
    middle = 59.5
    assert abs(found_slope * middle + found_intercept - (slope * middle + other - 0.5)) <= 1.0


def test_no_partner_without_a_step_back():
    along, across = np.mgrid[0:120, 0:160].astype(np.float32)
    grey = np.where(across >= 50, 150.0, 60.0).astype(np.float32)
    assert partner_line(grey, 0.0, 49.5, **LIMITS) is None


def test_a_weak_step_back_is_refused_below_the_strength_ratio():
    grey = _band(40, 90, 160.0, 60.0)
    grey[:, 90:] = 150.0
    assert partner_line(grey, 0.0, 39.5, **LIMITS) is None
    assert partner_line(grey, 0.0, 39.5, **{**LIMITS, "min_strength": 0.05}) is not None


def test_the_partner_keeps_to_the_width_limits():
    grey = _band(40, 90, 160.0, 60.0)
    assert partner_line(grey, 0.0, 39.5, **{**LIMITS, "max_width_px": 30.0}) is None


BORDER_LIMITS = dict(
    inlier_px=1.0, trials=200, min_length_share=0.5, min_inlier_share=0.3, min_width_px=5.0,
    max_width_px=120.0, max_skew=math.radians(10.0),
)
"""The settings of fit_borders in the tests of the profile pairing."""


def _one_border_scene(shape=(120, 160)):
    """A cable band from column 40 to 100, a region reaching only its right border, one straight piece on it."""
    grey = _band(40, 100, 170.0, 60.0, shape)
    straight = np.zeros(shape, np.float32)
    straight[:, 99] = 1.0
    region = np.zeros(shape, bool)
    region[:, 85:115] = True
    return grey, straight, region, cable_strip(region, 400)


def test_the_profile_pairing_finds_a_border_the_region_does_not_reach():
    grey, straight, region, strip = _one_border_scene()
    limits = BORDER_LIMITS
    rng = np.random.default_rng(0)
    assert fit_borders(strip, straight, rng, None, region, "parallel", **limits) is None
    found = fit_borders(
        strip, straight, rng, None, region, "parallel-profile", **limits, grey=grey, partner_strength=0.3
    )
    assert found is not None
    assert abs(found.w - 60.0) <= 2.0


def test_of_close_steps_the_outermost_is_the_border():
    grey = np.full((120, 160), 60.0, np.float32)
    grey[:, 40:60] = 220.0
    grey[:, 60:100] = 135.0
    strongest = partner_line(grey, 0.0, 39.5, **LIMITS)
    outermost = partner_line(grey, 0.0, 39.5, **{**LIMITS, "widest_share": 0.8})
    assert strongest is not None and outermost is not None
    assert abs(strongest[1] - 59.5) <= 1.0
    assert abs(outermost[1] - 99.5) <= 1.0


def test_grey_levels_given_as_a_function_are_read_only_when_a_profile_pairing_needs_them():
    grey, one_border, region, strip = _one_border_scene()
    calls = []

    def levels() -> np.ndarray:
        calls.append(1)
        return grey

    def fit(straight, grey_levels):
        return fit_borders(
            strip, straight, np.random.default_rng(0), None, region, "parallel-profile", **BORDER_LIMITS, grey=grey_levels
        )

    given_array, given_function = fit(one_border, grey), fit(one_border, levels)
    assert given_array is not None and given_function == given_array and len(calls) == 1
    two_borders = one_border.copy()
    two_borders[:, 88] = 1.0
    assert fit(two_borders, levels) is not None and len(calls) == 1
