"""Tests of benchmark.tracker: the contract and its parameters' defaults."""

import dataclasses
import inspect

import pytest

from benchmark.errors import ParameterError
from benchmark.tracker import NoParams, Tracker


@dataclasses.dataclass(frozen=True)
class Knobs:
    sigma: float = 3.0
    count: int = 5
    enabled: bool = False
    label: str = "x"


class Knobbed(Tracker):
    name, version, modality = "knobbed", "1.0", "camera"
    Params = Knobs

    def reset(self, info, rng, init=None):
        pass

    def step(self, frame):
        return None


def test_defaults_are_the_params_dataclass_defaults():
    assert Knobbed.defaults() == {"sigma": 3.0, "count": 5, "enabled": False, "label": "x"}
    assert Knobbed().params == Knobs()


def test_fit_is_not_part_of_the_contract():
    assert not hasattr(Tracker, "fit")
    assert Tracker.__abstractmethods__ == frozenset({"reset", "step"})
    assert list(inspect.signature(Tracker.reset).parameters) == ["self", "info", "rng", "init"]


def test_a_tracker_without_params_has_none():
    class Bare(Knobbed):
        name = "bare"
        Params = NoParams

    assert Bare.defaults() == {} and Bare.make_params() == NoParams()
    with pytest.raises(ParameterError, match=r"'bare' has no parameter 'x' \(known: none\)"):
        Bare.make_params({"x": "1"})
