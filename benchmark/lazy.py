"""Modules imported on first use, so that listing the trackers does not load what only running them needs.

``trackbench list`` and ``trackbench --help`` import every plugin to read
its trackers' names, versions and parameters; they should not pay for numba,
scikit-learn, SciPy or pandas, which only building, fitting or running a
tracker needs.  A tracker module that calls a kernel module only from
``reset`` or ``step`` names it with :func:`lazy_module` (plain Python:
:class:`importlib.util.LazyLoader`)::

    kernels = lazy_module("my_tracker.kernels")   # nothing imported yet
    ...
    def step(self, frame):
        return kernels.measure(frame.observation)   # imported here, once

A module imported lazily runs after the plugin manager's check of what a
plugin's import changes (:mod:`benchmark.shared_modules`); the workers'
check before and after every cell still applies to it.
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
from types import ModuleType


def lazy_module(name: str) -> ModuleType:
    """Module ``name``, whose code runs on first access to one of its attributes.

    Its parent packages are imported now; a module already imported is
    returned as it is.

    Raises
    ------
    ModuleNotFoundError
        If there is no module ``name`` (found now, not on first use).
    """
    if name in sys.modules:
        return sys.modules[name]
    parent = name.rpartition(".")[0]
    if parent:
        importlib.import_module(parent)
    spec = importlib.util.find_spec(name)
    if spec is None or spec.loader is None:
        raise ModuleNotFoundError(f"no module named {name!r}", name=name)
    spec.loader = importlib.util.LazyLoader(spec.loader)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    # Not set as an attribute of its package: pluggy reads every attribute of a plugin's package when it registers
    # it, which would load the module.  ``import`` and ``from ... import`` find it in ``sys.modules`` all the same.
    return module
