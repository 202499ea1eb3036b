"""Tests of the pixel quantities that follow the frame size."""

from __future__ import annotations

import dataclasses

import pytest
from hypothesis import given
from hypothesis import strategies as st
from trackbench_segmentation.params import SCALED_LENGTHS, SCALED_VARIANCES, SegmentationParams
from trackbench_segmentation.scaling import frame_params

PARAMS = SegmentationParams()


def test_at_the_reference_width_nothing_changes_but_the_reference():
    at_reference = frame_params(PARAMS, (320, 240))
    assert at_reference.reference_width_px is None
    assert dataclasses.replace(at_reference, reference_width_px=PARAMS.reference_width_px) == PARAMS


@given(width=st.integers(16, 4000), height=st.integers(16, 4000))
def test_lengths_are_shares_of_the_frame_width_and_variances_their_squares(width, height):
    scaled = frame_params(PARAMS, (width, height))
    factor = width / PARAMS.reference_width_px
    for name in SCALED_LENGTHS:
        assert getattr(scaled, name) == pytest.approx(getattr(PARAMS, name) * factor)
    for name in SCALED_VARIANCES:
        (d, alpha, w), (d0, alpha0, w0) = getattr(scaled, name), getattr(PARAMS, name)
        assert (d, alpha, w) == pytest.approx((d0 * factor**2, alpha0, w0 * factor**2))
    unscaled = set(SCALED_LENGTHS) | set(SCALED_VARIANCES) | {"reference_width_px"}
    for field in dataclasses.fields(PARAMS):
        if field.name not in unscaled:
            assert getattr(scaled, field.name) == getattr(PARAMS, field.name), field.name


def test_without_a_reference_the_lengths_are_pixels_of_any_frame():
    fixed = SegmentationParams(reference_width_px=None)
    assert frame_params(fixed, (640, 480)) is fixed


def test_a_pipe_half_the_frame_wide_is_plausible_at_both_camera_sizes():
    for size in ((320, 240), (640, 480)):
        assert frame_params(PARAMS, size).max_width_px >= 0.5 * size[0]
