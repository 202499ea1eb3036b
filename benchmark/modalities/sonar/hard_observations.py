"""Swaths without a pipe in them, or with the beams broken, for the conformance kit.

A multibeam echo sounder loses beams (no return over soft mud, or all of
them when the vehicle pitches), returns spikes (fish, bubbles, multipath),
looks at flat seabed where the pipe has ended, or gives noise.  A sonar
tracker may report no pipe on such pings, but must not raise or return
an invalid estimate (seeds/003, section 2: the detector works on whatever
returns the ping has).
"""

from __future__ import annotations

import numpy as np

from benchmark.modalities.sonar.model import Swath
from benchmark.model import Frame, SequenceInfo

MISSING_SHARE = 0.5
"""Share of the beams a ``nan_beams`` swath loses."""

SPIKE_SHARE = 0.1
"""Share of the beams a ``spikes`` swath turns into spikes."""

SPIKE_M = 50.0
"""How far a spike lands from its beam's true depth, m, above or below."""


def hard_observations(frame: Frame, info: SequenceInfo, rng: np.random.Generator) -> dict[str, Swath]:
    """Swaths with the beams of ``frame``'s swath, broken in five ways.

    Parameters
    ----------
    frame : Frame
        A sonar frame; its swath gives the beams' across-track positions and depths.
    info : SequenceInfo
        Its sequence (unused: a swath carries its own beams).
    rng : numpy.random.Generator
        Picks the broken beams and the noise.

    Returns
    -------
    dict
        ``"no_returns"`` (every beam NaN), ``"nan_beams"`` (a random half of
        the beams NaN), ``"spikes"`` (a tenth of the beams 50 m off),
        ``"flat"`` (every return at the median depth: seabed, no pipe) and
        ``"noise"`` (depths uniform between the swath's shallowest and
        deepest return).
    """
    swath: Swath = frame.observation
    across, depth = swath.across_m, swath.depth_m
    n = across.size
    valid = swath.valid
    median = float(np.median(depth[valid])) if valid.any() else 10.0
    low, high = (float(depth[valid].min()), float(depth[valid].max())) if valid.any() else (median, median)
    missing = rng.permutation(n) < round(MISSING_SHARE * n)
    spiked = rng.permutation(n) < max(1, round(SPIKE_SHARE * n))
    offsets = rng.choice([-SPIKE_M, SPIKE_M], size=n)
    return {
        "no_returns": Swath(np.full(n, np.nan), np.full(n, np.nan)),
        "nan_beams": Swath(np.where(missing, np.nan, across), np.where(missing, np.nan, depth)),
        "spikes": Swath(across.copy(), np.where(spiked, depth + offsets, depth)),
        "flat": Swath(across.copy(), np.where(valid, median, np.nan)),
        "noise": Swath(across.copy(), np.where(valid, rng.uniform(low, max(high, low + 1.0), size=n), np.nan)),
    }
