"""The compiled evidence against its array form (seeds/003, eq. 1 as evidence).

:func:`reference_candidates` is the evidence as NumPy arrays of shape
(candidates, returns), the form the plugin computed it in before the
compiled kernel (:mod:`trackbench_sonar.evidence_kernel`).  The two differ
only in the order of their sums and the last bits of ``exp``, ``log1p``,
the normal distribution and the 4 x 4 solve, so they agree to
:data:`RELATIVE` of the larger of the evidence and 1 (the evidence is a
sum of squared residuals in noise units, some hundreds at a pipe: 1e-9 of
it is far below anything a scan's maximum or a particle's weight can
resolve; measured on the pings of the sonar, sonar-dev and sonar-test
suites, the largest difference is about 1e-13).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_sonar.cross_section import CrossSection
from trackbench_sonar.evidence import MIN_RETURNS, FootprintLikelihood
from trackbench_sonar.footprint import SeenCrossSection, footprint_sigma
from trackbench_sonar.profile import Profile, resample_swath

from benchmark.modalities.sonar.model import Swath

RELATIVE = 1e-9
"""Largest difference between the kernel's evidence and the array form's, relative to max(evidence, 1)."""


def _solve(design: np.ndarray, weights: np.ndarray, target: np.ndarray) -> np.ndarray:
    weighted = design * weights[:, None, :]
    normal = weighted @ np.swapaxes(design, 1, 2)
    normal += np.eye(design.shape[1])[None] * 1e-12 * np.maximum(np.trace(normal, axis1=1, axis2=2), 1.0)[:, None, None]
    right = weighted @ target[:, :, None]
    return np.linalg.solve(normal, right)[:, :, 0]


def _robust_cost(model, design, mask, target):
    k = model.robust_sigmas * model.sigma_m
    weights = mask
    for _ in range(model.iterations):
        coefficients = _solve(design, weights, target)
        residual = target - np.einsum("kp,kpw->kw", coefficients, design)
        weights = mask / (1.0 + (residual / k) ** 2)
    cost = np.sum(mask * k * k * np.log1p((residual / k) ** 2), axis=1) / model.sigma_m**2
    return cost, coefficients[:, -1]


def reference_candidates(model: FootprintLikelihood, profile: Profile) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Evidence, pedestal and scored of every candidate, as arrays over (candidates, returns)."""
    centre = profile.across_m
    x, z = profile.returns_across_m, profile.returns_depth_m
    seen = SeenCrossSection(model.section)
    a = model.section.half_width_m
    reach = a + model.seabed_widths * model.section.major_m
    low = np.searchsorted(x, centre - reach, side="left")
    high = np.searchsorted(x, centre + reach, side="right")
    returns = high - low
    width = max(int(returns.max()), 1)
    index = low[:, None] + np.arange(width)[None, :]
    inside = index < high[:, None]
    index = np.minimum(index, x.size - 1)
    u = x[index] - centre[:, None]
    depth = z[index]
    sigma_f = footprint_sigma(centre, profile.depth_m, model.beam_width)[:, None]
    relief = model.relief_widths * seen.seen_half_width(sigma_f)
    seabed = np.stack([np.ones_like(u), u / reach, np.exp(-0.5 * (u / relief) ** 2)], axis=1)
    arc = seen.arc(u, sigma_f)
    mask = inside.astype(float)
    floor_cost, _ = _robust_cost(model, seabed, mask, depth)
    pipe = np.concatenate([seabed, -seen.pedestal(u, sigma_f)[:, None, :]], axis=1)
    pipe_cost, pedestal = _robust_cost(model, pipe, mask, depth + arc)
    negative = ~(pedestal >= 0.0)
    if np.any(negative):
        rows = np.flatnonzero(negative)
        pipe_cost[rows], _ = _robust_cost(model, seabed[rows], mask[rows], depth[rows] + arc[rows])
        pedestal[rows] = 0.0
    scored = (returns >= MIN_RETURNS) & np.any(inside & (u <= -a), axis=1) & np.any(inside & (u >= a), axis=1)
    evidence = np.where(scored, np.maximum(floor_cost - pipe_cost, 0.0), 0.0)
    evidence = np.where(np.isfinite(evidence), evidence, 0.0)
    return evidence, np.where(scored, pedestal, np.nan), scored


def assert_agrees(model: FootprintLikelihood, profile: Profile, pedestal_m: float = math.inf) -> None:
    """The evidence within :data:`RELATIVE`, the pedestal within ``pedestal_m`` (a fitted coefficient)."""
    found = model.candidates(profile)
    evidence, pedestal, scored = reference_candidates(model, profile)
    np.testing.assert_array_equal(found.scored, scored)
    scale = max(float(evidence.max(initial=0.0)), 1.0)
    np.testing.assert_allclose(found.evidence, evidence, rtol=0.0, atol=RELATIVE * scale)
    np.testing.assert_array_equal(np.isnan(found.pedestal_m), np.isnan(pedestal))
    assert np.all(found.pedestal_m[scored] >= 0.0)
    np.testing.assert_allclose(found.pedestal_m[scored], pedestal[scored], rtol=0.0, atol=pedestal_m)


@pytest.mark.parametrize(("diameter", "width_deg", "burial"), [(0.6, 0.5, 0.0), (0.5, 2.5, 0.3), (1.1, 1.5, 0.6)])
def test_the_kernel_agrees_with_the_array_form_on_pipes(swaths, diameter, width_deg, burial):
    swath = swaths.cast(lambda x: 0.05 * x, [(1.5, diameter, burial)], n_beams=200, swath_deg=120.0, altitude=12.0,
                        beam_width_deg=width_deg, noise=0.02, seed=3)  # fmt: skip
    profile = resample_swath(swath, 0.05, spike_m=0.3)
    model = FootprintLikelihood(CrossSection(diameter, diameter), 0.02, math.radians(width_deg))
    assert_agrees(model, profile, pedestal_m=1e-9)
    assert model.candidates(profile).evidence.max() > 1.0


@settings(max_examples=60, deadline=None)
@given(
    arrays(float, st.integers(MIN_RETURNS, 80), elements=st.floats(-30, 30)),
    arrays(float, 80, elements=st.floats(1.0, 60.0)),
    st.floats(0.0, 0.05),
    st.floats(0.2, 1.5),
    st.integers(1, 4),
)
def test_the_kernel_agrees_with_the_array_form_on_arbitrary_returns(across, depth, beam_width, diameter, iterations):
    model = FootprintLikelihood(CrossSection(diameter, diameter), 0.02, beam_width, iterations=iterations)
    profile = resample_swath(Swath(np.sort(across), depth[: across.size]), 0.05, spike_m=0.3)
    if profile.is_empty:
        return
    assert_agrees(model, profile)
