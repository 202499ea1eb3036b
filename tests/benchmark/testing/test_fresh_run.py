"""The parts of a run in a fresh interpreter that need no interpreter: the generator handed over, the global seeds."""

from __future__ import annotations


import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark import storage
from benchmark.testing.fresh_run import generator_record, rebuild_generator

BIT_GENERATORS = ["PCG64", "PCG64DXSM", "MT19937", "Philox", "SFC64"]


@settings(max_examples=40, deadline=None)
@given(
    kind=st.sampled_from(BIT_GENERATORS),
    entropy=st.lists(st.integers(0, 2**64 - 1), min_size=1, max_size=4),
    spawn_key=st.lists(st.integers(0, 2**32 - 1), max_size=2),
    drawn=st.integers(0, 5),
    spawned=st.integers(0, 3),
)
def test_a_rebuilt_generator_draws_and_spawns_as_the_original(
    kind: str, entropy: list[int], spawn_key: list[int], drawn: int, spawned: int
) -> None:
    original = np.random.Generator(getattr(np.random, kind)(np.random.SeedSequence(entropy, spawn_key=spawn_key)))
    original.random(drawn)
    original.spawn(spawned)
    packages = frozenset({"benchmark"})
    record = storage.loads(storage.dumps(generator_record(original), packages), packages, "a generator record")
    rebuilt = rebuild_generator(record)
    assert type(rebuilt.bit_generator) is type(original.bit_generator)
    assert np.array_equal(rebuilt.random(7), original.random(7))
    (child_of_rebuilt,), (child_of_original,) = rebuilt.spawn(1), original.spawn(1)
    assert np.array_equal(child_of_rebuilt.normal(size=5), child_of_original.normal(size=5))


def test_a_generator_record_naming_no_bit_generator_is_refused() -> None:
    record = {**generator_record(np.random.default_rng(3)), "kind": "Generator"}
    with pytest.raises(ValueError, match="'Generator' is not a bit generator of numpy.random"):
        rebuild_generator(record)
