"""``trackbench new-tracker``: write the skeleton of a third-party tracker plugin.

:func:`new_tracker` renders the templates of ``benchmark/scaffold/templates``
into ``DIR/NAME/``: a ``pyproject.toml`` that registers the plugin under the
``trackbench`` entry-point group, a package ``trackbench_NAME`` with a
minimal tracker and its ``trackbench_register_trackers`` hook, and a test
that runs the conformance kit (:mod:`benchmark.testing`) in one line.
"""

from __future__ import annotations

import keyword
import re
from dataclasses import dataclass
from pathlib import Path

import jinja2

from benchmark.errors import TrackbenchError
from benchmark.modality import Modality, Starter

__all__ = ["ScaffoldError", "Scaffold", "new_tracker"]

NAME_PATTERN = re.compile(r"[a-z][a-z0-9_]*(-[a-z0-9_]+)*")
"""A tracker name: lower-case letters, digits, ``_`` and single ``-``, starting with a letter."""

TEMPLATES = Path(__file__).parent / "templates"

FILES = {
    "pyproject.toml.j2": "pyproject.toml",
    "README.md.j2": "README.md",
    "__init__.py.j2": "{module}/__init__.py",
    "tracker.py.j2": "{module}/tracker.py",
    "test_tracker.py.j2": "tests/test_{module_suffix}.py",
}
"""Template file -> path in the new folder."""


class ScaffoldError(TrackbenchError):
    """An invalid tracker name or modality, or a folder that already exists."""


@dataclass(frozen=True)
class Scaffold:
    """The names one plugin skeleton is made of.

    Attributes
    ----------
    name : str
        The tracker's name (``demo``), also the entry-point name.
    modality : str
        The modality its tracker reads.
    starter : Starter
        That modality's part of the skeleton.
    """

    name: str
    modality: str
    starter: Starter

    @property
    def module_suffix(self) -> str:
        """``name`` as a Python identifier."""
        return self.name.replace("-", "_")

    @property
    def module(self) -> str:
        """The plugin's import name (``trackbench_demo``)."""
        return f"trackbench_{self.module_suffix}"

    @property
    def distribution(self) -> str:
        """The plugin's distribution name (``trackbench-demo``)."""
        return f"trackbench-{self.name.replace('_', '-')}"

    @property
    def class_name(self) -> str:
        """The tracker class (``DemoTracker``)."""
        return "".join(part.capitalize() for part in re.split(r"[-_]", self.name) if part) + "Tracker"


def validate_name(name: str) -> None:
    """Raise :class:`ScaffoldError` unless ``name`` can name a tracker, an entry point and a module."""
    if not NAME_PATTERN.fullmatch(name) or keyword.iskeyword(name):
        raise ScaffoldError(
            f"invalid tracker name {name!r}: use lower-case letters, digits, '_' and '-', starting with a letter"
        )


def new_tracker(name: str, modality: Modality, out: Path | str = ".") -> Path:
    """Write the plugin skeleton of tracker ``name`` into ``out/name`` and return that folder.

    Parameters
    ----------
    name : str
        The tracker's name.
    modality : Modality
        The modality it reads; its :attr:`~benchmark.modality.Modality.starter` fills the tracker's template.
    out : path
        The folder the plugin's folder is made in.

    Raises
    ------
    ScaffoldError
        If ``name`` is invalid, ``modality`` has no starter, or ``out/name`` exists.
    """
    validate_name(name)
    if modality.starter is None:
        raise ScaffoldError(f"modality {modality.name!r} has no tracker template (its Modality sets no starter)")
    folder = Path(out) / name
    if folder.exists():
        raise ScaffoldError(f"{folder} already exists; choose another name or --out folder")
    scaffold = Scaffold(name, modality.name, modality.starter)
    environment = jinja2.Environment(
        loader=jinja2.FileSystemLoader(TEMPLATES), keep_trailing_newline=True, undefined=jinja2.StrictUndefined
    )
    names = {"module": scaffold.module, "module_suffix": scaffold.module_suffix}
    for template, target in FILES.items():
        path = folder / target.format(**names)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(environment.get_template(template).render(s=scaffold), encoding="utf-8")
    return folder
