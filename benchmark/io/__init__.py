"""Readers and writers for camera and sonar data.

Researchers bring their own labelled sequences in the thesis' image sequence
file format (seeds/000, section 4.7.3; ``conventions.md`` section 2): a text
file listing, per frame, the ground-truth cable state ``d alpha w beta`` and
the image it belongs to.  The thesis' program also runs on a bare set of
images, and its test data were videos.  This package turns each of these
into a lazy, picklable :class:`~benchmark.model.Sequence`:

* :class:`ImageSequenceFile` -- an image sequence file, with ground truth;
* :class:`ImageFolder` -- every image in a folder, in natural order;
* :class:`VideoFile` -- the frames of a video OpenCV decodes;
* :class:`SwathFile` -- multibeam sonar pings with ground truth, one per
  line (seeds/003; :mod:`benchmark.io.swath_file`).

:func:`open_sequence` picks the right one for a path, which is how
``trackbench run --dataset PATH`` reads a dataset made anywhere else.  In
the other direction, :func:`write_sequence_file` writes the format and
:func:`export_sequence` writes any camera sequence (a rendered scene, say)
as PNG images plus a sequence file (any sonar sequence as a swath file),
so that it can be used elsewhere.

Frames are decoded one at a time while a sequence is iterated.  A missing,
corrupt or malformed input raises :class:`~benchmark.errors.DataError`
naming the file, and the line of a sequence file where there is one.
"""

from __future__ import annotations

import os
from pathlib import Path

from benchmark.errors import DataError
from benchmark.io.export import export_sequence
from benchmark.io.image_folder import ImageFolder
from benchmark.io.images import IMAGE_EXTENSIONS
from benchmark.io.sequence_file import (
    HEADER,
    ImageSequenceFile,
    SequenceRow,
    read_sequence_file,
    write_sequence_file,
)
from benchmark.io.swath_file import SWATH_SUFFIX, SwathFile, write_swath_file
from benchmark.io.video import VIDEO_EXTENSIONS, VideoFile
from benchmark.model import Sequence


def open_sequence(path: str | os.PathLike[str]) -> Sequence:
    """Open a camera or sonar dataset by its path.

    Parameters
    ----------
    path : str or path-like
        A folder of images (:class:`ImageFolder`), a video whose name ends
        in one of :data:`VIDEO_EXTENSIONS` (:class:`VideoFile`), a swath
        file whose name ends in :data:`SWATH_SUFFIX` (:class:`SwathFile`), or else an
        image sequence file of any name (:class:`ImageSequenceFile`; the
        thesis' files end in ``.txt``, ``.seq`` and more).

    Returns
    -------
    Sequence
        The opened sequence; images are decoded only while it is iterated.

    Raises
    ------
    DataError
        If nothing exists at ``path``, or the reader chosen for it rejects it.

    References
    ----------
    seeds/000, section 4.7.3; ``conventions.md`` section 2.
    """
    target = Path(path)
    if target.is_dir():
        return ImageFolder(path)
    if not target.exists():
        raise DataError(
            f"{target}: no such dataset (expected an image sequence file, an image folder, a video or a swath file)"
        )
    if target.suffix.lower() in VIDEO_EXTENSIONS:
        return VideoFile(path)
    if target.suffix.lower() == SWATH_SUFFIX:
        return SwathFile(path)
    return ImageSequenceFile(path)


__all__ = [
    "HEADER",
    "IMAGE_EXTENSIONS",
    "VIDEO_EXTENSIONS",
    "ImageFolder",
    "ImageSequenceFile",
    "SWATH_SUFFIX",
    "SequenceRow",
    "SwathFile",
    "VideoFile",
    "export_sequence",
    "open_sequence",
    "read_sequence_file",
    "write_sequence_file",
    "write_swath_file",
]
