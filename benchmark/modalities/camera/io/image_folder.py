"""A folder of images as an unlabelled camera sequence.

The thesis' tracking program runs on "a set of single images" as well as on
image sequence files, and then has no ground truth (seeds/000, section
4.7.3).  :class:`ImageFolder` is that input: every file in one folder whose
name ends in an image format OpenCV reads
(:data:`benchmark.modalities.camera.io.images.IMAGE_EXTENSIONS`, any letter case), in natural
order, so that ``frame2.png`` comes before ``frame10.png``.  Sub-folders are
not searched.  Every frame's truth is
:data:`benchmark.modalities.camera.model.UNKNOWN_CABLE`.

The folder's identity is its resolved path and the names, sizes and
modification times of its images; other files may come and go.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from benchmark.errors import DataError
from benchmark.modalities.camera.io.image_list import ImageListSequence
from benchmark.modalities.camera.io.images import IMAGE_EXTENSIONS, is_image_name
from benchmark.modalities.camera.io.sidecar import read_sidecar
from benchmark.modalities.camera.model import UNKNOWN_CABLE

_DIGITS = re.compile(r"(\d+)")


def natural_key(name: str) -> tuple[tuple[object, ...], str]:
    """Sort key that orders runs of digits by their value: ``a2 < a10``.

    Text runs compare without letter case; the name itself breaks ties, so
    the order is total and does not depend on the file system.
    """
    parts = _DIGITS.split(name)
    key = tuple(int(part) if i % 2 else part.casefold() for i, part in enumerate(parts))
    return key, name


class ImageFolder(ImageListSequence):
    """The images in a folder, in natural order, without ground truth.

    The folder is listed when the object is made; images are decoded only
    while frames are produced.

    Parameters
    ----------
    path : str or path-like
        The folder.  ``info.name`` is this path as given.
    frame_interval_s : float, optional
        Time between frames in s; without it or a sidecar's, ``time_s``
        counts frames.

    The sidecar ``DIR.toml`` beside the folder ``DIR``, where there is one,
    gives the calibration, the frame interval and each frame's navigation
    (:mod:`benchmark.modalities.camera.io.sidecar`).

    Raises
    ------
    DataError
        If the folder does not exist, cannot be listed, or holds no image;
        later, while iterating, for a corrupt or differently sized image,
        naming it.

    References
    ----------
    seeds/000, section 4.7.3 ("Open image sequence...").
    """

    def __init__(self, path: str | os.PathLike[str], *, frame_interval_s: float | None = None) -> None:
        folder = Path(path)
        if not folder.is_dir():
            raise DataError(f"{folder}: no such image folder")
        try:
            entries = [entry for entry in folder.absolute().resolve().iterdir() if is_image_name(entry)]
            images = sorted((entry for entry in entries if entry.is_file()), key=lambda p: natural_key(p.name))
        except OSError as exc:
            raise DataError(f"{folder}: cannot list image folder: {exc.strerror or exc}") from None
        if not images:
            endings = " ".join(sorted(IMAGE_EXTENSIONS))
            raise DataError(f"{folder}: no image files in folder (looked for {endings})")
        super().__init__(
            name=os.fspath(path),
            source=folder,
            images=images,
            cables=[UNKNOWN_CABLE] * len(images),
            frame_interval_s=frame_interval_s,
            # The folder's own size and mtime change with any file added to it; its images are its content.
            content=b"",
            sidecar=read_sidecar(folder, n_frames=len(images)),
        )
