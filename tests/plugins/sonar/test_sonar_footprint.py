"""The pipe's cross-section as wide beams see it: the semicircle and its span convolved with the footprint."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_sonar.cross_section import CrossSection
from trackbench_sonar.footprint import (
    FWHM_PER_SIGMA,
    TABLE_REACH,
    SeenCrossSection,
    footprint_sigma,
    smoothed_box,
    smoothed_semicircle,
)

from benchmark.modalities.sonar.model import beam_footprint


def _convolved_semicircle(offset: float, sigma: float) -> float:
    """The semicircle convolved with N(0, sigma^2) by brute quadrature."""
    t = np.linspace(-1.0, 1.0, 40001)
    kernel = np.exp(-0.5 * ((offset - t) / sigma) ** 2) / (sigma * math.sqrt(2.0 * math.pi))
    return float(np.sum(kernel * np.sqrt(1.0 - t * t)) * (t[1] - t[0]))


def test_without_a_footprint_the_arc_is_the_semicircle():
    v = np.linspace(-1.45, 1.45, 30)
    assert np.allclose(smoothed_semicircle(v, np.zeros_like(v)), np.sqrt(np.clip(1.0 - v * v, 0.0, None)), atol=3e-3)
    assert np.allclose(smoothed_box(v, np.zeros_like(v)), np.abs(v) < 1.0)


@settings(max_examples=40, deadline=None)
@given(st.floats(-4.0, 4.0), st.floats(0.05, 3.9))
def test_the_table_matches_the_convolution(offset, sigma):
    assert smoothed_semicircle(np.array(offset), np.array(sigma)) == pytest.approx(
        _convolved_semicircle(offset, sigma), abs=2e-3
    )


@settings(max_examples=30, deadline=None)
@given(st.floats(0.05, 3.0))
def test_smoothing_keeps_the_area_and_the_symmetry(sigma):
    v = np.linspace(-TABLE_REACH + 0.005, TABLE_REACH - 0.005, 4999)
    step = v[1] - v[0]
    arc = smoothed_semicircle(v, np.full(v.shape, sigma))
    box = smoothed_box(v, np.full(v.shape, sigma))
    assert np.sum(arc) * step == pytest.approx(math.pi / 2.0, rel=2e-3)
    assert np.sum(box) * step == pytest.approx(2.0, rel=2e-3)
    assert np.allclose(arc, arc[::-1], atol=1e-6) and np.allclose(box, box[::-1], atol=1e-9)
    assert np.all(arc >= 0.0) and np.all(arc <= 1.0) and np.all(box >= 0.0) and np.all(box <= 1.0)


def test_a_wide_footprint_lowers_and_widens_the_bump():
    v = np.array([0.0, 1.2])
    narrow = smoothed_semicircle(v, np.full(2, 0.1))
    wide = smoothed_semicircle(v, np.full(2, 1.0))
    assert wide[0] < 0.6 * narrow[0] and wide[1] > narrow[1] + 0.1


def test_offsets_beyond_the_table_see_nothing():
    assert smoothed_semicircle(np.array([TABLE_REACH + 1.0]), np.array([1.0]))[0] == 0.0


def test_the_footprint_is_the_beam_width_s_strip_across_the_track():
    x, z = np.array([0.0, 5.0, -12.0]), np.array([10.0, 10.0, 20.0])
    width = math.radians(1.5)
    assert np.allclose(footprint_sigma(x, z, width) * FWHM_PER_SIGMA, beam_footprint(x, z, width))
    assert footprint_sigma(x[:1], z[:1], width)[0] == pytest.approx(10.0 * width / FWHM_PER_SIGMA)
    assert np.all(footprint_sigma(x, z, 0.0) == 0.0)


def test_the_seen_section_scales_the_unit_shapes_by_its_axes():
    seen = SeenCrossSection(CrossSection(1.2, 0.8))
    u, sigma = np.array([0.0, 0.3, 0.9]), np.array([0.2, 0.2, 0.2])
    assert np.allclose(seen.arc(u, sigma), 0.4 * smoothed_semicircle(u / 0.6, sigma / 0.6))
    assert np.allclose(seen.pedestal(u, sigma), smoothed_box(u / 0.6, sigma / 0.6))
    assert seen.seen_half_width(np.array(0.8)) == pytest.approx(1.0)
