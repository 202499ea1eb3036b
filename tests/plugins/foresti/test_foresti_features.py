"""Tests of the feature extraction facade (seeds/004, section IV, Fig. 6)."""

from __future__ import annotations

import math

import numpy as np
import pydantic
import pytest
from trackbench_foresti.features import CandidateLine, FeatureExtractor, FeatureParams
from trackbench_foresti.grouping import GroupingParams

from benchmark.errors import ParameterError
from benchmark.modalities.camera.geometry import Line, cable_borders, model_to_pixel, score_line_pair
from benchmark.modalities.camera.model import CableState
from benchmark.model import Outcome
from benchmark.parameters import make_params

SIZE = (320, 240)
STATES = [
    CableState(0.0, 0.0, 40.0, math.radians(2.0)),
    CableState(-40.0, math.radians(12.0), 30.0, math.radians(1.5)),
    CableState(55.0, math.radians(-20.0), 48.0, math.radians(2.5)),
]


def truth_abscissae(line: Line) -> tuple[float, float]:
    """Pixel columns where a model line crosses rows 0 and H-1."""
    out = []
    for v in (0.0, SIZE[1] - 1.0):
        y = (SIZE[1] - 1) / 2.0 - v
        s = (y - line.y0) / line.dy
        out.append(model_to_pixel(line.x0 + s * line.dx, y, SIZE)[0])
    return out[0], out[1]


@pytest.fixture(scope="module")
def extractor() -> FeatureExtractor:
    return FeatureExtractor()


def test_candidate_convention_is_the_model_normal_form():
    vertical = CandidateLine(0.0, 10.0, 1.0, np.ones(240, bool), 1.0, 1.0, 1.0, 1.0)
    assert vertical.abscissae(SIZE) == (169.5, 169.5)
    line = vertical.line(SIZE)
    assert math.isclose(line.orientation, math.pi / 2) and math.isclose(line.nearest_point_to_origin()[0], 10.0)
    # alpha > 0 leans the top to the left, like the cable angle of conventions.md; rho is then the foot distance.
    tilted = CandidateLine(math.radians(10.0), 5.0, 1.0, np.ones(240, bool), 1.0, 1.0, 1.0, 1.0)
    top, bottom = tilted.abscissae(SIZE)
    assert top < bottom
    expected = truth_abscissae(Line.from_normal(5.0, math.radians(10.0)))
    assert np.allclose((top, bottom), expected)
    assert tilted.by_rows and not CandidateLine(math.radians(-60.0), 0.0, 1.0, np.ones(320, bool), 1, 1, 1, 1).by_rows
    with pytest.raises(ValueError, match="horizontal"):
        CandidateLine(-math.pi / 2, 0.0, 1.0, np.ones(320, bool), 1, 1, 1, 1).abscissae(SIZE)
    with pytest.raises(ValueError, match="size"):
        vertical.abscissae((320,))


@pytest.mark.parametrize("state", STATES)
@pytest.mark.parametrize("contrast", [-50.0, 45.0], ids=["dark", "bright"])
def test_the_borders_of_a_drawn_pipe_are_measured(draw, extractor, state, contrast):
    image = draw.pipe(state, contrast=contrast, seed=7)
    measured = extractor.measure(image)
    assert measured is not None
    left, right = measured
    truth = cable_borders(state)
    assert score_line_pair((left.line(SIZE), right.line(SIZE)), truth, SIZE) is Outcome.CORRECT
    for found, border in zip((left, right), truth, strict=True):
        assert np.allclose(found.abscissae(SIZE), truth_abscissae(border), atol=1.5)


def test_candidates_are_filtered_normalised_and_sorted(draw, extractor):
    candidates = extractor.candidates(draw.pipe(STATES[1], seed=2))
    assert len(candidates) >= 2
    assert all(c.pl > 0.5 and c.pr > 0.65 for c in candidates)
    assert max(c.pf for c in candidates) == 1.0
    assert [c.reliability for c in candidates] == sorted((c.reliability for c in candidates), reverse=True)
    for c in candidates:
        assert math.isclose(c.reliability, 0.5 * c.pl + 0.35 * c.pr + 0.15 * c.pf)
        assert c.domain.dtype == bool and c.domain.size == (SIZE[1] if c.by_rows else SIZE[0])


def test_a_prediction_selects_and_gates(draw, extractor):
    state = STATES[1]
    image = draw.pipe(state, seed=4)
    (i1, i3), (i2, i4) = (truth_abscissae(border) for border in cable_borders(state))
    measured = extractor.measure(image, (i1 + 3.0, i2 - 2.0, i3 - 4.0, i4 + 1.0))
    assert measured is not None
    assert score_line_pair(tuple(c.line(SIZE) for c in measured), cable_borders(state), SIZE) is Outcome.CORRECT
    assert extractor.measure(image, (i1 + 90.0, i2 + 90.0, i3 + 90.0, i4 + 90.0)) is None


def test_a_blank_image_gives_nothing(extractor):
    blank = np.full((240, 320), 100, np.uint8)
    assert extractor.candidates(blank) == []
    assert extractor.measure(blank) is None
    assert extractor.measure(blank, (100.0, 140.0, 90.0, 150.0)) is None


@pytest.mark.parametrize(
    "image",
    [np.zeros((240, 320), np.float64), np.zeros((240, 320, 3), np.uint8), np.zeros(320, np.uint8), None],
    ids=["float", "colour", "1-D", "none"],
)
def test_bad_images_are_refused(extractor, image):
    with pytest.raises(ValueError, match="image"):
        extractor.measure(image)
    with pytest.raises(ValueError, match="image"):
        extractor.candidates(image)


def test_bad_predictions_are_refused(draw, extractor):
    image = draw.pipe(STATES[0], seed=1)
    with pytest.raises(ValueError, match="predicted"):
        extractor.measure(image, (math.nan, 150.0, 130.0, 190.0))
    with pytest.raises(ValueError, match="predicted"):
        extractor.measure(image, (140.0, 150.0))


@pytest.mark.parametrize(
    ("overrides", "name"),
    [
        ({"weight_pl": 0.5, "weight_pr": 0.5, "weight_pf": 0.5}, "weight_pl"),
        ({"weight_pf": -0.1}, "weight_pf"),
        ({"canny_low": 80.0, "canny_high": 60.0}, "canny_low"),
        ({"canny_low": -1.0}, "canny_low"),
        ({"blur_sigma_px": -0.5}, "blur_sigma_px"),
        ({"min_votes": 2.5}, "min_votes"),
        ({"max_gap": -1}, "max_gap"),
        ({"min_run": -1}, "min_run"),
        ({"neighbourhood": -1}, "neighbourhood"),
        ({"min_pl": 1.5}, "min_pl"),
        ({"min_pr": -0.1}, "min_pr"),
        ({"rho_step_px": 0.0}, "rho_step_px"),
        ({"alpha_step_deg": 0.0}, "alpha_step_deg"),
        ({"alpha_step_deg": 0.7}, "alpha_step_deg"),
        ({"alpha_step_deg": 60.0}, "alpha_step_deg"),
        ({"phase_tolerance_deg": 95.0}, "phase_tolerance_deg"),
        ({"domain_tolerance_px": math.nan}, "domain_tolerance_px"),
        ({"max_divergence_deg": -0.1}, "max_divergence_deg"),
        ({"max_divergence_deg": 45.0}, "max_divergence_deg"),
        ({"min_pair_reliability": 1.5}, "min_pair_reliability"),
        ({"gate_px": 0.0}, "gate_px"),
        ({"meet_ratio": 0.0}, "meet_ratio"),
        ({"canny_rule": "otsu"}, "canny_rule"),
        ({"canny_percentile": 100.5}, "canny_percentile"),
        ({"reference_rows": -240.0}, "reference_rows"),
        ({"nest_slack": 1.5}, "nest_slack"),
        ({"nest_max_angle_deg": -1.0}, "nest_max_angle_deg"),
    ],
)
def test_bad_parameters_are_refused(overrides, name):
    with pytest.raises(pydantic.ValidationError, match=name):
        FeatureParams(**overrides)


def test_the_flat_parameters_give_the_submodules_theirs_in_rad():
    params = FeatureParams(alpha_step_deg=2.0, phase_tolerance_deg=8.0, max_divergence_deg=3.0, gate_px=25.0)
    assert params.weights == (0.5, 0.35, 0.15)
    assert params.grouping == GroupingParams(max_divergence=math.radians(3.0), gate_px=25.0, nest_slack=0.2)
    assert FeatureParams(nest_slack=0.0, nest_max_angle_deg=2.0).grouping == GroupingParams()
    hough = params.hough
    assert math.isclose(hough["alpha_step"], math.radians(2.0))
    assert math.isclose(hough["phase_tolerance"], math.radians(8.0))
    assert (hough["rho_step"], hough["tolerance"], hough["min_votes"]) == (1.0, 2.0, 60)


def test_parameters_reach_the_grouping(draw):
    image = draw.pipe(STATES[0], seed=5)
    (i1, i3), (i2, i4) = (truth_abscissae(border) for border in cable_borders(STATES[0]))
    off = (i1 + 30.0, i2 + 30.0, i3 + 30.0, i4 + 30.0)
    assert FeatureExtractor().measure(image, off) is not None
    assert FeatureExtractor(FeatureParams(gate_px=10.0)).measure(image, off) is None


def test_every_parameter_can_be_set_from_the_command_line():
    params = make_params(FeatureParams, "foresti", {"gate_px": "30", "alpha_step_deg": "2", "max_gap": "4"})
    assert (params.gate_px, params.alpha_step_deg, params.max_gap) == (30.0, 2.0, 4)
    assert params.grouping.gate_px == 30.0
    with pytest.raises(ParameterError, match="canny_low"):
        make_params(FeatureParams, "foresti", {"canny_low": "-1"})
