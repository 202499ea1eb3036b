"""Values kept on disk and read back without running code from them: cached frames, fitted models.

Pickle rebuilds whatever a file names, so a file planted in a cache or a
results folder would be a program run by the next reader.  A *record*
holds one value as data only:

What a record may hold
    None, bools, ints, floats (NaN and the infinities too), strings, lists,
    tuples, dicts, numpy arrays and scalars of numbers or bools, enum
    members, and dataclass instances; nested as deep as they like.  Enum
    and dataclass types must be defined in one of the *packages* the writer
    and the reader name (``benchmark`` and the plugin whose values they
    are): a record cannot name anything else.
Reading
    A dataclass is rebuilt by calling its constructor with the stored
    fields, an enum member by its value, an array from its raw bytes.  A
    type is looked up by module and name inside the named packages only, so
    a record can neither import a module outside them nor call anything but
    a constructor of theirs.
Layout
    ``MAGIC``, the structure's length (uint32), the payload's length
    (uint64), the CRC-32 of structure and payload (uint32), all little
    endian; then the structure (UTF-8 JSON, arrays replaced by their dtype
    and shape) and the payload (the arrays' bytes, each starting at a
    multiple of :data:`ALIGNMENT`).  A value is one record; a stream is
    records one after another, each read on its own.
Checking
    A record that is cut short, fails its checksum, or names a type, dtype
    or shape it may not is a :class:`StorageError` naming its file.  The
    checksum is against accident (a truncated write, flipped bits, a file
    put in the wrong place is caught by the identity its reader stores in
    it); a writer can always write a wrong value.

Reading a 320 x 240 camera frame back takes about 40 us against 15-20 us
for ``pickle.load`` (``benchmarks/test_scale.py``, side by side); the
checksum is 15 us of it, and rendering the frame 2.4 ms.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import importlib
import io
import json
import math
import struct
import sys
import zlib
from collections.abc import Callable
from typing import IO, Any

import numpy as np

from benchmark.errors import DataError

MAGIC = b"TBv1"
"""The first bytes of every record."""
ALIGNMENT = 16
"""Every array of a payload starts at a multiple of this many bytes."""
_PREFIX = struct.Struct("<4sIQI")
_NUMBER_KINDS = frozenset("biufc")


class StorageError(DataError):
    """A record that cannot be written or read back: damaged, cut short, or naming what it may not."""


Packages = frozenset[str]
"""Top-level packages whose enum and dataclass types a record may hold."""


def packages_of(*types: type) -> Packages:
    """``benchmark`` and the top-level packages defining ``types`` and their base classes, outside the standard library."""
    tops = {base.__module__.partition(".")[0] for kind in types for base in kind.__mro__}
    return frozenset({"benchmark", *(top for top in tops if top not in sys.stdlib_module_names)})


def dumps(value: Any, packages: Packages) -> bytes:
    """One record holding ``value``.

    Raises
    ------
    StorageError
        Naming the first part of ``value`` a record cannot hold.
    """
    arrays: list[np.ndarray] = []
    structure = json.dumps(_encode(value, _Writer(packages, arrays)), separators=(",", ":")).encode()
    payload = bytearray()
    for array in arrays:
        payload += bytes(-len(payload) % ALIGNMENT)
        payload += array.tobytes()
    checksum = zlib.crc32(payload, zlib.crc32(structure))
    return _PREFIX.pack(MAGIC, len(structure), len(payload), checksum) + structure + payload


def write(handle: IO[bytes], value: Any, packages: Packages) -> None:
    """Append a record holding ``value`` to ``handle``."""
    handle.write(dumps(value, packages))


def read(handle: IO[bytes], packages: Packages, source: str) -> Any:
    """The value of the next record of ``handle``.

    Parameters
    ----------
    handle : binary file
        Positioned at a record's start.
    packages : Packages
        Where the record's types may come from.
    source : str
        The file, for error messages.

    Raises
    ------
    EOFError
        When ``handle`` is at its end.
    StorageError
        Naming ``source``, when the record is cut short, fails its checksum
        or holds what it may not.
    """
    prefix = handle.read(_PREFIX.size)
    if not prefix:
        raise EOFError(source)
    if len(prefix) < _PREFIX.size:
        raise StorageError(f"{source}: a record is cut short")
    magic, structure_size, payload_size, checksum = _PREFIX.unpack(prefix)
    if magic != MAGIC:
        raise StorageError(f"{source}: not a trackbench record (it starts with {magic!r})")
    structure = handle.read(structure_size)
    payload = bytearray(payload_size)
    if len(structure) < structure_size or handle.readinto(payload) < payload_size:
        raise StorageError(f"{source}: a record is cut short")
    if zlib.crc32(payload, zlib.crc32(structure)) != checksum:
        raise StorageError(f"{source}: a record fails its checksum")
    return _decode_record(structure, payload, packages, source)


def loads(data: bytes, packages: Packages, source: str) -> Any:
    """The value of a record made by :func:`dumps` (see :func:`read`); bytes after it are an error."""
    handle = io.BytesIO(data)
    try:
        value = read(handle, packages, source)
    except EOFError:
        raise StorageError(f"{source}: empty") from None
    if handle.read(1):
        raise StorageError(f"{source}: bytes follow the record")
    return value


def _decode_record(structure: bytes, payload: bytearray, packages: Packages, source: str) -> Any:
    reader = _Reader(packages, memoryview(payload))
    try:
        tree = json.loads(structure)
        value = _decode(tree, reader)
    except StorageError as exc:
        raise StorageError(f"{source}: {exc}") from None
    except (ValueError, TypeError, KeyError, IndexError, AttributeError, RecursionError) as exc:
        raise StorageError(f"{source}: malformed record ({type(exc).__name__}: {exc})") from None
    if reader.offset != len(payload):
        raise StorageError(f"{source}: the record's payload holds bytes no array claims")
    return value


# Writing ---------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class _Writer:
    packages: Packages
    arrays: list[np.ndarray]


def _type_name(kind: type, packages: Packages) -> str:
    name = f"{kind.__module__}:{kind.__qualname__}"
    try:
        found = _lookup(name, packages)
    except StorageError:
        found = None
    if found is not kind:
        raise StorageError(f"cannot store a {name}: not a type defined at the top level of {_listed(packages)}")
    return name


def _listed(packages: Packages) -> str:
    return ", ".join(sorted(packages)) or "no package"


@functools.singledispatch
def _encode(value: Any, writer: _Writer) -> Any:
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = {field.name: _encode(getattr(value, field.name), writer) for field in dataclasses.fields(value) if field.init}
        return {"$data": [_type_name(type(value), writer.packages), fields]}
    raise StorageError(f"cannot store a {type(value).__module__}.{type(value).__qualname__}")


@_encode.register(type(None))
@_encode.register(bool)
@_encode.register(int)
@_encode.register(float)
@_encode.register(str)
def _encode_plain(value: Any, writer: _Writer) -> Any:
    return value


@_encode.register(enum.Enum)
@_encode.register(enum.IntEnum)
@_encode.register(enum.StrEnum)
def _encode_enum(value: enum.Enum, writer: _Writer) -> Any:
    return {"$enum": [_type_name(type(value), writer.packages), _encode(value.value, writer)]}


@_encode.register(list)
def _encode_list(value: list[Any], writer: _Writer) -> Any:
    return [_encode(item, writer) for item in value]


@_encode.register(tuple)
def _encode_tuple(value: tuple[Any, ...], writer: _Writer) -> Any:
    if type(value) is not tuple:
        raise StorageError(f"cannot store a {type(value).__qualname__} (a named tuple)")
    return {"$tuple": [_encode(item, writer) for item in value]}


@_encode.register(dict)
def _encode_dict(value: dict[Any, Any], writer: _Writer) -> Any:
    return {"$dict": [[_encode(key, writer), _encode(item, writer)] for key, item in value.items()]}


@_encode.register(np.ndarray)
def _encode_array(value: np.ndarray, writer: _Writer) -> Any:
    dtype = _number_dtype(value.dtype)
    writer.arrays.append(np.ascontiguousarray(value))
    return {"$array": [dtype.str, list(value.shape)]}


@_encode.register(np.generic)
def _encode_scalar(value: np.generic, writer: _Writer) -> Any:
    dtype = _number_dtype(value.dtype)
    item = value.item()
    return {"$scalar": [dtype.str, [item.real, item.imag] if isinstance(item, complex) else item]}


def _number_dtype(dtype: np.dtype[Any]) -> np.dtype[Any]:
    if dtype.kind not in _NUMBER_KINDS or dtype.fields is not None or dtype.subdtype is not None:
        raise StorageError(f"cannot store an array or scalar of dtype {dtype}: numbers and bools only")
    return dtype


# Reading ---------------------------------------------------------------


@dataclasses.dataclass
class _Reader:
    packages: Packages
    payload: memoryview
    offset: int = 0

    def array(self, dtype: np.dtype[Any], shape: tuple[int, ...]) -> np.ndarray:
        start = self.offset + (-self.offset % ALIGNMENT)
        size = dtype.itemsize * math.prod(shape)
        if start + size > len(self.payload):
            raise StorageError("an array runs past the record's payload")
        self.offset = start + size
        return np.frombuffer(self.payload, dtype=dtype, count=size // dtype.itemsize, offset=start).reshape(shape)


def _decode(tree: Any, reader: _Reader) -> Any:
    if isinstance(tree, list):
        return [_decode(item, reader) for item in tree]
    if not isinstance(tree, dict):
        return tree
    if len(tree) != 1:
        raise StorageError(f"an object with keys {sorted(tree)}, where one marker was expected")
    ((marker, body),) = tree.items()
    decoder = _DECODERS.get(marker)
    if decoder is None:
        raise StorageError(f"an unknown marker {marker!r}")
    return decoder(body, reader)


def _decode_data(body: Any, reader: _Reader) -> Any:
    name, fields = body
    kind = _lookup(name, reader.packages)
    if not (dataclasses.is_dataclass(kind) and isinstance(kind, type)):
        raise StorageError(f"{name} is not a dataclass")
    values = {str(key): _decode(value, reader) for key, value in fields.items()}
    try:
        return kind(**values)
    except Exception as exc:
        raise StorageError(f"{name} refuses the stored fields: {type(exc).__name__}: {exc}") from None


def _decode_enum(body: Any, reader: _Reader) -> Any:
    name, value = body
    kind = _lookup(name, reader.packages)
    if not (isinstance(kind, type) and issubclass(kind, enum.Enum)):
        raise StorageError(f"{name} is not an enum")
    return kind(_decode(value, reader))


def _decode_array(body: Any, reader: _Reader) -> np.ndarray:
    code, shape = body
    if not all(isinstance(size, int) and size >= 0 for size in shape):
        raise StorageError(f"an array of shape {shape}")
    return reader.array(_number_dtype(np.dtype(str(code))), tuple(shape))


def _decode_scalar(body: Any, reader: _Reader) -> np.generic:
    code, item = body
    dtype = _number_dtype(np.dtype(str(code)))
    return dtype.type(complex(*item) if dtype.kind == "c" else item)


_DECODERS: dict[str, Callable[[Any, _Reader], Any]] = {
    "$data": _decode_data,
    "$enum": _decode_enum,
    "$tuple": lambda body, reader: tuple(_decode(item, reader) for item in body),
    "$dict": lambda body, reader: {_decode(key, reader): _decode(value, reader) for key, value in body},
    "$array": _decode_array,
    "$scalar": _decode_scalar,
}


@functools.lru_cache(maxsize=256)
def _lookup(name: str, packages: Packages) -> Any:
    """The type ``module:qualname``, imported only when its module lies in ``packages``."""
    module, _, qualname = str(name).partition(":")
    if module.partition(".")[0] not in packages or not qualname or "<" in qualname:
        raise StorageError(f"the type {name!r} lies outside the packages {_listed(packages)}")
    try:
        found: Any = importlib.import_module(module)
        for part in qualname.split("."):
            found = getattr(found, part)
    except (ImportError, AttributeError):
        raise StorageError(f"the type {name!r} does not exist") from None
    return found
