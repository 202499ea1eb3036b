"""Tests of the Hough baseline tracker on drawn cable images."""

from __future__ import annotations

import math

import numpy as np
import pytest
from trackbench_hough import VARIANTS
from trackbench_hough.tracker import HoughTracker

from benchmark.errors import DataError, ParameterError
from benchmark.modalities.camera.geometry import cable_borders, score_line_pair
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, CameraTruth
from benchmark.model import Frame, Outcome, SequenceInfo

SIZE = (320, 240)
INFO = SequenceInfo("drawn", "camera", frame_size=SIZE)


def fresh(info: SequenceInfo = INFO, **overrides) -> HoughTracker:
    tracker = HoughTracker(HoughTracker.make_params(overrides))
    tracker.reset(info, np.random.default_rng(0))
    return tracker


def paper(info: SequenceInfo = INFO) -> HoughTracker:
    return fresh(info, **VARIANTS["hough-paper"])


def tracking(tracker: HoughTracker) -> bool:
    """True while the tracker limits the Hough parameter space to a window around a previous result."""
    return tracker._window is not None


def outcome(estimate: CableState | None, truth: CableState, size: tuple[int, int] = SIZE) -> Outcome:
    return score_line_pair(None if estimate is None else cable_borders(estimate), cable_borders(truth), size)


@pytest.mark.parametrize("contrast", [60.0, -60.0], ids=["bright", "dark"])
def test_finds_the_drawn_cable_for_both_polarities(drawing, contrast):
    truth = CableState(12.0, math.radians(8.0), 34.0, math.radians(1.5))
    estimate = fresh().step(Frame(0, drawing.draw_cable(truth, contrast=contrast)))
    assert outcome(estimate, truth) is Outcome.CORRECT


def test_finds_most_random_cables(drawing):
    # A baseline, not an oracle: the Hough accumulator's 1 degree bins split the
    # votes of a slightly skewed border, so an occasional miss is expected.
    rng = np.random.default_rng(2024)
    results = []
    for _ in range(40):
        truth = CableState(
            rng.uniform(-60.0, 60.0), math.radians(rng.uniform(-30.0, 30.0)), rng.uniform(15.0, 60.0),
            math.radians(rng.uniform(0.0, 1.5)),
        )
        contrast = -50.0 if rng.random() < 0.5 else 50.0
        image = drawing.draw_cable(truth, contrast=contrast, seed=int(rng.integers(2**16)))
        results.append(outcome(fresh().step(Frame(0, image)), truth))
    assert results.count(Outcome.CORRECT) >= 36
    assert Outcome.FALSE not in results


def test_returns_none_on_blank_and_noise_only_images(drawing):
    tracker = fresh()
    assert tracker.step(Frame(0, np.full(SIZE[::-1], 128, np.uint8))) is None
    for seed in range(3):
        assert tracker.step(Frame(1 + seed, drawing.to_uint8(drawing.background(SIZE, seed)))) is None
    assert not tracking(tracker)


def test_tracking_window_ignores_a_far_pair_until_enough_misses(drawing):
    cable = CableState(-70.0, math.radians(5.0), 30.0, 0.0)
    distractor = CableState(75.0, math.radians(-12.0), 40.0, 0.0)
    tracker = fresh(max_misses=3)
    assert outcome(tracker.step(Frame(0, drawing.draw_cable(cable))), cable) is Outcome.CORRECT
    assert tracking(tracker)
    # The distractor alone is found at once by a tracker that searches everywhere ...
    assert outcome(fresh().step(Frame(0, drawing.draw_cable(distractor, seed=1))), distractor) is Outcome.CORRECT
    # ... but a tracking one misses it while the window is limited, then widens.
    for index in range(1, 4):
        assert tracker.step(Frame(index, drawing.draw_cable(distractor, seed=index))) is None
    assert not tracking(tracker)
    assert outcome(tracker.step(Frame(4, drawing.draw_cable(distractor, seed=4))), distractor) is Outcome.CORRECT


def test_tracking_prefers_the_pair_near_the_previous_one(drawing):
    cable = CableState(-60.0, 0.0, 30.0, 0.0)
    stronger = CableState(60.0, 0.0, 30.0, 0.0)
    tracker = fresh()
    tracker.step(Frame(0, drawing.draw_cable(cable)))
    moved = CableState(-54.0, math.radians(2.0), 30.0, 0.0)
    sand = drawing.background(SIZE, 7)
    both = drawing.to_uint8(drawing.paint_band(drawing.paint_band(sand, moved, 40.0), stronger, 90.0))
    assert outcome(fresh().step(Frame(0, both)), stronger) is Outcome.CORRECT
    assert outcome(tracker.step(Frame(1, both)), moved) is Outcome.CORRECT


def test_init_starts_in_the_window_around_it(drawing):
    cable = CableState(-70.0, math.radians(5.0), 30.0, 0.0)
    distractor = CableState(75.0, math.radians(-12.0), 40.0, 0.0)
    tracker = HoughTracker()
    tracker.reset(INFO, np.random.default_rng(0), init=CameraTruth(cable))
    assert tracking(tracker)
    assert tracker.step(Frame(0, drawing.draw_cable(distractor))) is None
    ignoring = HoughTracker(HoughTracker.make_params({"use_init": "false"}))
    ignoring.reset(INFO, np.random.default_rng(0), init=CameraTruth(cable))
    assert not tracking(ignoring)
    assert outcome(ignoring.step(Frame(0, drawing.draw_cable(distractor))), distractor) is Outcome.CORRECT


def test_reset_forgets_the_previous_sequence(drawing):
    tracker = fresh()
    tracker.step(Frame(0, drawing.draw_cable(CableState(-70.0, 0.0, 30.0, 0.0))))
    assert tracking(tracker)
    tracker.reset(INFO, np.random.default_rng(0))
    assert not tracking(tracker)


def test_is_deterministic(drawing):
    images = [drawing.draw_cable(CableState(5.0 * k, 0.02 * k, 30.0, 0.0), seed=k) for k in range(4)]
    runs = []
    for seed in (1, 2):
        tracker = HoughTracker()
        tracker.reset(INFO, np.random.default_rng(seed))
        runs.append([tracker.step(Frame(k, image)) for k, image in enumerate(images)])
    assert runs[0] == runs[1]
    assert all(estimate is not None for estimate in runs[0])


def test_unknown_parameter_is_a_parameter_error():
    with pytest.raises(ParameterError, match="log_sigmaa"):
        HoughTracker.make_params({"log_sigmaa": 2.0})


@pytest.mark.parametrize(
    "bad",
    [
        {"log_sigma": 0.0},
        {"rho_step_px": -1.0},
        {"max_lines": 1},
        {"window_rho_px": 0.0},
        {"closeness_weight": 1.5},
        {"max_misses": 0},
        {"min_width_px": 200.0},
        {"max_skew_deg": 90.0},
        {"partner_fraction": 0.5},
        {"edge_rule": "mean"},
        {"reference_side_px": 0.0},
    ],
)
def test_values_outside_the_declared_domains_are_parameter_errors(bad):
    (name,) = bad
    with pytest.raises(ParameterError, match=rf"tracker 'hough'.*{name}"):
        HoughTracker.make_params(bad)


def test_an_unknown_cable_in_the_truth_leaves_the_whole_space_to_search():
    tracker = HoughTracker()
    tracker.reset(INFO, np.random.default_rng(0), init=CameraTruth(UNKNOWN_CABLE))
    assert not tracking(tracker)


def test_parameters_from_strings_are_converted():
    params = HoughTracker.make_params({"log_sigma": "5", "max_misses": "2"})
    assert params.log_sigma == 5.0 and params.max_misses == 2


def test_colour_image_is_a_data_error():
    with pytest.raises(DataError, match="frame 3"):
        fresh().step(Frame(3, np.zeros((*SIZE[::-1], 3), np.uint8)))


def test_a_wide_cable_in_a_large_frame_is_found_with_sizes_scaled_to_the_frame(drawing):
    # 640 x 480 shows the scene of a 320 x 240 frame with twice the pixels: a cable 150 px wide
    # is wider than the paper's 100 px, but within twice the reference frame's range.
    size = (640, 480)
    info = SequenceInfo("drawn-large", "camera", frame_size=size)
    truth = CableState(20.0, math.radians(6.0), 150.0, math.radians(0.5))
    image = drawing.draw_cable(truth, contrast=50.0, size=size)
    assert outcome(fresh(info).step(Frame(0, image)), truth, size) is Outcome.CORRECT
    assert paper(info).step(Frame(0, image)) is None


def test_a_faint_cable_on_a_quiet_seabed_survives_the_relative_edge_threshold(drawing):
    # Eight grey levels of contrast: below the paper's fixed 12-level step, far above the
    # frame's own noise crossings.
    truth = CableState(-25.0, math.radians(-4.0), 40.0, 0.0)
    quiet = drawing.background(SIZE, 3, texture=1.0, noise=1.0)
    image = drawing.to_uint8(drawing.paint_band(quiet, truth, 8.0))
    assert outcome(fresh().step(Frame(0, image)), truth) is Outcome.CORRECT
    assert paper().step(Frame(0, image)) is None


def test_the_init_window_waits_for_the_first_frame_when_the_size_is_unknown(drawing):
    cable = CableState(-70.0, math.radians(5.0), 30.0, 0.0)
    distractor = CableState(75.0, math.radians(-12.0), 40.0, 0.0)
    tracker = HoughTracker()
    tracker.reset(SequenceInfo("no-size", "camera"), np.random.default_rng(0), init=CameraTruth(cable))
    assert not tracking(tracker)
    assert tracker.step(Frame(0, drawing.draw_cable(distractor))) is None
    assert tracking(tracker)
