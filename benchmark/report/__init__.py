"""Reports built from leaderboards: the files a run publishes, and views laid out as the papers lay theirs.

:func:`write_leaderboards` writes a run's boards (:mod:`benchmark.leaderboard`)
as ``leaderboard.csv`` (:mod:`~benchmark.report.csv`, full precision),
``leaderboard.md`` (:mod:`~benchmark.report.markdown`) and
``leaderboard.html`` (:mod:`~benchmark.report.html`), the last two rounded
for reading (:mod:`~benchmark.report.display`).  :mod:`~benchmark.report.grid`
lays a suite out per case and condition, as seeds/002 does in its Tables 6-8.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import pandas as pd

from benchmark.files import make_folder, write_text_atomically
from benchmark.report.csv import to_csv
from benchmark.report.html import to_html
from benchmark.report.markdown import to_markdown, to_text

FILE_NAMES = {"csv": "leaderboard.csv", "markdown": "leaderboard.md", "html": "leaderboard.html"}
"""The file each form of the boards is written to."""


def write_leaderboards(
    boards: Mapping[str, pd.DataFrame], out_dir: str | Path, caption: str = "", problems: Sequence[str] = ()
) -> list[Path]:
    """Write ``leaderboard.csv``, ``leaderboard.md`` and ``leaderboard.html`` into ``out_dir``.

    Each file is written under a temporary name and renamed into place
    (:func:`benchmark.files.write_text_atomically`), so that a reader sees
    the old board or the new one, never half of one.

    Parameters
    ----------
    boards : Mapping
        Modality name to board (:func:`benchmark.leaderboard.leaderboards`).
    out_dir : str or pathlib.Path
        The folder, created if missing.
    caption : str
        A line shown under the title of the Markdown and HTML pages.
    problems : sequence of str
        Run-level problems (a plugin that failed to import), listed in a
        section of the Markdown and HTML pages; the CSV holds the boards only.

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
        "markdown": to_markdown(boards, caption, problems),
        "html": to_html(boards, caption, problems),
    }
    return [write_text_atomically(out / FILE_NAMES[kind], text, "leaderboard") for kind, text in contents.items()]


__all__ = ["FILE_NAMES", "to_csv", "to_html", "to_markdown", "to_text", "write_leaderboards"]
