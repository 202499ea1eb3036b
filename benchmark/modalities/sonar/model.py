"""What sonar frames hold: multibeam swaths, the pipe's truth and a tracker's estimate.

Sonar frames are pings of a multibeam echo sounder looking down at a pipe
(seeds/003): the observation is a :class:`Swath` (where each beam met the
bottom), the truth a :class:`SonarTruth`, and an estimate a
:class:`PipeEstimate`, the pipe's across-track position in the swath.
Across-track positions are in m from the sonar's nadir, starboard
positive; depths are in m below the transducer.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from benchmark.model import Frame


@dataclass(frozen=True, slots=True)
class SonarCalibration:
    """The multibeam echo sounder and the pipe of a sonar sequence (seeds/003, section 4).

    Attributes
    ----------
    n_beams : int
        Beams per ping.
    swath_angle : float
        Full across-track opening of the fan, rad; the beams are equiangular
        within it.
    range_sigma_m : float
        Standard deviation of a beam's range measurement.
    pipe_diameter_m : float
        Outer diameter of the pipe the sequence follows (its coating included).
    beam_width : float
        Across-track width of one beam (-3 dB), rad; 0 when not known.
        Where it exceeds the angle between beams, neighbouring beams
        overlap and each return averages the bottom over its footprint.
    """

    n_beams: int
    swath_angle: float
    range_sigma_m: float
    pipe_diameter_m: float
    beam_width: float = 0.0

    @property
    def beam_spacing(self) -> float:
        """Angle between neighbouring beams, rad."""
        return self.swath_angle / max(self.n_beams - 1, 1)


def beam_footprint(across_m: np.ndarray, depth_m: np.ndarray, beam_spacing: float) -> np.ndarray:
    """Across-track distance between neighbouring beams at points of the swath plane.

    A beam at angle ``theta`` from the vertical meets a level bottom at
    ``x = z tan(theta)``, so beams ``d theta`` apart land ``z d theta /
    cos^2(theta) = (x^2 + z^2) d theta / z`` apart: the sonar's across-track
    resolution there, which :attr:`SonarTruth.resolution_m` gives at the pipe.

    Parameters
    ----------
    across_m, depth_m : numpy.ndarray
        Points, depth positive.
    beam_spacing : float
        ``d theta``, rad (:attr:`SonarCalibration.beam_spacing`).

    Returns
    -------
    numpy.ndarray
        The spacing, m; ``inf`` at or above the transducer.

    References
    ----------
    seeds/003, section 4.1: the accuracy "set by the sensor's resolution".
    """
    x = np.asarray(across_m, dtype=float)
    z = np.asarray(depth_m, dtype=float)
    safe = np.where(z > 0.0, z, 1.0)
    with np.errstate(over="ignore"):
        return np.where(z > 0.0, (x * x + z * z) * beam_spacing / safe, np.inf)


@dataclass(frozen=True, slots=True, eq=False)
class Swath:
    """One ping of a multibeam echo sounder: where each beam met the bottom.

    Beams are in port-to-starboard order.  A beam without a return is
    ``nan`` in both arrays.  Because the beams are equiangular, the
    across-track spacing of the returns grows away from nadir (seeds/003,
    section 2: the reason the detector resamples the scan).

    Attributes
    ----------
    across_m : numpy.ndarray
        Across-track position of each return, shape ``(n_beams,)``.
    depth_m : numpy.ndarray
        Depth of each return below the transducer, shape ``(n_beams,)``.

    Raises
    ------
    ValueError
        If the arrays are not one-dimensional float arrays of one length.
    """

    across_m: np.ndarray
    depth_m: np.ndarray

    def __post_init__(self) -> None:
        for label in ("across_m", "depth_m"):
            values = np.asarray(getattr(self, label), dtype=float)
            if values.ndim != 1:
                raise ValueError(f"swath {label} must be one-dimensional, got shape {values.shape}")
            object.__setattr__(self, label, values)
        if self.across_m.shape != self.depth_m.shape:
            raise ValueError(
                f"swath across_m and depth_m differ in shape: {self.across_m.shape} vs {self.depth_m.shape}"
            )

    @property
    def valid(self) -> np.ndarray:
        """Mask of the beams with a finite return."""
        return np.isfinite(self.across_m) & np.isfinite(self.depth_m)


@dataclass(frozen=True, slots=True)
class SonarTruth:
    """Ground truth of one ping.

    Attributes
    ----------
    across_m : float
        Across-track position of the pipe's axis.
    depth_m : float
        Depth of the pipe's axis below the transducer.
    burial : float
        Share of the pipe's diameter below the surrounding seabed: 0 proud,
        1 fully buried.
    resolution_m : float
        Across-track distance between neighbouring beams at the pipe: the
        sonar's resolution there, and the default tolerance of a correct
        detection (seeds/003, section 4.1).
    """

    across_m: float
    depth_m: float
    burial: float
    resolution_m: float


@dataclass(frozen=True, slots=True)
class PipeEstimate:
    """A sonar tracker's estimate: the pipe's across-track position in the swath, m (seeds/003, eq. 5)."""

    across_m: float



SonarFrame = Frame[Swath, SonarTruth]
"""A sonar ping: a :class:`Swath` and a :class:`SonarTruth` or None."""
