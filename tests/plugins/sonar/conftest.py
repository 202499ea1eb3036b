"""Analytic swaths for the sonar trackers' tests.

A swath is cast from a sonar at the origin over a plane seabed at
``altitude`` m below it, sloping by ``slope`` (depth gained per metre to
starboard), with a circular pipe of ``diameter`` resting on it at
``pipe_at`` (sunk by ``burial`` of its diameter), and optionally a second
pipe.  The beams are equiangular over ``swath_deg``; each meets the nearest
of the surfaces; range noise, missing beams (``nan``) and spikes are
optional.  Tests use the helpers through the ``swaths`` fixture.

:func:`cast_scene` casts beams of a given width on any seabed profile with
pipes on it, through the sonar scenes' own caster
(:func:`benchmark.modalities.sonar.scenes.swath.beam_ranges`): wide beams
that smooth a pipe, rough seabed, trenches with spoil berms.
"""

from __future__ import annotations

import math
import types

import numpy as np
import pytest

from benchmark.modalities.sonar.model import SonarCalibration, SonarTruth, Swath
from benchmark.modalities.sonar.scenes.seabed import across_grid
from benchmark.modalities.sonar.scenes.swath import Ellipse, beam_angles, beam_ranges, swath_from_ranges
from benchmark.model import Frame, SequenceInfo


def _circle_range(dx: np.ndarray, dz: np.ndarray, cx: float, cz: float, radius: float) -> np.ndarray:
    """Range along unit rays ``(dx, dz)`` from the origin to a circle, ``inf`` where they miss."""
    along = dx * cx + dz * cz
    disc = along**2 - (cx * cx + cz * cz - radius * radius)
    hit = (disc >= 0.0) & (along > 0.0)
    return np.where(hit, along - np.sqrt(np.where(hit, disc, 0.0)), np.inf)


def seabed_depth(x: float, altitude: float, slope: float) -> float:
    """Depth of the plane seabed at across-track ``x``."""
    return altitude + slope * x


def pipe_centre(pipe_at: float, diameter: float, burial: float, altitude: float, slope: float) -> tuple[float, float]:
    """Centre of a pipe resting on the seabed at ``pipe_at``, sunk by ``burial`` of its diameter."""
    radius = 0.5 * diameter
    return pipe_at, seabed_depth(pipe_at, altitude, slope) - radius + burial * diameter


def make_swath(
    pipe_at: float | None = 0.0,
    *,
    n_beams: int = 240,
    swath_deg: float = 120.0,
    altitude: float = 10.0,
    slope: float = 0.0,
    diameter: float = 0.6,
    burial: float = 0.0,
    second_at: float | None = None,
    noise: float = 0.0,
    missing: float = 0.0,
    spikes: int = 0,
    seed: int = 0,
) -> Swath:
    """One analytic ping (see the module docstring)."""
    rng = np.random.default_rng(seed)
    angles = np.radians(np.linspace(-0.5 * swath_deg, 0.5 * swath_deg, n_beams))
    dx, dz = np.sin(angles), np.cos(angles)
    denominator = dz - slope * dx
    ranges = np.where(denominator > 1e-9, altitude / np.where(denominator > 1e-9, denominator, 1.0), np.inf)
    for where in (pipe_at, second_at):
        if where is not None:
            cx, cz = pipe_centre(where, diameter, burial, altitude, slope)
            ranges = np.minimum(ranges, _circle_range(dx, dz, cx, cz, 0.5 * diameter))
    ranges = ranges + noise * rng.standard_normal(n_beams)
    across, depth = ranges * dx, ranges * dz
    if spikes:
        which = rng.choice(n_beams, size=spikes, replace=False)
        depth[which] += rng.choice([-1.0, 1.0], size=spikes) * rng.uniform(3.0, 6.0, size=spikes)
    gone = ~np.isfinite(ranges) | (rng.random(n_beams) < missing)
    across[gone] = np.nan
    depth[gone] = np.nan
    return Swath(across, depth)


def cast_scene(
    relief,
    pipes=(),
    *,
    n_beams: int = 240,
    swath_deg: float = 120.0,
    altitude: float = 10.0,
    beam_width_deg: float = 0.0,
    noise: float = 0.0,
    seed: int = 0,
) -> Swath:
    """One ping of beams ``beam_width_deg`` wide over the seabed ``altitude + relief(x)`` (``relief`` positive down).

    ``pipes`` holds ``(across, diameter, gap)``: a circular pipe whose lowest point is ``gap`` m above the
    seabed under its axis (0: resting on it; negative: sunk).
    """
    across = across_grid(altitude * 4.0, 0.01)
    depth = altitude + relief(across)
    ellipses = []
    for x, diameter, gap in pipes:
        bottom = altitude + float(relief(np.array([x]))[0]) - gap
        ellipses.append(Ellipse(x, bottom - 0.5 * diameter, 0.5 * diameter, 0.5 * diameter))
    axes = beam_angles(n_beams, math.radians(swath_deg))
    ranges, _ = beam_ranges(across, depth, axes, ellipses, math.radians(beam_width_deg), 1e3)
    ranges = ranges + noise * np.random.default_rng(seed).standard_normal(n_beams)
    return swath_from_ranges(ranges, axes)


def beam_spacing_at(x: float, altitude: float, n_beams: int = 240, swath_deg: float = 120.0) -> float:
    """Across-track distance between neighbouring beams near ``x`` on a flat seabed at ``altitude``."""
    step = math.radians(swath_deg) / (n_beams - 1)
    angle = math.atan2(x, altitude)
    return altitude * step / math.cos(angle) ** 2


def calibration(
    n_beams: int = 240, swath_deg: float = 120.0, noise: float = 0.02, diameter: float = 0.6, beam_width_deg: float = 0.0
):
    """A SonarCalibration matching :func:`make_swath` (or :func:`cast_scene`)."""
    return SonarCalibration(n_beams, math.radians(swath_deg), noise, diameter, math.radians(beam_width_deg))


def info(name: str = "sonar/analytic", n_frames: int | None = None, **calibration_args) -> SequenceInfo:
    """A sonar SequenceInfo with :func:`calibration`."""
    return SequenceInfo(name, "sonar", n_frames, None, 0.3, calibration(**calibration_args))


def track(positions, seed: int = 0, **swath_args) -> list[Frame]:
    """Frames of pings with the pipe at each of ``positions``, with truth."""
    altitude = swath_args.get("altitude", 10.0)
    diameter = swath_args.get("diameter", 0.6)
    frames = []
    for k, x in enumerate(positions):
        swath = make_swath(x, seed=seed * 100_003 + k, **swath_args)
        truth = SonarTruth(float(x), altitude - 0.5 * diameter, 0.0, beam_spacing_at(x, altitude))
        frames.append(Frame(k, swath, truth, None, 0.3 * k))
    return frames


@pytest.fixture(scope="session")
def swaths() -> types.SimpleNamespace:
    """The analytic swath helpers of this module."""
    return types.SimpleNamespace(
        make=make_swath,
        cast=cast_scene,
        centre=pipe_centre,
        spacing_at=beam_spacing_at,
        calibration=calibration,
        info=info,
        track=track,
    )
