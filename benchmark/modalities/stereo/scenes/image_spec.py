"""Definitions of rendered stereo sequences: a stereo spec plus how its images look.

The field experiments of seeds/002, section 4.1 track a yellow blob on
board the target boat (TG) in the images of the chase boat's (CH) stereo
camera, and take TG's range from the disparity map (Fig. 10).  A rendered
stereo sequence reuses everything that defines a simulated one
(:class:`~benchmark.modalities.stereo.scenes.spec.StereoSceneSpec`: the boats' paths
and speed profiles, the camera of Tables 3-4, CH's GPS and compass) and
adds :class:`StereoRenderSpec`, the appearance of the scene the two cameras
see: sky, a distant shoreline, the sea, and TG's hull, cabin and marker.

Like the other specs it is built from plain data by
:meth:`StereoImageSceneSpec.from_dict`, with the ``render`` table nested
next to ``camera``, ``sensors``, ``target`` and ``chase``; an unknown key or
a bad value is a :class:`benchmark.errors.DataError` naming the file, the
key and the rule.  Lengths are in m, angles in degrees clockwise from north, colours
``(blue, green, red)`` in grey levels 0-255.
"""

from __future__ import annotations

from dataclasses import field
from typing import Annotated

import pydantic
from annotated_types import Ge, Gt, Interval

from benchmark.modalities.stereo.scenes.spec import StereoSceneSpec
from benchmark.scenes.spec import SPEC_CONFIG, Integer, NonNegative, Number, Positive

Level = Annotated[Number, Interval(ge=0, le=255)]
"""A grey level, 0-255."""

Colour = tuple[Level, Level, Level]
"""A BGR colour, grey levels 0-255."""


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class StereoRenderSpec:
    """How the scene in front of CH's stereo camera looks.

    Attributes
    ----------
    height_px : int
        Image height; the width is the calibration's (seeds/002, Table 4:
        320 px, the Bumblebee2 at 320 x 240).
    camera_height_m : float
        Height of both optical centres above the sea.  The cameras are
        level and look along CH's heading, so image rows are epipolar lines
        and eq. (15) holds exactly.
    hull_length_m, hull_beam_m, freeboard_m : float
        TG's hull: a box with a pointed bow, from the waterline up to the
        deck at ``freeboard_m``.
    cabin_height_m : float
        Height of the cabin on the deck, over TG's reference point.
    marker_radius_m, marker_height_m : float
        The yellow marker, an upright drum on the cabin roof whose axis
        passes through TG's reference point (the position the truth gives).
    marker_bgr : Colour
        The marker's colour in full sun.
    sky_zenith_bgr, sky_horizon_bgr : Colour
        Sky colour high up and at the horizon.
    sea_bgr : Colour
        Sea colour near the boats.
    wave_contrast : float
        Relative brightness swing of the waves near the camera; it fades
        with distance.
    wave_length_m : float
        Dominant wave length of the sea texture.
    wave_drift_mps : float
        Speed at which the wave pattern drifts, towards ``sun_azimuth_deg``.
    glint : float
        Strength of the sun glint on wave crests (0: none).
    sun_azimuth_deg, sun_elevation_deg : float
        Where the sun is; it lights TG and sets where the sea glitters.
    shore_distance_m : float
        The shoreline is a ring of this radius about the North-East origin,
        so its disparity is ~0 (1-3 km away along the paths of the suites).
    shore_height_m : float
        Height of the tallest hills; buildings are up to half of it.
    noise_grey : float
        Standard deviation of the sensor noise, grey levels.
    blur_px : float
        Standard deviation of the optics' Gaussian blur, px (0: none).
    """

    height_px: Annotated[Integer, Ge(8)] = 240
    camera_height_m: Positive = 1.0
    hull_length_m: Positive = 4.0
    hull_beam_m: Positive = 1.8
    freeboard_m: Positive = 0.8
    cabin_height_m: Positive = 0.55
    marker_radius_m: Positive = 0.3
    marker_height_m: Positive = 0.6
    marker_bgr: Colour = (20.0, 200.0, 235.0)
    sky_zenith_bgr: Colour = (185.0, 120.0, 70.0)
    sky_horizon_bgr: Colour = (225.0, 212.0, 200.0)
    sea_bgr: Colour = (95.0, 75.0, 40.0)
    wave_contrast: NonNegative = 0.35
    wave_length_m: Positive = 1.2
    wave_drift_mps: NonNegative = 0.8
    glint: NonNegative = 0.8
    sun_azimuth_deg: Number = 120.0
    sun_elevation_deg: Annotated[Number, Interval(gt=0, lt=90)] = 35.0
    shore_distance_m: Annotated[Number, Gt(100)] = 2000.0
    shore_height_m: Positive = 200.0
    noise_grey: NonNegative = 2.0
    blur_px: NonNegative = 0.5

    def __post_init__(self) -> None:
        if not 2.0 * self.marker_radius_m < min(self.hull_beam_m, self.hull_length_m):
            raise ValueError("the marker must fit on the cabin: 2 marker_radius_m < hull beam and length")


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class StereoImageSceneSpec(StereoSceneSpec):
    """A simulated stereo sequence rendered as image pairs (seeds/002, section 4.1).

    All fields of :class:`~benchmark.modalities.stereo.scenes.spec.StereoSceneSpec`
    keep their meaning: the same paths, speeds and seed give the same
    trajectories and the same GPS and compass errors.  The camera's pixel
    noise and dropouts are not used: what the images show decides what a
    front end measures.

    Attributes
    ----------
    render : StereoRenderSpec
        The appearance of the scene.
    """

    render: StereoRenderSpec = field(default_factory=StereoRenderSpec)

    @property
    def frame_size(self) -> tuple[int, int]:
        """``(W, H)`` of each image, px."""
        return self.camera.width_px, self.render.height_px
