"""Subjects made ready: frames read once, a learning tracker fitted as a run fits it and its model kept."""

from __future__ import annotations

from pathlib import Path

import pytest

from benchmark.selection import SelectionError
from benchmark.speed.subjects import MODELS, TrackerWorkload, prepare_subject

from ..conftest import FakeSequence, make_registry
from .fakes import LEARNING_PLUGIN, PLUGIN, Fast, Learner, Slow, bounds_of


def registry_with_training():  # type: ignore[no-untyped-def]
    registry = make_registry((Fast, Slow, Learner))
    registry.add_suite("learning-train", [FakeSequence("learning-train/S1", 3)], scored=False)
    registry.add_suite("learning", [FakeSequence("learning/S1", 5)], training="learning-train")
    return registry


def test_a_subject_holds_the_first_frames_of_its_dataset(tmp_path: Path) -> None:
    subject = prepare_subject(registry_with_training(), bounds_of(), "slow", 4, tmp_path)
    assert [frame.index for frame in subject.frames] == [0, 1, 2, 3]
    assert subject.init == subject.frames[0].truth and subject.info.name == "fake/S1"
    assert isinstance(subject.ours(subject.context), TrackerWorkload) and subject.context.model is None


def test_a_learning_tracker_is_fitted_once_and_its_model_kept_in_the_cache(tmp_path: Path) -> None:
    before = Learner.fits
    first = prepare_subject(registry_with_training(), bounds_of(PLUGIN, LEARNING_PLUGIN), "learner", 2, tmp_path)
    again = prepare_subject(registry_with_training(), bounds_of(PLUGIN, LEARNING_PLUGIN), "learner", 2, tmp_path)
    assert Learner.fits == before + 1
    assert first.context.model == again.context.model == pytest.approx(40 + 1)  # frames 0-2 of grey 40 + index
    assert len(list((tmp_path / MODELS).glob("*.model"))) == 1
    workload = first.ours(first.context)
    workload.reset(first.info, None, first.init)  # type: ignore[arg-type]
    assert workload.tracker.model == first.context.model


def test_a_learning_tracker_without_a_training_set_is_an_error(tmp_path: Path) -> None:
    registry = make_registry((Fast, Slow, Learner))
    registry.add_suite("learning", [FakeSequence("learning/S1", 5)])
    with pytest.raises(SelectionError, match="cannot train 'learner' for learning/S1"):
        prepare_subject(registry, bounds_of(PLUGIN, LEARNING_PLUGIN), "learner", 2, tmp_path)
