"""The nightly's replays: the night's failed cells recorded frame by frame for the site, within a size budget.

After a nightly has kept its run and found its changes,
:func:`record_replays` picks the cells worth watching and, in that order,
records each one's replay (:func:`benchmark.replay.record.record_cell`, in
this process, the very cell the run ran: the same tracker and parameters,
sequence, seed, initialisation and stored model) into a page
(:func:`benchmark.replay.page.replay_html`) that links back to the cell's
page of the site.  The pages are kept in the history with the run
(:meth:`benchmark.history.database.History.record_replays`), so that the
site of any later night, or ``trackbench report``, still shows them.

Which cells, first to last (:func:`replay_order`):

1. cells that did not end ``ok`` (``error`` or ``timeout``);
2. cells of a tracker and dataset with an accuracy regression in the
   night's changes;
3. every other cell with a false or missed frame;

within each group the cells with the most false and missed frames first.
Only a window of frames is kept (:func:`replay_window`): from
:data:`FRAMES_BEFORE` frames before the cell's first false or missed frame
to :data:`FRAMES_AFTER` after it; for a cell that did not end ok, the
:data:`FRAMES_BEFORE` frames before the frame it stopped at, which the
replay does not step (in this process, a tracker that hangs or ends its
process there would take the nightly with it).

Pages are recorded until the next one would pass the night's budget
(:attr:`ReplayPlan.budget`); that cell and those after it get no page.  A
cell without a page keeps why (over the budget, a modality the replay
cannot show, the recording failed) and the ``trackbench replay`` command
that makes it.  Nothing here fails the nightly: a replay that raises is a
line of the log and a reason on its cell's page.
"""

from __future__ import annotations

import dataclasses
import hashlib
import shlex
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import pandas as pd

from benchmark.faults import Call
from benchmark.history.database import RECORDED, CellReplay, History
from benchmark.results import CellKey
from benchmark.text import counted

if TYPE_CHECKING:
    from pathlib import Path

    from benchmark.frame_cache import FrameCache
    from benchmark.replay.record import FrameRange
    from benchmark.runner import Cell

FRAMES_BEFORE = 30
"""Frames a replay keeps before the cell's first failed frame (or before the frame where it stopped)."""
FRAMES_AFTER = 60
"""Frames a replay keeps after the cell's first failed frame."""
DEFAULT_BUDGET = 50_000_000
"""Bytes of replay pages a nightly writes at most, by default (``--replay-budget 50MB``).

Measured on ``hough`` over ``camera-test`` and ``camera/S1`` (21 replays of 61 to 91 frames): 0.60 to 1.47 MB a
page, 1.0 MB on average, so about 50 camera replays a night; the history keeps them compressed to 69 %."""

NO_FRAMES = ("the run kept none of the cell's frames (it stopped before its first, or its worker was stopped): "
             "the replay would not know where to stop")
"""Why a cell without a frame in the history has no replay."""

FAILED_OUTCOMES = ("false", "missed")
"""The outcomes of a frame that count as a failure."""

NOT_OK = "did not end ok"
REGRESSION = "accuracy regression"
FAILED_FRAMES = "failed frames"
PRIORITIES = (NOT_OK, REGRESSION, FAILED_FRAMES)
"""Why a cell is replayed, in the order of :func:`replay_order`."""


@dataclass(frozen=True)
class ReplayPlan:
    """What the nightly's replay step needs besides the history.

    Attributes
    ----------
    budget : int
        Bytes of replay pages at most for the night; 0 records none.
    cells : callable
        Returns the cells of the run as selected (models not yet attached),
        among which each replayed cell is found by its key.
    frame_cache : FrameCache or None
        The frame cache the run read its sequences through.
    """

    budget: int
    cells: Callable[[], Sequence[Cell]]
    frame_cache: FrameCache | None = None


@dataclass(frozen=True)
class Chosen:
    """A cell to replay: its row of :meth:`History.cells`, why it is chosen, and the frames to keep.

    ``frames`` is None when the cell has no frame to replay (it failed before its first).
    """

    cell: Mapping[str, Any]
    priority: str
    failed_frames: int
    frames: FrameRange | None


@dataclass
class ReplaySummary:
    """What the replay step did: its kept rows, the bytes written, and a line per problem.

    Attributes
    ----------
    replays : list of CellReplay
        One per chosen cell, in order (pages dropped once kept).
    budget, spent : int
        The night's budget and the bytes of the pages recorded.
    problems : list of str
        A line per replay that failed.
    """

    replays: list[CellReplay] = field(default_factory=list)
    budget: int = 0
    spent: int = 0
    problems: list[str] = field(default_factory=list)

    def describe(self) -> str:
        """One line: pages recorded and their size against the budget, and the cells without one by reason."""
        states = pd.Series([replay.state for replay in self.replays], dtype=object).value_counts()
        recorded = int(states.get(RECORDED, 0))
        others = ", ".join(f"{count} {state}" for state, count in states.items() if state != RECORDED)
        line = (f"replays: {counted(recorded, 'page')} ({shown_size(self.spent)} of the "
                f"{shown_size(self.budget)} budget)")
        return line + (f"; without a page: {others}" if others else "")


def shown_size(size: int) -> str:
    """A size in bytes as ``12.3 MB``, ``850 kB`` or ``12 B``."""
    if size >= 10**6:
        return f"{size / 1e6:.1f} MB"
    return f"{size / 1e3:.0f} kB" if size >= 10**3 else f"{size} B"


def failed_frames(frames: pd.DataFrame) -> int:
    """How many frames of a frame table are false or missed."""
    return int(frames["outcome"].isin(FAILED_OUTCOMES).sum()) if "outcome" in frames else 0


def replay_window(frames: pd.DataFrame, status: str) -> FrameRange | None:
    """The frames to replay of a cell with frame table ``frames`` that ended with ``status``.

    Returns
    -------
    FrameRange or None
        For a cell that ended ok, :data:`FRAMES_BEFORE` frames before its
        first false or missed frame to :data:`FRAMES_AFTER` after it (within
        the frames it ran), or as many frames
        from the first where none failed (an RMSE regression); for a cell
        that did not end ok, the :data:`FRAMES_BEFORE` frames before the
        frame it stopped at.  None for a cell without a frame to replay.
    """
    from benchmark.replay.record import FrameRange  # here, so that drawing the site does not import the runner

    if "frame" not in frames or frames.empty:
        return None
    if status != "ok":
        stopped = int(frames["frame"].max()) + 1
        return FrameRange(max(0, stopped - FRAMES_BEFORE), stopped)
    failed = frames["frame"][frames["outcome"].isin(FAILED_OUTCOMES)]
    first = int(failed.min()) if len(failed) else FRAMES_BEFORE
    return FrameRange(max(0, first - FRAMES_BEFORE), min(first + FRAMES_AFTER + 1, int(frames["frame"].max()) + 1))


def replay_order(history: History, cells: pd.DataFrame, changes: pd.DataFrame | None) -> list[Chosen]:
    """The cells of a run to replay, first to last (the module's order), each with its frames.

    Parameters
    ----------
    history : History
        Where the cells' frame tables are.
    cells : pandas.DataFrame
        The run's cells (:meth:`History.cells`).
    changes : pandas.DataFrame or None
        The run's changes (:func:`benchmark.history.regressions.find_changes`).
    """
    regressed: set[tuple[str, str]] = set()
    if changes is not None and len(changes):
        accuracy = changes[(changes["verdict"] == "regression") & (changes["kind"] == "accuracy")]
        regressed = set(zip(accuracy["tracker"], accuracy["dataset"]))
    chosen = []
    for cell in cells.to_dict("records"):
        not_ok = cell["status"] != "ok"
        if not_ok:
            priority = NOT_OK
        elif (cell["tracker"], cell["dataset"]) in regressed:
            priority = REGRESSION
        else:
            priority = FAILED_FRAMES
        if priority == FAILED_FRAMES and not any(cell.get(rate, 0) > 0 for rate in ("false_pct", "missed_pct")):
            continue  # no failed frame (or none scored): nothing to watch
        frames = history.frames(int(cell["id"]))
        window = replay_window(frames, str(cell["status"]))
        chosen.append(Chosen(cell, priority, failed_frames(frames), window))
    chosen.sort(key=lambda c: (PRIORITIES.index(c.priority), -c.failed_frames, int(c.cell["id"])))
    return chosen


def replay_command(cell: Mapping[str, Any], frames: FrameRange | None) -> str:
    """The ``trackbench replay`` command of a cell's replay, quoted for a POSIX shell.

    ``trackbench replay`` takes no ``--param`` or ``--train``: for a nightly
    given those, the command replays the tracker's registered parameters and
    default training (a recorded page is always the run's own cell).
    """
    words = ["trackbench", "replay", "--tracker", str(cell["tracker"]), "--dataset", str(cell["dataset"]),
             "--seed", str(int(cell["seed"])), "--init", str(cell["init"])]
    return shlex.join([*words, *(["--frames", str(frames)] if frames is not None else [])])


def _key(cell: Mapping[str, Any]) -> CellKey:
    return CellKey(str(cell["tracker_key"]), str(cell["dataset_key"]), int(cell["seed"]), str(cell["init"]))


def _refuse_to_fit(function: Any, args: Any, timeout_s: float | None) -> bytes:
    raise RuntimeError("the run stored no model to reuse (the replay fits none)")


def _prepared(cell: Cell, plan: ReplayPlan, out: Path) -> Cell:
    """``cell`` reading through the run's frame cache, with the model the run stored in ``out`` (never fitted here)."""
    from benchmark.training import fit_models

    (cell,) = fit_models([cell], out, _refuse_to_fit)
    if plan.frame_cache is not None:
        cell = dataclasses.replace(cell, sequence=plan.frame_cache.wrap(cell.sequence))
    return cell


def _page(cell: Cell, frames: FrameRange, back: tuple[str, str]) -> bytes:
    """The replay page of ``frames`` of ``cell``, opening at its first false or missed frame, or where it stopped."""
    from benchmark.replay.page import replay_html
    from benchmark.replay.record import record_cell

    recording = record_cell(cell, frames)
    failed = [frame.index for frame in recording.frames if frame.outcome in FAILED_OUTCOMES]
    stopped = recording.frames[-1].index if recording.ended and recording.frames else None
    return replay_html(recording, back=back, start=failed[0] if failed else stopped).encode("utf-8")


def record_replays(
    history: History,
    run_id: int,
    changes: pd.DataFrame | None,
    plan: ReplayPlan,
    out: Path,
    back: Callable[[int], tuple[str, str]],
    log: Callable[[str], None] = lambda line: None,
) -> ReplaySummary:
    """Record replays of run ``run_id``'s cells in :func:`replay_order` within ``plan.budget``; keep them in ``history``.

    Parameters
    ----------
    history : History
        The history holding the run; the replays are kept in it.
    run_id : int
        The run, in the history.
    changes : pandas.DataFrame or None
        Its changes, for the cells of an accuracy regression.
    plan : ReplayPlan
        The budget, the run's cells and frame cache.
    out : pathlib.Path
        The run's results folder, whose stored models the replays use.
    back : callable
        ``back(cell_id)``: the address of the cell's page as seen from its
        replay page, and its label (:func:`benchmark.site.pages.replay_back`).
    log : callable
        Told a line for every replay that failed.

    Returns
    -------
    ReplaySummary
        What was recorded, and what was not and why.  Never raises for a
        cell's replay: whatever recording it raises is kept as its reason.
    """
    from benchmark.replay.views import NoViewError

    summary = ReplaySummary(budget=plan.budget)
    if plan.budget <= 0:
        return summary
    order = replay_order(history, history.cells([run_id]), changes)
    selected = Call.of(lambda: {cell.key: cell for cell in plan.cells()} if order else {}, "selecting the cells")
    over_budget = f"beyond the night's replay budget ({shown_size(plan.budget)})"
    over = False
    for chosen in order:
        cell, frames = chosen.cell, chosen.frames
        row = _row_of(int(cell["id"]), "" if frames is None else str(frames), replay_command(cell, frames))
        if frames is None:
            summary.replays.append(row("no frames", NO_FRAMES))
            continue
        if over:
            summary.replays.append(row("over budget", over_budget))
            continue
        if not selected.ok:
            call = selected
        elif (found := selected.result.get(_key(cell))) is None:  # type: ignore[union-attr]
            call = Call("replay", "error", note="the cell is not among the cells the nightly selected")
        else:
            call = Call.of(lambda: _page(_prepared(found, plan, out), frames, back(int(cell["id"]))), "replay")
        if call.fault is not None and call.fault.is_a(NoViewError):
            summary.replays.append(row("no view", call.fault.message))
        elif not call.ok:
            summary.replays.append(row("failed", f"recording the replay failed: {call.summary}"))
            label = f"{cell['tracker']} on {cell['dataset']}, seed {int(cell['seed'])} (cell #{int(cell['id'])})"
            summary.problems.append(f"replay of {label} failed: {call.summary}")
            log(summary.problems[-1])
        elif summary.spent + len(call.result) > plan.budget:  # type: ignore[arg-type]
            over = True
            summary.replays.append(row("over budget", over_budget))
        else:
            page: bytes = call.result  # type: ignore[assignment]
            summary.spent += len(page)
            digest = hashlib.sha256(page).hexdigest()[:20]
            summary.replays.append(row(RECORDED, "", size=len(page), digest=digest, page=page))
    history.record_replays(summary.replays)
    summary.replays = [dataclasses.replace(replay, page=None) for replay in summary.replays]
    return summary


def _row_of(cell_id: int, frames: str, command: str) -> Callable[..., CellReplay]:
    """A maker of the :class:`CellReplay` of one cell, given its state, reason and page."""

    def row(state: str, why: str, **page: Any) -> CellReplay:
        return CellReplay(cell_id, state, why, frames, command, **page)

    return row
