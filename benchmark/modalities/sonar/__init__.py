"""The sonar modality: multibeam echo-sounder swaths over a pipe (seeds/003).

* :mod:`~benchmark.modalities.sonar.model`: swaths, the pipe's truth, the
  beam footprint, a tracker's estimate;
* :mod:`~benchmark.modalities.sonar.scoring`: a ping is correct within one
  beam spacing at the pipe;
* :mod:`~benchmark.modalities.sonar.io`: swath files, read and written;
* :mod:`~benchmark.modalities.sonar.scenes`: the simulated sonar scenes;
* :mod:`~benchmark.modalities.sonar.modality`: the modality as registered.
"""
