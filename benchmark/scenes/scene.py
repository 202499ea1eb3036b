"""What every simulated sequence shares: a spec, a lazy cache, seeded streams, frames one by one.

A simulated scene is a :class:`benchmark.model.Sequence` defined entirely
by a spec, a frozen dataclass that carries the sequence's name, length,
frame interval and seed.  :class:`SimulatedScene` holds the scaffolding
the scenes of this package have in common:

* construction from the spec, or from a plain mapping through the spec
  class's ``from_dict`` (:attr:`SimulatedScene.spec_type`), after the
  mapping's ``draw`` table is drawn (:mod:`benchmark.scenes.draws`); the
  conditions drawn are kept as :attr:`SimulatedScene.drawn_conditions`;
* a cache of whatever the scene computes once (trajectories, maps, a
  renderer), built on first use by :meth:`SimulatedScene._build_cache` and
  dropped when the scene is pickled, so that the object a worker process
  receives is just its spec;
* independent random streams: :meth:`SimulatedScene._stream` turns a
  spawn key into a generator seeded by ``SeedSequence(spec.seed,
  spawn_key=key)``, so that changing how one stream is used leaves the
  others alone and the same spec gives bit-identical frames;
* frames: :meth:`SimulatedScene.frame` assembles frame ``k`` from the
  scene's :meth:`~SimulatedScene.observation`, :meth:`~SimulatedScene.truth`
  and :meth:`~SimulatedScene.navigation` of that frame, any frame on its
  own, and :meth:`SimulatedScene.frames` yields them in order.

A scene class names its spec type, describes itself in ``info`` and
implements the cache builder and the three per-frame parts.
"""

from __future__ import annotations

import functools
from abc import abstractmethod
from collections.abc import Iterator, Mapping
from typing import Any, ClassVar, Generic, Protocol, Self, TypeVar

import numpy as np

from benchmark.identity import DatasetIdentity, digest, generator_source
from benchmark.model import Frame, Sequence
from benchmark.scenes.draws import Conditions, resolve_draws


class SceneSpec(Protocol):
    """What a scene needs of its spec."""

    name: str
    n_frames: int
    seed: int
    frame_interval_s: float


SpecT = TypeVar("SpecT", bound=SceneSpec)
CacheT = TypeVar("CacheT")


class SimulatedScene(Sequence, Generic[SpecT, CacheT]):
    """A sequence simulated from a spec, with a lazily built cache that pickling drops.

    Parameters
    ----------
    spec : SpecT
        The definition, seed included.
    conditions : Mapping, optional
        The conditions the scene was drawn under (water type, altitude, ...),
        by name; empty for a scene written out in full.

    Attributes
    ----------
    spec_type : type
        The spec class; its ``from_dict(data, source)`` parses a mapping.
    """

    spec_type: ClassVar[Any]
    cache_frames: ClassVar[bool] = True

    def __init__(self, spec: SpecT, conditions: Mapping[str, Any] | None = None) -> None:
        self._spec = spec
        self._conditions: Conditions = dict(conditions or {})
        self._cache: CacheT | None = None

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "<dict>") -> Self:
        """A scene from a plain mapping, its draws drawn; see the ``from_dict`` of :attr:`spec_type`."""
        table, conditions = resolve_draws(data, source)
        return cls(cls.spec_type.from_dict(table, source), conditions)

    @property
    def drawn_conditions(self) -> Conditions:
        """The conditions the scene was drawn under, by name (a copy); empty when it was not drawn."""
        return dict(self._conditions)

    def conditions(self) -> Conditions:
        """The conditions the scene was drawn under (:attr:`drawn_conditions`)."""
        return self.drawn_conditions

    @property
    def spec(self) -> SpecT:
        """The definition of this sequence."""
        return self._spec

    @functools.cached_property
    def identity(self) -> DatasetIdentity:
        """The scene's identity: its generator and version as source, its spec's digest as fingerprint.

        Worked out once: the spec is frozen, and the registry asks every
        sequence's identity each time a suite is added.
        """
        return DatasetIdentity(
            self._spec.name, self.info.modality, source=generator_source(type(self)), fingerprint=digest(self._spec)
        )

    def __getstate__(self) -> dict[str, Any]:
        return {"_spec": self._spec, "_conditions": self._conditions}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self._spec = state["_spec"]
        self._conditions = state.get("_conditions", {})
        self._cache = None

    def _state(self) -> CacheT:
        """The cache, built on first use."""
        if self._cache is None:
            self._cache = self._build_cache()
        return self._cache

    @abstractmethod
    def _build_cache(self) -> CacheT:
        """Compute what the scene keeps while it lives."""

    def _stream(self, *key: int) -> np.random.Generator:
        """The random stream with spawn key ``key`` under the spec's seed."""
        sequence = np.random.SeedSequence(self._spec.seed, spawn_key=key)
        return np.random.Generator(np.random.PCG64(sequence))

    @abstractmethod
    def observation(self, index: int) -> Any:
        """What the sensor delivers at frame ``index``."""

    @abstractmethod
    def truth(self, index: int) -> Any:
        """Ground truth of frame ``index``."""

    @abstractmethod
    def navigation(self, index: int) -> Any:
        """The vehicle's own sensors at frame ``index``."""

    def frame(self, index: int) -> Frame:
        """Frame ``index`` on its own (identical to the one :meth:`frames` yields)."""
        return Frame(
            index=index,
            observation=self.observation(index),
            truth=self.truth(index),
            navigation=self.navigation(index),
            time_s=index * self._spec.frame_interval_s,
        )

    def frames(self) -> Iterator[Frame]:
        """Yield the frames in order, one at a time."""
        for index in range(self._spec.n_frames):
            yield self.frame(index)

    def _check(self, index: int) -> int:
        """``index``, or IndexError naming the sequence when it is not a frame of it."""
        if not 0 <= index < self._spec.n_frames:
            raise IndexError(f"{self._spec.name}: frame {index} out of range 0..{self._spec.n_frames - 1}")
        return index
