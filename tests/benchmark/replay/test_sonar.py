"""The sonar view: the swath profile as a picture, the pipe and the estimate on it, the particles as ticks."""

from __future__ import annotations

import math

import cv2
import numpy as np
import pytest

from benchmark.modalities.sonar.draw import PIPE_RADIUS_PX
from benchmark.modalities.sonar.model import PipeEstimate, SonarTruth, Swath
from benchmark.model import Frame
from benchmark.replay.record import Belief, Recording
from benchmark.replay.sonar import PICTURE_SIZE, SEABED_BGR, TICK_LENGTH_PX, SonarView

VIEW = SonarView()


def ping(pipe_across: float = 1.5) -> Frame:
    """A flat seabed 10 m down from -20 m to 20 m across, a 1 m pipe on it, two beams without a return."""
    across = np.linspace(-20.0, 20.0, 81)
    depth = np.full(across.size, 10.0)
    depth[np.abs(across - pipe_across) < 0.5] = 9.2
    across[[3, 40]] = math.nan
    return Frame(7, Swath(across, depth), SonarTruth(pipe_across, 9.5, 0.0, 0.4))


def decoded(jpeg: bytes) -> np.ndarray:
    return cv2.imdecode(np.frombuffer(jpeg, np.uint8), cv2.IMREAD_COLOR)


def test_the_picture_is_the_swath_profile_with_the_seabed_below_it() -> None:
    frame = ping()
    picture = VIEW.picture(frame)
    image = decoded(picture.jpeg)
    assert (picture.width, picture.height) == PICTURE_SIZE == (image.shape[1], image.shape[0])
    plane = picture.plane
    u, v = (int(c) for c in plane.point(-10.0, 10.0))  # on the profile: a dark return
    assert image[v - 1 : v + 2, u - 1 : u + 2].min() < 90
    below = image[min(v + 15, picture.height - 1), u].astype(int)
    above = image[max(v - 15, 0), u].astype(int)
    assert np.abs(below - SEABED_BGR).max() < 25  # sand under the profile
    assert np.abs(above - SEABED_BGR).max() > 25  # water over it
    assert plane.box == (0.0, 0.0, float(PICTURE_SIZE[0]), float(PICTURE_SIZE[1]))


def test_the_pipe_is_a_circle_at_its_axis_and_an_estimate_a_line_at_its_across_track_position() -> None:
    frame = ping(pipe_across=1.5)
    picture = VIEW.picture(frame)
    (circle,) = VIEW.overlay(frame.truth, frame, picture)
    assert circle.shape == "ellipse" and circle.points[2:4] == (PIPE_RADIUS_PX, PIPE_RADIUS_PX)
    assert circle.points[:2] == pytest.approx(picture.plane.point(1.5, 9.5))
    (line,) = VIEW.overlay(PipeEstimate(-4.0), frame, picture)
    u = picture.plane.point(-4.0, 0.0)[0]
    assert line.shape == "segment" and line.points == pytest.approx((u, TICK_LENGTH_PX, u, PICTURE_SIZE[1]))
    assert VIEW.overlay(PipeEstimate(math.nan), frame, picture) == [] == VIEW.overlay(None, frame, picture)
    assert VIEW.state(frame.truth) == (1.5,) and VIEW.state(PipeEstimate(-4.0)) == (-4.0,)


def test_particles_are_ticks_at_their_positions_as_long_as_their_weight_relative_to_the_heaviest() -> None:
    frame = ping()
    picture = VIEW.picture(frame)
    particles = np.array([[-5.0], [0.0], [math.nan], [5.0]])
    belief = Belief("particles", particles=particles, weights=np.array([0.1, 0.4, 0.3, 0.2]))
    (ticks,) = VIEW.belief_marks(belief, picture)
    assert (ticks.shape, ticks.role) == ("ticks", "particle")
    v, length, *rest = ticks.points
    assert (v, length) == (0.0, TICK_LENGTH_PX)
    positions, weights = rest[::2], rest[1::2]
    assert positions == pytest.approx([picture.plane.point(x, 0.0)[0] for x in (-5.0, 0.0, 5.0)], abs=0.05)
    assert weights == [0.25, 1.0, 0.5]  # the particle without a position is left out
    assert VIEW.belief_marks(Belief("gaussian", mean=np.zeros(1), variance=np.ones(1)), picture) == []


def test_a_recorded_sonar_filter_draws_its_pipe_estimate_and_particles(real_recordings: dict[str, Recording]) -> None:
    recording = real_recordings["sonar"]
    assert recording.dimensions == ("across_m",) and recording.ended == ""
    for frame in recording.frames:
        assert frame.belief is not None and frame.belief.particles.shape[1] == 1
        (ticks,) = VIEW.belief_marks(frame.belief, frame.picture)
        assert len(ticks.points) == 2 + 2 * frame.belief.particles.shape[0]
        assert [m.shape for m in frame.truth_marks] == ["ellipse"]
        assert [m.shape for m in frame.estimate_marks] == ["segment"]
