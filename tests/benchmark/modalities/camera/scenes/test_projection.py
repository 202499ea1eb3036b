"""The pinhole camera of seeds/004, section II: versors, the matrix T, pixel rays."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.geometry import ImageSize
from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.projection import (
    camera_axes,
    homogeneous_line,
    pixel_rays,
    pose_axes,
    principal_point,
    project_points,
    projection_matrix,
)

SIZE = (320, 240)
FOCAL = 380.0

poses = st.builds(
    CameraPose,
    cx=st.floats(-1.0, 1.0),
    cy=st.floats(0.5, 4.0),
    cz=st.floats(-5.0, 5.0),
    theta=st.floats(-0.5, 0.5),
    phi=st.floats(0.3, 1.6),
    xi=st.floats(-0.3, 0.3),
)


def _points_ahead(pose: CameraPose, offsets: np.ndarray) -> np.ndarray:
    """World points at depths 1..5 along the optical axis, shifted sideways."""
    h, v, a = pose_axes(pose)
    centre = np.array((pose.cx, pose.cy, pose.cz))
    return centre + offsets[:, :1] * h + offsets[:, 1:2] * v + offsets[:, 2:3] * a


def project_direct(pose: CameraPose, focal_px: float, size: ImageSize, points: np.ndarray) -> np.ndarray:
    """Pixels of world points from the versors, without building ``T``.

    ``u = u0 + f (P-C).h / (P-C).a`` and ``v = v0 + f (P-C).v / (P-C).a``.

    References
    ----------
    seeds/004, section II (the pinhole model of Fig. 1).
    """
    h, v, a = pose_axes(pose)
    rel = np.asarray(points, dtype=float) - np.array((pose.cx, pose.cy, pose.cz))
    u0, v0 = principal_point(size)
    depth = rel @ a
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.stack((u0 + focal_px * (rel @ h) / depth, v0 + focal_px * (rel @ v) / depth), axis=-1)


@settings(max_examples=30, deadline=None)
@given(pose=poses)
def test_matrix_projection_equals_direct_projection(pose: CameraPose) -> None:
    offsets = np.array([[0.3, -0.2, 1.0], [-1.0, 0.5, 2.5], [0.0, 0.0, 4.0], [2.0, 1.5, 5.0]])
    points = _points_ahead(pose, offsets)
    by_matrix = project_points(projection_matrix(pose, FOCAL, SIZE), points)
    direct = project_direct(pose, FOCAL, SIZE, points)
    np.testing.assert_allclose(by_matrix, direct, atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(pose=poses)
def test_camera_centre_spans_the_null_space_of_t(pose: CameraPose) -> None:
    # This is what the sign of the i0 C.a term in eqs. (3d), (3h) decides.
    t = projection_matrix(pose, FOCAL, SIZE)
    np.testing.assert_allclose(t @ np.array((pose.cx, pose.cy, pose.cz, 1.0)), 0.0, atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(pose=poses, zero_pan=st.booleans())
def test_point_on_the_optical_axis_lands_on_the_image_centre(pose: CameraPose, zero_pan: bool) -> None:
    # The printed versors are orthonormal when pan or roll is zero; only then
    # is a perpendicular to the image axes h and v.
    theta, xi = (0.0, pose.xi) if zero_pan else (pose.theta, 0.0)
    pose = CameraPose(pose.cx, pose.cy, pose.cz, theta, pose.phi, xi)
    point = _points_ahead(pose, np.array([[0.0, 0.0, 3.0]]))
    np.testing.assert_allclose(project_points(projection_matrix(pose, FOCAL, SIZE), point)[0], principal_point(SIZE))


@settings(max_examples=30, deadline=None)
@given(pose=poses, u=st.integers(0, 319), v=st.integers(0, 239), depth=st.floats(0.5, 20.0))
def test_pixel_rays_project_back_to_their_pixel(pose: CameraPose, u: int, v: int, depth: float) -> None:
    qx, qy = pixel_rays(FOCAL, SIZE)
    assert qx.shape == qy.shape == (SIZE[1], SIZE[0])
    ray = np.linalg.inv(pose_axes(pose)) @ np.array((qx[v, u], qy[v, u], 1.0))
    point = np.array((pose.cx, pose.cy, pose.cz)) + depth * ray
    np.testing.assert_allclose(project_direct(pose, FOCAL, SIZE, point), (u, v), atol=1e-3)


@settings(max_examples=40, deadline=None)
@given(angle=st.floats(-1.5, 1.5), phi=st.floats(-1.6, 1.6), zero_pan=st.booleans())
def test_versors_are_orthonormal_when_pan_or_roll_is_zero(angle: float, phi: float, zero_pan: bool) -> None:
    axes = camera_axes(0.0, phi, angle) if zero_pan else camera_axes(angle, phi, 0.0)
    np.testing.assert_allclose(axes @ axes.T, np.eye(3), atol=1e-12)


def test_looking_down_the_image_is_not_mirrored() -> None:
    # Camera 20 cm to the right of the pipe, looking straight down: the pipe
    # is left of centre, the way ahead (+Z) is up, and +X is to the right.
    pose = CameraPose(0.2, 2.0, 0.0, 0.0, math.pi / 2, 0.0)
    t = projection_matrix(pose, FOCAL, SIZE)
    u0, v0 = principal_point(SIZE)
    (u_pipe, _), (_, v_ahead), (u_right, _) = project_points(
        t, np.array([[0.0, 0.0, 0.0], [0.2, -0.1, 1.0], [1.0, -0.1, 0.0]])
    )
    assert u_pipe < u0
    assert v_ahead < v0
    assert u_right > u0


def test_positive_tilt_looks_down_and_pan_turns_right() -> None:
    h, v, a = camera_axes(0.0, math.radians(60), 0.0)
    assert a[1] < 0 and a[2] > 0  # down and forward
    assert v[1] < 0  # image-down points down in the world
    h, v, a = camera_axes(math.radians(10), math.radians(60), 0.0)
    assert a[0] > 0


@settings(max_examples=20, deadline=None)
@given(pose=poses, x=st.floats(-0.5, 0.5), y=st.floats(-0.5, 0.5))
def test_homogeneous_line_contains_the_projected_points(pose: CameraPose, x: float, y: float) -> None:
    t = projection_matrix(pose, FOCAL, SIZE)
    line = homogeneous_line(t, (x, y, pose.cz), (0.0, 0.0, 1.0))
    a = pose_axes(pose)[2]
    for depth in (1.0, 3.0):
        # A point of the line X = x, Y = y in front of the camera, if a_z allows it.
        if abs(a[2]) < 1e-3:
            continue
        z = pose.cz + (depth - (x - pose.cx) * a[0] - (y - pose.cy) * a[1]) / a[2]
        u, v = project_points(t, np.array([[x, y, z]]))[0]
        assert abs(line[0] * u + line[1] * v + line[2]) <= 1e-6 * math.hypot(line[0], line[1]) * (1 + abs(u) + abs(v))
