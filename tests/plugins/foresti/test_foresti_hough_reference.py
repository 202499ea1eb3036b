"""The Hough transform's fast formulations equal straightforward references, bit for bit."""

from __future__ import annotations

import math

import cv2
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from trackbench_foresti.edges import EdgeMap
from trackbench_foresti.hough import EdgePoints, accumulate, find_peaks, fold, pooled_votes, stable_argsort


def reference_points(edges: EdgeMap) -> dict[str, np.ndarray]:
    """:meth:`EdgePoints.of` by row-major scan, cosine test and a stable sort."""
    v, u = np.nonzero(edges.mask)
    width, height = edges.size
    phase = edges.phase[v, u].astype(np.float64)
    normal = fold(phase)
    order = np.argsort(normal, kind="stable")
    fields = {
        "u": u,
        "v": v,
        "x": u.astype(np.float64) - (width - 1) / 2.0,
        "y": (height - 1) / 2.0 - v.astype(np.float64),
        "modulus": edges.modulus[v, u].astype(np.float64),
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
    return np.bincount(cells.ravel(), minlength=n_alpha * n_rho).reshape(n_alpha, n_rho)


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


@st.composite
def edge_maps(draw: st.DrawFn) -> EdgeMap:
    width, height = draw(st.integers(2, 24)), draw(st.integers(2, 24))
    mask = draw(hnp.arrays(bool, (height, width)))
    # Few distinct phases, many ties: the order within equal normals matters.
    levels = np.linspace(-math.pi, math.pi, 13, dtype=np.float32)
    phase = draw(hnp.arrays(np.float32, (height, width), elements=st.sampled_from(levels.tolist())))
    modulus = draw(hnp.arrays(np.float32, (height, width), elements=st.floats(0, 500, width=32)))
    return EdgeMap(mask, modulus, phase)


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


def test_accumulate_equals_the_reference_over_several_blocks():
    rng = np.random.default_rng(4)
    edges = EdgeMap(
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
