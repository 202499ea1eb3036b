"""Boards as text: values rounded for reading, columns aligned by type.

Boards keep full precision (and CSV exports them so); the Markdown, HTML and
terminal forms round percentages to 0.1, RMSEs to 0.01 and fps to 1 (and
the tables of ``trackbench pose-table``: metres to 0.01, degrees to 0.1,
pixels to 1, variances to three digits).
"""

from __future__ import annotations

import math

import pandas as pd


def one_line(text: object) -> str:
    """``text`` on one line: every run of whitespace, newlines included, becomes one space."""
    return " ".join(str(text).split())


def format_value(column: str, value: object) -> str:
    """A value as shown: percentages and degrees to 0.1, RMSEs and metres to 0.01, pixels to 1, variances as e-03."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    if column.endswith("_pct"):
        return f"{value:.1f}"
    if column.startswith("rmse_") or column.endswith("_m"):
        return f"{value:.2f}"
    if column.startswith("var_"):
        return f"{value:.2e}"
    if column.endswith("_deg"):
        return f"{value:.1f}"
    if column == "fps" or column.endswith("_px"):
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
