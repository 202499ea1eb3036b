"""The speed table: printed fitted to the terminal, written as CSV and as a markdown table.

Columns, in the order they are dropped last to first when the terminal is
narrow: subject, bound, ours (ms a frame and fps), the bound's ms a frame,
the median ratio ours / bound with its quartiles, the goal and whether it is
met.  The CSV holds every field of :class:`benchmark.speed.measure.Row` with
full precision; the markdown is the README's speed section.
"""

from __future__ import annotations

import csv
import dataclasses
import math
from collections.abc import Sequence
from pathlib import Path

from benchmark.files import make_folder
from benchmark.report.summary import GAP, terminal_width
from benchmark.speed.measure import Row
from benchmark.text import counted, printable, shortened

HEADERS = ("subject", "bound or peer", "ours ms", "ours fps", "bound ms", "ratio", "spread", "goal", "met")
"""The columns of the printed and markdown tables."""
TEXT_COLUMNS = ("subject", "bound or peer")
"""The columns of words, left-aligned and shortened to fit; the others are numbers, right-aligned."""
MIN_TEXT_WIDTH = 16
"""Subject and bound are shortened to no less than this before columns are left out."""
DROPPED_FIRST = ("spread", "ours fps", "bound ms", "goal")
"""The columns left out, in this order, when the table is too wide even with subject and bound shortened."""


def _ms(seconds: float) -> str:
    return "-" if math.isnan(seconds) else f"{seconds * 1e3:.3g}"


def _ratio(value: float) -> str:
    return "-" if math.isnan(value) else f"{value:.2f}x"


def met_text(row: Row) -> str:
    """``met``, ``not met``, or why the row could not be judged."""
    if row.met is None:
        return row.note or "-"
    return "met" if row.met else "not met"


def cells(row: Row) -> list[str]:
    """The row's values as the tables show them, in :data:`HEADERS` order."""
    spread = "-" if math.isnan(row.ratio_low) else f"{row.ratio_low:.2f}-{row.ratio_high:.2f}"
    return [
        printable(row.subject),
        printable(row.bound),
        _ms(row.ours_s),
        "-" if math.isnan(row.ours_s) else f"{row.ours_fps:.0f}",
        _ms(row.bound_s),
        _ratio(row.ratio),
        spread,
        row.goal or "-",
        met_text(row),
    ]


def terminal_table(rows: Sequence[Row], width: int | None = None) -> str:
    """The table as text at most ``width`` columns wide (the terminal's by default).

    The subject and the bound's description are shortened first (to
    :data:`MIN_TEXT_WIDTH`), then the columns of :data:`DROPPED_FIRST` are
    left out in that order; a line names those left out.
    """
    width = max(width or terminal_width(), 20)
    table = [list(HEADERS), *(cells(row) for row in rows)]
    widths = {title: max(len(line[i]) for line in table) for i, title in enumerate(HEADERS)}
    shown = list(HEADERS)

    def used() -> int:
        return sum(widths[title] for title in shown) + len(GAP) * (len(shown) - 1)

    for title in ("bound or peer", "subject"):
        widths[title] = max(min(widths[title], widths[title] - (used() - width)), min(MIN_TEXT_WIDTH, widths[title]))
    for title in DROPPED_FIRST:
        if used() <= width:
            break
        shown.remove(title)
    lines = []
    for line in table:
        values = dict(zip(HEADERS, line))
        parts = [
            shortened(values[title], widths[title]).ljust(widths[title])
            if title in TEXT_COLUMNS
            else values[title].rjust(widths[title])
            for title in shown
        ]
        lines.append(shortened(GAP.join(parts).rstrip(), width))
    if len(shown) < len(HEADERS):
        lines.append(shortened(f"(too narrow for {', '.join(t for t in HEADERS if t not in shown)})", width))
    return "\n".join(lines)


def markdown_table(rows: Sequence[Row]) -> str:
    """The table in markdown, with how it was measured (frames and rounds) under it."""
    escape = str.maketrans({"|": "\\|"})
    lines = [
        "| " + " | ".join(HEADERS) + " |",
        "|" + "---|" * len(HEADERS),
        *("| " + " | ".join(value.translate(escape) for value in cells(row)) + " |" for row in rows),
    ]
    measured = sorted({(row.dataset, row.frames, row.rounds) for row in rows})
    notes = "; ".join(
        f"{dataset}: {counted(frames, 'frame')} x {counted(rounds, 'round')}" for dataset, frames, rounds in measured
    )
    lines += [
        "",
        "Thread CPU time, one native thread, alternating rounds; ms and fps are medians over rounds, ratio the "
        "median of the per-round ratios ours / bound, spread its quartiles.",
        f"Frames: {notes}." if notes else "",
    ]
    return "\n".join(lines).rstrip() + "\n"


def write_csv(rows: Sequence[Row], path: Path) -> None:
    """Every field of every row, one row a line, with full precision."""
    make_folder(path.parent)
    fields = [field.name for field in dataclasses.fields(Row)]
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow([*fields, "ours_fps"])
        for row in rows:
            writer.writerow([*(getattr(row, name) for name in fields), row.ours_fps])


def write_markdown(rows: Sequence[Row], path: Path) -> None:
    """:func:`markdown_table` into ``path``."""
    make_folder(path.parent)
    path.write_text(markdown_table(rows), encoding="utf-8")


WRITERS = {".csv": write_csv, ".md": write_markdown}
"""How each suffix of ``--out`` is written."""
