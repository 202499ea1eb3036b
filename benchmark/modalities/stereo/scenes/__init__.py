"""Simulated stereo sequences: measurements and image pairs.

**Stereo** (the ``stereo`` suite).  The simulations of Sinisterra et al.
(seeds/002, section 3): a chase boat (CH) with a stereo camera follows a
target boat (TG); each frame holds what the stereo front end measures of
TG (pixel coordinates with the noise of eq. 19, triangulated by eq. 15),
CH's noisy GPS and compass, and TG's true position and velocity.  The
camera geometry (eqs. 10-11 and 15, the field of view) is :mod:`benchmark.modalities.stereo.geometry`,
shared with the trackers.  Modules:

* :mod:`~benchmark.modalities.stereo.scenes.spec`: sequence definitions as data
  (paths, speed profiles, the camera of Tables 3-4, sensor errors);
* :mod:`~benchmark.modalities.stereo.scenes.motion`: boat tracks and where TG is seen
  from CH;
* :mod:`~benchmark.modalities.stereo.scenes.sensors`: the simulated front end, GPS
  and compass, with their errors and dropouts;
* :mod:`~benchmark.modalities.stereo.scenes.scene`: :class:`StereoScene`.

**Stereo images** (the ``stereo-images`` suite).  The same boats, with the
same truth and navigation, seen by the camera instead of measured
(seeds/002, section 4.1): each frame is a pair of BGR images in which a
tracker has to find TG's yellow marker and its disparity.  Modules:

* :mod:`~benchmark.modalities.stereo.scenes.image_spec`: a stereo spec plus the look
  of the scene;
* :mod:`~benchmark.modalities.stereo.scenes.world`: the sea's wave field and the
  shoreline;
* :mod:`~benchmark.modalities.stereo.scenes.boat`: TG's hull, cabin and marker, and
  how they are drawn;
* :mod:`~benchmark.modalities.stereo.scenes.render`: one image pair at a time;
* :mod:`~benchmark.modalities.stereo.scenes.images`: :class:`StereoImageScene`.
"""
