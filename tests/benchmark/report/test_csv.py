"""Tests of benchmark.report.csv: every board in one table at full precision."""

from __future__ import annotations

import io

import numpy as np
import pandas as pd

from benchmark.report.csv import to_csv


def test_csv_keeps_full_precision(boards: dict[str, pd.DataFrame]) -> None:
    board = boards["camera"]
    back = pd.read_csv(io.StringIO(to_csv(boards)))
    assert back["modality"].tolist() == ["camera", "camera"]
    np.testing.assert_allclose(back["correct_pct"], board["correct_pct"])
    np.testing.assert_allclose(back["rmse_d_px"], board["rmse_d_px"])


def test_boards_of_several_modalities_share_one_table_with_the_modality_first() -> None:
    camera = pd.DataFrame({"rank": [1], "tracker": ["a"], "rmse_d_px": [1.5]})
    sonar = pd.DataFrame({"rank": [1], "tracker": ["b"], "rmse_across_m": [0.25]})
    back = pd.read_csv(io.StringIO(to_csv({"camera": camera, "sonar": sonar})))
    assert back.columns.tolist() == ["modality", "rank", "tracker", "rmse_d_px", "rmse_across_m"]
    assert back["modality"].tolist() == ["camera", "sonar"]
    assert back["rmse_across_m"].isna().tolist() == [True, False]
    assert to_csv({}) == "modality\n"
