"""Boards as a self-contained HTML page (``leaderboard.html``)."""

from __future__ import annotations

import html
from collections.abc import Mapping, Sequence

import pandas as pd

from benchmark.metrics import CORE, Metrics
from benchmark.report.display import display_table


def to_html(
    boards: Mapping[str, pd.DataFrame], caption: str = "", problems: Sequence[str] = (), metrics: Metrics = CORE
) -> str:
    """The boards as a self-contained HTML page, one section per modality, then a section listing ``problems``."""
    body = ["<h1>trackbench leaderboard</h1>"]
    if caption:
        body.append(f"<p>{html.escape(caption)}</p>")
    if not boards:
        body.append("<p>No results.</p>")
    for modality, board in boards.items():
        body.append(f"<h2>{html.escape(modality)}</h2>")
        body.append(display_table(board, metrics).to_html(index=False, escape=True, border=1))
    if problems:
        items = "".join(f"<li>{html.escape(problem)}</li>" for problem in problems)
        body += ["<h2>Problems</h2>", f"<ul>{items}</ul>"]
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        "<title>trackbench leaderboard</title>\n</head>\n<body>\n" + "\n".join(body) + "\n</body>\n</html>\n"
    )
