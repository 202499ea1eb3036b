"""Stereo observations with no target in them, for the conformance kit.

The front end of a stereo tracker loses the target (no measurement), or
locks onto something else in view: another boat, a wave crest (seeds/002,
section 4.1).  In the image suites the cameras also deliver black,
saturated or noisy pairs.  A stereo tracker may keep predicting or report
nothing, but must not raise or return an invalid estimate.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from benchmark.modalities.stereo.geometry import project
from benchmark.modalities.stereo.model import StereoCalibration, StereoMeasurement
from benchmark.model import Frame, SequenceInfo

NEAREST_M = 2.0
"""The nearest a decoy measurement lies ahead of the camera, m."""


def decoy(calibration: StereoCalibration, rng: np.random.Generator) -> StereoMeasurement | None:
    """A measurement of a random point in view: ahead within the range limit, inside both images.

    None if the calibration's field of view holds no such point.

    References
    ----------
    seeds/002, eq. (15) (the measurement is consistent: ``relative_m`` triangulates to ``(y_l, y_r)``).
    """
    ahead = rng.uniform(NEAREST_M, max(calibration.range_limit_m, NEAREST_M + 1.0))
    half_width = 0.5 * calibration.width_px * ahead / calibration.focal_px
    starboard = rng.uniform(-half_width, half_width) + 0.5 * calibration.baseline_m
    left, right = project(ahead, starboard, calibration)
    if not (0.0 <= left < calibration.width_px and 0.0 <= right < calibration.width_px):
        return None
    return StereoMeasurement(float(left), float(right), (float(ahead), float(starboard)))


def _pairs(pair: tuple[np.ndarray, np.ndarray], rng: np.random.Generator) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    left, right = (np.asarray(image) for image in pair)
    return {
        "blank": (np.zeros_like(left), np.zeros_like(right)),
        "saturated": (np.full_like(left, 255), np.full_like(right, 255)),
        "noise": tuple(rng.integers(0, 256, size=image.shape, dtype=np.uint8) for image in (left, right)),
    }


def hard_observations(frame: Frame, info: SequenceInfo, rng: np.random.Generator) -> dict[str, Any]:
    """What a stereo tracker may receive when the target is not what the front end sees.

    Parameters
    ----------
    frame : Frame
        A stereo frame: a measurement, None, or an image pair.
    info : SequenceInfo
        Its sequence; its :class:`StereoCalibration`, when it has one, places the decoy.
    rng : numpy.random.Generator
        Draws the decoy and the noise.

    Returns
    -------
    dict
        ``"lost"``: None (no measurement); ``"decoy"``: a measurement of a
        random point in view (:func:`decoy`), when the sequence has a
        calibration; and for an image pair ``"blank"``, ``"saturated"``
        and ``"noise"`` pairs of its images' shape.
    """
    observations: dict[str, Any] = {"lost": None}
    if isinstance(info.calibration, StereoCalibration):
        measurement = decoy(info.calibration, rng)
        if measurement is not None:
            observations["decoy"] = measurement
    if isinstance(frame.observation, tuple | list) and len(frame.observation) == 2:
        observations.update(_pairs(tuple(frame.observation), rng))
    return observations
