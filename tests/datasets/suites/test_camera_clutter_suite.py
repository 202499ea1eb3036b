"""The camera-clutter suite: S1's definition drawn with ten seeds fixed in advance."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from trackbench_suites.loader import load_suites

SEEDS = (3101, 4101, 5101, 6101, 7101, 8101, 9101, 10101, 11101, 12101)
NAMES = [f"camera-clutter/S1-d{draw:02d}" for draw in range(1, 11)]


@pytest.fixture(scope="module")
def suites(kinds) -> dict:
    return {suite.name: {seq.info.name: seq for seq in suite.sequences} for suite in load_suites(kinds)}


def test_ten_draws_with_the_seeds_fixed_in_advance(suites) -> None:
    clutter = suites["camera-clutter"]
    assert list(clutter) == NAMES
    assert tuple(seq.spec.seed for seq in clutter.values()) == SEEDS
    assert all(seq.info.modality == "camera" and seq.info.n_frames == 248 for seq in clutter.values())


def test_each_draw_is_s1_but_for_seed_name_and_description(suites) -> None:
    s1 = suites["camera"]["camera/S1"].spec
    for name, seq in suites["camera-clutter"].items():
        spec = seq.spec
        assert (spec.name, spec.seed) == (name, SEEDS[NAMES.index(name)])
        assert spec.description != s1.description
        assert dataclasses.replace(spec, seed=s1.seed, name=s1.name, description=s1.description) == s1, name


def test_two_draws_render_different_frames(suites) -> None:
    first, second = (next(iter(suites["camera-clutter"][name].frames())) for name in NAMES[:2])
    assert first.observation.shape == second.observation.shape == (240, 320)
    assert np.mean(first.observation != second.observation) > 0.1
