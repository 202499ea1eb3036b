"""trackbench_texture: the texture tracker of Grau et al. (seeds/000, section 2.2).

Five texture descriptors measured around every pixel (straightness,
abruptness, discontinuity, granularity, blurriness) are classified into the
region classes Grau et al. learned from labelled images (cable, sand, stones
and vegetation, undefined), and the cable's two borders are fitted to the
cable region.  It is the benchmark's first tracker that learns: it has
:meth:`~trackbench_texture.tracker.TextureTracker.fit` and
:meth:`~trackbench_texture.tracker.TextureTracker.use_model`
(:class:`benchmark.tracker.Learns`).

The plugin registers two trackers, one class with different parameters,
through the same ``trackbench`` entry-point group every third-party tracker
uses::

    [project.entry-points.trackbench]
    texture = "trackbench_texture"

* ``texture``: the descriptors measured on a working image of fixed height
  with normalised grey levels, so that a model learned on frames of one
  size, exposure and contrast applies to others, and the borders read as a
  parallel pair anywhere in the cable region
  (:mod:`trackbench_texture.params` argues each departure);
* ``texture-paper``: the reading for one camera, as Grau et al. learned and
  used their classes: masks in the frame's own pixels, thresholds in its own
  grey levels, the borders on either side of the cable strip.
"""

from benchmark import Registry, hookimpl
from trackbench_texture.model import TextureModel
from trackbench_texture.params import PAPER, TextureParams
from trackbench_texture.tracker import TextureTracker

__all__ = ["VARIANTS", "TextureModel", "TextureParams", "TextureTracker", "trackbench_register_trackers"]

VARIANTS: dict[str, dict[str, object]] = {"texture-paper": PAPER}
"""Registered variants of :class:`TextureTracker` and their parameter overrides."""


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the texture tracker and its variants."""
    registry.add_tracker(TextureTracker)
    for name, params in VARIANTS.items():
        registry.add_tracker(TextureTracker, name=name, params=params)
