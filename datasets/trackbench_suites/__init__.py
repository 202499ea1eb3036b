"""trackbench_suites: the shared synthetic suites, as a trackbench plugin.

The suites are data: one TOML file per suite next to this module
(``camera.toml`` defines the ``camera`` suite), parsed by
:mod:`trackbench_suites.loader`.  The plugin registers every suite through
the same ``trackbench`` entry-point group every third-party plugin uses::

    [project.entry-points.trackbench]
    suites = "trackbench_suites"

The ``camera`` suite holds seven rendered sequences.  ``camera/S1`` to
``camera/S6`` are modelled on the thesis' test sequences (seeds/000,
section 5.2.3 and appendix A: their lengths, the motion that makes each
hard, and the frame-to-frame variances of Tables 4.2 and 4.3), and
``camera/S7`` on Foresti's pipeline under sand (seeds/004, Fig. 14).

The ``stereo`` suite (``stereo.toml``) holds nine simulated chase-boat
sequences, ``stereo/case1-slow`` to ``stereo/case3-fast``: the three
trajectory cases of seeds/002, section 3, each at three speeds.
"""

from benchmark import Registry, hookimpl
from trackbench_suites.loader import SCENE_KINDS, load_suites, parse_suite

__all__ = ["SCENE_KINDS", "load_suites", "parse_suite", "trackbench_register_datasets"]


@hookimpl
def trackbench_register_datasets(registry: Registry) -> None:
    """Register every suite defined by a TOML file of this package."""
    for name, sequences in load_suites():
        registry.add_suite(name, sequences)
