"""The frame cache: a simulated sequence rendered once, read back bit for bit by every cell and run."""

from __future__ import annotations

import dataclasses
import pickle
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from benchmark.cli import main
from benchmark.frame_cache import CacheWarning, CachedSequence, FrameCache
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.sonar.scenes.scene import SonarScene
from benchmark.model import Frame, Sequence
from benchmark.plugins import load_registry


@pytest.fixture(scope="module")
def registry():  # type: ignore[no-untyped-def]
    return load_registry()


def short(registry, name: str, n_frames: int = 12) -> Sequence:  # type: ignore[no-untyped-def]
    """A registered simulated sequence cut to its first ``n_frames`` frames."""
    scene = registry.sequence(name)
    return type(scene)(dataclasses.replace(scene.spec, n_frames=n_frames))


def assert_same_frames(got: list[Frame], expected: list[Frame]) -> None:
    assert len(got) == len(expected)
    for mine, theirs in zip(got, expected):
        assert pickle.dumps(mine, protocol=5) == pickle.dumps(theirs, protocol=5)


@pytest.mark.parametrize("name", ["camera/S6", "sonar/concrete", "stereo/case1-slow", "stereo-images/case1-medium"])
def test_frames_read_back_equal_the_rendered_ones_bit_for_bit(registry, tmp_path: Path, name: str) -> None:  # type: ignore[no-untyped-def]
    scene = short(registry, name, 6)
    cache = FrameCache(tmp_path)
    cached = cache.wrap(scene)
    assert isinstance(cached, CachedSequence) and not cache.holds(scene)
    first = list(cached.frames())
    assert cache.holds(scene)
    again = list(cached.frames())
    expected = list(scene.frames())
    assert_same_frames(first, expected)
    assert_same_frames(again, expected)
    assert cached.identity == scene.identity and cached.info == scene.info


def test_a_cached_sequence_is_not_rendered_again_in_this_process_or_another(
    registry, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:  # type: ignore[no-untyped-def]
    scene = short(registry, "camera/S6")
    cache = FrameCache(tmp_path)
    expected = list(cache.wrap(scene).frames())

    def no_rendering(self, index):  # type: ignore[no-untyped-def]
        raise AssertionError("rendered again")

    monkeypatch.setattr(CameraScene, "observation", no_rendering)
    again = pickle.loads(pickle.dumps(cache.wrap(scene)))  # as a worker receives it
    assert_same_frames(list(again.frames()), expected)


def test_the_key_follows_the_spec_and_files_are_not_cached(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    cache = FrameCache(tmp_path)
    scene = short(registry, "camera/S6")
    assert cache.key(scene) == cache.key(short(registry, "camera/S6"))
    assert cache.key(scene) != cache.key(type(scene)(dataclasses.replace(scene.spec, seed=scene.spec.seed + 1)))
    assert cache.key(scene) != cache.key(short(registry, "camera/S6", 13))

    class FromFile(Sequence):  # a sequence read from files has cache_frames False
        info = scene.info

        def frames(self):  # type: ignore[no-untyped-def]
            return iter(())

    plain = FromFile()
    assert cache.key(plain) is None and cache.wrap(plain) is plain


def test_clear_removes_every_entry_and_leftover_and_counts_the_bytes(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    scene = short(registry, "sonar/concrete", 30)
    cache = FrameCache(tmp_path)
    stream = cache.wrap(scene).frames()
    assert next(stream).index == 0 and next(stream).index == 1
    stream.close()
    (tmp_path / f".{cache.path('x').name}.0123.tmp").write_bytes(b"12345")  # left by a killed writer
    size = cache.path(cache.key(scene)).stat().st_size
    [entry] = cache.entries()
    assert (entry.name, entry.modality, entry.frames, entry.size_bytes) == ("sonar/concrete", "sonar", 30, size)
    assert [path.name for path in cache.leftovers()] == [f".{cache.path('x').name}.0123.tmp"]
    assert cache.clear() == (1, size + 5)
    assert not list(tmp_path.iterdir())


def test_an_unwritable_cache_still_gives_every_frame(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    blocked = tmp_path / "a-file"
    blocked.write_text("in the way")
    scene = short(registry, "camera/S6", 4)
    cache = FrameCache(blocked / "frames")
    assert_same_frames(list(cache.wrap(scene).frames()), list(scene.frames()))
    assert not cache.holds(scene)


class BreaksAt(SonarScene):
    """A sonar scene whose rendering fails at frame 3."""

    def observation(self, index: int):  # type: ignore[no-untyped-def]
        if index == 3:
            raise ValueError("renderer broke at frame 3")
        return super().observation(index)


def test_a_rendering_error_reaches_the_reader_at_its_frame_and_leaves_no_entry(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    scene = BreaksAt(short(registry, "sonar/concrete", 6).spec)
    cache = FrameCache(tmp_path)
    seen = []
    with pytest.raises(ValueError, match="frame 3"):
        for frame in cache.wrap(scene).frames():
            seen.append(frame.index)
    assert seen == [0, 1, 2]
    assert not cache.holds(scene) and not list(tmp_path.glob("*.tmp")) and not cache.entries()


def cached_entry(registry, tmp_path: Path, name: str = "camera/S6", n_frames: int = 5):  # type: ignore[no-untyped-def]
    """A cache holding a short sequence: (cache, scene, the entry's file)."""
    scene = short(registry, name, n_frames)
    cache = FrameCache(tmp_path)
    list(cache.wrap(scene).frames())
    return cache, scene, cache.path(cache.key(scene))


def read_back_rebuilt(cache: FrameCache, scene: Sequence, path: Path) -> str:
    """Read ``scene`` through ``cache`` expecting its entry to be rebuilt; the warning's message."""
    with pytest.warns(CacheWarning, match=path.name) as caught:
        frames = list(cache.wrap(scene).frames())
    assert_same_frames(frames, list(scene.frames()))
    assert cache.holds(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert_same_frames(list(cache.wrap(scene).frames()), frames)  # the rebuilt entry passes its checks
    return str(caught[0].message)


def test_a_cut_entry_is_rendered_again_and_the_reader_carries_on_without_repeating_a_frame(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    cache, scene, path = cached_entry(registry, tmp_path)
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    assert "cut short" in read_back_rebuilt(cache, scene, path)


def test_a_frame_blanked_inside_an_entry_fails_its_checksum_and_is_never_served(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    cache, scene, path = cached_entry(registry, tmp_path)
    data = bytearray(path.read_bytes())
    image = bytes(scene.frames().__next__().observation)  # frame 0's pixels, found in the file
    at = data.index(image)
    data[at : at + len(image)] = bytes(len(image))
    path.write_bytes(data)
    assert "checksum" in read_back_rebuilt(cache, scene, path)


def test_another_sequence_s_entry_under_this_one_s_name_is_not_served(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    cache, scene, path = cached_entry(registry, tmp_path)
    other = type(scene)(dataclasses.replace(scene.spec, seed=scene.spec.seed + 1))
    list(cache.wrap(other).frames())
    path.write_bytes(cache.path(cache.key(other)).read_bytes())
    assert "not camera/S6" in read_back_rebuilt(cache, scene, path)


class Planted:
    """What a pickle planted in a cache would run: it leaves a mark."""

    def __init__(self, mark: Path) -> None:
        self.mark = mark

    def __reduce__(self):  # type: ignore[no-untyped-def]
        return (Path.write_text, (self.mark, "code ran"))


def test_a_pickle_planted_in_the_cache_runs_nothing(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    cache, scene, path = cached_entry(registry, tmp_path / "cache")
    mark = tmp_path / "mark"
    planted = pickle.dumps(Planted(mark))
    path.write_bytes(planted * 3)
    (tmp_path / "cache" / "0123abcd.frames").write_bytes(planted)
    info = CliRunner().invoke(main, ["cache", "info", "--cache", str(tmp_path / "cache")])
    assert info.exit_code == 0 and "unreadable" in info.output
    assert "not a trackbench record" in read_back_rebuilt(cache, scene, path)
    assert not mark.exists()


def test_frames_that_cannot_be_stored_are_streamed_with_a_warning_naming_the_sequence(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    class Unstorable(SonarScene):
        def frames(self):  # type: ignore[no-untyped-def]
            for frame in super().frames():
                yield dataclasses.replace(frame, navigation=object())

    scene = Unstorable(short(registry, "sonar/concrete", 3).spec)
    cache = FrameCache(tmp_path)
    with pytest.warns(CacheWarning, match="sonar/concrete: frames not cached: cannot store a builtins.object"):
        frames = list(cache.wrap(scene).frames())
    assert [frame.index for frame in frames] == [0, 1, 2] and not cache.holds(scene)


def test_a_second_run_renders_nothing_and_gives_the_same_board(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    cache = tmp_path / "cache"
    runner = CliRunner()
    args = ["run", "--tracker", "hough", "--tracker", "sonar_detector", "--dataset", "camera/S6"]
    args += ["--dataset", "sonar/concrete", "--jobs", "1", "--cache", str(cache)]
    first = runner.invoke(main, [*args, "--out", str(tmp_path / "first")])
    assert first.exit_code == 0, first.output
    assert "2 sequences rendered" in first.stderr

    def no_rendering(self):  # type: ignore[no-untyped-def]
        raise AssertionError("rendered again")

    # Workers are forked from this process, so they inherit the patch.
    monkeypatch.setattr(CameraScene, "_build_cache", no_rendering)
    monkeypatch.setattr(SonarScene, "_build_cache", no_rendering)
    second = runner.invoke(main, [*args, "--out", str(tmp_path / "second")])
    assert second.exit_code == 0, second.output
    assert "0 sequences rendered" in second.stderr and "0 sequences to render" in second.stderr
    columns = ["tracker", "dataset", "correct_pct", "false_pct", "missed_pct"]
    boards = [pd.read_csv(tmp_path / run / "leaderboard.csv")[columns] for run in ("first", "second")]
    pd.testing.assert_frame_equal(*boards)

    info = runner.invoke(main, ["cache", "info", "--cache", str(cache)])
    assert info.exit_code == 0 and "camera/S6" in info.output and "sonar/concrete" in info.output
    assert "2 sequences" in info.output
    cleared = runner.invoke(main, ["cache", "clear", "--cache", str(cache)])
    assert cleared.exit_code == 0 and "removed 2 sequences" in cleared.output
    assert not list(cache.glob("*.frames")) and not list(cache.glob("*.lock"))


def test_no_cache_renders_in_every_cell(tmp_path: Path) -> None:
    cache = tmp_path / "cache"
    result = CliRunner().invoke(
        main,
        ["run", "--tracker", "hough", "--dataset", "camera/S6", "--jobs", "0", "--no-cache", "--cache", str(cache)]
        + ["--out", str(tmp_path / "out")],
    )
    assert result.exit_code == 0, result.output
    assert not cache.exists()


def test_frames_differ_between_specs(registry, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    cache = FrameCache(tmp_path)
    scene = short(registry, "camera/S6", 3)
    other = type(scene)(dataclasses.replace(scene.spec, seed=scene.spec.seed + 1))
    mine = [frame.observation for frame in cache.wrap(scene).frames()]
    theirs = [frame.observation for frame in cache.wrap(other).frames()]
    assert not all(np.array_equal(a, b) for a, b in zip(mine, theirs))
