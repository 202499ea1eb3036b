"""Ground truth of the pipe's image: tangent generators and the cable state they give."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.geometry import ImageSize, Line, cable_borders, pixel_to_model
from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.projection import project_points, projection_matrix
from benchmark.modalities.camera.scenes.silhouette import cable_truth, tangent_points

SIZE = (320, 240)
FOCAL = 380.0
RADIUS = 0.1

forward_down = st.builds(
    CameraPose,
    cx=st.floats(-0.5, 0.5),
    cy=st.floats(1.0, 4.0),
    cz=st.floats(-3.0, 3.0),
    theta=st.floats(-0.3, 0.3),
    phi=st.floats(math.radians(35), math.radians(89)),
    xi=st.floats(-0.05, 0.05),
)


def silhouette_borders(pose: CameraPose, radius: float, focal_px: float, size: ImageSize) -> tuple[Line, Line]:
    """The pipe's two occluding contours in model coordinates, ordered as ``cable_borders`` orders them."""
    return cable_borders(cable_truth(pose, radius, focal_px, size))


@settings(max_examples=40, deadline=None)
@given(cx=st.floats(-3, 3), cy=st.floats(0.2, 4), radius=st.floats(0.01, 0.15))
def test_tangent_points_touch_the_circle_at_right_angles(cx: float, cy: float, radius: float) -> None:
    for x, y in tangent_points(cx, cy, radius):
        assert math.hypot(x, y) == pytest.approx(radius)
        # The radius to the tangent point is perpendicular to the line from the camera.
        assert (x - cx) * x + (y - cy) * y == pytest.approx(0.0, abs=1e-9)


def test_camera_inside_the_pipe_is_an_error() -> None:
    with pytest.raises(ValueError, match="not outside"):
        tangent_points(0.01, 0.02, 0.1)


@pytest.mark.parametrize("height", [0.8, 2.0, 3.5])
def test_straight_down_view_gives_the_cone_width(height: float) -> None:
    # From straight above, the silhouette is seen under the half angle asin(r / Cy).
    state = cable_truth(CameraPose(0.0, height, 0.0, 0.0, math.pi / 2, 0.0), RADIUS, FOCAL, SIZE)
    assert state.w == pytest.approx(2 * FOCAL * math.tan(math.asin(RADIUS / height)))
    assert state.d == pytest.approx(0.0, abs=1e-9)
    assert state.alpha == pytest.approx(0.0, abs=1e-9)
    assert state.beta == pytest.approx(0.0, abs=1e-9)


@settings(max_examples=60, deadline=None)
@given(pose=forward_down)
def test_forward_down_views_have_positive_width_and_skew(pose: CameraPose) -> None:
    state = cable_truth(pose, RADIUS, FOCAL, SIZE)
    assert state.w > 0
    assert state.beta >= -1e-12


@settings(max_examples=30, deadline=None)
@given(pose=forward_down)
def test_mirroring_the_camera_mirrors_the_cable(pose: CameraPose) -> None:
    level = CameraPose(pose.cx, pose.cy, pose.cz, 0.0, pose.phi, 0.0)
    mirrored = CameraPose(-pose.cx, pose.cy, pose.cz, 0.0, pose.phi, 0.0)
    a, b = cable_truth(level, RADIUS, FOCAL, SIZE), cable_truth(mirrored, RADIUS, FOCAL, SIZE)
    assert b.d == pytest.approx(-a.d, abs=1e-7)
    assert b.alpha == pytest.approx(-a.alpha, abs=1e-9)
    assert b.w == pytest.approx(a.w)
    assert b.beta == pytest.approx(a.beta, abs=1e-9)


def test_camera_right_of_the_pipe_sees_it_left_of_centre() -> None:
    state = cable_truth(CameraPose(0.3, 2.0, 0.0, 0.0, math.radians(60), 0.0), RADIUS, FOCAL, SIZE)
    assert state.d < 0 and abs(state.alpha) < 0.5


@settings(max_examples=30, deadline=None)
@given(pose=forward_down)
def test_generator_points_lie_on_the_border_lines(pose: CameraPose) -> None:
    borders = silhouette_borders(pose, RADIUS, FOCAL, SIZE)
    t = projection_matrix(pose, FOCAL, SIZE)
    for x, y in tangent_points(pose.cx, pose.cy, RADIUS):
        for ahead in (0.5, 2.0, 6.0):
            u, v = project_points(t, np.array([[x, y, pose.cz + ahead]]))[0]
            px, py = pixel_to_model(u, v, SIZE)
            distances = [abs((px - line.x0) * line.dy - (py - line.y0) * line.dx) for line in borders]
            assert min(distances) < 1e-6 * (1 + abs(px) + abs(py))
