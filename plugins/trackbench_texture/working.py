"""The image the descriptors are measured on: the frame at a working size, its grey levels normalised.

Grau et al. measured their descriptors on the frames of one camera at one
exposure (seeds/000, section 2.2), so that masks in pixels and steps in
grey levels meant the same on every frame their classes were learned from.
A model that is to apply to other frames needs the same guarantee, and the
method allows it, since each descriptor is a density of pixels picked by
a mask and a threshold:

* **Size.**  The frame is resampled to ``working_height_px`` rows (its
  aspect kept; area averaging when shrinking), so that every size in pixels
  (masks, neighbourhood, grid, border tests) is a share of the frame's
  height: the same cable seen at 320 x 240 and at 640 x 480 gives the same
  descriptors.  0 keeps the frame as it is (the thesis' reading, one camera).
* **Grey levels.**  The thresholds (Canny's, the speck and the soft steps)
  are grey-level differences; a frame at another exposure or contrast
  would cross them on other pixels.  A normaliser (:data:`NORMALISERS`)
  maps the frame's grey levels to a reference spread first, so that the
  thresholds are in units of the frame's own contrast.

:class:`WorkingImage` keeps the scale, and maps lines found on the working
image back to the frame's pixels.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import cv2
import numpy as np

from benchmark.modalities.camera.geometry import Line
from benchmark.modalities.camera.io.video import check_grey_image

Normalisation = Literal["none", "global", "local"]
"""The names of :data:`NORMALISERS`."""

REFERENCE_GREY = 128.0
"""Grey level a normalised image is centred on."""

LOCAL_FLOOR_SHARE = 0.25
"""The local normaliser divides by no less than this share of the whole image's spread.

A flat patch of seabed (spread of a grey level or two: noise and JPEG's
blocks) would otherwise be stretched to the full reference spread, and its
blocks' edges become lines.  On camera-train (2-fold by sequence) 52.6 %
correct with the floor against 51.1 % without; on camera-dev 64.3 against
66.0 %: no difference beyond the sequences' spread, and the floor keeps
the stretch of any patch to at most four times the image's.
"""


def _unchanged(image: np.ndarray, spread: float, scale_px: float) -> np.ndarray:
    """The image as it is (the thesis' reading)."""
    return image


def _global(image: np.ndarray, spread: float, scale_px: float) -> np.ndarray:
    """The whole image shifted and scaled to mean :data:`REFERENCE_GREY` and standard deviation ``spread``."""
    mean, sd = cv2.meanStdDev(image.astype(np.float32))
    gain = spread / max(float(sd[0, 0]), 1.0)
    # Each grey level maps to the same value wherever it is: the map is worked out once per level.
    levels = np.arange(256, dtype=np.float32)
    return cv2.LUT(image, _to_grey((levels - np.float32(mean[0, 0])) * np.float32(gain)))


def _local(image: np.ndarray, spread: float, scale_px: float) -> np.ndarray:
    """Each pixel's difference to its Gaussian-weighted neighbourhood mean, in units of its neighbourhood's spread.

    The neighbourhood's standard deviation is ``scale_px``; the spread is
    the neighbourhood's standard deviation of grey levels (at least
    :data:`LOCAL_FLOOR_SHARE` of the image's, and one grey level), scaled to ``spread``.  Lamp fall-off, vignetting and daylight
    gradients, slower than the neighbourhood, are taken out with the mean.
    """
    values = image.astype(np.float32)
    mean = cv2.GaussianBlur(values, (0, 0), scale_px, borderType=cv2.BORDER_REFLECT)
    power = cv2.GaussianBlur(values * values, (0, 0), scale_px, borderType=cv2.BORDER_REFLECT)
    floor = max(LOCAL_FLOOR_SHARE * float(cv2.meanStdDev(values)[1][0, 0]), 1.0) ** 2
    sd = np.sqrt(np.maximum(power - mean * mean, np.float32(floor)))
    return _to_grey((values - mean) * (np.float32(spread) / sd))


def _to_grey(centred: np.ndarray) -> np.ndarray:
    return np.clip(np.rint(centred + np.float32(REFERENCE_GREY)), 0, 255).astype(np.uint8)


NORMALISERS: dict[str, Callable[[np.ndarray, float, float], np.ndarray]] = {
    "none": _unchanged,
    "global": _global,
    "local": _local,
}
"""Grey-level normalisers by name: ``(image, spread, scale_px) -> uint8 image`` of the same shape."""


@dataclass(frozen=True, eq=False)
class WorkingImage:
    """A frame resampled and normalised for the descriptors, and how it maps to the frame.

    Attributes
    ----------
    image : numpy.ndarray
        ``uint8`` grey image of shape ``(h, w)``, its grey levels normalised.
    frame_size : tuple of int
        The frame's ``(W, H)`` in px.
    grey : numpy.ndarray
        The same before normalisation: the frame resampled.
    """

    image: np.ndarray
    frame_size: tuple[int, int]
    grey: np.ndarray

    @property
    def size(self) -> tuple[int, int]:
        """The working image's ``(w, h)`` in px."""
        return self.image.shape[1], self.image.shape[0]

    @property
    def resampled(self) -> bool:
        """Whether the working image has another size than the frame."""
        return self.size != self.frame_size

    def to_frame(self, u: float, v: float) -> tuple[float, float]:
        """The frame pixel ``(u, v)`` of a working-image pixel (pixel centres map to pixel centres' positions)."""
        (w, h), (width, height) = self.size, self.frame_size
        return (u + 0.5) * width / w - 0.5, (v + 0.5) * height / h - 0.5

    def frame_line(self, p: tuple[float, float], q: tuple[float, float]) -> Line:
        """The frame's model-coordinate line through two working-image pixel points."""
        return Line.from_pixels(self.to_frame(*p), self.to_frame(*q), self.frame_size)

    def frame_mask(self, mask: np.ndarray) -> np.ndarray:
        """A ``bool`` frame-sized mask resampled (nearest pixel) to the working image's size."""
        if not self.resampled:
            return mask
        return cv2.resize(mask.view(np.uint8), self.size, interpolation=cv2.INTER_NEAREST).view(bool)


def working_image(
    image: np.ndarray, height_px: int, normalisation: Normalisation, spread: float, scale_share: float
) -> WorkingImage:
    """The frame at ``height_px`` rows (0: as it is), its grey levels normalised.

    Parameters
    ----------
    image : numpy.ndarray
        ``uint8`` grey frame of shape ``(H, W)``.
    height_px : int
        Rows of the working image; 0 keeps the frame's size.
    normalisation : str
        A key of :data:`NORMALISERS`.
    spread : float
        The normalised image's standard deviation of grey levels.
    scale_share : float
        The local normaliser's neighbourhood, a share of the working image's height.

    Returns
    -------
    WorkingImage

    Raises
    ------
    ValueError
        If ``image`` is not a non-empty 2-D ``uint8`` array.
    """
    check_grey_image(image)
    height, width = image.shape
    work = image
    if height_px and height_px != height:
        size = (max(1, round(width * height_px / height)), height_px)
        shrinking = height_px < height
        work = cv2.resize(image, size, interpolation=cv2.INTER_AREA if shrinking else cv2.INTER_LINEAR)
    normalised = NORMALISERS[normalisation](work, spread, max(scale_share * work.shape[0], 0.5))
    return WorkingImage(normalised, (width, height), work)
