"""The camera suite as specified: sequence lengths, ranges of the truth, burial, ripples."""

from __future__ import annotations

import math

import numpy as np
import pytest
from trackbench_suites.loader import load_suites

from benchmark.modalities.camera.scenes.overgrowth import overgrowth_layer
from benchmark.modalities.camera.scenes.texture import TextureGrid, profile_factor


@pytest.fixture(scope="module")
def camera(kinds):
    suites = {suite.name: suite.sequences for suite in load_suites(kinds)}
    return {seq.info.name.split("/")[1]: seq for seq in suites["camera"]}


@pytest.fixture(scope="module")
def truths(camera):
    return {name: [seq.truth(k) for k in range(seq.spec.n_frames)] for name, seq in camera.items()}


def test_lengths_follow_the_thesis_and_foresti(camera) -> None:
    assert {name: seq.spec.n_frames for name, seq in camera.items()} == {
        "S1": 248, "S1b": 248, "S1c": 248, "S2": 499, "S3": 409, "S4": 172, "S5": 171, "S6": 129, "S7": 150,
    }


def test_truth_stays_in_the_thesis_ranges(truths) -> None:
    for name, frames in truths.items():
        states = np.array([t.cable.as_array() for t in frames])
        d, alpha, w, beta = states.T
        assert np.all(w > 0) and np.all(beta >= 0), name
        assert np.all(beta < math.radians(10)), name
        assert np.mean((w >= 15) & (w <= 60)) > 0.95, name
        assert np.mean(np.abs(alpha) < math.radians(30)) > 0.95, name
        assert np.mean(np.abs(d) < 100) > 0.95, name  # the cable stays in view


def test_s6_moves_from_looking_down_to_looking_forward(camera, truths) -> None:
    phi = np.degrees(camera["S6"].trajectory().phi)
    assert phi[:12].mean() > 80 and phi[35:].mean() < 45
    w = np.array([t.cable.w for t in truths["S6"]])
    assert w[:12].mean() > 1.4 * w[35:].mean()


def test_s2_width_drops_near_frame_430(truths) -> None:
    w = np.array([t.cable.w for t in truths["S2"]])
    assert w[440:460].mean() < 0.8 * w[400:425].mean()


def test_s7_pipe_is_buried_for_consecutive_frames_with_partial_burial_around(truths) -> None:
    visible = np.array([t.visible_fraction for t in truths["S7"]])
    buried = np.flatnonzero(visible == 0.0)
    assert 15 <= buried.size <= 25
    assert np.all(np.diff(buried) == 1)
    before, after = visible[buried[0] - 10 : buried[0]], visible[buried[-1] + 1 : buried[-1] + 11]
    assert np.all((before > 0) & (before < 1)) and np.all((after > 0) & (after < 1))
    assert visible[0] == 1.0 and visible[-1] == 1.0


def test_other_sequences_are_not_buried(truths) -> None:
    for name in ("S1", "S3", "S5", "S6"):
        assert min(t.visible_fraction for t in truths[name]) == 1.0, name


def test_ripples_in_at_least_two_sequences_and_clutter_in_s1(camera) -> None:
    assert sum(bool(seq.spec.seabed.ripples) for seq in camera.values()) >= 2
    clutter = camera["S1"].spec.seabed.clutter
    assert clutter and clutter[0].rocks_per_m2 > 0 and clutter[0].algae_per_m2 > 0
    assert camera["S5"].spec.cable.albedo > camera["S5"].spec.seabed.albedo


def test_a_frame_renders(camera) -> None:
    frame = camera["S5"].frame(10)
    assert frame.observation.shape == (240, 320)
    # The bright cable: grey along the truth centreline exceeds the image median.
    state = frame.truth.cable
    column = round(159.5 + state.d / math.cos(state.alpha))
    assert np.median(frame.observation[110:130, column - 2 : column + 3]) > np.median(frame.observation) + 30


def test_s1_clutter_over_the_cable_is_dense_early_and_light_late(camera) -> None:
    seq = camera["S1"]
    spec, trajectory = seq.spec, seq.trajectory()
    assert spec.overgrowth and spec.seabed.clutter[0].density
    # The seabed at the image centre: the optical axis meets it this far ahead of the camera.
    centre = trajectory.cz + (trajectory.cy + spec.radius) / np.tan(trajectory.phi)
    early, late = centre[:80], centre[170 : spec.n_frames]
    for profile in (spec.overgrowth[0].density, spec.seabed.clutter[0].density):
        assert profile_factor(early, profile).min() >= 0.9
        assert profile_factor(late, profile).max() <= 0.3
    # The layer over the pipe itself follows the same profile.
    grid = TextureGrid(x0=-1.28, z0=-1.0, cell=0.01, nx=256, nz=1000)
    layer = overgrowth_layer(spec.overgrowth, grid, spec.radius, np.random.default_rng(0))
    band, _ = layer.pipe_band(spec.radius)
    z = grid.z_coords()
    cover = band[..., 0].mean(axis=1)
    dense = cover[(z > early.min()) & (z < early.max())].mean()
    light = cover[(z > late.min()) & (z < late.max())].mean()
    assert dense > 0.15 and light < 0.3 * dense


def test_the_extra_clutter_draws_differ_from_s1_only_in_their_seed(camera) -> None:
    import dataclasses

    for name in ("S1b", "S1c"):
        spec = camera[name].spec
        assert spec.seed != camera["S1"].spec.seed
        same = dataclasses.replace(spec, seed=camera["S1"].spec.seed, name=camera["S1"].spec.name, description=camera["S1"].spec.description)
        assert same == camera["S1"].spec
