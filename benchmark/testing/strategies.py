"""Hypothesis strategies for a tracker's property-based tests, one namespace per modality.

Each modality keeps its strategies in its own folder
(``benchmark/modalities/<name>/strategies.py``); this module gathers them
where a tracker author looks first::

    from hypothesis import given
    from benchmark.testing import strategies

    @given(strategies.cable_states(width=320, height=240))
    def test_my_likelihood_is_finite(state): ...

    @given(strategies.sequences("sonar", max_frames=6))
    def test_my_tracker_survives(sequence): ...

The namespaces :mod:`camera`, :mod:`sonar` and :mod:`stereo` hold every
strategy of the built-in modalities; the names below are the ones most
tests want.  :func:`sequences` reaches any registered modality, a
third-party sensor's too, through its
:attr:`~benchmark.modality.Modality.example_sequences`.
"""

from __future__ import annotations

from hypothesis import strategies as st

from benchmark.modalities.camera import strategies as camera
from benchmark.modalities.sonar import strategies as sonar
from benchmark.modalities.stereo import strategies as stereo
from benchmark.modality import Modality
from benchmark.model import Sequence
from benchmark.registry import Registry

__all__ = [
    "cable_states",
    "camera",
    "camera_frames",
    "camera_scene_specs",
    "sequences",
    "sonar",
    "stereo",
    "stereo_measurements",
    "swaths",
]

cable_states = camera.cable_states
camera_scene_specs = camera.scene_specs
camera_frames = camera.frames
swaths = sonar.swaths
stereo_measurements = stereo.stereo_measurements


def sequences(
    modality: Modality | str, max_frames: int = 4, registry: Registry | None = None
) -> st.SearchStrategy[Sequence]:
    """Short labelled sequences of ``modality``, simulated from random scenes.

    Parameters
    ----------
    modality : Modality or str
        The modality, or its registered name.
    max_frames : int
        Longest sequence.
    registry : Registry, optional
        Where a name is looked up; by default every installed plugin's.

    Returns
    -------
    SearchStrategy of Sequence
        The modality's :attr:`~benchmark.modality.Modality.example_sequences`.

    Raises
    ------
    LookupError
        For a name no plugin registers, or a modality without example sequences.
    """
    if isinstance(modality, str):
        if registry is None:
            from benchmark.plugins import load_registry

            registry = load_registry()
        if modality not in registry.modalities:
            known = ", ".join(sorted(registry.modalities)) or "none"
            raise LookupError(f"unknown modality {modality!r} (registered: {known})")
        modality = registry.modalities[modality]
    if modality.example_sequences is None:
        raise LookupError(f"modality {modality.name!r} declares no example sequences")
    return modality.example_sequences(max_frames)
