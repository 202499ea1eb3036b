"""Simulated camera sequences.

**Camera** (the ``camera`` suite).  The scene model of Foresti (seeds/004,
section II): a pinhole camera on a vehicle that moves over a seabed plane,
and a pipe or cable, a cylinder of known diameter, lying on it.  Every
frame is ray-cast from that 3-D model, so its ground truth is exact: the
camera pose, the vehicle speeds of eq. (7), the projected cable state
``(d, alpha, w, beta)`` of the thesis (seeds/000, section 4.2) and the
share of the cable that sand leaves visible.  Modules, from the geometry up:

* :mod:`~benchmark.modalities.camera.scenes.projection`: camera versors, the matrix ``T`` of
  eqs. (1)-(3), projection and per-pixel rays;
* :mod:`~benchmark.modalities.camera.scenes.silhouette`: the pipe's occluding contours and
  the cable state they give;
* :mod:`~benchmark.modalities.camera.scenes.motion`: trajectories and the speeds of eq. (7);
* :mod:`~benchmark.modalities.camera.scenes.texture`: seabed and pipe albedo maps;
* :mod:`~benchmark.modalities.camera.scenes.burial`: sand over the pipe, visible fraction;
* :mod:`~benchmark.modalities.camera.scenes.overgrowth`: algae and stones on the pipe and
  against its sides, drawn over its borders;
* :mod:`~benchmark.modalities.camera.scenes.render`: the per-frame ray caster;
* :mod:`~benchmark.modalities.camera.scenes.spec`: sequence definitions as data;
* :mod:`~benchmark.modalities.camera.scenes.scene`: :class:`CameraScene`.
"""
