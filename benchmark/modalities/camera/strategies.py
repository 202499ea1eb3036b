"""Hypothesis strategies of the camera modality, for property-based tests of camera trackers.

A tracker author who wants to know how a tracker copes with any cable, not
just the ones of the suites, draws from these strategies:
:func:`cable_states` gives the state ``(d, alpha, w, beta)`` of a cable
lying in an image (conventions.md section 1); :func:`scene_specs` gives a
short, cheap scene with the pipe in view; :func:`sequences` renders such a
scene, and is what the conformance kit (:mod:`benchmark.testing`) draws
camera sequences from; :func:`frames` picks one frame of it.

Every draw is a function of hypothesis' choices alone (the scene's seed is
one of them), so a failing example shrinks and replays exactly.

Examples
--------
>>> from hypothesis import given
>>> @given(frames())
... def test_the_tracker_keeps_its_estimate_in_the_image(frame):
...     ...
"""

from __future__ import annotations

import math
from typing import TypeVar

from hypothesis import strategies as st

from benchmark.modalities.camera.model import CableState, CameraFrame
from benchmark.modalities.camera.scenes.scene import CameraScene
from benchmark.modalities.camera.scenes.spec import (
    Burial,
    CableLook,
    CameraSceneSpec,
    Clutter,
    MotionSpec,
    OpticsSpec,
    Overgrowth,
    Ripples,
    SeabedSpec,
    ZRange,
)
from benchmark.model import Sequence
from benchmark.scenes.signal import Signal

T = TypeVar("T")

MIN_CABLE_WIDTH_PX = 3.0
MAX_CABLE_WIDTH_SHARE = 0.4
"""Widest cable of :func:`cable_states`, as a share of the image's shorter side."""

CENTRELINE_REACH = 0.95
"""Farthest a centreline of :func:`cable_states` passes from the image centre, as a share of the farthest
line of its angle that still touches the image."""


def cable_states(width: int = 320, height: int = 240) -> st.SearchStrategy[CableState]:
    """Cable states of a cable lying in a ``width x height`` image.

    The centreline crosses the image, i.e. the rectangle spanned by the pixel
    centres that :func:`benchmark.modalities.camera.geometry.chord_midpoint`
    clips lines to; the borders converge towards ``+t`` as ground truth's do,
    but meet outside the image.

    Parameters
    ----------
    width, height : int
        Image size ``(W, H)`` in px, at least 8 each.

    Returns
    -------
    SearchStrategy of CableState
        ``alpha`` in ``(-pi/2, pi/2]``; ``|d|`` up to 95 % of the farthest
        distance at which a line of angle ``alpha`` still touches the image;
        ``w`` from 3 px to 40 % of ``min(W, H)``; ``beta`` from 0 to
        ``atan(w / (2 R))``, ``R`` the image's half diagonal, so that the
        borders meet at least ``R`` from the image centre.

    References
    ----------
    conventions.md sections 1 and 3.
    """
    if min(width, height) < 8:
        raise ValueError(f"image must be at least 8 x 8 px, got {width} x {height}")
    half_width, half_height = (width - 1) / 2.0, (height - 1) / 2.0
    half_diagonal = math.hypot(half_width, half_height)
    widest = MAX_CABLE_WIDTH_SHARE * min(width, height)

    @st.composite
    def states(draw: st.DrawFn) -> CableState:
        alpha = draw(st.floats(-math.pi / 2, math.pi / 2, exclude_min=True))
        # The centreline p . n = d touches the image while |d| is at most the image's extent along n.
        extent = half_width * abs(math.cos(alpha)) + half_height * abs(math.sin(alpha))
        d = draw(st.floats(-CENTRELINE_REACH * extent, CENTRELINE_REACH * extent))
        w = draw(st.floats(MIN_CABLE_WIDTH_PX, widest))
        beta = draw(st.floats(0.0, math.atan(w / (2.0 * half_diagonal))))
        return CableState(d, alpha, w, beta)

    return states()


def scene_specs(max_frames: int = 4) -> st.SearchStrategy[CameraSceneSpec]:
    """Valid specs of short, cheap camera scenes with the pipe in view.

    Parameters
    ----------
    max_frames : int
        Longest sequence, at least 1.

    Returns
    -------
    SearchStrategy of CameraSceneSpec
        A seed in ``[0, 2**32)`` and 1 to ``max_frames`` frames of 96 to
        320 px wide, 60 % to 75 % as high, with a focal length of 1.1 to 1.5
        image widths; a pipe of 0.1 to 0.2 m; the camera 1 to 2.5 m above the
        pipe axis and beside it by up to 12 % of that, tilted 50 to 90 deg,
        panned and rolled up to 5 deg, each with a little noise; a seabed of
        albedo 0.35 to 0.8 and a pipe darker by 0.1 to 0.3; light and sensor
        noise drawn; and each of ripples, clutter, burial and overgrowth
        present or not.  Four frames render in some 15 ms, those of the
        widest views in about 60 ms.
    """
    if max_frames < 1:
        raise ValueError(f"max_frames must be >= 1, got {max_frames}")

    @st.composite
    def specs(draw: st.DrawFn) -> CameraSceneSpec:
        width = draw(st.integers(96, 320))
        height = draw(st.integers(round(0.6 * width), round(0.75 * width)))
        seabed = draw(_seabeds())
        return CameraSceneSpec(
            name="camera/example",
            n_frames=draw(st.integers(1, max_frames)),
            seed=draw(st.integers(0, 2**32 - 1)),
            frame_size=(width, height),
            focal_px=draw(st.floats(1.1, 1.5)) * width,
            pipe_diameter_m=draw(st.floats(0.1, 0.2)),
            motion=draw(_motions()),
            seabed=seabed,
            cable=draw(_cable_looks(seabed.albedo)),
            burial=draw(_sometimes(_burials())),
            overgrowth=draw(_sometimes(_overgrowths())),
            optics=draw(_optics()),
        )

    return specs()


def sequences(max_frames: int = 4) -> st.SearchStrategy[Sequence]:
    """Rendered camera sequences of 1 to ``max_frames`` labelled frames, from :func:`scene_specs`.

    Parameters
    ----------
    max_frames : int
        Longest sequence, at least 1.

    Returns
    -------
    SearchStrategy of Sequence
        :class:`CameraScene` objects, which render their frames as they are
        iterated, each with its :class:`~benchmark.modalities.camera.model.CameraTruth`.
    """
    return scene_specs(max_frames).map(CameraScene)


def frames(max_frames: int = 4) -> st.SearchStrategy[CameraFrame]:
    """Any one labelled frame of a sequence from :func:`sequences`.

    Parameters
    ----------
    max_frames : int
        Longest sequence the frame is taken from, at least 1.

    Returns
    -------
    SearchStrategy of Frame
        The frame rendered on its own, equal to the one the sequence's
        iteration yields.
    """

    @st.composite
    def one_frame(draw: st.DrawFn) -> CameraFrame:
        scene = CameraScene(draw(scene_specs(max_frames)))
        return scene.frame(draw(st.integers(0, scene.spec.n_frames - 1)))

    return one_frame()


def _sometimes(parts: st.SearchStrategy[T]) -> st.SearchStrategy[tuple[T, ...]]:
    """No part or one, as the tuple a spec holds."""
    return st.lists(parts, max_size=1).map(tuple)


def _noisy(means: st.SearchStrategy[float], max_noise: float) -> st.SearchStrategy[Signal]:
    """Signals with a mean from ``means`` and smoothed noise of at most ``max_noise``."""
    return st.builds(Signal, mean=means, noise_std=st.floats(0.0, max_noise))


@st.composite
def _motions(draw: st.DrawFn) -> MotionSpec:
    """Camera paths above the pipe, beside it by a share of the height, looking forward and down along it."""
    height = draw(_noisy(st.floats(1.0, 2.5), 0.02))
    beside = draw(st.floats(-0.12, 0.12)) * height.mean
    return MotionSpec(
        cx_m=draw(_noisy(st.just(beside), 0.01)),
        cy_m=height,
        theta_deg=draw(_noisy(st.floats(-5.0, 5.0), 0.5)),
        phi_deg=draw(_noisy(st.floats(50.0, 90.0), 0.5)),
        xi_deg=draw(_noisy(st.floats(-5.0, 5.0), 0.5)),
        speed_mps=draw(_noisy(st.floats(0.1, 0.8), 0.05)),
        speed_noise_mps=draw(st.floats(0.0, 0.05)),
    )


def _stretch(start: float, length: float) -> ZRange:
    return start, start + length


def _stretches() -> st.SearchStrategy[ZRange]:
    """Stretches along the pipe, somewhere in the first metres the camera sees."""
    return st.builds(_stretch, start=st.floats(0.0, 3.0), length=st.floats(0.2, 3.0))


def _seabeds() -> st.SearchStrategy[SeabedSpec]:
    ripples = st.builds(
        Ripples,
        amplitude=st.floats(0.05, 0.3),
        wavelength_m=st.floats(0.06, 0.3),
        angle_deg=st.floats(-60.0, 60.0),
        sharpness=st.floats(0.0, 1.0),
    )
    clutter = st.builds(
        Clutter,
        z_m=_stretches(),
        x_m=st.floats(0.5, 1.5),
        rocks_per_m2=st.floats(0.0, 4.0),
        rock_albedo=st.floats(0.2, 0.6),
        algae_per_m2=st.floats(0.0, 2.0),
    )
    return st.builds(
        SeabedSpec,
        albedo=st.floats(0.35, 0.8),
        patchiness=st.floats(0.0, 0.3),
        ripples=_sometimes(ripples),
        clutter=_sometimes(clutter),
    )


def _cable_looks(seabed_albedo: float) -> st.SearchStrategy[CableLook]:
    """Pipes darker than the seabed, as in the thesis' and Foresti's sequences."""
    return st.builds(
        CableLook,
        albedo=st.floats(0.1, 0.3).map(lambda contrast: seabed_albedo - contrast),
        specular=st.floats(0.0, 0.3),
        growth_coverage=st.floats(0.0, 0.6),
    )


def _burials() -> st.SearchStrategy[Burial]:
    return st.builds(Burial, z_m=_stretches(), level=st.floats(0.2, 1.3))


def _overgrowths() -> st.SearchStrategy[Overgrowth]:
    return st.builds(
        Overgrowth,
        z_m=_stretches(),
        mat_cover=st.floats(0.0, 0.3),
        fronds_per_m=st.floats(0.0, 8.0),
        side_stones_per_m=st.floats(0.0, 4.0),
        top_stones_per_m=st.floats(0.0, 1.0),
    )


def _optics() -> st.SearchStrategy[OpticsSpec]:
    return st.builds(
        OpticsSpec,
        exposure=st.floats(250.0, 600.0),
        attenuation_per_m=st.floats(0.0, 0.3),
        blur_px=st.floats(0.0, 1.5),
        noise_grey=st.floats(0.0, 8.0),
        snow_per_frame=st.floats(0.0, 8.0),
    )
