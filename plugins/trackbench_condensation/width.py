"""A prior on the cable's width: it stays near the width the tracker has been reporting.

The thesis lets ``w`` diffuse freely (eq. 4.9, Table 5.1: 4 px^2 a frame)
and weighs particles by their borders' contrast alone (eq. 4.11).  Where an
algae mat or a rock edge runs along the cable, the pair of edges cable
border + clutter edge can out-score the cable's own pair, and the filter
widens onto it: on the clutter family most of the false frames left after
:mod:`trackbench_condensation.report` have one border on the cable and the
other 3-8 px outside (median width error +5.5 px).  The cable does not
change width; its image changes only slowly with the altitude.  So each
particle's weight is multiplied by a Gaussian in its width around a running
mean of the reported widths,

    pi'' = pi' exp(-(w - w_bar)^2 / (2 (k w_bar)^2)),
    w_bar_t = (1 - r) w_bar_(t-1) + r w_t,

with ``k`` = ``spread`` (relative, as the image of a cable scales with
range) and ``r`` = ``rate``.  ``w_bar`` starts at the first frame's true
width when the run gives it, at the first reported width otherwise, and
only reported states update it, so a frame reported lost or too wide
changes nothing.  The prior enters the particle weights only; the lost
test, re-detection and the reported mode judge the plain eq. (4.11) score.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from benchmark.filters.condensation import ObservationModel

WIDTH = 2
"""Column of ``w`` in a particle state ``(d, alpha, w, beta, ...)``."""


@dataclass
class WidthPrior:
    """An observation model's weights times a Gaussian prior on ``w`` around a running mean.

    Parameters
    ----------
    observation : ObservationModel
        The model whose weights are multiplied (eq. 4.11, sharpened).
    spread : float
        ``k > 0``: the prior's standard deviation as a multiple of ``w_bar``.
    rate : float
        ``r`` in ``(0, 1]``: the weight of each new width in ``w_bar``.

    Attributes
    ----------
    mean_width : float or None
        ``w_bar``, px; None until the first width is known (no prior then).
    """

    observation: ObservationModel
    spread: float
    rate: float
    mean_width: float | None = None

    def __post_init__(self) -> None:
        if not self.spread > 0:
            raise ValueError(f"width prior spread must be > 0, got {self.spread}")
        if not 0 < self.rate <= 1:
            raise ValueError(f"width prior rate must be in (0, 1], got {self.rate}")

    def reset(self, width: float | None) -> None:
        """Start a sequence with ``w_bar = width`` (None or not positive: no prior until a width is reported)."""
        self.mean_width = float(width) if width is not None and width > 0 else None

    def update(self, width: float) -> None:
        """Take a reported width into the running mean."""
        self.mean_width = width if self.mean_width is None else (1 - self.rate) * self.mean_width + self.rate * width

    def likelihood(self, states: np.ndarray, observation: object) -> np.ndarray:
        """The wrapped model's weights times ``exp(-(w - w_bar)^2 / (2 (k w_bar)^2))``."""
        weights = self.observation.likelihood(states, observation)
        if self.mean_width is None:
            return weights
        # In place, the same operations as ``weights * exp(-0.5 * z * z)`` on ``z = (w - w_bar) / (k w_bar)``.
        z = states[:, WIDTH] - self.mean_width
        z /= self.spread * self.mean_width
        prior = z * -0.5
        prior *= z
        prior = np.exp(prior)
        prior *= weights
        return prior
