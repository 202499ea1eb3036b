"""The tracker contract every plugin implements.

A tracker class declares who it is (``name``, ``version``, ``modality``) and
its parameters as a frozen dataclass ``Params`` whose defaults are the
published values.  The harness creates one instance per cell, calls
:meth:`Tracker.reset` once and :meth:`Tracker.step` once per frame::

    tracker = entry.create()
    tracker.reset(info, rng, init=first_truth_or_none)
    for frame in sequence:
        estimate = tracker.step(frame)   # None: no detection this frame

All randomness must come from the ``rng`` handed to :meth:`Tracker.reset`,
so that a seed replays a run bit for bit.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import typing
from abc import ABC, abstractmethod
from collections.abc import Iterable, Mapping
from typing import Any, ClassVar

import numpy as np

from benchmark.errors import ParameterError
from benchmark.model import Frame, Modality, Sequence, SequenceInfo


@dataclasses.dataclass(frozen=True)
class NoParams:
    """Parameters of a tracker that has none."""


class Tracker(ABC):
    """Base class of all trackers, first-party and third-party alike.

    Class attributes
    ----------------
    name : str
        Unique name in leaderboards and on the command line.
    version : str
        Bumped whenever results may change; part of the cache key.
    modality : {"camera", "sonar", "stereo"}
        The observations the tracker reads.
    Params : type
        A frozen dataclass whose fields, with defaults, are the parameters.
    """

    name: ClassVar[str]
    version: ClassVar[str]
    modality: ClassVar[Modality]
    Params: ClassVar[type] = NoParams

    def __init__(self, params: Any = None) -> None:
        self.params = params if params is not None else self.Params()

    @classmethod
    def defaults(cls) -> dict[str, Any]:
        """Parameter names with their default values, in declaration order."""
        return dataclasses.asdict(cls.Params())

    @classmethod
    def make_params(cls, overrides: Mapping[str, Any] | None = None) -> Any:
        """Build ``Params`` from defaults and overrides.

        Values given as strings (from the command line) are converted to the
        type of the default.

        Raises
        ------
        ParameterError
            For a name ``Params`` does not declare or a value that does not
            convert; the message names the tracker and the parameter.
        """
        overrides = dict(overrides or {})
        fields = {f.name: f for f in dataclasses.fields(cls.Params)}
        unknown = sorted(set(overrides) - set(fields))
        if unknown:
            known = ", ".join(fields) or "none"
            raise ParameterError(
                f"tracker {cls.name!r} has no parameter {', '.join(map(repr, unknown))} (known: {known})"
            )
        defaults = cls.Params()
        hints = typing.get_type_hints(cls.Params)
        converted = {
            key: _convert(cls.name, key, value, getattr(defaults, key), hints.get(key))
            for key, value in overrides.items()
        }
        return dataclasses.replace(defaults, **converted)

    def fit(self, training: Iterable[Sequence]) -> None:  # noqa: B027 - optional hook
        """Learn from labelled training sequences; only learning trackers override it."""

    @abstractmethod
    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        """Prepare for a new sequence.

        Parameters
        ----------
        info : SequenceInfo
            What is known of the sequence before its first frame.
        rng : numpy.random.Generator
            The only source of randomness the tracker may use.
        init : optional
            The first frame's whole ground-truth object (camera: a
            ``CameraTruth``) when the run initialises from truth
            (``--init truth``), otherwise None.
        """

    @abstractmethod
    def step(self, frame: Frame) -> Any:
        """Process one frame and return the estimate, or None for no detection."""


def _convert(tracker: str, key: str, value: Any, default: Any, hint: Any) -> Any:
    target = type(default) if default is not None else hint
    if not isinstance(value, str) or target is str or not isinstance(target, type):
        return value
    try:
        if target is bool:
            lowered = value.strip().lower()
            if lowered not in {"1", "0", "true", "false", "yes", "no", "on", "off"}:
                raise ValueError(value)
            return lowered in {"1", "true", "yes", "on"}
        if target in (tuple, list):
            return target(json.loads(value))
        return target(value)
    except (TypeError, ValueError) as exc:
        raise ParameterError(
            f"tracker {tracker!r}: parameter {key!r} expects {target.__name__}, got {value!r}"
        ) from exc


def params_key(name: str, version: str, params: Any) -> str:
    """Hash of a tracker's name, version and parameters: the results cache key."""
    payload = json.dumps(
        {"name": name, "version": version, "params": dataclasses.asdict(params)},
        sort_keys=True,
        default=repr,
    )
    return hashlib.sha256(payload.encode()).hexdigest()[:16]
