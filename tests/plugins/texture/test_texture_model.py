"""Tests of learning the texture model from labelled sequences."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
from trackbench_texture.model import TextureModel, train
from trackbench_texture.params import TextureParams
from trackbench_texture.tracker import TextureTracker

from benchmark import storage
from benchmark.errors import DataError
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CameraTruth
from benchmark.model import Frame


PACKAGES = storage.packages_of(TextureTracker)


def _params(drawn) -> TextureParams:
    return TextureParams(**drawn.FAST)


def _probe(drawn) -> np.ndarray:
    """A drawn image no model learned from, to compare models by their outputs."""
    state = drawn.random_states(np.random.default_rng(11), 1)[0]
    return drawn.cable_image(state, "sand", seed=999)


def test_the_same_seed_gives_the_same_model_bit_for_bit(drawn):
    image = _probe(drawn)
    outputs = []
    for seed in (7, 7, 8):
        model = train(drawn.training_set(), _params(drawn), np.random.default_rng(seed))
        kinds, regions = model.analyse(image)
        probabilities = model.regions.probabilities(np.random.default_rng(0).random((500, 5)))
        outputs.append((regions, probabilities))
    assert np.array_equal(outputs[0][0], outputs[1][0])
    assert np.array_equal(outputs[0][1], outputs[1][1])
    # Another seed draws other frames and pixels, so the model differs.
    assert not np.array_equal(outputs[0][1], outputs[2][1])


@pytest.mark.parametrize(
    "round_trip",
    [
        lambda model: pickle.loads(pickle.dumps(model)),  # to a worker process
        lambda model: storage.loads(storage.dumps(model, PACKAGES), PACKAGES, "model"),  # to and from disk
    ],
    ids=["pickle", "storage"],
)
def test_the_model_round_trips_and_classifies_alike(trained, drawn, round_trip):
    model = trained.model
    copy = round_trip(model)
    assert isinstance(copy, TextureModel)
    image = _probe(drawn)
    assert np.array_equal(copy.analyse(image)[1], model.analyse(image)[1])
    assert copy.training == model.training and copy.n_frames == model.n_frames
    assert copy.descriptors == model.descriptors and copy.regions.regions == model.regions.regions


def test_the_model_records_what_it_learned_from(trained):
    assert trained.model.training == ("drawn/sand-0", "drawn/blank-1", "drawn/sand-2")
    assert trained.model.n_frames == 3 * 4


def test_unlabelled_frames_are_skipped(drawn):
    image = drawn.cable_image(drawn.random_states(np.random.default_rng(0), 1)[0])
    unlabelled = drawn.DrawnSequence(
        "drawn/unlabelled", [Frame(0, image), Frame(1, image, CameraTruth(UNKNOWN_CABLE))]
    )
    model = train([unlabelled, *drawn.training_set()], _params(drawn), np.random.default_rng(0))
    assert model.n_frames == 3 * 4


@pytest.mark.parametrize("contents", ["no truth", "unknown cable", "no sequence"])
def test_a_set_without_labelled_frames_cannot_teach(drawn, contents):
    image = drawn.cable_image(drawn.random_states(np.random.default_rng(0), 1)[0])
    if contents == "no sequence":
        training = []
    else:
        truth = None if contents == "no truth" else CameraTruth(UNKNOWN_CABLE)
        training = [drawn.DrawnSequence("drawn/empty", [Frame(k, image, truth) for k in range(3)])]
    with pytest.raises(DataError, match="no labelled frame"):
        train(training, _params(drawn), np.random.default_rng(0))


def test_a_bad_training_image_is_a_data_error_naming_sequence_and_frame(drawn):
    good = drawn.training_set()[0]
    frames = list(good.frames())
    frames[2] = Frame(2, frames[2].observation.astype(np.float64), frames[2].truth)
    bad = drawn.DrawnSequence("drawn/bad", frames)
    params = TextureParams(**{**drawn.FAST, "frames_per_sequence": 10})
    with pytest.raises(DataError, match=r"'drawn/bad', frame 2: .*float64"):
        train([bad], params, np.random.default_rng(0))


@pytest.mark.parametrize("rounds", [3, 10])
def test_the_classifier_boosts_as_many_rounds_as_asked(drawn, rounds):
    params = TextureParams(**{**drawn.FAST, "boosting_rounds": rounds})
    model = train(drawn.training_set(), params, np.random.default_rng(0))
    trees_per_round = 1 if len(model.regions.regions) == 2 else len(model.regions.regions)
    assert model.regions.forest.leaf_values.shape[0] == rounds * trees_per_round
