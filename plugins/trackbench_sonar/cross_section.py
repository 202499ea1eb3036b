"""The pipe's cross-section through two points of a scan.

seeds/003 (section 2, after Petillot et al. [1]) describes a pipe in a scan
by its centre ``[C_x, C_y]``, its depth and burial, and the major and minor
axes ``[M_a, M_i]`` of its cross-section, and creates "a pipe cross section
... using two consecutive points and the known dimensions of the pipe".

Here the cross-section is an ellipse with horizontal axis ``M_a`` and
vertical axis ``M_i`` in the across-track / depth plane: a circle of the
pipe's diameter when the pipe runs along track, wider (``D / cos(theta)``)
when it crosses the swath at an angle ``theta``.  Through two points there
are two such ellipses (when the points are closer than the ellipse's
extent); the sonar sees the top of a pipe, so the one kept has its centre
on the deeper side of the chord, and both points lie on its upper arc.

Coordinates are the swath's: across-track ``x`` (starboard positive) and
depth ``z`` (positive down), so "below" means a larger depth.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class CrossSection:
    """The known dimensions of the pipe's cross-section.

    Attributes
    ----------
    major_m : float
        ``M_a``: the horizontal (across-track) axis, m.
    minor_m : float
        ``M_i``: the vertical axis, m.

    Raises
    ------
    ValueError
        If an axis is not a positive finite number.

    References
    ----------
    seeds/003, section 2 (the parameter set Theta).
    """

    major_m: float
    minor_m: float

    def __post_init__(self) -> None:
        for label in ("major_m", "minor_m"):
            value = getattr(self, label)
            if isinstance(value, bool) or not isinstance(value, int | float | np.number) or not 0.0 < value < np.inf:
                raise ValueError(f"pipe cross-section {label} must be a positive finite number, got {value!r}")
            object.__setattr__(self, label, float(value))

    @property
    def half_width_m(self) -> float:
        """``M_a / 2``: the semi-axis across track."""
        return 0.5 * self.major_m

    @property
    def half_height_m(self) -> float:
        """``M_i / 2``: the semi-axis in depth."""
        return 0.5 * self.minor_m

    def centres_below(
        self, x1: np.ndarray, z1: np.ndarray, x2: np.ndarray, z2: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Centres of the ellipses through pairs of points, on the deeper side of each chord.

        Parameters
        ----------
        x1, z1, x2, z2 : numpy.ndarray
            Across-track positions and depths of the two points of each
            pair, one shape.

        Returns
        -------
        cx, cz : numpy.ndarray
            Centre of each ellipse (``nan`` where none exists).
        ok : numpy.ndarray
            True where an ellipse exists: the points are distinct and no
            farther apart than the ellipse allows.

        References
        ----------
        seeds/003, section 2 ("a pipe cross section is created using two
        consecutive points and the known dimensions of the pipe").
        """
        a, b = self.half_width_m, self.half_height_m
        # In coordinates scaled by the semi-axes the ellipse is a unit circle:
        # its centre lies on the chord's perpendicular bisector, sqrt(1 - c^2/4) away.
        u1, v1 = np.asarray(x1, float) / a, np.asarray(z1, float) / b
        u2, v2 = np.asarray(x2, float) / a, np.asarray(z2, float) / b
        du, dv = u2 - u1, v2 - v1
        chord2 = du * du + dv * dv
        ok = np.isfinite(chord2) & (chord2 > 0.0) & (chord2 <= 4.0)
        chord = np.sqrt(np.where(ok, chord2, 1.0))
        rise = np.sqrt(np.clip(1.0 - 0.25 * chord2, 0.0, None))
        nu, nv = -dv / chord, du / chord
        deeper = np.where(nv < 0.0, -1.0, 1.0)
        cu = 0.5 * (u1 + u2) + rise * deeper * nu
        cv = 0.5 * (v1 + v2) + rise * deeper * nv
        return np.where(ok, cu * a, np.nan), np.where(ok, cv * b, np.nan), ok

    def residual(self, x: np.ndarray, z: np.ndarray, cx: np.ndarray, cz: np.ndarray) -> np.ndarray:
        """Distance of points from the ellipse centred at ``(cx, cz)``, along the ray from its centre.

        For a circle this is the exact distance ``|p - c| - R``; for an
        ellipse it is ``|p - c| - r(theta)``, with ``r(theta)`` the ellipse's
        radius in the direction of the point.  Unlike the difference in
        depth it stays small for a point just beside the steep ends of the
        arc.

        Parameters
        ----------
        x, z : numpy.ndarray
            Points; broadcast against the centres.
        cx, cz : numpy.ndarray
            Centres.

        Returns
        -------
        numpy.ndarray
            Signed distance, m: positive outside the ellipse.
        """
        dx = np.asarray(x, float) - cx
        dz = np.asarray(z, float) - cz
        u, v = dx / self.half_width_m, dz / self.half_height_m
        scaled = np.sqrt(u * u + v * v)
        distance = np.sqrt(dx * dx + dz * dz)
        radius = np.where(scaled > 0.0, distance / np.where(scaled > 0.0, scaled, 1.0), self.half_height_m)
        return distance - radius
