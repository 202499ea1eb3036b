"""The stereo modality: a stereo camera on a chase boat measuring a target boat (seeds/002).

* :mod:`~benchmark.modalities.stereo.model`: measurements, the chase boat's
  navigation, the target's truth and a tracker's estimate;
* :mod:`~benchmark.modalities.stereo.geometry`: triangulation, projection,
  the North-East frame, the field of view and the depth accuracy;
* :mod:`~benchmark.modalities.stereo.scoring`: position, speed and heading
  errors;
* :mod:`~benchmark.modalities.stereo.frontend`: the image pair to
  measurement front end of the field system (section 4.1), and
  :mod:`~benchmark.modalities.stereo.observation`, which every stereo
  tracker reads a frame through;
* :mod:`~benchmark.modalities.stereo.scenes`: the simulated chases, as
  measurements and as image pairs;
* :mod:`~benchmark.modalities.stereo.modality`: the modality as registered.
"""
