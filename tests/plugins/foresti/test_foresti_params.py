"""The Foresti trackers' parameters: pixel counts relative to the frame, the ``-paper`` variants."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from trackbench_foresti import PAPER, trackbench_register_trackers
from trackbench_foresti.baseline import ForestiLinesTracker
from trackbench_foresti.features import FeatureExtractor
from trackbench_foresti.params import FeatureParams, ForestiParams
from trackbench_foresti.tracker import ForestiEkfTracker

from benchmark.modalities.camera.geometry import cable_borders, score_line_pair
from benchmark.modalities.camera.model import CableState
from benchmark.modalities.camera.modality import CAMERA
from benchmark.model import Outcome
from benchmark.registry import Registry


@given(st.integers(1, 4000), st.integers(0, 500))
def test_pixel_counts_scale_with_the_frame_height(height, count):
    params = FeatureParams()
    assert params.pixel_scale(height) == height / 240.0
    assert params.scaled_count(count, height) == round(count * height / 240.0)
    assert params.scaled_count(count, 240) == count
    assert FeatureParams(reference_rows=0.0).scaled_count(count, height) == count


def test_a_frame_without_rows_is_refused():
    with pytest.raises(ValueError, match="height"):
        FeatureParams().pixel_scale(0)


def test_a_pipe_drawn_twice_as_large_is_found_with_counts_twice_as_large(draw):
    """The same scene at 640 x 480: every border is twice as long, min_votes doubles, the pair is found."""
    state = CableState(-30.0, math.radians(6.0), 70.0, math.radians(1.5))
    image = draw.pipe(state, contrast=-40.0, seed=11, size=(640, 480))
    extractor = FeatureExtractor()
    assert extractor._hough_for(480)["min_votes"] == 120 and extractor._hough_for(240)["min_votes"] == 60
    left, right = extractor.measure(image)
    outcome = score_line_pair((left.line((640, 480)), right.line((640, 480))), cable_borders(state), (640, 480))
    assert outcome is Outcome.CORRECT


def test_the_paper_variants_restore_the_fixed_image_thresholds():
    paper = FeatureParams(**PAPER)
    assert (paper.canny_rule, paper.blur_sigma_px, paper.phase_tolerance_deg, paper.domain_tolerance_px) == (
        "fixed",
        1.5,
        5.0,
        1.5,
    )
    assert paper.reference_rows == 0 and paper.nest_slack == 0
    assert ForestiParams(**PAPER).border_model == ForestiParams().border_model == "plane"
    # The filter keeps the narrower edge windows by default; the extractor alone the wider ones.
    assert (ForestiParams().phase_tolerance_deg, FeatureParams().phase_tolerance_deg) == (5.0, 8.0)


def test_the_plugin_registers_each_tracker_with_its_paper_variant():
    registry = Registry()
    registry.add_modality(CAMERA)
    trackbench_register_trackers(registry)
    names = set(registry.trackers)
    assert {"foresti_ekf", "foresti_lines", "foresti_ekf-paper", "foresti_lines-paper"} <= names
    lines = registry.trackers["foresti_lines-paper"]
    ekf = registry.trackers["foresti_ekf-paper"]
    assert lines.tracker_class is ForestiLinesTracker and ekf.tracker_class is ForestiEkfTracker
    assert lines.params == FeatureParams(**PAPER) and ekf.params == ForestiParams(**PAPER)
    assert np.isclose(registry.trackers["foresti_lines"].params.canny_percentile, 95.0)
