"""The hash-seed check on fake trackers run here and in a fresh interpreter.

The trackers live in ``hash_seed_plugin.py``, installed for each test as
the module ``acme_hash_seed`` of a temporary site folder, which the fresh
interpreter finds through this process's ``sys.path``.
"""

from __future__ import annotations

import dataclasses
import importlib
import importlib.util
import json
import os
import shutil
import sys
import types
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from benchmark.registry import TrackerEntry
from benchmark.testing import Check, Subject, prepare, run_check
from benchmark.testing.checks import NotApplicable
from benchmark.testing.hash_seed import OTHER_HASH_SEEDS, check_hash_seed, hash_seed_here

PLUGIN_SOURCE = Path(__file__).with_name("hash_seed_plugin.py")
N_FRAMES = 6


@pytest.fixture(scope="module")
def acme(tmp_path_factory: pytest.TempPathFactory) -> Iterator[types.ModuleType]:
    """The module ``acme_hash_seed``, importable here and, through ``sys.path``, in a fresh interpreter.

    Imported once: records look a type up once per process (``benchmark.storage``).
    """
    site = tmp_path_factory.mktemp("site")
    shutil.copy(PLUGIN_SOURCE, site / "acme_hash_seed.py")
    with pytest.MonkeyPatch.context() as patch:
        patch.syspath_prepend(str(site))
        yield importlib.import_module("acme_hash_seed")
    sys.modules.pop("acme_hash_seed", None)


def subject_of(tracker: type, fakes: types.ModuleType, params: dict[str, Any] | None = None) -> Subject:
    """``tracker`` with the first frames of a fake camera sequence."""
    entry = TrackerEntry(tracker.name, tracker, tracker.make_params(params))
    return prepare(entry, fakes.make_registry(()), fakes.FakeSequence("fake/S1", N_FRAMES), n_frames=N_FRAMES)


def other_seed() -> int:
    return next(seed for seed in OTHER_HASH_SEEDS if str(seed) != hash_seed_here())


def test_an_estimate_that_follows_the_order_of_a_set_of_strings_fails_naming_the_frame_and_the_seeds(
    acme: types.ModuleType, fakes: types.ModuleType
) -> None:
    with pytest.raises(AssertionError) as failure:
        check_hash_seed(subject_of(acme.SetOrdered, fakes))
    message = str(failure.value)
    assert message.startswith("tracker 'set-ordered': its estimates depend on the hash seed")
    assert f"here (PYTHONHASHSEED={hash_seed_here()})" in message
    assert f"in a fresh interpreter (PYTHONHASHSEED={other_seed()})" in message
    assert f"differ at frame {acme.FROM_FRAME}:" in message


def test_a_correct_tracker_passes_with_its_parameters_model_and_spawned_generator_handed_over(
    acme: types.ModuleType, fakes: types.ModuleType
) -> None:
    subject = dataclasses.replace(subject_of(acme.Drifting, fakes, {"offset_px": 1.5}), model={"bias_px": -2.0})
    detail = check_hash_seed(subject)
    assert detail == (
        f"{N_FRAMES} identical estimates here (PYTHONHASHSEED={hash_seed_here()}) "
        f"and in a fresh interpreter (PYTHONHASHSEED={other_seed()})"
    )


def test_a_tracker_class_defined_in_a_function_is_not_checked(acme: types.ModuleType, fakes: types.ModuleType) -> None:
    class Local(acme.Drifting):
        name = "local"

    with pytest.raises(NotApplicable) as skipped:
        check_hash_seed(subject_of(Local, fakes))
    assert str(skipped.value).startswith("not checked: its class ")
    assert "<locals>.Local is defined inside a function" in str(skipped.value)


def test_a_module_a_fresh_interpreter_cannot_import_is_not_checked(tmp_path: Path, fakes: types.ModuleType) -> None:
    spec = importlib.util.spec_from_file_location("acme_elsewhere", PLUGIN_SOURCE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["acme_elsewhere"] = module  # importable here only: its folder is not on sys.path
    try:
        spec.loader.exec_module(module)
        with pytest.raises(NotApplicable) as skipped:
            check_hash_seed(subject_of(module.Drifting, fakes))
    finally:
        del sys.modules["acme_elsewhere"]
    assert str(skipped.value) == (
        "not checked: its module 'acme_elsewhere' cannot be imported in a fresh interpreter: "
        "no finder finds 'acme_elsewhere'"
    )


HOSTED = """
import sys

from acme_hash_seed import Drifting

if "acme_host" not in sys.modules:
    {without_host}


class Hosted(Drifting):
    name = "hosted"
"""
"""A plugin module that needs a module only this process has (which a test puts in ``sys.modules``)."""


@pytest.mark.parametrize(
    ("name", "without_host", "verdict"),
    [
        (
            "acme_hosted_0",
            "import acme_host",
            "not checked: its module 'acme_hosted_0' cannot be imported in a fresh interpreter: "
            "ModuleNotFoundError: No module named 'acme_host'",
        ),
        (
            "acme_hosted_1",
            "raise RuntimeError('no host')",
            "tracker 'hosted': in a fresh interpreter (PYTHONHASHSEED={seed}), though not here: importing its "
            "module 'acme_hosted_1' in a fresh interpreter raised RuntimeError: no host",
        ),
    ],
    ids=["import error: not checked", "other error: fails"],
)
def test_a_module_that_imports_here_only(
    acme: types.ModuleType,
    fakes: types.ModuleType,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    name: str,
    without_host: str,
    verdict: str,
) -> None:
    (tmp_path / f"{name}.py").write_text(HOSTED.format(without_host=without_host))
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setitem(sys.modules, "acme_host", types.ModuleType("acme_host"))
    hosted = importlib.import_module(name)
    try:
        try:
            outcome = check_hash_seed(subject_of(hosted.Hosted, fakes))
        except (AssertionError, NotApplicable) as failure:
            outcome = str(failure)
    finally:
        del sys.modules[name]
    assert outcome == verdict.format(seed=other_seed())


def test_a_tracker_that_raises_in_the_fresh_interpreter_fails_with_its_error(
    acme: types.ModuleType, fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(acme.HomeOnly, "home_pid", os.getpid())
    with pytest.raises(AssertionError) as failure:
        check_hash_seed(subject_of(acme.HomeOnly, fakes))
    assert str(failure.value) == (
        f"tracker 'home-only': in a fresh interpreter (PYTHONHASHSEED={other_seed()}), though not here: "
        f"RuntimeError: runs only in process 0 (step, frame 0)"
    )


def test_a_tracker_that_spins_in_the_fresh_interpreter_fails_as_a_hang(
    acme: types.ModuleType, fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(acme.SpinsAway, "home_pid", os.getpid())
    result = run_check(Check("hash_seed", check_hash_seed), subject_of(acme.SpinsAway, fakes), time_limit_s=1.0)
    assert not result.ok
    assert result.message.endswith("does it hang?"), result.message


def test_the_fresh_interpreter_imports_neither_the_kit_nor_pytest_nor_pandas(
    acme: types.ModuleType, fakes: types.ModuleType, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    census = tmp_path / "modules.json"
    monkeypatch.setenv(acme.CENSUS_VARIABLE, str(census))
    monkeypatch.setattr(acme.Census, "home_pid", os.getpid())
    check_hash_seed(subject_of(acme.Census, fakes))
    loaded = set(json.loads(census.read_text()))
    assert {"acme_hash_seed", "benchmark.storage"} <= loaded
    assert not {name for name in loaded if name.startswith(("benchmark.testing", "pytest", "pandas", "hypothesis"))}
