"""trackbench_texture: the texture tracker of Grau et al. (seeds/000, section 2.2).

Five texture descriptors measured around every pixel (straightness,
abruptness, discontinuity, granularity, blurriness) are classified into the
region classes Grau et al. learned from labelled images (cable, sand, stones
and vegetation, undefined), and the cable's two borders are fitted to the
cable region.  It is the benchmark's first tracker that learns: it has
:meth:`~trackbench_texture.tracker.TextureTracker.fit` and
:meth:`~trackbench_texture.tracker.TextureTracker.use_model`
(:class:`benchmark.tracker.Learns`).

The plugin registers one tracker, ``texture`` (:class:`TextureTracker`),
through the same ``trackbench`` entry-point group every third-party tracker
uses::

    [project.entry-points.trackbench]
    texture = "trackbench_texture"
"""

from benchmark import Registry, hookimpl
from trackbench_texture.model import TextureModel
from trackbench_texture.params import TextureParams
from trackbench_texture.tracker import TextureTracker

__all__ = ["TextureModel", "TextureParams", "TextureTracker", "trackbench_register_trackers"]


@hookimpl
def trackbench_register_trackers(registry: Registry) -> None:
    """Register the texture tracker."""
    registry.add_tracker(TextureTracker)
