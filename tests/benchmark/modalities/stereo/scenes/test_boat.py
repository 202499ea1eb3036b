"""The target boat of the stereo images: painter's order, size on the image, clipping."""

from __future__ import annotations

import numpy as np
import pytest

from benchmark.modalities.stereo.scenes.boat import CABIN, HULL, MARKER, BoatView, boat_body, draw_boat
from benchmark.modalities.stereo.scenes.image_spec import StereoRenderSpec

SPEC = StereoRenderSpec()
BODY = boat_body(SPEC)
FOCAL = 140.8
CENTRE = (159.5, 119.5)
SUN = np.array((0.0, 0.6, 0.8))


def coverage(view: BoatView) -> np.ndarray:
    """Share of every pixel the boat covers, from drawing it over two different backgrounds."""
    dark = np.zeros((240, 320, 3), dtype=np.float32)
    bright = np.full((240, 320, 3), 1000.0, dtype=np.float32)
    draw_boat(dark, BODY, view, FOCAL, CENTRE)
    draw_boat(bright, BODY, view, FOCAL, CENTRE)
    return 1.0 - (bright - dark)[..., 0] / 1000.0


def test_a_solid_on_another_hides_it_from_above_and_is_hidden_by_it_from_below() -> None:
    deck, roof = BODY.deck_m, BODY.roof_m
    assert BODY.solid_order(roof + 0.5) == (HULL, CABIN, MARKER)
    assert BODY.solid_order(0.5 * (deck + roof)) == (HULL, MARKER, CABIN)
    assert BODY.solid_order(0.5 * deck) == (MARKER, CABIN, HULL)


def test_the_marker_drum_stands_on_the_cabin_roof_round_the_reference_point() -> None:
    drum = BODY.vertices[BODY.starts[np.flatnonzero(BODY.solids == MARKER)[0]] :]
    radii = np.hypot(drum[:, 0], drum[:, 1])
    assert radii.max() == pytest.approx(SPEC.marker_radius_m)
    assert radii.min() > 0.99 * SPEC.marker_radius_m
    assert drum[:, 2].min() == pytest.approx(SPEC.freeboard_m + SPEC.cabin_height_m)
    assert drum[:, 2].max() == pytest.approx(BODY.top_m)


@pytest.mark.parametrize("distance", [6.0, 11.0, 19.5])
def test_seen_from_astern_the_transom_is_as_wide_as_the_beam_projects(distance: float) -> None:
    view = BoatView(ahead_m=distance, starboard_m=0.3, aspect=0.0, camera_height_m=1.0, sun=SUN)
    cover = coverage(view)
    stern = distance - SPEC.hull_length_m / 2
    # A row through the hull just below the deck, where only the transom is seen.
    row = int(round(CENTRE[1] - FOCAL * (0.6 - 1.0) / stern))
    assert cover[row].sum() == pytest.approx(FOCAL * SPEC.hull_beam_m / stern, abs=0.15)
    middle = (cover[row] * np.arange(320)).sum() / cover[row].sum()
    assert middle == pytest.approx(CENTRE[0] + FOCAL * 0.3 / stern, abs=0.1)
    assert cover.min() >= -1e-3 and cover.max() <= 1.0 + 1e-3


def test_nothing_is_drawn_for_a_boat_behind_the_camera_and_a_close_one_is_clipped() -> None:
    image = np.zeros((240, 320, 3), dtype=np.float32)
    behind = BoatView(ahead_m=-8.0, starboard_m=0.0, aspect=0.0, camera_height_m=1.0, sun=SUN)
    assert draw_boat(image, BODY, behind, FOCAL, CENTRE) is None
    assert not image.any()
    # The stern is behind the camera, the bow ahead and to starboard: only the starboard half shows it.
    straddling = BoatView(ahead_m=1.0, starboard_m=1.0, aspect=0.0, camera_height_m=1.0, sun=SUN)
    box = draw_boat(image, BODY, straddling, FOCAL, CENTRE)
    assert box is not None
    (u0, u1), _ = box
    assert u0 > CENTRE[0] and u1 == 320
    assert np.isfinite(image).all() and image[:, 160:].any() and not image[:, :150].any()
