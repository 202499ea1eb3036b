"""Tests of the pixel labels taken from a frame's truth."""

from __future__ import annotations

import math

import numpy as np
import pytest
from trackbench_texture.labels import cable_mask, outward_offsets

from benchmark.modalities.camera.model import CableState

SIZE = (41, 21)


def test_a_vertical_cable_covers_the_columns_between_its_borders():
    # Centre column u = 20; borders at x = -5.25 and x = +5.25, so columns 15 to 25.
    mask = cable_mask(CableState(0.0, 0.0, 10.5, 0.0), SIZE)
    assert mask.shape == (21, 41)
    assert np.array_equal(np.flatnonzero(mask.all(axis=0)), np.arange(15, 26))
    assert not mask[:, :15].any() and not mask[:, 26:].any()


def test_the_mask_follows_distance_and_angle():
    shifted = cable_mask(CableState(8.0, 0.0, 4.5, 0.0), SIZE)
    assert np.array_equal(np.flatnonzero(shifted[10]), np.arange(26, 31))
    lying = cable_mask(CableState(0.0, math.pi / 2, 4.5, 0.0), SIZE)
    assert np.array_equal(np.flatnonzero(lying[:, 3]), np.arange(8, 13))


def test_a_skewed_cable_narrows_towards_the_top():
    mask = cable_mask(CableState(0.0, 0.0, 12.0, math.radians(8.0)), (41, 61))
    assert mask[0].sum() < mask[30].sum() < mask[60].sum()


def test_outward_offsets_are_distances_beyond_the_borders_and_negative_inside():
    cable = CableState(0.0, 0.0, 10.0, 0.0)
    points = np.array([[20.0, 10.0], [16.0, 3.0], [12.0, 10.0], [29.0, 0.0]])
    assert outward_offsets(cable, points, SIZE) == pytest.approx([-5.0, -1.0, 3.0, 4.0])
