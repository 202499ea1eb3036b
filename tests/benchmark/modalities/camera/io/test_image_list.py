"""The list-of-images sequence behind sequence files and image folders."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from benchmark.modalities.camera.io.image_list import ImageListSequence, check_frame_interval
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState


def test_image_and_state_counts_must_match(tmp_path):
    with pytest.raises(ValueError, match="2 images but 1"):
        ImageListSequence("s", tmp_path, [tmp_path / "a.png", tmp_path / "b.png"], [UNKNOWN_CABLE])


@pytest.mark.parametrize("bad", [0.0, -0.04, math.nan, math.inf])
def test_frame_interval_must_be_positive_and_finite(bad):
    with pytest.raises(ValueError, match="frame_interval_s"):
        check_frame_interval(bad)
    assert check_frame_interval(None) is None
    assert check_frame_interval(0.04) == 0.04


def test_repr_and_len_do_not_touch_images(tmp_path):
    missing = [Path(tmp_path / "x.png"), Path(tmp_path / "y.png")]
    sequence = ImageListSequence("suite/s", tmp_path, missing, [CableState(1, 0, 2, 0)] * 2)
    assert repr(sequence) == "<ImageListSequence 'suite/s'>"
    assert len(sequence) == 2


def test_frames_take_the_states_in_order(tmp_path, make_image):
    paths = [tmp_path / f"{i}.png" for i in range(3)]
    for path in paths:
        make_image(path)
    states = [CableState(float(i), 0.0, 5.0, 0.0) for i in range(3)]
    sequence = ImageListSequence("s", tmp_path, paths, states, frame_interval_s=2.0)
    frames = list(sequence.frames())
    assert [f.truth.cable for f in frames] == states
    assert [f.time_s for f in frames] == [0.0, 2.0, 4.0]
    assert sequence.info.extra == {"source": str(tmp_path)}
