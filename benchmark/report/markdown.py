"""Boards as Markdown: a page for ``leaderboard.md``, and the same tables for a terminal."""

from __future__ import annotations

from collections.abc import Mapping

import pandas as pd

from benchmark.report.display import alignment, display_table


def _shorten(text: str, width: int) -> str:
    return text if len(text) <= width else text[: width - 3] + "..."


def to_text(boards: Mapping[str, pd.DataFrame], status_width: int = 60) -> str:
    """The boards for a terminal, one block per modality, long statuses shortened."""
    if not boards:
        return "No results."
    blocks = []
    for modality, board in boards.items():
        shown = display_table(board)
        shown["status"] = [_shorten(text, status_width) for text in shown["status"]]
        table = shown.to_markdown(index=False, tablefmt="simple", disable_numparse=True, colalign=alignment(board))
        blocks.append(f"{modality}\n\n{table}")
    return "\n\n".join(blocks)


def to_markdown(boards: Mapping[str, pd.DataFrame], caption: str = "") -> str:
    """The boards as a Markdown page, one section per modality."""
    parts = ["# trackbench leaderboard", ""]
    if caption:
        parts += [caption, ""]
    if not boards:
        parts += ["No results.", ""]
    for modality, board in boards.items():
        shown = display_table(board).map(lambda text: text.replace("|", "\\|"))
        table = shown.to_markdown(index=False, disable_numparse=True, colalign=alignment(board))
        parts += [f"## {modality}", "", table, ""]
    return "\n".join(parts)
