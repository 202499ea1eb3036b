"""Text from plugins and data files made safe to print: control characters escaped, one line where asked.

Kept apart from the boards (:mod:`benchmark.report.display`) so that the
command line prints its warnings and errors without importing pandas.
"""

from __future__ import annotations

import re

_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")
"""Control characters but tab and newline: C0, DEL and C1, terminal escapes (ESC, CSI) among them."""


def printable(text: object) -> str:
    r"""``text`` with every control character but tab and newline written as an escape, ``\x1b`` for ESC.

    Names and messages come from plugins and data files; shown raw, their
    escape sequences would recolour, retitle or rewrite the user's terminal.

    Examples
    --------
    >>> print(printable("\x1b[31mred\x07"))
    \x1b[31mred\x07
    """
    return _CONTROL.sub(lambda match: match.group().encode("unicode_escape").decode("ascii"), str(text))


def one_line(text: object) -> str:
    """``text`` on one line, printable: runs of whitespace, newlines included, become one space (:func:`printable`)."""
    return printable(" ".join(str(text).split()))


def shortened(text: str, width: int) -> str:
    """``text`` cut to ``width`` characters, an ellipsis marking the cut."""
    return text if len(text) <= width else text[: max(width - 1, 0)] + "\u2026"


def counted(count: int, noun: str) -> str:
    """``count`` and ``noun``, plural unless one: ``1 tracker``, ``3 datasets``."""
    return f"{count} {noun}{'' if count == 1 else 's'}"
