"""The Hough transform's fast formulations equal straightforward references (or the ones they replaced), bit for bit."""

from __future__ import annotations

import math

import cv2
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from trackbench_foresti.edges import EdgeMap
from trackbench_foresti.hough import (
    EdgePoints,
    _distinct,
    accumulate,
    find_peaks,
    fold,
    fold_angle,
    line_support,
    pooled_votes,
    refine_lines,
    stable_argsort,
    supporters,
)


def reference_points(edges: EdgeMap) -> dict[str, np.ndarray]:
    """:meth:`EdgePoints.of` by row-major scan, cosine test and a stable sort."""
    v, u = np.nonzero(edges.mask)
    width, height = edges.size
    phase = edges.phase.astype(np.float64)
    normal = fold(phase)
    order = np.argsort(normal, kind="stable")
    fields = {
        "u": u,
        "v": v,
        "x": u.astype(np.float64) - (width - 1) / 2.0,
        "y": (height - 1) / 2.0 - v.astype(np.float64),
        "modulus": edges.modulus.astype(np.float64),
        "normal": normal,
        "step": np.where(np.cos(phase - normal) >= 0.0, 1, -1),
    }
    return {name: values[order] for name, values in fields.items()}


def reference_votes(points: EdgePoints, alpha_step: float, rho_step: float, phase_tolerance: float) -> np.ndarray:
    """:func:`accumulate`'s votes, all points and angle bins at once."""
    n_alpha = round(math.pi / alpha_step)
    width, height = points.size
    half = math.ceil(math.hypot((width - 1) / 2.0, (height - 1) / 2.0) / rho_step) + 1
    n_rho = 2 * half + 1
    alphas = -math.pi / 2 + alpha_step * np.arange(n_alpha)
    reach = int(math.floor(phase_tolerance / alpha_step + 1e-9))
    centre = np.rint((points.normal + math.pi / 2) / alpha_step).astype(np.int64)
    bins = np.mod(centre[:, None] + np.arange(-reach, reach + 1)[None, :], n_alpha)
    rho = points.x[:, None] * np.cos(alphas)[bins] + points.y[:, None] * np.sin(alphas)[bins]
    cells = bins * n_rho + (np.rint(rho / rho_step).astype(np.int64) + half)
    return np.bincount(cells.ravel(), minlength=n_alpha * n_rho).reshape(n_alpha, n_rho).astype(np.int32)


def reference_pooled(votes: np.ndarray) -> np.ndarray:
    """:func:`pooled_votes` by concatenating the wrapped row."""
    both = np.concatenate([votes[1:], votes[:1, ::-1]], axis=0) + votes
    pooled = both.copy()
    pooled[:, :-1] += both[:, 1:]
    return pooled


def reference_peaks(votes: np.ndarray, min_votes: int, neighbourhood: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`find_peaks` by a grey dilation of the whole accumulator."""
    n_alpha = votes.shape[0]
    ranked = votes + np.arange(votes.size, dtype=np.float64).reshape(votes.shape) / (votes.size + 1)
    n = min(neighbourhood, n_alpha)
    padded = np.concatenate([ranked[n_alpha - n :, ::-1], ranked, ranked[:n, ::-1]], axis=0) if n else ranked
    kernel = np.ones((2 * n + 1, 2 * n + 1), np.uint8)
    dominant = cv2.dilate(padded, kernel, borderType=cv2.BORDER_CONSTANT, borderValue=-1.0)[n : n + n_alpha]
    k, j = np.nonzero((ranked >= dominant) & (votes >= min_votes))
    order = np.argsort(-ranked[k, j], kind="stable")
    return k[order], j[order]


def reference_fold(angle: np.ndarray | float) -> np.ndarray:
    """:func:`fold` by ``np.mod``."""
    return np.mod(np.asarray(angle, dtype=np.float64) + math.pi / 2, math.pi) - math.pi / 2


def reference_supporters(
    points: EdgePoints, alphas: np.ndarray, rhos: np.ndarray, tolerance: float, phase_tolerance: float
) -> list[np.ndarray]:
    """:func:`supporters` by index arrays over the window of normals and its copies a half turn up and down."""
    found = []
    for alpha, rho in zip(np.reshape(alphas, -1), np.reshape(rhos, -1), strict=True):
        if phase_tolerance >= math.pi / 2:
            near = np.arange(points.normal.size)
        else:
            low, high = alpha - phase_tolerance, alpha + phase_tolerance
            bounds = np.array([low, high, low + math.pi, high + math.pi, low - math.pi, high - math.pi])
            starts = np.searchsorted(points.normal, bounds[0::2], side="left")
            stops = np.searchsorted(points.normal, bounds[1::2], side="right")
            near = np.concatenate([np.arange(a, b) for a, b in zip(starts, stops, strict=True)])
        distance = np.abs(points.x[near] * math.cos(alpha) + points.y[near] * math.sin(alpha) - rho)
        found.append(near[distance <= tolerance])
    return found


def reference_refine(
    points: EdgePoints, alphas: np.ndarray, rhos: np.ndarray, capture: float, phase_tolerance: float
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`refine_lines` with ``np.mean`` and :func:`reference_fold`."""
    alphas, rhos = np.array(alphas, dtype=np.float64), np.array(rhos, dtype=np.float64)
    for i, near in enumerate(reference_supporters(points, alphas, rhos, capture, phase_tolerance)):
        if near.size < 2:
            continue
        x, y = points.x[near], points.y[near]
        dx, dy = x - x.mean(), y - y.mean()
        sxx, syy, sxy = float(dx @ dx), float(dy @ dy), float(dx @ dy)
        alphas[i] = reference_fold(0.5 * math.atan2(2.0 * sxy, sxx - syy) + math.pi / 2)
        rhos[i] = x.mean() * math.cos(alphas[i]) + y.mean() * math.sin(alphas[i])
    return alphas, rhos


def reference_moduli(
    points: EdgePoints, alphas: np.ndarray, rhos: np.ndarray, tolerance: float, phase_tolerance: float
):
    """The moduli of :func:`line_support`, by ``np.mean``."""
    return [
        points.modulus[near].mean() if near.size else 0.0
        for near in reference_supporters(points, alphas, rhos, tolerance, phase_tolerance)
    ]


def reference_distinct(alphas: np.ndarray, rhos: np.ndarray, alpha_reach: float, rho_reach: float) -> list[int]:
    """:func:`_distinct` against all kept lines at once, by :func:`reference_fold`."""
    kept: list[int] = []
    for i in range(alphas.size):
        if kept:
            others = np.array(kept)
            difference = alphas[i] - alphas[others]
            turn = reference_fold(difference)
            other_rhos = np.where(np.abs(difference - turn) > math.pi / 2, -rhos[others], rhos[others])
            if np.any((np.abs(turn) <= alpha_reach) & (np.abs(rhos[i] - other_rhos) <= rho_reach)):
                continue
        kept.append(i)
    return kept


@st.composite
def edge_maps(draw: st.DrawFn) -> EdgeMap:
    width, height = draw(st.integers(2, 24)), draw(st.integers(2, 24))
    mask = draw(hnp.arrays(bool, (height, width)))
    # Few distinct phases, many ties: the order within equal normals matters.
    levels = np.linspace(-math.pi, math.pi, 13, dtype=np.float32)
    phase = draw(hnp.arrays(np.float32, (height, width), elements=st.sampled_from(levels.tolist())))
    modulus = draw(hnp.arrays(np.float32, (height, width), elements=st.floats(0, 500, width=32)))
    return EdgeMap.from_images(mask, modulus, phase)


@settings(max_examples=200, deadline=None)
@given(hnp.arrays(np.float64, st.integers(0, 60), elements=st.sampled_from([-1.5, -0.0, 0.0, 0.25, 1.0, 3.0])))
def test_stable_argsort_is_numpys_stable_sort(values):
    assert np.array_equal(stable_argsort(values), np.argsort(values, kind="stable"))


@settings(max_examples=100, deadline=None)
@given(edge_maps())
def test_edge_points_equal_the_reference(edges):
    points = EdgePoints.of(edges)
    for name, expected in reference_points(edges).items():
        actual = getattr(points, name)
        assert actual.dtype == expected.dtype and np.array_equal(actual, expected), name


@settings(max_examples=100, deadline=None)
@given(
    edge_maps(),
    st.sampled_from([0.5, 1.0, 2.0, 45.0]),
    st.sampled_from([0.7, 1.0, 3.0]),
    st.floats(0.0, 90.0),
)
def test_accumulate_equals_the_reference(edges, step_deg, rho_step, tolerance_deg):
    points = EdgePoints.of(edges)
    alpha_step, phase_tolerance = math.radians(step_deg), math.radians(tolerance_deg)
    votes = accumulate(points, alpha_step, rho_step, phase_tolerance).votes
    expected = reference_votes(points, alpha_step, rho_step, phase_tolerance)
    assert votes.dtype == expected.dtype and np.array_equal(votes, expected)


def test_accumulate_equals_the_reference_on_many_edges():
    rng = np.random.default_rng(4)
    edges = EdgeMap.from_images(
        rng.random((120, 160)) < 0.3,
        rng.uniform(0, 300, (120, 160)).astype(np.float32),
        rng.uniform(-math.pi, math.pi, (120, 160)).astype(np.float32),
    )
    points = EdgePoints.of(edges)
    assert points.x.size > 3000
    votes = accumulate(points, math.radians(1.0), 1.0, math.radians(5.0)).votes
    assert np.array_equal(votes, reference_votes(points, math.radians(1.0), 1.0, math.radians(5.0)))


@settings(max_examples=300, deadline=None)
@given(
    hnp.arrays(np.int64, st.tuples(st.integers(1, 12), st.integers(1, 12)), elements=st.integers(0, 5)),
    st.integers(-1, 5),
    st.integers(0, 14),
)
def test_pooled_votes_and_peaks_equal_the_references(votes, min_votes, neighbourhood):
    assert np.array_equal(pooled_votes(votes), reference_pooled(votes))
    k, j = find_peaks(votes, min_votes, neighbourhood)
    expected_k, expected_j = reference_peaks(votes, min_votes, neighbourhood)
    assert np.array_equal(k, expected_k) and np.array_equal(j, expected_j)
    assert k.dtype == expected_k.dtype and j.dtype == expected_j.dtype


angles = st.floats(-1e6, 1e6, allow_subnormal=True)


@settings(max_examples=300, deadline=None)
@given(hnp.arrays(np.float64, st.integers(0, 40), elements=angles | st.sampled_from([-math.pi / 2, math.pi / 2])))
def test_fold_and_fold_angle_equal_np_mod(values):
    assert np.array_equal(fold(values), reference_fold(values))
    for value in values.tolist():
        assert fold_angle(value) == reference_fold(value)


lines = st.lists(st.tuples(st.floats(-math.pi / 2, math.pi / 2, exclude_max=True), st.floats(-20.0, 20.0)), max_size=6)


@settings(max_examples=200, deadline=None)
@given(edge_maps(), lines, st.floats(0.0, 6.0), st.floats(0.0, math.pi / 2) | st.just(math.pi / 2))
def test_supporters_refits_and_moduli_equal_the_references(edges, drawn, tolerance, phase_tolerance):
    points = EdgePoints.of(edges)
    alphas, rhos = np.array([a for a, _ in drawn], dtype=np.float64), np.array([r for _, r in drawn], dtype=np.float64)
    found = supporters(points, alphas, rhos, tolerance, phase_tolerance)
    expected = reference_supporters(points, alphas, rhos, tolerance, phase_tolerance)
    assert len(found) == len(expected)
    for near, reference in zip(found, expected, strict=True):
        assert near.dtype == reference.dtype and np.array_equal(near, reference)
    refined = refine_lines(points, alphas, rhos, tolerance, phase_tolerance)
    for actual, reference in zip(refined, reference_refine(points, alphas, rhos, tolerance, phase_tolerance)):
        assert np.array_equal(actual, reference)
    moduli = line_support(points, alphas, rhos, tolerance, phase_tolerance)[0]
    assert np.array_equal(moduli, reference_moduli(points, alphas, rhos, tolerance, phase_tolerance))


@settings(max_examples=300, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.sampled_from([-math.pi / 2, -1.5, -0.01, 0.0, 0.01, 1.55, 1.5707]) | st.floats(-math.pi / 2, 1.5707),
            st.sampled_from([-3.0, -1.0, 0.0, 1.0, 2.5]) | st.floats(-5.0, 5.0),
        ),
        max_size=10,
    ),
    st.sampled_from([0.0, 0.01, 0.035]),
    st.sampled_from([0.0, 1.0, 2.0]),
)
def test_distinct_equals_the_reference(drawn, alpha_reach, rho_reach):
    alphas, rhos = np.array([a for a, _ in drawn], dtype=np.float64), np.array([r for _, r in drawn], dtype=np.float64)
    assert _distinct(alphas, rhos, alpha_reach, rho_reach) == reference_distinct(alphas, rhos, alpha_reach, rho_reach)
