"""Simulators that render the shared synthetic datasets.

Every simulated sequence is a :class:`~benchmark.scenes.scene.SimulatedScene`:
a :class:`benchmark.model.Sequence` defined by a spec (frozen dataclasses
built from plain data, so suites are TOML files), seed included, that
computes what it needs on first use, draws every random number from
independent streams of that seed, and renders any frame on its own.  The
same spec gives bit-identical frames, and a pickled scene is only its spec.

Four kinds of scene share that scaffolding.

**Camera** (the ``camera`` suite).  The scene model of Foresti (seeds/004,
section II): a pinhole camera on a vehicle that moves over a seabed plane,
and a pipe or cable, a cylinder of known diameter, lying on it.  Every
frame is ray-cast from that 3-D model, so its ground truth is exact: the
camera pose, the vehicle speeds of eq. (7), the projected cable state
``(d, alpha, w, beta)`` of the thesis (seeds/000, section 4.2) and the
share of the cable that sand leaves visible.  Modules, from the geometry up:

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
* :mod:`~benchmark.scenes.camera_scene`: :class:`CameraScene`.

**Stereo** (the ``stereo`` suite).  The simulations of Sinisterra et al.
(seeds/002, section 3): a chase boat (CH) with a stereo camera follows a
target boat (TG); each frame holds what the stereo front end measures of
TG (pixel coordinates with the noise of eq. 19, triangulated by eq. 15),
CH's noisy GPS and compass, and TG's true position and velocity.  The
camera geometry (eqs. 10-11 and 15) is :mod:`benchmark.stereo_geometry`,
shared with the trackers.  Modules:

* :mod:`~benchmark.scenes.stereo_spec`: sequence definitions as data
  (paths, speed profiles, the camera of Tables 3-4, sensor errors);
* :mod:`~benchmark.scenes.stereo_motion`: boat tracks and where TG is seen
  from CH;
* :mod:`~benchmark.scenes.stereo_projection`: the camera's field of view
  and the depth accuracy of Table 3;
* :mod:`~benchmark.scenes.stereo_sensors`: the simulated front end, GPS
  and compass, with their errors and dropouts;
* :mod:`~benchmark.scenes.stereo_scene`: :class:`StereoScene`.

**Stereo images** (the ``stereo-images`` suite).  The same boats, with the
same truth and navigation, seen by the camera instead of measured
(seeds/002, section 4.1): each frame is a pair of BGR images in which a
tracker has to find TG's yellow marker and its disparity.  Modules:

* :mod:`~benchmark.scenes.stereo_image_spec`: a stereo spec plus the look
  of the scene;
* :mod:`~benchmark.scenes.stereo_world`: the sea's wave field and the
  shoreline;
* :mod:`~benchmark.scenes.stereo_boat`: TG's hull, cabin and marker, and
  how they are drawn;
* :mod:`~benchmark.scenes.stereo_render`: one image pair at a time;
* :mod:`~benchmark.scenes.stereo_images`: :class:`StereoImageScene`.

**Sonar** (the ``sonar`` suite).  The multibeam echo-sounder data of Tena
Ruiz et al. (seeds/003, section 4): a vehicle runs along a pipe and its
sonar measures one swath of equiangular beams across the track per ping.
Each frame holds the swath (across-track positions and depths of the
returns, with range noise, spikes and missing beams) and the first pipe's
axis position, depth, burial and the beam spacing there.  The seabed has
slope, roughness correlated from ping to ping, ripples, trenches with spoil
heaps and boulders; a second pipe may lie nearby.  Modules:

* :mod:`~benchmark.scenes.sonar_spec`: sequence definitions as data (the
  sonar, the vehicle, the seabed, the pipes);
* :mod:`~benchmark.scenes.sonar_seabed`: the seabed as a grid of depths
  over (ping, across-track position);
* :mod:`~benchmark.scenes.sonar_pipes`: where each pipe lies, how deep and
  how buried;
* :mod:`~benchmark.scenes.sonar_swath`: beams cast on seabed and pipes,
  and the sonar's errors;
* :mod:`~benchmark.scenes.sonar_scene`: :class:`SonarScene`.
"""

from benchmark.scenes.camera_scene import CameraScene
from benchmark.scenes.projection import camera_axes, project_points, projection_matrix
from benchmark.scenes.scene import SimulatedScene
from benchmark.scenes.silhouette import cable_truth, silhouette_borders
from benchmark.scenes.sonar_scene import SonarScene
from benchmark.scenes.sonar_spec import SonarSceneSpec
from benchmark.scenes.spec import CameraSceneSpec
from benchmark.scenes.stereo_image_spec import StereoImageSceneSpec
from benchmark.scenes.stereo_images import StereoImageScene
from benchmark.scenes.stereo_scene import StereoScene
from benchmark.scenes.stereo_spec import StereoSceneSpec

__all__ = [
    "CameraScene",
    "CameraSceneSpec",
    "SimulatedScene",
    "SonarScene",
    "SonarSceneSpec",
    "StereoImageScene",
    "StereoImageSceneSpec",
    "StereoScene",
    "StereoSceneSpec",
    "cable_truth",
    "camera_axes",
    "project_points",
    "projection_matrix",
    "silhouette_borders",
]
