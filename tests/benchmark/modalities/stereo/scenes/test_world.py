"""Sea texture pyramid and shoreline of the stereo images."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from benchmark.modalities.stereo.scenes.image_spec import StereoRenderSpec
from benchmark.modalities.stereo.scenes.world import SHORE_BINS, sea_texture, shoreline

SPEC = StereoRenderSpec()


@pytest.fixture(scope="module")
def sea():
    return sea_texture(SPEC, np.random.default_rng(4))


def test_sea_levels_halve_and_the_finest_has_unit_spread(sea) -> None:
    sizes = [level.shape[0] for level in sea.levels]
    assert all(b * 2 == a for a, b in zip(sizes, sizes[1:]))
    assert float(sea.levels[0].std()) == pytest.approx(1.0, abs=1e-3)
    assert sea.period_m == pytest.approx(sea.texel_m * sizes[0])
    spreads = [float(level.std()) for level in sea.levels]
    assert all(b <= a for a, b in zip(spreads, spreads[1:]))


def test_the_wave_field_tiles_without_a_seam(sea) -> None:
    field = sea.levels[0]
    inside = np.abs(np.diff(field, axis=1)).mean()
    across = np.abs(field[:, -1] - field[:, 0]).mean()
    assert across < 1.3 * inside
    inside_rows = np.abs(np.diff(field, axis=0)).mean()
    assert np.abs(field[-1] - field[0]).mean() < 1.3 * inside_rows


@pytest.mark.parametrize("level", [1, 2, 3])
def test_coarse_levels_are_the_fine_field_seen_from_afar(sea, level: int) -> None:
    fine = cv2.resize(sea.levels[0], sea.levels[level].shape[::-1], interpolation=cv2.INTER_AREA)
    assert np.corrcoef(fine.ravel(), sea.levels[level].ravel())[0, 1] > 0.7


def test_shoreline_has_land_open_sea_and_a_fixed_look_per_seed() -> None:
    shore = shoreline(SPEC, np.random.default_rng(9))
    heights = shore.heights_m
    assert heights.shape == (SHORE_BINS,)
    assert heights.min() >= 0.0 and heights.max() <= SPEC.shore_height_m + 1e-3
    assert 0.02 < np.mean(heights < 1.0) < 0.6
    assert np.mean(heights > 0.3 * SPEC.shore_height_m) > 0.2
    assert shore.colours.min() >= 0.0 and shore.colours.max() <= 255.0
    again = shoreline(SPEC, np.random.default_rng(9))
    np.testing.assert_array_equal(again.colours, shore.colours)
    assert not np.array_equal(shoreline(SPEC, np.random.default_rng(10)).heights_m, heights)
