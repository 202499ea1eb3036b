"""Reusable filter cores that tracker plugins build on.

* :mod:`~benchmark.filters.particles`: a weighted particle set, its
  effective sample size and estimates;
* :mod:`~benchmark.filters.resampling`: multinomial (cumulative weights with
  binary search), systematic, stratified and residual resampling;
* :mod:`~benchmark.filters.condensation`: one step of the condensation
  algorithm from swappable movement and observation models;
* :mod:`~benchmark.filters.kalman`: linear and extended Kalman filter
  steps on a Gaussian belief.

Every random draw comes from a ``numpy.random.Generator`` handed in by the
caller, so a seed replays a filter bit for bit.
"""

from benchmark.filters.condensation import Condensation, LinearDriftDiffusion, MovementModel, ObservationModel
from benchmark.filters.kalman import Gaussian, predict, update
from benchmark.filters.particles import ParticleSet, effective_sample_size, normalise_weights
from benchmark.filters.resampling import (
    RESAMPLERS,
    Resampler,
    ResamplerName,
    multinomial_resample,
    residual_resample,
    stratified_resample,
    systematic_resample,
)

__all__ = [
    "RESAMPLERS",
    "Condensation",
    "Gaussian",
    "LinearDriftDiffusion",
    "MovementModel",
    "ObservationModel",
    "ParticleSet",
    "Resampler",
    "ResamplerName",
    "effective_sample_size",
    "multinomial_resample",
    "normalise_weights",
    "predict",
    "residual_resample",
    "stratified_resample",
    "systematic_resample",
    "update",
]
