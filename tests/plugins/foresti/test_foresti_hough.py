"""Tests of the Hough transform with modulus and domain (seeds/004, section IV, Fig. 7)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from trackbench_foresti.edges import EdgeMap, canny_edges
from trackbench_foresti.features import FeatureParams
from trackbench_foresti.hough import EdgePoints, accumulate, find_peaks, hough_lines, refine_lines

from benchmark.modalities.camera.geometry import Line, cable_borders, chord_midpoint, orientation_difference
from benchmark.modalities.camera.model import CableState

ODD = (101, 81)  # an odd size puts the model origin on a pixel centre
STEP = math.radians(1.0)
DEFAULTS = FeatureParams(blur_sigma_px=1.5, phase_tolerance_deg=5.0)
"""The settings the drawn images below were made for (the ``-paper`` variants' edges)."""


def edge_map(u, v, phase, size=ODD, modulus=100.0) -> EdgeMap:
    """An edge map with edges at pixels ``(u, v)`` of the given phase(s) and modulus (moduli)."""
    width, height = size
    mask = np.zeros((height, width), bool)
    phases = np.zeros((height, width), np.float32)
    moduli = np.zeros((height, width), np.float32)
    mask[v, u] = True
    phases[v, u] = phase
    moduli[v, u] = modulus
    return EdgeMap.from_images(mask, moduli, phases)


def lines_of(edges: EdgeMap, **overrides):
    settings = dict(
        alpha_step=STEP,
        rho_step=1.0,
        phase_tolerance=math.radians(DEFAULTS.phase_tolerance_deg),
        min_votes=20,
        neighbourhood=2,
        tolerance=1.5,
    )
    settings.update(overrides)
    return hough_lines(edges, **settings)


def test_a_vertical_line_votes_into_its_bin_and_the_bins_its_phase_allows():
    rows = np.arange(ODD[1])
    edges = edge_map(np.full(rows.size, 70), rows, 0.0)  # x = 70 - 50 = 20
    accumulator = accumulate(EdgePoints.of(edges), STEP, 1.0, math.radians(5.0))
    k = int(np.argmin(np.abs(accumulator.alphas)))
    j = int(np.argmin(np.abs(accumulator.rhos - 20.0)))
    assert accumulator.votes[k, j] == rows.size
    assert accumulator.votes.sum() == rows.size * 11  # bins -5 .. +5 deg
    assert accumulator.votes[np.abs(accumulator.alphas) > math.radians(5.5)].sum() == 0
    assert np.allclose(accumulator.rhos, -accumulator.rhos[::-1])


def test_edges_do_not_vote_for_lines_across_their_gradient():
    rows = np.arange(ODD[1])
    edges = edge_map(np.full(rows.size, 70), rows, math.pi / 2)  # collinear, but gradients along the line
    accumulator = accumulate(EdgePoints.of(edges), STEP, 1.0, math.radians(5.0))
    assert accumulator.votes[np.abs(accumulator.alphas) < math.radians(60.0)].sum() == 0
    assert lines_of(edges) == []


def test_a_plateau_gives_one_peak_and_the_angle_axis_wraps():
    votes = np.zeros((180, 41), np.int64)
    votes[90, 10:12] = 50  # a plateau of two equal bins
    votes[0, 30] = 40  # near alpha = -90 deg ...
    votes[179, 40 - 30] = 45  # ... and its neighbour across the wrap (rho flipped), stronger
    k, j = find_peaks(votes, 30, 2)
    assert [(int(a), int(b)) for a, b in zip(k, j, strict=True)] in ([(90, 11), (179, 10)], [(90, 10), (179, 10)])


def test_a_horizontal_line_is_found_once_with_a_column_domain():
    columns = np.arange(10, 91)
    edges = edge_map(columns, np.full(columns.size, 30), math.pi / 2)  # y = 40 - 30 = 10, brighter above
    found = lines_of(edges)
    assert len(found) == 1
    line = found[0]
    assert not line.by_rows and line.domain.size == ODD[0]
    assert np.array_equal(np.flatnonzero(line.domain), columns)
    assert math.isclose(abs(line.alpha), math.pi / 2, abs_tol=1e-6) and math.isclose(abs(line.rho), 10.0, abs_tol=1e-6)


def test_domain_modulus_and_parameters_of_a_segment():
    rows = np.arange(20, 61)
    moduli = np.linspace(50.0, 150.0, rows.size)
    edges = edge_map(np.full(rows.size, 30), rows, math.pi, modulus=moduli)  # x = -20, darker right
    found = lines_of(edges)
    assert len(found) == 1
    line = found[0]
    assert line.by_rows and line.domain.size == ODD[1]
    assert np.array_equal(np.flatnonzero(line.domain), rows)
    assert math.isclose(line.modulus, float(moduli.astype(np.float32).mean()), rel_tol=1e-6)
    assert math.isclose(line.alpha, 0.0, abs_tol=1e-9) and math.isclose(line.rho, -20.0, abs_tol=1e-9)


def test_refit_recovers_a_line_between_angle_bins():
    alpha, rho = math.radians(19.5), 12.3
    t = np.arange(-150, 151)
    x = rho * math.cos(alpha) - t * math.sin(alpha)
    y = rho * math.sin(alpha) + t * math.cos(alpha)
    size = (321, 241)
    u = np.rint(x + (size[0] - 1) / 2).astype(int)
    v = np.rint((size[1] - 1) / 2 - y).astype(int)
    inside = (u >= 0) & (u < size[0]) & (v >= 0) & (v < size[1])
    points = EdgePoints.of(edge_map(u[inside], v[inside], alpha, size))
    fitted_alpha, fitted_rho = refine_lines(points, np.array([math.radians(20.0)]), np.array([13.0]), 3.0, 0.1)
    assert abs(math.degrees(fitted_alpha[0]) - 19.5) < 0.2 and abs(fitted_rho[0] - rho) < 0.3


@pytest.mark.parametrize(
    "state",
    [
        CableState(0.0, 0.0, 40.0, math.radians(2.0)),
        CableState(-50.0, 0.3, 30.0, 0.04),  # the right border at 19.5 deg falls between angle bins
        CableState(45.0, -0.4, 50.0, 0.0),
    ],
)
def test_the_borders_of_a_drawn_pipe_are_found(draw, state):
    size = draw.SIZE
    image = draw.pipe(state, seed=3)
    edges = canny_edges(image, DEFAULTS.blur_sigma_px, DEFAULTS.canny_low, DEFAULTS.canny_high)
    found = [Line.from_normal(line.rho, line.alpha) for line in lines_of(edges, min_votes=DEFAULTS.min_votes)]
    for border in cable_borders(state):
        target = np.array(chord_midpoint(border, size))
        assert any(
            np.linalg.norm(np.array(chord_midpoint(line, size)) - target) < 1.5
            and orientation_difference(line, border) < math.radians(1.0)
            for line in found
        ), f"border {border} of {state} not among {found}"


@pytest.mark.parametrize("contrast, left, right", [(-50.0, -1, 1), (50.0, 1, -1)])
def test_the_borders_of_a_band_step_opposite_ways(draw, contrast, left, right):
    """A dark band: the grey level falls across its left border and rises across its right one."""
    state = CableState(0.0, 0.0, 40.0, 0.0)
    edges = canny_edges(draw.pipe(state, contrast=contrast, seed=5), DEFAULTS.blur_sigma_px, 20.0, 60.0)
    found = sorted(lines_of(edges, min_votes=DEFAULTS.min_votes), key=lambda line: line.rho)
    assert len(found) == 2 and all(abs(abs(line.rho) - 20.0) < 1.5 for line in found)
    assert [line.polarity for line in found] == [left, right]


def test_bad_resolutions_are_refused():
    points = EdgePoints.of(edge_map([1], [1], 0.0))
    with pytest.raises(ValueError, match="alpha_step"):
        accumulate(points, math.radians(0.7), 1.0, 0.1)
    with pytest.raises(ValueError, match="rho_step"):
        accumulate(points, STEP, 0.0, 0.1)
    with pytest.raises(ValueError, match="neighbourhood"):
        find_peaks(np.zeros((4, 4), np.int64), 1, -1)
