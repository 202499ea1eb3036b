"""Signals: a quantity of a scene that varies from frame to frame, defined as data.

A :class:`Signal` is a mean, a slope, tapered sinusoids (:class:`Wave`),
smooth steps and pulses (:class:`Event`) and smoothed Gaussian noise;
:func:`evaluate_signal` samples it at every frame.  The camera's pose
(seeds/004, section V) and the sonar vehicle's altitude and attitude are
signals.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
import pydantic

from benchmark.parameters import require_order
from benchmark.scenes.noise import smoothed_noise
from benchmark.scenes.spec import SPEC_CONFIG, NonNegative, Number, Positive


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Wave:
    """A sinusoid ``amplitude * sin(2 pi k / period_frames + phase)`` of frame ``k``.

    It is active between ``start_frame`` and ``stop_frame`` and fades in and
    out over ``taper_frames`` at both ends.
    """

    amplitude: Number
    period_frames: Positive
    phase_deg: Number = 0.0
    start_frame: Number = -math.inf
    stop_frame: Number = math.inf
    taper_frames: NonNegative = 0.0

    def __post_init__(self) -> None:
        require_order(self, ("start_frame", "stop_frame"))


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Event:
    """A manoeuvre centred on ``frame`` that lasts ``duration_frames``.

    ``shape = "step"`` moves the signal smoothly by ``amplitude`` and keeps
    it there; ``shape = "pulse"`` goes out by ``amplitude`` and back.
    """

    frame: Number
    amplitude: Number
    duration_frames: Positive = 10.0
    shape: Literal["step", "pulse"] = "step"


@pydantic.dataclasses.dataclass(frozen=True, config=SPEC_CONFIG)
class Signal:
    """One pose coordinate over time: ``mean + slope k + waves + events + noise``.

    The noise is white Gaussian noise smoothed by a Gaussian of
    ``noise_smooth_frames`` (its standard deviation, in frames) and scaled to
    the standard deviation ``noise_std``.
    """

    mean: Number = 0.0
    slope_per_frame: Number = 0.0
    waves: tuple[Wave, ...] = ()
    events: tuple[Event, ...] = ()
    noise_std: NonNegative = 0.0
    noise_smooth_frames: NonNegative = 4.0


def _taper(k: np.ndarray, start: float, stop: float, width: float) -> np.ndarray:
    """1 inside ``[start, stop]``, 0 outside, with raised-cosine edges of ``width``."""
    inside = ((k >= start) & (k <= stop)).astype(float)
    if width <= 0:
        return inside
    rise = np.clip((k - start) / width, 0.0, 1.0)
    fall = np.clip((stop - k) / width, 0.0, 1.0)
    ramp = np.minimum(rise, fall)
    return 0.5 - 0.5 * np.cos(math.pi * ramp)


def evaluate_signal(signal: Signal, n: int, rng: np.random.Generator) -> np.ndarray:
    """Values of a signal at frames ``0 .. n-1``.

    Parameters
    ----------
    signal : Signal
        Its definition.
    n : int
        Number of frames.
    rng : numpy.random.Generator
        Source of its noise; always consumed the same way for a given ``n``
        and ``noise_smooth_frames``.

    Returns
    -------
    numpy.ndarray
        ``float`` array of length ``n``.
    """
    k = np.arange(n, dtype=float)
    values = signal.mean + signal.slope_per_frame * k
    for wave in signal.waves:
        envelope = _taper(k, wave.start_frame, wave.stop_frame, wave.taper_frames)
        values = values + wave.amplitude * envelope * np.sin(
            2 * math.pi * k / wave.period_frames + math.radians(wave.phase_deg)
        )
    for event in signal.events:
        s = np.clip((k - event.frame) / event.duration_frames + 0.5, 0.0, 1.0)
        if event.shape == "step":
            profile = 0.5 - 0.5 * np.cos(math.pi * s)
        else:
            profile = 0.5 - 0.5 * np.cos(2 * math.pi * s)
        values = values + event.amplitude * profile
    noise = smoothed_noise(rng, n, signal.noise_smooth_frames)
    return values + signal.noise_std * noise


