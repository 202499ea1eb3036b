"""Camera data on disk: image sequence files, image folders, videos, and the exporter.

Researchers bring their own labelled sequences in the thesis' image
sequence file format (seeds/000, section 4.7.3; ``conventions.md``
section 2): a text file listing, per frame, the ground-truth cable state
``d alpha w beta`` and the image it belongs to.  The thesis' program also
runs on a bare set of images, and its test data were videos.  Each of
these becomes a lazy, picklable :class:`~benchmark.model.Sequence`:

* :class:`~benchmark.modalities.camera.io.sequence_file.ImageSequenceFile`:
  an image sequence file, with ground truth;
* :class:`~benchmark.modalities.camera.io.image_folder.ImageFolder`: every
  image in a folder, in natural order;
* :class:`~benchmark.modalities.camera.io.video.VideoFile`: the frames of a
  video OpenCV decodes.

Each may carry a sidecar, ``S.toml`` beside ``S.txt``
(:mod:`~benchmark.modalities.camera.io.sidecar`): the camera calibration,
the frame interval and each frame's navigation, which the thesis' format
has no place for.

:mod:`~benchmark.modalities.camera.io.export` writes any camera sequence
as PNG images plus a sequence file.  Frames are decoded one at a time while
a sequence is iterated; a missing, corrupt or malformed input raises
:class:`~benchmark.errors.DataError` naming the file, and the line of a
sequence file where there is one.
"""
