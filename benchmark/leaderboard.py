"""Leaderboards: cells pooled per tracker and dataset, ranked per modality.

A leaderboard row pools every scored frame of every seed a tracker ran on a
dataset: rates are percentages of all those frames (so seeds weigh by their
frame counts), each RMSE is the square root of the mean squared error over
all frames with an estimate and a truth, and ``fps`` is all frames over all
``step`` time (:func:`benchmark.metrics.summarise` applied to the pooled
frames).  A row with dataset ``(all)`` pools each tracker over every dataset
of the board and comes first.

Within each dataset trackers are ranked by ``correct_pct`` (higher first),
then by the first RMSE column (``rmse_d_px`` for cameras, lower first), the
order of seeds/004, Table V followed by the accuracy of seeds/000,
section 5.2.3.  Rows whose cells failed (status other than ``ok``) rank
after every row that ran cleanly, since their rates cover only the frames
before the failure.

There is one board per modality, as the modalities score different things.
Numeric column names carry their units (``conventions.md`` section 4).
Boards keep full precision (and CSV exports them so); the Markdown, HTML and
terminal forms round percentages to 0.1, RMSEs to 0.01 and fps to 1.
"""

from __future__ import annotations

import html
import math
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import pandas as pd

from benchmark.metrics import scorer_for, summarise
from benchmark.model import Outcome

if TYPE_CHECKING:
    from benchmark.store import ResultStore

ALL_DATASETS = "(all)"
"""Dataset name of the row that pools a tracker over all datasets of a board."""

LEADING_COLUMNS = ("rank", "tracker", "dataset", "init", "seeds", "frames")
RATE_COLUMNS = tuple(f"{outcome}_pct" for outcome in Outcome)
FILE_NAMES = {"csv": "leaderboard.csv", "markdown": "leaderboard.md", "html": "leaderboard.html"}


def error_columns(modality: str, frames: pd.DataFrame) -> tuple[str, ...]:
    """The error columns of a modality; those found in ``frames`` if it has no scorer here."""
    try:
        return tuple(scorer_for(modality).error_columns)
    except KeyError:
        return tuple(column for column in frames.columns if str(column).startswith("err_"))


def board_columns(errors: tuple[str, ...]) -> list[str]:
    """Columns of a board whose modality has the error columns ``errors``."""
    rmse = ["rmse_" + column.removeprefix("err_") for column in errors]
    return [*LEADING_COLUMNS, *RATE_COLUMNS, *rmse, "fps", "status"]


def pooled_status(cells: pd.DataFrame) -> str:
    """``ok``, or how many cells failed and the first failure's message.

    Returns ``"error (k/n cells): message"``, or ``"timeout (k/n cells): ..."``
    when every failed cell timed out.
    """
    failed = cells[cells["status"] != "ok"].sort_values("id")
    if failed.empty:
        return "ok"
    kind = "timeout" if (failed["status"] == "timeout").all() else "error"
    first = failed[failed["status"] == kind].iloc[0]
    return f"{kind} ({len(failed)}/{len(cells)} cells): {first['message']}"


def _tracker_labels(cells: pd.DataFrame) -> pd.Series:
    """Tracker names, with the cache key added where one name ran with several parameter sets."""
    keys_per_name = cells.groupby("tracker")["tracker_key"].transform("nunique")
    short_keys = cells["tracker_key"].astype(str).str.slice(0, 8)
    return cells["tracker"].where(keys_per_name <= 1, cells["tracker"] + " [" + short_keys + "]")


def _rank(board: pd.DataFrame, first_rmse: str | None) -> pd.DataFrame:
    ordered = board.assign(
        _failed=board["status"] != "ok",
        _correct=-board["correct_pct"].fillna(-math.inf),
        _rmse=board[first_rmse].fillna(math.inf) if first_rmse else 0.0,
        _all=board["dataset"] != ALL_DATASETS,
    )
    ordered = ordered.sort_values(
        ["_all", "dataset", "init", "_failed", "_correct", "_rmse", "tracker"], kind="stable"
    )
    ordered["rank"] = ordered.groupby(["dataset", "init"]).cumcount() + 1
    return ordered.drop(columns=["_failed", "_correct", "_rmse", "_all"]).reset_index(drop=True)


def modality_board(cells: pd.DataFrame, frames: pd.DataFrame, errors: tuple[str, ...]) -> pd.DataFrame:
    """The ranked board of one modality.

    Parameters
    ----------
    cells : pandas.DataFrame
        Cells of one modality, with at least ``id``, ``tracker``,
        ``tracker_key``, ``dataset``, ``seed``, ``init``, ``status`` and
        ``message`` (as :meth:`benchmark.store.ResultStore.cells` returns).
    frames : pandas.DataFrame
        Their frame scores: ``cell_id``, ``outcome``, the error columns and
        ``step_ms`` (as :meth:`benchmark.store.ResultStore.frame_tables`).
    errors : tuple of str
        The modality's error columns, ``err_*``.

    Returns
    -------
    pandas.DataFrame
        Columns :func:`board_columns`; ``(all)`` rows first, then each
        dataset's rows in rank order.

    References
    ----------
    seeds/004, section VI-C and Table V (rates); seeds/000, sections 5.2.3
    and 5.2.5 (state errors and speed).
    """
    columns = board_columns(errors)
    if cells.empty:
        return pd.DataFrame(columns=columns)
    if "cell_id" not in frames.columns:
        frames = pd.DataFrame(columns=["cell_id", "frame", "outcome", "step_ms"])
    cells = cells.assign(label=_tracker_labels(cells))
    by_cell = {int(cell_id): group for cell_id, group in frames.groupby("cell_id", sort=False)}
    empty = frames.iloc[0:0]

    def row(group: pd.DataFrame, label: str, dataset: str, init: str) -> dict[str, object]:
        parts = [by_cell[int(i)] for i in group["id"] if int(i) in by_cell]
        pooled = pd.concat(parts, ignore_index=True) if parts else empty
        summary = summarise(pooled, errors)
        summary["frames"] = int(summary["frames"])
        return {
            "tracker": label,
            "dataset": dataset,
            "init": init,
            "seeds": int(group["seed"].nunique()),
            **summary,
            "status": pooled_status(group),
        }

    rows = [
        row(group, label, ALL_DATASETS, init)
        for (label, init), group in cells.groupby(["label", "init"], sort=True)
    ]
    rows += [
        row(group, label, dataset, init)
        for (label, dataset, init), group in cells.groupby(["label", "dataset", "init"], sort=True)
    ]
    board = pd.DataFrame(rows).reindex(columns=columns)
    rmse = [column for column in columns if column.startswith("rmse_")]
    ranked = _rank(board, rmse[0] if rmse else None)
    return ranked.astype({"rank": "int64", "seeds": "int64", "frames": "int64"})[columns]


def leaderboards(cells: pd.DataFrame, frames: pd.DataFrame) -> dict[str, pd.DataFrame]:
    """One ranked board per modality present in ``cells``.

    Parameters
    ----------
    cells, frames : pandas.DataFrame
        As for :func:`modality_board`, any mix of modalities.

    Returns
    -------
    dict
        Modality name to board, in alphabetical order of modality.
    """
    boards: dict[str, pd.DataFrame] = {}
    for modality, group in cells.groupby("modality", sort=True):
        part = frames[frames["cell_id"].isin(group["id"])] if "cell_id" in frames.columns else frames
        boards[str(modality)] = modality_board(group, part, error_columns(str(modality), part))
    return boards


def load_leaderboards(
    store: ResultStore, run_id: int | None = None, *, all_runs: bool = False
) -> dict[str, pd.DataFrame]:
    """The boards of a run stored in ``store`` (default: its latest run).

    With ``all_runs`` the boards take, for each tracker key, dataset, seed
    and initialisation, the latest cell of any run.
    """
    cells = store.cells(run_id, all_runs=all_runs)
    return leaderboards(cells, store.frame_tables(cells["id"]))


def _format_value(column: str, value: object) -> str:
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
        {column: [_format_value(column, value) for value in board[column].tolist()] for column in board.columns},
        columns=board.columns,
        dtype=object,
    )


def _numeric(board: pd.DataFrame) -> list[bool]:
    return [pd.api.types.is_numeric_dtype(board[column]) for column in board.columns]


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
        align = ["right" if numeric else "left" for numeric in _numeric(board)]
        table = shown.to_markdown(index=False, tablefmt="simple", disable_numparse=True, colalign=align)
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
        align = ["right" if numeric else "left" for numeric in _numeric(board)]
        shown = display_table(board).map(lambda text: text.replace("|", "\\|"))
        table = shown.to_markdown(index=False, disable_numparse=True, colalign=align)
        parts += [f"## {modality}", "", table, ""]
    return "\n".join(parts)


def to_html(boards: Mapping[str, pd.DataFrame], caption: str = "") -> str:
    """The boards as a self-contained HTML page, one section per modality."""
    body = ["<h1>trackbench leaderboard</h1>"]
    if caption:
        body.append(f"<p>{html.escape(caption)}</p>")
    if not boards:
        body.append("<p>No results.</p>")
    for modality, board in boards.items():
        body.append(f"<h2>{html.escape(modality)}</h2>")
        body.append(display_table(board).to_html(index=False, escape=True, border=1))
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        "<title>trackbench leaderboard</title>\n</head>\n<body>\n" + "\n".join(body) + "\n</body>\n</html>\n"
    )


def to_csv(boards: Mapping[str, pd.DataFrame]) -> str:
    """All boards in one CSV table at full precision, with a ``modality`` column first."""
    if not boards:
        return "modality\n"
    tables = [board.assign(modality=modality) for modality, board in boards.items()]
    combined = pd.concat(tables, ignore_index=True)
    ordered = ["modality", *[column for column in combined.columns if column != "modality"]]
    return combined[ordered].to_csv(index=False)


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
