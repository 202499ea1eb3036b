"""Reports built from leaderboards: the files a run publishes, and views laid out as the papers lay theirs.

:func:`write_leaderboards` writes a run's boards (:mod:`benchmark.leaderboard`)
as ``leaderboard.csv`` (:mod:`~benchmark.report.csv`, full precision),
``leaderboard.md`` (:mod:`~benchmark.report.markdown`) and
``leaderboard.html`` (:mod:`~benchmark.report.html`), the last two rounded
for reading (:mod:`~benchmark.report.display`).  :func:`write_condition_board` writes the boards by condition
(:mod:`benchmark.by_condition`) as ``conditions.csv`` and ``conditions.md``.
:mod:`~benchmark.report.grid` lays a suite out per case and condition, as
seeds/002 does in its Tables 6-8.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import pandas as pd

from benchmark.metrics import CORE, Metrics
from benchmark.files import make_folder, write_text_atomically
from benchmark.report.csv import to_csv
from benchmark.report.html import to_html
from benchmark.report.markdown import condition_markdown, to_markdown, to_text

FILE_NAMES = {"csv": "leaderboard.csv", "markdown": "leaderboard.md", "html": "leaderboard.html"}
"""The file each form of the boards is written to."""

CONDITION_FILE_NAMES = {"csv": "conditions.csv", "markdown": "conditions.md"}
"""The file each form of the boards by condition is written to."""


def write_leaderboards(
    boards: Mapping[str, pd.DataFrame],
    out_dir: str | Path,
    caption: str = "",
    problems: Sequence[str] = (),
    metrics: Metrics = CORE,
) -> list[Path]:
    """Write ``leaderboard.csv``, ``leaderboard.md`` and ``leaderboard.html`` into ``out_dir``.

    Each file is written under a temporary name and renamed into place
    (:func:`benchmark.files.write_text_atomically`), so that a reader sees
    the old board or the new one, never half of one.

    Parameters
    ----------
    boards : Mapping
        Board name (a modality, or a suite's closed-loop board) to board
        (:func:`benchmark.leaderboard.leaderboards`).
    out_dir : str or pathlib.Path
        The folder, created if missing.
    caption : str
        A line shown under the title of the Markdown and HTML pages.
    problems : sequence of str
        Run-level problems (a plugin that failed to import), listed in a
        section of the Markdown and HTML pages; the CSV holds the boards only.
    metrics : Metrics
        The catalogue of metrics, which rounds each for reading.

    Returns
    -------
    list of pathlib.Path
        The files written, in that order.

    Raises
    ------
    DataError
        If a file cannot be written, naming it.
    """
    out = make_folder(out_dir)
    contents = {
        "csv": to_csv(boards),
        "markdown": to_markdown(boards, caption, problems, metrics),
        "html": to_html(boards, caption, problems, metrics),
    }
    return [write_text_atomically(out / FILE_NAMES[kind], text, "leaderboard") for kind, text in contents.items()]


def write_condition_board(board: pd.DataFrame, out_dir: str | Path, caption: str = "") -> list[Path]:
    """Write ``conditions.csv`` (full precision) and ``conditions.md`` into ``out_dir``; nothing for an empty board.

    Parameters
    ----------
    board : pandas.DataFrame
        As :func:`benchmark.by_condition.condition_board` returns it.
    out_dir : str or pathlib.Path
        The folder, created if missing.
    caption : str
        A line shown under the page's title.

    Returns
    -------
    list of pathlib.Path
        The files written; stale files of an earlier run are removed when
        this run has no conditions, so the folder never shows another run's.
    """
    from benchmark.by_condition import condition_tables

    out = make_folder(out_dir)
    if board.empty:
        for name in CONDITION_FILE_NAMES.values():
            (out / name).unlink(missing_ok=True)
        return []
    contents = {
        "csv": board.drop(columns="order").to_csv(index=False),
        "markdown": condition_markdown(condition_tables(board), caption),
    }
    return [
        write_text_atomically(out / CONDITION_FILE_NAMES[kind], text, "board by condition")
        for kind, text in contents.items()
    ]


__all__ = ["CONDITION_FILE_NAMES", "FILE_NAMES", "write_condition_board", "to_csv", "to_html", "to_markdown", "to_text", "write_leaderboards"]
