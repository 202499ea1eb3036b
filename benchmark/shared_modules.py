"""The modules every tracker and scorer shares, which no plugin may change for the others.

A plugin that replaces ``numpy.mean`` when it is imported, or during a
cell, would change every other tracker's numbers and the board's own
arithmetic, and every row would still say ``ok``.  A :class:`Snapshot`
keeps the names of the :data:`SHARED` modules loaded when it is taken, and
tells which of them were since replaced or removed, and puts them back.
Names added later (numpy loads some submodules on first use) are left alone.

* :func:`benchmark.plugins.make_plugin_manager` takes one before each
  plugin's import: a plugin that changed a shared module is left out, with
  what it changed, and the module restored;
* :func:`benchmark.workers.cell_isolation` restores the snapshot taken when
  :mod:`benchmark.workers` was first imported, before and after every cell,
  so that neither an import in a worker (a Dask worker imports a plugin while
  it reads its first cell) nor a cell reaches the next cell.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from dataclasses import dataclass
from types import ModuleType
from typing import Any

SHARED = ("math", "random", "numpy", "numpy.linalg", "numpy.random", "numpy.fft", "cv2", "scipy.ndimage", "scipy.stats")
"""Modules whose names a plugin must not replace."""


@dataclass(frozen=True)
class Snapshot:
    """The names of the :data:`SHARED` modules loaded when taken (:meth:`take`).

    Attributes
    ----------
    names : dict
        Module name to (module, a copy of its namespace).
    """

    names: dict[str, tuple[ModuleType, dict[str, Any]]]
    numpy_errors: dict[str, str] | None = None

    @classmethod
    def take(cls) -> Snapshot:
        """The shared modules loaded now, and their names; numpy's handling of floating-point errors."""
        loaded = {name: sys.modules.get(name) for name in SHARED}
        numpy = sys.modules.get("numpy")
        return cls(
            {name: (module, dict(vars(module))) for name, module in loaded.items() if module is not None},
            numpy.geterr() if numpy is not None else None,
        )

    def extended(self) -> Snapshot:
        """This snapshot, plus the shared modules loaded since (their names as they are now)."""
        now = Snapshot.take()
        return Snapshot({**now.names, **self.names}, self.numpy_errors or now.numpy_errors)

    def changes(self) -> list[str]:
        """Every name replaced or removed since, as ``module.name``, and ``numpy.seterr`` if its state changed."""
        return [f"{module_name}.{name}" for module_name, _, name, _ in self._changed()] + self._errors_changed()

    def restore(self) -> list[str]:
        """Put every replaced or removed name and numpy's error handling back; what was put back, as :meth:`changes` gives it."""
        replaced = list(self._changed())
        for _, module, name, value in replaced:
            setattr(module, name, value)
        errors = self._errors_changed()
        if errors:
            sys.modules["numpy"].seterr(**self.numpy_errors)
        return [f"{module_name}.{name}" for module_name, _, name, _ in replaced] + errors

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


_MISSING = object()
