"""Boards as one CSV table at full precision (``leaderboard.csv``), the form other tools compare."""

from __future__ import annotations

from collections.abc import Mapping

import pandas as pd


def to_csv(boards: Mapping[str, pd.DataFrame]) -> str:
    """All boards in one CSV table at full precision, with a ``modality`` column first.

    That column holds the board's name: its modality, or ``SUITE (closed
    loop)`` for a suite's closed-loop board (:data:`benchmark.leaderboard.LAYOUTS`).
    """
    if not boards:
        return "modality\n"
    tables = [board.assign(modality=modality) for modality, board in boards.items()]
    combined = pd.concat(tables, ignore_index=True)
    ordered = ["modality", *[column for column in combined.columns if column != "modality"]]
    return combined[ordered].to_csv(index=False)
