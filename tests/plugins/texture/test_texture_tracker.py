"""Tests of the texture tracker on drawn cable images (seeds/000, section 2.2)."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
from trackbench_texture.tracker import TextureTracker

from benchmark.errors import DataError
from benchmark.modalities.camera.geometry import cable_borders, score_line_pair
from benchmark.modalities.camera.model import CableState
from benchmark.model import Frame, Outcome, SequenceInfo
from benchmark.tracker import Learns

INFO = SequenceInfo("drawn", "camera", frame_size=(160, 120))


def _outcome(estimate: CableState | None, truth: CableState, size: tuple[int, int]) -> Outcome:
    return score_line_pair(None if estimate is None else cable_borders(estimate), cable_borders(truth), size)


def _run(tracker: TextureTracker, images: list[np.ndarray], seed: int = 0) -> list[CableState | None]:
    tracker.reset(INFO, np.random.default_rng(seed))
    return [tracker.step(Frame(k, image)) for k, image in enumerate(images)]


def test_the_tracker_learns_and_says_so():
    tracker = TextureTracker()
    assert isinstance(tracker, Learns)
    assert (tracker.name, tracker.modality) == ("texture", "camera")


@pytest.mark.parametrize("kind", ["sand", "blank"])
def test_finds_a_drawn_cable_after_fitting(trained, drawn, kind):
    states = drawn.random_states(np.random.default_rng(2024), 10)
    images = [drawn.cable_image(state, kind, seed=300 + k) for k, state in enumerate(states)]
    estimates = _run(trained, images)
    outcomes = [_outcome(estimate, state, drawn.SIZE) for estimate, state in zip(estimates, states)]
    # Where sand relief crosses a border its straight pieces break up, and a
    # border seen on too few rows is not reported: a miss, never a false pair.
    assert outcomes.count(Outcome.CORRECT) >= 8, outcomes
    assert Outcome.FALSE not in outcomes, outcomes


def test_finds_the_same_scene_in_a_frame_of_twice_the_size(trained, drawn):
    # Sizes are shares of the working height: a model learned on 160 x 120
    # frames finds the cable in 320 x 240 frames of the same scenes.  (Blank
    # ground: a seabed's grain is per pixel, and shrinking a frame smooths it.)
    size = (320, 240)
    states = drawn.random_states(np.random.default_rng(77), 6)
    doubled = [CableState(2.0 * s.d, s.alpha, 2.0 * s.w, s.beta) for s in states]
    images = [drawn.cable_image(s, "blank", size=size) for s in doubled]
    trained.reset(SequenceInfo("drawn-large", "camera", frame_size=size), np.random.default_rng(0))
    estimates = [trained.step(Frame(k, image)) for k, image in enumerate(images)]
    outcomes = [_outcome(estimate, state, size) for estimate, state in zip(estimates, doubled)]
    assert outcomes.count(Outcome.CORRECT) >= 5, outcomes


def test_finds_a_bright_cable_and_a_colour_image(trained, drawn):
    state = drawn.random_states(np.random.default_rng(5), 1)[0]
    bright = drawn.cable_image(state, "sand", contrast=60.0, seed=4)
    colour = np.repeat(drawn.cable_image(state, "sand", seed=4)[:, :, None], 3, axis=2)
    for image in (bright, colour):
        assert _outcome(_run(trained, [image])[0], state, drawn.SIZE) is Outcome.CORRECT


def test_reports_nothing_on_blank_or_noise_images(trained, drawn):
    rng = np.random.default_rng(0)
    blank = np.full((120, 160), 140, np.uint8)
    noise = rng.integers(0, 256, (120, 160), dtype=np.uint8)
    sand = np.clip(drawn.ground("sand", seed=3), 0, 255).astype(np.uint8)
    assert _run(trained, [blank, noise, sand]) == [None, None, None]


def test_a_pickled_model_gives_identical_results(trained, drawn):
    states = drawn.random_states(np.random.default_rng(77), 4)
    images = [drawn.cable_image(state, "sand", seed=50 + k) for k, state in enumerate(states)]
    fresh = TextureTracker(trained.params)
    fresh.use_model(pickle.loads(pickle.dumps(trained.model)))
    assert _run(fresh, images, seed=3) == _run(trained, images, seed=3)
    assert any(estimate is not None for estimate in _run(fresh, images, seed=3))


def test_fit_adopts_and_returns_its_model(drawn):
    tracker = TextureTracker(TextureTracker.make_params(drawn.FAST))
    model = tracker.fit(drawn.training_set()[:1], np.random.default_rng(0))
    assert tracker.model is model


def test_no_model_is_a_clear_error(drawn):
    tracker = TextureTracker()
    with pytest.raises(RuntimeError, match="no model"):
        tracker.reset(INFO, np.random.default_rng(0))
    with pytest.raises(RuntimeError, match="no model"):
        tracker.step(Frame(0, np.zeros((120, 160), np.uint8)))


def test_step_before_reset_is_a_clear_error(trained):
    tracker = TextureTracker(trained.params)
    tracker.use_model(trained.model)
    with pytest.raises(RuntimeError, match="reset"):
        tracker.step(Frame(0, np.zeros((120, 160), np.uint8)))


def test_use_model_refuses_anything_but_a_texture_model():
    with pytest.raises(TypeError, match="TextureModel"):
        TextureTracker().use_model({"not": "a model"})


@pytest.mark.parametrize(
    "image",
    [
        np.full((120, 160), np.nan),
        np.zeros((120, 160), np.float32),
        np.zeros(160, np.uint8),
        np.zeros((0, 160), np.uint8),
        np.zeros((120, 160, 2), np.uint8),
    ],
    ids=["nan", "float", "1-D", "empty", "two channels"],
)
def test_a_bad_image_is_a_data_error_naming_the_frame(trained, image):
    trained.reset(INFO, np.random.default_rng(0))
    with pytest.raises(DataError, match=r"^texture: frame 42: "):
        trained.step(Frame(42, image))
