"""A swath as a bottom profile on a uniform across-track grid.

The beams of a multibeam echo sounder are equiangular, so the across-track
distance between neighbouring returns grows away from nadir: at an opening
of 60 deg from the vertical it is four times that below the sonar.  The
detector of seeds/003 fits pipe cross-sections to consecutive points of the
scan, and "re-sampling of the data is required as the data sampling rate is
not constant" (seeds/003, section 2).  :func:`resample_swath` does that in
three moves:

1. drop the beams without a return (``nan`` or infinite in either array),
   keeping the others in beam order (port to starboard);
2. drop outlier spikes.  A spike is a wrong range: the return moves along
   its beam, nearer to the sonar or farther, and with it across track, so
   that in beam order it draws a long slanted segment into the profile.
   A return is dropped when its range differs from the running median of
   the ranges of the ``spike_window`` returns centred on it (in beam order)
   by more than ``spike_m`` in depth, ``|r - median(r)| cos(theta) >
   spike_m`` with ``cos(theta) = depth / range``.  A pipe that spans at
   least three returns is followed by a running median of five, so its
   returns differ from the median by much less than its height; the
   threshold is set in pipe heights by the detector;
3. sample the polyline joining consecutive returns at the points
   ``k * grid_m`` (whole multiples, so that the grid is the same from ping to
   ping) between the outermost returns.  Where the polyline passes over a
   grid point more than once, the shallowest crossing is kept: the bottom
   seen from above.  This matters at a pipe: the sonar sees part of its
   lower flank on the side facing nadir, returns that lie across-track
   *behind* the pipe's widest point, and sorting them by position would
   fold them into the arc.  A gap of missing beams is bridged by a straight
   line.

Too few returns leave an *empty* profile and an empty likelihood scan:
``sonar_detector`` then reports no detection and ``sonar_pf`` coasts.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from benchmark.errors import DataError
from benchmark.lazy import lazy_module
from benchmark.modalities.sonar.model import Swath

envelope_kernel = lazy_module("trackbench_sonar.envelope_kernel")

MAX_GRID_POINTS = 200_000
"""Most points a profile may have; a wider swath is taken for corrupt data."""


@dataclass(frozen=True, eq=False)
class Profile:
    """Depths of the bottom at equally spaced across-track positions.

    Attributes
    ----------
    across_m : numpy.ndarray
        Grid positions ``k * spacing_m``, increasing, shape ``(n,)``; empty
        when the swath had too few returns.
    depth_m : numpy.ndarray
        Depth below the transducer at each grid position, shape ``(n,)``.
    spacing_m : float
        Distance between neighbouring grid positions.
    gap_m : numpy.ndarray
        Across-track distance between the two returns each depth is
        interpolated from, shape ``(n,)``: how well the data sample the
        bottom there (lost beams and shadows widen it).
    returns_across_m, returns_depth_m : numpy.ndarray
        The cleaned returns the profile was drawn through, sorted by
        across-track position (ties in beam order), shape ``(m,)``: the
        measurements themselves, one per beam, for a fit that counts each
        beam once wherever the beams are dense or sparse.
    """

    across_m: np.ndarray
    depth_m: np.ndarray
    spacing_m: float
    gap_m: np.ndarray
    returns_across_m: np.ndarray = field(default_factory=lambda: np.empty(0))
    returns_depth_m: np.ndarray = field(default_factory=lambda: np.empty(0))

    @property
    def size(self) -> int:
        """Number of grid points."""
        return int(self.across_m.size)

    @property
    def is_empty(self) -> bool:
        """True when the profile has no points."""
        return self.size == 0

    @classmethod
    def empty(cls, spacing_m: float) -> Profile:
        """A profile without points."""
        return cls(np.empty(0), np.empty(0), spacing_m, np.empty(0))


def running_median(values: np.ndarray, window: int) -> np.ndarray:
    """Median of the ``window`` values centred on each value (fewer at the ends).

    Parameters
    ----------
    values : numpy.ndarray
        Shape ``(n,)``, finite.
    window : int
        Odd number of values in each median.

    Returns
    -------
    numpy.ndarray
        Shape ``(n,)``; near the ends the window is cut to the values that
        exist, which keeps it centred where it can.
    """
    values = np.asarray(values, dtype=float)
    if window % 2 == 0 or values.size == 0:
        import pandas as pd  # here, so that loading the plugin does not import pandas

        return pd.Series(values).rolling(window, center=True, min_periods=1).median().to_numpy()
    half = window // 2
    padded = np.concatenate([np.full(half, np.inf), values, np.full(half, np.inf)])
    # Each window sorted, the missing ends last; the middle one, or the mean of the middle two as pandas takes it.
    windows = np.sort(np.lib.stride_tricks.sliding_window_view(padded, window), axis=1)
    index = np.arange(values.size)
    count = np.minimum(index + half, values.size - 1) - np.maximum(index - half, 0) + 1
    rows = np.arange(values.size)
    return (windows[rows, (count - 1) // 2] + windows[rows, count // 2]) / 2


def spike_mask(across_m: np.ndarray, depth_m: np.ndarray, window: int, spike_m: float) -> np.ndarray:
    """Mask of the returns that are not outlier spikes.

    Parameters
    ----------
    across_m, depth_m : numpy.ndarray
        Consecutive valid returns, port to starboard, depth positive.
    window : int
        Odd number of returns in the running median; below 3 nothing is
        removed.
    spike_m : float
        Largest accepted difference from the running median of the ranges,
        as a depth (times ``depth / range``), m; ``inf`` or ``<= 0`` removes
        nothing.

    Returns
    -------
    numpy.ndarray
        Boolean mask, True for the returns kept.
    """
    if window < 3 or not (0.0 < spike_m < math.inf) or depth_m.size < 3:
        return np.ones(depth_m.size, dtype=bool)
    ranges = np.hypot(across_m, depth_m)
    cosine = np.divide(depth_m, ranges, out=np.ones_like(ranges), where=ranges > 0.0)
    return np.abs(ranges - running_median(ranges, window)) * np.abs(cosine) <= spike_m


def resample_swath(
    swath: Swath, grid_m: float, *, spike_window: int = 5, spike_m: float = math.inf, min_beams: int = 5
) -> Profile:
    """Clean a swath and resample it on a uniform across-track grid.

    Parameters
    ----------
    swath : Swath
        One ping.
    grid_m : float
        Spacing of the grid, m.
    spike_window : int
        Returns in the running median of the spike test (odd).
    spike_m : float
        Largest difference of a return's range from that median, as a
        depth, m (``inf``: no test).
    min_beams : int
        Fewest returns left after cleaning for a profile; fewer give an
        empty one.

    Returns
    -------
    Profile
        The resampled profile, empty when too few returns remain or they
        span less than two grid steps.

    Raises
    ------
    DataError
        If the returns span more than :data:`MAX_GRID_POINTS` grid steps
        (no sonar sees that far across track at any useful spacing).

    References
    ----------
    seeds/003, section 2 ("re-sampling of the data is required as the data
    sampling rate is not constant").
    """
    if spike_window % 2 == 0 and spike_window >= 3:
        valid = swath.valid
        across, depth = swath.across_m[valid], swath.depth_m[valid]
        keep = spike_mask(across, depth, spike_window, spike_m)
        across, depth = across[keep], depth[keep]
    else:
        across, depth = envelope_kernel.clean_returns(swath.across_m, swath.depth_m, int(spike_window), float(spike_m))
    if across.size < max(min_beams, 2):
        return Profile.empty(grid_m)
    low, high = float(across.min()) / grid_m, float(across.max()) / grid_m
    if not (math.isfinite(low) and math.isfinite(high) and high - low <= MAX_GRID_POINTS):
        raise DataError(
            f"swath returns span {across.min():.6g} .. {across.max():.6g} m across track: "
            f"more than {MAX_GRID_POINTS} points at {grid_m:g} m"
        )
    first = math.ceil(low)
    last = math.floor(high)
    if last - first < 2:
        return Profile.empty(grid_m)
    grid, envelope, gap, sorted_across, sorted_depth = envelope_kernel.profile_arrays(
        across, depth, float(grid_m), first, last
    )
    return Profile(grid, envelope, grid_m, gap, sorted_across, sorted_depth)


def upper_envelope(
    across: np.ndarray, depth: np.ndarray, grid_m: float, first: int, last: int
) -> tuple[np.ndarray, np.ndarray]:
    """The shallowest depth of the polyline through the returns at each grid point.

    Parameters
    ----------
    across, depth : numpy.ndarray
        Returns in beam order, finite, at least two.
    grid_m : float
        Grid spacing.
    first, last : int
        Grid indices ``k`` of the first and last points ``k * grid_m``; the
        polyline must span them.

    Returns
    -------
    depth : numpy.ndarray
        Depth at the ``last - first + 1`` grid points.
    segment : numpy.ndarray
        Index ``j`` of the polyline segment (from return ``j`` to ``j + 1``)
        each depth was read on.
    """
    return envelope_kernel.shallowest_crossings(
        np.asarray(across, dtype=float), np.asarray(depth, dtype=float), grid_m, first, last
    )
