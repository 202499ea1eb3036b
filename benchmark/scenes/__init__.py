"""The shared core of the simulators that render the synthetic datasets.

Every simulated sequence is a :class:`~benchmark.scenes.scene.SimulatedScene`:
a :class:`benchmark.model.Sequence` defined by a spec (frozen pydantic
dataclasses that declare their ranges, built from plain data, so suites are
TOML files), seed included, that
computes what it needs on first use, draws every random number from
independent streams of that seed, and renders any frame on its own.  The
same spec gives bit-identical frames, and a pickled scene is only its spec.

This package holds only what the scenes of every modality share:

* :mod:`~benchmark.scenes.scene`: :class:`SimulatedScene`, the scaffolding;
* :mod:`~benchmark.scenes.spec`: :class:`~benchmark.scenes.spec.TableSpec`,
  specs built from and turned back into plain data, the vocabulary their
  fields declare their ranges with, and the errors that name file, key
  and rule;
* :mod:`~benchmark.scenes.signal`: quantities that vary from frame to frame
  (a vehicle's pose, a sonar's altitude), defined as data;
* :mod:`~benchmark.scenes.noise`: smoothed Gaussian noise and a fast table
  of normal quantiles.

The scenes themselves belong to their modality: the camera's in
:mod:`benchmark.modalities.camera.scenes`, the sonar's in
:mod:`benchmark.modalities.sonar.scenes`, the stereo camera's in
:mod:`benchmark.modalities.stereo.scenes`.  Each modality names the scene
kinds a suite file may use (:attr:`benchmark.modality.Modality.scene_kinds`).
"""
