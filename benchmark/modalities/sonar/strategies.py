"""Hypothesis strategies of the sonar modality: calibrations, scene specs, sequences and swaths.

For property-based tests of sonar trackers and for the conformance kit
(:data:`benchmark.modality.ExampleSequences`).  Every sequence is a
:class:`~benchmark.modalities.sonar.scenes.scene.SonarScene`, simulated
from a random but valid spec, so its frames are exactly what a suite
would hold: a multibeam swath over a pipe, with the scene's own range
noise, missing beams and spikes, and the pipe's truth.

:func:`swaths` gives single pings whose faults the test controls: the
scene casts a clean swath, then chosen beams are lost (one by one, in
runs, or all of them) and others spiked to depths no bottom return can
have, more than :data:`RANGE_GATE_M` above or below their own return.

The geometry is drawn so that the scene always accepts it: the vehicle
flies high enough that the pipe's top stays below the transducer whatever
the relief, the seabed's slope leaves every beam of a level sonar a bottom
within the range gate, and the pipe stays inside the seabed grid and the
swath's footprint.  Hypothesis makes every choice, seeds included, so that
an example shrinks and replays bit for bit.

Examples
--------
>>> from hypothesis import given
>>> @given(swaths(spikes=False))
... def test_the_detector_survives_missing_beams(swath):
...     ...
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from hypothesis import strategies as st

from benchmark.modalities.sonar.model import SonarCalibration, Swath
from benchmark.modalities.sonar.scenes.scene import SonarScene
from benchmark.modalities.sonar.scenes.spec import SonarSceneSpec
from benchmark.model import Sequence

N_BEAMS = (16, 300)
"""Beams per ping of the sonars drawn (a fan of a few beams, mostly outer ones, may lose every return)."""

SWATH_DEG = (30.0, 150.0)
"""Full opening of their fans, degrees."""

RANGE_SIGMA_M = (0.0, 0.1)
"""Standard deviation of their range error head-on."""

PIPE_DIAMETER_M = (0.1, 2.0)
"""Diameter of the pipes they follow."""

RANGE_GATE_M = 100.0
"""Range gate of every sonar drawn; no bottom return is farther, and a spike lands at least this far off."""

RELIEF_M = 2.0
"""Bound on how far roughness and ripples move the seabed from its plane (many standard deviations)."""

MAX_SLOPE_DEG = 10.0
"""Steepest across-track slope of the seabed."""

MAX_CROSSING_DEG = 30.0
"""Largest angle between the pipe and the track."""


def calibrations() -> st.SearchStrategy[SonarCalibration]:
    """Plausible multibeam echo sounders and the pipes they follow.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of SonarCalibration
        :data:`N_BEAMS` beams over a fan of :data:`SWATH_DEG`, a range
        error of :data:`RANGE_SIGMA_M` and a pipe of :data:`PIPE_DIAMETER_M`,
        all of which the sonar scenes accept.
    """
    return st.builds(
        SonarCalibration,
        n_beams=st.integers(*N_BEAMS),
        swath_angle=_floats(*SWATH_DEG).map(math.radians),
        range_sigma_m=_floats(*RANGE_SIGMA_M),
        pipe_diameter_m=_floats(*PIPE_DIAMETER_M),
    )


def scene_specs(max_frames: int = 4) -> st.SearchStrategy[SonarSceneSpec]:
    """Random but valid sonar scene specs, built from plain tables as a suite file's are.

    Each spec has a random seed and 1 to ``max_frames`` pings; a sonar from
    :func:`calibrations` with a random beam width, range step, outer-beam
    noise, missing beams and spikes; a rolling vehicle at a random
    altitude; a sloping seabed with roughness, ripples and sometimes
    boulders; and the pipe at a random position (drifting across the
    swath from ping to ping) and burial (0 proud to 1 covered).

    Parameters
    ----------
    max_frames : int
        Most pings in a spec, at least 1.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of SonarSceneSpec

    Raises
    ------
    ValueError
        If ``max_frames`` is below 1.
    """
    if max_frames < 1:
        raise ValueError(f"max_frames must be >= 1, got {max_frames}")
    return _scene_tables(st.integers(1, max_frames), calibrations(), faults=True).map(SonarSceneSpec.from_dict)


def sequences(max_frames: int = 4) -> st.SearchStrategy[Sequence]:
    """Simulated sonar sequences of 1 to ``max_frames`` labelled pings, from :func:`scene_specs`.

    This is the modality's :data:`benchmark.modality.ExampleSequences`, the
    strategy the conformance kit draws sonar sequences from.

    Parameters
    ----------
    max_frames : int
        Most pings in a sequence, at least 1.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of benchmark.model.Sequence
        :class:`~benchmark.modalities.sonar.scenes.scene.SonarScene` s; each
        frame holds a :class:`~benchmark.modalities.sonar.model.Swath` and
        a :class:`~benchmark.modalities.sonar.model.SonarTruth`.
    """
    return scene_specs(max_frames).map(SonarScene)


def swaths(
    calibration: SonarCalibration | None = None, *, missing: bool = True, spikes: bool = True
) -> st.SearchStrategy[Swath]:
    """Single pings over a pipe, with the faults a test asks for.

    The clean swath is the only ping of a random scene with ``calibration``'s
    sonar and pipe, a level vehicle and no faults of its own but range
    noise: every beam returns from the bottom or the pipe, within
    :data:`RANGE_GATE_M` (for a fan wider than :data:`SWATH_DEG` the outer
    beams may find no bottom).  Then

    * with ``missing``, some beams lose their return (``nan`` in both
      arrays): scattered single beams, runs of neighbours, none, or, now
      and then, every beam;
    * with ``spikes``, one or more of the remaining beams (at least one if
      any remain) keep their across-track position but report a depth
      :data:`RANGE_GATE_M` to twice that above or below their return: above
      the transducer or beyond the range gate.

    Parameters
    ----------
    calibration : SonarCalibration or None
        The sonar and pipe; None draws them from :func:`calibrations`.
        Its swath angle must be below 175 degrees and its pipe diameter
        between 0.05 and 5 m, as the scenes require.
    missing, spikes : bool
        Whether to lose beams and add spikes.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of Swath
        Swaths of ``calibration.n_beams`` beams.
    """
    sonars = calibrations() if calibration is None else st.just(calibration)
    clean = _scene_tables(st.just(1), sonars, faults=False).map(_first_ping)
    return _damaged(clean, missing, spikes)


def _first_ping(table: dict[str, Any]) -> Swath:
    """The swath of the first ping of the scene ``table`` defines."""
    return SonarScene.from_dict(table).observation(0)


def _floats(low: float, high: float) -> st.SearchStrategy[float]:
    """Floats in ``[low, high]``, without the subnormals that underflow the scene's arithmetic."""
    return st.floats(low, high, allow_subnormal=False)


@st.composite
def _scene_tables(
    draw: st.DrawFn,
    frame_counts: st.SearchStrategy[int],
    sonars: st.SearchStrategy[SonarCalibration],
    *,
    faults: bool,
) -> dict[str, Any]:
    """Scene tables the sonar scene accepts; without ``faults``, a level sonar whose every beam returns."""
    seed = draw(st.integers(0, 2**32 - 1))
    n_frames = draw(frame_counts)
    calibration = draw(sonars)
    diameter = calibration.pipe_diameter_m
    half_swath = calibration.swath_angle / 2.0

    # The slope may lift the seabed under the pipe by 30 % of the altitude,
    # the relief by RELIEF_M: the pipe's top stays a metre below the sonar.
    lowest = (diameter + RELIEF_M + 1.0) / 0.7
    # Every beam must meet the bottom within 90 % of the range gate (level
    # seabed: altitude / cos(half_swath)); the slope takes what is left.
    highest = 0.9 * RANGE_GATE_M * math.cos(half_swath) - RELIEF_M
    altitude = draw(_floats(lowest, max(lowest, min(lowest + 15.0, highest))))
    reach = (altitude + RELIEF_M) / (0.9 * RANGE_GATE_M)
    steepest = math.atan(max(math.cos(half_swath) - reach, 0.0) / math.sin(half_swath))
    steepest_deg = min(math.degrees(steepest), MAX_SLOPE_DEG)
    slope_deg = draw(_floats(-steepest_deg, steepest_deg))

    interval = draw(_floats(0.1, 0.5))
    speed = draw(_floats(0.5, 2.5))
    # The pipe keeps inside the swath's footprint, the seabed grid and the
    # stretch where the slope lifts the seabed by at most 30 % of the altitude.
    limit = 0.8 * max(
        0.0,
        min(
            altitude * math.tan(half_swath),
            RANGE_GATE_M * math.sin(half_swath) - diameter - 1.0,
            0.3 * altitude / max(math.tan(math.radians(abs(slope_deg))), 1e-9),
        ),
    )
    start, end = draw(_floats(-1.0, 1.0)), draw(_floats(-1.0, 1.0))
    fastest = interval * speed * math.tan(math.radians(MAX_CROSSING_DEG))
    drift = float(np.clip((end - start) * limit / max(n_frames - 1, 1), -fastest, fastest))

    sonar: dict[str, Any] = {
        "model": "random multibeam",
        "n_beams": calibration.n_beams,
        "swath_deg": math.degrees(calibration.swath_angle),
        "beam_width_deg": draw(_floats(0.0, 3.0)),
        "range_sigma_m": calibration.range_sigma_m,
        "outer_sigma_factor": draw(_floats(1.0, 3.0)),
        "range_resolution_m": draw(st.just(0.0) | _floats(0.001, 0.05)),
        "max_range_m": RANGE_GATE_M,
    }
    vehicle: dict[str, Any] = {"altitude_m": {"mean": altitude}, "speed_mps": speed}
    if faults:
        sonar |= {
            "missing_nadir": draw(_floats(0.0, 0.05)),
            "missing_outer": draw(_floats(0.0, 0.3)),
            "outlier_rate": draw(_floats(0.0, 0.05)),
            "outlier_scale_m": draw(_floats(0.2, 3.0)),
        }
        vehicle["roll_deg"] = {"mean": draw(_floats(-5.0, 5.0)), "noise_std": draw(_floats(0.0, 1.0))}
    roughness = st.fixed_dictionaries({"std_m": _floats(0.0, 0.15), "length_m": _floats(0.3, 5.0)})
    boulders = st.fixed_dictionaries({"per_100m2": _floats(0.0, 2.0)})
    return {
        "name": f"sonar/random-{seed}",
        "n_frames": n_frames,
        "seed": seed,
        "frame_interval_s": interval,
        "sonar": sonar,
        "vehicle": vehicle,
        "seabed": {
            "slope_deg": {"mean": slope_deg},
            "roughness": draw(st.lists(roughness, max_size=2)),
            "ripples": {
                "height_m": draw(_floats(0.0, 0.1)),
                "wavelength_m": draw(_floats(0.5, 3.0)),
                "crest_deg": draw(_floats(-90.0, 90.0)),
            },
            "boulders": draw(st.lists(boulders, max_size=1)),
        },
        "pipe": {
            "diameter_m": diameter,
            "across_m": {"mean": start * limit, "slope_per_frame": drift},
            "burial": {"mean": draw(_floats(-0.5, 1.5)), "slope_per_frame": draw(_floats(-0.3, 0.3))},
        },
    }


@st.composite
def _damaged(draw: st.DrawFn, clean: st.SearchStrategy[Swath], missing: bool, spikes: bool) -> Swath:
    """A swath from ``clean`` with beams lost and spiked as :func:`swaths` describes."""
    swath = draw(clean)
    n_beams = swath.across_m.size
    across, depth = swath.across_m.copy(), swath.depth_m.copy()
    if missing:
        lost = draw(_lost_beams(n_beams))
        across[lost] = depth[lost] = np.nan
    returning = np.flatnonzero(np.isfinite(depth))
    if spikes and returning.size:
        picks = st.sets(st.integers(0, returning.size - 1), min_size=1, max_size=max(1, returning.size // 10))
        for beam in returning[sorted(draw(picks))]:
            offset = draw(_floats(RANGE_GATE_M, 2.0 * RANGE_GATE_M))
            depth[beam] += offset if draw(st.booleans()) else -offset
    return Swath(across, depth)


@st.composite
def _lost_beams(draw: st.DrawFn, n_beams: int) -> np.ndarray:
    """Mask of lost beams: scattered ones and runs of neighbours, or, now and then, all of them."""
    lost = np.zeros(n_beams, dtype=bool)
    if draw(st.integers(0, 9)) == 9:
        lost[:] = True
        return lost
    lost[draw(st.lists(st.integers(0, n_beams - 1), max_size=n_beams // 4))] = True
    longest = max(2, n_beams // 4)
    for first, length in draw(st.lists(st.tuples(st.integers(0, n_beams - 1), st.integers(2, longest)), max_size=3)):
        lost[first : first + length] = True
    return lost
