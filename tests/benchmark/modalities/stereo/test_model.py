"""The stereo data model: a target's speed and heading, the boats' range, stereo frames."""

import math

import pytest

from benchmark.modalities.stereo.model import StereoFrame, StereoMeasurement, StereoTruth, TargetEstimate


@pytest.mark.parametrize(
    ("velocity", "heading_deg"),
    [((1.0, 0.0), 0.0), ((0.0, 1.0), 90.0), ((-1.0, 0.0), 180.0), ((0.0, -2.0), -90.0)],
)
def test_heading_is_clockwise_from_north(velocity: tuple[float, float], heading_deg: float) -> None:
    target = TargetEstimate((0.0, 0.0), velocity)
    assert math.degrees(target.heading) == pytest.approx(heading_deg)
    assert target.speed_mps == pytest.approx(math.hypot(*velocity))


def test_range_is_the_distance_between_the_boats() -> None:
    truth = StereoTruth(TargetEstimate((10.0, 4.0), (1.0, 0.0)), chase_position_m=(7.0, 0.0), chase_heading=0.0)
    assert truth.range_m == pytest.approx(5.0)


def test_a_stereo_frame_is_built_through_its_alias() -> None:
    frame = StereoFrame(0, StereoMeasurement(200.0, 190.0, (14.0, 0.5)))
    assert frame.truth is None and frame.observation.relative_m == (14.0, 0.5)
