"""The EKF speed bound: the tracker's compiled filter step and FilterPy's EKF do the same work (issue 34)."""

from __future__ import annotations

import numpy as np
from trackbench_stereo_ekf.speed_bound import FilterPyExtended, FilterPyLinear, OursExtended, OursLinear

from benchmark.filters.kalman import Gaussian
from benchmark.speed.bounds import BoundContext


def test_ours_and_filterpy_reach_the_same_estimates_frame_by_frame(scene) -> None:
    frames = scene.straight_chase(40, seed=6, gps_std=0.3)
    info = scene.info(len(frames))
    context = BoundContext(None, info)
    pairs = ((OursExtended(context), FilterPyExtended(context)), (OursLinear(context), FilterPyLinear(context)))
    for ours, peer in pairs:
        for workload in (ours, peer):
            workload.reset(info, np.random.default_rng(0), frames[0].truth)
        for frame in frames:
            estimate = ours.step(frame)
            mean = estimate.mean if isinstance(estimate, Gaussian) else estimate
            np.testing.assert_allclose(mean, np.ravel(peer.step(frame)), rtol=1e-9, atol=1e-9)
