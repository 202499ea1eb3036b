"""The modality contract: everything the harness needs to know about one kind of sensor.

A *modality* is a kind of sensor data: camera images of a cable, multibeam
sonar swaths over a pipe, stereo measurements of a boat.  The harness itself
knows none of them.  Each arrives as a :class:`Modality` that a plugin adds
in its ``trackbench_register_modalities`` hook, and declares:

* its ``name``, by which trackers (``Tracker.modality``) and sequences
  (``SequenceInfo.modality``) refer to it;
* the types of a frame's observation and truth and of a tracker's estimate,
  which the runner checks, so that a tracker and a scorer can rely on them;
* its :class:`Scorer`: the error columns of its leaderboard and the
  per-frame outcome rule (correct, false or missed);
* the :class:`Reader` objects that open its files and folders, and the
  exporter that writes a sequence in its on-disk form;
* the scene kinds a suite file may name to simulate its sequences;
* optionally, its :data:`Drawer`: a small picture of a frame with the truth
  and the tracker's estimate drawn on it, which the runner keeps for the
  first frame of each run of failures (:mod:`benchmark.drawing`);
* optionally, for the conformance kit (:mod:`benchmark.testing`), its
  :data:`HardObservations` (blank, saturated, pure-noise observations,
  missing beams: what a tracker must survive) and its
  :data:`ExampleSequences` (a hypothesis strategy of short labelled
  sequences from random scenes);
* optionally, its :class:`Starter`: what ``trackbench new-tracker`` writes
  into the skeleton of a tracker of this modality (:mod:`benchmark.scaffold`).

The built-in modalities, :mod:`benchmark.modalities.camera`,
:mod:`~benchmark.modalities.sonar` and :mod:`~benchmark.modalities.stereo`,
are registered through that hook exactly as a third-party sensor would be.
"""

from __future__ import annotations

import functools
import importlib
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from benchmark.errors import DataError
from benchmark.model import Frame, Outcome, Sequence, SequenceInfo

ANY_FILE = "*"
"""A :attr:`Reader.suffixes` entry that accepts a file whose suffix no other reader claims."""

SceneFactory = Callable[[Mapping[str, Any], str], Sequence]
"""Builds a simulated sequence from its table of a suite file and a description of where the table came from."""

Exporter = Callable[[Sequence, Path, str], Path]
"""Writes a sequence into a folder under a file stem and returns the file that opens it again."""

Drawer = Callable[[Frame, Any], np.ndarray]
"""Draws a frame and an estimate (or None) as a small ``uint8`` BGR picture ``(H, W, 3)``.

The observation is drawn with the frame's truth in green and the estimate
in red (:data:`benchmark.drawing.TRUTH_BGR`, :data:`~benchmark.drawing.ESTIMATE_BGR`);
the frame is left unchanged.
"""

HardObservations = Callable[[Frame, SequenceInfo, np.random.Generator], Mapping[str, Any]]
"""Observations a tracker must survive, by name, made in the likeness of a frame's own.

Called with a frame, its sequence's description and a generator, it
returns observations of the frame's type and size that carry no usable
signal or break a sensor's usual promises (``"blank"``, ``"saturated"``,
``"noise"``, ``"nan_beams"``...).  A tracker may return None on them, never
raise or return an invalid estimate (:func:`benchmark.testing.checks.check_hard_observations`).
"""

ExampleSequences = Callable[[int], Any]
"""``example_sequences(max_frames)``: a hypothesis strategy of short labelled sequences of the modality.

Each example is a :class:`~benchmark.model.Sequence` of 1 to ``max_frames``
frames, simulated from a random scene; the conformance kit runs trackers on
a few of them (:func:`benchmark.testing.checks.check_random_sequences`).
:func:`sequences_in` makes one from a module's ``sequences`` function.
"""


def sequences_in(module: str) -> ExampleSequences:
    """The :data:`ExampleSequences` of ``module.sequences``, imported (hypothesis with it) only when called.

    Parameters
    ----------
    module : str
        A module with a function ``sequences(max_frames)`` that returns the strategy
        (``"benchmark.modalities.sonar.strategies"``).
    """
    return functools.partial(_sequences_of_module, module)


def _sequences_of_module(module: str, max_frames: int) -> Any:
    return importlib.import_module(module).sequences(max_frames)


@dataclass(frozen=True)
class Starter:
    """The modality's part of a new tracker's skeleton (``trackbench new-tracker --modality NAME``).

    The skeleton tracker holds the estimate its first frame's truth gives
    (``--init truth``): a baseline that passes the conformance kit and that
    every real tracker should beat.  Each attribute is Python source.

    Attributes
    ----------
    imports : str
        The import statement of the truth and estimate types.
    truth, estimate : str
        Their class names as imported.
    hold : str
        An expression of ``init`` (the first truth, never None) that gives
        the estimate to hold, or None when that truth cannot give one.
    observation : str
        A comment line on what ``frame.observation`` holds.
    dataset : str
        A registered sequence the skeleton's README runs it on (``camera/S2``).
    """

    imports: str
    truth: str
    estimate: str
    hold: str
    observation: str
    dataset: str


class EstimateError(TypeError):
    """A tracker returned something that is not an estimate of its modality."""


class Scorer(Protocol):
    """How a modality scores an estimate against the truth of one frame."""

    error_columns: tuple[str, ...]
    """Names of the per-frame error columns, with units, e.g. ``err_d_px``; ``err_X`` becomes ``rmse_X``."""

    def check(self, estimate: Any) -> None:
        """Raise :class:`EstimateError` unless the values of an estimate (already of the right type) are valid."""

    def score(self, estimate: Any, truth: Any, info: SequenceInfo) -> tuple[Outcome | None, tuple[float, ...]]:
        """Outcome and errors (in ``error_columns`` order) of one frame; outcome None for an unscored frame.

        Errors are finite, or ``nan`` where there is no estimate or no truth.
        The store drops non-finite errors and :func:`benchmark.results.summarise`
        ignores them, so an error too large for a float (overflow of the
        scorer's arithmetic on a finite but absurd estimate) is reported as
        ``+-sys.float_info.max`` and its frame as false: an ``inf`` would
        leave out of the RMSE exactly the frames that should weigh most.
        """


@dataclass(frozen=True)
class Reader:
    """A way of opening a dataset on disk as a :class:`~benchmark.model.Sequence`.

    Attributes
    ----------
    open : callable
        ``open(path) -> Sequence``; raises :class:`~benchmark.errors.DataError`
        naming the file for anything it cannot read.
    description : str
        What it reads, for messages (``"an image sequence file"``).
    suffixes : tuple of str
        File name endings it reads, lower case with the dot (``".swaths"``);
        :data:`ANY_FILE` for files whose ending no other reader claims.
    folders : bool
        Whether it opens a folder.
    folder_holds : tuple of str
        Names a folder must hold for this reader to open it (a stereo
        folder's ``("left", "right")``); a folder reader that asks for
        them is chosen before one that asks for nothing (a plain image
        folder), and two modalities may not ask for the same names.
    """

    open: Callable[[str | os.PathLike[str]], Sequence]
    description: str
    suffixes: tuple[str, ...] = ()
    folders: bool = False
    folder_holds: tuple[str, ...] = ()

    @property
    def folder_claim(self) -> str | None:
        """``"folders"``, ``"folders holding left, right"``, or None for a reader of files only."""
        if not self.folders:
            return None
        return f"folders holding {', '.join(self.folder_holds)}" if self.folder_holds else "folders"

    def opens_folder(self, folder: Path) -> bool:
        """Whether this reader takes the folder ``folder``: a folder reader whose names are all in it."""
        return self.folders and all((folder / name).exists() for name in self.folder_holds)


@dataclass(frozen=True, eq=False)
class Modality:
    """One kind of sensor data, as plugins register it.

    Attributes
    ----------
    name : str
        The name trackers and sequences use (``"camera"``).
    observation_type : type or tuple of types
        What a frame's ``observation`` may be (``isinstance``'s second argument).
    truth_type : type
        What a frame's ``truth`` is when the frame is labelled; the first
        frame's truth is what ``Tracker.reset`` receives as ``init``.
    estimate_type : type
        What a tracker's ``step`` returns when it detects something.
    scorer : Scorer
        Error columns and the per-frame outcome rule.
    readers : tuple of Reader
        The files and folders of this modality that ``--dataset PATH`` opens.
    exporter : Exporter or None
        Writes a sequence of this modality to disk (``trackbench make-dataset``);
        None if it cannot be exported.
    scene_kinds : Mapping
        Scene kind name (as a suite file's ``[suite] kind`` names it) to the
        factory that builds one sequence of it.
    description : str
        One line for listings.
    draw : Drawer or None
        Draws a frame with its truth and an estimate, for the pictures of
        failed frames in reports; None draws nothing.
    hard_observations : HardObservations or None
        Observations without signal that a tracker must survive; None: the
        conformance kit has none to try.
    example_sequences : ExampleSequences or None
        Random short sequences for property-based checks; None: the
        conformance kit runs on registered sequences only.
    starter : Starter or None
        The modality's part of a new tracker's skeleton; None: ``trackbench
        new-tracker`` cannot write one for it.
    """

    name: str
    observation_type: type | tuple[type, ...]
    truth_type: type
    estimate_type: type
    scorer: Scorer
    readers: tuple[Reader, ...] = ()
    exporter: Exporter | None = None
    scene_kinds: Mapping[str, SceneFactory] = field(default_factory=dict)
    description: str = ""
    draw: Drawer | None = None
    hard_observations: HardObservations | None = None
    example_sequences: ExampleSequences | None = None
    starter: Starter | None = None

    def check_frame(self, frame: Frame, where: str) -> None:
        """Raise :class:`~benchmark.errors.DataError`, prefixed by ``where``, unless ``frame`` is of this modality."""
        if not isinstance(frame.observation, self.observation_type):
            raise DataError(
                f"{where}: the observation is a {type(frame.observation).__name__}, "
                f"not what a {self.name} frame holds ({_type_names(self.observation_type)})"
            )
        if frame.truth is not None and not isinstance(frame.truth, self.truth_type):
            raise DataError(
                f"{where}: the truth is a {type(frame.truth).__name__}, not a {self.truth_type.__name__} or None"
            )

    def check_estimate(self, estimate: Any) -> None:
        """Raise :class:`EstimateError` unless ``estimate`` is None or a valid estimate of this modality."""
        if estimate is None:
            return
        if not isinstance(estimate, self.estimate_type):
            raise EstimateError(
                f"expected a {self.estimate_type.__name__} or None, got {type(estimate).__name__}: {estimate!r}"
            )
        self.scorer.check(estimate)

    @property
    def claims(self) -> tuple[str, ...]:
        """What its readers open: ``"files ending .x"``, ``"any other file"``, ``"folders"`` (holding names)."""
        return tuple(
            claim
            for reader in self.readers
            for claim in (
                *("any other file" if suffix == ANY_FILE else f"files ending {suffix}" for suffix in reader.suffixes),
                *([reader.folder_claim] if reader.folder_claim else []),
            )
        )

    @property
    def error_columns(self) -> tuple[str, ...]:
        """The scorer's error columns."""
        return tuple(self.scorer.error_columns)


def _type_names(types: type | tuple[type, ...]) -> str:
    listed = types if isinstance(types, tuple) else (types,)
    return " or ".join("None" if kind is type(None) else kind.__name__ for kind in listed)

