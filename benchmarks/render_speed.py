"""Milliseconds per frame of the camera renderer: the haze model of S3 against the water model, side by side.

    python benchmarks/render_speed.py [FRAMES]

Every variant renders the same poses of ``camera/S3`` (its motion, seabed
and cable) at 320x240 and at 640x480 (focal length doubled), interleaved in
rounds so that the machine's load falls on all of them alike; the report is
the median over rounds of the mean time per frame, and each variant's ratio
to the haze model at the same size.  Variants:

* ``haze``: S3 as the suite defines it (the thesis suites' model);
* ``water``: S3 with ``[optics.water]`` (type 3C, one lamp), shot noise and JPEG;
* ``water+day``: the same with daylight and sun flicker as well;
* ``water+snow``: the same with marine snow (50 particles per m^3).
"""

from __future__ import annotations

import statistics
import sys
import time
from typing import Any

from benchmark.plugins import load_registry
from benchmark.modalities.camera.scenes.scene import CameraScene
from trackbench_suites.loader import merge_tables

SIZES = {"320x240": ([320, 240], 380.0), "640x480": ([640, 480], 760.0)}

WATER = {"jerlov": "3C", "lamps": [{"offset_m": [0.3, -0.3, 0.0]}]}
VARIANTS: dict[str, dict[str, Any]] = {
    "haze": {},
    "water": {"optics": {"water": WATER, "shot_noise": 0.2, "jpeg_quality": 70}},
    "water+day": {
        "optics": {"water": {**WATER, "sun": 20.0, "depth_m": 8.0, "caustics": 0.7}, "shot_noise": 0.2, "jpeg_quality": 70}
    },
    "water+snow": {"optics": {"water": {**WATER, "snow_per_m3": 50.0}, "shot_noise": 0.2, "jpeg_quality": 70}},
}


def scenes(frames: int) -> dict[tuple[str, str], CameraScene]:
    """The variants of S3 at both sizes."""
    registry = load_registry()
    (s3,) = [seq for seq in registry.suites["camera"].sequences if seq.info.name == "camera/S3"]
    base = s3.spec.to_dict()
    base["n_frames"] = frames
    made = {}
    for size, (frame_size, focal) in SIZES.items():
        for name, change in VARIANTS.items():
            table = merge_tables(merge_tables(base, {"frame_size": frame_size, "focal_px": focal}), change)
            made[(size, name)] = CameraScene.from_dict(table)
    return made


def main(frames: int = 20, rounds: int = 5) -> None:
    made = scenes(frames)
    for scene in made.values():
        scene.render(0)
    times: dict[tuple[str, str], list[float]] = {key: [] for key in made}
    for _ in range(rounds):
        for key, scene in made.items():
            start = time.perf_counter()
            for index in range(frames):
                scene.render(index)
            times[key].append(1000.0 * (time.perf_counter() - start) / frames)
    for size in SIZES:
        haze = statistics.median(times[(size, "haze")])
        for name in VARIANTS:
            ms = statistics.median(times[(size, name)])
            print(f"{size}  {name:11s} {ms:7.2f} ms/frame  x{ms / haze:4.2f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 20)
