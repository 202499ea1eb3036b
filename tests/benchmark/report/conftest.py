"""A small camera board, ranked by benchmark.leaderboard, for the writer tests."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from benchmark.leaderboard import leaderboards
from benchmark.modalities.camera.modality import CAMERA


@pytest.fixture
def boards() -> dict[str, pd.DataFrame]:
    """Tracker ``a`` on ``s/1``: correct, correct, false, d errors 1, 2, 3 px, 3 ms a step; beta never known."""
    cells = pd.DataFrame(
        [
            {
                "id": 1,
                "tracker": "a",
                "tracker_key": "key-a",
                "dataset": "s/1",
                "dataset_key": "data-s/1",
                "modality": "camera",
                "seed": 0,
                "init": "truth",
                "status": "ok",
                "message": "",
            }
        ]
    )
    frames = pd.DataFrame(
        [
            {
                "cell_id": 1,
                "frame": index,
                "outcome": outcome,
                "step_ms": 3.0,
                "wall_ms": 3.0,
                "err_d_px": d_error,
                "err_alpha_deg": d_error / 10,
                "err_w_px": 0.0,
                "err_beta_deg": math.nan,
            }
            for index, (outcome, d_error) in enumerate(zip(["correct", "correct", "false"], [1.0, 2.0, 3.0]))
        ]
    )
    return leaderboards(cells, frames, {"camera": CAMERA})
