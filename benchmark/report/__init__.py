"""Reports built from leaderboards: the files a run publishes, and views laid out as the papers lay theirs.

:func:`write_leaderboards` writes a run's boards (:mod:`benchmark.leaderboard`)
as ``leaderboard.csv`` (:mod:`~benchmark.report.csv`, full precision),
``leaderboard.md`` (:mod:`~benchmark.report.markdown`) and
``leaderboard.html`` (:mod:`~benchmark.report.html`), the last two rounded
for reading (:mod:`~benchmark.report.display`).  :mod:`~benchmark.report.grid`
lays a suite out per case and condition, as seeds/002 does in its Tables 6-8.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import pandas as pd

from benchmark.report.csv import to_csv
from benchmark.report.html import to_html
from benchmark.report.markdown import to_markdown, to_text

FILE_NAMES = {"csv": "leaderboard.csv", "markdown": "leaderboard.md", "html": "leaderboard.html"}
"""The file each form of the boards is written to."""


def write_leaderboards(boards: Mapping[str, pd.DataFrame], out_dir: str | Path, caption: str = "") -> list[Path]:
    """Write ``leaderboard.csv``, ``leaderboard.md`` and ``leaderboard.html`` into ``out_dir``.

    Returns
    -------
    list of pathlib.Path
        The files written, in that order.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    contents = {
        "csv": to_csv(boards),
        "markdown": to_markdown(boards, caption),
        "html": to_html(boards, caption),
    }
    written = []
    for kind, text in contents.items():
        path = out / FILE_NAMES[kind]
        path.write_text(text, encoding="utf-8")
        written.append(path)
    return written


__all__ = ["FILE_NAMES", "to_csv", "to_html", "to_markdown", "to_text", "write_leaderboards"]
