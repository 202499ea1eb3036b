"""Tests of benchmark.selection: command-line words to cells, each carrying its modality."""

from __future__ import annotations

import dataclasses
import types
from pathlib import Path

import pytest

from benchmark.errors import DataError, ParameterError
from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.sonar.modality import SONAR
from benchmark.registry import Registry
from benchmark.selection import (
    NamedSequence,
    Selection,
    SelectionError,
    make_cells,
    open_dataset_path,
    parse_param_overrides,
    select_cells,
)


def test_a_selection_becomes_tracker_by_sequence_by_seed_cells_of_one_modality(fake_registry: Registry) -> None:
    cells = select_cells(fake_registry, Selection(trackers=("perfect", "sonar-only", "raising"), seeds=2))
    assert [(c.tracker.name, c.dataset, c.seed) for c in cells] == [
        (tracker, dataset, seed)
        for tracker in ("perfect", "raising")
        for dataset in ("fake/S1", "fake/S2")
        for seed in (0, 1)
    ]
    assert all(cell.modality is CAMERA and cell.init == "truth" for cell in cells)


def test_overrides_and_init_reach_every_cell(fake_registry: Registry) -> None:
    selection = Selection(trackers=("raising",), datasets=("fake/S2",), params=("raising.fail_at=7",), init="none")
    (cell,) = select_cells(fake_registry, selection)
    assert cell.tracker.params.fail_at == 7 and cell.init == "none" and cell.dataset == "fake/S2"


@pytest.mark.parametrize(
    ("selection", "error", "message"),
    [
        (Selection(trackers=("nope",)), SelectionError, r"unknown tracker 'nope' \(known: blind, counting"),
        (Selection(suites=("nope",)), SelectionError, r"unknown suite 'nope' \(known: fake\)"),
        (Selection(datasets=("fake/S9",)), SelectionError, r"unknown dataset 'fake/S9'.*registered: fake/S1, fake/S2"),
        (Selection(params=("raising.fail_at",)), ParameterError, r"expected TRACKER.KEY=VALUE"),
        (Selection(trackers=("perfect",), params=("raising.fail_at=1",)), ParameterError, r"'raising'.*not selected"),
        (Selection(trackers=("raising",), params=("raising.fail_at=soon",)), ParameterError, r"'fail_at'"),
        (Selection(trackers=("sonar-only",)), SelectionError, r"nothing to run.*sonar-only \(sonar\).*S1 \(camera\)"),
        (Selection(trackers=("perfect",), real_time=True), SelectionError, r"closed-loop sequences only.*fake/S1"),
        (Selection(trackers=("perfect",), step_times=("perfect=17",)), ParameterError, r"add --real-time"),
    ],
)
def test_every_word_is_checked_before_any_cell_exists(
    fake_registry: Registry, selection: Selection, error: type[Exception], message: str
) -> None:
    with pytest.raises(error, match=message):
        select_cells(fake_registry, selection)


def test_make_cells_gives_each_cell_the_modality_its_tracker_reads(
    fake_registry: Registry, fakes: types.ModuleType
) -> None:
    trackers = [fake_registry.trackers["sonar-only"], fake_registry.trackers["blind"]]
    modalities = {"camera": CAMERA, "sonar": SONAR}
    cells = make_cells(trackers, [fakes.FakeSequence()], [3], "truth", modalities)
    assert [(cell.tracker.name, cell.modality, cell.seed) for cell in cells] == [("blind", CAMERA, 3)]
    assert make_cells(trackers, [fakes.FakeSequence()], [], "truth", modalities) == []


def test_parse_param_overrides_splits_at_the_last_dot() -> None:
    assert parse_param_overrides(["my.tracker.sigma = 3 ", "hough.n=1", "hough.n=2"]) == {
        "my.tracker": {"sigma": "3"},
        "hough": {"n": "2"},
    }


def test_a_dataset_path_is_opened_by_its_modality_and_named_as_written(tmp_path: Path, make_image) -> None:
    make_image(tmp_path / "frames" / "a.png")
    written = str(tmp_path / "frames") + "/"
    sequence = open_dataset_path(written, [CAMERA, SONAR])
    assert sequence.info.name == written
    assert sequence.info.modality == "camera" and len(list(sequence.frames())) == 1
    with pytest.raises(DataError, match=r"no registered reader opens this"):
        open_dataset_path(str(tmp_path / "frames"), [SONAR])


def test_a_named_sequence_is_its_inner_sequence_under_another_name(fakes: types.ModuleType) -> None:
    inner = fakes.FakeSequence(n_frames=3)
    named = NamedSequence(inner, "my/path.txt")
    assert named.info.name == "my/path.txt"
    assert named.info == dataclasses.replace(inner.info, name="my/path.txt")
    assert [frame.index for frame in named.frames()] == [0, 1, 2]


def test_a_dataset_path_selects_a_cell_next_to_registered_sequences(
    fake_registry: Registry, tmp_path: Path, make_image
) -> None:
    make_image(tmp_path / "frames" / "a.png")
    path = str(tmp_path / "frames")
    cells = select_cells(fake_registry, Selection(trackers=("blind",), datasets=("fake/S1", path)))
    assert [cell.dataset for cell in cells] == ["fake/S1", path]
    assert all(cell.modality is CAMERA for cell in cells)


def test_two_paths_naming_one_file_are_one_dataset_under_the_first_name(
    fake_registry: Registry, tmp_path: Path, make_image, monkeypatch: pytest.MonkeyPatch
) -> None:
    make_image(tmp_path / "data" / "a.png")
    (tmp_path / "data" / "seq.txt").write_text("1 0 6 0 # a.png\n")
    (tmp_path / "work").mkdir()
    monkeypatch.chdir(tmp_path / "work")
    datasets = ("../data/seq.txt", str(tmp_path / "data" / "seq.txt"), "../work/../data/seq.txt")
    cells = select_cells(fake_registry, Selection(trackers=("blind",), datasets=datasets))
    assert [cell.dataset for cell in cells] == ["../data/seq.txt"]
