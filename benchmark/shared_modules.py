"""What every tracker and scorer of a process shares, which no plugin may change for the others.

A plugin that replaces ``numpy.mean`` when it is imported, or during a
cell, would change every other tracker's numbers and the board's own
arithmetic, and every row would still say ``ok``; one that changes the
working folder would move every later cell's relative paths.  A
:class:`Snapshot` keeps the names of the :data:`SHARED` modules loaded
when it is taken, numpy's handling of floating-point errors and the working
folder, tells what was since changed, and puts it back.  Names added later
(numpy loads some submodules on first use) are left alone.

* :func:`benchmark.plugins.make_plugin_manager` takes one before each
  plugin's import: a plugin whose import changed any of it is left out,
  with what it changed, and the process restored.  Workers are forked from
  that process, so a worker holds only plugins whose import changed nothing
  the others share.  (The environment is not held against an import:
  libraries set variables of their own when imported, scikit-learn two);
* :func:`benchmark.workers.cell_isolation` restores, before and after every
  cell, the modules as they were when :mod:`benchmark.workers` was first
  imported and the folder as it was when the cell began (and the
  environment too), so that neither an import in a worker (a Dask worker imports a
  plugin while it reads its first cell) nor a cell reaches the next cell.
"""

from __future__ import annotations

import dataclasses
import os
import random
import sys
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from types import ModuleType
from typing import Any

SHARED = ("math", "random", "numpy", "numpy.linalg", "numpy.random", "numpy.fft", "cv2", "scipy.ndimage", "scipy.stats")
"""Modules whose names a plugin must not replace."""


@dataclass(frozen=True)
class Snapshot:
    """The names of the :data:`SHARED` modules loaded when taken (:meth:`take`), and the process's state.

    Attributes
    ----------
    names : dict
        Module name to (module, a copy of its namespace).
    numpy_errors : dict or None
        ``numpy.geterr()``, if numpy was loaded.
    folder : str or None
        The working folder (None if it no longer existed).
    """

    names: dict[str, tuple[ModuleType, dict[str, Any]]]
    numpy_errors: dict[str, str] | None = None
    folder: str | None = None

    @classmethod
    def take(cls) -> Snapshot:
        """The shared modules loaded now and their names, numpy's error handling and the working folder."""
        loaded = {name: sys.modules.get(name) for name in SHARED}
        numpy = sys.modules.get("numpy")
        return cls(
            {name: (module, dict(vars(module))) for name, module in loaded.items() if module is not None},
            numpy.geterr() if numpy is not None else None,
            _working_folder(),
        )

    def extended(self) -> Snapshot:
        """This snapshot, plus the shared modules loaded since (their names as they are now)."""
        now = Snapshot.take()
        return dataclasses.replace(
            self, names={**now.names, **self.names}, numpy_errors=self.numpy_errors or now.numpy_errors
        )

    def in_folder_now(self) -> Snapshot:
        """This snapshot's modules, with the working folder as it is now."""
        return dataclasses.replace(self, folder=_working_folder())

    def changes(self) -> list[str]:
        """What changed since: ``module.name``, ``numpy.seterr`` and ``the working folder``."""
        return (
            [f"{module_name}.{name}" for module_name, _, name, _ in self._changed()]
            + self._errors_changed()
            + self._folder_changed()
        )

    def restore(self) -> list[str]:
        """Put back every replaced or removed name, numpy's error handling and the folder; what was put back."""
        replaced = list(self._changed())
        for _, module, name, value in replaced:
            setattr(module, name, value)
        errors = self._errors_changed()
        if errors:
            sys.modules["numpy"].seterr(**self.numpy_errors)
        folder = self._folder_changed()
        if folder:
            try:
                os.chdir(self.folder)  # type: ignore[arg-type]
            except OSError:
                pass  # the folder is gone; there is nothing to go back to
        return [f"{module_name}.{name}" for module_name, _, name, _ in replaced] + errors + folder

    def _folder_changed(self) -> list[str]:
        return ["the working folder"] if self.folder is not None and self.folder != _working_folder() else []

    def _errors_changed(self) -> list[str]:
        numpy = sys.modules.get("numpy")
        if self.numpy_errors is None or numpy is None or numpy.geterr() == self.numpy_errors:
            return []
        return ["numpy.seterr"]

    def _changed(self) -> Iterator[tuple[str, ModuleType, str, Any]]:
        for module_name, (module, names) in self.names.items():
            now = vars(module)
            for name, value in names.items():
                if now.get(name, _MISSING) is not value:
                    yield module_name, module, name, value


def seed_global_generators(words: Sequence[int]) -> None:
    """Seed NumPy's legacy global generator, Python's ``random`` and OpenCV's (where loaded) from ``words``.

    Parameters
    ----------
    words : sequence of int
        32-bit words (a ``SeedSequence``'s state): NumPy's generator takes
        them all, Python's their bytes as one integer, OpenCV's the first
        word's low 31 bits.
    """
    import numpy as np

    state = np.asarray(words, dtype=np.uint32)
    np.random.seed(state)
    random.seed(int.from_bytes(state.tobytes(), "little"))
    if "cv2" in sys.modules:
        sys.modules["cv2"].setRNGSeed(int(state[0] & 0x7FFFFFFF))


def _working_folder() -> str | None:
    try:
        return os.getcwd()
    except OSError:  # removed while we were in it
        return None


_MISSING = object()
