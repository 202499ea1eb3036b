"""The tracker contract every plugin implements.

A tracker class declares who it is (``name``, ``version``, ``modality``) and
its parameters as a frozen dataclass ``Params`` whose defaults are the
published values.  The harness creates one instance per cell, calls
:meth:`Tracker.reset` once and :meth:`Tracker.step` once per frame::

    tracker = entry.create()
    tracker.reset(info, rng, init=first_truth_or_none)
    for frame in sequence:
        estimate = tracker.step(frame)   # None: no detection this frame

The runner guarantees that every frame, and ``init``, has the types the
tracker's modality declares (:class:`benchmark.modality.Modality`), so a
tracker need not check them.  ``Tracker`` is generic in the truth and the
estimate of its modality: a camera tracker is a
``Tracker[CameraTruth, CableState]``.

All randomness must come from the ``rng`` handed to :meth:`Tracker.reset`,
so that a seed replays a run bit for bit.

Parameters are validated when they are made, by one declarative mechanism
for every tracker (:mod:`benchmark.parameters`): a field declares its range
or its choices beside it.
"""

from __future__ import annotations

import dataclasses
from abc import ABC, abstractmethod
from collections.abc import Mapping
from collections.abc import Sequence as SequenceOf
from typing import Any, ClassVar, Generic, Protocol, TypeVar, runtime_checkable

import numpy as np

from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.parameters import make_params

TruthT = TypeVar("TruthT")
EstimateT = TypeVar("EstimateT")


@dataclasses.dataclass(frozen=True)
class NoParams:
    """Parameters of a tracker that has none."""


class Tracker(ABC, Generic[TruthT, EstimateT]):
    """Base class of all trackers, first-party and third-party alike.

    Class attributes
    ----------------
    name : str
        Unique name in leaderboards and on the command line.
    version : str
        Bumped whenever results may change; part of the cache key.
    modality : str
        Name of the registered modality whose frames the tracker reads
        (``"camera"``, ``"sonar"``, ``"stereo"``, or a plugin's).
    Params : type
        A frozen dataclass whose fields, with defaults, are the parameters.
    deterministic : bool
        True for a tracker that draws no random numbers, whose output does
        not depend on the seed; the conformance kit holds a tracker to it
        either way (:func:`benchmark.testing.checks.check_seed_matters`).
        Only a tracker that declares it is marked ``deterministic`` on a
        board (:mod:`benchmark.leaderboard`).
    starts_without_truth : bool
        True (the default) for a tracker that can start from nothing
        (``init=None``, ``--init none``); one that needs the first frame's
        truth says False, and the kit skips its ``starts_without_truth`` check.
    expected_failed_checks : Mapping
        Checks of the conformance kit the tracker is known to fail, by name,
        each with the reason; the kit reports them as expected failures
        (``xfail``), and as a failure if one passes, so the list stays true
        (scikit-learn's ``expected_failed_checks``).
    needs : tuple of str
        Fields of :class:`~benchmark.model.SequenceInfo` the tracker cannot
        run without, e.g. ``("calibration", "frame_interval_s")``.  Before
        any cell runs, the harness asks every sequence which of them it
        lacks (:meth:`benchmark.model.Sequence.lacks`); a tracker is not run
        on a sequence that lacks one, and the run reports the pair with
        what to add (:func:`benchmark.selection.unmet_needs`).
    """

    name: ClassVar[str]
    version: ClassVar[str]
    modality: ClassVar[str]
    Params: ClassVar[type] = NoParams
    deterministic: ClassVar[bool] = False
    starts_without_truth: ClassVar[bool] = True
    expected_failed_checks: ClassVar[Mapping[str, str]] = {}
    needs: ClassVar[tuple[str, ...]] = ()

    def __init__(self, params: Any = None) -> None:
        self.params = params if params is not None else self.Params()

    @classmethod
    def defaults(cls) -> dict[str, Any]:
        """Parameter names with their default values, in declaration order."""
        return dataclasses.asdict(cls.Params())

    @classmethod
    def make_params(cls, overrides: Mapping[str, Any] | None = None) -> Any:
        """This tracker's ``Params`` from its defaults and ``overrides``, validated.

        See :func:`benchmark.parameters.make_params`.

        Raises
        ------
        ParameterError
            For an unknown name or an invalid value, naming tracker, parameter and value.
        """
        return make_params(cls.Params, cls.name, overrides)

    @abstractmethod
    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: TruthT | None = None) -> None:
        """Prepare for a new sequence.

        Parameters
        ----------
        info : SequenceInfo
            What is known of the sequence before its first frame.
        rng : numpy.random.Generator
            The only source of randomness the tracker may use.
        init : TruthT or None
            The first frame's ground truth, of the modality's truth type
            (camera: a ``CameraTruth``), when the run initialises from truth
            (``--init truth``) and the frame is labelled; otherwise None.
        """

    @abstractmethod
    def step(self, frame: Frame[Any, TruthT]) -> EstimateT | None:
        """Process one frame and return the estimate, or None for no detection."""


@runtime_checkable
class ScoresStates(Protocol):
    """A tracker that can score any state against a frame with its own observation model.

    Diagnostics use it to tell observation-model failures from tracker
    failures: if the best-scoring state near the truth is itself wrong, no
    search with that model can be right (``trackbench diagnose``).
    """

    def score_states(self, frame: Frame[Any, Any], states: np.ndarray) -> np.ndarray:
        """Scores, higher better, of ``(N, D)`` states on ``frame``; ``D`` as the modality's state array.

        A camera state is ``(d, alpha, w, beta)`` in px, rad, px, rad
        (:meth:`benchmark.modalities.camera.model.CableState.as_array`).
        """
        ...



@runtime_checkable
class Searches(Protocol):
    """A tracker that searches only part of each frame: a window or region of interest around its prediction.

    ``search_region`` is the part its latest ``step`` searched, None where it
    searched the whole frame.  Its type is the modality's: for a camera, the
    border lines (:class:`benchmark.modalities.camera.geometry.Line`, model
    coordinates) that bound the searched bands, two a band.  ``trackbench
    replay`` draws it on the frame.
    """

    @property
    def search_region(self) -> Any: ...


@runtime_checkable
class Learns(Protocol):
    """A tracker that learns from labelled sequences before it runs.

    ``trackbench run`` trains such a tracker once per (tracker version,
    parameters, training set) on a training split that never overlaps the
    scored sequences, stores the model :meth:`fit` returns, and hands it to
    every cell's fresh instance through :meth:`use_model` before
    :meth:`Tracker.reset`.  The model is stored as data, never as code
    (:mod:`benchmark.storage`): it must be built of None, numbers, strings,
    lists, tuples, dicts, numpy arrays of numbers, and enums and dataclasses
    defined in the tracker's own package; ``trackbench check`` fails a
    model that is not.
    """

    def fit(self, training: SequenceOf[Sequence], rng: np.random.Generator) -> Any:
        """Learn from the labelled frames of ``training``; adopt the model and return it.

        Raises
        ------
        DataError
            If the training set cannot teach the tracker (no labelled frame,
            a class never seen), naming what is missing.
        """
        ...

    def use_model(self, model: Any) -> None:
        """Adopt a model an earlier :meth:`fit` returned, perhaps in another process."""
        ...
