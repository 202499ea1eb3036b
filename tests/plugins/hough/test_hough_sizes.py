"""Tests of the sizes scaled to a frame."""

from __future__ import annotations

import math

from hypothesis import given
from hypothesis import strategies as st
from trackbench_hough.params import HoughParams
from trackbench_hough.sizes import FrameSizes


def test_without_a_reference_sizes_are_pixels_of_any_frame():
    params = HoughParams(reference_side_px=None, vote_fraction=0.3, partner_fraction=0.3)
    for size in ((320, 240), (640, 480)):
        sizes = FrameSizes.for_frame(params, size)
        assert sizes.scale == 1.0
        assert (sizes.rho_step, sizes.min_width, sizes.max_width) == (1.0, 5.0, params.max_width_px)
        assert (sizes.window_rho, sizes.duplicate_rho, sizes.theta_step) == (15.0, 3.0, math.radians(1.0))
        assert sizes.min_votes == math.ceil(0.3 * size[1]) and sizes.anchor_votes == 0.3 * size[1]


def test_the_reference_frame_keeps_the_stated_sizes_and_twice_its_side_doubles_them():
    params = HoughParams()
    at_reference = FrameSizes.for_frame(params, (320, 240))
    doubled = FrameSizes.for_frame(params, (640, 480))
    assert at_reference.scale == 1.0 and doubled.scale == 2.0
    assert at_reference.max_width == params.max_width_px and doubled.max_width == 2.0 * params.max_width_px
    assert doubled.window_rho == 2.0 * at_reference.window_rho and doubled.rho_step == 2.0 * at_reference.rho_step
    assert doubled.theta_step == at_reference.theta_step / 2.0
    assert doubled.min_votes == math.ceil(params.partner_fraction * 480)


@given(width=st.integers(16, 4000), height=st.integers(16, 4000))
def test_an_accumulator_cell_spans_the_same_share_of_any_frame(width, height):
    sizes = FrameSizes.for_frame(HoughParams(), (width, height))
    short = min(width, height)
    # The line's end moves by rho_step per angle step at every frame size; widths keep their share of the side.
    assert math.isclose(sizes.theta_step * sizes.rho_step, math.radians(1.0) * 1.0)
    assert math.isclose(sizes.max_width / short, HoughParams().max_width_px / 240.0)
    assert sizes.anchor_votes >= sizes.min_votes - 1
