"""``trackbench import rosbag``: ROS 1 and ROS 2 bags, written here with rosbags' own writers, into sequence files."""

from __future__ import annotations

import csv
import tomllib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import cv2
import numpy as np
import pytest
from click.testing import CliRunner, Result
from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import Writer as Writer2
from rosbags.typesys import Stores, get_typestore

from benchmark.cli import main
from benchmark.modalities.camera.importers.rosbag import vehicle_speeds
from benchmark.modalities.camera.io.sequence_file import read_sequence_file
from benchmark.modalities.camera.model import VehicleSpeeds

START_NS = 1_700_000_000_123_456_789
"""A realistic epoch stamp: large enough that float seconds would lose the nanoseconds."""

PERIOD_NS = 40_000_000
"""The images' stamps are 0.04 s apart."""


@dataclass(frozen=True)
class BagKind:
    """How to write one kind of bag: its path, writer and serialisation."""

    name: str
    store: Stores
    path: Callable[[Path], Path]
    writer: Callable[[Path], Any]
    serialize: str

    @property
    def typestore(self) -> Any:
        return get_typestore(self.store)


ROS1 = BagKind("ros1", Stores.ROS1_NOETIC, lambda d: d / "run.bag", Writer1, "serialize_ros1")
ROS2 = BagKind("ros2", Stores.ROS2_HUMBLE, lambda d: d / "run", lambda p: Writer2(p, version=9), "serialize_cdr")


class Messages:
    """Messages of one typestore, with stamps in nanoseconds."""

    def __init__(self, typestore: Any) -> None:
        self.types = typestore.types

    def header(self, stamp_ns: int) -> Any:
        header = self.types["std_msgs/msg/Header"]
        time = self.types["builtin_interfaces/msg/Time"](sec=stamp_ns // 10**9, nanosec=stamp_ns % 10**9)
        extra = {"seq": 0} if "seq" in header.__dataclass_fields__ else {}
        return header(stamp=time, frame_id="camera", **extra)

    def raw_image(self, stamp_ns: int, pixels: np.ndarray, encoding: str, padding: int = 0) -> Any:
        height, width = pixels.shape[:2]
        rows = pixels.reshape(height, -1)
        data = np.concatenate((rows, np.full((height, padding), 7, np.uint8)), axis=1)
        return self.types["sensor_msgs/msg/Image"](
            header=self.header(stamp_ns),
            height=height,
            width=width,
            encoding=encoding,
            is_bigendian=0,
            step=rows.shape[1] + padding,
            data=data.ravel(),
        )

    def compressed_image(self, stamp_ns: int, pixels: np.ndarray) -> Any:
        encoded = cv2.imencode(".png", pixels)[1].ravel()
        return self.types["sensor_msgs/msg/CompressedImage"](header=self.header(stamp_ns), format="png", data=encoded)

    def twist(self, linear: tuple[float, float, float]) -> Any:
        vector = self.types["geometry_msgs/msg/Vector3"]
        return self.types["geometry_msgs/msg/Twist"](linear=vector(*linear), angular=vector(0.0, 0.0, 0.0))

    def odometry(self, stamp_ns: int, linear: tuple[float, float, float]) -> Any:
        t = self.types
        pose = t["geometry_msgs/msg/Pose"](
            position=t["geometry_msgs/msg/Point"](0.0, 0.0, 0.0),
            orientation=t["geometry_msgs/msg/Quaternion"](0.0, 0.0, 0.0, 1.0),
        )
        return t["nav_msgs/msg/Odometry"](
            header=self.header(stamp_ns),
            child_frame_id="base_link",
            pose=t["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.zeros(36)),
            twist=t["geometry_msgs/msg/TwistWithCovariance"](twist=self.twist(linear), covariance=np.zeros(36)),
        )

    def twist_stamped(self, stamp_ns: int, linear: tuple[float, float, float]) -> Any:
        return self.types["geometry_msgs/msg/TwistStamped"](header=self.header(stamp_ns), twist=self.twist(linear))


def write_bag(kind: BagKind, folder: Path, topics: dict[str, list[tuple[int, Any]]]) -> Path:
    """A bag of ``kind`` with, per topic, ``(recorded_ns, message)`` pairs."""
    path = kind.path(folder)
    typestore = kind.typestore
    serialize = getattr(typestore, kind.serialize)
    with kind.writer(path) as writer:
        for topic, messages in topics.items():
            connection = writer.add_connection(topic, messages[0][1].__msgtype__, typestore=typestore)
            for recorded_ns, message in messages:
                writer.write(connection, recorded_ns, serialize(message, message.__msgtype__))
    return path


def frames(count: int = 3) -> list[np.ndarray]:
    """Tiny colour frames, ``(6, 8, 3)`` BGR, each different."""
    rng = np.random.default_rng(4)
    return [rng.integers(0, 256, (6, 8, 3), dtype=np.uint8) for _ in range(count)]


def import_rosbag(*args: str | Path) -> Result:
    return CliRunner().invoke(main, ["import", "rosbag", *(str(arg) for arg in args)])


NAVIGATION = [(0, (1.0, 0.2, 0.1)), (50_000_000, (1.5, 0.2, -0.1))]
"""Body-frame linear velocities ``(x, y, z)`` at offsets from START_NS; the last image comes after the last one."""

EXPECTED_SPEEDS = [(-0.2, -0.1, 1.0), (-0.2, 0.06, 1.4), (-0.2, 0.1, 1.5)]
"""``(lateral, vertical, frontal)`` at the images' stamps 0, 0.04 and 0.08 s: interpolated, then held."""

IMAGE_KINDS = {
    "mono8": lambda m, t, bgr: m.raw_image(t, cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY), "mono8", padding=3),
    "bgr8": lambda m, t, bgr: m.raw_image(t, bgr, "bgr8"),
    "rgb8": lambda m, t, bgr: m.raw_image(t, bgr[:, :, ::-1], "rgb8", padding=1),
    "compressed": lambda m, t, bgr: m.compressed_image(t, cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY)),
}


@pytest.mark.parametrize(
    ("kind", "image_kind", "navigation"),
    [
        (ROS1, "mono8", "odometry"),
        (ROS1, "compressed", "twist_stamped"),
        (ROS1, "rgb8", "twist_stamped"),
        (ROS2, "bgr8", "odometry"),
        (ROS2, "compressed", "odometry"),
        (ROS2, "mono8", "twist_stamped"),
    ],
    ids=lambda value: getattr(value, "name", value),
)
def test_a_bag_becomes_frames_an_unlabelled_sequence_file_a_sidecar_and_speeds(
    tmp_path: Path, kind: BagKind, image_kind: str, navigation: str
) -> None:
    messages = Messages(kind.typestore)
    images = frames()
    # Recorded times jitter; the header stamps are what count.
    image_messages = [
        (START_NS + i * PERIOD_NS + 3_000_000 * i * i, IMAGE_KINDS[image_kind](messages, START_NS + i * PERIOD_NS, bgr))
        for i, bgr in enumerate(images)
    ]
    nav = getattr(messages, navigation)
    nav_messages = [(START_NS + offset, nav(START_NS + offset, linear)) for offset, linear in NAVIGATION]
    bag = write_bag(kind, tmp_path, {"/camera/image": image_messages, "/nav": nav_messages})
    out = tmp_path / "out"
    result = import_rosbag(bag, "--image-topic", "/camera/image", "--nav-topic", "/nav", "--out", out)
    assert result.exit_code == 0, result.output

    rows = read_sequence_file(out / "run.txt")
    assert [row.image for row in rows] == [(out / f"frame_{i:05d}.png").resolve() for i in range(3)]
    assert not any(row.cable.is_known for row in rows)
    assert (out / "run.txt").read_text().splitlines()[1] == "nan nan nan nan # frame_00000.png"
    for row, bgr in zip(rows, images, strict=True):
        grey = cv2.imread(str(row.image), cv2.IMREAD_UNCHANGED)
        np.testing.assert_array_equal(grey, cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY))

    sidecar = out / "run.toml"
    assert tomllib.loads(sidecar.read_text()) == {"frame_interval_s": 0.04, "navigation": {"file": "run.nav.csv"}}
    with (out / "run.nav.csv").open() as handle:
        table = list(csv.reader(handle))
    assert table[0] == ["frame", "lateral_mps", "vertical_mps", "frontal_mps"]
    assert [int(row[0]) for row in table[1:]] == [0, 1, 2]
    speeds = np.array([[float(v) for v in row[1:]] for row in table[1:]])
    np.testing.assert_allclose(speeds, EXPECTED_SPEEDS, atol=1e-12)


def test_without_navigation_stamps_of_zero_fall_back_to_the_recorded_times_and_calibration_goes_in_the_sidecar(
    tmp_path: Path,
) -> None:
    messages = Messages(ROS2.typestore)
    image_messages = [
        (START_NS + i * 50_000_000, messages.compressed_image(0, bgr[:, :, 0])) for i, bgr in enumerate(frames())
    ]
    bag = write_bag(ROS2, tmp_path, {"/image": image_messages})
    out = tmp_path / "out"
    calibration = ["--focal-px", "800", "--pipe-diameter-m", "0.3", "--tilt-deg", "30"]
    assert import_rosbag(bag, "--image-topic", "/image", "--out", out, *calibration).exit_code == 0
    assert tomllib.loads((out / "run.toml").read_text()) == {
        "frame_interval_s": 0.05,
        "camera": {"focal_px": 800.0, "pipe_diameter_m": 0.3, "tilt_deg": 30.0},
    }
    assert not (out / "run.nav.csv").exists()
    assert len(read_sequence_file(out / "run.txt")) == 3


def test_ros_body_velocities_map_to_lateral_right_vertical_down_frontal_forward() -> None:
    assert vehicle_speeds(np.array([2.0, 0.5, -0.25])) == VehicleSpeeds(lateral=-0.5, vertical=0.25, frontal=2.0)


@pytest.fixture
def bag(tmp_path: Path) -> Path:
    messages = Messages(ROS1.typestore)
    grey = cv2.cvtColor(frames(1)[0], cv2.COLOR_BGR2GRAY)
    return write_bag(
        ROS1,
        tmp_path,
        {
            "/image": [(START_NS, messages.raw_image(START_NS, grey, "mono8"))],
            "/depth": [(START_NS, messages.raw_image(START_NS, grey, "16UC1"))],
            "/bad_png": [(START_NS, bad_compressed(messages, grey))],
            "/short": [(START_NS, short_image(messages, grey))],
            "/odom": [(START_NS, messages.odometry(START_NS, (1.0, 0.0, 0.0)))],
            "/twist": [
                (START_NS, messages.twist_stamped(START_NS, (1.0, 0.0, 0.0))),
                (START_NS + 1, messages.twist_stamped(START_NS + 1, (1.0, float("nan"), 0.0))),
            ],
        },
    )


def bad_compressed(messages: Messages, grey: np.ndarray) -> Any:
    message = messages.compressed_image(START_NS, grey)
    message.data = np.arange(9, dtype=np.uint8)
    return message


def short_image(messages: Messages, grey: np.ndarray) -> Any:
    message = messages.raw_image(START_NS, grey, "mono8")
    message.data = message.data[:-1]
    return message


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--image-topic", "/camera"], "no image topic '/camera'; its topics: "),
        (["--image-topic", "/odom"], "image topic '/odom' carries nav_msgs/msg/Odometry, not one of"),
        (["--image-topic", "/image", "--nav-topic", "/image"], "navigation topic '/image' carries sensor_msgs/msg/"),
        (["--image-topic", "/image", "--nav-topic", "/gps"], "no navigation topic '/gps'"),
        (["--image-topic", "/image", "--nav-topic", "/twist"], "topic '/twist': message 1: linear velocity (1.0, nan"),
        (["--image-topic", "/depth"], "topic '/depth': message 0: image encoding '16UC1' is not one of mono8"),
        (["--image-topic", "/bad_png"], "topic '/bad_png': message 0: cannot decode its 'png' data"),
        (["--image-topic", "/short"], "topic '/short': message 0: 8x6 mono8 image with a row step of 8 bytes"),
    ],
)
def test_bad_topics_and_images_are_one_error_line_naming_the_bag_and_topic(
    tmp_path: Path, bag: Path, args: list[str], message: str
) -> None:
    result = import_rosbag(bag, *args, "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert result.output.startswith(f"Error: {bag}: ") and message in result.output, result.output
    assert not (tmp_path / "out" / "run.txt").exists()


def test_a_missing_or_corrupt_bag_is_an_error(tmp_path: Path) -> None:
    result = import_rosbag(tmp_path / "none.bag", "--image-topic", "/image", "--out", tmp_path / "out")
    assert result.exit_code == 2 and f"Error: {tmp_path / 'none.bag'}: no such ROS bag" in result.output
    corrupt = tmp_path / "corrupt.bag"
    corrupt.write_bytes(b"#ROSBAG V2.0\nnot a bag")
    result = import_rosbag(corrupt, "--image-topic", "/image", "--out", tmp_path / "out")
    assert result.exit_code == 2 and f"Error: {corrupt}: cannot read ROS bag" in result.output, result.output
