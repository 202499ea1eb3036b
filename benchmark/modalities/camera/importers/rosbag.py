"""The images of a ROS bag as an image sequence file, with the vehicle speeds of a navigation topic.

A ROS 1 bag (a ``.bag`` file) or a ROS 2 bag (a folder) is read with the
``rosbags`` package (:class:`rosbags.highlevel.AnyReader`), which decodes
messages from the definitions the bag carries; no ROS installation is
needed and nothing in the bag is executed.  For a bag ``NAME`` it writes::

    out/frame_00000.png ...   one lossless grey PNG per image message, in bag order
    out/NAME.txt              the image sequence file, every frame unlabelled (nan)
    out/NAME.toml             the sidecar: frame_interval_s, [camera], [navigation]
    out/NAME.nav.csv          with a navigation topic: the speeds at each frame

Images are ``sensor_msgs/msg/Image`` (encodings in :data:`ENCODINGS`,
turned grey) or ``sensor_msgs/msg/CompressedImage`` (whatever OpenCV
decodes).  Speeds come from ``nav_msgs/msg/Odometry`` (``twist.twist.linear``)
or ``geometry_msgs/msg/TwistStamped`` (``twist.linear``), taken in the
vehicle's body frame, and are interpolated linearly to each image's time
stamp; before the first and after the last navigation message the nearest
one holds.  A message's time is its header stamp, or the time the bag
recorded it where the stamp is zero.  ``frame_interval_s`` is the median
time between consecutive images.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import cv2
import numpy as np

from benchmark.errors import DataError
from benchmark.files import make_folder
from benchmark.modalities.camera.io.sidecar import CameraTable, write_navigation_file, write_sidecar
from benchmark.modalities.camera.io.images import size_of, write_png
from benchmark.modalities.camera.io.sequence_file import write_sequence_file
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState, VehicleSpeeds

ENCODINGS: dict[str, tuple[int, int | None]] = {
    "mono8": (1, None),
    "8UC1": (1, None),
    "bgr8": (3, cv2.COLOR_BGR2GRAY),
    "rgb8": (3, cv2.COLOR_RGB2GRAY),
    "bgra8": (4, cv2.COLOR_BGRA2GRAY),
    "rgba8": (4, cv2.COLOR_RGBA2GRAY),
}
"""The raw image encodings read: channels per pixel and the OpenCV conversion to grey."""


def _raw_image(message: Any, where: str) -> np.ndarray:
    encoding = ENCODINGS.get(message.encoding)
    if encoding is None:
        raise DataError(f"{where}: image encoding {message.encoding!r} is not one of {', '.join(ENCODINGS)}")
    channels, conversion = encoding
    height, width, step = int(message.height), int(message.width), int(message.step)
    data = np.asarray(message.data, dtype=np.uint8)
    if height < 1 or width < 1 or step < width * channels or data.size < step * height:
        raise DataError(
            f"{where}: {width}x{height} {message.encoding} image with a row step of {step} bytes "
            f"does not fit its {data.size} bytes"
        )
    pixels = data[: step * height].reshape(height, step)[:, : width * channels].reshape(height, width, channels)
    grey = pixels[:, :, 0] if conversion is None else cv2.cvtColor(pixels, conversion)
    return np.ascontiguousarray(grey)


def _compressed_image(message: Any, where: str) -> np.ndarray:
    data = np.asarray(message.data, dtype=np.uint8)
    image = cv2.imdecode(data, cv2.IMREAD_GRAYSCALE) if data.size else None
    if image is None or image.dtype != np.uint8:
        raise DataError(f"{where}: cannot decode its {message.format!r} data as an 8-bit image")
    return image


IMAGE_TYPES: dict[str, Callable[[Any, str], np.ndarray]] = {
    "sensor_msgs/msg/Image": _raw_image,
    "sensor_msgs/msg/CompressedImage": _compressed_image,
}
"""The image message types read, with what turns a message into a grey ``uint8`` image."""

NAVIGATION_TYPES: dict[str, Callable[[Any], Any]] = {
    "nav_msgs/msg/Odometry": lambda message: message.twist.twist.linear,
    "geometry_msgs/msg/TwistStamped": lambda message: message.twist.linear,
}
"""The navigation message types read, with where each keeps its linear velocity."""


def vehicle_speeds(linear: np.ndarray) -> VehicleSpeeds:
    """The :class:`VehicleSpeeds` of a ROS linear velocity ``(x, y, z)`` in the body frame.

    ROS REP 103 puts the body frame's ``x`` forward, ``y`` to the left and
    ``z`` up.  The speeds ``(s_x, s_y, s_z)`` of seeds/004 eq. (7), read
    through its eq. (12) as :mod:`benchmark.modalities.camera.scenes.motion`
    does, point right, down and forward at a level attitude; so lateral is
    ``-y``, vertical ``-z`` and frontal ``x``.

    References
    ----------
    seeds/004, eqs. (7) and (12); ROS REP 103.
    """
    x, y, z = (float(v) for v in linear)
    return VehicleSpeeds(lateral=-y, vertical=-z, frontal=x)


def _time_ns(message: Any, recorded_ns: int) -> int:
    stamp = message.header.stamp
    stamp_ns = int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)
    return stamp_ns or recorded_ns


def _connections(reader: Any, bag: Path, topic: str, types: dict[str, Any], what: str) -> list[Any]:
    connections = [c for c in reader.connections if c.topic == topic]
    if not connections:
        known = ", ".join(f"{c.topic} ({c.msgtype})" for c in reader.connections) or "none"
        raise DataError(f"{bag}: no {what} topic {topic!r}; its topics: {known}")
    for connection in connections:
        if connection.msgtype not in types:
            raise DataError(
                f"{bag}: {what} topic {topic!r} carries {connection.msgtype}, not one of {', '.join(types)}"
            )
    return connections


@dataclass
class _Recording:
    """What one pass over the bag gathers besides the images it writes."""

    image_times_ns: list[int]
    navigation_times_ns: list[int]
    navigation: list[tuple[float, float, float]]


def _bag_name(bag: Path) -> str:
    return bag.absolute().stem if bag.is_file() else bag.absolute().name


def import_rosbag(
    bag: Path,
    image_topic: str,
    out: Path,
    navigation_topic: str | None = None,
    camera: CameraTable | None = None,
) -> Path:
    """Write the images of ``bag`` as PNG frames, an unlabelled image sequence file and its sidecar.

    Parameters
    ----------
    bag : pathlib.Path
        A ROS 1 ``.bag`` file or a ROS 2 bag folder.
    image_topic : str
        The topic of ``sensor_msgs/msg/Image`` or ``CompressedImage`` messages.
    out : pathlib.Path
        The folder to write into; created if missing.
    navigation_topic : str, optional
        A topic of ``nav_msgs/msg/Odometry`` or ``geometry_msgs/msg/TwistStamped``.
    camera : CameraTable, optional
        The sidecar's ``[camera]`` table.

    Returns
    -------
    pathlib.Path
        The sequence file ``out/NAME.txt``, ``NAME`` the bag's stem.

    Raises
    ------
    DataError
        If the bag is missing or unreadable, a topic is not in it or carries
        another message type, the image topic has no messages, the
        navigation topic none, an image has an unknown encoding, cannot be
        decoded or differs in size from the first, or a file cannot be
        written; naming the bag, the topic and the message.

    References
    ----------
    seeds/000, section 4.7.3; seeds/004, eq. (7); conventions.md section 2.
    """
    from rosbags.highlevel import AnyReader, AnyReaderError
    from rosbags.rosbag1 import ReaderError as Reader1Error
    from rosbags.rosbag2 import ReaderError as Reader2Error
    from rosbags.typesys import Stores, get_typestore

    if not bag.exists():
        raise DataError(f"{bag}: no such ROS bag (a .bag file or a ROS 2 bag folder)")
    name = _bag_name(bag)
    folder = make_folder(out)
    recording = _Recording([], [], [])
    sequence_file = folder / f"{name}.txt"
    try:
        with AnyReader([bag], default_typestore=get_typestore(Stores.LATEST)) as reader:
            images = _connections(reader, bag, image_topic, IMAGE_TYPES, "image")
            navigation = (
                _connections(reader, bag, navigation_topic, NAVIGATION_TYPES, "navigation")
                if navigation_topic is not None
                else []
            )

            def rows() -> Iterator[tuple[CableState, str]]:
                first_size: tuple[int, int] | None = None
                for connection, recorded_ns, raw in reader.messages(connections=[*images, *navigation]):
                    message = reader.deserialize(raw, connection.msgtype)
                    if connection.msgtype in NAVIGATION_TYPES:
                        linear = NAVIGATION_TYPES[connection.msgtype](message)
                        velocity = (float(linear.x), float(linear.y), float(linear.z))
                        if not all(math.isfinite(v) for v in velocity):
                            index = len(recording.navigation)
                            where = f"{bag}: topic {navigation_topic!r}: message {index}"
                            raise DataError(f"{where}: linear velocity {velocity} is not finite")
                        recording.navigation_times_ns.append(_time_ns(message, recorded_ns))
                        recording.navigation.append(velocity)
                        continue
                    index = len(recording.image_times_ns)
                    where = f"{bag}: topic {image_topic!r}: message {index}"
                    image = IMAGE_TYPES[connection.msgtype](message, where)
                    size = size_of(image)
                    first_size = first_size or size
                    if size != first_size:
                        width, height = first_size
                        raise DataError(f"{where}: image is {size[0]}x{size[1]} px, the first {width}x{height} px")
                    file_name = f"frame_{index:05d}.png"
                    write_png(folder / file_name, image, where=f"{where}: ")
                    recording.image_times_ns.append(_time_ns(message, recorded_ns))
                    yield UNKNOWN_CABLE, file_name
                if not recording.image_times_ns:
                    raise DataError(f"{bag}: image topic {image_topic!r} has no messages")
                if navigation_topic is not None and not recording.navigation:
                    raise DataError(f"{bag}: navigation topic {navigation_topic!r} has no messages")

            write_sequence_file(sequence_file, rows())
    except (AnyReaderError, Reader1Error, Reader2Error, OSError) as exc:
        raise DataError(f"{bag}: cannot read ROS bag: {exc}") from None
    _write_sidecar(sequence_file, recording, camera)
    return sequence_file


def _write_sidecar(sequence_file: Path, recording: _Recording, camera: CameraTable | None) -> None:
    """The sidecar of an imported bag, with its navigation file when the bag had a navigation topic."""
    image_times = np.asarray(recording.image_times_ns, dtype=np.int64)
    periods = np.diff(image_times) / 1e9
    frame_interval_s = float(np.median(periods)) if periods.size and np.median(periods) > 0 else None
    navigation_file = None
    if recording.navigation:
        order = np.argsort(np.asarray(recording.navigation_times_ns, dtype=np.int64), kind="stable")
        times = np.asarray(recording.navigation_times_ns, dtype=np.int64)[order]
        values = np.asarray(recording.navigation, dtype=float)[order]
        # Times as offsets from the first image keep the nanoseconds exact in float64.
        at = (image_times - image_times[0]).astype(float)
        known = (times - image_times[0]).astype(float)
        interpolated = np.column_stack([np.interp(at, known, values[:, axis]) for axis in range(3)])
        navigation_file = f"{sequence_file.stem}.nav.csv"
        write_navigation_file(sequence_file.parent / navigation_file, (vehicle_speeds(v) for v in interpolated))
    if frame_interval_s is not None or camera is not None or navigation_file is not None:
        write_sidecar(sequence_file, frame_interval_s=frame_interval_s, camera=camera, navigation_file=navigation_file)
