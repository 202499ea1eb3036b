"""The frames being labelled and their cable states, saved as an image sequence file.

A :class:`LabelDocument` is opened from anything the camera modality reads
(:func:`benchmark.io.open_sequence` with its readers): an image sequence
file is labelled in place; an image folder ``F`` gets the sequence file
``F.txt`` beside it; a video ``V.avi`` is first written out as PNG frames
plus an unlabelled sequence file ``V.txt`` (the modality's exporter), which
is then labelled.  The image paths are fixed; only the states change.

Saving writes the thesis' format (seeds/000, section 4.7.3;
``conventions.md`` section 2) with the modality's writer, atomically, and
keeps the file it replaces as ``S.txt.bak``.
"""

from __future__ import annotations

import functools
import hashlib
import os
import threading
from collections.abc import Sequence as Items
from dataclasses import dataclass, field
from pathlib import Path

import cv2

from benchmark.errors import DataError
from benchmark.files import resolved, write_bytes_atomically
from benchmark.io import open_sequence
from benchmark.modalities.camera.geometry import ImageSize
from benchmark.modalities.camera.io.export import export_camera_sequence
from benchmark.modalities.camera.io.image_folder import ImageFolder
from benchmark.modalities.camera.io.images import read_grey
from benchmark.modalities.camera.io.sequence_file import ImageSequenceFile, write_sequence_file
from benchmark.modalities.camera.io.video import VideoFile
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState
from benchmark.model import Sequence

BACKUP_SUFFIX = ".bak"
"""Appended to the sequence file's name for the copy of the version a save replaces."""


@dataclass
class LabelDocument:
    """Images in frame order, a cable state per image, and the sequence file they are saved to.

    Attributes
    ----------
    name : str
        What the page shows as the sequence's name.
    images : tuple of pathlib.Path
        The images, absolute, in frame order.
    states : list of CableState
        The saved state of each frame, :data:`UNKNOWN_CABLE` where unlabelled.
    output : pathlib.Path
        The image sequence file saves go to.
    size : tuple of int
        ``(W, H)`` of every frame, px.
    """

    name: str
    images: tuple[Path, ...]
    states: list[CableState]
    output: Path
    size: ImageSize
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False, compare=False)

    @property
    def backup(self) -> Path:
        """Where a save keeps the file it replaces: ``S.txt.bak``."""
        return self.output.with_name(self.output.name + BACKUP_SUFFIX)

    @property
    def revision(self) -> str:
        """A digest of the saved file's bytes (of nothing before the first save): what a page's draft builds on."""
        try:
            content = self.output.read_bytes()
        except FileNotFoundError:
            content = b""
        except OSError as exc:
            raise DataError(f"{self.output}: cannot read image sequence file: {exc.strerror or exc}") from None
        return hashlib.sha256(content).hexdigest()[:16]

    def frame_png(self, index: int) -> bytes:
        """Frame ``index`` as a grey PNG image, decoded as the camera readers decode it."""
        image = read_grey(self.images[index], where=f"{self.name}: frame {index}: ")
        ok, encoded = cv2.imencode(".png", image)
        if not ok:
            raise DataError(f"{self.name}: frame {index}: cannot encode as PNG")
        return encoded.tobytes()

    def save(self, states: Items[CableState]) -> str:
        """Write ``states`` (one per frame) to :attr:`output`, keeping the file it replaces as :attr:`backup`.

        Both files are written atomically: a reader sees the old file or the
        new one, never part of one.

        Returns
        -------
        str
            The new :attr:`revision`.

        Raises
        ------
        DataError
            If the number of states is not the number of frames, or a file
            cannot be written (naming it); the files are then left as they were.
        """
        if len(states) != len(self.images):
            raise DataError(f"{self.output}: {len(states)} states for {len(self.images)} frames")
        with self._lock:
            if self.output.is_file():
                write_bytes_atomically(self.backup, self.output.read_bytes(), "backup of the image sequence file")
            write_sequence_file(self.output, zip(states, self.images, strict=True))
            self.states = list(states)
            return self.revision


def open_document(path: str | os.PathLike[str], output: Path | None = None) -> LabelDocument:
    """Open an image sequence file, an image folder or a video for labelling.

    Parameters
    ----------
    path : str or path-like
        What to label; opened with the camera modality's readers.
    output : pathlib.Path, optional
        The sequence file to save to.  Default: the sequence file itself,
        ``F.txt`` beside a folder ``F``, ``V.txt`` beside a video ``V.avi``.

    Raises
    ------
    DataError
        If the camera readers cannot open ``path``; if ``output`` exists
        already for a folder or a video (open that file to go on labelling
        it); for a video, if its frames cannot be written out.

    References
    ----------
    seeds/000, appendix B (the GroundTruthEditor) and section 4.7.3.
    """
    from benchmark.modalities.camera.modality import CAMERA

    sequence = open_sequence(path, [CAMERA])
    return _document(sequence, output)


@functools.singledispatch
def _document(sequence: Sequence, output: Path | None) -> LabelDocument:
    raise DataError(f"{sequence.info.name}: cannot label a {type(sequence).__name__}")


@_document.register
def _(sequence: ImageSequenceFile, output: Path | None) -> LabelDocument:
    elsewhere = output is not None and resolved(output) != resolved(sequence.path)
    target = _new_output(output) if output is not None and elsewhere else sequence.path
    return _made(sequence, [row.cable for row in sequence.rows], target)


@_document.register
def _(sequence: ImageFolder, output: Path | None) -> LabelDocument:
    folder = resolved(sequence.info.name)
    target = _new_output(output or folder.with_name(folder.name + ".txt"))
    return _made(sequence, [UNKNOWN_CABLE] * len(sequence), target)


@_document.register
def _(sequence: VideoFile, output: Path | None) -> LabelDocument:
    target = _new_output(output or sequence.path.with_suffix(".txt"))
    if target.with_suffix("").exists():
        raise DataError(f"{target.with_suffix('')}: exists already; the video's frames would be written into it")
    written = export_camera_sequence(sequence, target.parent, target.stem)
    if written != target:
        written.replace(target)
    return _document(ImageSequenceFile(target), None)


def _new_output(output: Path) -> Path:
    """A sequence file to create: refused if it exists (it holds someone's labels) or its folder does not."""
    if output.exists():
        raise DataError(f"{output}: exists already; label it with 'trackbench label {output}', or choose --out")
    if not output.absolute().parent.is_dir():
        raise DataError(f"{output}: no such folder to save the image sequence file in")
    return output.absolute()


def _made(sequence: ImageSequenceFile | ImageFolder, states: list[CableState], output: Path) -> LabelDocument:
    info = sequence.info
    assert info.frame_size is not None  # an image list reads its first image for the size
    return LabelDocument(info.name, sequence.images, states, output.absolute(), info.frame_size)
