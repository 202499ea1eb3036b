"""Boards by condition: bins of words and of numbers, frames pooled per tracker and bin, tables laid out to read."""

from __future__ import annotations

import pandas as pd
import pytest
from hypothesis import given
from hypothesis import strategies as st

from benchmark.by_condition import RANK_BINS, condition_bins, condition_board, condition_tables


def test_words_and_lists_get_one_bin_per_value() -> None:
    bins = condition_bins({"a": "9C", "b": "I", "c": "9C", "d": "III"})
    assert bins == {"a": (0, "9C"), "b": (1, "I"), "c": (0, "9C"), "d": (2, "III")}
    assert condition_bins({"a": [640, 480], "b": [320, 240]}) == {"a": (1, "640x480"), "b": (0, "320x240")}


def test_numbers_are_binned_by_rank_into_tenths_and_halves() -> None:
    values = {f"k{index:02d}": float(index) for index in range(48)}
    bins = condition_bins(values)
    sizes = [sum(1 for order, _ in bins.values() if order == position) for position in range(4)]
    assert sizes == [5, 19, 19, 5]
    assert bins["k00"] == (0, "lowest tenth (0-4)") and bins["k04"][0] == 0 and bins["k05"][0] == 1
    assert bins["k47"] == (3, "highest tenth (43-47)")


@given(st.lists(st.floats(-1e6, 1e6), min_size=1, max_size=60))
def test_every_sequence_gets_one_bin_and_bins_are_ordered_by_value(values: list[float]) -> None:
    named = {f"k{index:03d}": value for index, value in enumerate(values)}
    bins = condition_bins(named)
    assert set(bins) == set(named)
    assert all(label.startswith(RANK_BINS[order]) for order, label in bins.values())
    members = [[named[key] for key, (order, _) in bins.items() if order == position] for position in range(4)]
    filled = [values for values in members if values]
    assert all(max(lower) <= min(upper) for lower, upper in zip(filled, filled[1:]))
    assert sum(1 for order, _ in bins.values() if order == 0) == max(1, -(-len(values) // 10))


def cells_and_frames() -> tuple[pd.DataFrame, pd.DataFrame]:
    """Two trackers on three sequences: ``good`` is right everywhere, ``weak`` only on clear water."""
    cells, frames = [], []
    for number, (tracker, dataset) in enumerate(
        (t, d) for t in ("good", "weak") for d in ("world/A", "world/B", "world/C")
    ):
        cells.append(
            {"id": number, "tracker": tracker, "tracker_key": tracker, "dataset": dataset, "dataset_key": dataset,
             "modality": "camera", "seed": 0, "init": "truth", "status": "ok"}
        )
        right = tracker == "good" or dataset == "world/A"
        frames += [{"cell_id": number, "frame": k, "outcome": "correct" if right else "missed"} for k in range(4)]
    return pd.DataFrame(cells), pd.DataFrame(frames)


CONDITIONS = {
    "world/A": {"water": "I", "contrast_grey": 80.0},
    "world/B": {"water": "9C", "contrast_grey": 20.0},
    "world/C": {"water": "9C", "contrast_grey": 40.0},
}


def test_frames_are_pooled_per_tracker_condition_and_bin() -> None:
    cells, frames = cells_and_frames()
    board = condition_board(cells, frames, CONDITIONS).set_index(["condition", "bin", "tracker"])
    assert board.loc[("water", "I", "weak"), "correct_pct"] == 100.0
    assert board.loc[("water", "9C", "weak"), "correct_pct"] == 0.0
    assert board.loc[("water", "9C", "weak"), "missed_pct"] == 100.0
    assert board.loc[("water", "9C", "good"), ["sequences", "frames"]].tolist() == [2, 8]
    assert board.loc[("contrast_grey", "lowest tenth (20)", "weak"), "correct_pct"] == 0.0
    assert set(board.reset_index()["suite"]) == {"world"}


def test_datasets_without_conditions_are_left_out() -> None:
    cells, frames = cells_and_frames()
    board = condition_board(cells, frames, {"world/A": {"water": "I"}, "world/B": {}})
    assert set(board["bin"]) == {"I"} and set(board["sequences"]) == {1}
    assert condition_board(cells, frames, {}).empty


def test_tables_put_trackers_in_rows_and_bins_in_columns_best_first() -> None:
    cells, frames = cells_and_frames()
    tables = condition_tables(condition_board(cells, frames, CONDITIONS))
    water = tables[("camera", "world", "water")]
    assert water.columns.tolist() == ["tracker", "9C, 2 seq.", "I, 1 seq."]
    assert water["tracker"].tolist() == ["good", "weak"]
    assert water.iloc[1, 1:].tolist() == pytest.approx([0.0, 100.0])
    contrast = tables[("camera", "world", "contrast_grey")]
    assert [column.split(" (")[0] for column in contrast.columns[1:]] == ["lowest tenth", "50-90 %", "highest tenth"]
