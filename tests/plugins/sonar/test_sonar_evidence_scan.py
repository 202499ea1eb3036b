"""The evidence scan computed where it is read, against the scan computed everywhere (seeds/003, eq. 1 as evidence).

:class:`~trackbench_sonar.evidence.EvidenceScan` bounds each candidate's
evidence by the straight line through its window, then by its seafloor's
fit, and fits the pipe only where a value is read or a bound can reach the
maximum or the level asked about.  Everything it reports must be what the
scan of every candidate (:meth:`FootprintLikelihood.candidates`) gives,
bit for bit: the values, the maximum, the peak, whether a level is
exceeded and the values between grid positions, in whatever order they
are read.  The line's bound must hold wherever the seafloor is fitted.
The fits themselves (:func:`~trackbench_sonar.evidence_kernel._fused_fit`,
fewer passes over the returns) must equal the form they replaced,
:func:`old_robust_fit` below (the plugin's code before, kept here as the
reference), to the last bit.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_sonar import evidence_kernel
from trackbench_sonar.cross_section import CrossSection
from trackbench_sonar.evidence import MIN_RETURNS, EvidenceScan, FootprintLikelihood
from trackbench_sonar.footprint import FWHM_PER_SIGMA, footprint_sigma
from trackbench_sonar.likelihood import LikelihoodScan
from trackbench_sonar.profile import resample_swath

from benchmark.modalities.sonar.model import Swath


@numba.njit(cache=True)
def old_normal_equations(
    design: np.ndarray, weights: np.ndarray, target: np.ndarray, n: int, pipe: bool, normal: np.ndarray
) -> None:
    """The weighted normal equations of the seabed's three columns (and the pipe's fourth) into ``normal``."""
    a00 = a01 = a02 = a03 = a11 = a12 = a13 = a22 = a23 = a33 = 0.0
    b0 = b1 = b2 = b3 = 0.0
    for j in range(n):
        d0, d1, d2, t = design[0, j], design[1, j], design[2, j], target[j]
        w0, w1, w2 = weights[j] * d0, weights[j] * d1, weights[j] * d2
        a00 += w0 * d0
        a01 += w0 * d1
        a02 += w0 * d2
        a11 += w1 * d1
        a12 += w1 * d2
        a22 += w2 * d2
        b0 += w0 * t
        b1 += w1 * t
        b2 += w2 * t
        if pipe:
            d3 = design[3, j]
            w3 = weights[j] * d3
            a03 += w0 * d3
            a13 += w1 * d3
            a23 += w2 * d3
            a33 += w3 * d3
            b3 += w3 * t
    columns = 4 if pipe else 3
    normal[0, 0], normal[0, 1], normal[0, 2] = a00, a01, a02
    normal[1, 1], normal[1, 2], normal[2, 2] = a11, a12, a22
    if pipe:
        normal[0, 3], normal[1, 3], normal[2, 3], normal[3, 3] = a03, a13, a23, a33
        normal[3, columns] = b3
    normal[0, columns], normal[1, columns], normal[2, columns] = b0, b1, b2


@numba.njit(cache=True)
def old_robust_fit(
    design: np.ndarray,
    target: np.ndarray,
    n: int,
    columns: int,
    k: float,
    iterations: int,
    coefficients: np.ndarray,
    normal: np.ndarray,
    weights: np.ndarray,
) -> float:
    """IRLS with the Cauchy loss of scale ``k`` on the first ``columns`` rows of ``design``; the cost times ``sigma^2``.

    The fitted coefficients are left in ``coefficients``; ``normal`` (4 x 5) and ``weights`` are work space.
    """
    weights[:n] = 1.0
    inverse = 1.0 / k
    cost = 0.0
    for iteration in range(iterations):
        old_normal_equations(design, weights, target, n, columns == 4, normal)
        trace = 0.0
        for p in range(columns):
            trace += normal[p, p]
            for q in range(p):
                normal[p, q] = normal[q, p]
        ridge = 1e-12 * max(trace, 1.0)
        for p in range(columns):
            normal[p, p] += ridge
        # Gaussian elimination with partial pivoting on the augmented matrix.
        for p in range(columns):
            pivot = p
            for q in range(p + 1, columns):
                if abs(normal[q, p]) > abs(normal[pivot, p]):
                    pivot = q
            if pivot != p:
                for c in range(columns + 1):
                    normal[p, c], normal[pivot, c] = normal[pivot, c], normal[p, c]
            for q in range(p + 1, columns):
                factor = normal[q, p] / normal[p, p]
                for c in range(p, columns + 1):
                    normal[q, c] -= factor * normal[p, c]
        for p in range(columns - 1, -1, -1):
            total = normal[p, columns]
            for c in range(p + 1, columns):
                total -= normal[p, c] * coefficients[c]
            coefficients[p] = total / normal[p, p]
        last = iteration == iterations - 1
        c0, c1, c2 = coefficients[0], coefficients[1], coefficients[2]
        c3 = coefficients[3] if columns == 4 else 0.0
        for j in range(n):
            fitted = c0 * design[0, j] + c1 * design[1, j] + c2 * design[2, j]
            if columns == 4:
                fitted += c3 * design[3, j]
            scaled = (target[j] - fitted) * inverse
            scaled *= scaled
            if last:
                cost += math.log1p(scaled)
            else:
                weights[j] = 1.0 / (1.0 + scaled)
    return k * k * cost


def bits(values: np.ndarray) -> np.ndarray:
    """The bit patterns of float values, so that equality is to the last bit (and ``nan`` equals ``nan``)."""
    return np.ascontiguousarray(values, dtype=float).view(np.int64)


@settings(max_examples=80, deadline=None)
@given(
    st.integers(1, 40),
    st.sampled_from([3, 4]),
    st.floats(0.01, 10.0),
    st.integers(1, 4),
    st.integers(0, 2**32 - 1),
)
def test_the_fused_fit_is_the_old_fit_to_the_last_bit(n, columns, k, iterations, seed):
    rng = np.random.default_rng(seed)
    design = np.vstack([np.ones(n), rng.uniform(-1.0, 1.0, n), rng.uniform(0.0, 1.0, n), -rng.uniform(0.0, 1.0, n)])
    target = rng.normal(20.0, 0.5, n) + rng.standard_cauchy(n) * 0.05
    old_coefficients, new_coefficients = np.zeros(4), np.zeros(4)
    old_cost = old_robust_fit(
        design, target, n, columns, k, iterations, old_coefficients, np.empty((4, 5)), np.empty(n)
    )
    new_cost = evidence_kernel._fused_fit(design, target, n, columns, k, iterations, new_coefficients, np.empty((4, 5)))
    assert bits(np.array([new_cost]))[0] == bits(np.array([old_cost]))[0]
    np.testing.assert_array_equal(bits(new_coefficients[:columns]), bits(old_coefficients[:columns]))


def assert_same_scan(model: FootprintLikelihood, profile, probes: np.ndarray) -> None:
    """Every reading of the lazy scan equals the full scan's, each on a fresh scan (so that none relies on another)."""
    full = LikelihoodScan(profile.across_m, model.candidates(profile).evidence)
    assert EvidenceScan(model, profile).maximum() == full.maximum()
    assert EvidenceScan(model, profile).is_empty == full.is_empty
    for refine in (False, True):
        assert EvidenceScan(model, profile).peak(refine) == full.peak(refine)
    np.testing.assert_array_equal(bits(EvidenceScan(model, profile).at(probes)), bits(full.at(probes)))
    np.testing.assert_array_equal(bits(EvidenceScan(model, profile).values), bits(full.values))
    lazy = EvidenceScan(model, profile)
    lazy.peak(True)
    np.testing.assert_array_equal(bits(lazy.at(probes)), bits(full.at(probes)))
    np.testing.assert_array_equal(bits(lazy.values), bits(full.values))
    best = full.maximum()
    for level in (0.0, best, float(np.nextafter(best, -math.inf)), 0.5 * best, 2.0 * best):
        assert EvidenceScan(model, profile).exceeds(level) == (best > level)
        # As the particle filter reads it: the values at its particles first, then a level, then the maximum.
        lazy = EvidenceScan(model, profile)
        np.testing.assert_array_equal(bits(lazy.at(probes)), bits(full.at(probes)))
        assert lazy.exceeds(level) == (best > level)
        assert lazy.maximum() == best and lazy.peak(True) == full.peak(True)


def test_a_pipe_scan_is_the_full_scan_with_few_pipes_fitted(swaths):
    swath = swaths.cast(lambda x: 0.05 * x, [(1.5, 0.6, 0.0)], n_beams=200, swath_deg=120.0, altitude=12.0,
                        beam_width_deg=1.5, noise=0.02, seed=3)  # fmt: skip
    profile = resample_swath(swath, 0.05, spike_m=0.3)
    model = FootprintLikelihood(CrossSection(0.6, 0.6), 0.02, math.radians(1.5))
    rng = np.random.default_rng(0)
    probes = np.concatenate([1.5 + rng.normal(0.0, 0.3, 200), [np.nan, -np.inf, profile.across_m[0], 1e9]])
    assert_same_scan(model, profile, probes)
    lazy = EvidenceScan(model, profile)
    assert abs(lazy.peak(True) - 1.5) < 0.1
    assert 0 < lazy.evaluated < profile.size // 4


@settings(max_examples=60, deadline=None)
@given(
    arrays(float, st.integers(2, 80), elements=st.floats(-30, 30)),
    arrays(float, 80, elements=st.floats(1.0, 60.0)),
    st.floats(0.0, 0.05),
    st.floats(0.2, 1.5),
    st.integers(1, 4),
    arrays(float, st.integers(0, 30), elements=st.floats(-40, 40) | st.sampled_from([math.nan, math.inf])),
)
def test_the_lazy_scan_is_the_full_scan_on_arbitrary_returns(across, depth, beam_width, diameter, iterations, probes):
    model = FootprintLikelihood(CrossSection(diameter, diameter), 0.02, beam_width, iterations=iterations)
    profile = resample_swath(Swath(np.sort(across), depth[: across.size]), 0.05, spike_m=0.3, min_beams=2)
    if profile.is_empty:
        return
    assert_same_scan(model, profile, probes)


def test_too_few_returns_give_an_empty_scan():
    profile = resample_swath(Swath(np.linspace(-1.0, 1.0, MIN_RETURNS - 1), np.full(MIN_RETURNS - 1, 10.0)), 0.05)
    assert not profile.is_empty
    scan = EvidenceScan(FootprintLikelihood(CrossSection(0.5, 0.5), 0.02), profile)
    assert scan.is_empty and scan.peak() is None and scan.maximum() == 0.0
    assert not np.any(scan.values) and not np.any(scan.at(np.array([0.0, 0.5])))


@settings(max_examples=80, deadline=None)
@given(
    arrays(float, st.integers(0, 60), elements=st.floats(-30, 30)),
    arrays(float, st.integers(1, 60), elements=st.floats(-30, 30)),
    st.floats(-1.0, 60.0) | st.just(math.nan),
    st.floats(0.0, 5.0),
    st.floats(0.0, 0.05),
)
def test_the_compiled_windows_are_the_array_form(returns, centre, depth, reach, beam_width):
    x = np.sort(returns)
    centre = np.sort(centre)
    depths = np.full(centre.size, depth)
    low, high, sigma = evidence_kernel.candidate_windows(x, centre, depths, reach, beam_width, FWHM_PER_SIGMA)
    np.testing.assert_array_equal(low, np.searchsorted(x, centre - reach, side="left"))
    np.testing.assert_array_equal(high, np.searchsorted(x, centre + reach, side="right"))
    np.testing.assert_array_equal(bits(sigma), bits(footprint_sigma(centre, depths, beam_width)))


def returns_about_a_line(
    draw_rng: np.random.Generator, count: int, noise: float, kind: str
) -> tuple[np.ndarray, np.ndarray]:
    """Sorted returns over 20 m on a sloping seabed, with a pipe-sized bump or none, and noise of ``noise`` m."""
    x = np.sort(draw_rng.uniform(-10.0, 10.0, count))
    z = 30.0 + draw_rng.uniform(-0.3, 0.3) * x + noise * draw_rng.standard_normal(count)
    if kind == "bump":
        z -= 0.5 * np.clip(1.0 - (x / 0.4) ** 2, 0.0, None) ** 0.5
    elif kind == "flat":
        z = np.full(count, 30.0)
    return x, z


@settings(max_examples=80, deadline=None)
@given(
    st.integers(6, 120),
    st.sampled_from([0.0, 1e-9, 1e-4, 0.02, 0.3]),
    st.sampled_from(["line", "bump", "flat"]),
    st.floats(0.0, 0.3),
    st.floats(0.2, 1.5),
    st.integers(1, 4),
    st.floats(0.001, 0.1),
    st.integers(0, 2**32 - 1),
)
def test_the_line_through_a_window_bounds_its_seafloor_s_cost(count, noise, kind, beam_width, diameter, iterations,
                                                             sigma, seed):
    """:func:`~trackbench_sonar.evidence_kernel.line_bounds` is at least ``C_floor / sigma^2`` wherever the seafloor is fitted.

    Noise down to none (a seabed the line fits exactly, where the chain of bounds has no slack left but
    its margin for rounding and the ridge), a pipe in the window, one return or many per window, beams
    up to 17 deg wide (a mound as wide as the window: its column all but the constant's).
    """
    x, z = returns_about_a_line(np.random.default_rng(seed), count, noise, kind)
    model = FootprintLikelihood(CrossSection(diameter, diameter), sigma, beam_width, iterations=iterations)
    profile = resample_swath(Swath(x, z), 0.05, spike_window=0, min_beams=2)
    if profile.is_empty:
        return
    low, high, sigma_f = model.windows(profile)
    arrays_ = (profile.returns_across_m, profile.returns_depth_m, profile.across_m, sigma_f, low, high)
    floor = evidence_kernel.seabed_costs(*arrays_, model.settings)
    bounds = evidence_kernel.line_bounds(*arrays_[:3], low, high, model.settings)
    fitted = np.isfinite(floor)
    assert np.all(bounds[fitted] >= floor[fitted] / (sigma * sigma))
    evidence = model.candidates(profile).evidence
    assert np.all(bounds >= evidence)
