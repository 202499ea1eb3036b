"""A tiny image folder to label, and the labeller served from a thread."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import cv2
import numpy as np
import pytest
import uvicorn

from benchmark.modalities.camera.labeller.app import bind, create_app, new_token
from benchmark.modalities.camera.labeller.document import LabelDocument

N_FRAMES = 6
SIZE = (64, 48)


@pytest.fixture
def image_folder(tmp_path: Path) -> Path:
    """``tmp_path/frames``: six 64x48 grey PNG frames, each with its own brightness and a dark stripe."""
    folder = tmp_path / "frames"
    folder.mkdir()
    width, height = SIZE
    for index in range(N_FRAMES):
        image = np.full((height, width), 60 + 30 * index, np.uint8)
        image[:, 20 + index : 28 + index] = 10
        cv2.imwrite(str(folder / f"frame{index}.png"), image)
    return folder


@contextmanager
def served(document: LabelDocument) -> Iterator[str]:
    """The labeller of ``document`` served by uvicorn in a thread on a free port; yields the page's URL."""
    token = new_token()
    listening = bind(0)
    server = uvicorn.Server(uvicorn.Config(create_app(document, token), log_level="warning"))
    thread = threading.Thread(target=server.run, kwargs={"sockets": [listening]}, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{listening.getsockname()[1]}/{token}/"
    finally:
        server.should_exit = True
        thread.join()
        listening.close()
