"""The observation model: how well a hypothetical cable fits the grey levels.

Seeds/000, section 4.5 weighs a particle by the grey-level changes across
its two projected borders.  :func:`~trackbench_condensation.measure.border_scores`
sums derivative-of-Gaussian responses along each border into the border
counts ``c_l`` and ``c_r``; eq. (4.11) turns them into the unnormalised
weight

    pi' = c_l - c_r   if c_l > 0 and c_r < 0   (a dark cable on bright ground),
          c_r - c_l   if c_r > 0 and c_l < 0   (a bright cable on dark ground),
          epsilon     otherwise,

so both polarities are accepted, each particle deciding its own, while a pair
of borders whose grey-level changes run the same way (a staircase, or one
border on the cable and one on the seabed) is worth only ``epsilon``.  The
counts are sums of step heights in grey levels (:mod:`~trackbench_condensation.kernel`),
so ``pi'`` is a total contrast in grey levels; ``epsilon`` is on that scale.
A particle with a non-positive width has no left and right border and also
gets ``epsilon``; so does one whose borders both miss the image.

Brighter centre (seeds/000, section 6.1, a proposed improvement; off by
default).  The thesis observes that a cylindrical cable under the vehicle's
lights is mostly brighter along its centre than near its borders.  With
``centre_weight = lambda > 0`` a particle that eq. (4.11) accepts gets

    pi' = pi'_(4.11) + lambda max(0, C),

where ``C`` is the summed centre-minus-flank contrast along its centreline
(:func:`~trackbench_condensation.measure.centre_contrast`), also in grey
levels.  Particles eq. (4.11) rejects keep ``epsilon``: the centre term
refines the border evidence but never replaces it.

Sharper weights.  :meth:`BorderObservation.likelihood` raises the weights to
a power ``gamma`` (``exponent``; 1 is the thesis).  The ratio of two weights
is what resampling sees, and eq. (4.11) changes only linearly with the
misalignment of a hypothesis; ``gamma`` turns that into a likelihood that
falls off as fast as the filter can resolve.  Neither the sign test nor the
scale-freeness of eq. (4.11) changes.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal, get_args

import numpy as np

from benchmark.errors import DataError
from benchmark.lazy import lazy_module
from trackbench_condensation.kernel import dog_taps

# The numba kernels load on the first frame, so that listing the trackers does not import numba.
measure = lazy_module("trackbench_condensation.measure")

Interpolation = Literal["nearest", "bilinear"]
"""How the image is read between pixel centres."""

INTERPOLATIONS: tuple[str, ...] = get_args(Interpolation)
"""The values of :data:`Interpolation`."""


def as_grey_image(observation: object) -> np.ndarray:
    """A C-contiguous 2-D ``uint8`` or ``float32`` image the compiled loops can read.

    Raises
    ------
    DataError
        If the observation is not a non-empty 2-D grey image.
    """
    image = np.asarray(observation)
    if image.ndim != 2 or image.size == 0:
        raise DataError(f"expected a grey image of shape (H, W), got shape {image.shape}")
    if image.dtype == np.uint8:
        return np.ascontiguousarray(image)
    return np.ascontiguousarray(image, dtype=np.float32)


@dataclass(frozen=True)
class BorderObservation:
    """Eq. (4.11) weights from derivative-of-Gaussian responses along both borders.

    Parameters
    ----------
    filter_size_px : int
        Size of the filter window across a border, odd, px (Table 5.1: 11).
    sample_distance_px : float
        Distance between sample points along a border, px (Table 5.1: 20).
    epsilon : float
        Weight of a rejected particle, grey levels (eq. 4.11).
    interpolation : {"nearest", "bilinear"}
        How the image is read.
    centre_weight : float
        ``lambda`` of the brighter-centre term; 0 switches it off.
    exponent : float
        ``gamma``: :meth:`likelihood` is :meth:`score` to this power (1: the
        thesis; :mod:`trackbench_condensation.params` explains the default
        of the tracker).

    References
    ----------
    seeds/000, section 4.5, eqs. (4.10)-(4.11), Table 5.1; section 6.1.
    """

    filter_size_px: int = 11
    sample_distance_px: float = 20.0
    epsilon: float = 1e-3
    interpolation: Interpolation = "nearest"
    centre_weight: float = 0.0
    exponent: float = 1.0
    taps: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not self.sample_distance_px > 0:
            raise ValueError(f"sample distance must be positive, got {self.sample_distance_px} px")
        if not self.epsilon > 0:
            raise ValueError(f"epsilon must be positive, got {self.epsilon}")
        if self.interpolation not in INTERPOLATIONS:
            raise ValueError(f"interpolation must be one of {INTERPOLATIONS}, got {self.interpolation!r}")
        if not self.centre_weight >= 0:
            raise ValueError(f"centre weight must be >= 0, got {self.centre_weight}")
        if not self.exponent > 0:
            raise ValueError(f"weight exponent must be positive, got {self.exponent}")
        object.__setattr__(self, "taps", dog_taps(self.filter_size_px))

    def score(self, states: np.ndarray, image: np.ndarray) -> np.ndarray:
        """Eq. (4.11) weights of ``(N, D)`` states on a grey image, before any exponent.

        Returns
        -------
        numpy.ndarray
            ``(N,)`` finite weights ``>= epsilon``, in grey levels: eq. (4.11),
            plus the centre term when ``centre_weight > 0``
            (:func:`trackbench_condensation.measure.particle_weights`).

        References
        ----------
        seeds/000, section 4.5, eq. (4.11); section 6.1.
        """
        return self._weights(states, image, 1.0)

    def likelihood(self, states: np.ndarray, image: np.ndarray) -> np.ndarray:
        """Unnormalised weights ``pi'``: :meth:`score` raised to ``exponent``."""
        return self._weights(states, image, float(self.exponent))

    def _weights(self, states: np.ndarray, image: np.ndarray, exponent: float) -> np.ndarray:
        return self.grey_weights(states, as_grey_image(image), exponent)

    def grey_weights(self, states: np.ndarray, grey: np.ndarray, exponent: float) -> np.ndarray:
        """:meth:`score` to the power ``exponent`` on an image :func:`as_grey_image` already made."""
        return measure.particle_weights(
            np.ascontiguousarray(states, dtype=float),
            grey,
            self.taps,
            float(self.sample_distance_px),
            self.interpolation == "bilinear",
            float(self.epsilon),
            float(self.centre_weight),
            exponent,
        )


@dataclass(frozen=True)
class ImageScore:
    """:meth:`BorderObservation.score` on one image: a callable from ``(N, D)`` states to ``(N,)`` scores.

    Besides scoring, it runs a local ascent of that score in one compiled
    call (:meth:`ascend`), which :class:`~trackbench_condensation.detect.LocalAscent`
    uses instead of scoring each round's moves from Python.

    Parameters
    ----------
    observation : BorderObservation
        The observation model.
    image : numpy.ndarray
        The frame's grey image (:func:`as_grey_image`).

    References
    ----------
    seeds/000, section 4.5, eq. (4.11).
    """

    observation: BorderObservation
    image: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "image", as_grey_image(self.image))

    def __call__(self, states: np.ndarray) -> np.ndarray:
        """Eq. (4.11) scores of ``(N, D)`` states (:meth:`BorderObservation.score`)."""
        return self.observation.grey_weights(states, self.image, 1.0)

    def ascend(
        self,
        states: np.ndarray,
        low: np.ndarray,
        high: np.ndarray,
        first_steps: np.ndarray,
        smallest: float,
        max_rounds: int,
    ) -> tuple[np.ndarray, np.ndarray]:
        """The compass search of :func:`trackbench_condensation.measure.compass_ascent` from ``(K, 4)`` states.

        Returns
        -------
        states : numpy.ndarray
            ``(K, 4)`` refined states.
        scores : numpy.ndarray
            ``(K,)`` their eq. (4.11) scores.
        """
        observation = self.observation
        return measure.compass_ascent(
            np.ascontiguousarray(states, dtype=float),
            self.image,
            observation.taps,
            float(observation.sample_distance_px),
            observation.interpolation == "bilinear",
            float(observation.epsilon),
            float(observation.centre_weight),
            np.ascontiguousarray(low, dtype=float),
            np.ascontiguousarray(high, dtype=float),
            np.ascontiguousarray(first_steps, dtype=float),
            float(smallest),
            int(max_rounds),
        )
