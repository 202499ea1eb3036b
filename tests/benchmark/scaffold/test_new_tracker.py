"""``trackbench new-tracker``: the plugin skeleton, its conformance, and the one-line pytest helper."""

from __future__ import annotations

import dataclasses
import importlib
import subprocess
import sys
import sysconfig
import venv
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from benchmark.cli import main
from benchmark.errors import ParameterError
from benchmark.io import export_sequence
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.plugins import load_registry
from benchmark.scaffold import ScaffoldError
from benchmark.scaffold import new_tracker as write_skeleton
from benchmark.testing import assert_conforms, check_tracker
from benchmark.tracker import Tracker

from ..site.conftest import Clip

FILES = (
    "pyproject.toml",
    "README.md",
    "trackbench_demo/__init__.py",
    "trackbench_demo/tracker.py",
    "tests/test_demo.py",
)


def new_tracker(*args: str) -> tuple[int, str]:
    """Run ``trackbench new-tracker ARGS`` in-process; exit status and output."""
    result = CliRunner().invoke(main, ["new-tracker", *args])
    return result.exit_code, result.output


@pytest.fixture
def demo(tmp_path: Path) -> Iterator[Path]:
    """The ``demo`` skeleton in ``tmp_path``, importable while the test runs."""
    code, output = new_tracker("demo", "--out", str(tmp_path))
    assert code == 0, output
    folder = tmp_path / "demo"
    sys.path.insert(0, str(folder))
    try:
        yield folder
    finally:
        sys.path.remove(str(folder))
        for module in [name for name in sys.modules if name.split(".")[0] == "trackbench_demo"]:
            del sys.modules[module]


def demo_tracker() -> type[Tracker]:
    return importlib.import_module("trackbench_demo").DemoTracker


def test_new_tracker_writes_the_plugin_files(demo: Path) -> None:
    for name in FILES:
        assert (demo / name).is_file(), name
    pyproject = (demo / "pyproject.toml").read_text()
    assert '[project.entry-points.trackbench]\ndemo = "trackbench_demo"' in pyproject
    assert '"subsea-trackbench"' in pyproject
    assert "assert_conforms(DemoTracker)" in (demo / "tests/test_demo.py").read_text()


@pytest.mark.parametrize("modality", ["camera", "sonar", "stereo"])
def test_a_new_tracker_of_each_modality_passes_the_conformance_kit(tmp_path: Path, modality: str) -> None:
    code, output = new_tracker("demo", "--modality", modality, "--out", str(tmp_path))
    assert code == 0, output
    sys.path.insert(0, str(tmp_path / "demo"))
    try:
        tracker = demo_tracker()
        assert (tracker.name, tracker.modality) == ("demo", modality)
        assert dataclasses.is_dataclass(tracker.Params) and tracker.Params.__dataclass_params__.frozen
        results = check_tracker(tracker, n_frames=4)
    finally:
        sys.path.remove(str(tmp_path / "demo"))
        for module in [name for name in sys.modules if name.split(".")[0] == "trackbench_demo"]:
            del sys.modules[module]
    assert [r for r in results if not r.ok] == []
    details = {r.check: r.detail for r in results}
    assert "0 valid estimates in 4 frames without init or truth" in details["starts_without_truth"]
    assert details["runs"].startswith("4 estimates in 4 frames")


def test_the_hold_parameter_is_validated_and_stops_the_estimates(demo: Path) -> None:
    tracker = demo_tracker()
    with pytest.raises(ParameterError, match="hold_frames"):
        tracker.make_params({"hold_frames": -1})
    (first,) = CameraScene.from_dict({"name": "hold", "n_frames": 1, "seed": 1}, "test").frames()
    instance = tracker(tracker.make_params({"hold_frames": 2}))
    instance.reset(None, np.random.default_rng(0), init=first.truth)
    assert [instance.step(first) for _ in range(4)] == [first.truth.cable] * 2 + [None] * 2


def test_the_new_tracker_registers_through_its_hook(demo: Path) -> None:
    module = importlib.import_module("trackbench_demo")
    added = []

    class Recorder:
        def add_tracker(self, cls: type[Tracker]) -> None:
            added.append(cls)

    module.trackbench_register_trackers(Recorder())
    assert added == [module.DemoTracker]


@pytest.mark.parametrize("name", ["9lives", "Demo", "my.tracker", "a b", "class", "x-", "a--b", ""])
def test_an_invalid_name_exits_2(tmp_path: Path, name: str) -> None:
    code, output = new_tracker(name, "--out", str(tmp_path))
    assert code == 2
    assert "invalid tracker name" in output
    assert list(tmp_path.iterdir()) == []


def test_an_existing_folder_exits_2(tmp_path: Path) -> None:
    (tmp_path / "demo").mkdir()
    code, output = new_tracker("demo", "--out", str(tmp_path))
    assert code == 2
    assert "already exists" in output
    assert list((tmp_path / "demo").iterdir()) == []


def test_an_unknown_modality_exits_2(tmp_path: Path) -> None:
    code, output = new_tracker("demo", "--modality", "lidar", "--out", str(tmp_path))
    assert code == 2
    assert "unknown modality 'lidar' (registered: camera, sonar, stereo)" in output
    assert list(tmp_path.iterdir()) == []


def test_a_modality_without_a_starter_is_refused(tmp_path: Path) -> None:
    bare = dataclasses.replace(CAMERA, name="bare", starter=None)
    with pytest.raises(ScaffoldError, match="modality 'bare' has no tracker template"):
        write_skeleton("demo", bare, tmp_path)
    assert list(tmp_path.iterdir()) == []


def test_a_hyphenated_name_makes_a_valid_module(tmp_path: Path) -> None:
    code, output = new_tracker("my-tracker", "--out", str(tmp_path))
    assert code == 0, output
    folder = tmp_path / "my-tracker"
    assert (folder / "trackbench_my_tracker" / "__init__.py").is_file()
    assert 'my-tracker = "trackbench_my_tracker"' in (folder / "pyproject.toml").read_text()
    assert "class MyTrackerTracker(" in (folder / "trackbench_my_tracker" / "tracker.py").read_text()


def test_pytest_plugin_assert_conforms_lists_every_failed_check(demo: Path) -> None:
    tracker = demo_tracker()
    assert_conforms(tracker, n_frames=3)

    class Broken(tracker):
        name = "broken"

        def step(self, frame):  # type: ignore[no-untyped-def]
            raise RuntimeError("boom")

    with pytest.raises(AssertionError) as raised:
        assert_conforms(Broken, n_frames=3)
    message = str(raised.value)
    assert "conformance check(s) failed" in message
    assert "broken: frames_without_truth:" in message and "boom" in message


def test_pytest_plugin_fixture_and_entry_point(pytestconfig: pytest.Config, tracker_check) -> None:  # type: ignore[no-untyped-def]
    assert tracker_check is assert_conforms
    assert pytestconfig.pluginmanager.has_plugin("trackbench")


CLIP_FRAMES = 20
"""Frames of the sequence the installed skeleton is run on."""


def _run(*command: object, timeout: float = 600) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(part) for part in command], capture_output=True, text=True, timeout=timeout)


@pytest.mark.slow
def test_end_to_end_install_check_and_run(tmp_path: Path) -> None:
    """The skeleton pip-installed into a fresh venv, then ``trackbench check`` and ``trackbench run`` on it.

    The venv sees this environment's packages (the harness and its
    dependencies) through a ``.pth`` file, since ``--system-site-packages``
    reaches only the base interpreter's; it gets its own ``trackbench``
    script, as pip writes for the harness's console script.  This
    environment's pip installs into the venv (``pip --python``), which so
    needs no pip of its own; the run reads a clip of :data:`CLIP_FRAMES`
    frames of camera/S2 written as files, not the whole rendered sequence.
    """
    code, output = new_tracker("demo", "--out", str(tmp_path))
    assert code == 0, output
    env = tmp_path / "venv"
    venv.EnvBuilder(system_site_packages=True, with_pip=False).create(env)
    python = env / "bin" / "python"
    pip = [sys.executable, "-m", "pip", "--python", python]
    site_packages = Path(_run(python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])").stdout.strip())
    parent = sysconfig.get_paths()["purelib"]
    (site_packages / "trackbench-parent.pth").write_text(f"import site; site.addsitedir({parent!r})\n")
    has_backend = _run(python, "-c", "import setuptools.command.bdist_wheel")
    if has_backend.returncode != 0 and _run(python, "-c", "import wheel").returncode != 0:
        fetched = _run(*pip, "install", "--retries", "0", "--timeout", "10", "wheel", timeout=120)
        if fetched.returncode != 0:
            pytest.skip(f"building the plugin needs the 'wheel' package, which pip could not fetch: {fetched.stderr}")
    install = _run(*pip, "install", "--no-deps", "--no-build-isolation", "--no-index", tmp_path / "demo")
    assert install.returncode == 0, install.stdout + install.stderr
    trackbench = env / "bin" / "trackbench"
    trackbench.write_text(f"#!{python}\nimport sys\nfrom benchmark.cli import main\nsys.exit(main())\n")
    trackbench.chmod(0o755)

    check = _run(trackbench, "check", "demo", "--frames", "5")
    assert check.returncode == 0, check.stdout + check.stderr
    assert "13 passed, 0 failed, 1 skipped (1 trackers)" in check.stdout
    registry = load_registry()
    clip = export_sequence(Clip(registry.sequence("camera/S2"), CLIP_FRAMES), tmp_path / "clip", registry.modalities)
    out = tmp_path / "board"
    run = _run(trackbench, "run", "--tracker", "demo", "--dataset", clip, "--in-process", "--out", out)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "demo" in run.stdout
    board = (out / "leaderboard.csv").read_text()
    assert "demo" in board and str(clip) in board
