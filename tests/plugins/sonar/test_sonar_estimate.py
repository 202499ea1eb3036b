"""Peak extraction: eq. (5) over the heaviest peak of the particles (seeds/003, section 3.3)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_sonar.estimate import peak_mean


def test_all_particles_give_the_weighted_mean_of_eq_5():
    x = np.array([0.0, 1.0, 10.0])
    w = np.array([0.5, 0.3, 0.2])
    expected = 0.3 + 2.0
    assert peak_mean(x, w, 0.0) == pytest.approx(expected)
    assert peak_mean(x, w, math.inf) == pytest.approx(expected)


def test_the_heavier_of_two_peaks_is_averaged_on_its_own():
    rng = np.random.default_rng(0)
    main = rng.normal(-2.0, 0.05, 200)
    rival = rng.normal(3.0, 0.05, 100)
    x = np.concatenate([main, rival])
    w = np.full(300, 1.0 / 300)
    assert peak_mean(x, w, 0.6) == pytest.approx(np.mean(main))
    assert peak_mean(x, w, 0.0) == pytest.approx(np.mean(x))
    w[200:] *= 3.0
    w /= w.sum()
    assert peak_mean(x, w, 0.6) == pytest.approx(np.mean(rival))


@settings(max_examples=80, deadline=None)
@given(
    arrays(float, st.integers(1, 60), elements=st.floats(-50, 50)),
    st.floats(0.01, 20.0),
    st.integers(0, 2**16),
)
def test_the_estimate_lies_within_the_particles_and_within_h_of_one(x, halfwidth, seed):
    w = np.random.default_rng(seed).random(x.size) + 1e-3
    w /= w.sum()
    estimate = peak_mean(x, w, halfwidth)
    assert x.min() - 1e-9 <= estimate <= x.max() + 1e-9
    assert np.min(np.abs(x - estimate)) <= halfwidth + 1e-9


def array_peak_mean(positions: np.ndarray, weights: np.ndarray, halfwidth: float) -> float:
    """:func:`peak_mean` for ``0 < h < inf`` in NumPy, the form the compiled pass replaced (the reference)."""
    order = np.argsort(positions, kind="stable")
    x, w = positions[order], weights[order]
    mass = np.concatenate([[0.0], np.cumsum(w)])
    moment = np.concatenate([[0.0], np.cumsum(w * x)])
    low = np.searchsorted(x, x - halfwidth, side="left")
    high = np.searchsorted(x, x + halfwidth, side="right")
    window = mass[high] - mass[low]
    best = int(np.argmax(window))
    if not window[best] > 0.0:
        return float(np.mean(positions))
    return float((moment[high[best]] - moment[low[best]]) / window[best])


@settings(max_examples=150, deadline=None)
@given(
    arrays(float, st.integers(1, 300), elements=st.floats(-50, 50) | st.sampled_from([0.0, -0.0, 1.0])),
    st.floats(1e-6, 60.0),
    st.integers(0, 2**16),
    st.sampled_from(["random", "equal", "sparse", "none"]),
)
def test_the_compiled_peak_is_the_array_form_to_the_last_bit(x, halfwidth, seed, kind):
    rng = np.random.default_rng(seed)
    w = {
        "random": rng.random(x.size),
        "equal": np.full(x.size, 1.0 / x.size),
        "sparse": np.where(rng.random(x.size) < 0.1, rng.random(x.size), 0.0),
        "none": np.zeros(x.size),
    }[kind]
    # As the filter hands them over: a column of its states (a strided view).
    states = np.column_stack([x, np.zeros(x.size)])
    assert np.float64(peak_mean(states[:, 0], w, halfwidth)).view(np.int64) == np.float64(
        array_peak_mean(x, w, halfwidth)
    ).view(np.int64)
