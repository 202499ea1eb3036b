"""What a stereo tracker reads from a frame: TG's measurement and CH's navigation.

A stereo frame's observation comes in one of two forms:

* a :class:`benchmark.modalities.stereo.model.StereoMeasurement`, or None when the front end
  lost the target (the simulated ``stereo`` suite, seeds/002, section 3);
* an image pair ``(left, right)`` of ``uint8`` BGR images (the rendered
  ``stereo-images`` suite, section 4.1), which the front end of
  :mod:`benchmark.modalities.stereo.frontend` turns into a measurement or None.

:func:`read_frame` accepts both and returns the measurement with CH's
:class:`~benchmark.modalities.stereo.model.ChaseNavigation`, or None; anything else is a
:class:`~benchmark.errors.DataError` naming the sequence and the frame.

The front end's settings become tracker parameters through
:class:`FrontEndSettings`: one flat field ``frontend_<name>`` per field of
:class:`~benchmark.modalities.stereo.frontend.FrontEndParams`, with the same
default and the same declared domain, so that a tracker's ``Params`` stays
a flat frozen dataclass, ``--param TRACKER.frontend_block_size=9`` reaches
the block matcher and ``--param TRACKER.frontend_block_size=8`` is refused
when the parameters are made.  A tracker's ``Params`` inherits them and
builds the front end's parameters with :func:`front_end_params`.

This module and the front end belong to the stereo modality, so that every
stereo tracker builds on them (``trackbench_stereo_ekf`` and the raw
baseline ``trackbench_stereo_raw`` alike) without one plugin importing
another.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import pydantic

from benchmark.errors import DataError
from benchmark.modalities.stereo.frontend import (
    BlobSize,
    DisparityRange,
    FrontEndParams,
    Hue,
    Level,
    Prefilter,
    PrefilterCap,
    Threshold,
    WindowSize,
    front_end_rules,
    measure,
)
from benchmark.modalities.stereo.model import ChaseNavigation, StereoCalibration, StereoMeasurement
from benchmark.model import Frame, SequenceInfo
from benchmark.parameters import NonNegative

PREFIX = "frontend_"
"""Prefix of the tracker parameters that set the front end."""


@pydantic.dataclasses.dataclass(frozen=True)
class FrontEndSettings:
    """The front end's parameters as flat tracker parameters; see :class:`FrontEndParams` for each.

    Each field has the type, hence the domain, of its :class:`FrontEndParams`
    field, and :meth:`__post_init__` applies the same
    :func:`~benchmark.modalities.stereo.frontend.front_end_rules`, so that
    settings that validate always make valid front-end parameters.  A
    subclass that defines its own ``__post_init__`` must call this one.
    """

    frontend_hue_min: Hue = FrontEndParams.hue_min
    """Lowest hue of the marker (OpenCV's 8-bit HSV)."""

    frontend_hue_max: Hue = FrontEndParams.hue_max
    """Highest hue of the marker."""

    frontend_saturation_min: Level = FrontEndParams.saturation_min
    """Lowest saturation of the marker."""

    frontend_value_min: Level = FrontEndParams.value_min
    """Lowest brightness of the marker."""

    frontend_min_blob_px: BlobSize = FrontEndParams.min_blob_px
    """Fewest pixels of a blob taken as the marker."""

    frontend_num_disparities: DisparityRange = FrontEndParams.num_disparities
    """Width of the block matcher's disparity search range, a positive multiple of 16."""

    frontend_min_disparity: int = FrontEndParams.min_disparity
    """Lowest disparity the block matcher searches, px."""

    frontend_block_size: WindowSize = FrontEndParams.block_size
    """Side of the matching window, odd, 5-255 px (seeds/002, section 2.2.1: 11)."""

    frontend_texture_threshold: Threshold = FrontEndParams.texture_threshold
    """Windows with less texture give no disparity."""

    frontend_uniqueness_ratio: Threshold = FrontEndParams.uniqueness_ratio
    """Percent by which the best match must beat the second best."""

    frontend_prefilter: Prefilter = FrontEndParams.prefilter
    """The matcher's pre-filter, ``"normalized"`` or ``"xsobel"``."""

    frontend_prefilter_size: WindowSize = FrontEndParams.prefilter_size
    """Window of the normalising pre-filter, odd, 5-255 px."""

    frontend_prefilter_cap: PrefilterCap = FrontEndParams.prefilter_cap
    """Clip of the pre-filtered image, 1-63."""

    frontend_speckle_window: Threshold = FrontEndParams.speckle_window
    """Speckle filter window; 0 turns the filter off."""

    frontend_min_disparity_px: NonNegative = FrontEndParams.min_disparity_px
    """TG's disparity (less ``C_y - C_y*``) must exceed this to give a measurement, px."""

    def __post_init__(self) -> None:
        front_end_rules(_front_end_values(self), PREFIX)


def _front_end_values(settings: FrontEndSettings) -> dict[str, Any]:
    """The ``frontend_*`` fields of ``settings`` by their :class:`FrontEndParams` names."""
    return {
        item.name.removeprefix(PREFIX): getattr(settings, item.name) for item in dataclasses.fields(FrontEndSettings)
    }


def front_end_params(settings: FrontEndSettings) -> FrontEndParams:
    """The front end's parameters a tracker's ``frontend_*`` parameters set.

    Parameters
    ----------
    settings : FrontEndSettings
        A tracker's ``Params`` (a subclass), validated when it was made.

    Returns
    -------
    FrontEndParams

    References
    ----------
    seeds/002, section 4.1 (the field system's colour tracker and disparity map).
    """
    return FrontEndParams(**_front_end_values(settings))


def read_frame(
    frame: Frame, info: SequenceInfo, front_end: FrontEndParams
) -> tuple[StereoMeasurement, ChaseNavigation] | None:
    """A frame's measurement of TG and CH's navigation, or None when the frame has no measurement.

    Parameters
    ----------
    frame : Frame
        Its observation is a StereoMeasurement, None, or an image pair
        ``(left, right)``; its navigation a ChaseNavigation.
    info : SequenceInfo
        The sequence: its name for messages, its StereoCalibration for the
        front end.
    front_end : FrontEndParams
        Settings of the front end that measures an image pair.

    Returns
    -------
    tuple of (StereoMeasurement, ChaseNavigation) or None
        None when the observation is None or the front end finds no target
        in the pair.

    Raises
    ------
    DataError
        Naming the sequence and the frame, when the observation is of
        another type or a pair of bad images, a pair comes without a
        StereoCalibration, or a measurement comes without CH's
        ChaseNavigation.

    References
    ----------
    seeds/002, section 2.2 (what the stereo camera measures, eq. 15, and
    CH's GPS and heading, eq. 10) and section 4.1 (the field system's front end).
    """
    where = f"sequence {info.name!r}, frame {frame.index}"
    observation = frame.observation
    if isinstance(observation, tuple | list) and len(observation) == 2:
        if not isinstance(info.calibration, StereoCalibration):
            raise DataError(f"{where}: an image pair needs the sequence's StereoCalibration")
        try:
            observation = measure(observation[0], observation[1], info.calibration, front_end)
        except DataError as exc:
            raise DataError(f"{where}: {exc}") from exc
    elif observation is not None and not isinstance(observation, StereoMeasurement):
        raise DataError(
            f"{where}: expected a StereoMeasurement, None or an image pair (left, right), "
            f"got {type(observation).__name__}"
        )
    if observation is None:
        return None
    if not isinstance(frame.navigation, ChaseNavigation):
        raise DataError(
            f"{where}: a measurement needs the chase boat's ChaseNavigation, got {type(frame.navigation).__name__}"
        )
    return observation, frame.navigation
