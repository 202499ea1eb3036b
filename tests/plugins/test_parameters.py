"""Every first-party tracker's parameters: declared domains, command-line text, refusal before any cell runs.

Each tracker's ``Params`` is a pydantic dataclass whose fields declare their
ranges and choices; :meth:`benchmark.tracker.Tracker.make_params` (and with
it ``TrackerEntry.with_params``, which ``--param`` goes through) turns a
value outside them into a :class:`~benchmark.errors.ParameterError` naming
the tracker and the parameter.
"""

from __future__ import annotations

import dataclasses
import re
import sqlite3
from typing import Annotated

import pydantic
import pytest
from annotated_types import Gt
from click.testing import CliRunner
from trackbench_condensation import CondensationTracker
from trackbench_stereo_raw import StereoRawParams, StereoRawTracker

import benchmark.harness
from benchmark.cli import main
from benchmark.errors import ParameterError
from benchmark.modalities.stereo.modality import STEREO
from benchmark.registry import Registry
from benchmark.store import DATABASE_NAME

FIRST_PARTY = {"hough", "condensation", "sonar", "stereo_ekf", "stereo_raw"}
"""The plugins of this repository that register trackers."""

REFUSED = [
    ("hough", "log_sigma", 0.0),
    ("hough", "closeness_weight", 1.5),
    ("hough", "max_misses", 0),
    ("hough", "min_width_px", 200.0),
    ("hough-paper", "partner_fraction", 0.5),
    ("condensation", "n_particles", 0),
    ("condensation", "filter_size_px", 4),
    ("condensation", "init_w_px", (10.0, 1.0)),
    ("condensation", "resampler", "lottery"),
    ("condensation", "var_w_px2", -1.0),
    ("condensation-thesis", "lost_threshold", 2.0),
    ("condensation-fast", "filter_size_px", 1),
    ("condensation-8d", "var_v_w_px2", float("inf")),
    ("condensation-centre", "centre_weight", -1.0),
    ("sonar_detector", "fit_span", 1.5),
    ("sonar_detector", "spike_window", 2.5),
    ("sonar_pf", "inject_fraction", 1.5),
    ("sonar_pf", "resampler", "bogus"),
    ("sonar_detector-paper", "spike_window", 2.5),
    ("sonar_pf-paper", "inject_fraction", 1.5),
    ("stereo_ekf", "covariance", "eq19"),
    ("stereo_ekf", "sigma_a_mps2", 0.0),
    ("stereo_ekf-paper", "beyond_range_inflation", 0.5),
    ("stereo_ekf-eq18", "frontend_block_size", 8),
    ("stereo_raw", "window", 0),
    ("stereo_raw", "frontend_hue_max", 180),
    ("stereo_raw", "frontend_num_disparities", 24),
    ("stereo_raw", "frontend_hue_min", 50),
]
"""``(registered tracker, parameter, a value outside its declared domain)``: bounds, choices and cross-field rules."""


def first_party_trackers(registry: Registry) -> list[str]:
    return [name for name, entry in registry.trackers.items() if entry.origin.plugin in FIRST_PARTY]


def test_every_first_party_tracker_declares_its_parameters_with_pydantic(plugin_registry):
    names = first_party_trackers(plugin_registry)
    assert len(names) == 15
    for name in names:
        assert pydantic.dataclasses.is_pydantic_dataclass(plugin_registry.trackers[name].tracker_class.Params), name
    # Every registered first-party tracker has a refused value below.
    assert set(names) == {name for name, _, _ in REFUSED}


@pytest.mark.parametrize(("name", "parameter", "value"), REFUSED, ids=[f"{n}.{p}" for n, p, _ in REFUSED])
def test_a_value_outside_the_declared_domain_is_refused_naming_tracker_and_parameter(
    plugin_registry, name, parameter, value
):
    entry = plugin_registry.trackers[name]
    cls = entry.tracker_class
    pattern = rf"tracker '{cls.name}'.*{parameter}"
    with pytest.raises(ParameterError, match=pattern):
        entry.with_params({parameter: value})
    # The same value as command-line text.
    with pytest.raises(ParameterError, match=pattern):
        entry.with_params({parameter: str(value)})
    with pytest.raises(ParameterError, match=pattern):
        cls.make_params({parameter: value})
    # Built directly, the parameters refuse it too.
    with pytest.raises(pydantic.ValidationError, match=parameter):
        dataclasses.replace(entry.params, **{parameter: value})


def test_a_bad_variant_is_a_problem_of_its_plugin_at_registration_and_left_out():
    registry = Registry()
    registry.add_modality(STEREO)
    assert registry.add_tracker(StereoRawTracker, name="stereo_raw-none", params={"window": 0}) is None
    assert re.search(r"tracker 'stereo_raw'.*'window'", registry.problems[0])
    assert "stereo_raw-none" not in registry.trackers


def test_a_bad_parameter_on_the_command_line_stops_the_run_before_any_cell(tmp_path, monkeypatch):
    started = []
    monkeypatch.setattr(benchmark.harness, "run_benchmark", lambda *args, **kwargs: started.append(args))
    result = CliRunner().invoke(
        main,
        [
            "run",
            "--tracker",
            "condensation",
            "--dataset",
            "camera/S3",
            "--param",
            "condensation.n_particles=0",
            "--out",
            str(tmp_path),
        ],
    )
    assert result.exit_code == 2, result.output
    errors = [line for line in result.output.splitlines() if line.startswith("Error:")]
    assert len(errors) == 1
    assert "'condensation'" in errors[0] and "'n_particles'" in errors[0] and "got 0" in errors[0]
    assert started == []
    database = tmp_path / DATABASE_NAME
    if database.exists():
        with sqlite3.connect(database) as connection:
            assert connection.execute("SELECT COUNT(*) FROM cells").fetchone() == (0,)


def test_command_line_text_of_a_tuple_arrives_as_a_tuple_of_floats(plugin_registry):
    entry = plugin_registry.trackers["condensation"]
    for text in ("(-100, 100)", "[-100, 100]", " (-100, 100.0) "):
        limits = entry.with_params({"init_d_px": text}).params.init_d_px
        assert limits == (-100.0, 100.0) and isinstance(limits, tuple)
        assert [type(value) for value in limits] == [float, float]
        assert CondensationTracker.make_params({"init_d_px": text}).init_d_px == limits
    # The other parameters keep the entry's values.
    fast = plugin_registry.trackers["condensation-fast"].with_params({"init_d_px": "(-100, 100)"}).params
    assert (fast.n_particles, fast.filter_size_px) == (300, 5)
    for text in ("wide", "(1, 2, 3)", "(-100, inf)"):
        with pytest.raises(ParameterError, match="'init_d_px'"):
            entry.with_params({"init_d_px": text})


def test_command_line_text_of_numbers_arrives_as_their_declared_types(plugin_registry):
    ekf = plugin_registry.trackers["stereo_ekf"].with_params({"sigma_a_mps2": "1", "frontend_block_size": "9"}).params
    assert ekf.sigma_a_mps2 == 1.0 and type(ekf.sigma_a_mps2) is float
    assert ekf.frontend_block_size == 9 and type(ekf.frontend_block_size) is int
    sonar = plugin_registry.trackers["sonar_pf"].with_params({"walk_sigma_m": "0.25", "n_particles": "40"}).params
    assert (sonar.walk_sigma_m, sonar.n_particles) == (0.25, 40)
    # No first-party number is optional: "none" is refused, naming the parameter.
    with pytest.raises(ParameterError, match="'walk_sigma_m'"):
        plugin_registry.trackers["sonar_pf"].with_params({"walk_sigma_m": "none"})


@pydantic.dataclasses.dataclass(frozen=True)
class GatedRawParams(StereoRawParams):
    """The raw baseline's parameters and an optional number, as a plugin extending the baseline would declare them."""

    gate_m: Annotated[float, Gt(0)] | None = None
    """Largest jump between consecutive positions, m; None: no gate."""


class GatedRaw(StereoRawTracker):
    """The raw baseline under another name, with :class:`GatedRawParams`."""

    name = "stereo_raw-gated"
    Params = GatedRawParams


def test_an_optional_number_of_an_extended_first_party_params_arrives_as_none_or_a_float():
    registry = Registry()
    registry.add_modality(STEREO)
    entry = registry.add_tracker(GatedRaw)
    assert entry.params.gate_m is None and entry.params.window == 15
    for text in ("none", "None", "null"):
        assert entry.with_params({"gate_m": text}).params.gate_m is None
    gated = entry.with_params({"gate_m": "2.5"}).params
    assert gated.gate_m == 2.5 and type(gated.gate_m) is float
    assert GatedRaw.make_params({"gate_m": "3"}).gate_m == 3.0
    with pytest.raises(ParameterError, match=r"'stereo_raw-gated'.*'gate_m'"):
        entry.with_params({"gate_m": "0"})
    # The inherited domains and rules (three pydantic dataclasses deep) still hold.
    with pytest.raises(ParameterError, match=r"'stereo_raw-gated'.*frontend_block_size must be odd"):
        entry.with_params({"frontend_block_size": "8"})
    with pytest.raises(ParameterError, match=r"'stereo_raw-gated'.*'window'"):
        entry.with_params({"window": "0"})
    assert GatedRaw(gated)._front_end.block_size == 11
