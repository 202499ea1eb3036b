"""Records: values written as data and read back bit for bit, without running code from the file."""

from __future__ import annotations

import enum
import io
import json
import math
import pickle
import struct
import sys
import zlib
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from benchmark import storage
from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.model import Frame, Outcome
from benchmark.storage import StorageError

OURS = storage.packages_of(Frame)
TESTS = storage.packages_of(Frame) | {"tests"}


class Colour(enum.IntEnum):
    RED = 1
    BLUE = 2


@dataclass(frozen=True)
class Pair:
    left: Any
    right: Any = None


def same(a: Any, b: Any) -> bool:
    """Equal in type and value, NaN equal to NaN, arrays equal in dtype, shape and bytes."""
    if type(a) is not type(b):
        return False
    if isinstance(a, np.ndarray):
        return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()
    if isinstance(a, float | np.floating):
        return (math.isnan(a) and math.isnan(b)) or (a == b and math.copysign(1, a) == math.copysign(1, b))
    if isinstance(a, list | tuple):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, dict):
        return list(a) == list(b) and all(same(a[k], b[k]) for k in a)
    if isinstance(a, Pair):
        return same(a.left, b.left) and same(a.right, b.right)
    return bool(a == b)


arrays = hnp.arrays(
    st.sampled_from(["u1", "i2", "<i8", ">i4", "f4", "<f8", "c16", "?"]).map(np.dtype),
    hnp.array_shapes(min_dims=0, max_dims=3, min_side=0, max_side=5),
)
leaves = (
    st.none()
    | st.booleans()
    | st.integers(-(2**70), 2**70)
    | st.floats(allow_nan=True, allow_infinity=True)
    | st.text(max_size=8)
    | st.sampled_from([Colour.RED, Colour.BLUE, Outcome.CORRECT])
    | arrays
    | st.builds(np.float32, st.floats(width=32))
    | st.builds(np.int64, st.integers(-(2**63), 2**63 - 1))
)
values = st.recursive(
    leaves,
    lambda inner: st.lists(inner, max_size=4)
    | st.lists(inner, max_size=4).map(tuple)
    | st.dictionaries(st.text(max_size=4) | st.integers(), inner, max_size=4)
    | st.builds(Pair, inner, inner),
    max_leaves=12,
)


@settings(max_examples=150, deadline=None)
@given(values)
def test_any_storable_value_comes_back_equal_in_type_and_value(value: Any) -> None:
    assert same(storage.loads(storage.dumps(value, TESTS), TESTS, "value"), value)


@settings(max_examples=30, deadline=None)
@given(st.lists(values, min_size=1, max_size=4))
def test_a_stream_gives_its_records_one_by_one_then_ends(items: list[Any]) -> None:
    handle = io.BytesIO(b"".join(storage.dumps(item, TESTS) for item in items))
    assert all(same(storage.read(handle, TESTS, "stream"), item) for item in items)
    with pytest.raises(EOFError):
        storage.read(handle, TESTS, "stream")


def test_a_frame_comes_back_bit_for_bit_with_writable_aligned_arrays() -> None:
    image = np.arange(240 * 320, dtype=np.uint8).reshape(240, 320)
    frame = Frame(3, image, CameraTruth(CableState(1.5, -0.25, 40.0, 0.01)), None, 0.12)
    copy = storage.loads(storage.dumps(frame, OURS), OURS, "frame")
    assert pickle.dumps(copy, protocol=5) == pickle.dumps(frame, protocol=5)
    assert copy.observation.flags.writeable and copy.observation.ctypes.data % storage.ALIGNMENT == 0


def record(tree: Any, payload: bytes = b"") -> bytes:
    """A well-formed record holding ``tree`` as written, whatever it says."""
    structure = json.dumps(tree).encode()
    checksum = zlib.crc32(payload, zlib.crc32(structure))
    return struct.pack("<4sIQI", storage.MAGIC, len(structure), len(payload), checksum) + structure + payload


@pytest.mark.parametrize(
    ("tree", "says"),
    [
        ({"$data": ["os:system", {}]}, "outside the packages"),
        ({"$data": ["subprocess:Popen", {"args": "true"}]}, "outside the packages"),
        ({"$data": ["benchmark.storage:dumps", {}]}, "is not a dataclass"),
        ({"$enum": ["benchmark.model:Frame", 1]}, "is not an enum"),
        ({"$data": ["benchmark.model:Nothing", {}]}, "does not exist"),
        ({"$data": ["benchmark.model:Frame", {"spin": 1}]}, "refuses the stored fields"),
        ({"$array": ["|O", [1]]}, "numbers and bools only"),
        ({"$array": ["<f8", [1000]]}, "runs past"),
        ({"$array": ["<f8", [-1]]}, "shape"),
        ({"$code": "print(1)"}, "unknown marker"),
        ({"$tuple": [], "$dict": []}, "one marker"),
    ],
)
def test_a_record_naming_what_it_may_not_is_refused_naming_the_file(tree: Any, says: str) -> None:
    before = set(sys.modules)
    with pytest.raises(StorageError, match=f"^planted.rec: .*{says}"):
        storage.loads(record(tree), OURS, "planted.rec")
    assert not {"subprocess", "os"} & (set(sys.modules) - before)


def test_a_record_never_imports_a_module_outside_its_packages() -> None:
    assert "antigravity" not in sys.modules
    with pytest.raises(StorageError, match="outside the packages"):
        storage.loads(record({"$data": ["antigravity:geohash", {}]}), OURS, "planted.rec")
    assert "antigravity" not in sys.modules


@pytest.mark.parametrize(
    ("spoil", "says"),
    [
        (lambda data: data[:-1], "cut short"),
        (lambda data: data[:10], "cut short"),
        (lambda data: data[:-1] + bytes([data[-1] ^ 1]), "checksum"),
        (lambda data: pickle.dumps([1, 2]), "not a trackbench record"),
        (lambda data: data + b"x", "bytes follow"),
        (lambda data: b"", "empty"),
    ],
)
def test_a_damaged_record_is_refused_naming_the_file(spoil: Any, says: str) -> None:
    data = storage.dumps({"weights": np.linspace(0, 1, 7)}, OURS)
    with pytest.raises(StorageError, match=f"^model.rec: .*{says}"):
        storage.loads(spoil(data), OURS, "model.rec")


@pytest.mark.parametrize(
    ("value", "says"),
    [
        (object(), "builtins.object"),
        (np.array([object()]), "numbers and bools only"),
        (Pair(1), "tests.benchmark.test_storage:Pair"),
        (lambda: 0, "function"),
        (b"bytes", "builtins.bytes"),
    ],
)
def test_what_a_record_cannot_hold_is_refused_when_written(value: Any, says: str) -> None:
    with pytest.raises(StorageError, match=f"cannot store .*{says}"):
        storage.dumps(value, OURS)


def test_the_packages_of_a_class_are_benchmark_and_those_of_its_bases_outside_the_standard_library() -> None:
    class Mine(Pair):
        pass

    assert storage.packages_of(Mine) == {"benchmark", "tests"}
    assert storage.packages_of(Frame, enum.Enum) == {"benchmark"}
