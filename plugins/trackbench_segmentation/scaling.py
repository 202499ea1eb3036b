"""Pixel quantities that follow the frame size.

Ortiz et al. worked on 320 x 240 images (seeds/000, section 2.3), and the
tracker's lengths in pixels were chosen for that size: the plausible cable
widths, the region of interest's margin, the length of a long segment.  A
camera of twice the resolution sees the same cable twice as wide, its
borders twice as long and its frame-to-frame moves twice as large, so those
lengths are stated for a frame :attr:`~trackbench_segmentation.params.SegmentationParams.reference_width_px`
wide and multiplied by ``W / reference_width_px`` on a frame ``W`` px wide
(:func:`frame_params`); variances in px^2 by the square of that factor.

What does not scale: the columns a chain may step per row (``reach_px``, a
slope), the angles, the shares and the counts, and the tolerances that
describe pixel noise rather than the scene (which ones, and why, is in
:mod:`trackbench_segmentation.params`).
"""

from __future__ import annotations

import dataclasses
import functools

from trackbench_segmentation.params import SCALED_LENGTHS, SCALED_VARIANCES, SegmentationParams


@functools.lru_cache(maxsize=32)
def frame_params(params: SegmentationParams, size: tuple[int, int]) -> SegmentationParams:
    """The parameters with their lengths in pixels of a frame of ``size``.

    Parameters
    ----------
    params : SegmentationParams
        Lengths stated for a frame ``reference_width_px`` wide; with
        ``reference_width_px`` None they are returned unchanged.
    size : tuple of int
        The frame's ``(W, H)``.

    Returns
    -------
    SegmentationParams
        With ``reference_width_px`` None: every field of
        :data:`~trackbench_segmentation.params.SCALED_LENGTHS` multiplied by
        ``W / reference_width_px``, the ``d`` and ``w`` variances of
        :data:`~trackbench_segmentation.params.SCALED_VARIANCES` by its square.

    References
    ----------
    seeds/000, section 2.3: 320 x 240 images.
    """
    if params.reference_width_px is None:
        return params
    factor = size[0] / params.reference_width_px
    changes: dict[str, object] = {"reference_width_px": None}
    for name in SCALED_LENGTHS:
        changes[name] = getattr(params, name) * factor
    for name in SCALED_VARIANCES:
        d_var, alpha_var, w_var = getattr(params, name)
        changes[name] = (d_var * factor**2, alpha_var, w_var * factor**2)
    return dataclasses.replace(params, **changes)
