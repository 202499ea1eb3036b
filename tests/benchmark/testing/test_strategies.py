"""The strategies of benchmark.testing: every modality's, reached by name through the registry."""

from __future__ import annotations

import dataclasses
import types

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.sonar.modality import SONAR
from benchmark.modalities.stereo.modality import STEREO
from benchmark.registry import Registry
from benchmark.testing import strategies


def built_in(fakes: types.ModuleType) -> Registry:
    """A registry of the three built-in modalities."""
    registry = Registry()
    with registry.acting_for(fakes.BUILT_IN):
        for modality in (CAMERA, SONAR, STEREO):
            registry.add_modality(modality)
    return registry


def test_every_built_in_modality_has_example_sequences(fakes: types.ModuleType) -> None:
    registry = built_in(fakes)
    assert list(registry.modalities) == ["camera", "sonar", "stereo"]
    for name, modality in registry.modalities.items():

        @settings(max_examples=3, deadline=None)
        @given(strategies.sequences(name, max_frames=2, registry=registry))
        def frames_are_of_the_modality(sequence: object) -> None:
            frames = list(sequence.frames())  # type: ignore[attr-defined]
            assert 1 <= len(frames) <= 2
            for frame in frames:
                modality.check_frame(frame, f"{name} example")
                assert frame.truth is not None
            assert sequence.info.modality == name  # type: ignore[attr-defined]

        frames_are_of_the_modality()


@settings(max_examples=2, deadline=None)
@given(strategies.sequences(SONAR, max_frames=1))
def test_a_modality_object_works_as_well_as_its_name(sequence: object) -> None:
    assert sequence.info.modality == "sonar"  # type: ignore[attr-defined]


def test_an_unknown_modality_is_named(fakes: types.ModuleType) -> None:
    with pytest.raises(LookupError, match="unknown modality 'lidar' \\(registered: camera, sonar, stereo\\)"):
        strategies.sequences("lidar", registry=built_in(fakes))


def test_a_modality_without_examples_says_so(fakes: types.ModuleType) -> None:
    bare = dataclasses.replace(built_in(fakes).modalities["camera"], name="bare", example_sequences=None)
    with pytest.raises(LookupError, match="modality 'bare' declares no example sequences"):
        strategies.sequences(bare)


@settings(max_examples=10, deadline=None)
@given(st.data())
def test_the_short_names_are_the_modalities_own(data: st.DataObject) -> None:
    state = data.draw(strategies.cable_states(width=200, height=150))
    assert strategies.cable_states is strategies.camera.cable_states
    assert type(state).__name__ == "CableState"
    swath = data.draw(strategies.swaths())
    assert swath.across_m.shape == swath.depth_m.shape
    measurement = data.draw(strategies.stereo_measurements())
    assert measurement.left_px - measurement.right_px != 0.0
