"""The built-in modalities: everything that is only about one kind of sensor.

Each folder holds one modality, and nothing outside this package knows any
of them by name:

* :mod:`~benchmark.modalities.camera`: grey images of a cable or pipe on
  the seabed (seeds/000, seeds/004): the cable model and its geometry, the
  line-pair scoring rule, image sequence files, image folders and videos,
  and the rendered camera scenes;
* :mod:`~benchmark.modalities.sonar`: multibeam echo-sounder swaths over a
  pipe (seeds/003): swaths and the beam footprint, scoring against the
  sonar's resolution, swath files, and the simulated sonar scenes;
* :mod:`~benchmark.modalities.stereo`: a stereo camera on a chase boat
  measuring a target boat (seeds/002): the stereo geometry, scoring, the
  image-pair front end that stereo trackers share, and the chase scenes
  with their images.

Each folder's ``modality`` module declares its
:class:`~benchmark.modality.Modality` and registers it through the
``trackbench_register_modalities`` hook, under an entry point of the
``trackbench`` group (``modality-camera``, ...), as a third-party sensor
would.  A new sensor is a new folder here, or a plugin of its own.
"""
