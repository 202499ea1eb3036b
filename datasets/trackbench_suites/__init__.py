"""trackbench_suites: the shared synthetic suites, as a trackbench plugin.

The suites are data: one TOML file per suite next to this module
(``camera.toml`` defines the ``camera`` suite), parsed by
:mod:`trackbench_suites.loader`.  The plugin registers every suite through
the same ``trackbench`` entry-point group every third-party plugin uses::

    [project.entry-points.trackbench]
    suites = "trackbench_suites"

The ``camera`` suite holds nine rendered sequences.  ``camera/S1`` to
``camera/S6`` are modelled on the thesis' test sequences (seeds/000,
section 5.2.3 and appendix A: their lengths, the motion that makes each
hard, and the frame-to-frame variances of Tables 4.2 and 4.3),
``camera/S1b`` and ``camera/S1c`` are S1 with other draws of its clutter,
and ``camera/S7`` is modelled on Foresti's pipeline under sand (seeds/004,
Fig. 14).

The ``camera-clutter`` suite (``camera_clutter.toml``) is S1's clutter
family: ``camera-clutter/S1-d01`` to ``S1-d10`` are ``based_on``
``camera/S1`` with ten more seeds (3101, 4101, ..., 12101, continuing S1b
and S1c), fixed before any tracker ran on them.

The camera world (``worlds/camera.toml``) declares the ranges the wide
camera splits are drawn from: Jerlov water type, lamps and daylight, cable
polarity and seabed, altitude, tilt and motion, frame size, sensor noise and
JPEG quality, rendered through the image formation model of
:mod:`benchmark.modalities.camera.scenes.water`.  ``camera-train``
(``camera_train.toml``, not scored) holds S1-S7 with other seeds and 24
sequences of the world (``w01``-``w24``); ``camera-dev`` holds 48 and
``camera-test`` 48 more, with seeds of their own, the test seeds written
before any tracker ran on them.  Thresholds and models are fitted on
``camera-train``, defaults chosen on ``camera-dev``; ``camera-test`` is
scored to publish, never to choose.

The ``stereo`` suite (``stereo.toml``) holds nine simulated chase-boat
sequences, ``stereo/case1-slow`` to ``stereo/case3-fast``: the three
trajectory cases of seeds/002, section 3 (case 1 both boats straight,
case 2 the target sinusoidal, case 3 both sinusoidal), each at three
speeds (the target's top speed 3.6, 7 or 9 m/s).  A frame holds the stereo
front end's measurement of the target boat, or None when it lost it
(:class:`benchmark.modalities.stereo.scenes.scene.StereoScene`).

The ``stereo-images`` suite (``stereo_images.toml``) holds three rendered
sequences, ``stereo-images/case1-medium`` to ``case3-medium``: each is
``based_on`` the ``stereo`` sequence of the same name (same paths, speeds,
seed, so the same truth and navigation errors), but a frame holds the
camera's pair of BGR images instead of a measurement, in which a tracker
finds the target's yellow marker and its disparity itself, as the field
system of seeds/002, section 4.1 did (:class:`benchmark.modalities.stereo.scenes.images.StereoImageScene`).

The ``sonar`` suite (``sonar.toml``) holds four simulated multibeam
echo-sounder sequences modelled on the data of seeds/003, section 4:
``sonar/autotracker`` (an EM2000-like sonar over a 0.9 m pipe),
``sonar/as-laid`` and ``sonar/concrete`` (RESON 8125-like, a pipe as laid
and a concrete-coated section), and ``sonar/second-pipe``, with a second
pipe laid nearby to tempt a tracker away.  A frame holds one swath
(:class:`benchmark.modalities.sonar.scenes.scene.SonarScene`).

The splits ``sonar-train`` (never scored by default), ``sonar-dev`` and
``sonar-test`` (``sonar_train.toml`` ...) hold sequences of a few hundred
pings drawn from one world, ``worlds/sonar-wide.toml``: 128-400 beams over
90-150 deg, beams 0.5-3 deg wide, 5-30 m altitude, pipes whose diameter a
beam's footprint often reaches half of or exceeds, rough bare seabed,
trenches with spoil berms, sand waves whose troughs the pipe spans, and a
smooth cross-track drift of up to 1.2 m/s.  Each split lists only names and
seeds; the test split's seeds were fixed before any tracker ran on it.

Each suite file names its scene kind, one of those the registered
modalities declare (``camera``, ``sonar``, ``stereo``, ``stereo-images``),
a sequence may start from a sequence of another shipped suite
(``based_on``), and splits may share a world's declared ranges
(``world = "<name>"``); see :mod:`trackbench_suites.loader`.
"""

from benchmark import Registry, hookimpl
from benchmark.errors import DataError
from trackbench_suites.loader import SuiteDefinition, load_suites, parse_suite, shipped_table, suite_files

__all__ = ["SuiteDefinition", "load_suites", "parse_suite", "shipped_table", "trackbench_register_datasets"]


@hookimpl
def trackbench_register_datasets(registry: Registry) -> None:
    """Register every suite defined by a TOML file of this package; an invalid file costs only its suite."""
    for item in suite_files():
        try:
            suite = parse_suite(item.read_text(encoding="utf-8"), item.name, registry.scene_kinds)
        except DataError as exc:
            registry.add_problem(f"{exc} (suite left out)")
            continue
        registry.add_suite(suite.name, suite.sequences, training=suite.training, scored=suite.scored)
