"""Digests of plain data: fields added later with OMIT_AT_DEFAULT leave old digests alone."""

from __future__ import annotations

from dataclasses import dataclass, field

from benchmark.identity import OMIT_AT_DEFAULT, digest


def spec_class(version: str) -> type:
    """A spec class ``Spec`` as first written (``old``), grown with marked fields (``marked``) or an unmarked one."""
    if version == "old":

        @dataclass(frozen=True)
        class Spec:
            a: float = 1.0

    elif version == "marked":

        @dataclass(frozen=True)
        class Spec:  # type: ignore[no-redef]
            a: float = 1.0
            b: int = field(default=0, metadata=OMIT_AT_DEFAULT)
            c: tuple[float, ...] = field(default_factory=tuple, metadata=OMIT_AT_DEFAULT)

    else:

        @dataclass(frozen=True)
        class Spec:  # type: ignore[no-redef]
            a: float = 1.0
            b: int = 0

    return Spec


def test_marked_fields_at_their_defaults_keep_the_digest_of_the_spec_written_before_them() -> None:
    old, marked, unmarked = spec_class("old"), spec_class("marked"), spec_class("unmarked")
    assert digest(marked()) == digest(old())
    assert digest(marked(a=2.0)) == digest(old(a=2.0))
    assert digest(marked(b=1)) != digest(old())
    assert digest(marked(c=(1.0,))) != digest(old())
    assert digest(unmarked()) != digest(old())
