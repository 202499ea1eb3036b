"""The conformance kit on fake trackers: a well-behaved one passes, each broken one fails exactly its check."""

from __future__ import annotations

import dataclasses
import math
import os
import time
import types
from typing import Any

import numpy as np
import pytest

from benchmark.modalities.camera.modality import CAMERA
from benchmark.modalities.camera.model import CableState
from benchmark.model import Frame, SequenceInfo
from benchmark.filters.resampling import systematic_resample
from benchmark.registry import Registry
from benchmark.testing import Check, CheckResult, check_tracker, checks, conformance_cases, entry_of, prepare, run_check
from benchmark.testing.checks import same
from benchmark.tracker import Tracker

from ..conftest import HEIGHT, WIDTH
from .conftest import Steady

ALL_CHECKS = [check.name for check in checks()]


class GlobalRandom(Steady):
    """Draws from NumPy's global generator (and ignores the draw)."""

    name = "global-random"

    def step(self, frame: Frame) -> Any:
        np.random.random()
        return super().step(frame)


class Sticky(Steady):
    """Counts frames across resets, and the count moves its estimates."""

    name = "sticky"
    seen = 0

    def step(self, frame: Frame) -> Any:
        self.seen += 1
        estimate = super().step(frame)
        return CableState(estimate.d + self.seen, estimate.alpha, estimate.w, estimate.beta)


class NotANumber(Steady):
    """Returns a NaN distance at frame 2."""

    name = "not-a-number"

    def step(self, frame: Frame) -> Any:
        estimate = super().step(frame)
        return CableState(math.nan, 0.0, 12.0, 0.0) if frame.index == 2 else estimate


class Peeking(Steady):
    """Returns the frame's truth where it has one."""

    name = "peeking"

    def step(self, frame: Frame) -> Any:
        return frame.truth.cable if frame.truth is not None else super().step(frame)


class NanWithoutTruth(Steady):
    """Returns a NaN state on a frame without truth (once lost, as it were)."""

    name = "nan-without-truth"

    def step(self, frame: Frame) -> Any:
        return super().step(frame) if frame.truth is not None else CableState(math.nan, 0.0, 12.0, 0.0)


class NeedsAStart(Steady):
    """Cannot start without the first frame's truth, and says so."""

    name = "needs-a-start"
    starts_without_truth = False

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        if init is None:
            raise ValueError("needs the first frame's truth")
        super().reset(info, rng, init)


class KnownToKeepState(Steady):
    """Keeps state across sequences, and lists that check as an expected failure."""

    name = "known-to-keep-state"
    expected_failed_checks = {"reset_leaves_no_state": "keeps its map across sequences by design"}

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        kept = getattr(self, "state", None)
        super().reset(info, rng, init)
        self.state = kept or self.state


class WronglyExpected(Steady):
    """Lists a check it passes as an expected failure."""

    name = "wrongly-expected"
    expected_failed_checks = {"pickles": "holds a file"}


class MisspeltExpected(Steady):
    """Lists a check that does not exist."""

    name = "misspelt-expected"
    expected_failed_checks = {"pickle": "typo"}


class LateBug(Steady):
    """Right until frame 50, then a NaN state: a bug only a long enough run shows."""

    name = "late-bug"

    def step(self, frame: Frame) -> Any:
        return CableState(math.nan, 0.0, 12.0, 0.0) if frame.index >= 50 else super().step(frame)


class OpensAFileAtFrame5(Steady):
    """Keeps a file open from frame 5 on, which pickle refuses."""

    name = "opens-a-file"

    def step(self, frame: Frame) -> Any:
        if frame.index == 5:
            self.log = open(os.devnull, "w")  # noqa: SIM115
        return super().step(frame)


class Unseeded(Steady):
    """Draws from a generator of its own, seeded the same on every reset."""

    name = "unseeded"

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        super().reset(info, np.random.default_rng(7), init)


class FalselyDeterministic(Steady):
    """Says it draws no random numbers, and draws them."""

    name = "falsely-deterministic"
    deterministic = True


class Frightened(Steady):
    """Returns a NaN state on a black image."""

    name = "frightened"

    def step(self, frame: Frame) -> Any:
        estimate = super().step(frame)
        return CableState(math.nan, 0.0, 12.0, 0.0) if not frame.observation.any() else estimate


class Dazzled(Steady):
    """Loops forever on a white image."""

    name = "dazzled"

    def step(self, frame: Frame) -> Any:
        while frame.observation.min() == 255:
            pass
        return super().step(frame)


class OneSize(Steady):
    """Only reads images of the size of the kit's fake sequence."""

    name = "one-size"

    def step(self, frame: Frame) -> Any:
        if frame.observation.shape != (HEIGHT, WIDTH):
            raise ValueError(f"expects {WIDTH}x{HEIGHT} images")
        return super().step(frame)


class SlowLearner(Steady):
    """Learns, but its fit never ends."""

    name = "slow-learner"
    fits_started = 0

    def fit(self, training: Any, rng: np.random.Generator) -> Any:
        type(self).fits_started += 1
        while True:
            pass

    def use_model(self, model: Any) -> None:
        self.model = model


class CodeLearner(SlowLearner):
    """Learns a model that holds a function, which no stored model may."""

    name = "code-learner"

    def fit(self, training: Any, rng: np.random.Generator) -> Any:
        self.model = {"threshold": 0.5, "rule": abs}
        return self.model


class Unpicklable(Steady):
    """Keeps a lambda, which pickle refuses."""

    name = "unpicklable"

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        super().reset(info, rng, init)
        self.scale = lambda value: value


class FakeKalman(Steady):
    """A Kalman filter on Steady's ``(d, w)``: ``d`` measured on every ``measured_every``-th frame, ``w`` never.

    Its update is the textbook ``(I - K H) P`` (seeds/002 Table 2, line 6),
    in the dtype ``dtype``; it exposes the prior of each update as
    ``prior_covariance``, and None on a frame it did not measure.
    """

    name = "fake-kalman"
    measured_every = 1
    dtype: type = np.float64
    mean: np.ndarray | None = None
    covariance: np.ndarray | None = None
    prior_covariance: np.ndarray | None = None

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        super().reset(info, rng, init)
        self.mean = np.array([self.state.d, self.state.w], dtype=self.dtype)
        self.covariance = np.diag([4.0, 1.0]).astype(self.dtype)
        self.prior_covariance = None
        self.steps = 0

    def step(self, frame: Frame) -> Any:
        estimate = super().step(frame)
        prior = self.predicted()
        self.mean, self.covariance, self.prior_covariance = np.array([estimate.d, estimate.w], self.dtype), prior, None
        if self.steps % self.measured_every == 0:
            self.covariance, self.prior_covariance = self.corrected(prior), prior
        self.steps += 1
        return estimate

    def predicted(self) -> np.ndarray:
        return self.covariance + np.diag([0.5, 0.1]).astype(self.dtype)

    def corrected(self, prior: np.ndarray) -> np.ndarray:
        observe = np.array([[1.0, 0.0]], dtype=self.dtype)
        gain = prior @ observe.T / (observe @ prior @ observe.T + self.dtype(2.0))
        return (np.eye(2, dtype=self.dtype) - gain @ observe) @ prior


class InflatingKalman(FakeKalman):
    """Its update has the sign of the gain's term wrong: ``(I + K H) P`` widens the belief it should narrow."""

    name = "inflating-kalman"

    def corrected(self, prior: np.ndarray) -> np.ndarray:
        return 2.0 * prior - super().corrected(prior)


class SometimesMeasured(FakeKalman):
    """Measures every third frame; exposes a prior only then."""

    name = "sometimes-measured"
    measured_every = 3


class PriorWhenUnmeasured(SometimesMeasured):
    """Exposes its prediction as the prior on unmeasured frames too, where the posterior is that prior."""

    name = "prior-when-unmeasured"

    def step(self, frame: Frame) -> Any:
        estimate = super().step(frame)
        if self.prior_covariance is None:
            self.prior_covariance = self.covariance.copy()
        return estimate


class Float32Kalman(FakeKalman):
    """Filters in float32."""

    name = "float32-kalman"
    dtype = np.float32


class ForgetsWhenBlind(FakeKalman):
    """Holds no belief (mean, covariance and prior None) on a frame without signal; restarts after it."""

    name = "forgets-when-blind"

    def step(self, frame: Frame) -> Any:
        if not frame.observation.any():
            self.mean = self.covariance = self.prior_covariance = None
            return super(FakeKalman, self).step(frame)
        if self.covariance is None:
            self.covariance = np.diag([4.0, 1.0]).astype(self.dtype)
        return super().step(frame)


class FakeParticles(Steady):
    """A particle filter on Steady's ``d``: walk, then weigh by closeness to the estimate; exposes the walked set."""

    name = "fake-particles"
    particles: np.ndarray | None = None
    weights: np.ndarray | None = None
    prior_particles: np.ndarray | None = None

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: Any = None) -> None:
        super().reset(info, rng, init)
        self.particles = self.state.d + rng.normal(size=(16, 1))
        self.weights = np.full(16, 1 / 16)
        self.prior_particles = None

    def step(self, frame: Frame) -> Any:
        estimate = super().step(frame)
        walked = self.particles + self.rng.normal(0.0, 0.5, size=self.particles.shape)
        likelihood = np.exp(-0.5 * (walked[:, 0] - estimate.d) ** 2) + 1e-12
        self.prior_particles = walked
        self.particles, self.weights = self.posterior(walked, likelihood / likelihood.sum())
        return estimate

    def posterior(self, walked: np.ndarray, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return walked, weights


class ResamplesAfterWeighing(FakeParticles):
    """Resamples at the end of each update (SIR): copies of the walked particles, equally weighted."""

    name = "resamples-after-weighing"

    def posterior(self, walked: np.ndarray, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return walked[systematic_resample(weights, self.rng)], np.full(len(weights), 1 / len(weights))


class ClimbsAfterWeighing(FakeParticles):
    """Moves every particle half way to the estimate after weighing them, as a local ascent of the particles would."""

    name = "climbs-after-weighing"

    def posterior(self, walked: np.ndarray, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return walked + 0.5 * (self.state.d - walked), weights


@pytest.fixture
def registry(fakes: types.ModuleType) -> Registry:
    return fakes.make_registry()


def run_kit(
    tracker: type[Tracker], registry: Registry, fakes: types.ModuleType, time_limit_s: float = 60.0
) -> list[CheckResult]:
    sequence = fakes.FakeSequence("fake/S1", 10)
    return check_tracker(tracker, registry=registry, modality_data=sequence, time_limit_s=time_limit_s)


def failures(results: list[CheckResult]) -> dict[str, str]:
    return {result.check: result.message for result in results if not result.ok}


@pytest.mark.parametrize(
    ("tracker", "says"),
    [
        (Peeking, "its estimates change when the frames' truth is taken away at frame 1"),
        (NanWithoutTruth, "invalid estimate at frame 1, truth only for init: EstimateError"),
    ],
    ids=["reads truth", "nan without truth"],
)
def test_a_tracker_that_leans_on_the_truth_fails_frames_without_truth(
    registry: Registry, fakes: types.ModuleType, tracker: type[Tracker], says: str
) -> None:
    failed = failures(run_kit(tracker, registry, fakes))
    assert says in failed["frames_without_truth"], failed


def test_nan_on_frames_without_truth_fails_starting_without_truth_too(registry: Registry, fakes: types.ModuleType) -> None:
    failed = failures(run_kit(NanWithoutTruth, registry, fakes))
    assert list(failed) == ["frames_without_truth", "starts_without_truth"]
    assert "invalid estimate at frame 0, no init, no truth: EstimateError" in failed["starts_without_truth"]


def test_a_tracker_that_needs_its_first_truth_says_so_and_skips_starting_without_it(
    registry: Registry, fakes: types.ModuleType
) -> None:
    results = {result.check: result for result in run_kit(NeedsAStart, registry, fakes)}
    assert [name for name, result in results.items() if not result.ok] == []
    assert results["starts_without_truth"].outcome == "skipped"
    assert "starts_without_truth = False" in results["starts_without_truth"].message


def test_a_tracker_that_becomes_unpicklable_part_way_fails_where_it_does(registry: Registry, fakes: types.ModuleType) -> None:
    failed = failures(run_kit(OpensAFileAtFrame5, registry, fakes))
    assert list(failed) == ["pickles"]
    assert "an instance after frame 8 does not pickle: TypeError" in failed["pickles"]  # fine after frames 0 and 4


def test_checks_are_named_in_order() -> None:
    assert ALL_CHECKS == [
        "metadata",
        "runs",
        "same_seed_same_output",
        "frames_without_truth",
        "starts_without_truth",
        "seed_matters",
        "no_global_randomness",
        "reset_leaves_no_state",
        "hard_observations",
        "random_sequences",
        "pickles",
        "hash_seed",
        "belief_invariants",
        "step_time",
    ]
    assert all(isinstance(check, Check) and callable(check) for check in checks())


def test_a_well_behaved_tracker_passes_everything(registry: Registry, fakes: types.ModuleType) -> None:
    results = run_kit(Steady, registry, fakes)
    assert [result.check for result in results] == ALL_CHECKS
    assert failures(results) == {}
    assert "ms per frame" in results[-1].detail


def test_perfect_passes_everything_but_the_runs_without_truth(registry: Registry, fakes: types.ModuleType) -> None:
    """The oracle reads ``frame.truth`` in ``step``, which the kit is right to refuse."""
    failed = failures(check_tracker(registry.trackers["perfect"], registry=registry))
    assert list(failed) == ["frames_without_truth", "starts_without_truth"]
    assert all("'perfect'" in failed[name] and "AttributeError" in failed[name] for name in failed)


def test_the_registry_suite_is_used_when_no_sequence_is_given(registry: Registry) -> None:
    results = check_tracker(Steady, registry=registry)
    assert failures(results) == {}
    assert "fake/S1" in results[1].detail


@pytest.mark.parametrize(
    ("tracker", "check", "words"),
    [
        (GlobalRandom, "no_global_randomness", "np.random"),
        (Sticky, "reset_leaves_no_state", "reset keeps state"),
        (Unpicklable, "pickles", "does not pickle"),
        (Unseeded, "seed_matters", "seeds 0 and 1 give identical estimates"),
        (FalselyDeterministic, "seed_matters", "declares itself deterministic, but runs with seeds 0 and 1 differ"),
        (Frightened, "hard_observations", "invalid estimate at frame 3, 'blank' observations in frames 3-6"),
        (OneSize, "random_sequences", "expects 64x48 images (step, frame 0, random sequence"),
    ],
)
def test_a_broken_tracker_fails_exactly_its_check(
    tracker: type[Tracker], check: str, words: str, registry: Registry, fakes: types.ModuleType
) -> None:
    failed = failures(run_kit(tracker, registry, fakes))
    assert list(failed) == [check]
    assert f"tracker {tracker.name!r}" in failed[check]
    assert words in failed[check]


def test_a_nan_estimate_fails_runs_first_and_the_checks_that_follow_say_so(registry: Registry, fakes: types.ModuleType) -> None:
    results = run_kit(NotANumber, registry, fakes)
    failed = failures(results)
    followers = ["frames_without_truth", "starts_without_truth", "hard_observations", "random_sequences"]
    assert list(failed) == ["runs", *followers]  # the root cause first
    assert failed["runs"].startswith("tracker 'not-a-number': invalid estimate at frame 2: EstimateError")
    assert all(failed[name].startswith("follows from 'runs': tracker 'not-a-number'") for name in followers)
    assert "invalid estimate at frame 2, truth only for init: EstimateError" in failed["frames_without_truth"]
    assert "invalid estimate at frame 2, 'blank' observations" in failed["hard_observations"]
    assert "invalid estimate at frame 2, random sequence" in failed["random_sequences"]
    assert {result.check: result.follows for result in results if not result.ok}["hard_observations"] == "runs"


def test_a_failure_that_follows_from_two_earlier_ones_names_the_first_to_run(registry: Registry, fakes: types.ModuleType) -> None:
    class Erratic(NotANumber):
        """Invalid at frame 2, and draws from numpy's global generator, so that no two runs agree."""

        name = "erratic"

        def step(self, frame: Frame) -> Any:
            cable = super().step(frame)
            return None if cable is None else dataclasses.replace(cable, d=cable.d + np.random.normal())

    failed = failures(run_kit(Erratic, registry, fakes))
    assert list(failed)[0] == "runs" and not failed["runs"].startswith("follows")
    assert failed["same_seed_same_output"].startswith("follows from 'runs'")
    # after both runs and same_seed_same_output, both failed: the first to run is the root cause
    assert failed["reset_leaves_no_state"].startswith("follows from 'runs': tracker 'erratic'")


@pytest.mark.parametrize(
    ("tracker", "check", "outcome", "ok", "says"),
    [
        (KnownToKeepState, "reset_leaves_no_state", "xfailed", True, "expected to fail: keeps its map"),
        (WronglyExpected, "pickles", "xpassed", False, "listed in expected_failed_checks (holds a file), but it passed"),
    ],
    ids=["fails as declared", "passes though declared"],
)
def test_expected_failures_are_reported_as_such_and_must_stay_true(
    registry: Registry, fakes: types.ModuleType, tracker: type[Tracker], check: str, outcome: str, ok: bool, says: str
) -> None:
    results = {result.check: result for result in run_kit(tracker, registry, fakes)}
    assert (results[check].outcome, results[check].ok) == (outcome, ok)
    assert says in results[check].detail + results[check].message
    assert [name for name, result in results.items() if name != check and not result.ok] == []


def test_an_expected_failure_of_an_unknown_check_fails_the_metadata(registry: Registry, fakes: types.ModuleType) -> None:
    failed = failures(run_kit(MisspeltExpected, registry, fakes))
    assert "expected_failed_checks must map names of checks" in failed["metadata"] and "'pickle'" in failed["metadata"]


def test_a_tracker_that_hangs_fails_its_check_and_the_kit_goes_on(registry: Registry, fakes: types.ModuleType) -> None:
    results = run_kit(Dazzled, registry, fakes, time_limit_s=1.0)
    failed = failures(results)
    assert list(failed) == ["hard_observations"]
    assert "did not finish within 1 s" in failed["hard_observations"]
    assert "'saturated' observations" in failed["hard_observations"]
    assert [result.check for result in results] == ["hard_observations", *(c for c in ALL_CHECKS if c != "hard_observations")]


class Drowsy(Steady):
    """Sleeps through its second frame: it hangs without using the processor."""

    name = "drowsy"

    def step(self, frame: Frame) -> Any:
        if frame.index == 1:
            time.sleep(60.0)
        return super().step(frame)


def test_the_checks_after_one_that_ran_out_of_time_fail_unrun(registry: Registry, fakes: types.ModuleType) -> None:
    results = {result.check: result for result in run_kit(Drowsy, registry, fakes, time_limit_s=0.1)}
    assert results["runs"].hung and "does it hang?" in results["runs"].message
    after = [check for check in ALL_CHECKS if check not in ("metadata", "runs")]
    for check in after:
        assert results[check].outcome == "failed" and not results[check].hung
        assert results[check].message == "follows from 'runs': not run: 'runs' ran out of time"
    assert results["metadata"].outcome == "passed" and not results["metadata"].hung


def test_an_unrun_check_the_tracker_expects_to_fail_is_an_expected_failure(
    registry: Registry, fakes: types.ModuleType
) -> None:
    class Excused(Drowsy):
        name = "excused"
        expected_failed_checks = {"pickles": "holds a lock"}

    results = {result.check: result for result in run_kit(Excused, registry, fakes, time_limit_s=0.1)}
    assert results["pickles"].outcome == "xfailed" and results["seed_matters"].outcome == "failed"


def test_global_state_is_restored_after_the_check(registry: Registry, fakes: types.ModuleType) -> None:
    before = np.random.get_state()
    run_kit(GlobalRandom, registry, fakes)
    after = np.random.get_state()
    assert all(same(np.asarray(a), np.asarray(b)) for a, b in zip(before, after))


def test_bad_metadata_is_reported_and_the_runs_say_why_they_cannot_happen(registry: Registry) -> None:
    class Elsewhere(Steady):
        name = "elsewhere"
        modality = "lidar"

    failed = failures(check_tracker(Elsewhere, registry=registry))
    assert "modality 'lidar' is not registered" in failed["metadata"]
    assert failed["runs"].startswith("follows from 'metadata'") and "cannot run" in failed["runs"]
    assert "step_time" not in failed


def test_estimates_compare_nan_aware() -> None:
    assert same(CableState(math.nan, 0.0, 1.0, 0.0), CableState(math.nan, 0.0, 1.0, 0.0))
    assert not same(CableState(1.0, 0.0, 1.0, 0.0), CableState(1.5, 0.0, 1.0, 0.0))
    assert same(np.array([1.0, math.nan]), np.array([1.0, math.nan]))
    assert not same(None, CableState(0.0, 0.0, 1.0, 0.0))


def test_a_fit_that_hangs_is_stopped_and_every_run_says_why(registry: Registry, fakes: types.ModuleType) -> None:
    SlowLearner.fits_started = 0
    failed = failures(run_kit(SlowLearner, registry, fakes, time_limit_s=0.5))
    assert "metadata" not in failed
    assert "cannot run: preparing its frames and model did not finish within 0.5 s of CPU time" in failed["runs"]
    assert SlowLearner.fits_started == 1  # prepared once; every check says why it cannot run


def test_a_model_that_cannot_be_stored_fails_the_runs_saying_what_it_holds(registry: Registry, fakes: types.ModuleType) -> None:
    failed = failures(run_kit(CodeLearner, registry, fakes))
    assert "metadata" not in failed
    assert "its fitted model cannot be stored: cannot store a builtins.builtin_function_or_method" in failed["runs"]


def test_conformance_cases_are_one_test_per_check(registry: Registry, fakes: types.ModuleType) -> None:
    sequence = fakes.FakeSequence("fake/S1", 6)
    cases = conformance_cases(Sticky, registry=registry, modality_data=sequence)
    assert [case.id for case in cases] == ALL_CHECKS
    by_name = {case.id: case.values[0] for case in cases}
    by_name["runs"]()
    with pytest.raises(AssertionError, match="tracker 'sticky': reset keeps state"):
        by_name["reset_leaves_no_state"]()
    assert by_name["runs"].subject() is by_name["pickles"].subject()


def test_conformance_cases_skip_xfail_and_name_the_root_cause(registry: Registry, fakes: types.ModuleType) -> None:
    sequence = fakes.FakeSequence("fake/S1", 6)
    cases = conformance_cases(KnownToKeepState, registry=registry, modality_data=sequence)
    by_name = {case.id: case.values[0] for case in cases}
    with pytest.raises(pytest.skip.Exception, match="exposes no belief"):
        by_name["belief_invariants"]()
    with pytest.raises(pytest.xfail.Exception, match="by design"):
        by_name["reset_leaves_no_state"]()
    cases = {case.id: case.values[0] for case in conformance_cases(NotANumber, registry=registry, modality_data=sequence)}
    with pytest.raises(AssertionError, match="^follows from 'runs': tracker 'not-a-number': invalid estimate at frame 2"):
        cases["hard_observations"]()


def test_conformance_cases_of_a_name_load_the_plugins_only_when_a_case_runs(loads: list[tuple[str, ...]]) -> None:
    cases = conformance_cases("blind", n_frames=3)
    assert loads == []
    cases[1].values[0]()
    assert len(loads) == 1
    cases[2].values[0]()
    assert len(loads) == 1


def test_a_modality_that_cannot_make_hard_observations_is_named(fakes: types.ModuleType) -> None:
    def broken(frame: Frame, info: SequenceInfo, rng: np.random.Generator) -> dict[str, Any]:
        raise KeyError("exposure")

    registry = Registry()
    with registry.acting_for(fakes.BUILT_IN):
        registry.add_modality(dataclasses.replace(CAMERA, hard_observations=broken))
    failed = failures(check_tracker(Steady, registry=registry, modality_data=fakes.FakeSequence("fake/S1", 6)))
    assert list(failed) == ["hard_observations"]
    assert "modality 'camera' could not make hard observations (not the tracker's fault): KeyError" in failed[
        "hard_observations"
    ]


def test_a_bug_that_starts_at_frame_50_is_caught_by_default(registry: Registry, fakes: types.ModuleType) -> None:
    long = fakes.FakeSequence("fake/long", 80)
    failed = failures(check_tracker(LateBug, registry=registry, modality_data=long))
    assert "invalid estimate at frame 50: EstimateError" in failed["runs"]
    assert failures(check_tracker(LateBug, registry=registry, modality_data=long, n_frames=15)) == {}


def belief_check(tracker: type[Tracker], registry: Registry, fakes: types.ModuleType) -> CheckResult:
    """The ``belief_invariants`` check alone, on ten frames of the fake sequence."""
    subject = prepare(entry_of(tracker), registry, fakes.FakeSequence("fake/S1", 10))
    (check,) = [check for check in checks() if check.name == "belief_invariants"]
    return run_check(check, subject)


@pytest.mark.parametrize(
    ("tracker", "words"),
    [
        (
            InflatingKalman,
            "its Gaussian measurement update is broken at frame 0: the update widened the belief: the posterior "
            "exceeds the prior along (1, 0) (on the prior's scales, component 0 leading) by 0.692 of its scale; "
            "variance of component 0 grew from 4.5 to 7.62",
        ),
        (ClimbsAfterWeighing, "its particle measurement update is broken at frame 0: the update moved particles: 16"),
    ],
)
def test_an_update_that_widens_or_moves_the_belief_fails_exactly_belief_invariants(
    tracker: type[Tracker], words: str, registry: Registry, fakes: types.ModuleType
) -> None:
    failed = failures(run_kit(tracker, registry, fakes))
    assert list(failed) == ["belief_invariants"]
    assert f"tracker {tracker.name!r}: {words}" in failed["belief_invariants"]


@pytest.mark.parametrize(
    ("tracker", "updates"),
    [
        (FakeKalman, "compared at 40 Gaussian updates"),  # 10 frames, 4 runs: the frames and each hard kind
        (Float32Kalman, "compared at 40 Gaussian updates"),
        (SometimesMeasured, "compared at 16 Gaussian updates"),  # frames 0, 3, 6, 9
        (PriorWhenUnmeasured, "compared at 40 Gaussian updates"),
        (ForgetsWhenBlind, "compared at 36 Gaussian updates"),  # no belief on the 4 blank frames
        (FakeParticles, "compared at 40 particle updates"),
        (ResamplesAfterWeighing, "compared at 40 particle updates"),
    ],
)
def test_sound_updates_pass_and_are_counted(
    tracker: type[Tracker], updates: str, registry: Registry, fakes: types.ModuleType
) -> None:
    result = belief_check(tracker, registry, fakes)
    assert result.ok, result.message
    assert result.detail.endswith(f"prior and posterior {updates}")


def test_a_tracker_without_priors_says_no_update_was_compared(registry: Registry, fakes: types.ModuleType) -> None:
    class NoPrior(FakeKalman):
        name = "no-prior"

        def step(self, frame: Frame) -> Any:
            estimate = super().step(frame)
            self.prior_covariance = None
            return estimate

    result = belief_check(NoPrior, registry, fakes)
    assert result.ok and result.detail.endswith("; no update exposed its prior")
