"""The data model every modality shares: frames, sequences and outcomes.

A dataset is a :class:`Sequence`: a :class:`SequenceInfo` and a stream of
:class:`Frame` objects, produced one at a time so that nothing holds a whole
video in memory.  Each frame carries the sensor's observation, the
navigation data the platform reports, and the ground truth.

What an observation, a truth and an estimate are depends on the sensor and
is declared by its modality (:class:`benchmark.modality.Modality`): the
camera's cable states, the sonar's swaths and the stereo camera's target
measurements live under :mod:`benchmark.modalities`.  :class:`Frame` is
generic in its observation and truth types, and each modality names its own
frame type (``CameraFrame = Frame[numpy.ndarray, CameraTruth]``), so that a
tracker states what it reads.
"""

from __future__ import annotations

import dataclasses
import enum
from abc import ABC, abstractmethod
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar, Generic, TypeVar

from benchmark.identity import DatasetIdentity, digest

if TYPE_CHECKING:
    from benchmark.results import LoopValues


class Outcome(enum.StrEnum):
    """Per-frame detection outcome (seeds/004, section VI-C, Table V)."""

    CORRECT = "correct"
    FALSE = "false"
    MISSED = "missed"


ObsT = TypeVar("ObsT")
TruthT = TypeVar("TruthT")


@dataclass(frozen=True)
class Frame(Generic[ObsT, TruthT]):
    """One time step of a sequence.

    Attributes
    ----------
    index : int
        Position in the sequence, from 0.
    observation : ObsT
        What the sensor delivered, of the type the sequence's modality
        declares (a grey image, a swath, a stereo measurement, ...).
    truth : TruthT or None
        Ground truth of the modality's truth type, or None when the frame is
        unlabelled.
    navigation : Any
        Navigation data where the platform has it (vehicle speeds, the chase
        boat's GPS and heading), else None.
    time_s : float
        Time stamp in s from the start of the sequence.
    """

    index: int
    observation: ObsT
    truth: TruthT | None = None
    navigation: Any = None
    time_s: float = 0.0


@dataclass(frozen=True)
class SequenceInfo:
    """What a tracker may know about a sequence before its first frame.

    Attributes
    ----------
    name : str
        Name used in results: ``suite/sequence`` or the path of a file.
    modality : str
        Name of the registered modality the frames come from (``"camera"``,
        ``"sonar"``, ``"stereo"``, or a plugin's).
    n_frames : int or None
        Number of frames, where known in advance.
    frame_size : tuple of int or None
        Images: ``(W, H)`` in px.
    frame_interval_s : float or None
        Time between frames.
    calibration : Any
        The sensor's calibration, of the modality's type, where the data set
        knows it.
    extra : Mapping
        Anything else a data set wants to tell (description, source).
    """

    name: str
    modality: str
    n_frames: int | None = None
    frame_size: tuple[int, int] | None = None
    frame_interval_s: float | None = None
    calibration: Any = None
    extra: Mapping[str, Any] = field(default_factory=dict)


INFO_FIELDS: frozenset[str] = frozenset(item.name for item in dataclasses.fields(SequenceInfo))
"""The names of :class:`SequenceInfo`'s fields: what a tracker may declare it :attr:`~benchmark.tracker.Tracker.needs`."""


class Sequence(ABC):
    """A stream of frames with its :class:`SequenceInfo`.

    Implementations produce frames lazily and must be picklable (cells run in
    worker processes), so they hold a definition or a path, never decoded
    frames.

    Attributes
    ----------
    cache_frames : bool
        The frames are a pure function of :attr:`identity` and worth keeping
        once produced (simulated scenes): a run reads them through its frame
        cache (:mod:`benchmark.frame_cache`).  False for data read from files.
    closed_loop : bool
        The frames depend on the estimates: after each frame is scored the
        runner hands the tracker's estimate to :meth:`steer`, and the next
        frame is made from where it steered the vehicle
        (:mod:`benchmark.closedloop`).  Such frames are never cached.
    """

    cache_frames: ClassVar[bool] = False
    closed_loop: ClassVar[bool] = False

    @property
    @abstractmethod
    def info(self) -> SequenceInfo:
        """Describe the sequence."""

    @abstractmethod
    def frames(self) -> Iterator[Frame]:
        """Yield the frames in order, one at a time."""

    @property
    def identity(self) -> DatasetIdentity:
        """What the sequence is, known without reading a frame (:mod:`benchmark.identity`).

        Cells are keyed, resumed and seeded by it.  This default knows only
        the sequence's class and name, taken from :attr:`info`; sequences
        read from files or simulated from a spec override it with their
        resolved path and file fingerprint, or their generator and spec, and
        so never read data to name themselves.
        """
        info = self.info
        generator = f"{type(self).__module__}.{type(self).__qualname__}"
        return DatasetIdentity(info.name, info.modality, source=generator, fingerprint=digest(info.name))

    def steer(self, estimate: Any, busy_s: float = 0.0) -> LoopValues | None:
        """Take the estimate of the frame :meth:`frames` yielded last; only a :attr:`closed_loop` sequence uses it.

        ``busy_s`` is how long the tracker was busy with that frame in
        real-time mode (:mod:`benchmark.closedloop.real_time`), 0 otherwise.

        Returns
        -------
        LoopValues or None
            A closed-loop sequence gives the vehicle's values at that frame
            (:class:`benchmark.results.LoopValues`), which the runner adds to
            the frame's score; None otherwise.
        """
        return None

    def lacks(self, needs: Iterable[str]) -> dict[str, str]:
        """Of the :class:`SequenceInfo` fields ``needs`` (a tracker's :attr:`~benchmark.tracker.Tracker.needs`), those the sequence does not give.

        It is asked in the coordinating process before any cell runs, so
        that a tracker that cannot run on a sequence is reported instead of
        failing in every cell.  This default reads :attr:`info`, which
        costs nothing for a sequence defined by a spec; a sequence that
        reads a frame to describe itself (a frame size from its first
        image) answers from what it holds instead, and tells how its data
        could give what is missing.

        Returns
        -------
        dict
            Field name to a phrase that names what is missing and, where the
            sequence knows, how to add it (``"camera calibration: add
            focal_px, pipe_diameter_m, tilt_deg under [camera] in S.toml"``).
        """
        info = self.info
        return {need: need for need in needs if getattr(info, need) is None}

    def conditions(self) -> Mapping[str, Any]:
        """The conditions the sequence was made under, by name, for boards that split results by them.

        It is asked in the coordinating process, outside any cell's time
        limit, so this default reads no data and knows nothing; a simulated
        scene gives what it drew (:mod:`benchmark.scenes.draws`) and may add
        what it measures of itself (a camera scene its cable's contrast),
        rendering a frame or two but never reading a file.
        """
        return {}

    def __iter__(self) -> Iterator[Frame]:
        return self.frames()

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.identity.name!r}>"
