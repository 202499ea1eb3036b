"""The pipe cross-section through two points, centre below (seeds/003, section 2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_sonar.cross_section import CrossSection


def arc_depth(section: CrossSection, x: np.ndarray, cx: float, cz: float) -> np.ndarray:
    """Depth of the upper arc of the ellipse of ``section`` centred at ``(cx, cz)`` at positions ``x``.

    Returns
    -------
    numpy.ndarray
        ``cz - (M_i/2) sqrt(1 - ((x - cx) / (M_a/2))^2)``, broadcast over
        the inputs; ``nan`` where ``|x - cx| > M_a/2``.
    """
    u = (np.asarray(x, float) - cx) / section.half_width_m
    inside = np.abs(u) <= 1.0
    return np.where(inside, cz - section.half_height_m * np.sqrt(np.clip(1.0 - u * u, 0.0, None)), np.nan)


@settings(max_examples=100, deadline=None)
@given(
    st.floats(0.2, 2.0),
    st.floats(0.2, 2.0),
    st.floats(-20.0, 20.0),
    st.floats(2.0, 40.0),
    st.floats(-0.95 * math.pi, -0.05 * math.pi),
    st.floats(0.01, 0.8),
)
def test_two_points_of_the_upper_arc_give_back_the_centre(major, minor, cx, cz, angle, gap):
    section = CrossSection(major, minor)
    a, b = section.half_width_m, section.half_height_m
    # Two points of the upper half (depth less than the centre's), ``gap`` rad apart.
    second = min(angle + gap, -0.01 * math.pi)
    x1, z1 = cx + a * math.cos(angle), cz + b * math.sin(angle)
    x2, z2 = cx + a * math.cos(second), cz + b * math.sin(second)
    if math.hypot(x2 - x1, z2 - z1) < 1e-6:
        return
    fx, fz, ok = section.centres_below(np.array([x2]), np.array([z2]), np.array([x1]), np.array([z1]))
    assert ok[0]
    assert fx[0] == pytest.approx(cx, abs=1e-6 * (1 + abs(cx)))
    assert fz[0] == pytest.approx(cz, abs=1e-6 * (1 + cz))
    arc = arc_depth(section, np.array([x1, x2]), fx[0], fz[0])
    assert np.allclose(arc, [z1, z2], atol=1e-6 * (1 + cz))


def test_the_centre_is_below_both_points_whatever_their_order():
    section = CrossSection(0.9, 0.9)
    x = np.array([0.0, 0.1])
    z = np.array([10.0, 10.02])
    for first, second in ((0, 1), (1, 0)):
        fx, fz, ok = section.centres_below(x[[first]], z[[first]], x[[second]], z[[second]])
        assert ok[0] and fz[0] > z.max()
        assert np.hypot(fx[0] - x, fz[0] - z) == pytest.approx([0.45, 0.45])


def test_points_too_far_apart_or_equal_have_no_cross_section():
    section = CrossSection(0.6, 0.6)
    fx, fz, ok = section.centres_below(
        np.zeros(3), np.full(3, 10.0), np.array([0.7, 0.0, np.nan]), np.full(3, 10.0)
    )
    assert not ok.any()
    assert np.isnan(fx).all() and np.isnan(fz).all()


def test_the_arc_is_the_upper_half_and_nan_beyond_the_axis():
    section = CrossSection(1.0, 0.5)
    depth = arc_depth(section, np.array([0.0, 0.5, -0.5, 0.6]), 0.0, 10.0)
    assert depth[0] == pytest.approx(9.75)
    assert depth[1] == pytest.approx(10.0) and depth[2] == pytest.approx(10.0)
    assert np.isnan(depth[3])


@pytest.mark.parametrize("bad", [0.0, -1.0, math.inf, math.nan, "1", True])
def test_axes_must_be_positive_numbers(bad):
    with pytest.raises(ValueError, match="major_m"):
        CrossSection(bad, 1.0)
