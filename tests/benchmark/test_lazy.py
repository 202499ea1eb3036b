"""Tests of benchmark.lazy: a module named now runs its code on first use, once."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from benchmark.lazy import lazy_module


@pytest.fixture
def package(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A package ``lazypkg`` whose module ``kernels`` counts how often it ran, on a path of its own."""
    root = tmp_path / "lazypkg"
    root.mkdir()
    (root / "__init__.py").write_text("RUNS = []\n")
    (root / "kernels.py").write_text("import lazypkg\nlazypkg.RUNS.append(1)\n\ndef twice(x):\n    return 2 * x\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    yield root
    for name in [name for name in sys.modules if name.startswith("lazypkg")]:
        del sys.modules[name]


def test_the_module_runs_on_first_attribute_access_and_only_once(package: Path) -> None:
    kernels = lazy_module("lazypkg.kernels")
    import lazypkg

    assert lazypkg.RUNS == [] and "kernels" not in vars(lazypkg)
    assert kernels.twice(3) == 6 and kernels.twice(4) == 8
    from lazypkg.kernels import twice  # an ordinary import finds the same module

    assert twice(5) == 10 and lazypkg.RUNS == [1]
    assert lazy_module("lazypkg.kernels") is sys.modules["lazypkg.kernels"]


def test_a_missing_module_is_an_error_when_named(package: Path) -> None:
    with pytest.raises(ModuleNotFoundError, match="lazypkg.nowhere"):
        lazy_module("lazypkg.nowhere")
