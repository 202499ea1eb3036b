"""Labels made in other tools, read into cable states: CSV files and CVAT 1.1 XML exports.

A label gives, per image, either the cable state ``(d, alpha, w, beta)`` of
``conventions.md`` section 1 (px, rad, px, rad, as the image sequence file
writes them) or the two border lines of the cable, each by two of its points
in pixel coordinates (OpenCV's: column right, row down).  Borders become a
cable state through the camera geometry
(:func:`~benchmark.modalities.camera.geometry.cable_from_borders`), so a
label tool needs to know nothing of the cable model.

* CSV: a header row, then one row per frame, in frame order, with either the
  columns ``image,d,alpha,w,beta`` or
  ``image,x1a,y1a,x2a,y2a,x1b,y1b,x2b,y2b`` (border ``a`` from ``(x1a, y1a)``
  to ``(x2a, y2a)``, border ``b`` likewise), in any order.  A row whose
  numbers are all empty or ``nan`` is an unlabelled frame.
* CVAT 1.1 XML, as CVAT exports annotations "for images": one ``<image
  name=... width=... height=...>`` element per frame, in file order, with
  two ``<polyline points="x,y;x,y;...">`` children, the borders; each
  border is the line through its polyline's first and last point.  An
  image without polylines shows no cable and is an unlabelled frame.

An unlabelled frame is written as the sequence file's ``nan`` row
(:data:`~benchmark.modalities.camera.model.UNKNOWN_CABLE`).  Each row is
checked by a pydantic model; every error names the file, the line (CSV) or
the image element (CVAT) and the field.
"""

from __future__ import annotations

import csv
import io
import math
from abc import abstractmethod
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, ClassVar
from xml.etree import ElementTree

import pydantic
from annotated_types import Interval, MinLen

from benchmark.errors import DataError
from benchmark.files import make_folder
from benchmark.io import read_regular_file
from benchmark.modalities.camera.geometry import ImageSize, Line, cable_from_borders
from benchmark.modalities.camera.io.images import read_grey, size_of
from benchmark.modalities.camera.io.sequence_file import write_sequence_file
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState
from benchmark.parameters import Finite, Positive
from benchmark.scenes.spec import validate_table

ImageName = Annotated[str, pydantic.StringConstraints(strip_whitespace=True, min_length=1)]
"""An image's path relative to the image folder."""

Skew = Annotated[Finite, Interval(ge=0, lt=math.pi / 2)]
"""Ground-truth ``beta`` in rad: the borders converge towards the top (``conventions.md`` section 1)."""

SizeOf = Callable[[], ImageSize]
"""The ``(W, H)`` of the labelled image, read only where a label needs it."""

_UNKNOWN_TEXT = frozenset({"", "nan"})
"""What a CSV cell of an unlabelled frame holds (letter case aside)."""


@dataclass(frozen=True, slots=True)
class Label:
    """One frame's label: the image, relative to the image folder, its cable state and where it was read."""

    image: str
    cable: CableState
    where: str


def _border(points: tuple[tuple[float, float], tuple[float, float]], size: ImageSize, name: str) -> Line:
    try:
        return Line.from_pixels(*points, size)
    except ValueError:
        raise ValueError(f"border {name}: its two end points coincide, {points[0]}") from None


class _Row(pydantic.BaseModel):
    model_config = pydantic.ConfigDict(frozen=True, extra="forbid")
    image: ImageName

    @abstractmethod
    def cable(self, size: SizeOf) -> CableState:
        """The labelled cable state."""


class CableRow(_Row):
    """A CSV row that gives the cable state itself (``conventions.md`` section 1: px, rad, px, rad)."""

    columns: ClassVar[tuple[str, ...]] = ("image", "d", "alpha", "w", "beta")
    d: Finite
    alpha: Finite
    w: Positive
    beta: Skew

    def cable(self, size: SizeOf) -> CableState:
        return CableState(self.d, self.alpha, self.w, self.beta)


class BorderRow(_Row):
    """A CSV row that gives the two borders by two pixel points each."""

    columns: ClassVar[tuple[str, ...]] = ("image", "x1a", "y1a", "x2a", "y2a", "x1b", "y1b", "x2b", "y2b")
    x1a: Finite
    y1a: Finite
    x2a: Finite
    y2a: Finite
    x1b: Finite
    y1b: Finite
    x2b: Finite
    y2b: Finite

    def cable(self, size: SizeOf) -> CableState:
        image_size = size()
        first = _border(((self.x1a, self.y1a), (self.x2a, self.y2a)), image_size, "a")
        second = _border(((self.x1b, self.y1b), (self.x2b, self.y2b)), image_size, "b")
        return cable_from_borders(first, second)


ROW_KINDS: dict[frozenset[str], type[_Row]] = {frozenset(kind.columns): kind for kind in (CableRow, BorderRow)}
"""The CSV row models by the set of columns their header names."""


def _cells_unknown(cells: dict[str, str]) -> bool:
    return all(value.strip().lower() in _UNKNOWN_TEXT for key, value in cells.items() if key != "image")


def _image_size(images: Path, name: str, where: str) -> SizeOf:
    return lambda: size_of(read_grey(images / name, where=where))


def read_csv_labels(path: Path, images: Path) -> Iterator[Label]:
    """The labels of a CSV file, in row order.

    Parameters
    ----------
    path : pathlib.Path
        The CSV file.
    images : pathlib.Path
        The folder the ``image`` column is relative to; a border row reads
        its image for its size.

    Raises
    ------
    DataError
        If the file cannot be read, its header names neither column set, a
        row has the wrong number of cells or breaks its model, or a border
        row's image cannot be read; naming the file, the line and the field.

    References
    ----------
    conventions.md section 1 (the cable state); seeds/000, section 4.2.
    """
    try:
        text = read_regular_file(path, "label file").decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DataError(f"{path}: not a UTF-8 text file ({exc.reason} at byte {exc.start})") from None
    reader = csv.reader(io.StringIO(text))
    header = [name.strip() for name in next(reader, [])]
    kind = ROW_KINDS.get(frozenset(header))
    if kind is None or len(header) != len(kind.columns):
        expected = " or ".join(",".join(kind.columns) for kind in ROW_KINDS.values())
        raise DataError(f"{path}:1: header {','.join(header)!r} names neither column set; expected {expected}")
    for cells in reader:
        if not cells:
            continue
        where = f"{path}:{reader.line_num}"
        if len(cells) != len(header):
            raise DataError(f"{where}: expected {len(header)} cells as the header has, found {len(cells)}")
        values = dict(zip(header, cells, strict=True))
        if _cells_unknown(values):
            image = validate_table(ImageName, values["image"], f"{where}: image")
            yield Label(image, UNKNOWN_CABLE, where)
            continue
        row = validate_table(kind, values, where)
        try:
            cable = row.cable(_image_size(images, row.image, f"{where}: "))
        except ValueError as exc:
            raise DataError(f"{where}: {exc}") from None
        yield Label(row.image, cable, where)


def _points(text: str) -> list[list[str]]:
    return [pair.split(",") for pair in text.split(";")] if text.strip() else []


Point = tuple[Finite, Finite]
"""A pixel point ``(u, v)``."""


class CvatPolyline(pydantic.BaseModel):
    """A ``<polyline>`` of a CVAT 1.1 image: a border, the line through its first and last point."""

    model_config = pydantic.ConfigDict(frozen=True)
    points: Annotated[tuple[Point, ...], pydantic.BeforeValidator(_points), MinLen(2)]


class CvatImage(pydantic.BaseModel):
    """The attributes of a CVAT 1.1 ``<image>`` element this importer uses."""

    model_config = pydantic.ConfigDict(frozen=True)
    name: ImageName
    width: pydantic.PositiveInt
    height: pydantic.PositiveInt


def _cvat_root(path: Path) -> ElementTree.Element:
    # ElementTree resolves no external entities, and the expat it uses bounds entity expansion.
    content = read_regular_file(path, "label file")
    try:
        root = ElementTree.fromstring(content)
    except ElementTree.ParseError as exc:
        raise DataError(f"{path}: not well-formed XML: {exc}") from None
    if root.tag != "annotations":
        raise DataError(f"{path}: root element is <{root.tag}>, not the <annotations> of a CVAT 1.1 export")
    if root.find("track") is not None:
        raise DataError(f"{path}: holds <track> elements (a CVAT export for video); export the task 'for images'")
    return root


def read_cvat_labels(path: Path, images: Path) -> Iterator[Label]:
    """The labels of a CVAT 1.1 XML export for images, in file order.

    Parameters
    ----------
    path : pathlib.Path
        The XML file.
    images : pathlib.Path
        The folder the images' names are relative to (not read: the size
        comes from the element's ``width`` and ``height``).

    Raises
    ------
    DataError
        If the file cannot be read or parsed, is not a CVAT export for
        images, or an ``<image>`` has bad attributes, a polyline count other
        than 0 or 2, or a polyline whose points are malformed or whose ends
        coincide; naming the file, the image element and the field.

    References
    ----------
    conventions.md section 1; seeds/000, section 4.2.
    """
    for number, element in enumerate(_cvat_root(path).iter("image"), start=1):
        where = f"{path}: <image> {number} (name={element.get('name')!r})"
        image = validate_table(CvatImage, dict(element.attrib), where)
        polylines = element.findall("polyline")
        if not polylines:
            yield Label(image.name, UNKNOWN_CABLE, where)
            continue
        if len(polylines) != 2:
            raise DataError(f"{where}: {len(polylines)} <polyline> elements; a cable has 2 borders, none if unseen")
        size = (image.width, image.height)
        borders = []
        for name, polyline in zip("ab", polylines, strict=True):
            line = validate_table(CvatPolyline, dict(polyline.attrib), f"{where}: <polyline> {name}")
            try:
                borders.append(_border((line.points[0], line.points[-1]), size, name))
            except ValueError as exc:
                raise DataError(f"{where}: {exc}") from None
        yield Label(image.name, cable_from_borders(*borders), where)


LABEL_READERS: dict[str, Callable[[Path, Path], Iterator[Label]]] = {
    ".csv": read_csv_labels,
    ".xml": read_cvat_labels,
}
"""The label readers by file name ending (lower case)."""


def import_labels(labels: Path, images: Path, out: Path) -> Path:
    """Write an image sequence file of the images in ``images`` labelled in ``labels``.

    Parameters
    ----------
    labels : pathlib.Path
        A CSV file (``.csv``) or a CVAT 1.1 export (``.xml``).
    images : pathlib.Path
        The folder the labels name their images in; each must be a file.
    out : pathlib.Path
        The sequence file to write; its folder is created.  Image paths in
        it are relative to its folder where the images lie below it.

    Returns
    -------
    pathlib.Path
        ``out``.

    Raises
    ------
    DataError
        For an unknown label format, a missing image folder or image, any
        error of the label reader, or a file that cannot be written.

    References
    ----------
    seeds/000, section 4.7.3; conventions.md sections 1 and 2.
    """
    reader = LABEL_READERS.get(labels.suffix.lower())
    if reader is None:
        raise DataError(f"{labels}: unknown label format; expected one of {', '.join(sorted(LABEL_READERS))}")
    if not images.is_dir():
        raise DataError(f"{images}: no such image folder")
    folder = images.absolute()

    def rows() -> Iterator[tuple[CableState, Path]]:
        count = 0
        for count, label in enumerate(reader(labels, folder), start=1):
            image = folder / label.image
            if not image.is_file():
                raise DataError(f"{label.where}: image {label.image!r} is not a file in {images}")
            yield label.cable, image
        if not count:
            raise DataError(f"{labels}: no labelled images")

    make_folder(out.absolute().parent)
    write_sequence_file(out, rows())
    return out
