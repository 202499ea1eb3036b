import math

import numpy as np
import pytest

from benchmark.model import SonarCalibration, Swath


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
