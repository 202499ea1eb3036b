"""Light in the water model: the vehicle's lamps, their backscatter, and daylight with its flicker.

Lamps
    A lamp at ``L`` (offset from the camera, fixed to the vehicle) lights a
    point ``X`` with the irradiance

        E = I P(theta) cos(iota) / |X - L|^2 * exp(-beta |X - L|)

    (inverse-square fall-off, Lambert's cosine of the incidence ``iota``,
    attenuation on the way), where ``P`` is the beam: 1 inside the cone,
    a smoothstep across its soft edge, 0 outside, times ``1 + hotspot`` on
    its axis falling off as a Gaussian in angle.  Every lamp is aimed at the
    point of the optical axis at the aim distance, so the lamps' cross
    light is where the camera looks.

Backscatter of the lamps' light
    The water between the camera and a surface at range ``z`` scatters the
    lamps' light back into the camera.  In single scattering, with the
    volume scattering function over the backward hemisphere taken as flat,
    ``b_b / (2 pi)`` per steradian (the flat backward lobe of Petzold's
    phase function), the radiance added along a ray ``u`` is

        pi B(z) = int_0^z (b_b / 2) I P(theta(s)) / rho(s)^2 exp(-beta_B (rho(s) + s)) ds

    with ``rho(s) = |s u - L|`` the distance from the lamp to the point
    ``s u`` of the ray (radiances here are ``pi`` times the radiance, the
    units in which a white Lambertian surface under irradiance ``E``
    returns ``E``).  The geometry is rigid with the vehicle, so the integral
    depends only on the pixel and the range: it is tabulated once per
    sequence on a coarse grid of pixels and on ranges spaced evenly in
    logarithm (:func:`lamp_backscatter_table`), and looked up per frame.
    Jaffe (1990), "Computer modeling and the design of optimal underwater
    imaging systems", IEEE J. Oceanic Eng. 15(2), writes the same
    single-scattering integral; the table is this project's way of making
    it cheap.

Daylight and sun flicker
    Below the surface, daylight is white light filtered by ``K_d`` over the
    depth (:func:`benchmark.modalities.camera.scenes.water.daylight_at_depth`).
    Surface waves focus it into moving bright lines on the seabed, caustics;
    they are modelled as ``exp(g s) / mean`` with ``s`` the mean of three
    plane waves that travel across the seabed (:class:`CausticWaves`), the
    sharpness ``g`` making thin bright lines of the crests where the waves
    meet.  Their depth of modulation fades with depth as
    ``exp(-depth / CAUSTIC_FADE_M)``: scattering blurs the focus of the
    waves' lenses (caustics are strongest in the first few metres and rarely
    visible below about 15-20 m).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from benchmark.modalities.camera.scenes.spec import Lamp
from benchmark.modalities.camera.scenes.water import GREY_WEIGHTS, WaterOptics

CAUSTIC_FADE_M = 6.0
"""Depth over which the sun flicker's modulation falls to ``1/e``."""

CAUSTIC_SHARPNESS = 4.0
"""``g`` of the caustic pattern ``exp(g s)``."""

CAUSTIC_WAVES = 3
"""Plane waves summed into the caustic pattern."""

NEAREST_SCATTER_M = 0.03
"""The water closer than this to the camera's port scatters nothing into it."""

BACKSCATTER_KNOTS = 24
"""Ranges at which the lamps' backscatter is tabulated, evenly spaced in logarithm."""

BACKSCATTER_CELL_PX = 80
"""The backscatter table has this many coarse pixels across the image, at most."""


def lamp_axis(lamp: Lamp, aim_m: float) -> np.ndarray:
    """Unit direction (camera frame: right, down, forward) from the lamp to the point ``(0, 0, aim_m)``."""
    target = np.array((0.0, 0.0, aim_m)) - np.asarray(lamp.offset_m, dtype=float)
    return target / np.linalg.norm(target)


def beam_profile(cos_angle: np.ndarray, lamp: Lamp) -> np.ndarray:
    """The beam ``P(theta)`` at the cosine of the angle off the lamp's axis.

    1 inside the cone (``cone_deg - edge_deg``), 0 outside
    (``cone_deg + edge_deg``), a smoothstep in ``cos(theta)`` across the edge,
    times ``1 + hotspot exp(-theta^2 / hotspot_deg^2)`` with
    ``theta^2 ~ 2 (1 - cos(theta))``.
    """
    cos_angle = np.asarray(cos_angle, dtype=np.float32)
    inner = math.cos(math.radians(lamp.cone_deg - lamp.edge_deg))
    outer = math.cos(math.radians(lamp.cone_deg + lamp.edge_deg))
    ramp = np.clip((cos_angle - np.float32(outer)) * np.float32(1.0 / max(inner - outer, 1e-9)), 0.0, 1.0)
    profile = ramp * ramp * (np.float32(3.0) - np.float32(2.0) * ramp)
    if lamp.hotspot > 0:
        spread = np.float32(1.0 / (0.5 * math.radians(lamp.hotspot_deg) ** 2))
        profile *= np.float32(1.0) + np.float32(lamp.hotspot) * np.exp((cos_angle - np.float32(1.0)) * spread)
    return profile


def backscatter_knots(max_range_m: float) -> np.ndarray:
    """The ranges of the backscatter table: :data:`BACKSCATTER_KNOTS` from 5 cm to ``max_range_m``, log-spaced."""
    return np.geomspace(0.05, max(max_range_m, 0.1), BACKSCATTER_KNOTS)


def lamp_backscatter_table(
    lamps: tuple[Lamp, ...], water: WaterOptics, rays: np.ndarray, aim_m: float, max_range_m: float
) -> np.ndarray:
    """The lamps' backscatter ``pi B(z)`` in grey (BT.601 of R, G, B) along given rays, at :func:`backscatter_knots`.

    Parameters
    ----------
    lamps : tuple of Lamp
    water : WaterOptics
        ``b_b`` and ``beta_B`` per channel.
    rays : numpy.ndarray
        Shape ``(3, n)``: camera-frame ray directions ``(qx, qy, 1)``.
    aim_m : float
        Distance along the optical axis the lamps are aimed at.
    max_range_m : float
        Farthest range tabulated.

    Returns
    -------
    numpy.ndarray
        Shape ``(BACKSCATTER_KNOTS, n)``, ``float32``: cumulative backscatter
        up to each knot's range (the range is the distance along the ray).

    References
    ----------
    Jaffe (1990), eq. for the backscatter component in single scattering;
    Akkaynak and Treibitz (2018), eq. (11), whose ``B_inf (1 - exp(-beta_B z))``
    it becomes for light that fills the water evenly.
    """
    knots = backscatter_knots(max_range_m)
    samples = np.concatenate(([NEAREST_SCATTER_M], np.geomspace(NEAREST_SCATTER_M * 1.05, knots[-1], 160)))
    units = rays / np.linalg.norm(rays, axis=0, keepdims=True)
    table = np.zeros((len(knots), rays.shape[1]))
    for lamp in lamps:
        if lamp.intensity <= 0:
            continue
        offset = np.asarray(lamp.offset_m, dtype=float)[:, None, None]
        axis = lamp_axis(lamp, aim_m)
        points = units[:, :, None] * samples[None, None, :]
        towards = points - offset
        rho = np.maximum(np.linalg.norm(towards, axis=0), 0.02)
        cos_angle = np.einsum("i,ijk->jk", axis, towards) / rho
        light = lamp.intensity * beam_profile(cos_angle, lamp).astype(float) / rho**2
        grey = np.zeros_like(light)
        for weight, scatter, beta in zip(GREY_WEIGHTS, water.backscatter, water.beta_b):
            grey += weight * 0.5 * scatter * light * np.exp(-beta * (rho + samples[None, :]))
        steps = np.diff(samples)[None, :] * 0.5 * (grey[:, 1:] + grey[:, :-1])
        cumulative = np.concatenate((np.zeros((grey.shape[0], 1)), np.cumsum(steps, axis=1)), axis=1)
        table += np.stack([np.interp(knots, samples, row) for row in cumulative], axis=1)
    return table.astype(np.float32)


def lookup_backscatter(table: np.ndarray, max_range_m: float, range_m: np.ndarray) -> np.ndarray:
    """Values of a :func:`lamp_backscatter_table` at per-ray ranges (linear between knots), shape of ``range_m``."""
    knots = backscatter_knots(max_range_m)
    step = math.log(knots[1] / knots[0])
    position = np.log(np.clip(range_m, knots[0], knots[-1]) / knots[0]) / np.float32(step)
    index = np.minimum(position.astype(np.int32), len(knots) - 2)
    share = (position - index).astype(np.float32)
    columns = np.arange(table.shape[1])
    low = table[index, columns]
    high = table[index + 1, columns]
    return low + share * (high - low)


@dataclass(frozen=True)
class CausticWaves:
    """The plane waves whose crests make the sun flicker on the seabed.

    Attributes
    ----------
    wavevectors : numpy.ndarray
        Shape ``(CAUSTIC_WAVES, 2)``: ``2 pi / wavelength`` times the unit
        direction in ``(X, Z)``, rad/m.
    angular_speeds : numpy.ndarray
        rad/s of each wave.
    phases : numpy.ndarray
        rad at time 0.
    amplitude : float
        Depth of modulation at the camera's depth (0 for no flicker).
    """

    wavevectors: np.ndarray
    angular_speeds: np.ndarray
    phases: np.ndarray
    amplitude: float

    @classmethod
    def draw(
        cls, rng: np.random.Generator, scale_m: float, speed_mps: float, surface_amplitude: float, depth_m: float
    ) -> CausticWaves:
        """Waves of wavelengths around ``2 scale_m`` in random directions, moving at about ``speed_mps``."""
        angles = rng.uniform(0.0, 2 * math.pi, CAUSTIC_WAVES)
        wavelengths = 2.0 * scale_m * rng.uniform(0.8, 1.25, CAUSTIC_WAVES)
        numbers = 2 * math.pi / wavelengths
        vectors = numbers[:, None] * np.stack((np.cos(angles), np.sin(angles)), axis=1)
        speeds = numbers * speed_mps * rng.uniform(0.7, 1.3, CAUSTIC_WAVES)
        phases = rng.uniform(0.0, 2 * math.pi, CAUSTIC_WAVES)
        amplitude = min(surface_amplitude * math.exp(-depth_m / CAUSTIC_FADE_M), 1.0)
        return cls(vectors, speeds, phases, amplitude)

    def factor(self, x: np.ndarray, z: np.ndarray, time_s: float) -> np.ndarray:
        """The daylight's factor at seabed points ``(x, z)``: ``1 + amplitude (exp(g s) / mean - 1)``, mean 1."""
        total = np.zeros(np.shape(x), dtype=np.float32)
        for (kx, kz), omega, phase in zip(self.wavevectors, self.angular_speeds, self.phases):
            total += np.cos(np.float32(kx) * x + np.float32(kz) * z + np.float32(phase - omega * time_s))
        total *= np.float32(CAUSTIC_SHARPNESS / CAUSTIC_WAVES)
        pattern = np.exp(total)
        pattern *= np.float32(self.amplitude / _caustic_mean())
        pattern += np.float32(1.0 - self.amplitude)
        return pattern


def _caustic_mean() -> float:
    """Mean of ``exp(g s)`` over uniform independent phases: ``I_0(g / n)^n`` (modified Bessel function)."""
    return float(np.i0(CAUSTIC_SHARPNESS / CAUSTIC_WAVES) ** CAUSTIC_WAVES)


__all__ = [
    "CausticWaves",
    "backscatter_knots",
    "beam_profile",
    "lamp_axis",
    "lamp_backscatter_table",
    "lookup_backscatter",
]
