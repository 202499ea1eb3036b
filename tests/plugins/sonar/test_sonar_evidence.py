"""Eq. (1) as evidence for the cross-section as wide beams see it (seeds/003, section 2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.ndimage import gaussian_filter1d
from trackbench_sonar.cross_section import CrossSection
from trackbench_sonar.detection import SwathDetector
from trackbench_sonar.evidence import MIN_RETURNS, FootprintLikelihood, WidestEvidence
from trackbench_sonar.params import DetectorParams
from trackbench_sonar.profile import resample_swath

from benchmark.modalities.sonar.model import Swath
from benchmark.model import SequenceInfo


def detector(swaths, n_beams, swath_deg, noise, diameter, width_deg, **overrides) -> SwathDetector:
    """The detector set up for a sonar of ``n_beams`` beams ``width_deg`` wide (the calibration's) and a pipe."""
    calibration = swaths.calibration(n_beams, swath_deg, noise, diameter, width_deg)
    info = SequenceInfo("sonar/scene", "sonar", None, None, 0.3, calibration)
    return SwathDetector.for_sequence(DetectorParams(**overrides), info, "t")


def peak(swaths, swath, *args, **overrides) -> float | None:
    found = detector(swaths, *args, **overrides)
    return found.likelihood.scan(found.profile(swath, 0)).peak(refine=True)


def rough_edges(seed: int, std_m: float = 0.12, length_m: float = 1.2, start_m: float = 10.0):
    """Bare seabed, rough (smoothed noise of ``std_m`` over ``length_m``) beyond ``start_m`` either side."""
    grid = np.arange(-100.0, 100.005, 0.01)
    noise = gaussian_filter1d(np.random.default_rng(seed).standard_normal(grid.size), length_m / 0.01)
    noise *= std_m / noise.std()

    def relief(x):
        return np.clip((np.abs(x) - start_m) / 2.0, 0.0, 1.0) * np.interp(x, grid, noise)

    return relief


def trench_with_berms(centre: float, depth: float = 0.8, berm_height: float = 0.6, berm_sd: float = 0.5):
    """A trench 1.2 m wide at the bottom and 4 m at the top, with a Gaussian spoil berm beyond each wall."""

    def relief(x):
        distance = np.abs(x - centre)
        wall = np.clip((2.0 - distance) / 1.4, 0.0, 1.0)
        berm = np.exp(-0.5 * ((distance - 2.0 - berm_sd) / berm_sd) ** 2)
        return depth * wall - berm_height * berm

    return relief


@pytest.mark.parametrize("seed", range(6))
def test_a_pipe_smoothed_by_wide_beams_beats_rough_seabed_at_the_swath_s_edge(swaths, seed):
    # A 0.5 m pipe 15 m down under beams 2.5 deg wide: a footprint of 0.65 m at nadir, 1.3 diameters.
    sonar = (180, 130.0, 0.02, 0.5, 2.5)
    swath = swaths.cast(rough_edges(seed), [(2.0, 0.5, 0.0)], n_beams=180, swath_deg=130.0, altitude=15.0,
                        beam_width_deg=2.5, noise=0.02, seed=seed)  # fmt: skip
    found = peak(swaths, swath, *sonar)
    assert found is not None and abs(found - 2.0) <= swaths.spacing_at(2.0, 15.0, 180, 130.0)


def test_taken_as_rays_the_beams_leave_the_pipe_to_rough_seabed(swaths):
    # The same scenes when the detector ignores the footprint: it is fooled on some of them.
    sonar = (180, 130.0, 0.02, 0.5, 2.5)
    misses = 0
    for seed in range(6):
        swath = swaths.cast(rough_edges(seed), [(2.0, 0.5, 0.0)], n_beams=180, swath_deg=130.0, altitude=15.0,
                            beam_width_deg=2.5, noise=0.02, seed=seed)  # fmt: skip
        found = peak(swaths, swath, *sonar, beam_width_deg=1e-6)
        misses += found is None or abs(found - 2.0) > 1.0
    assert misses >= 2


def test_without_a_beam_width_each_ping_keeps_the_width_that_explains_it_best(swaths):
    # The scenes above, their beam width unknown to the detector: tried at 1, 2 and 4 beam spacings
    # (0.72, 1.45 and 2.9 deg), the pipe wins in every one.
    for seed in range(6):
        swath = swaths.cast(rough_edges(seed), [(2.0, 0.5, 0.0)], n_beams=180, swath_deg=130.0, altitude=15.0,
                            beam_width_deg=2.5, noise=0.02, seed=seed)  # fmt: skip
        found = detector(swaths, 180, 130.0, 0.02, 0.5, 0.0)
        assert isinstance(found.likelihood, WidestEvidence)
        scan = found.likelihood.scan(found.profile(swath, 0))
        assert abs(scan.peak(refine=True) - 2.0) <= swaths.spacing_at(2.0, 15.0, 180, 130.0)
        best = max(model.scan(found.profile(swath, 0)).values.max() for model in found.likelihood.models)
        assert scan.values.max() == best


@pytest.mark.parametrize("seed", range(3))
def test_spoil_berms_beside_the_trench_do_not_win(swaths, seed):
    sonar = (240, 120.0, 0.01, 0.6, 1.5)
    swath = swaths.cast(trench_with_berms(1.0), [(1.0, 0.6, 0.0)], beam_width_deg=1.5, noise=0.01, seed=seed)
    assert abs(peak(swaths, swath, *sonar) - 1.0) <= swaths.spacing_at(1.0, 10.0)
    # The ellipse of the paper takes a berm for the pipe here.
    assert abs(peak(swaths, swath, *sonar, likelihood="ellipse", spike_heights=0.5) - 1.0) > 1.0


def test_berms_alone_give_little_evidence_against_a_pipe(swaths):
    sonar = (240, 120.0, 0.01, 0.6, 1.5)
    found = detector(swaths, *sonar)
    berms = found.likelihood.scan(found.profile(swaths.cast(trench_with_berms(1.0), beam_width_deg=1.5), 0))
    pipe = found.likelihood.scan(found.profile(swaths.cast(lambda x: 0.0 * x, [(1.0, 0.6, 0.0)], beam_width_deg=1.5), 0))
    assert berms.values.max() < 0.5 * pipe.values.max()


def test_the_fitted_pedestal_is_the_height_of_the_centre_above_the_seabed(swaths):
    found = detector(swaths, 240, 120.0, 0.01, 0.6, 0.5)
    for gap, expected in [(0.0, 0.3), (0.6, 0.9), (-0.3, 0.0)]:
        swath = swaths.cast(lambda x: 0.0 * x, [(-1.5, 0.6, gap)], beam_width_deg=0.5, noise=0.005, seed=1)
        candidates = found.likelihood.candidates(found.profile(swath, 0))
        best = int(np.argmax(candidates.evidence))
        assert candidates.across_m[best] == pytest.approx(-1.5, abs=0.1)
        assert candidates.pedestal_m[best] == pytest.approx(expected, abs=0.08)


def test_the_evidence_grows_with_the_beams_on_the_pipe(swaths):
    evidence = []
    for n_beams in (120, 240, 480):
        found = detector(swaths, n_beams, 120.0, 0.01, 0.6, 0.5)
        swath = swaths.cast(lambda x: 0.0 * x, [(1.0, 0.6, 0.0)], n_beams=n_beams, beam_width_deg=0.5)
        evidence.append(found.likelihood.scan(found.profile(swath, 0)).values.max())
    assert evidence[0] < evidence[1] < evidence[2]


def test_flat_seabed_with_sparse_edges_gives_no_evidence_where_nothing_stands(swaths):
    found = detector(swaths, 128, 150.0, 0.02, 0.6, 1.0)
    candidates = found.likelihood.candidates(found.profile(swaths.make(None, n_beams=128, swath_deg=150.0), 0))
    assert np.all(candidates.evidence <= 1e-6 * max(1.0, np.max(candidates.evidence)) + 1e-9)


def test_a_candidate_needs_returns_on_both_sides_and_enough_of_them(swaths):
    found = detector(swaths, 240, 120.0, 0.01, 0.6, 0.5)
    candidates = found.likelihood.candidates(found.profile(swaths.make(3.0), 0))
    assert np.all(candidates.evidence[~candidates.scored] == 0.0)
    assert np.all(candidates.returns[candidates.scored] >= MIN_RETURNS)
    ends = candidates.across_m[[0, -1]]
    assert not np.any(candidates.scored[[0, -1]]) and ends[0] < -15.0 < 15.0 < ends[1]


@settings(max_examples=50, deadline=None)
@given(
    arrays(float, st.integers(0, 80), elements=st.floats(-30, 30) | st.just(math.nan)),
    arrays(float, 80, elements=st.floats(0.0, 60.0) | st.just(math.nan)),
    st.floats(0.0, 0.05),
)
def test_the_evidence_is_finite_and_non_negative_for_arbitrary_returns(across, depth, beam_width):
    model = FootprintLikelihood(CrossSection(0.6, 0.6), 0.02, beam_width)
    profile = resample_swath(Swath(across, depth[: across.size]), 0.05, spike_m=0.3)
    scan = model.scan(profile)
    assert scan.positions.shape == scan.values.shape == profile.across_m.shape
    assert np.all(np.isfinite(scan.values)) and np.all(scan.values >= 0.0)


@pytest.mark.parametrize(
    ("field", "value"),
    [("sigma_m", 0.0), ("seabed_widths", math.inf), ("relief_widths", -1.0), ("robust_sigmas", math.nan)],
)
def test_bad_settings_are_rejected(field, value):
    settings_ = {"section": CrossSection(0.6, 0.6), "sigma_m": 0.02, field: value}
    with pytest.raises(ValueError, match=field):
        FootprintLikelihood(**settings_)
    with pytest.raises(ValueError, match="beam_width"):
        FootprintLikelihood(CrossSection(0.6, 0.6), 0.02, beam_width=-0.1)
    with pytest.raises(ValueError, match="iterations"):
        FootprintLikelihood(CrossSection(0.6, 0.6), 0.02, iterations=0)
    with pytest.raises(ValueError, match="at least one model"):
        WidestEvidence(())
