"""The pipe's border lines in the cross-section: the paper's plane lines and the occluding contours."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_foresti.borders import BORDER_MODELS, plane_borders, tangent_borders

from benchmark.modalities.camera.scenes.silhouette import tangent_points

outside = st.tuples(st.floats(-1.0, 1.0), st.floats(0.3, 3.0), st.floats(0.02, 0.25)).filter(
    lambda c: math.hypot(c[0], c[1]) > 1.05 * c[2]
)


@settings(max_examples=80, deadline=None)
@given(outside)
def test_each_contour_passes_through_a_tangent_point_and_the_camera(centre):
    """n is normal to the plane through the camera and the generator: n . (T - C) = 0, with T on the circle."""
    cx, cy, radius = centre
    normals, _ = tangent_borders(cx, cy, radius)
    touching = tangent_points(cx, cy, radius)
    for normal, (x, y) in zip(normals, touching, strict=True):
        assert math.hypot(x, y) == pytest.approx(radius)
        assert normal[0] * (x - cx) + normal[1] * (y - cy) == pytest.approx(0.0, abs=1e-9)
        # The plane through C and the generator at T: the generator's foot T is the line's point, n parallel to T.
        assert normal[0] * y - normal[1] * x == pytest.approx(0.0, abs=1e-9)
    # Left first: the contour on the side of -X when the camera is above the pipe.
    assert normals[0][0] < normals[1][0]


@settings(max_examples=80, deadline=None)
@given(outside, st.sampled_from(sorted(BORDER_MODELS)))
def test_the_derivatives_match_central_differences(centre, model):
    cx, cy, radius = centre
    borders = BORDER_MODELS[model]
    _, analytic = borders(cx, cy, radius)
    step = 1e-7
    for axis in range(2):
        shift = np.eye(2)[axis] * step
        ahead, _ = borders(cx + shift[0], cy + shift[1], radius)
        behind, _ = borders(cx - shift[0], cy - shift[1], radius)
        np.testing.assert_allclose(analytic[:, axis], (ahead - behind) / (2 * step), rtol=1e-5, atol=1e-6)


def test_the_plane_lines_are_the_papers():
    normals, derivatives = plane_borders(0.25, 1.5, 0.25)
    np.testing.assert_array_equal(normals, [[-1.5, 0.5, 0.0], [-1.5, 0.0, 0.0]])
    np.testing.assert_array_equal(derivatives, [[[0, 1, 0], [-1, 0, 0]]] * 2)


@pytest.mark.parametrize("ratio", [0.05, 0.01, 0.001])
def test_the_contours_approach_the_plane_lines_for_a_thin_pipe(ratio):
    """As r / C_y falls, the outline's lines turn towards the plane's: their angle difference shrinks as (r/C_y)^2."""
    cy, radius = 2.0, 2.0 * ratio
    plane, _ = plane_borders(0.0, cy, radius)
    tangent, _ = tangent_borders(0.0, cy, radius)
    for p, t in zip(plane, tangent, strict=True):
        angle = math.atan2(abs(p[0] * t[1] - p[1] * t[0]), abs(p[0] * t[0] + p[1] * t[1]))
        assert angle < ratio**2


def test_there_is_no_outline_from_inside_the_pipe():
    normals, derivatives = tangent_borders(0.05, 0.05, 0.2)
    assert np.isnan(normals).all() and np.isnan(derivatives).all()
