"""Pings per second of the detector and of the filter on 240-beam swaths (not a timed test).

Run with ``pytest tests/plugins/sonar/test_sonar_speed.py``; pytest-benchmark
reports the time per ping, and each benchmark stores its pings per second in
``extra_info["pings_per_s"]`` and prints it.  Nothing is asserted about
time.  The swaths are RESON 8125-like: 240 beams over 120 deg, 10 m above a
sloping seabed with a 0.6 m pipe, range noise and a few lost beams.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from trackbench_sonar import SonarDetector, SonarParticleFilter

TRACKERS = {"sonar_detector": SonarDetector, "sonar_pf": SonarParticleFilter}


@pytest.mark.parametrize("tracker_class", TRACKERS.values(), ids=TRACKERS.keys())
def test_ping_speed(benchmark, swaths, tracker_class):
    positions = 1.0 + 2.0 * np.sin(np.arange(40) / 8.0)
    frames = swaths.track(positions, noise=0.02, slope=0.05, missing=0.03, spikes=1)
    tracker = tracker_class()
    tracker.reset(swaths.info(), np.random.default_rng(0), frames[0].truth)
    for frame in frames:
        tracker.step(frame)
    stream = itertools.cycle(frames[::-1] + frames)
    benchmark.pedantic(lambda: tracker.step(next(stream)), rounds=60, iterations=1, warmup_rounds=5)
    assert tracker.step(frames[0]) is not None
    if benchmark.stats is not None:
        mean, median = benchmark.stats.stats.mean, benchmark.stats.stats.median
        benchmark.extra_info["pings_per_s"] = round(1.0 / mean, 1)
        benchmark.extra_info["ms_per_ping"] = round(1000.0 * mean, 3)
        print(
            f"\n{benchmark.name}: mean {1000.0 * mean:.3f} ms per ping ({1.0 / mean:.0f} pings/s), "
            f"median {1000.0 * median:.3f} ms ({1.0 / median:.0f} pings/s)"
        )
