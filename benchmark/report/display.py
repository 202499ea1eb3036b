"""Boards as text: values rounded for reading, columns aligned by type.

Boards keep full precision (and CSV exports them so); the Markdown, HTML and
terminal forms round percentages to 0.1, RMSEs to 0.01 and fps to 1.
"""

from __future__ import annotations

import math

import pandas as pd


def one_line(text: object) -> str:
    """``text`` on one line: every run of whitespace, newlines included, becomes one space."""
    return " ".join(str(text).split())


def format_value(column: str, value: object) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    if column.endswith("_pct"):
        return f"{value:.1f}"
    if column.startswith("rmse_"):
        return f"{value:.2f}"
    if column == "fps":
        return f"{value:.0f}"
    return str(value)


def display_table(board: pd.DataFrame) -> pd.DataFrame:
    """The board as rounded text, for Markdown, HTML and the terminal."""
    return pd.DataFrame(
        {column: [format_value(column, value) for value in board[column].tolist()] for column in board.columns},
        columns=board.columns,
        dtype=object,
    )


def alignment(board: pd.DataFrame) -> list[str]:
    """``"right"`` for numeric columns, ``"left"`` for the others."""
    return ["right" if pd.api.types.is_numeric_dtype(board[column]) else "left" for column in board.columns]
