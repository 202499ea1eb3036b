"""Video files: frames streamed from OpenCV, in grey, without ground truth."""

from __future__ import annotations

import pickle
from pathlib import Path

import cv2
import numpy as np
import pytest

from benchmark.errors import DataError
from benchmark.modalities.camera.io.video import VideoFile, grey_frame, grey_image, to_grey

LEVELS = [20, 60, 100, 140, 180, 220]


def _write_video(path: Path, fourcc: str = "MJPG", fps: float = 10.0, size: tuple[int, int] = (40, 32)) -> None:
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*fourcc), fps, size, True)
    if not writer.isOpened():
        pytest.skip(f"this OpenCV build cannot write {fourcc} into {path.suffix}")
    for level in LEVELS:
        writer.write(np.full((size[1], size[0], 3), level, dtype=np.uint8))
    writer.release()


def test_video_frames_are_grey_and_timed(tmp_path):
    path = tmp_path / "clip.avi"
    _write_video(path)
    video = VideoFile(path)
    info = video.info
    assert info.name == str(path)
    assert info.modality == "camera"
    assert info.n_frames == len(LEVELS)
    assert info.frame_size == (40, 32)
    assert info.frame_interval_s == pytest.approx(0.1)
    frames = list(video.frames())
    assert [f.index for f in frames] == list(range(len(LEVELS)))
    assert [f.time_s for f in frames] == pytest.approx([0.1 * i for i in range(len(LEVELS))])
    for frame, level in zip(frames, LEVELS, strict=True):
        assert frame.observation.dtype == np.uint8
        assert frame.observation.shape == (32, 40)
        assert abs(float(frame.observation.mean()) - level) < 4
        assert not frame.truth.cable.is_known


def test_video_pickles_and_replays(tmp_path):
    path = tmp_path / "clip.avi"
    _write_video(path)
    video = VideoFile(path)
    copy = pickle.loads(pickle.dumps(video))
    first = [f.observation for f in video.frames()]
    again = [f.observation for f in copy.frames()]
    assert len(first) == len(again) == len(LEVELS)
    assert all(np.array_equal(a, b) for a, b in zip(first, again, strict=True))


def test_unreadable_video_is_named(tmp_path):
    bad = tmp_path / "broken clip.avi"
    bad.write_bytes(b"this is no video" * 64)
    with pytest.raises(DataError, match="broken clip.avi"):
        VideoFile(bad)


def test_missing_video_is_named(tmp_path):
    with pytest.raises(DataError, match="gone.mp4"):
        VideoFile(tmp_path / "gone.mp4")


def test_to_grey_accepts_grey_bgr_and_bgra():
    grey = np.arange(12, dtype=np.uint8).reshape(3, 4) * 20
    assert np.array_equal(to_grey(grey), grey)
    assert np.array_equal(to_grey(np.dstack([grey] * 3)), grey)
    assert np.array_equal(to_grey(np.dstack([grey] * 3 + [np.full_like(grey, 255)])), grey)
    blue = np.zeros((2, 2, 3), dtype=np.uint8)
    blue[..., 0] = 255
    red = np.zeros((2, 2, 3), dtype=np.uint8)
    red[..., 2] = 255
    assert to_grey(red)[0, 0] > to_grey(blue)[0, 0]


@pytest.mark.parametrize(
    ("observation", "message"),
    [
        (np.full((4, 4), np.nan), "NaN"),
        (np.zeros((4, 4), np.float32), "float32"),
        (np.zeros((4, 4, 2), np.uint8), r"shape \(4, 4, 2\)"),
        (np.zeros((0, 4), np.uint8), r"shape \(0, 4\) is smaller than 1 px"),
        ([[1, 2]], "list"),
    ],
)
def test_grey_image_names_what_it_cannot_read(observation: object, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        grey_image(observation)


def test_grey_image_passes_grey_through_and_converts_colour_and_16_bit() -> None:
    grey = np.arange(12, dtype=np.uint8).reshape(3, 4)
    assert grey_image(grey) is grey
    assert np.array_equal(grey_image(np.repeat(grey[:, :, None], 3, axis=2)), grey)
    assert np.array_equal(grey_image(grey.astype(np.uint16) * 257), grey)
    with pytest.raises(ValueError, match="smaller than 5 px"):
        grey_image(grey, min_size_px=5)


def test_grey_frame_accepts_grey_colour_and_16_bit_images() -> None:
    grey = np.arange(12, dtype=np.uint8).reshape(3, 4)
    assert np.array_equal(grey_frame(grey, "here"), grey)
    colour = np.repeat(grey[:, :, None], 3, axis=2)
    assert np.array_equal(grey_frame(colour, "here"), grey)
    assert grey_frame((grey.astype(np.uint16) * 257), "here").dtype == np.uint8


@pytest.mark.parametrize(
    ("image", "detail"),
    [
        (np.full((4, 4), np.nan), "NaN"),
        (np.zeros((4, 4), np.float32), "float32"),
        (np.zeros(16, np.uint8), "shape (16,)"),
        (np.zeros((0, 4), np.uint8), "shape (0, 4)"),
        (np.zeros((4, 4, 2), np.uint8), "shape (4, 4, 2)"),
        (np.zeros((4, 4), bool), "bool"),
        ("not an image", "str"),
    ],
)
def test_grey_frame_makes_anything_else_a_data_error_naming_where(image: object, detail: str) -> None:
    with pytest.raises(DataError) as error:
        grey_frame(image, "texture: frame 5")
    assert str(error.value).startswith("texture: frame 5: ")
    assert detail in str(error.value)
