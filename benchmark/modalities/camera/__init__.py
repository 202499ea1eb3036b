"""The camera modality: grey images of a cable or pipe on the seabed.

* :mod:`~benchmark.modalities.camera.model`: the cable state ``(d, alpha, w,
  beta)`` of seeds/000 section 4.2, the camera pose and the frame's truth;
* :mod:`~benchmark.modalities.camera.geometry`: border lines of a cable
  state and the line-pair detection rule (seeds/004, section VI-C);
* :mod:`~benchmark.modalities.camera.scoring`: the scorer built on that rule;
* :mod:`~benchmark.modalities.camera.io`: image sequence files, image
  folders, videos, and the exporter;
* :mod:`~benchmark.modalities.camera.scenes`: the rendered camera scenes;
* :mod:`~benchmark.modalities.camera.modality`: the modality as registered;
* :mod:`~benchmark.modalities.camera.commands`: its commands ``trackbench
  diagnose`` (:mod:`~benchmark.modalities.camera.diagnostics`) and
  ``trackbench pose-table`` (:mod:`~benchmark.modalities.camera.pose_table`),
  added through the ``trackbench_register_commands`` hook.
"""
