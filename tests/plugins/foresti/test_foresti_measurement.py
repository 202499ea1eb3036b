"""The measurement model g of seeds/004 (eqs. 11, 18-22) and its Jacobian G."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_foresti.measurement import (
    PipeCamera,
    _image_lines,
    border_abscissae,
    border_jacobian,
    border_lines,
    border_measurement,
    pose_angles,
)

from benchmark.modalities.camera.geometry import cable_borders, cable_from_borders, chord_midpoint
from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.silhouette import cable_truth
from benchmark.modalities.camera.scenes.projection import (
    camera_axes_derivatives,
    project_points,
    projection_matrix,
)

CAMERA = PipeCamera(
    focal_px=380.0, size=(320, 240), diameter_m=0.2, nominal_tilt=math.radians(60.0), frame_interval_s=0.04
)
OUTLINE = dataclasses.replace(CAMERA, border_model="tangent")

states = st.tuples(
    st.floats(-0.4, 0.4),
    st.floats(0.6, 2.5),
    st.floats(math.radians(-10.0), math.radians(10.0)),
    st.floats(math.radians(35.0), math.radians(85.0)),
    st.floats(math.radians(-8.0), math.radians(8.0)),
).map(np.array)


def appendix_abscissae(state: np.ndarray, camera: PipeCamera) -> np.ndarray:
    """Eqs. (18)-(22) as the Appendix derives them: solve (2b) for P_z on the row, substitute in (2a)."""
    cx, cy, theta, phi, xi = state
    t = projection_matrix(CameraPose(cx, cy, 0.0, theta, phi, xi), camera.focal_px, camera.size).reshape(-1)
    half = camera.diameter_m / 2.0
    out = []
    for row in (0.0, camera.size[1] - 1.0):
        for x in (-half, half):
            # (T4 X + T6 Z + T7) = row (T8 X + T10 Z + T11), with P_y = 0.
            z = (row * (t[8] * x + t[11]) - t[4] * x - t[7]) / (t[6] - row * t[10])
            out.append((t[0] * x + t[2] * z + t[3]) / (t[8] * x + t[10] * z + t[11]))
    return np.array(out)


@settings(max_examples=60, deadline=None)
@given(states)
def test_g_is_the_appendix_solution_of_eqs_2a_2b(state):
    np.testing.assert_allclose(border_abscissae(state, CAMERA), appendix_abscissae(state, CAMERA), rtol=1e-9, atol=1e-6)


@settings(max_examples=60, deadline=None)
@given(states, st.floats(0.5, 30.0))
def test_the_borders_g_gives_hold_the_images_of_the_pipe_lines(state, z):
    """g, its line pair and the cable model round-trip: points of X = -+d/2, Y = 0 project onto the lines."""
    cx, cy, theta, phi, xi = state
    matrix = projection_matrix(CameraPose(cx, cy, -3.0, theta, phi, xi), CAMERA.focal_px, CAMERA.size)
    left, right = border_lines(border_abscissae(state, CAMERA), CAMERA.size)
    for line, x in ((left, -0.1), (right, 0.1)):
        u, v = project_points(matrix, np.array((x, 0.0, z)))
        px, py = u - (CAMERA.size[0] - 1) / 2.0, (CAMERA.size[1] - 1) / 2.0 - v
        distance = abs((px - line.x0) * line.dy - (py - line.y0) * line.dx)
        assert distance < 1e-6 * max(1.0, abs(px) + abs(py))
    # The cable model of conventions section 1 holds the same two borders.
    state_lines = cable_from_borders(left, right)
    assert state_lines.w > 0 and state_lines.beta >= -1e-9
    assert chord_midpoint(left, CAMERA.size)[0] < chord_midpoint(right, CAMERA.size)[0]


@settings(max_examples=60, deadline=None)
@given(states, st.booleans(), st.sampled_from([CAMERA, OUTLINE]))
def test_the_jacobian_matches_central_differences(state, with_roll, camera):
    x = state if with_roll else state[:4]
    step = 1e-6
    numeric = np.stack(
        [
            (border_abscissae(x + step * e, camera) - border_abscissae(x - step * e, camera)) / (2 * step)
            for e in np.eye(len(x))
        ],
        axis=1,
    )
    analytic = border_jacobian(x, camera)
    assert analytic.shape == (4, len(x))
    np.testing.assert_allclose(analytic, numeric, rtol=1e-5, atol=1e-4)


def reference_jacobian(state: np.ndarray, camera: PipeCamera) -> np.ndarray:
    """:func:`border_jacobian` entry by entry."""
    lines, inverse_t, intrinsics, by_normal = _image_lines(state, camera)
    rows = camera.rows
    axes = camera_axes_derivatives(*pose_angles(state))[: len(state) - 2]
    jacobian = np.empty((4, len(state)))
    for border, line in enumerate(lines):
        derivatives = [inverse_t @ by_normal[border, 0], inverse_t @ by_normal[border, 1]]
        derivatives += [-inverse_t @ (intrinsics @ d_axes).T @ line for d_axes in axes]
        along = line[1] * rows + line[2]
        for column, dl in enumerate(derivatives):
            jacobian[[border, border + 2], column] = -(dl[1] * rows + dl[2]) / line[0] + along * dl[0] / line[0] ** 2
    return jacobian


@settings(max_examples=100, deadline=None)
@given(states, st.booleans(), st.sampled_from([CAMERA, OUTLINE]))
def test_the_jacobian_and_the_joint_measurement_equal_their_references(state, with_roll, camera):
    x = state if with_roll else state[:4]
    np.testing.assert_allclose(border_jacobian(x, camera), reference_jacobian(x, camera), rtol=1e-12, atol=1e-9)
    abscissae, jacobian = border_measurement(x, camera)
    assert np.array_equal(abscissae, border_abscissae(x, camera))
    assert jacobian is not None
    np.testing.assert_allclose(jacobian, reference_jacobian(x, camera), rtol=1e-12, atol=1e-9)


def crossings(line, size: tuple[int, int]) -> tuple[float, float]:
    """Pixel columns where a model line crosses the first and last rows."""
    half_w, half_h = (size[0] - 1) / 2.0, (size[1] - 1) / 2.0
    return tuple(line.x0 + (y - line.y0) / line.dy * line.dx + half_w for y in (half_h, -half_h))


@settings(max_examples=60, deadline=None)
@given(states, st.floats(0.1, 0.45))
def test_the_outline_model_gives_the_rendered_truth_and_the_plane_model_lies_inside_it(state, diameter):
    """The "tangent" borders are the silhouette the scenes score against; the paper's lines lie within it."""
    cx, cy, theta, phi, xi = state
    camera = dataclasses.replace(CAMERA, diameter_m=diameter, border_model="tangent")
    truth = cable_truth(CameraPose(cx, cy, 0.0, theta, phi, xi), diameter / 2, camera.focal_px, camera.size)
    left, right = sorted(cable_borders(truth), key=lambda line: crossings(line, camera.size)[1])
    (i1, i3), (i2, i4) = crossings(left, camera.size), crossings(right, camera.size)
    np.testing.assert_allclose(border_abscissae(state, camera), (i1, i2, i3, i4), atol=1e-6)
    plane = border_abscissae(state, dataclasses.replace(camera, border_model="plane"))
    assert i1 - 1e-6 <= plane[0] and plane[1] <= i2 + 1e-6 and i3 - 1e-6 <= plane[2] and plane[3] <= i4 + 1e-6


def test_the_joint_measurement_has_no_jacobian_without_abscissae():
    on_the_left_border = np.array([-CAMERA.diameter_m / 2, 0.0, 0.0, 1.0])  # the left border's image degenerates
    abscissae, jacobian = border_measurement(on_the_left_border, CAMERA)
    assert not np.all(np.isfinite(abscissae)) and jacobian is None


def test_the_camera_height_along_the_pipe_does_not_matter_and_roll_zero_is_the_four_state():
    state = np.array([0.1, 1.5, 0.02, 1.0])
    np.testing.assert_array_equal(border_abscissae(state, CAMERA), border_abscissae(np.r_[state, 0.0], CAMERA))


def test_a_centred_level_camera_sees_symmetric_borders():
    z = border_abscissae(np.array([0.0, 1.5, 0.0, 1.0]), CAMERA)
    centre = (CAMERA.size[0] - 1) / 2.0
    assert z[0] < centre < z[1] and z[2] < centre < z[3]
    assert z[0] + z[1] == pytest.approx(2 * centre) and z[2] + z[3] == pytest.approx(2 * centre)
    assert z[3] - z[2] > z[1] - z[0]  # nearer at the bottom: wider


def test_border_lines_refuse_non_finite_abscissae():
    with pytest.raises(ValueError, match="not a line"):
        border_lines(np.array([1.0, 2.0, math.nan, 4.0]), CAMERA.size)
