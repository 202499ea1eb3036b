import math

import pandas as pd
import pytest

from benchmark.report.grid import grid_markdown, grid_tables, split_grid_name


def board() -> pd.DataFrame:
    rows = []
    for tracker, scale in (("ekf", 1.0), ("raw", 3.0)):
        rows.append({"tracker": tracker, "dataset": "(all)", "rmse_position_m": 99.0, "rmse_speed_mps": 99.0})
        for case in ("case1", "case2"):
            for offset, speed in enumerate(("slow", "medium", "fast")):
                rows.append(
                    {
                        "tracker": tracker,
                        "dataset": f"stereo/{case}-{speed}",
                        "rmse_position_m": scale * (1 + offset),
                        "rmse_speed_mps": scale * 10 + offset,
                    }
                )
    return pd.DataFrame(rows).iloc[::-1]  # order of rows must not matter


def test_split_grid_name():
    assert split_grid_name("stereo/case1-slow") == ("case1", "slow")
    assert split_grid_name("stereo/case-1-slow") == ("case-1", "slow")
    assert split_grid_name("camera/S1") is None
    assert split_grid_name("x/-slow") is None


def test_one_table_per_case_with_metric_and_tracker_rows_and_ordered_columns():
    order = [f"stereo/{case}-{speed}" for case in ("case1", "case2") for speed in ("slow", "medium", "fast")]
    tables = grid_tables(board(), ["rmse_position_m", "rmse_speed_mps"], order)
    assert list(tables) == ["case1", "case2"]
    table = tables["case2"]
    assert list(table.columns) == ["slow", "medium", "fast"]
    # metrics in the order asked, trackers in the board's order
    assert list(table.index) == ["rmse_position_m raw", "rmse_position_m ekf", "rmse_speed_mps raw", "rmse_speed_mps ekf"]
    assert table.loc["rmse_position_m ekf", "fast"] == 3.0
    assert table.loc["rmse_position_m raw", "slow"] == 3.0
    assert table.loc["rmse_speed_mps raw", "medium"] == 31.0


def test_the_pooled_row_is_left_out_and_missing_cells_stay_empty():
    partial = board()
    partial = partial[~((partial.tracker == "raw") & (partial.dataset == "stereo/case1-fast"))]
    table = grid_tables(partial, ["rmse_position_m"])["case1"]
    assert math.isnan(table.loc["rmse_position_m raw", "fast"])
    assert 99.0 not in table.to_numpy()


def test_markdown_has_a_section_per_case():
    text = grid_markdown(grid_tables(board(), ["rmse_position_m"]), "stereo: results per case")
    assert text.startswith("# stereo: results per case")
    assert "## case1" in text and "## case2" in text and "3.00" in text


@pytest.mark.parametrize("name", ["fake/S1", "plain"])
def test_datasets_without_a_case_are_ignored(name):
    rows = pd.DataFrame([{"tracker": "t", "dataset": name, "rmse_position_m": 1.0}])
    assert grid_tables(rows, ["rmse_position_m"]) == {}
