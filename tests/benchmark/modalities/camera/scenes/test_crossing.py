"""A second cable across the pipe: drawn where its cylinder projects, nearer surface first, truth unchanged."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.errors import DataError
from benchmark.identity import digest
from benchmark.modalities.camera.model import CameraPose
from benchmark.modalities.camera.scenes.crossing import CrossingCable, crossing_axis_line
from benchmark.modalities.camera.scenes.projection import pixel_rays, pose_axes, project_points, projection_matrix
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.camera.scenes.spec import CameraSceneSpec, Crossing
from benchmark.modalities.camera.scenes.texture import TextureGrid

SIZE = (96, 72)
FOCAL = 114.0
SEABED_GREY, PIPE_GREY = 200.0, 25.0  # the flat scene's sand and pipe (albedo 0.8 and 0.1 at exposure 250)
POSE = CameraPose(cx=0.2, cy=1.5, cz=0.0, theta=0.0, phi=np.radians(60.0), xi=0.0)


def _scene(flat_scene: Callable[..., dict[str, Any]], *crossings: dict[str, Any]) -> CameraScene:
    data = flat_scene(frame_size=list(SIZE), focal_px=FOCAL, n_frames=2)
    if crossings:
        data["crossing"] = list(crossings)
    return CameraScene.from_dict(data)


def _image(scene: CameraScene, pose: CameraPose = POSE) -> np.ndarray:
    return scene.render_from(pose, 0, clean=True)


def _pixels_of(points: np.ndarray, pose: CameraPose = POSE) -> np.ndarray:
    """The pixels (row, col) of world points, those inside the image."""
    uv = np.rint(project_points(projection_matrix(pose, FOCAL, SIZE), points)).astype(int)
    inside = (uv[:, 0] >= 0) & (uv[:, 0] < SIZE[0]) & (uv[:, 1] >= 0) & (uv[:, 1] < SIZE[1])
    return uv[inside][:, ::-1]


def _distance_px(line: np.ndarray) -> np.ndarray:
    """Distance of every pixel from a homogeneous pixel line, shape ``(H, W)``."""
    a, b, c = line
    v, u = np.mgrid[0 : SIZE[1], 0 : SIZE[0]]
    return np.abs(a * u + b * v + c) / np.hypot(a, b)


def test_the_crossing_darkens_the_seabed_along_its_projected_top_and_nothing_else(flat_scene) -> None:
    plain = _scene(flat_scene)
    crossed = _scene(flat_scene, {"at_m": 1.0, "angle_deg": 50.0})
    without, with_it = _image(plain), _image(crossed)
    cable = CrossingCable.build(crossed.spec.crossing[0], crossed.spec, crossed._state().grid, np.random.default_rng(0))
    along = np.linspace(-3.0, 3.0, 1201)[:, None]
    top = cable.origin + along * cable.direction + np.array((0.0, cable.radius, 0.0))
    rows, cols = _pixels_of(top).T
    on_sand = without[rows, cols] > 0.9 * SEABED_GREY
    assert on_sand.sum() > 40  # it runs across the image, beside the pipe
    np.testing.assert_allclose(with_it[rows, cols][on_sand], PIPE_GREY, atol=0.5)
    # Away from its image (more than its apparent width) the frame is the frame without it.
    far = _distance_px(crossing_axis_line(cable, POSE, FOCAL, SIZE)) > 25.0
    assert far.sum() > without.size // 3
    np.testing.assert_array_equal(with_it[far], without[far])


def test_where_the_cables_cross_the_ray_sees_the_nearer_surface(flat_scene) -> None:
    grey = {"albedo": 0.3, "texture": 0.0, "specular": 0.0}  # 75 grey: neither sand nor pipe
    thick = _scene(flat_scene, {"at_m": 1.0, "angle_deg": 90.0, "diameter_m": 0.3, "look": grey})
    thin = _scene(flat_scene, {"at_m": 1.0, "angle_deg": 90.0, "diameter_m": 0.1, "look": grey})
    pipe_radius = thick.spec.radius
    above_axis = CameraPose(cx=0.0, cy=1.5, cz=0.0, theta=0.0, phi=np.radians(60.0), xi=0.0)
    # The thick one's top (0.3 m above the seabed) hides the pipe's; the pipe's top hides the thin one.
    (thick_top,) = _pixels_of(np.array([[0.0, 0.3 - pipe_radius, 1.0]]), above_axis)
    (pipe_top,) = _pixels_of(np.array([[0.0, pipe_radius, 1.0]]), above_axis)
    assert _image(thick, above_axis)[tuple(thick_top)] == pytest.approx(75.0, abs=0.5)
    assert _image(thin, above_axis)[tuple(pipe_top)] == pytest.approx(PIPE_GREY, abs=0.5)


def test_the_truth_stays_the_followed_cable(flat_scene) -> None:
    plain, crossed = _scene(flat_scene), _scene(flat_scene, {"at_m": 0.8, "angle_deg": 120.0})
    assert crossed.truth(0) == plain.truth(0) and crossed.truth(1) == plain.truth(1)
    assert not np.array_equal(crossed.render(0), plain.render(0))


def test_a_spec_without_crossing_keeps_its_identity(flat_scene) -> None:
    data = flat_scene(frame_size=list(SIZE), focal_px=FOCAL)
    spec = CameraSceneSpec.from_dict(data)
    assert digest(spec) == digest(CameraSceneSpec.from_dict({**data, "crossing": []}))
    assert digest(spec) != digest(CameraSceneSpec.from_dict({**data, "crossing": [{"at_m": 1.0, "angle_deg": 45.0}]}))


def test_the_same_spec_draws_the_same_crossing(flat_scene) -> None:
    textured = {"at_m": 1.5, "angle_deg": 50.0, "look": {"albedo": 0.2, "texture": 0.3}}
    first, again = _scene(flat_scene, textured), _scene(flat_scene, textured)
    np.testing.assert_array_equal(_image(first), _image(again))


@pytest.mark.parametrize(
    ("crossing", "message"),
    [
        ({"at_m": 1.0, "angle_deg": 0.0}, "angle_deg"),
        ({"at_m": 1.0, "angle_deg": 180.0}, "angle_deg"),
        ({"at_m": 1.0, "angle_deg": 45.0, "diameter_m": -0.1}, "diameter_m"),
        ({"angle_deg": 45.0}, "at_m"),
    ],
)
def test_a_bad_crossing_is_a_data_error_naming_the_key(flat_scene, crossing: dict[str, Any], message: str) -> None:
    with pytest.raises(DataError, match=message):
        CameraSceneSpec.from_dict(flat_scene(crossing=[crossing]), "suite.toml")


def test_the_water_model_draws_the_crossing_dark_as_the_pipe(flat_scene) -> None:
    water = {**flat_scene()["optics"], "water": {"sun": 0.5}}
    plain = CameraScene.from_dict(flat_scene(frame_size=list(SIZE), focal_px=FOCAL, optics=water))
    crossed = CameraScene.from_dict(
        flat_scene(frame_size=list(SIZE), focal_px=FOCAL, optics=water, crossing=[{"at_m": 1.0, "angle_deg": 50.0}])
    )
    without, with_it = _image(plain), _image(crossed)
    cable = CrossingCable.build(crossed.spec.crossing[0], crossed.spec, crossed._state().grid, np.random.default_rng(0))
    top = cable.origin + np.linspace(-3.0, 3.0, 1201)[:, None] * cable.direction + np.array((0.0, cable.radius, 0.0))
    rows, cols = _pixels_of(top).T
    pipe_column = np.abs(cols - np.median(np.argmin(without, axis=1))) < 10
    darkened = (with_it[rows, cols] / without[rows, cols])[~pipe_column]
    far = _distance_px(crossing_axis_line(cable, POSE, FOCAL, SIZE)) > 25.0
    exposure = np.median(with_it[far] / without[far])  # the automatic exposure scales the whole frame
    assert darkened.size > 40 and np.median(darkened) < 0.4 * exposure


def test_crossing_spec_defaults_take_the_followed_cable(flat_scene) -> None:
    spec = CameraSceneSpec.from_dict(flat_scene(crossing=[{"at_m": 1.0, "angle_deg": 45.0}]))
    cable = CrossingCable.build(spec.crossing[0], spec, _scene(flat_scene)._state().grid, np.random.default_rng(1))
    assert cable.radius == spec.radius and cable.look == spec.cable
    assert cable.origin[1] == pytest.approx(0.0)  # resting on the seabed Y = -r, as the pipe
    assert spec.crossing == (Crossing(at_m=1.0, angle_deg=45.0),)


@settings(max_examples=30, deadline=None)
@given(
    angle=st.floats(5.0, 175.0),
    at=st.floats(-1.0, 4.0),
    diameter=st.floats(0.05, 0.5),
    cx=st.floats(-1.5, 1.5),
    cy=st.floats(0.8, 3.0),
    theta=st.floats(-30.0, 30.0),
    phi=st.floats(30.0, 90.0),
)
def test_every_hit_lies_on_the_crossing_cylinder_ahead_of_the_camera(
    angle: float, at: float, diameter: float, cx: float, cy: float, theta: float, phi: float
) -> None:
    crossing = {"at_m": at, "angle_deg": angle, "diameter_m": diameter}
    spec = CameraSceneSpec.from_dict({"name": "t/c", "n_frames": 1, "crossing": [crossing]})
    grid = TextureGrid(x0=-2.56, z0=0.0, cell=0.01, nx=512, nz=64)
    cable = CrossingCable.build(spec.crossing[0], spec, grid, np.random.default_rng(2))
    pose = CameraPose(cx=cx, cy=cy, cz=0.0, theta=np.radians(theta), phi=np.radians(phi), xi=0.0)
    qx, qy = pixel_rays(FOCAL, SIZE)
    rays = (np.linalg.inv(pose_axes(pose)) @ np.stack((qx.ravel(), qy.ravel(), np.ones(qx.size)))).astype(np.float32)
    seen = cable.hits(pose, rays, (rays * rays).sum(axis=0))
    assert np.all(seen.t > 0) and np.all((seen.facing >= 0) & (seen.facing <= 1.001))
    points = np.array((cx, cy, 0.0))[:, None] + seen.t * rays[:, seen.index].astype(float) - cable.origin[:, None]
    across = points - np.outer(cable.direction, cable.direction @ points)
    np.testing.assert_allclose(np.linalg.norm(across, axis=0), cable.radius, rtol=0, atol=1e-3)  # float32, grazing rays
    assert np.all(points[1] + cable.origin[1] >= -spec.radius - 1e-3)  # on or above the seabed Y = -r
