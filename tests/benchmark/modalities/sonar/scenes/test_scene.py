"""SonarScene: the Sequence contract, swaths that show the pipes where the truth says, and its errors."""

from __future__ import annotations

import math
import pickle
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from trackbench_suites.loader import merge_tables

from benchmark.errors import DataError
from benchmark.modalities.sonar.model import SonarCalibration, SonarTruth, Swath
from benchmark.modalities.sonar.scenes.scene import SonarScene
from benchmark.modalities.sonar.scenes.spec import SonarSceneSpec
from benchmark.modalities.sonar.strategies import scene_specs
from benchmark.model import Sequence

BUSY: dict[str, Any] = {
    "name": "sonar/busy",
    "n_frames": 30,
    "seed": 11,
    "frame_interval_s": 0.3,
    "sonar": {
        "n_beams": 111,
        "beam_width_deg": 1.5,
        "range_sigma_m": 0.04,
        "outer_sigma_factor": 3.0,
        "range_resolution_m": 0.02,
        "missing_nadir": 0.02,
        "missing_outer": 0.3,
        "outlier_rate": 0.02,
    },
    "vehicle": {"altitude_m": {"mean": 12.0, "noise_std": 0.5}, "roll_deg": {"noise_std": 2.0}},
    "seabed": {
        "slope_deg": {"mean": 2.0},
        "roughness": [{"std_m": 0.2, "length_m": 6.0}, {"std_m": 0.05, "length_m": 0.8}],
        "ripples": {"height_m": 0.05, "wavelength_m": 0.8, "crest_deg": 20.0},
        "boulders": [{"per_100m2": 3.0}],
    },
    "pipe": {
        "diameter_m": 0.9,
        "across_m": {"mean": 1.0, "noise_std": 1.0, "noise_smooth_frames": 5.0},
        "burial": {"events": [{"frame": 20.0, "amplitude": 0.5}]},
        "trench": {"depth_m": {"mean": 0.5}, "berm_ratio": 0.3},
    },
    "second_pipe": {"diameter_m": 0.5, "offset_m": {"mean": -5.0}},
}
"""Everything switched on: noise, gaps, spikes, roll, relief, boulders, a trench, a second pipe."""

QUIET: dict[str, Any] = {
    "name": "sonar/quiet",
    "n_frames": 12,
    "seed": 2,
    "sonar": {"n_beams": 240, "beam_width_deg": 0.0, "range_sigma_m": 0.0},
    "vehicle": {"altitude_m": {"mean": 10.0}},
    "pipe": {"diameter_m": 0.6, "across_m": {"mean": 1.5}},
}
"""A level, smooth seabed 10 m down, a 0.6 m pipe 1.5 m to starboard, a sonar without errors."""


def _busy(**changes: Any) -> SonarScene:
    return SonarScene.from_dict(merge_tables(BUSY, changes))


def _quiet(**changes: Any) -> SonarScene:
    return SonarScene.from_dict(merge_tables(QUIET, changes))


def _same_swath(a: Swath, b: Swath) -> bool:
    return np.array_equal(a.across_m, b.across_m, equal_nan=True) and np.array_equal(
        a.depth_m, b.depth_m, equal_nan=True
    )


def _on_circle(swath: Swath, centre: tuple[float, float], radius: float, tol: float = 1e-6) -> np.ndarray:
    return np.abs(np.hypot(swath.across_m - centre[0], swath.depth_m - centre[1]) - radius) < tol


def test_info_describes_the_sequence() -> None:
    scene = _busy(description="busy")
    info = scene.info
    assert isinstance(scene, Sequence)
    assert (info.name, info.modality, info.n_frames, info.frame_size) == ("sonar/busy", "sonar", 30, None)
    assert info.frame_interval_s == 0.3
    assert info.calibration == SonarCalibration(111, math.radians(120.0), 0.04, 0.9, math.radians(1.5))
    assert info.extra["description"] == "busy" and info.extra["second_pipe"] is True
    assert info.extra["ping_spacing_m"] == pytest.approx(0.45)


def test_frames_carry_swaths_and_truth_and_any_frame_renders_on_its_own() -> None:
    scene = _busy()
    frames = list(scene.frames())
    assert [f.index for f in frames] == list(range(30))
    assert [f.time_s for f in frames] == pytest.approx([0.3 * k for k in range(30)])
    for f in frames:
        assert isinstance(f.observation, Swath) and f.observation.across_m.shape == (111,)
        assert isinstance(f.truth, SonarTruth) and f.navigation is None
    fresh = _busy()
    for k in (17, 3, 29):
        alone = fresh.frame(k)
        assert _same_swath(alone.observation, frames[k].observation) and alone.truth == frames[k].truth
    with pytest.raises(IndexError, match="sonar/busy: frame 30"):
        scene.frame(30)


def test_same_spec_gives_bit_identical_pings_and_seed_changes_them() -> None:
    a, b = _busy(), _busy()
    assert all(_same_swath(a.observation(k), b.observation(k)) for k in range(0, 30, 7))
    assert np.array_equal(a.seabed()[1], b.seabed()[1])
    other = _busy(seed=12)
    assert not _same_swath(a.observation(5), other.observation(5))


def test_pings_are_independent_draws() -> None:
    scene = _quiet(sonar={"range_sigma_m": 0.05})
    swaths = [scene.observation(k) for k in (1, 2)]
    noise = [np.hypot(s.across_m, s.depth_m) - scene.true_ranges(k)[0] for k, s in zip((1, 2), swaths)]
    assert np.std(noise[0]) == pytest.approx(0.05, rel=0.2)
    assert abs(np.corrcoef(noise[0], noise[1])[0, 1]) < 0.25


def test_streams_are_independent_of_each_other() -> None:
    base = _busy()
    gappy = _busy(sonar={"missing_nadir": 0.3, "missing_outer": 0.6})
    for k in (0, 9):
        full, holes = base.observation(k), gappy.observation(k)
        kept = holes.valid
        assert kept.sum() < full.valid.sum()
        assert np.array_equal(holes.depth_m[kept], full.depth_m[kept])
    smoother = _busy(seabed={"roughness": [{"std_m": 0.0, "length_m": 6.0}, {"std_m": 0.05, "length_m": 0.8}]})
    assert np.array_equal(smoother.pipes()[0].across_m, base.pipes()[0].across_m)
    assert np.array_equal(smoother.pipes()[0].burial, base.pipes()[0].burial)


def test_a_pickled_scene_is_its_spec_and_renders_the_same() -> None:
    scene = _busy()
    before = scene.frame(4)
    payload = pickle.dumps(scene)
    assert len(payload) < 10_000
    clone = pickle.loads(payload)
    assert clone.spec == scene.spec
    after = clone.frame(4)
    assert _same_swath(after.observation, before.observation) and after.truth == before.truth


def test_a_proud_pipe_shows_on_its_circle_where_the_truth_puts_it() -> None:
    scene = _quiet()
    for k in (0, 7):
        swath, truth = scene.observation(k), scene.truth(k)
        assert truth.burial == 0.0 and truth.depth_m == pytest.approx(10.0 - 0.3)
        above = swath.depth_m < 10.0 - 1e-6
        assert above.sum() >= 5
        assert np.all(_on_circle(swath, (truth.across_m, truth.depth_m), 0.3)[above])
        top = np.argmin(np.where(above, swath.depth_m, np.inf))
        assert abs(swath.across_m[top] - truth.across_m) <= truth.resolution_m
        assert swath.across_m[above].min() < truth.across_m < swath.across_m[above].max()


def test_resolution_is_the_beam_spacing_found_at_the_pipe() -> None:
    scene = _quiet(pipe={"across_m": {"mean": 4.0}})
    swath, truth = scene.observation(3), scene.truth(3)
    beside = np.flatnonzero((np.abs(swath.across_m - 4.0) < 1.5) & (swath.depth_m > 10.0 - 1e-6))
    gaps = np.diff(swath.across_m[beside])
    top = truth.depth_m - 0.3
    # the seabed beside the pipe is 10 m down, its top 9.4 m: the same beams, 10 / 9.4 farther apart
    assert np.median(gaps[gaps < 0.3]) == pytest.approx(truth.resolution_m * 10.0 / top, rel=0.05)
    assert truth.resolution_m == pytest.approx(top * math.radians(0.5) * (1 + (4.0 / top) ** 2), rel=0.05)


def test_across_track_spacing_grows_away_from_nadir() -> None:
    swath = _quiet(pipe={"across_m": {"mean": 25.0}}).observation(0)
    starboard = np.diff(swath.across_m[120:])
    port = np.diff(swath.across_m[:120])[::-1]
    for gaps in (starboard, port):
        assert np.all(gaps > 0) and np.all(np.diff(gaps) > 0)
    assert starboard[-1] > 3.5 * starboard[0]


def test_missing_beams_are_nan_in_both_arrays() -> None:
    scene = _busy()
    lost = 0
    for k in range(0, 30, 3):
        swath = scene.observation(k)
        assert np.array_equal(np.isnan(swath.across_m), np.isnan(swath.depth_m))
        lost += int(np.sum(~swath.valid))
    assert lost > 0


def test_a_fully_buried_stretch_shows_no_bump() -> None:
    burial = {"events": [{"frame": 4.0, "amplitude": 1.0, "duration_frames": 2.0}]}
    scene = _quiet(pipe={"burial": burial})
    buried = [k for k in range(12) if scene.truth(k).burial >= 1.0]
    proud = [k for k in range(12) if scene.truth(k).burial == 0.0]
    assert buried and proud
    for k in buried:
        assert np.allclose(scene.observation(k).depth_m, 10.0, atol=1e-9)
    for k in proud:
        assert np.nanmin(scene.observation(k).depth_m) == pytest.approx(9.4, abs=0.01)


def test_a_partly_buried_pipe_shows_only_its_top() -> None:
    scene = _quiet(pipe={"burial": {"mean": 0.5}})
    swath, truth = scene.observation(2), scene.truth(2)
    assert truth.depth_m == pytest.approx(10.0)
    above = swath.depth_m < 10.0 - 1e-6
    assert np.nanmin(swath.depth_m) == pytest.approx(9.7, abs=1e-3)
    assert np.all(_on_circle(swath, (truth.across_m, truth.depth_m), 0.3)[above])


def test_the_second_pipe_appears_where_specified_and_the_truth_stays_on_the_first() -> None:
    second = {"diameter_m": 0.5, "offset_m": {"mean": -1.5}}
    scene = _quiet(second_pipe=second)
    swath, truth = scene.observation(5), scene.truth(5)
    assert truth.across_m == pytest.approx(1.5)  # the second pipe, at 0.0, is nearer nadir
    first = _on_circle(swath, (1.5, 9.7), 0.3)
    other = _on_circle(swath, (0.0, 9.75), 0.25)
    assert first.sum() >= 5 and other.sum() >= 5
    assert np.all(first | other | (np.abs(swath.depth_m - 10.0) < 1e-9))
    alone = _quiet()
    assert alone.truth(5) == truth


@settings(max_examples=15, deadline=None)
@given(scene_specs(max_frames=3))
def test_random_specs_give_finite_truth_and_full_swaths(spec: SonarSceneSpec) -> None:
    for frame in SonarScene(spec).frames():
        truth = frame.truth
        values = (truth.across_m, truth.depth_m, truth.burial, truth.resolution_m)
        assert all(math.isfinite(v) for v in values)
        assert 0.0 <= truth.burial <= 1.0 and truth.resolution_m > 0
        assert frame.observation.across_m.shape == frame.observation.depth_m.shape == (spec.sonar.n_beams,)
        assert frame.observation.valid.any()


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"vehicle": {"altitude_m": {"mean": 5.0, "slope_per_frame": -0.5}}}, r"sonar/busy: altitude at frame 9"),
        ({"vehicle": {"roll_deg": {"mean": 40.0}}}, r"sonar/busy: roll at frame 0"),
        ({"pipe": {"across_m": {"mean": 60.0}}}, r"sonar/busy: pipe 1 across-track position at frame 0"),
        ({"second_pipe": {"offset_m": {"mean": 80.0}}}, r"sonar/busy: pipe 2 across-track position at frame 0"),
        (
            {"vehicle": {"altitude_m": {"mean": 2.5}}, "pipe": {"diameter_m": 4.0}},
            r"sonar/busy: pipe 1 top depth below the sonar at frame 0",
        ),
    ],
)
def test_impossible_geometry_is_a_data_error_naming_sequence_and_frame(changes, message) -> None:
    with pytest.raises(DataError, match=message):
        _busy(**changes).frame(0)


SPANNING: dict[str, Any] = {
    "name": "sonar/spans",
    "n_frames": 120,
    "seed": 5,
    "frame_interval_s": 0.25,
    "sonar": {"n_beams": 200, "beam_width_deg": 1.0, "range_sigma_m": 0.0},
    "vehicle": {"altitude_m": {"mean": 12.0}, "speed_mps": 1.6},
    "seabed": {"sand_waves": {"height_m": 1.5, "wavelength_m": 20.0, "crest_deg": 90.0}},
    "pipe": {"diameter_m": 0.5, "bend_radius_m": 300.0, "drift": {"amplitude_m": 2.0, "speed_mps": 1.0}},
}
"""Sand waves across the track, a stiff pipe spanning their troughs, drifting across the swath at 1 m/s."""


def test_a_stiff_pipe_spans_the_troughs_of_sand_waves_and_the_swath_shows_the_gap() -> None:
    scene = SonarScene.from_dict(SPANNING)
    pipe = scene.pipes()[0]
    across, depth = scene.seabed()
    under = np.array([np.interp(x, across, row) for x, row in zip(pipe.across_m, depth)])
    gap = under - (pipe.axis_depth_m + pipe.radius_m)
    assert gap.max() > 0.5 and gap.min() > -1e-6
    assert np.all(pipe.burial == 0.0)
    hanging = int(np.argmax(gap))
    swath, truth = scene.observation(hanging), scene.truth(hanging)
    assert truth.depth_m == pytest.approx(pipe.axis_depth_m[hanging])
    beside = np.abs(swath.across_m - truth.across_m) < 1.0
    assert np.nanmax(swath.depth_m[beside]) > truth.depth_m + pipe.radius_m + 0.4  # the seabed below the span
    assert np.nanmin(swath.depth_m[beside]) < truth.depth_m  # the pipe's top
    follows = SonarScene.from_dict(merge_tables(SPANNING, {"pipe": {"bend_radius_m": 0.0}}))
    assert np.all(follows.pipes()[0].axis_depth_m[hanging] > pipe.axis_depth_m[hanging] + 0.5)


def test_the_drift_moves_the_pipe_across_the_swath_at_its_speed() -> None:
    scene = SonarScene.from_dict(SPANNING)
    across = scene.pipes()[0].across_m
    assert np.max(np.abs(np.diff(across))) / 0.25 == pytest.approx(1.0, rel=0.02)
    assert np.ptp(across) == pytest.approx(4.0, rel=0.02)
    still = SonarScene.from_dict(merge_tables(SPANNING, {"pipe": {"drift": {"speed_mps": 0.0}}}))
    assert np.all(still.pipes()[0].across_m == 0.0)


def test_conditions_add_the_footprint_ratio_and_the_pipe_s_speed_to_what_was_drawn() -> None:
    scene = SonarScene.from_dict(SPANNING)
    conditions = scene.conditions()
    assert conditions["footprint_ratio"] == pytest.approx(2 * 12.0 * math.tan(math.radians(0.5)) / 0.5)
    assert conditions["pipe_speed_mps"] == pytest.approx(1.0, rel=0.02)
    # A drawn condition of the same name wins (here an unrelated value drawn under that name).
    draws = {
        "beams": {"integers": [128, 400], "into": "sonar.n_beams"},
        "pipe_speed_mps": {"choice": [0.05], "into": "seabed.cell_m"},
    }
    drawn = SonarScene.from_dict(SPANNING | {"draw": draws})
    conditions = drawn.conditions()
    assert list(conditions)[:2] == ["beams", "pipe_speed_mps"] and conditions["pipe_speed_mps"] == 0.05
    assert conditions["beams"] == drawn.info.calibration.n_beams and "footprint_ratio" in conditions
