"""Confidence intervals over seeds: how far a stochastic tracker's board values may move with other seeds.

A board value pools every frame of every seed (:mod:`benchmark.leaderboard`).
Its 95 % interval is a percentile bootstrap over **seeds**: seeds are drawn
with replacement, their frames pooled again and the value recomputed, 2000
times (:func:`scipy.stats.bootstrap`).  Seeds, not frames or sequences,
are resampled because they are the independent repetitions: frames of one
sequence are correlated, and the sequences of a suite are a fixed design,
not a sample.  Each seed is reduced first to the sums its values are made
of (frames per outcome, squared errors per column), so a resample costs a
sum, and the bootstrap draws from a generator of fixed seed, so a board is
the same every time it is made.

A tracker whose seeds all gave the same frames, outcome for outcome and
error for error, is *deterministic* on that row: its interval is the value
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

from benchmark.model import Outcome

CONFIDENCE = 0.95
RESAMPLES = 2000
BOOTSTRAP_SEED = 20260701
"""Seed of the bootstrap's generator, fixed so that a board is reproducible."""


def _sums(frames: pd.DataFrame, error_columns: Sequence[str], scales: np.ndarray) -> np.ndarray:
    """Scored frames, frames per outcome, then per error column the count and sum of squares over ``scales``."""
    outcomes = frames["outcome"].dropna() if "outcome" in frames else pd.Series(dtype=object)
    sums = [float(len(outcomes)), *(float((outcomes == str(outcome)).sum()) for outcome in Outcome)]
    for column, scale in zip(error_columns, scales):
        values = frames[column].to_numpy(dtype=float) if column in frames else np.array([])
        values = values[np.isfinite(values)]
        sums += [float(values.size), float(np.sum((values / scale) ** 2)) if scale > 0 else 0.0]
    return np.array(sums)


def _metrics(sums: np.ndarray, scales: np.ndarray) -> np.ndarray:
    """Rates then RMSEs from summed :func:`_sums` (last axis), as :func:`benchmark.results.summarise` makes them."""
    scored = sums[..., 0]
    with np.errstate(invalid="ignore", divide="ignore"):
        rates = [100.0 * sums[..., 1 + k] / scored for k in range(len(Outcome))]
        first = 1 + len(Outcome)
        rmses = [
            scale * np.sqrt(sums[..., first + 2 * c + 1] / sums[..., first + 2 * c]) for c, scale in enumerate(scales)
        ]
    return np.stack([*rates, *rmses])


def _scale(tables: Sequence[pd.DataFrame], column: str) -> float:
    """The largest finite ``|error|`` of a column over all tables, the unit errors are squared in."""
    values = [np.abs(t[column].to_numpy(dtype=float)) for t in tables if column in t]
    finite = np.concatenate([v[np.isfinite(v)] for v in values]) if values else np.array([])
    return float(np.max(finite, initial=0.0))


def _identical(tables: Sequence[pd.DataFrame], columns: Sequence[str]) -> bool:
    """Whether every table has the same outcomes and errors, frame by frame."""
    kept = [table.reindex(columns=["frame", "outcome", *columns]).reset_index(drop=True) for table in tables]
    return all(table.equals(kept[0]) for table in kept[1:])


def seed_intervals(
    per_seed: Sequence[pd.DataFrame], error_columns: Sequence[str]
) -> tuple[dict[str, tuple[float, float]], bool | None]:
    """The 95 % interval of each rate and RMSE of frames pooled over seeds, and whether the seeds agree.

    Parameters
    ----------
    per_seed : sequence of pandas.DataFrame
        One frame table per seed (:func:`benchmark.results.frame_table`,
        pooled over the datasets of a row), in seed order.
    error_columns : sequence of str
        The modality's error columns, ``err_*``.

    Returns
    -------
    intervals : dict
        ``correct_pct``, ``false_pct``, ``missed_pct`` and ``rmse_*`` to
        ``(low, high)``; NaN bounds for a single seed or a value no seed has.
    deterministic : bool or None
        True when all seeds gave identical frames (the interval is then the
        value), False when they differ, None for a single seed.
    """
    names = [f"{outcome}_pct" for outcome in Outcome] + ["rmse_" + c.removeprefix("err_") for c in error_columns]
    nothing = {name: (math.nan, math.nan) for name in names}
    if len(per_seed) < 2:
        return nothing, None
    scales = np.array([_scale(per_seed, column) for column in error_columns])
    sums = np.stack([_sums(table, error_columns, scales) for table in per_seed])
    if _identical(per_seed, error_columns):
        return {name: (float(v), float(v)) for name, v in zip(names, _metrics(sums[0], scales))}, True

    def statistic(seeds: np.ndarray, axis: int = -1) -> np.ndarray:
        return _metrics(sums[np.asarray(seeds, dtype=int)].sum(axis=-2), scales)

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
