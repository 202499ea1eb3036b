"""Hypothesis strategies of the stereo modality, for property-based tests of stereo trackers.

Four strategies, from the camera to whole sequences:

* :func:`calibrations`: a plausible stereo camera, a
  :class:`~benchmark.modalities.stereo.model.StereoCalibration`;
* :func:`stereo_measurements`: what a front end reports of a target in
  view and within the operational range, triangulated by eq. (15) of
  seeds/002 (:func:`benchmark.modalities.stereo.geometry.triangulate`);
* :func:`scene_specs`: a short random scene, chase boat and target boat on
  random paths with random speed profiles, random sensor errors and
  dropouts, and for the rendered suite a random look of sea and sky;
* :func:`sequences`: the scenes such specs simulate, their frames holding
  measurements or rendered image pairs: the strategy the conformance kit
  (:mod:`benchmark.testing`) draws stereo sequences from.

Every draw is a pure function of hypothesis' choices: scenes get their seed
from hypothesis, so a failing example shrinks and replays exactly.

Examples
--------
>>> from hypothesis import given
>>> @given(sequences())
... def test_my_tracker_runs_on_any_scene(sequence):
...     ...
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from hypothesis import strategies as st

from benchmark.modalities.stereo.geometry import triangulate
from benchmark.modalities.stereo.model import StereoCalibration, StereoMeasurement
from benchmark.modalities.stereo.scenes.image_spec import StereoImageSceneSpec, StereoRenderSpec
from benchmark.modalities.stereo.scenes.images import StereoImageScene
from benchmark.modalities.stereo.scenes.motion import BoatTrack, boat_track
from benchmark.modalities.stereo.scenes.scene import MIN_SEPARATION_M, StereoScene
from benchmark.modalities.stereo.scenes.spec import (
    BoatSpec,
    PathSpec,
    SpeedKnots,
    StereoCameraSpec,
    StereoSceneSpec,
    StereoSensorSpec,
)
from benchmark.model import Sequence

CALIBRATION_WIDTHS_PX = (64, 1280)
"""Image widths of :func:`calibrations`."""

RENDERED_WIDTHS_PX = (32, 128)
RENDERED_HEIGHTS_PX = (24, 96)
"""Image sizes of rendered scenes: small, so that a few frames render in milliseconds."""

ROUNDING_MARGIN_PX = 1e-6
"""Measurements keep this far inside their bounds, so that rounding never carries them across."""

SEPARATION_MARGIN_M = 0.5
"""Boats stay this much farther apart than the scenes' :data:`MIN_SEPARATION_M`."""

TOP_SPEED_MPS = 9.0
"""Fastest boat: TG's top speed in the fast class of seeds/002, section 3.5."""


def _zero_or(low: float, high: float) -> st.SearchStrategy[float]:
    """0, which turns a feature off, or a value in ``[low, high]``, never a vanishing one in between."""
    return st.one_of(st.just(0.0), st.floats(low, high))


@st.composite
def _camera_specs(draw: st.DrawFn, widths_px: tuple[int, int]) -> StereoCameraSpec:
    """Stereo cameras with a horizontal field of view of 30-100 degrees."""
    width = draw(st.integers(*widths_px))
    field_of_view = math.radians(draw(st.floats(30.0, 100.0)))
    centre = (width - 1) / 2.0
    return StereoCameraSpec(
        focal_px=width / 2.0 / math.tan(field_of_view / 2.0),
        baseline_m=draw(st.floats(0.05, 0.6)),
        width_px=width,
        principal_left_px=centre + width * draw(st.floats(-0.05, 0.05)),
        principal_right_px=centre + width * draw(st.floats(-0.05, 0.05)),
        range_limit_m=draw(st.floats(5.0, 50.0)),
        correlation_accuracy_px=draw(st.floats(0.0, 0.5)),
    )


def calibrations() -> st.SearchStrategy[StereoCalibration]:
    """Plausible stereo cameras.

    Returns
    -------
    SearchStrategy of StereoCalibration
        Width 64-1280 px; focal length for a horizontal field of view of
        30-100 degrees; baseline 0.05-0.6 m; each principal point within
        5 % of the width of the image centre; range limit 5-50 m;
        correlation accuracy 0-0.5 px.  A target straight ahead at the
        range limit is in view of both cameras.

    References
    ----------
    seeds/002, Tables 3 and 4 (the Bumblebee2: 320 px, 12 cm, 16 m, 0.11 px).
    """
    return _camera_specs(CALIBRATION_WIDTHS_PX).map(StereoCameraSpec.calibration)


def stereo_measurements(calibration: StereoCalibration | None = None) -> st.SearchStrategy[StereoMeasurement]:
    """Measurements of a target in view of both cameras and within the range limit.

    Here the disparity is corrected for the principal points,
    ``(y_l - C_y) - (y_r - C_y*)``: positive for a target in front of the
    camera, ``f B / x_v`` for a target ``x_v`` ahead.

    Parameters
    ----------
    calibration : StereoCalibration, optional
        The camera; by default one drawn from :func:`calibrations`.

    Returns
    -------
    SearchStrategy of StereoMeasurement
        ``left_px`` and ``right_px`` inside the image, ``[-0.5, width - 0.5]``;
        the disparity from ``f B / range_limit_m`` (the target at the range
        limit) up to the largest that fits in the image (the nearest
        target); ``relative_m`` their triangulation by eq. (15).

    Raises
    ------
    ValueError
        If no target within the range limit is in view of both cameras of
        ``calibration``.

    References
    ----------
    seeds/002, eqs. (13) and (15).
    """
    if calibration is None:
        return calibrations().flatmap(_measurements_in)
    return _measurements_in(calibration)


def _measurements_in(calibration: StereoCalibration) -> st.SearchStrategy[StereoMeasurement]:
    """Measurements within range and inside both images of ``calibration``; see :func:`stereo_measurements`."""
    first, last = -0.5 + ROUNDING_MARGIN_PX, calibration.width_px - 0.5 - ROUNDING_MARGIN_PX
    principal_offset = calibration.principal_left_px - calibration.principal_right_px
    # y_r = y_l - (disparity + principal_offset) keeps both inside [first, last] while that shift is at most the span
    span = last - first
    least = max(calibration.focal_px * calibration.baseline_m / calibration.range_limit_m, -span - principal_offset)
    least += ROUNDING_MARGIN_PX
    most = span - principal_offset
    if not least <= most:
        raise ValueError(f"no target within the range limit is in view of both cameras of {calibration}")

    @st.composite
    def measurements(draw: st.DrawFn) -> StereoMeasurement:
        shift = draw(st.floats(least, most)) + principal_offset
        left = draw(st.floats(max(first, first + shift), min(last, last + shift)))
        right = left - shift
        ahead, starboard = triangulate(left, right, calibration)
        return StereoMeasurement(left_px=left, right_px=right, relative_m=(float(ahead), float(starboard)))

    return measurements()


@st.composite
def _speed_knots(draw: st.DrawFn) -> SpeedKnots:
    """One to three knots a fraction of a second to a few seconds apart, speeds up to :data:`TOP_SPEED_MPS`."""
    speeds = draw(st.lists(st.floats(0.0, TOP_SPEED_MPS), min_size=1, max_size=3))
    gaps = draw(st.lists(st.floats(0.1, 5.0), min_size=len(speeds) - 1, max_size=len(speeds) - 1))
    times = np.concatenate(([0.0], np.cumsum(gaps)))
    return tuple((float(time), speed) for time, speed in zip(times, speeds))


@st.composite
def _paths(draw: st.DrawFn) -> PathSpec:
    """Straight lines and sinusoids, from the North-East origin on a random course."""
    sinusoid = draw(st.booleans())
    return PathSpec(
        course_deg=draw(st.floats(-180.0, 180.0)),
        amplitude_m=draw(st.floats(0.5, 15.0)) if sinusoid else 0.0,
        wavelength_m=draw(st.floats(20.0, 200.0)),
        phase_deg=draw(st.floats(-180.0, 180.0)),
        onset_m=draw(st.floats(0.0, 50.0)),
        ramp_m=draw(_zero_or(1.0, 60.0)),
    )


def _boats() -> st.SearchStrategy[BoatSpec]:
    return st.builds(BoatSpec, path=_paths(), start_m=st.floats(0.0, 50.0), speed_knots=_speed_knots())


def _sensors() -> st.SearchStrategy[StereoSensorSpec]:
    return st.builds(
        StereoSensorSpec,
        gps_sigma_m=st.floats(0.0, 2.0),
        gps_correlation_s=_zero_or(0.2, 5.0),
        heading_sigma_deg=st.floats(0.0, 3.0),
        min_disparity_px=st.floats(0.0, 1.0),
        dropout_rate=st.floats(0.0, 0.6),
        dropout_burst_frames=st.floats(1.0, 5.0),
    )


def _render_specs() -> st.SearchStrategy[StereoRenderSpec]:
    return st.builds(
        StereoRenderSpec,
        height_px=st.integers(*RENDERED_HEIGHTS_PX),
        camera_height_m=st.floats(0.5, 3.0),
        wave_contrast=st.floats(0.0, 0.6),
        wave_length_m=st.floats(0.5, 3.0),
        glint=st.floats(0.0, 1.5),
        sun_azimuth_deg=st.floats(0.0, 360.0),
        sun_elevation_deg=st.floats(5.0, 85.0),
        noise_grey=st.floats(0.0, 8.0),
        blur_px=_zero_or(0.2, 1.5),
    )


def _nearest_safe_range(chase: BoatTrack, target: BoatTrack, direction: np.ndarray) -> float:
    """The least start range along ``direction`` from the chase boat that keeps the boats apart throughout.

    With the target starting ``r`` along the unit vector ``direction``,
    their separation at each frame is ``r direction + moved``, where
    ``moved`` is how far the target has moved relative to the chase boat
    since the start; its length is at least its component along
    ``direction``, ``r + moved . direction``.
    """
    moved = (target.position_m - target.position_m[0]) - (chase.position_m - chase.position_m[0])
    return MIN_SEPARATION_M + SEPARATION_MARGIN_M + max(0.0, -float(np.min(moved @ direction)))


@st.composite
def scene_specs(
    draw: st.DrawFn, max_frames: int = 4, *, images: bool = False
) -> StereoSceneSpec | StereoImageSceneSpec:
    """Random, valid specs of short stereo scenes.

    The chase boat (CH) and the target boat (TG) each follow a straight or
    sinusoidal path on a random course, from a random start along it, with
    a random speed profile.  TG starts within 90 % of the camera's
    half-field of view off CH's bow, 0-30 m beyond the nearest range at
    which the boats stay more than :data:`MIN_SEPARATION_M` apart
    throughout; it may drift out of view or out of range later.

    Parameters
    ----------
    max_frames : int
        Most frames of a scene, at least 1.
    images : bool
        Specs of the rendered ``stereo-images`` suite (small images and a
        random look of sea, sky and sun) rather than of the ``stereo`` one.

    Returns
    -------
    SearchStrategy of StereoSceneSpec or StereoImageSceneSpec
        A random seed; 1 to ``max_frames`` frames 0.05-0.5 s apart; a
        camera as :func:`calibrations` draws them (32-128 px wide when
        ``images``); GPS noise up to 2 m, compass noise up to 3 degrees,
        dropouts of up to 60 % of the frames in bursts of 1-5.

    References
    ----------
    seeds/002, section 3 (the simulations: paths, constant-acceleration
    speed legs, noisy measurements and navigation) and section 4.1 (the
    field system's images).
    """
    seed = draw(st.integers(0, 2**32 - 1))
    n_frames = draw(st.integers(1, max_frames))
    frame_interval_s = draw(st.floats(0.05, 0.5))
    camera = draw(_camera_specs(RENDERED_WIDTHS_PX if images else CALIBRATION_WIDTHS_PX))
    chase = draw(_boats())
    target = draw(_boats())

    times = np.arange(n_frames) * frame_interval_s
    chase_track, target_track = boat_track(chase, times), boat_track(target, times)
    calibration = camera.calibration()
    half_view = math.atan(calibration.width_px / 2.0 / calibration.focal_px)
    bearing = half_view * draw(st.floats(-0.9, 0.9))
    direction = np.array((math.cos(chase_track.heading[0] + bearing), math.sin(chase_track.heading[0] + bearing)))
    start_range_m = _nearest_safe_range(chase_track, target_track, direction) + draw(st.floats(0.0, 30.0))
    start = chase_track.position_m[0] + start_range_m * direction
    # the target's path was drawn from the origin: move it so that the target starts there
    north, east = start - target_track.position_m[0]
    target = dataclasses.replace(target, path=dataclasses.replace(target.path, origin_m=(float(north), float(east))))

    kind, spec_type = ("stereo-images", StereoImageSceneSpec) if images else ("stereo", StereoSceneSpec)
    look = {"render": draw(_render_specs())} if images else {}
    return spec_type(
        name=f"{kind}/random-{seed}",
        n_frames=n_frames,
        seed=seed,
        description=f"TG starts {start_range_m:.1f} m away, {math.degrees(bearing):+.0f} deg off CH's bow",
        frame_interval_s=frame_interval_s,
        camera=camera,
        sensors=draw(_sensors()),
        target=target,
        chase=chase,
        **look,
    )


def sequences(max_frames: int = 4) -> st.SearchStrategy[Sequence]:
    """Short simulated stereo sequences, of measurements or of rendered image pairs.

    Parameters
    ----------
    max_frames : int
        Most frames of a sequence, at least 1.

    Returns
    -------
    SearchStrategy of Sequence
        A :class:`~benchmark.modalities.stereo.scenes.scene.StereoScene` or a
        :class:`~benchmark.modalities.stereo.scenes.images.StereoImageScene`
        of a spec from :func:`scene_specs`: 1 to ``max_frames`` labelled
        frames, whose observations are measurements (None where the front
        end lost the target) or image pairs of at most 128 x 96 px.

    References
    ----------
    seeds/002, sections 3 and 4.1.
    """
    measured = scene_specs(max_frames).map(StereoScene)
    rendered = scene_specs(max_frames, images=True).map(StereoImageScene)
    return st.one_of(measured, rendered)
