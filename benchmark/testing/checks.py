"""The checks of the conformance kit, one function per rule of the tracker contract.

Every check takes a :class:`Subject`: the tracker's registry entry with
frames of its modality (and, for a tracker that learns, a model fitted on
training frames), prepared once by :func:`prepare` and shared by all
checks.  A check returns a line of detail for the report, raises
:class:`AssertionError` with a message that names the tracker and what
broke, or raises :class:`NotApplicable` when the tracker declares that it
lacks the capability the check is about.  Exceptions the tracker raises
become assertion errors, naming the frame.

A :class:`Check` names the checks it comes after (``after``): one whose
failure would make it fail too.  A tracker that raises on every frame fails
``runs``, and with it nearly every other check; the kit then reports
``runs`` first and the others as following from it
(:func:`benchmark.testing.with_root_causes`).

The rules are those of :mod:`benchmark.tracker` and the design page's
plugin contract: a tracker declares ``name``, ``version``, ``modality`` and a
frozen ``Params`` dataclass with valid defaults; it returns estimates of its
modality or None; it copes with unlabelled frames, with observations that
carry no signal and with random scenes of its modality; it draws randomness
only from the generator handed to ``reset``, so a seed replays a run bit
for bit and another seed changes it (unless the tracker declares itself
deterministic); ``reset`` forgets the previous sequence; and it pickles,
since cells run in worker processes.
"""

from __future__ import annotations

import dataclasses
import math
import pickle
import random
import time
import zlib
from collections.abc import Callable, Iterator, Mapping
from collections.abc import Sequence as SequenceOf
from contextlib import contextmanager
from dataclasses import dataclass
from itertools import islice
from typing import Any, TypeVar

import numpy as np

from benchmark import storage
from benchmark.faults import Call, UserInterrupt
from benchmark.identity import DatasetIdentity
from benchmark.modality import Modality
from benchmark.model import Frame, Sequence, SequenceInfo
from benchmark.registry import Registry, TrackerEntry
from benchmark.runner import cell_rng
from benchmark.testing.beliefs import (
    GaussianBelief,
    GaussianUpdate,
    ParticleBelief,
    ParticleUpdate,
    declares_belief,
    gaussian_belief_problems,
    gaussian_update_problems,
    particle_belief_problems,
    particle_update_problems,
)
from benchmark.testing.hash_seed import check_hash_seed
from benchmark.testing.time_limit import CheckTimeout
from benchmark.tracker import Tracker
from benchmark.training import learns

DEFAULT_FRAMES = 60
"""Frames each run of a check reads: a bug that starts at frame 50 shows, and the middle third of hard observations is 20 frames long."""

RANDOM_EXAMPLES = 10
"""Random sequences :func:`check_random_sequences` runs a tracker on."""

RANDOM_FRAMES = 5
"""Frames of each random sequence, unless the caller chooses another length."""

SEED = 0
"""Seed of the checks' runs, turned into a generator by the runner's convention (:func:`cell_rng`)."""

PASS_THROUGH = (UserInterrupt, CheckTimeout)
"""What the kit lets through: the user's Ctrl-C and a check's time running out.

Anything else a tracker raises, ``SystemExit`` and its own
``KeyboardInterrupt`` included, is the failure of the check it happened in,
as it is of its cell in a run (:func:`benchmark.runner.run_cell`).
"""


_TRACKER_CALL: dict[str, Any] = {"reraise": (UserInterrupt,), "timeouts": (CheckTimeout,)}
"""How :meth:`Subject.run` calls a tracker: a check's time running out is a timeout of the phase it happened in."""

T = TypeVar("T")


class NotApplicable(Exception):
    """Raised by a check that does not apply to the tracker (it declares that it lacks the capability); the reason."""


class FrameList(Sequence):
    """A sequence of frames already in memory, with the identity of the sequence they were taken from.

    Parameters
    ----------
    info : SequenceInfo
        Its description; ``n_frames`` should be ``len(frames)``.
    identity : DatasetIdentity
        The identity that seeds runs on it.
    frames : tuple of Frame
        The frames, in order.
    """

    def __init__(self, info: SequenceInfo, identity: DatasetIdentity, frames: tuple[Frame, ...]) -> None:
        self._info = info
        self._identity = identity
        self.frame_list = frames

    @classmethod
    def head(cls, sequence: Sequence, n_frames: int) -> FrameList:
        """The first ``n_frames`` frames of ``sequence``, read once."""
        frames = tuple(islice(sequence.frames(), n_frames))
        info = dataclasses.replace(sequence.info, n_frames=len(frames))
        return cls(info, sequence.identity, frames)

    @property
    def info(self) -> SequenceInfo:
        return self._info

    @property
    def identity(self) -> DatasetIdentity:
        return self._identity

    def frames(self) -> Iterator[Frame]:
        return iter(self.frame_list)


@dataclass(frozen=True)
class Subject:
    """A tracker with everything its checks need, prepared once.

    Attributes
    ----------
    entry : TrackerEntry
        The tracker and its parameters.
    modalities : Mapping
        The registered modalities, by name.
    frames : FrameList or None
        A few frames of the tracker's modality; None if none could be found.
    model : Any
        For a tracker that learns, the model it fitted on a few training frames.
    problem : str
        Why the frames or the model could not be prepared; empty when they were.
    random_frames : int
        Frames of each random sequence :func:`check_random_sequences` draws.
    """

    entry: TrackerEntry
    modalities: Mapping[str, Modality]
    frames: FrameList | None = None
    model: Any = None
    problem: str = ""
    random_frames: int = RANDOM_FRAMES

    @property
    def name(self) -> str:
        """The tracker's name, for messages."""
        return self.entry.name

    def fail(self, text: str) -> AssertionError:
        """An assertion error naming the tracker."""
        return AssertionError(f"tracker {self.name!r}: {text}")

    def skip(self, reason: str) -> NotApplicable:
        """The exception that says the check does not apply to this tracker, and why."""
        return NotApplicable(reason)

    def ready(self) -> tuple[Modality, FrameList]:
        """The modality and the frames, or an assertion error saying why the runs cannot happen."""
        if self.problem or self.frames is None:
            raise self.fail(f"cannot run: {self.problem or 'no frames'}")
        return self.modalities[self.entry.modality], self.frames

    def attempt(self, function: Callable[[], T], phase: str, *, saying: str = "") -> T:
        """``function()``'s value; whatever it raises, but what the kit lets through, fails the check.

        The failure names the tracker and says ``saying`` followed by the
        fault, or, without ``saying``, the fault and ``phase`` in parentheses.
        """
        call = Call.of(function, phase, reraise=PASS_THROUGH)
        if not call.ok:
            raise self.fail(f"{saying}{call.summary}" if saying else call.message)
        return call.value()

    def create(self) -> Tracker:
        """A fresh instance, with the fitted model adopted if the tracker learns."""

        def created() -> Tracker:
            tracker = self.entry.create()
            if self.model is not None:
                tracker.use_model(self.model)  # type: ignore[attr-defined]
            return tracker

        return self.attempt(created, "creating an instance", saying="creating an instance raised ")

    def run(
        self,
        tracker: Tracker,
        frames: FrameList | SequenceOf[Frame] | None = None,
        *,
        seed: int = SEED,
        truth: bool = True,
        label: str = "",
    ) -> list[Any]:
        """Reset ``tracker`` and step it over ``frames`` (default: the subject's); the estimates.

        ``frames`` is a :class:`FrameList` of another sequence, or frames
        standing in for the subject's own.  ``truth`` hands the first
        frame's truth to ``reset`` as the runner's ``--init truth`` does.
        The generator is the runner's for ``seed`` on the sequence.
        ``label`` says in messages what the frames are (``"'blank' observations"``).
        """
        _, own = self.ready()
        source = frames if isinstance(frames, FrameList) else own
        steps = source.frame_list if frames is None or isinstance(frames, FrameList) else frames
        suffix = f", {label}" if label else ""
        rng = self.rng(seed, source)
        init = steps[0].truth if truth else None

        def played() -> list[Any]:
            Call.of(lambda: tracker.reset(source.info, rng, init=init), f"reset{suffix}", **_TRACKER_CALL).value()
            return [
                Call.of(lambda: tracker.step(frame), f"step, frame {frame.index}{suffix}", frame.index, **_TRACKER_CALL)
                .value()
                for frame in steps
            ]

        ran = Call.of(played, "run", **_TRACKER_CALL)
        if ran.ending == "timeout":
            raise CheckTimeout(ran.message)
        if not ran.ok:
            raise self.fail(ran.message)
        return ran.value()

    def rng(self, seed: int = SEED, frames: FrameList | None = None) -> np.random.Generator:
        """The generator a cell of this tracker on ``frames`` (default: the subject's) gets for ``seed``."""
        if frames is None:
            _, frames = self.ready()
        return cell_rng(seed, self.name, frames.identity)


def _sequences_of(registry: Registry, modality: str, suites: SequenceOf[str]) -> list[Sequence]:
    found = [seq for name in suites for seq in registry.suites[name].sequences if seq.identity.modality == modality]
    return sorted(found, key=lambda seq: not seq.cache_frames)  # simulated first: a pure function of its spec


def pick_sequence(registry: Registry, modality: str) -> Sequence | None:
    """A registered sequence of ``modality``: from a scored suite and simulated where there is one."""
    suites = sorted(registry.suites, key=lambda name: not registry.suites[name].scored)
    found = _sequences_of(registry, modality, suites)
    return found[0] if found else None


def pick_training(registry: Registry, modality: str, scored: Sequence) -> Sequence | None:
    """A registered sequence of ``modality`` to train on, other than ``scored``.

    The training suite of ``scored``'s suite first, then the training
    splits, then anything else.
    """
    named = [suite.training for suite in registry.suites.values() if scored in suite.sequences and suite.training]
    splits = [name for name, suite in registry.suites.items() if not suite.scored]
    rest = list(registry.suites)
    order = [name for name in dict.fromkeys([*named, *splits, *rest]) if name in registry.suites]
    found = [seq for seq in _sequences_of(registry, modality, order) if seq.identity.key != scored.identity.key]
    return found[0] if found else None


def prepare(
    entry: TrackerEntry,
    registry: Registry,
    sequence: Sequence | None = None,
    n_frames: int = DEFAULT_FRAMES,
    random_frames: int = RANDOM_FRAMES,
) -> Subject:
    """The subject of the checks of ``entry``: frames of its modality and, if it learns, a fitted model.

    Parameters
    ----------
    entry : TrackerEntry
        The tracker to check.
    registry : Registry
        Where its modality, and the sequences when ``sequence`` is None, come from.
    sequence : Sequence, optional
        The sequence to take frames from; by default a registered one (:func:`pick_sequence`).
    n_frames : int
        Frames read from it (and from the training sequence).
    random_frames : int
        Frames of each random sequence.

    Returns
    -------
    Subject
        With :attr:`Subject.problem` set, rather than raising, when something is missing.
    """
    modalities = dict(registry.modalities)
    subject = Subject(entry, modalities, random_frames=random_frames)
    modality = modalities.get(entry.modality)
    if modality is None:
        return dataclasses.replace(subject, problem=f"modality {entry.modality!r} is not registered")
    if entry.params is None:
        return dataclasses.replace(subject, problem="its default parameters cannot be made")
    source = sequence if sequence is not None else pick_sequence(registry, entry.modality)
    if source is None:
        return dataclasses.replace(subject, problem=f"no registered {entry.modality} sequence to run on")

    def read() -> FrameList:
        frames = FrameList.head(source, n_frames)
        for frame in frames.frame_list:
            modality.check_frame(frame, f"sequence {frames.info.name!r}, frame {frame.index}")
        return frames

    frames, problem = _value_or_problem(read, f"reading {source!r}: ")
    if frames is None:
        return dataclasses.replace(subject, problem=problem)
    if not frames.frame_list:
        return dataclasses.replace(subject, problem=f"sequence {frames.info.name!r} has no frames")
    subject = dataclasses.replace(subject, frames=frames)
    if not learns(entry):
        return subject
    training = pick_training(registry, entry.modality, source)
    if training is None:
        return dataclasses.replace(subject, problem=f"it learns, but no other {entry.modality} sequence trains it")

    def fit() -> Any:
        head = FrameList.head(training, n_frames)
        rng = np.random.default_rng([zlib.crc32(entry.name.encode()), head.identity.seed_material])
        return entry.create().fit([head], rng)  # type: ignore[attr-defined]

    model, problem = _value_or_problem(fit, f"fit on {training!r} raised ")
    if problem:
        return dataclasses.replace(subject, problem=problem)
    packages = storage.packages_of(entry.tracker_class)
    try:  # as a run stores the model and every cell reads it back
        model = storage.loads(storage.dumps(model, packages), packages, "the fitted model")
    except storage.StorageError as exc:
        return dataclasses.replace(subject, problem=f"its fitted model cannot be stored: {exc}")
    return dataclasses.replace(subject, model=model)


def _value_or_problem(function: Callable[[], T], saying: str) -> tuple[T | None, str]:
    """``function()``'s value and no problem, or None and ``saying`` followed by the fault (see :meth:`Subject.attempt`)."""
    call = Call.of(function, saying, reraise=PASS_THROUGH)
    return (call.value(), "") if call.ok else (None, f"{saying}{call.summary}")


def same(a: Any, b: Any) -> bool:
    """Whether two estimates are equal, field by field, NaN equal to NaN.

    Handles None, dataclasses, arrays, floats, mappings and sequences;
    anything else is compared with ``==``.
    """
    if type(a) is not type(b):
        return False
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        return all(same(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a))
    if isinstance(a, np.ndarray):
        if a.shape != b.shape or a.dtype != b.dtype:
            return False
        numeric = a.dtype.kind in "fc"
        return bool(np.array_equal(a, b, equal_nan=numeric))
    if isinstance(a, float | np.floating):
        return bool(a == b or (math.isnan(a) and math.isnan(b)))
    if isinstance(a, Mapping):
        return a.keys() == b.keys() and all(same(a[key], b[key]) for key in a)
    if isinstance(a, list | tuple):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    return bool(a == b)


def first_difference(frames: FrameList, first: SequenceOf[Any], second: SequenceOf[Any]) -> str:
    """Where two runs' estimates first differ (``"at frame k: a vs b"``), or ``""`` when they agree."""
    if len(first) != len(second):
        return f"in length: {len(first)} vs {len(second)} estimates"
    for frame, a, b in zip(frames.frame_list, first, second):
        if not same(a, b):
            return f"at frame {frame.index}: {a} vs {b}"
    return ""


def check_metadata(subject: Subject) -> str:
    """Name and version are non-empty strings, the modality is registered, ``Params`` makes valid defaults.

    Raises
    ------
    AssertionError
        Naming the first attribute that breaks the contract.
    """
    cls = subject.entry.tracker_class
    for attribute in ("name", "version", "modality"):
        value = getattr(cls, attribute, None)
        if not isinstance(value, str) or not value:
            raise subject.fail(f"class {cls.__name__} must set a non-empty str {attribute!r}, not {value!r}")
    if cls.modality not in subject.modalities:
        known = ", ".join(subject.modalities) or "none"
        raise subject.fail(f"modality {cls.modality!r} is not registered (registered: {known})")
    params = getattr(cls, "Params", None)
    if not (isinstance(params, type) and dataclasses.is_dataclass(params) and params.__dataclass_params__.frozen):
        raise subject.fail(f"Params must be a frozen dataclass, not {params!r}")
    for attribute in ("deterministic", "starts_without_truth"):
        if not isinstance(getattr(cls, attribute, False), bool):
            raise subject.fail(f"{attribute} must be True or False, not {getattr(cls, attribute)!r}")
    expected = getattr(cls, "expected_failed_checks", {})
    known = [check.name for check in CHECKS]
    if not isinstance(expected, Mapping) or not all(
        name in known and isinstance(reason, str) and reason.strip() for name, reason in expected.items()
    ):
        raise subject.fail(
            f"expected_failed_checks must map names of checks ({', '.join(known)}) to the reason each fails, "
            f"not {expected!r}"
        )
    saying = "the default parameters do not validate: "
    defaults = subject.attempt(cls.make_params, "making the default parameters", saying=saying)
    return f"{cls.name} {cls.version}, {cls.modality}, {len(dataclasses.fields(defaults))} parameters"


def _valid_run(
    subject: Subject, frames: FrameList | SequenceOf[Frame] | None = None, *, truth: bool = True, label: str = ""
) -> tuple[list[Any], int]:
    """A fresh instance's estimates over ``frames`` (as :meth:`Subject.run`), and how many are not None.

    Raises
    ------
    AssertionError
        Unless every estimate is None or valid for the modality, naming the frame and ``label``.
    """
    modality, own = subject.ready()
    estimates = subject.run(subject.create(), frames, truth=truth, label=label)
    steps = own.frame_list if frames is None else frames.frame_list if isinstance(frames, FrameList) else frames
    suffix = f", {label}" if label else ""
    for frame, estimate in zip(steps, estimates):
        saying = f"invalid estimate at frame {frame.index}{suffix}: "
        subject.attempt(lambda: modality.check_estimate(estimate), "checking the estimate", saying=saying)
    return estimates, sum(estimate is not None for estimate in estimates)


def check_runs(subject: Subject) -> str:
    """Reset, then step over the frames; every estimate is None or valid for the modality.

    Raises
    ------
    AssertionError
        If the tracker raises or returns an invalid estimate, naming the frame.
    """
    _, frames = subject.ready()
    estimates, detected = _valid_run(subject)
    return f"{detected} estimates in {len(estimates)} frames of {frames.info.name}"


def _without_truth(frames: SequenceOf[Frame]) -> list[Frame]:
    return [dataclasses.replace(frame, truth=None) for frame in frames]


def check_frames_without_truth(subject: Subject) -> str:
    """The tracker never reads the frames' truth.

    With the truth removed from every frame but the first (which ``init``
    hands to ``reset``), every estimate is valid and equal to the one the
    frames with truth give.

    Raises
    ------
    AssertionError
        If the tracker raises or returns an invalid estimate without truth,
        or an estimate changes when the truth is taken away: it reads
        ``frame.truth``.
    """
    _, frames = subject.ready()
    blind_frames = [frames.frame_list[0], *_without_truth(frames.frame_list[1:])]
    blind, detected = _valid_run(subject, blind_frames, label="truth only for init")
    with_truth = subject.run(subject.create())
    difference = first_difference(frames, with_truth, blind)
    if difference:
        raise subject.fail(f"its estimates change when the frames' truth is taken away {difference}: it reads frame.truth")
    return f"{detected} valid estimates without truth, the same whether frames carry truth or not"


def check_starts_without_truth(subject: Subject) -> str:
    """Without ``init`` and without truth on any frame, the tracker runs and every estimate is valid.

    Skipped for a tracker that declares ``starts_without_truth = False``.

    Raises
    ------
    AssertionError
        If the tracker raises or returns an invalid estimate, naming the frame.
    NotApplicable
        If the tracker declares that it needs the first frame's truth.
    """
    _, frames = subject.ready()
    if not getattr(subject.entry.tracker_class, "starts_without_truth", True):
        raise subject.skip("declares starts_without_truth = False: it needs the first frame's truth")
    estimates, detected = _valid_run(subject, _without_truth(frames.frame_list), truth=False, label="no init, no truth")
    return f"{detected} valid estimates in {len(estimates)} frames without init or truth"


def check_same_seed_same_output(subject: Subject) -> str:
    """Two fresh instances run with generators of the same seed give identical estimates.

    Raises
    ------
    AssertionError
        Naming the first frame where the runs differ.
    """
    _, frames = subject.ready()
    first = subject.run(subject.create())
    second = subject.run(subject.create())
    difference = first_difference(frames, first, second)
    if difference:
        raise subject.fail(f"two runs with seed {SEED} differ {difference}")
    return f"{len(first)} identical estimates"


def check_seed_matters(subject: Subject) -> str:
    """Another seed changes a stochastic tracker's estimates, and leaves a deterministic one's alone.

    A tracker declares that it draws no random numbers with the class
    attribute ``deterministic = True`` (:class:`benchmark.tracker.Tracker`).
    A tracker that does not, yet gives the same estimates with two seeds,
    ignores the generator handed to ``reset``: its randomness comes from
    elsewhere, or it has none and should say so.

    Raises
    ------
    AssertionError
        If the runs with seeds 0 and 1 agree for a stochastic tracker, or differ for a deterministic one.
    """
    _, frames = subject.ready()
    first = subject.run(subject.create())
    other = subject.run(subject.create(), seed=SEED + 1)
    difference = first_difference(frames, first, other)
    seeds = f"seeds {SEED} and {SEED + 1}"
    if getattr(subject.entry.tracker_class, "deterministic", False):
        if difference:
            raise subject.fail(f"declares itself deterministic, but runs with {seeds} differ {difference}")
        return f"deterministic: {seeds} give identical estimates"
    if not difference:
        raise subject.fail(
            f"runs with {seeds} give identical estimates: draw every random number from the rng handed to "
            "reset, or declare the class deterministic (deterministic = True) if it draws none"
        )
    return f"stochastic: {seeds} differ {difference.split(':')[0]}"


def _numpy_state_equal(a: tuple[Any, ...], b: tuple[Any, ...]) -> bool:
    return len(a) == len(b) and all(same(np.asarray(x), np.asarray(y)) for x, y in zip(a, b))


@contextmanager
def global_random_state_kept() -> Iterator[None]:
    """Restore NumPy's legacy global generator and Python's ``random`` when the body ends."""
    numpy_state, python_state = np.random.get_state(), random.getstate()
    try:
        yield
    finally:
        np.random.set_state(numpy_state)
        random.setstate(python_state)


def check_no_global_randomness(subject: Subject) -> str:
    """Creating and running the tracker leaves NumPy's and Python's global random state unchanged.

    Raises
    ------
    AssertionError
        Naming the global generator the tracker used.
    """
    subject.ready()
    numpy_before, python_before = np.random.get_state(), random.getstate()
    with global_random_state_kept():
        subject.run(subject.create())
        numpy_after, python_after = np.random.get_state(), random.getstate()
    used = [
        *(["NumPy's global generator (np.random.*)"] if not _numpy_state_equal(numpy_before, numpy_after) else []),
        *(["Python's random module"] if python_before != python_after else []),
    ]
    if used:
        raise subject.fail(f"draws from {' and '.join(used)}; use only the rng handed to reset")
    return "global random state unchanged"


def _reversed(frames: SequenceOf[Frame]) -> list[Frame]:
    """Another sequence of the same modality: the observations, truth and navigation in reverse order."""
    backwards = list(reversed(frames))
    return [dataclasses.replace(back, index=frame.index, time_s=frame.time_s) for frame, back in zip(frames, backwards)]


def check_reset_leaves_no_state(subject: Subject) -> str:
    """On one instance, run A, then B, then A again: both runs of A are identical.

    A is the subject's frames, B the same frames in reverse order with
    another seed.

    Raises
    ------
    AssertionError
        Naming the first frame where the second run of A differs.
    """
    _, frames = subject.ready()
    tracker = subject.create()
    first = subject.run(tracker)
    subject.run(tracker, _reversed(frames.frame_list), seed=SEED + 1)
    again = subject.run(tracker)
    difference = first_difference(frames, first, again)
    if difference:
        raise subject.fail(f"reset keeps state from the previous sequence: a rerun differs {difference}")
    return f"{len(first)} identical estimates after another sequence"


def check_hard_observations(subject: Subject) -> str:
    """Observations without signal (the modality's :data:`~benchmark.modality.HardObservations`) raise nothing.

    For each kind the modality makes (camera: blank, saturated, noise;
    sonar: no returns, NaN beams, spikes, flat seabed, noise; stereo: a lost
    target, a decoy, and blank, saturated and noisy image pairs), the middle
    third of the frames gets that observation in place of its own, so the
    tracker meets it with a track and must go on after it.  Estimates must
    stay None or valid: a NaN state fails.

    Raises
    ------
    AssertionError
        Naming the kind of observation and the frame.
    """
    modality, frames = subject.ready()
    if modality.hard_observations is None:
        return f"modality {modality.name!r} declares no hard observations"
    own = frames.frame_list
    counts = []
    for kind, label, hard in _hard_runs(subject):
        counts.append(f"{kind} {_valid_run(subject, hard, label=label)[1]}")
    start, stop = _hard_stretch(own)
    return f"estimates with each kind in the middle {stop - start} of {len(own)} frames: {', '.join(counts)}"


def _hard_stretch(frames: SequenceOf[Frame]) -> tuple[int, int]:
    """The middle third of the frames, where hard observations replace the frames' own."""
    return len(frames) // 3, len(frames) - len(frames) // 3


def _hard_runs(subject: Subject) -> list[tuple[str, str, list[Frame]]]:
    """For each kind of hard observation: its name, a label for messages, and the frames with the middle third replaced.

    Raises
    ------
    AssertionError
        If the modality cannot make them (not the tracker's fault).
    """
    modality, frames = subject.ready()
    if modality.hard_observations is None:
        return []
    own = frames.frame_list
    start, stop = _hard_stretch(own)
    rng = np.random.default_rng(SEED)
    make = modality.hard_observations
    made = subject.attempt(
        lambda: [make(frame, frames.info, rng) if start <= index < stop else {} for index, frame in enumerate(own)],
        "making hard observations",
        saying=f"modality {modality.name!r} could not make hard observations (not the tracker's fault): ",
    )
    runs = []
    for kind in dict.fromkeys(kind for observations in made for kind in observations):
        hard = [
            dataclasses.replace(frame, observation=observations[kind]) if kind in observations else frame
            for frame, observations in zip(own, made)
        ]
        runs.append((kind, f"{kind!r} observations in frames {own[start].index}-{own[stop - 1].index}", hard))
    return runs


def _describe(info: SequenceInfo) -> str:
    """A sequence's name with what tells random ones apart: its seed and frame size, where it has them."""
    facts = [f"seed {info.extra['seed']}"] if "seed" in info.extra else []
    if info.frame_size is not None:
        facts.append("x".join(map(str, info.frame_size)) + " px")
    return f"{info.name!r}" + (f" ({', '.join(facts)})" if facts else "")


def check_random_sequences(subject: Subject) -> str:
    """Runs on a few random sequences of the modality (its :data:`~benchmark.modality.ExampleSequences`) are valid.

    Hypothesis draws :data:`RANDOM_EXAMPLES` sequences of up to
    ``subject.random_frames`` frames (:data:`RANDOM_FRAMES` unless the
    caller chose another length) from random scenes, the same ones on every
    call (derandomised, no example database); the tracker runs on each
    from its first frame's truth, and every estimate must be None or valid.

    Raises
    ------
    AssertionError
        Naming the random sequence, its description and the frame.
    """
    from hypothesis import HealthCheck, Phase, given, settings

    modality, _ = subject.ready()
    if modality.example_sequences is None:
        return f"modality {modality.name!r} declares no example sequences"
    seen: list[tuple[int, int]] = []

    @settings(
        max_examples=RANDOM_EXAMPLES,
        derandomize=True,
        database=None,
        deadline=None,
        phases=(Phase.generate,),
        suppress_health_check=list(HealthCheck),
        print_blob=False,
    )
    @given(modality.example_sequences(subject.random_frames))
    def runs_on(sequence: Sequence) -> None:
        frames = FrameList.head(sequence, subject.random_frames)
        label = f"random sequence {_describe(frames.info)}"
        estimates, detected = _valid_run(subject, frames, label=label)
        seen.append((len(estimates), detected))

    runs_on()
    return f"{sum(n for n, _ in seen)} frames of {len(seen)} random sequences: {sum(d for _, d in seen)} estimates"


def check_pickles(subject: Subject) -> str:
    """The entry, and an instance at the start, the middle and the end of the frames, round-trip through pickle.

    After each of those frames the copy's next estimate must equal the
    original's: a tracker that opens a file or starts a thread part way
    through is caught where it does.

    Raises
    ------
    AssertionError
        Naming what could not be pickled and after which frame, or the frame where the copy differs.
    """
    _, frames = subject.ready()
    saying = "its registry entry does not pickle: "
    subject.attempt(lambda: pickle.loads(pickle.dumps(subject.entry)), "pickling", saying=saying)
    steps = frames.frame_list
    points = sorted({1, len(steps) // 2, len(steps) - 1} - {0}) or [1]
    for point in points:
        tracker = subject.create()
        subject.run(tracker, steps[:point])
        after = steps[min(point, len(steps)) - 1].index
        saying = f"an instance after frame {after} does not pickle: "
        copy = subject.attempt(lambda: pickle.loads(pickle.dumps(tracker)), "pickling", saying=saying)
        if point >= len(steps):
            continue
        following = steps[point]
        original, copied = subject.attempt(
            lambda: (tracker.step(following), copy.step(following)), f"step after pickling, frame {following.index}"
        )
        if not same(original, copied):
            raise subject.fail(f"the unpickled instance's estimate at frame {following.index} differs: {copied}")
    return f"pickled after frames {', '.join(str(steps[min(p, len(steps)) - 1].index) for p in points)}; the copies step alike"


def check_step_time(subject: Subject) -> str:
    """Milliseconds per ``step``, for the report; never fails."""

    def timed() -> str:
        _, frames = subject.ready()
        tracker = subject.create()
        tracker.reset(frames.info, subject.rng(), init=frames.frame_list[0].truth)
        elapsed = 0.0
        for frame in frames.frame_list:
            tick = time.perf_counter()
            tracker.step(frame)
            elapsed += time.perf_counter() - tick
        return f"{1000.0 * elapsed / len(frames.frame_list):.2f} ms per frame over {len(frames.frame_list)} frames"

    ended = Call.of(timed, "timing", reraise=PASS_THROUGH)
    return ended.value() if ended.ok else f"not timed: {ended.summary}"


def _belief_problems(tracker: Tracker) -> tuple[list[str], list[str]]:
    """The kinds of belief ``tracker`` exposes right now (a None belief is not one), and what is wrong with them."""
    kinds: list[str] = []
    problems: list[str] = []
    if isinstance(tracker, ParticleBelief):
        particles, weights = tracker.particles, tracker.weights
        if particles is not None or weights is not None:
            kinds.append("particle")
            problems += particle_belief_problems(particles, weights)
    if isinstance(tracker, GaussianBelief):
        mean, covariance = tracker.mean, tracker.covariance
        if mean is not None or covariance is not None:
            kinds.append("Gaussian")
            problems += gaussian_belief_problems(mean, covariance)
    return kinds, problems


UpdateProblems = Callable[[Any, Any], list[str]]

UPDATES: tuple[tuple[type, str, str, str, UpdateProblems], ...] = (
    (ParticleUpdate, "particle", "prior_particles", "particles", particle_update_problems),
    (GaussianUpdate, "Gaussian", "prior_covariance", "covariance", gaussian_update_problems),
)
"""Each kind of update the kit compares: its protocol, name, prior and posterior attributes, and what judges them."""


def _update_problems(tracker: Tracker) -> tuple[list[str], list[str]]:
    """The kinds of update whose prior ``tracker`` exposes for its latest step, and what is wrong with them.

    A prior of None (no update this step) is not one; a prior without a
    posterior belief is a problem.
    """
    kinds: list[str] = []
    problems: list[str] = []
    for protocol, kind, prior_name, posterior_name, judge in UPDATES:
        prior = getattr(tracker, prior_name) if isinstance(tracker, protocol) else None
        if prior is None:
            continue
        kinds.append(kind)
        posterior = getattr(tracker, posterior_name)
        missing = [f"it exposes {prior_name} but no {posterior_name}"]
        problems += missing if posterior is None else judge(prior, posterior)
    return kinds, problems


def check_belief_invariants(subject: Subject) -> str:
    """A belief the tracker exposes keeps its invariants after ``reset`` and every ``step``, and so do its updates.

    A tracker exposes its belief through :class:`~benchmark.testing.beliefs.ParticleBelief`
    (weights finite, non-negative, summing to one, effective sample size in
    ``[1, N]``, particles finite) or :class:`~benchmark.testing.beliefs.GaussianBelief`
    (mean and covariance finite, covariance symmetric and positive
    semi-definite).  It is checked along the frames, and along the frames
    with each kind of hard observation in their middle third, where a
    tracker loses its target and coasts (a variance that goes negative only
    while lost shows there).  A belief of None (no start yet, target lost)
    is not checked; for a tracker that satisfies neither protocol the check
    does not apply (:class:`NotApplicable`).  A run that raises on hard
    observations is left to :func:`check_hard_observations`.

    After every step, a tracker that also exposes the prior of that step's
    measurement update (:class:`~benchmark.testing.beliefs.GaussianUpdate`,
    :class:`~benchmark.testing.beliefs.ParticleUpdate`) has the update
    checked: the posterior covariance no wider than the prior in the
    Loewner order, every posterior particle one of the predicted set.  The
    detail says how many updates were compared.

    Raises
    ------
    AssertionError
        Naming the run, and the first point (after reset, or the frame) where the belief breaks an invariant
        or the frame whose update does.
    """
    _, frames = subject.ready()
    tally = _BeliefTally()
    runs: list[tuple[str, str, list[Frame]]] = [("", "", frames.frame_list)]
    declared = declares_belief(subject.entry.tracker_class)
    if declared:
        try:
            runs += _hard_runs(subject)
        except AssertionError:  # the modality cannot make them: check_hard_observations says so
            pass
    for kind, label, steps in runs:
        ended = _observe_beliefs(subject, frames.info, steps, label, tally)
        if not ended.ok and not kind:  # a hard run's fault: the hard_observations check reports it
            raise subject.fail(ended.message)
    kinds, updated, held, points, updates = tally.kinds, tally.updated, tally.held, tally.points, tally.updates
    if not declared and not kinds:
        raise subject.skip("exposes no belief (neither ParticleBelief nor GaussianBelief)")
    checked = (
        f"prior and posterior compared at {updates} {' and '.join(sorted(updated))} updates"
        if updates
        else "no update exposed its prior"
    )
    return (
        f"{' and '.join(sorted(kinds)) or 'no'} belief held at {held} of {points} points "
        f"({len(runs)} runs: reset and each frame); {checked}"
    )


@dataclass
class _BeliefTally:
    """What :func:`check_beliefs` saw over its runs."""

    kinds: set[str] = dataclasses.field(default_factory=set)
    updated: set[str] = dataclasses.field(default_factory=set)
    held: int = 0
    points: int = 0
    updates: int = 0


_BELIEF_CALL: dict[str, Any] = {"reraise": (*PASS_THROUGH, AssertionError)}
"""How :func:`_observe_beliefs` calls a tracker: its own failures, raised as assertion errors, go through."""


def _observe_beliefs(
    subject: Subject, info: SequenceInfo, steps: list[Frame], label: str, tally: _BeliefTally
) -> Call[None]:
    """Run a fresh instance over ``steps``, checking its belief after reset and each step; how the run ended.

    Raises
    ------
    AssertionError
        Naming the point where the belief, or an update, breaks an invariant.
    """
    tracker = subject.create()
    among = f", {label}" if label else ""

    def observe(frame: Frame | None) -> None:
        if frame is not None:
            tracker.step(frame)
        now, problems = _belief_problems(tracker)
        if problems:
            point = "after reset" if frame is None else f"at frame {frame.index}"
            raise subject.fail(f"its {' and '.join(now)} belief is broken {point}{among}: {'; '.join(problems)}")
        tally.kinds.update(now)
        tally.held += bool(now)
        tally.points += 1
        if frame is None:
            return
        compared, problems = _update_problems(tracker)
        if problems:
            raise subject.fail(
                f"its {' and '.join(compared)} measurement update is broken at frame {frame.index}{among}: "
                + "; ".join(problems)
            )
        tally.updated.update(compared)
        tally.updates += bool(compared)

    def observed() -> None:
        rng = subject.rng()

        def reset() -> None:
            tracker.reset(info, rng, init=steps[0].truth)
            observe(None)

        Call.of(reset, "reset, reading the belief", **_BELIEF_CALL).value()
        for frame in steps:
            phase = f"step, frame {frame.index}, reading the belief"
            Call.of(lambda: observe(frame), phase, frame.index, **_BELIEF_CALL).value()

    return Call.of(observed, "reading the belief", **_BELIEF_CALL)


CheckFunction = Callable[[Subject], str]


@dataclass(frozen=True)
class Check:
    """One named check.

    Attributes
    ----------
    name : str
        Its name in reports (``"pickles"``).
    function : callable
        ``function(subject) -> str``: a line of detail, or
        :class:`AssertionError` naming the tracker and what broke, or
        :class:`NotApplicable`.
    after : tuple of str
        The checks whose failure makes this one fail too: where one of them
        failed, this one's failure is reported as following from it.
    """

    name: str
    function: CheckFunction
    after: tuple[str, ...] = ()

    def __call__(self, subject: Subject) -> str:
        return self.function(subject)


_RUNS = ("runs",)
_REPEATS = ("runs", "same_seed_same_output")
CHECKS: tuple[Check, ...] = (
    Check("metadata", check_metadata),
    Check("runs", check_runs, after=("metadata",)),
    Check("same_seed_same_output", check_same_seed_same_output, after=_RUNS),
    Check("frames_without_truth", check_frames_without_truth, after=_REPEATS),
    Check("starts_without_truth", check_starts_without_truth, after=_RUNS),
    Check("seed_matters", check_seed_matters, after=_REPEATS),
    Check("no_global_randomness", check_no_global_randomness, after=_RUNS),
    Check("reset_leaves_no_state", check_reset_leaves_no_state, after=_REPEATS),
    Check("hard_observations", check_hard_observations, after=_RUNS),
    Check("random_sequences", check_random_sequences, after=_RUNS),
    Check("pickles", check_pickles, after=_REPEATS),
    Check("hash_seed", check_hash_seed, after=_REPEATS),
    Check("belief_invariants", check_belief_invariants, after=_RUNS),
    Check("step_time", check_step_time, after=_RUNS),
)
"""Every check, in the order they run: a check comes after every check it names in ``after``."""


def prerequisites(name: str) -> list[str]:
    """The checks check ``name`` comes after, directly or through others, in the order they run."""
    after = {check.name: check.after for check in CHECKS}
    found: set[str] = set()
    pending = list(after.get(name, ()))
    while pending:
        earlier = pending.pop()
        if earlier not in found:
            found.add(earlier)
            pending.extend(after.get(earlier, ()))
    return [check.name for check in CHECKS if check.name in found]
