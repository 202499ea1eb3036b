"""Frames per second of one condensation step on 320 x 240 frames (not a timed test).

Run with ``pytest tests/plugins/condensation/test_condensation_speed.py``;
pytest-benchmark reports the time per step, and each benchmark stores its
frames per second in ``extra_info["fps"]`` and prints it.  Nothing is
asserted about time: the numbers are for the report, at the thesis' settings
(500 particles, 11 px filter, 20 px sample distance; seeds/000, Table 5.3)
and its high-speed settings (300 particles, 5 px filter; section 5.2.5).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from trackbench_condensation import CondensationTracker

from benchmark.modalities.camera.model import CableState, CameraTruth
from benchmark.model import Frame, SequenceInfo

SETTINGS = {
    "thesis-500-11px-20px": {},
    "high-speed-300-5px": {"n_particles": 300, "filter_size_px": 5},
    "thesis-500-11px-20px-no-redetect": {"redetect_fraction": 0.0},
}


@pytest.mark.parametrize("overrides", SETTINGS.values(), ids=SETTINGS.keys())
def test_step_speed(benchmark, scene, overrides):
    states = [CableState(-20.0 + k, math.radians(-3.0 + 0.2 * k), 30.0, math.radians(1.0)) for k in range(40)]
    frames = [Frame(k, scene.draw_cable(state, seed=k)) for k, state in enumerate(states)]
    tracker = CondensationTracker(CondensationTracker.make_params(overrides))
    info = SequenceInfo("drawn", "camera", frame_size=scene.SIZE)
    tracker.reset(info, np.random.default_rng(0), CameraTruth(states[0]))
    # Warm up: the first call loads (or compiles) the numba kernels.
    for frame in frames:
        tracker.step(frame)
    # Back and forth, so that the cable moves smoothly as in a real sequence.
    stream = itertools.cycle(frames[::-1] + frames)
    benchmark.pedantic(lambda: tracker.step(next(stream)), rounds=400, iterations=1, warmup_rounds=20)
    assert tracker.particles is not None and np.all(np.isfinite(tracker.particles))
    if benchmark.stats is not None:
        mean, median = benchmark.stats.stats.mean, benchmark.stats.stats.median
        benchmark.extra_info["fps"] = round(1.0 / mean, 1)
        benchmark.extra_info["ms_per_step"] = round(1000.0 * mean, 3)
        benchmark.extra_info["fps_median"] = round(1.0 / median, 1)
        print(
            f"\n{benchmark.name}: mean {1000.0 * mean:.3f} ms per step ({1.0 / mean:.0f} fps), "
            f"median {1000.0 * median:.3f} ms ({1.0 / median:.0f} fps)"
        )
