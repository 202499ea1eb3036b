"""Boards as Markdown: a page for ``leaderboard.md``, and the same tables for a terminal.

Names, statuses, the caption and problems come from plugins and users, so
the page escapes them (:func:`escape_markdown`): whatever they hold shows
as literal text, never as a link, an image, emphasis, HTML or a broken table
(GitHub still makes a bare URL or e-mail address clickable, shown as written).
"""

from __future__ import annotations

import html
import re
from collections.abc import Mapping, Sequence

import pandas as pd

from benchmark.metrics import CORE, RATES, Metrics
from benchmark.report.display import alignment, display_table, format_value
from benchmark.text import one_line, printable

_INLINE_MARKUP = re.compile(r"[\\`*_\[\]|~$]")
"""Characters that mean something anywhere in a line: code, emphasis, links, table cells, strikethrough, math."""

_LINE_START_MARKUP = re.compile(r"^(\d+(?=[.)](?: |$))|)([#+\-=.)])")
"""A heading, list or underline marker opening a line; ``1.`` only before a space, so that ``66.7`` stays as it is."""


def escape_markdown(text: object) -> str:
    r"""``text`` as literal Markdown on one line.

    Runs of whitespace, newlines included, become one space; ``&``, ``<``
    and ``>`` become entities; Markdown punctuation gets a backslash.
    Digits and ``.`` inside a number are left alone.

    Examples
    --------
    >>> print(escape_markdown("[x](y) <b>*z*</b> | 1.5"))
    \[x\](y) &lt;b&gt;\*z\*&lt;/b&gt; \| 1.5
    """
    escaped = _INLINE_MARKUP.sub(r"\\\g<0>", html.escape(one_line(text), quote=False))
    return _LINE_START_MARKUP.sub(r"\1\\\2", escaped)


def _shorten(text: str, width: int) -> str:
    return text if len(text) <= width else text[: width - 3] + "..."


def to_text(
    boards: Mapping[str, pd.DataFrame],
    status_width: int = 60,
    problems: Sequence[str] = (),
    metrics: Metrics = CORE,
) -> str:
    """The boards for a terminal, one block per modality, long statuses shortened, then any ``problems``."""
    blocks = [] if boards else ["No results."]
    for modality, board in boards.items():
        shown = display_table(board, metrics).map(lambda value: printable(value) if isinstance(value, str) else value)
        shown["status"] = [_shorten(text, status_width) for text in shown["status"]]
        aligned = alignment(board, metrics)
        table = shown.to_markdown(index=False, tablefmt="simple", disable_numparse=True, colalign=aligned)
        blocks.append(f"{modality}\n\n{table}")
    if problems:
        blocks.append("\n".join(["Problems", "", *(f"- {one_line(problem)}" for problem in problems)]))
    return "\n\n".join(blocks)


def to_markdown(
    boards: Mapping[str, pd.DataFrame], caption: str = "", problems: Sequence[str] = (), metrics: Metrics = CORE
) -> str:
    """The boards as a Markdown page, one section per modality, then a section listing ``problems``.

    Every text taken from the boards, the caption and the problems is
    escaped (:func:`escape_markdown`).
    """
    parts = ["# trackbench leaderboard", ""]
    if caption:
        parts += [escape_markdown(caption), ""]
    if not boards:
        parts += ["No results.", ""]
    for modality, board in boards.items():
        shown = display_table(board, metrics).map(escape_markdown)
        shown.columns = [escape_markdown(column) for column in shown.columns]
        table = shown.to_markdown(index=False, disable_numparse=True, colalign=alignment(board, metrics))
        parts += [f"## {escape_markdown(modality)}", "", table, ""]
    if problems:
        parts += ["## Problems", "", *(f"- {escape_markdown(problem)}" for problem in problems), ""]
    return "\n".join(parts)


def condition_markdown(tables: Mapping[tuple[str, str, str], pd.DataFrame], caption: str = "") -> str:
    """Boards by condition (:func:`benchmark.by_condition.condition_tables`) as a Markdown page.

    One section per modality and suite, one table per condition: per cent
    of frames correct, a row per tracker and a column per bin.
    """
    parts = ["# trackbench: correct % by condition", ""]
    if caption:
        parts += [escape_markdown(caption), ""]
    suite = None
    for (modality, suite_name, condition), table in tables.items():
        if (modality, suite_name) != suite:
            suite = (modality, suite_name)
            parts += [f"## {escape_markdown(suite_name)} ({escape_markdown(modality)})", ""]
        cells = {
            escape_markdown(column): [
                escape_markdown(value) if column == "tracker" else format_value(RATES[0].name, value)
                for value in table[column]
            ]
            for column in table.columns
        }
        shown = pd.DataFrame(cells, dtype=object)
        aligned = ["left", *["right"] * (len(table.columns) - 1)]
        body = shown.to_markdown(index=False, disable_numparse=True, colalign=aligned)
        parts += [f"### {escape_markdown(condition)}", "", body, ""]
    if not tables:
        parts += ["No sequence of this run records its conditions.", ""]
    return "\n".join(parts)


def titled_table(table: pd.DataFrame, title: str) -> str:
    """A table under a level-one heading, values rounded for reading (:mod:`benchmark.report.display`)."""
    shown = display_table(table)
    # Numbers need no escaping, and a minus sign escaped as a list marker would read badly in a terminal.
    for column in table.columns:
        if not pd.api.types.is_numeric_dtype(table[column]):
            shown[column] = shown[column].map(escape_markdown)
    body = shown.to_markdown(index=False, disable_numparse=True, colalign=alignment(table))
    return f"# {escape_markdown(title)}\n\n{body}\n"
