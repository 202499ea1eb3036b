"""From a ping to its likelihood scan: the detector of seeds/003, section 2.

A :class:`SwathDetector` is set up once per sequence from the trackers'
parameters and the sequence's :class:`~benchmark.modalities.sonar.model.SonarCalibration`
(the pipe's diameter, the sonar's range noise and beam width), and then
turns each frame's :class:`~benchmark.modalities.sonar.model.Swath` into a
resampled profile (:mod:`trackbench_sonar.profile`) and the likelihood of
eq. (1) over it.  Eq. (1) has two forms, registered in
:data:`LIKELIHOODS` and chosen by the parameter ``likelihood``: the
ellipse through two consecutive points as the paper draws it
(``"ellipse"``, :mod:`trackbench_sonar.likelihood`) and the cross-section
as the beams' footprints see it, scored as evidence over the seafloor
(``"footprint"``, :mod:`trackbench_sonar.evidence`).  Both trackers of the plugin share it,
so that ``sonar_pf`` observes exactly what ``sonar_detector`` reports;
:class:`ScanTracker` is the part of a tracker both build on.

Bad input is a :class:`~benchmark.errors.DataError` that names the tracker
and the frame (an observation that is not a swath) or the tracker and the
sequence (a calibration that does not describe the pipe); a swath without
enough returns is not an error but an empty scan.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from benchmark.errors import DataError
from benchmark.modalities.sonar.model import PipeEstimate, SonarCalibration, SonarFrame, SonarTruth, Swath
from benchmark.model import SequenceInfo
from benchmark.tracker import Tracker
from trackbench_sonar.cross_section import CrossSection
from trackbench_sonar.evidence import FootprintLikelihood, WidestEvidence
from trackbench_sonar.likelihood import PipeLikelihood, Scan
from trackbench_sonar.params import DetectorParams
from trackbench_sonar.profile import Profile, resample_swath

GRID_PER_PIPE = 10
"""The profile's grid is at most a tenth of the pipe's width ``M_a``, whatever ``grid_m`` says."""


class ScanModel(Protocol):
    """A form of eq. (1): the pipe's cross-section and the likelihood scan of a profile."""

    section: CrossSection

    def scan(self, profile: Profile) -> Scan:
        """The likelihood over the profile's grid."""
        ...


@dataclass(frozen=True)
class SensorFacts:
    """What the sequence tells the detector about its pipe and sonar.

    Attributes
    ----------
    section : CrossSection
        The pipe's axes.
    sigma_m : float
        The range noise and ``model_sigma_m`` in quadrature, m.
    beam_spacing : float
        Angle between neighbouring beams, rad (0: unknown).
    beam_width : float
        The beams' across-track width, rad: the parameter ``beam_width_deg``
        when set, else the calibration's; 0 when neither says.
    """

    section: CrossSection
    sigma_m: float
    beam_spacing: float
    beam_width: float

    def candidate_widths(self, spacings: tuple[float, ...]) -> tuple[float, ...]:
        """The beam width if known; else those multiples of the beam spacing (or none: rays)."""
        if self.beam_width > 0.0:
            return (self.beam_width,)
        return tuple(factor * self.beam_spacing for factor in spacings) if self.beam_spacing > 0.0 else (0.0,)


def ellipse_model(params: DetectorParams, facts: SensorFacts) -> PipeLikelihood:
    """Eq. (1) with the ellipse through two consecutive points (:mod:`trackbench_sonar.likelihood`)."""
    return PipeLikelihood(
        facts.section,
        facts.sigma_m,
        float(params.proud_weight),
        params.flank_widths * facts.section.major_m,
        float(params.fit_span),
        facts.beam_spacing,
        float(params.min_pipe_returns),
    )


def footprint_model(params: DetectorParams, facts: SensorFacts) -> FootprintLikelihood | WidestEvidence:
    """Eq. (1) with the cross-section as the beams see it, as evidence (:mod:`trackbench_sonar.evidence`).

    When neither the parameters nor the calibration give the beam width, one
    model per width of ``unknown_width_spacings`` (in beam spacings), of
    which each ping keeps the best (:class:`~trackbench_sonar.evidence.WidestEvidence`).
    """
    models = tuple(
        FootprintLikelihood(
            facts.section,
            facts.sigma_m,
            width,
            float(params.seabed_widths),
            float(params.relief_widths),
            float(params.robust_sigmas),
        )
        for width in facts.candidate_widths(tuple(params.unknown_width_spacings))
    )
    return models[0] if len(models) == 1 else WidestEvidence(models)


LIKELIHOODS: dict[str, Callable[[DetectorParams, SensorFacts], ScanModel]] = {
    "ellipse": ellipse_model,
    "footprint": footprint_model,
}
"""The forms of eq. (1) by the name the parameter ``likelihood`` gives."""


@dataclass(frozen=True)
class SwathDetector:
    """Resample a swath and compute its pipe likelihood scan.

    Attributes
    ----------
    likelihood : ScanModel
        Eq. (1) for the sequence's pipe.
    grid_m : float
        Spacing of the resampled profile.
    spike_window : int
        Returns in the running median of the spike test.
    spike_m : float
        Spike threshold in m (``inf``: no test).
    min_beams : int
        Fewest returns for a scan.
    tracker : str
        Name used in error messages.

    References
    ----------
    seeds/003, section 2, eq. (1) and Fig. 2.
    """

    likelihood: ScanModel
    grid_m: float
    spike_window: int
    spike_m: float
    min_beams: int
    tracker: str

    @classmethod
    def for_sequence(cls, params: DetectorParams, info: SequenceInfo, tracker: str) -> SwathDetector:
        """Set the detector up for a sequence.

        Parameters
        ----------
        params : DetectorParams
            The tracker's parameters.
        info : SequenceInfo
            Its ``calibration`` should be a SonarCalibration: the pipe's
            diameter gives the axes left at 0 and its range sigma joins
            ``model_sigma_m`` in L1's scale.
        tracker : str
            Tracker name for error messages.

        Raises
        ------
        DataError
            If an axis is left at 0 and the sequence has no SonarCalibration
            with a positive pipe diameter.
        """
        calibration = info.calibration if isinstance(info.calibration, SonarCalibration) else None
        diameter = float(calibration.pipe_diameter_m) if calibration is not None else math.nan
        major = params.major_axis_m or diameter
        minor = params.minor_axis_m or diameter
        if not (0.0 < major < math.inf and 0.0 < minor < math.inf):
            raise DataError(
                f"{tracker}: sequence {info.name!r} has no SonarCalibration with a positive pipe diameter "
                f"(calibration {info.calibration!r}); set the parameters major_axis_m and minor_axis_m"
            )
        range_sigma = float(calibration.range_sigma_m) if calibration is not None else 0.0
        if not 0.0 <= range_sigma < math.inf:
            raise DataError(f"{tracker}: sequence {info.name!r} has an invalid range_sigma_m {range_sigma!r}")
        sigma = math.hypot(range_sigma, params.model_sigma_m)
        if not sigma > 0.0:
            raise DataError(
                f"{tracker}: sequence {info.name!r}: range_sigma_m and model_sigma_m are both 0; L1 needs a scale"
            )
        section = CrossSection(major, minor)
        spacing = float(calibration.beam_spacing) if calibration is not None else 0.0
        spacing = spacing if 0.0 < spacing < math.pi else 0.0
        width = math.radians(params.beam_width_deg)
        if width <= 0.0 and calibration is not None and 0.0 < calibration.beam_width < math.pi:
            width = float(calibration.beam_width)
        facts = SensorFacts(section, sigma, spacing, width)
        likelihood = LIKELIHOODS[params.likelihood](params, facts)
        spike_m = params.spike_heights * minor if params.spike_heights > 0 else math.inf
        grid = min(float(params.grid_m), major / GRID_PER_PIPE)
        return cls(likelihood, grid, params.spike_window, spike_m, params.min_beams, tracker)

    def read(self, frame: SonarFrame) -> Swath:
        """The frame's swath.

        Raises
        ------
        DataError
            If the observation is not a Swath; the message names the tracker
            and the frame.
        """
        swath = frame.observation
        if not isinstance(swath, Swath):
            raise DataError(
                f"{self.tracker}: frame {frame.index}: observation is a {type(swath).__name__}, expected a Swath"
            )
        return swath

    def profile(self, swath: Swath, index: int) -> Profile:
        """The swath cleaned and resampled (:func:`trackbench_sonar.profile.resample_swath`).

        Raises
        ------
        DataError
            If the returns span an impossible across-track extent; names the
            tracker and the frame ``index``.
        """
        try:
            return resample_swath(
                swath, self.grid_m, spike_window=self.spike_window, spike_m=self.spike_m, min_beams=self.min_beams
            )
        except DataError as exc:
            raise DataError(f"{self.tracker}: frame {index}: {exc}") from exc

    def scan(self, frame: SonarFrame) -> tuple[Profile, Scan]:
        """The frame's resampled profile and its likelihood scan (empty without enough returns).

        Raises
        ------
        DataError
            For an observation that is not a usable Swath, naming the frame.
        """
        profile = self.profile(self.read(frame), frame.index)
        return profile, self.likelihood.scan(profile)


class ScanTracker(Tracker[SonarTruth, PipeEstimate]):
    """A sonar tracker that sees each ping through its likelihood scan.

    Subclasses set ``name``, ``version`` and ``Params`` (a subclass of
    :class:`DetectorParams`, whose fields declare their domains) and call
    :meth:`scan` in their ``step``.

    Attributes
    ----------
    last_scan : Scan or None
        The likelihood scan of the last ping.
    """

    modality = "sonar"

    def __init__(self, params: DetectorParams | None = None) -> None:
        super().__init__(params)
        self._detector: SwathDetector | None = None
        self.last_scan: Scan | None = None

    def reset(self, info: SequenceInfo, rng: np.random.Generator, init: SonarTruth | None = None) -> None:
        """Set the detector up for the sequence's pipe and sonar.

        Raises
        ------
        DataError
            If the pipe's dimensions are neither in the calibration nor in
            the parameters.
        """
        self._detector = SwathDetector.for_sequence(self.params, info, self.name)
        self.last_scan = None

    @property
    def detector(self) -> SwathDetector:
        """The detector set up by :meth:`reset`.

        Raises
        ------
        RuntimeError
            Before :meth:`reset`.
        """
        if self._detector is None:
            raise RuntimeError(f"{self.name}: step() called before reset()")
        return self._detector

    def scan(self, frame: SonarFrame) -> tuple[Profile, Scan]:
        """The frame's resampled profile and likelihood scan, kept as :attr:`last_scan`.

        Raises
        ------
        DataError
            If the observation is not a Swath (the message names the frame).
        RuntimeError
            Before :meth:`reset`.
        """
        profile, self.last_scan = self.detector.scan(frame)
        return profile, self.last_scan
