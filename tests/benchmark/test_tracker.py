import dataclasses

import pytest

from benchmark.errors import ParameterError
from benchmark.tracker import Tracker, params_key


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


def test_string_overrides_are_converted_to_the_type_of_the_default():
    params = Knobbed.make_params({"sigma": "1.5", "count": "7", "enabled": "yes", "label": "abc"})
    assert params == Knobs(1.5, 7, True, "abc")


def test_unknown_parameter_names_tracker_and_parameter():
    with pytest.raises(ParameterError, match=r"'knobbed'.*'sigmaa'.*known: sigma, count"):
        Knobbed.make_params({"sigmaa": 1})


@pytest.mark.parametrize("key, value", [("count", "many"), ("enabled", "perhaps"), ("sigma", "1,5")])
def test_unconvertible_value_names_the_parameter(key, value):
    with pytest.raises(ParameterError, match=repr(key)):
        Knobbed.make_params({key: value})


def test_cache_key_changes_with_parameters_and_version():
    base = params_key("knobbed", "1.0", Knobs())
    assert base == params_key("knobbed", "1.0", Knobs())
    assert base != params_key("knobbed", "1.0", Knobs(sigma=2.0))
    assert base != params_key("knobbed", "1.1", Knobs())
    assert base != params_key("other", "1.0", Knobs())
