"""Confidence intervals over seeds: how far a stochastic tracker's board values may move with other seeds.

A board value pools every frame of every seed (:mod:`benchmark.leaderboard`).
Its 95 % interval is a percentile bootstrap over **seeds**: seeds are drawn
with replacement, their frames pooled again and the value recomputed, 2000
times (:func:`scipy.stats.bootstrap`).  Seeds, not frames or sequences,
are resampled because they are the independent repetitions: frames of one
sequence are correlated, and the sequences of a suite are a fixed design,
not a sample.  Each seed is reduced first to the sums its values are made
of (:class:`benchmark.metrics.Metric`: frames per outcome, squared errors
per column, ...), so a resample costs a sum, and the bootstrap draws from a generator of fixed seed, so a board is
the same every time it is made.

A tracker whose seeds all gave the same frames, outcome for outcome and
error for error (every column the metrics read but the step time),
is *deterministic* on that row: its interval is the value
itself.  With a single seed nothing is known about the spread, and the
interval is empty (NaN).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np
import pandas as pd
from scipy.stats import DegenerateDataWarning, bootstrap

from benchmark.metrics import Metric

CONFIDENCE = 0.95
RESAMPLES = 2000
BOOTSTRAP_SEED = 20260701
"""Seed of the bootstrap's generator, fixed so that a board is reproducible."""


def _identical(tables: Sequence[pd.DataFrame], columns: Sequence[str]) -> bool:
    """Whether every table has the same values in ``columns``, frame by frame."""
    kept = [table.reindex(columns=["frame", *columns]).reset_index(drop=True) for table in tables]
    return all(table.equals(kept[0]) for table in kept[1:])


def seed_intervals(
    per_seed: Sequence[pd.DataFrame], metrics: Sequence[Metric]
) -> tuple[dict[str, tuple[float, float]], bool | None]:
    """The 95 % interval of each metric of frames pooled over seeds, and whether the seeds agree.

    Parameters
    ----------
    per_seed : sequence of pandas.DataFrame
        One frame table per seed (:func:`benchmark.results.frame_table`,
        pooled over the datasets of a row), in seed order.
    metrics : sequence of Metric
        The board's metrics; those with an interval
        (:attr:`benchmark.metrics.Metric.interval`) get one.

    Returns
    -------
    intervals : dict
        Each such metric's name to ``(low, high)``; NaN bounds for a single
        seed or a value no seed has.
    deterministic : bool or None
        True when all seeds gave identical frames in every column those
        metrics read (the interval is then the value), False when they
        differ, None for a single seed.
    """
    metrics = [metric for metric in metrics if metric.interval]
    names = [metric.name for metric in metrics]
    if len(per_seed) < 2:
        return {name: (math.nan, math.nan) for name in names}, None
    scales = [metric.scale(per_seed) for metric in metrics]
    sums = [np.array([metric.sums(table, scale) for table in per_seed], dtype=float).reshape(len(per_seed), -1)
            for metric, scale in zip(metrics, scales)]
    read = list(dict.fromkeys(column for metric in metrics for column in metric.columns if column != "frame"))
    if _identical(per_seed, read):
        values = [
            metric.value(metric.pooled(part[:1], axis=0), scale) for metric, part, scale in zip(metrics, sums, scales)
        ]
        return {name: (float(v), float(v)) for name, v in zip(names, values)}, True

    def statistic(seeds: np.ndarray, axis: int = -1) -> np.ndarray:
        chosen = np.asarray(seeds, dtype=int)
        return np.stack([
            metric.value(metric.pooled(part[chosen], axis=-2), scale)
            for metric, part, scale in zip(metrics, sums, scales)
        ])

    with warnings.catch_warnings():
        # A value every resample gives alike (a rate no seed reaches) is a point interval, as it should be.
        warnings.simplefilter("ignore", DegenerateDataWarning)
        result = bootstrap(
            (np.arange(len(per_seed)),),
            statistic,
            vectorized=True,
            n_resamples=RESAMPLES,
            confidence_level=CONFIDENCE,
            method="percentile",
            rng=np.random.default_rng(BOOTSTRAP_SEED),
        )
    low, high = result.confidence_interval
    return {name: (float(lo), float(hi)) for name, lo, hi in zip(names, low, high)}, False
