"""Simulators that render the shared synthetic datasets.

The camera simulator follows the scene model of Foresti (seeds/004,
section II): a pinhole camera on a vehicle that moves over a seabed plane,
and a pipe or cable, a cylinder of known diameter, lying on it.  Every
frame is ray-cast from that 3-D model, so its ground truth is exact: the
camera pose, the vehicle speeds of eq. (7), the projected cable state
``(d, alpha, w, beta)`` of the thesis (seeds/000, section 4.2) and the share
of the cable that sand leaves visible.

Modules, from the geometry up:

* :mod:`~benchmark.scenes.projection`: camera versors, the matrix ``T`` of
  eqs. (1)-(3), projection and per-pixel rays;
* :mod:`~benchmark.scenes.silhouette`: the pipe's occluding contours and
  the cable state they give;
* :mod:`~benchmark.scenes.motion`: trajectories and the speeds of eq. (7);
* :mod:`~benchmark.scenes.texture`: seabed and pipe albedo maps;
* :mod:`~benchmark.scenes.burial`: sand over the pipe, visible fraction;
* :mod:`~benchmark.scenes.overgrowth`: algae and stones on the pipe and
  against its sides, drawn over its borders;
* :mod:`~benchmark.scenes.render`: the per-frame ray caster;
* :mod:`~benchmark.scenes.spec`: sequence definitions as data;
* :mod:`~benchmark.scenes.camera_scene`: :class:`CameraScene`, the
  :class:`benchmark.model.Sequence` that ties them together.
"""

from benchmark.scenes.camera_scene import CameraScene
from benchmark.scenes.projection import camera_axes, project_points, projection_matrix
from benchmark.scenes.silhouette import cable_truth, silhouette_borders
from benchmark.scenes.spec import CameraSceneSpec

__all__ = [
    "CameraScene",
    "CameraSceneSpec",
    "cable_truth",
    "camera_axes",
    "project_points",
    "projection_matrix",
    "silhouette_borders",
]
