"""The sonar data model: swaths, their calibration and the beam footprint (seeds/003)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.modalities.sonar.model import SonarCalibration, Swath, beam_footprint


def test_a_swath_keeps_its_beams_as_float_arrays_and_marks_missing_ones():
    swath = Swath([-1, 0, 1], [20.0, math.nan, 20.5])
    assert swath.across_m.dtype == float and swath.depth_m.dtype == float
    assert swath.valid.tolist() == [True, False, True]


@pytest.mark.parametrize(
    ("across", "depth", "message"),
    [
        (np.zeros((2, 3)), np.zeros((2, 3)), "across_m must be one-dimensional"),
        (np.zeros(3), np.zeros(4), "differ in shape"),
    ],
)
def test_a_swath_of_the_wrong_shape_is_refused_with_its_shapes(across, depth, message):
    with pytest.raises(ValueError, match=message):
        Swath(across, depth)


def test_beam_spacing_divides_the_fan_between_neighbouring_beams():
    calibration = SonarCalibration(n_beams=111, swath_angle=math.radians(110.0), range_sigma_m=0.05, pipe_diameter_m=0.9)
    assert calibration.beam_spacing == pytest.approx(math.radians(1.0))


@given(st.floats(-0.9, 0.9), st.floats(3.0, 30.0))
def test_beam_footprint_is_the_spacing_of_neighbouring_beams_on_a_level_seabed(theta: float, depth: float) -> None:
    spacing = math.radians(0.5)
    x = depth * math.tan(theta)
    gap = depth * (math.tan(theta + spacing / 2) - math.tan(theta - spacing / 2))
    assert beam_footprint(np.array([x]), np.array([depth]), spacing)[0] == pytest.approx(gap, rel=1e-3)


def test_beam_footprint_grows_away_from_nadir_and_is_infinite_above_the_transducer() -> None:
    beam_240 = math.radians(120.0) / 239
    assert beam_footprint(np.array([0.0]), np.array([10.0]), 0.01)[0] == pytest.approx(0.1)
    for x in (0.0, 5.0, 12.0):
        theta = math.atan2(x, 10.0)
        between = 10.0 * (math.tan(theta + beam_240 / 2) - math.tan(theta - beam_240 / 2))
        assert beam_footprint(np.array([x]), np.array([10.0]), beam_240)[0] == pytest.approx(between, rel=1e-3)
    assert np.isinf(beam_footprint(np.array([1.0]), np.array([0.0]), 0.01)[0])
