"""The stereo front end of the field system: colour tracker plus block-matching disparity.

In the field experiments of seeds/002, section 4.1, the target boat (TG)
carries a yellow blob; a colour tracker follows it in the left image while
the stereo camera computes a disparity map (Fig. 10), and TG's range comes
from the disparities inside the tracked region.  For the TLD tracker the
paper takes "the median of disparity values corresponding to the upper half
subset of the entire range of disparity values" inside the bounding box
(section 4.2), the part of the region nearest the camera.  :func:`measure`
does the same for a rectified pair ``(left, right)``:

1. colour tracker: threshold the left image in HSV for the marker's yellow
   and keep the largest connected component (at least
   ``min_blob_px`` pixels); its centroid column is ``y_l``;
2. disparity: OpenCV's block matcher (:class:`cv2.StereoBM`) on the grey
   images, left image as the reference, over the rows of the blob only
   (rows are epipolar lines, so a band of rows is a smaller rectified
   pair); its output is fixed point, 16 units per pixel;
3. TG's disparity ``d``: the median of the upper half of the valid
   disparities at the blob's pixels;
4. ``y_r = y_l - d`` and the relative position by eq. (15)
   (:func:`benchmark.modalities.stereo.geometry.triangulate`).

It reports nothing (None) when there is no blob, no valid disparity in it,
or the disparity is too small to give a range (``min_disparity_px``, as the
simulated front end of :mod:`benchmark.modalities.stereo.scenes.sensors`).

The disparities here are small: 2.8 px at 6 m and 0.7 px at 24 m for the
Bumblebee2 at 320 px (Table 3), so everything rests on the matcher's
sub-pixel step.  It refines its best integer shift to 1/16 px from the
matching costs of the two neighbouring shifts, which it can only do when
the best shift is not an end of the search range.  With OpenCV's default
``minDisparity = 0`` a target beyond 16.9 m has its best shift at 0 or 1,
the end of the range, and on the ``stereo-images`` suite 11 % of the raw
disparities in the blob there come out as exactly 0 or 1 px (26 % with the
default x-Sobel pre-filter) and 4 % of those frames (9 %) get no valid
disparity at all; a negative ``min_disparity`` moves the end of the range
out of the way, and every frame is measured.  The normalising pre-filter
with the largest clip and the 11 px window of the Bumblebee2's matcher
(section 2.2.1) roughly halve the spread of the disparity error against
the x-Sobel pre-filter with a 9 px window (from 0.13-0.15 px to
0.08-0.11 px).  The images are padded on both sides before matching, so a
marker near an image border still has disparities.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Annotated, Any, Literal

import cv2
import numpy as np
import pydantic
from annotated_types import Ge, Interval

from benchmark.errors import DataError
from benchmark.modalities.stereo.geometry import triangulate
from benchmark.modalities.stereo.model import StereoCalibration, StereoMeasurement
from benchmark.parameters import NonNegative

DISPARITY_SCALE = 16
""":class:`cv2.StereoBM` returns disparities in fixed point with 4 fractional bits."""

PREFILTERS = {
    "normalized": cv2.StereoBM_PREFILTER_NORMALIZED_RESPONSE,
    "xsobel": cv2.StereoBM_PREFILTER_XSOBEL,
}
"""The block matcher's pre-filters by name."""

# The domain of each front-end parameter, declared once: :class:`FrontEndParams`
# and the trackers' flat ``frontend_*`` parameters
# (:class:`benchmark.modalities.stereo.observation.FrontEndSettings`) both use these types.

Hue = Annotated[int, Interval(ge=0, lt=180)]
"""A hue in OpenCV's 8-bit HSV, ``[0, 180)``."""

Level = Annotated[int, Interval(ge=0, le=255)]
"""A saturation or value in OpenCV's 8-bit HSV, ``[0, 255]``."""

BlobSize = Annotated[int, Ge(1)]
"""A number of pixels of a blob, at least 1."""

DisparityRange = Annotated[int, Ge(16)]
"""``numDisparities``: at least 16 (a multiple of 16, :func:`front_end_rules`)."""

WindowSize = Annotated[int, Interval(ge=5, le=255)]
"""``blockSize`` or ``preFilterSize``: 5-255 px (odd, :func:`front_end_rules`)."""

Threshold = Annotated[int, Ge(0)]
"""``textureThreshold``, ``uniquenessRatio`` or ``speckleWindowSize``: not negative."""

Prefilter = Literal["normalized", "xsobel"]
"""A pre-filter of :data:`PREFILTERS`."""

PrefilterCap = Annotated[int, Interval(ge=1, le=63)]
"""``preFilterCap``: 1-63."""


def front_end_rules(values: Mapping[str, Any], prefix: str = "") -> None:
    """Check the front end's rules that are not bounds of one parameter.

    ``hue_min <= hue_max``; ``num_disparities`` a multiple of 16 and
    ``block_size`` and ``prefilter_size`` odd, as :class:`cv2.StereoBM` requires.

    Parameters
    ----------
    values : Mapping
        The front end's parameters by their :class:`FrontEndParams` names.
    prefix : str
        Prefix of the parameters' names in messages (``"frontend_"`` for a
        tracker's flat parameters).

    Raises
    ------
    ValueError
        Naming the parameter (with ``prefix``) and its value.
    """
    if values["hue_min"] > values["hue_max"]:
        raise ValueError(
            f"{prefix}hue_min must not exceed {prefix}hue_max, got {values['hue_min']} > {values['hue_max']}"
        )
    if values["num_disparities"] % 16:
        raise ValueError(f"{prefix}num_disparities must be a multiple of 16, got {values['num_disparities']}")
    for name in ("block_size", "prefilter_size"):
        if values[name] % 2 == 0:
            raise ValueError(f"{prefix}{name} must be odd, got {values[name]}")


@pydantic.dataclasses.dataclass(frozen=True)
class FrontEndParams:
    """Parameters of the colour tracker and the block matcher.

    The hue, saturation and value bounds are in OpenCV's 8-bit HSV: hue in
    ``[0, 180)`` (yellow is about 30), saturation and value in ``[0, 255]``.
    Each field's type declares its domain; the rules that are not bounds are
    :func:`front_end_rules`.  A value outside them is a
    :class:`pydantic.ValidationError`.
    """

    hue_min: Hue = 18
    """Lowest hue of the marker."""

    hue_max: Hue = 40
    """Highest hue of the marker."""

    saturation_min: Level = 110
    """Lowest saturation of the marker: white hulls, haze and sky are far less saturated."""

    value_min: Level = 80
    """Lowest brightness of the marker: its side away from the sun is still this bright."""

    min_blob_px: BlobSize = 3
    """Fewest pixels of a blob taken as the marker (a 0.6 m drum at 24 m covers about 12)."""

    num_disparities: DisparityRange = 16
    """Width of the disparity search range, a positive multiple of 16 (``numDisparities``)."""

    min_disparity: int = -3
    """Lowest disparity searched (``minDisparity``); negative so that sub-pixel disparities get refined."""

    block_size: WindowSize = 11
    """Side of the matching window, odd, 5-255 (``blockSize``); 11 px is the mask of seeds/002, section 2.2.1."""

    texture_threshold: Threshold = 10
    """Windows with less texture (sum of pre-filtered absolute values) are invalid (``textureThreshold``)."""

    uniqueness_ratio: Threshold = 5
    """Percent by which the best match must beat the second best (``uniquenessRatio``)."""

    prefilter: Prefilter = "normalized"
    """Pre-filter of both images: ``"normalized"`` (each pixel minus its window mean, over the window's
    spread) or ``"xsobel"`` (horizontal derivative), ``preFilterType``."""

    prefilter_size: WindowSize = 9
    """Window of the normalising pre-filter, odd, 5-255 (``preFilterSize``)."""

    prefilter_cap: PrefilterCap = 63
    """Clip of the pre-filtered image (``preFilterCap``, 1-63)."""

    speckle_window: Threshold = 0
    """Speckle filter window (``speckleWindowSize``); 0 turns the filter off."""

    min_disparity_px: NonNegative = 0.3
    """TG's disparity (less ``C_y - C_y*``) must exceed this, px: 0.3 px is about 56 m, where the
    matcher's 1/16 px steps and the upward pull of the upper-half median (about 0.1 px even for
    a target at infinity) leave no range worth reporting."""

    def __post_init__(self) -> None:
        front_end_rules(dataclasses.asdict(self))


@dataclass(frozen=True)
class Blob:
    """The marker found by the colour tracker in the left image.

    Attributes
    ----------
    column_px : float
        Centroid column, ``y_l``.
    row_px : float
        Centroid row.
    box : tuple of int
        ``(left, top, width, height)`` of its bounding box, px.
    mask : numpy.ndarray
        Boolean, shape ``(height, width)`` of the box: the blob's pixels.
    """

    column_px: float
    row_px: float
    box: tuple[int, int, int, int]
    mask: np.ndarray


def find_marker(left: np.ndarray, params: FrontEndParams) -> Blob | None:
    """The colour tracker: the largest yellow connected component of the left image.

    Parameters
    ----------
    left : numpy.ndarray
        ``uint8`` BGR image.
    params : FrontEndParams
        HSV bounds and the smallest blob.

    Returns
    -------
    Blob or None
        None when no component has ``min_blob_px`` pixels.

    References
    ----------
    seeds/002, section 4.1 and Fig. 10: a yellow blob on TG, tracked by colour.
    """
    hsv = cv2.cvtColor(left, cv2.COLOR_BGR2HSV)
    lower = (params.hue_min, params.saturation_min, params.value_min)
    upper = (params.hue_max, 255, 255)
    mask = cv2.inRange(hsv, lower, upper)
    count, labels, stats, centroids = cv2.connectedComponentsWithStats(mask, connectivity=8)
    if count < 2:
        return None
    areas = stats[1:, cv2.CC_STAT_AREA]
    label = int(np.argmax(areas)) + 1
    if stats[label, cv2.CC_STAT_AREA] < params.min_blob_px:
        return None
    x, y, w, h = (int(v) for v in stats[label, :4])
    return Blob(
        column_px=float(centroids[label, 0]),
        row_px=float(centroids[label, 1]),
        box=(x, y, w, h),
        mask=labels[y : y + h, x : x + w] == label,
    )


def _matcher(params: FrontEndParams) -> cv2.StereoBM:
    matcher = cv2.StereoBM.create(numDisparities=params.num_disparities, blockSize=params.block_size)
    matcher.setMinDisparity(params.min_disparity)
    matcher.setTextureThreshold(params.texture_threshold)
    matcher.setUniquenessRatio(params.uniqueness_ratio)
    matcher.setPreFilterType(PREFILTERS[params.prefilter])
    matcher.setPreFilterSize(params.prefilter_size)
    matcher.setPreFilterCap(params.prefilter_cap)
    matcher.setSpeckleWindowSize(params.speckle_window)
    return matcher


def blob_disparities(left: np.ndarray, right: np.ndarray, blob: Blob, params: FrontEndParams) -> np.ndarray:
    """Valid block-matching disparities at the blob's pixels, px.

    Parameters
    ----------
    left, right : numpy.ndarray
        The rectified ``uint8`` BGR pair.
    blob : Blob
        The marker in the left image.
    params : FrontEndParams
        Block matcher settings.

    Returns
    -------
    numpy.ndarray
        ``d = y_l - y_r`` (positive for a point ahead) at every blob pixel
        where the matcher found a valid match, ``float``.

    References
    ----------
    seeds/002, section 4.1 and Fig. 10 (the disparity map), eq. (15)
    (``d = y_l - y_r``).
    """
    x, y, w, h = blob.box
    half = params.block_size // 2
    height = left.shape[0]
    top, bottom = max(y - half - 1, 0), min(y + h + half + 1, height)
    # Pad the band so that the matcher's window and search range fit round any blob pixel.
    pad_rows = max(0, params.block_size + 2 - (bottom - top))
    pad_left = params.num_disparities + params.min_disparity + params.block_size
    pad_right = max(0, -params.min_disparity) + params.block_size
    grey = []
    for image in (left, right):
        band = cv2.cvtColor(image[top:bottom], cv2.COLOR_BGR2GRAY)
        grey.append(cv2.copyMakeBorder(band, 0, pad_rows, max(pad_left, 0), pad_right, cv2.BORDER_REPLICATE))
    raw = _matcher(params).compute(grey[0], grey[1])
    rows = slice(y - top, y - top + h)
    cols = slice(x + max(pad_left, 0), x + max(pad_left, 0) + w)
    values = raw[rows, cols][blob.mask]
    # Invalid pixels hold (minDisparity - 1) * 16.
    valid = values[values >= params.min_disparity * DISPARITY_SCALE]
    return valid.astype(float) / DISPARITY_SCALE


def upper_half_median(disparities: np.ndarray) -> float:
    """The median of the upper half of a set of disparities.

    The values are sorted and the larger half kept (for an odd count the
    middle value too); their median is the result.  The larger
    disparities belong to the part of the region nearest the camera: the
    marker itself rather than the farther background that the matching
    windows on the blob's border take in.

    Parameters
    ----------
    disparities : numpy.ndarray
        At least one value.

    Returns
    -------
    float

    References
    ----------
    seeds/002, section 4.2: "the median of disparity values corresponding
    to the upper half subset of the entire range of disparity values".
    """
    ordered = np.sort(np.asarray(disparities, dtype=float))
    return float(np.median(ordered[len(ordered) // 2 :]))


def measure(
    left: np.ndarray,
    right: np.ndarray,
    calibration: StereoCalibration,
    params: FrontEndParams | None = None,
) -> StereoMeasurement | None:
    """TG's image coordinates and relative position from one rectified stereo pair.

    Parameters
    ----------
    left, right : numpy.ndarray
        ``uint8`` BGR images of the same shape ``(H, W, 3)``.
    calibration : StereoCalibration
        Focal length, baseline and principal points for eq. (15).
    params : FrontEndParams, optional
        Defaults to ``FrontEndParams()``.

    Returns
    -------
    StereoMeasurement or None
        ``y_l`` (blob centroid column), ``y_r = y_l - d`` and ``(x_v, y_v)``
        by eq. (15); None when the marker is not found, has no valid
        disparity, or its disparity does not exceed
        ``C_y - C_y* + min_disparity_px``.

    Raises
    ------
    DataError
        If the images are not two ``uint8`` BGR images of the same shape.

    References
    ----------
    seeds/002, section 4.1 (colour tracker and disparity map, Fig. 10),
    section 4.2 (median of the upper half of the disparities) and eq. (15).
    """
    params = FrontEndParams() if params is None else params
    for name, image in (("left", left), ("right", right)):
        if not (isinstance(image, np.ndarray) and image.dtype == np.uint8 and image.ndim == 3 and image.shape[2] == 3):
            raise DataError(f"stereo front end: the {name} image must be a uint8 BGR array of shape (H, W, 3)")
    if left.shape != right.shape:
        raise DataError(f"stereo front end: left image {left.shape} and right image {right.shape} differ in shape")
    blob = find_marker(left, params)
    if blob is None:
        return None
    disparities = blob_disparities(left, right, blob, params)
    if disparities.size == 0:
        return None
    disparity = upper_half_median(disparities)
    if not disparity - (calibration.principal_left_px - calibration.principal_right_px) > params.min_disparity_px:
        return None
    y_l = blob.column_px
    y_r = y_l - disparity
    ahead, starboard = triangulate(y_l, y_r, calibration)
    return StereoMeasurement(left_px=y_l, right_px=y_r, relative_m=(float(ahead), float(starboard)))
