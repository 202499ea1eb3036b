"""The modules every tracker shares: what a plugin replaces in them is named and put back, what it adds is left."""

from __future__ import annotations

import math
import random
import os
import sys

import numpy as np
import pytest

from benchmark.shared_modules import Snapshot, seed_global_generators


def test_replaced_and_removed_names_and_numpy_s_error_handling_are_named_and_put_back() -> None:
    mean, sqrt, errors = np.mean, math.sqrt, np.geterr()
    snapshot = Snapshot.take()
    assert snapshot.changes() == []
    try:
        np.mean = lambda *args, **kwargs: 0.0
        del math.sqrt
        np.seterr(divide="raise")
        np.added_by_a_plugin = "new"  # additions are left alone
        assert sorted(snapshot.changes()) == ["math.sqrt", "numpy.mean", "numpy.seterr"]
        assert sorted(snapshot.restore()) == ["math.sqrt", "numpy.mean", "numpy.seterr"]
        assert (np.mean, math.sqrt, np.geterr()) == (mean, sqrt, errors)
        assert np.added_by_a_plugin == "new" and snapshot.changes() == []
    finally:
        np.mean, math.sqrt = mean, sqrt
        np.seterr(**errors)
        vars(np).pop("added_by_a_plugin", None)


def test_an_extended_snapshot_keeps_what_it_knew_and_adds_modules_loaded_since(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delitem(sys.modules, "math")
    early = Snapshot.take()
    assert "math" not in early.names
    monkeypatch.undo()
    assert "math" in early.extended().names and early.extended().names["numpy"] is early.names["numpy"]


def test_a_changed_working_folder_is_named_and_put_back(tmp_path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    monkeypatch.chdir(tmp_path)
    snapshot = Snapshot.take()
    (tmp_path / "elsewhere").mkdir()
    os.chdir(tmp_path / "elsewhere")
    assert snapshot.changes() == ["the working folder"]
    assert snapshot.restore() == ["the working folder"] and os.getcwd() == str(tmp_path)
    assert snapshot.in_folder_now().folder == str(tmp_path) and snapshot.changes() == []


def test_seeding_the_globals_twice_gives_the_same_draws() -> None:
    numpy_state, python_state = np.random.get_state(), random.getstate()
    try:
        seed_global_generators([11])
        first = (np.random.random(3), random.random())
        np.random.random(5)
        seed_global_generators([11])
        again = (np.random.random(3), random.random())
    finally:
        np.random.set_state(numpy_state)
        random.setstate(python_state)
    assert np.array_equal(first[0], again[0]) and first[1] == again[1]
