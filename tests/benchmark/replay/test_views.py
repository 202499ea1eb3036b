"""The views' registry, marks and plane map: corners on pixel centres, ellipses at two standard deviations."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.drawing import Viewport
from benchmark.replay.views import Mark, NoViewError, PlaneMap, view_of


def test_every_built_in_modality_has_a_view_and_others_are_refused() -> None:
    assert [view_of(name).dimensions[0] for name in ("camera", "sonar", "stereo")] == ["d_px", "across_m", "north_m"]
    with pytest.raises(NoViewError, match="replay cannot show lidar frames yet .it shows: camera, sonar, stereo."):
        view_of("lidar")


def test_the_plane_map_puts_the_viewport_s_corners_on_pixel_centres_and_keeps_points_in_its_box() -> None:
    viewport = Viewport(left=-10.0, right=30.0, top=5.0, bottom=-15.0, width=81, height=41)
    plane = PlaneMap.of(viewport, offset=(0, 100))
    assert plane.point(-10.0, 5.0) == pytest.approx((0.5, 100.5))
    assert plane.point(30.0, -15.0) == pytest.approx((80.5, 140.5))
    assert plane.point(10.0, -5.0) == pytest.approx((40.5, 120.5))
    assert plane.box == (0.0, 100.0, 81.0, 141.0)
    assert plane.point(1e6, 1e6) == (81.0, 100.0)  # far east and far up: the box's top-right corner


def test_the_ellipse_of_a_known_covariance() -> None:
    """Variances 1 along x and 4 along y, 2 px per unit, y up: half-axes 2 * 2 * 2 = 8 px upright and 4 px across."""
    plane = PlaneMap(u0=100.0, du=2.0, v0=50.0, dv=-2.0, box=(0.0, 0.0, 200.0, 100.0))
    mark = plane.ellipse((3.0, 4.0), np.diag([1.0, 4.0]), sigmas=2.0, role="covariance")
    u, v, major, minor, angle = mark.points
    assert (mark.shape, mark.role) == ("ellipse", "covariance")
    assert (u, v) == (106.0, 42.0)
    assert (major, minor) == pytest.approx((8.0, 4.0))
    assert abs(math.cos(angle)) < 1e-12  # the long axis upright


covariances = st.tuples(
    st.floats(0.05, 20.0), st.floats(0.05, 20.0), st.floats(-0.95, 0.95), st.floats(0.5, 8.0), st.floats(0.5, 8.0)
)


@given(covariances, st.booleans(), st.floats(0.0, 2 * math.pi))
def test_the_ellipse_joins_the_points_two_standard_deviations_from_the_mean(
    case: tuple[float, float, float, float, float], y_up: bool, t: float
) -> None:
    sx, sy, rho, du, dv = case
    covariance = np.array([[sx * sx, rho * sx * sy], [rho * sx * sy, sy * sy]])
    plane = PlaneMap(u0=10.0, du=du, v0=20.0, dv=-dv if y_up else dv, box=(0.0, 0.0, 1e3, 1e3))
    u, v, major, minor, angle = plane.ellipse((1.0, -2.0), covariance).points
    assert major >= minor >= 0
    along = np.array([math.cos(angle), math.sin(angle)])
    across = np.array([-math.sin(angle), math.cos(angle)])
    boundary = np.array([u, v]) + major * math.cos(t) * along + minor * math.sin(t) * across
    offset = np.array([(boundary[0] - plane.u0) / plane.du - 1.0, (boundary[1] - plane.v0) / plane.dv + 2.0])
    assert offset @ np.linalg.solve(covariance, offset) == pytest.approx(4.0, rel=1e-6)


def test_a_mark_knows_whether_its_numbers_are_finite() -> None:
    assert Mark.circle(1.0, 2.0, 3.0).finite and Mark.cross(0.0, 0.0, 4.0, "measurement").finite
    assert not Mark.segment((0.0, 1.0, math.nan, 2.0)).finite
    assert not Mark("ticks", (0.0, 48.0, math.inf, 1.0), "particle").finite
