"""Sea water as a camera sees it: Jerlov's water types and the revised image formation model.

Akkaynak and Treibitz (2018), "A Revised Underwater Image Formation Model",
CVPR 2018, pp. 6723-6732, eq. (11), write the colour channel ``c`` of an
underwater image at camera-to-object range ``z`` as

    I_c = J_c exp(-beta_D_c z) + B_inf_c (1 - exp(-beta_B_c z))

where ``J_c`` is the signal the object sends back, ``B_inf_c`` the veiling
light of the water far away, and ``beta_D_c`` (direct signal) and
``beta_B_c`` (backscatter) are *wideband* coefficients: integrals over the
camera's spectral response ``S_c(lambda)`` of spectral quantities, which
differ from each other and from any single wavelength's attenuation.  Their
eqs. (12) and (13) (written here for a range step ``dz``):

    beta_D_c = ln( int S_c rho E exp(-beta z) / int S_c rho E exp(-beta (z + dz)) ) / dz
    beta_B_c = -ln( 1 - int S_c B_inf (1 - exp(-beta z)) / int S_c B_inf ) / z

with ``rho(lambda)`` the object's reflectance, ``E(lambda)`` the light on it
and ``B_inf(lambda)`` the spectral veiling light.  This module computes
them once per sequence, at the sequence's typical range, for each of
Jerlov's ten water types; the renderer then applies the per-channel
equation to every pixel.

Coefficients and their sources
------------------------------
* ``K_d(lambda)``: Jerlov's diffuse attenuation coefficient of downward
  irradiance, N. G. Jerlov, *Marine Optics*, 2nd ed., Elsevier 1976,
  Table XXVII (p. 135), 400-700 nm every 25 nm, oceanic types I, IA, IB,
  II, III and coastal 1, 3, 5, 7, 9 (written ``1C`` ... ``9C`` here).  It
  is what defines the types; daylight is attenuated with depth by it.
* Pure water absorption ``a_w(lambda)``: R. M. Pope and E. S. Fry,
  "Absorption spectrum (380-700 nm) of pure water. II", Applied Optics 36
  (1997) 8710-8723, at the same wavelengths.  Pure water scattering
  ``b_w(lambda) = 0.0038 (400 / lambda)^4.32`` m^-1, half of it backwards:
  A. Morel (1974), as summarised by C. D. Mobley, *Light and Water*
  (1994), section 3.8.
* The particles' (and dissolved matter's) share follows from ``K_d`` by
  ``K_d ~ (a + b_b) / mu_d`` (J. T. O. Kirk, *Light and Photosynthesis in
  Aquatic Ecosystems*, 1994, section 6.4; H. R. Gordon, "Can the
  Lambert-Beer law be applied to the diffuse attenuation coefficient of
  ocean water?", Limnol. Oceanogr. 34 (1989)) with the mean cosine of
  downward light ``mu_d =`` :data:`MEAN_COSINE`, a single-scattering
  albedo of the particles ``b_p / (a_p + b_p) =``
  :data:`PARTICLE_SCATTERING_ALBEDO` (typical of marine particles, Mobley
  1994, section 3.9) and Petzold's backscattering ratio ``b_bp / b_p =``
  :data:`PARTICLE_BACKSCATTER_RATIO` (T. J. Petzold, SIO Ref. 72-78, 1972;
  Mobley 1994, Table 3.10).  This gives ``a``, ``b``, ``b_b`` and the beam
  attenuation ``c = a + b`` of each type.
* The attenuation ``beta(lambda)`` of A&T's model along a camera's line of
  sight is ``a + (1 - FORWARD_SHARE) b``: light scattered by less than a
  few degrees still reaches the camera near its pixel (Petzold's phase
  functions put about half of all scattering within 5 degrees), so only
  the rest of the scattering removes it from the image; the blur that
  forward scattering adds is
  :attr:`~benchmark.modalities.camera.scenes.spec.OpticsSpec.blur_px`.
* Veiling light of the water lit from above, looking down: the radiance of
  the upwelling light field, ``B_inf = R E / pi`` with the irradiance
  reflectance ``R = 0.33 b_b / a`` of H. R. Gordon, O. B. Brown and M. M.
  Jacobs, "Computed relationships between the inherent and apparent
  optical properties of a flat homogeneous ocean", Applied Optics 14
  (1975) 417-427.
* Camera: Gaussian spectral responses (:data:`CHANNEL_RESPONSES`, peaks
  near those of common colour sensors); grey is ITU-R BT.601 luma,
  ``Y = 0.299 R + 0.587 G + 0.114 B`` (:data:`GREY_WEIGHTS`), the weights
  OpenCV's colour-to-grey conversion uses.  Lamps are white (flat
  spectrum); daylight is flat at the surface and filtered by ``K_d`` on
  its way down.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

WAVELENGTHS_NM = np.arange(400.0, 701.0, 25.0)
"""Wavelengths of Jerlov's table, nm."""

JerlovType = Literal["I", "IA", "IB", "II", "III", "1C", "3C", "5C", "7C", "9C"]
"""Jerlov's water types: oceanic I-III, coastal 1-9."""

JERLOV_KD: dict[str, tuple[float, ...]] = {
    "I": (0.027, 0.022, 0.019, 0.018, 0.027, 0.043, 0.063, 0.089, 0.235, 0.305, 0.36, 0.42, 0.56),
    "IA": (0.038, 0.031, 0.026, 0.025, 0.032, 0.048, 0.067, 0.094, 0.24, 0.31, 0.37, 0.43, 0.57),
    "IB": (0.051, 0.042, 0.036, 0.033, 0.042, 0.054, 0.072, 0.099, 0.245, 0.315, 0.375, 0.435, 0.58),
    "II": (0.096, 0.081, 0.068, 0.062, 0.07, 0.076, 0.089, 0.115, 0.26, 0.335, 0.4, 0.465, 0.61),
    "III": (0.185, 0.16, 0.135, 0.116, 0.115, 0.116, 0.12, 0.148, 0.295, 0.375, 0.445, 0.52, 0.66),
    "1C": (0.51, 0.36, 0.25, 0.17, 0.14, 0.13, 0.12, 0.15, 0.3, 0.37, 0.45, 0.51, 0.65),
    "3C": (0.78, 0.54, 0.39, 0.29, 0.22, 0.2, 0.19, 0.21, 0.33, 0.4, 0.46, 0.56, 0.71),
    "5C": (1.1, 0.78, 0.56, 0.43, 0.36, 0.31, 0.3, 0.33, 0.4, 0.48, 0.54, 0.65, 0.8),
    "7C": (1.6, 1.2, 0.89, 0.71, 0.58, 0.49, 0.46, 0.46, 0.48, 0.54, 0.63, 0.78, 0.92),
    "9C": (2.4, 1.9, 1.6, 1.23, 0.99, 0.78, 0.63, 0.58, 0.6, 0.65, 0.76, 0.92, 1.1),
}
"""``K_d(lambda)`` in m^-1 at :data:`WAVELENGTHS_NM`, Jerlov (1976), Table XXVII."""

PURE_WATER_ABSORPTION = np.array(
    (0.00663, 0.00478, 0.00922, 0.0114, 0.0204, 0.0487, 0.0565, 0.0894, 0.2224, 0.2834, 0.340, 0.4245, 0.624)
)
"""``a_w(lambda)`` in m^-1 at :data:`WAVELENGTHS_NM`, Pope and Fry (1997)."""

PARTICLE_SCATTERING_ALBEDO = 0.8
"""``b_p / (a_p + b_p)``: share of the particles' attenuation that scatters rather than absorbs."""

MEAN_COSINE = 0.8
"""``mu_d``: mean cosine of the downward light field, ``K_d ~ (a + b_b) / mu_d``."""

FORWARD_SHARE = 0.5
"""Share of the scattering within a few degrees forward, which stays in the image."""

PARTICLE_BACKSCATTER_RATIO = 0.0183
"""``b_bp / b_p`` of Petzold's average particle phase function."""

GORDON_REFLECTANCE = 0.33
"""``R = 0.33 b_b / a``: irradiance reflectance of deep water (Gordon, Brown and Jacobs 1975)."""

CHANNEL_RESPONSES = ((600.0, 35.0), (540.0, 35.0), (460.0, 30.0))
"""Peak and standard deviation (nm) of the Gaussian responses of the R, G and B channels."""

GREY_WEIGHTS = np.array((0.299, 0.587, 0.114))
"""ITU-R BT.601 luma weights of R, G, B."""

DEFAULT_RANGE_M = 2.0
"""Range at which the wideband coefficients are taken when none is given."""


@dataclass(frozen=True)
class WaterOptics:
    """Wideband optical properties of one water type for the three colour channels (R, G, B).

    Attributes
    ----------
    jerlov : str
        The water type.
    beta_d : numpy.ndarray
        ``beta_D_c``, m^-1: attenuation of the direct signal (A&T 2018, eq. (12)).
    beta_b : numpy.ndarray
        ``beta_B_c``, m^-1: the rate at which backscatter saturates with range (eq. (13)).
    backscatter : numpy.ndarray
        ``b_b``, m^-1, weighted by the channel's response: the volume
        scattering into the backward hemisphere that lights marine snow
        and the lamp's backscatter.
    reflectance : numpy.ndarray
        ``R`` of the water column (Gordon et al. 1975): the veiling light of
        daylight is ``R E / pi``.
    """

    jerlov: str
    beta_d: np.ndarray
    beta_b: np.ndarray
    backscatter: np.ndarray
    reflectance: np.ndarray


def channel_responses() -> np.ndarray:
    """Spectral responses ``S_c(lambda)`` of R, G, B at :data:`WAVELENGTHS_NM`, each summing to 1, shape ``(3, n)``."""
    peaks = np.array([peak for peak, _ in CHANNEL_RESPONSES])[:, None]
    widths = np.array([width for _, width in CHANNEL_RESPONSES])[:, None]
    response = np.exp(-0.5 * ((WAVELENGTHS_NM[None, :] - peaks) / widths) ** 2)
    return response / response.sum(axis=1, keepdims=True)


def spectral_iops(jerlov: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Image attenuation ``beta``, absorption ``a`` and backscattering ``b_b`` spectra of a water type, m^-1.

    Raises
    ------
    ValueError
        For a name that is not one of Jerlov's types.
    """
    if jerlov not in JERLOV_KD:
        raise ValueError(f"unknown Jerlov water type {jerlov!r}; known: {', '.join(JERLOV_KD)}")
    diffuse = np.array(JERLOV_KD[jerlov])
    water_scattering = 0.0038 * (400.0 / WAVELENGTHS_NM) ** 4.32
    water_part = (PURE_WATER_ABSORPTION + 0.5 * water_scattering) / MEAN_COSINE
    rest = MEAN_COSINE * np.maximum(diffuse - water_part, 0.0)
    # a_p + b_bp = rest with b_p = omega / (1 - omega) a_p and b_bp = ratio b_p.
    per_absorption = PARTICLE_SCATTERING_ALBEDO / (1.0 - PARTICLE_SCATTERING_ALBEDO)
    particle_absorption = rest / (1.0 + PARTICLE_BACKSCATTER_RATIO * per_absorption)
    particle_scattering = per_absorption * particle_absorption
    absorption = PURE_WATER_ABSORPTION + particle_absorption
    scattering = water_scattering + particle_scattering
    backscatter = 0.5 * water_scattering + PARTICLE_BACKSCATTER_RATIO * particle_scattering
    beta = absorption + (1.0 - FORWARD_SHARE) * scattering
    return beta, absorption, backscatter


def diffuse_attenuation(jerlov: str) -> np.ndarray:
    """Jerlov's ``K_d(lambda)`` of a water type at :data:`WAVELENGTHS_NM`, m^-1."""
    if jerlov not in JERLOV_KD:
        raise ValueError(f"unknown Jerlov water type {jerlov!r}; known: {', '.join(JERLOV_KD)}")
    return np.array(JERLOV_KD[jerlov])


def daylight_at_depth(jerlov: str, depth_m: float) -> np.ndarray:
    """Daylight at ``depth_m`` per channel, relative to white light of 1 at the surface, shape ``(3,)``.

    ``E_c(d) = int S_c exp(-K_d d)``: each wavelength is filtered on its own
    before the channel integrates them (Jerlov 1976, the definition of ``K_d``).
    """
    return channel_responses() @ np.exp(-diffuse_attenuation(jerlov) * depth_m)


def water_optics(jerlov: str, depth_m: float = 0.0, range_m: float = DEFAULT_RANGE_M) -> WaterOptics:
    """The wideband coefficients of a water type, for a camera at ``depth_m`` seeing objects at ``range_m``.

    Parameters
    ----------
    jerlov : str
        One of :data:`JERLOV_KD`'s types.
    depth_m : float
        Depth below the surface; it colours the daylight, which weighs
        ``B_inf``.  The lamp's light is white whatever the depth.
    range_m : float
        The range at which ``beta_D`` and ``beta_B`` are evaluated (they
        depend on it weakly, A&T 2018, section 4).

    Returns
    -------
    WaterOptics

    References
    ----------
    Akkaynak and Treibitz (2018), eqs. (11)-(13); Jerlov (1976), Table XXVII.
    """
    if not (math.isfinite(range_m) and range_m > 0 and math.isfinite(depth_m) and depth_m >= 0):
        raise ValueError(f"need range_m > 0 and depth_m >= 0, got {range_m}, {depth_m}")
    beta, absorption, backscatter = spectral_iops(jerlov)
    response = channel_responses()
    step = 0.01
    # Direct signal of a grey object under white light (eq. (12)).
    near = response @ np.exp(-beta * range_m)
    far = response @ np.exp(-beta * (range_m + step))
    beta_d = np.log(near / far) / step
    # Backscatter of the daylight at depth (eq. (13)), B_inf(lambda) = R(lambda) E(lambda) / pi.
    reflectance = GORDON_REFLECTANCE * backscatter / absorption
    daylight = np.exp(-diffuse_attenuation(jerlov) * depth_m)
    veiling = reflectance * daylight
    filled = (response @ (veiling * (1.0 - np.exp(-beta * range_m)))) / (response @ veiling)
    beta_b = -np.log1p(-filled) / range_m
    return WaterOptics(
        jerlov=jerlov,
        beta_d=beta_d,
        beta_b=beta_b,
        backscatter=response @ backscatter,
        reflectance=(response @ veiling) / np.maximum(response @ daylight, 1e-30),
    )


def transmission(beta: np.ndarray, range_m: np.ndarray) -> np.ndarray:
    """``exp(-beta z)``: the share of a signal left after ``z`` metres, per channel.

    ``beta`` has shape ``(3,)``, ``range_m`` any shape; the result has shape ``(3, *range_m.shape)``.
    """
    return np.exp(-np.multiply.outer(np.asarray(beta, dtype=float), np.asarray(range_m, dtype=float)))


def backscatter(veiling: np.ndarray, beta_b: np.ndarray, range_m: np.ndarray) -> np.ndarray:
    """``B_inf (1 - exp(-beta_B z))``: the backscatter in front of an object at range ``z`` (A&T 2018, eq. (11))."""
    return np.asarray(veiling, dtype=float)[:, None] * -np.expm1(
        -np.multiply.outer(np.asarray(beta_b, dtype=float), np.ravel(range_m))
    ).reshape((3, *np.shape(range_m)))


def formed_image(
    signal: np.ndarray, veiling: np.ndarray, optics: WaterOptics, range_m: np.ndarray
) -> np.ndarray:
    """A&T 2018 eq. (11) per channel: ``J_c exp(-beta_D_c z) + B_inf_c (1 - exp(-beta_B_c z))``.

    ``signal`` and ``veiling`` have shape ``(3,)`` (or ``(3, *range_m.shape)`` for ``signal``).
    """
    shape = (3,) + (1,) * np.ndim(range_m)
    direct = np.reshape(signal, shape) if np.ndim(signal) == 1 else signal
    return direct * transmission(optics.beta_d, range_m) + backscatter(veiling, optics.beta_b, range_m)


def to_grey(channels: np.ndarray) -> np.ndarray:
    """BT.601 luma of an ``(3, ...)`` array of R, G, B."""
    return np.tensordot(GREY_WEIGHTS, channels, axes=1)


__all__ = [
    "GREY_WEIGHTS",
    "JERLOV_KD",
    "WaterOptics",
    "backscatter",
    "channel_responses",
    "daylight_at_depth",
    "diffuse_attenuation",
    "formed_image",
    "spectral_iops",
    "to_grey",
    "transmission",
    "water_optics",
]
