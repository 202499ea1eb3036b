"""Camera images without a cable in them, for the conformance kit.

A camera tracker meets black frames (lights off, lens covered), white
frames (the lamp's reflection off silt fills the sensor) and frames of
pure sensor noise.  None has a cable to find; a tracker may report none,
but must not raise or return an invalid state.
"""

from __future__ import annotations

import numpy as np

from benchmark.model import Frame, SequenceInfo


def hard_observations(frame: Frame, info: SequenceInfo, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """Blank, saturated and pure-noise images of the shape and type of ``frame``'s image.

    Parameters
    ----------
    frame : Frame
        A camera frame; its observation gives the shape and dtype.
    info : SequenceInfo
        Its sequence (unused: an image carries its own size).
    rng : numpy.random.Generator
        Draws the noise.

    Returns
    -------
    dict
        ``"blank"`` (all 0), ``"saturated"`` (all at the type's maximum,
        1.0 for float images) and ``"noise"`` (independent uniform grey levels).
    """
    image = np.asarray(frame.observation)
    top = np.iinfo(image.dtype).max if image.dtype.kind in "iu" else 1.0
    noise = rng.uniform(0.0, top, size=image.shape)
    return {
        "blank": np.zeros_like(image),
        "saturated": np.full_like(image, top),
        "noise": (np.rint(noise) if image.dtype.kind in "iu" else noise).astype(image.dtype),
    }
