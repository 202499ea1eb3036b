"""Swaths with no returns, missing beams, spikes, a flat seabed or noise, made from a real ping."""

from __future__ import annotations

import numpy as np
import pytest

from benchmark.modalities.sonar.hard_observations import MISSING_SHARE, SPIKE_M, hard_observations
from benchmark.modalities.sonar.model import Swath
from benchmark.modalities.sonar.scenes.scene import SonarScene
from benchmark.model import Frame


@pytest.fixture(scope="module")
def ping() -> tuple[Frame, object]:
    scene = SonarScene.from_dict({"name": "hard", "n_frames": 1, "seed": 5}, "test")
    return next(iter(scene.frames())), scene.info


def made(ping: tuple[Frame, object], seed: int = 0) -> dict[str, Swath]:
    frame, info = ping
    return hard_observations(frame, info, np.random.default_rng(seed))


def test_every_kind_keeps_the_beam_count(ping: tuple[Frame, object]) -> None:
    swaths = made(ping)
    assert list(swaths) == ["no_returns", "nan_beams", "spikes", "flat", "noise"]
    n = ping[0].observation.across_m.size
    assert all(swath.across_m.shape == swath.depth_m.shape == (n,) for swath in swaths.values())


def test_missing_beams_are_missing_in_both_arrays(ping: tuple[Frame, object]) -> None:
    swaths = made(ping)
    original: Swath = ping[0].observation
    assert not swaths["no_returns"].valid.any()
    gone = ~swaths["nan_beams"].valid
    assert np.array_equal(np.isnan(swaths["nan_beams"].across_m), np.isnan(swaths["nan_beams"].depth_m))
    assert gone.sum() >= round(MISSING_SHARE * original.across_m.size) - (~original.valid).sum()
    kept = swaths["nan_beams"].valid
    assert np.array_equal(swaths["nan_beams"].depth_m[kept], original.depth_m[kept])


def test_spikes_flat_and_noise(ping: tuple[Frame, object]) -> None:
    swaths = made(ping)
    original: Swath = ping[0].observation
    valid = original.valid
    offsets = np.abs(swaths["spikes"].depth_m[valid] - original.depth_m[valid])
    assert set(np.round(offsets, 6)) <= {0.0, SPIKE_M} and (offsets == SPIKE_M).any()
    flat = swaths["flat"].depth_m[valid]
    assert np.ptp(flat) == 0.0 and flat[0] == np.median(original.depth_m[valid])
    noise = swaths["noise"].depth_m[valid]
    assert original.depth_m[valid].min() <= noise.min() and noise.max() <= original.depth_m[valid].max() + 1.0
    assert not np.array_equal(noise, original.depth_m[valid])


def test_a_ping_without_returns_still_gives_every_kind(ping: tuple[Frame, object]) -> None:
    frame, info = ping
    n = frame.observation.across_m.size
    empty = Frame(0, Swath(np.full(n, np.nan), np.full(n, np.nan)), None)
    swaths = hard_observations(empty, info, np.random.default_rng(0))
    assert len(swaths) == 5 and not any(swath.valid.any() for swath in swaths.values())
