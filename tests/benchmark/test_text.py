"""Tests of benchmark.text: text from plugins and data files made safe to print."""

from __future__ import annotations

import pytest

from benchmark.text import one_line, printable


@pytest.mark.parametrize(
    ("text", "shown"),
    [
        ("\x1b[31mred\x1b[0m", "\\x1b[31mred\\x1b[0m"),
        ("bell\x07 and C1 \x9b2J", "bell\\x07 and C1 \\x9b2J"),
        ("tab\tand\nnewline stay", "tab\tand\nnewline stay"),
        ("accents é and 雪 stay", "accents é and 雪 stay"),
    ],
)
def test_printable_writes_control_characters_as_escapes(text: str, shown: str) -> None:
    assert printable(text) == shown


def test_one_line_is_printable_and_on_one_line() -> None:
    assert one_line("a\n\x1b[2Jb\t c") == "a \\x1b[2Jb c"
