"""The compiled cleaning and resampling of a swath against the array form it replaced (seeds/003, section 2).

:func:`old_resample_swath` is :func:`trackbench_sonar.profile.resample_swath`
as it was, in NumPy calls (the valid mask, :func:`spike_mask` with its
sorted windows, :func:`upper_envelope`, a stable argsort); the compiled
form (:func:`trackbench_sonar.envelope_kernel.clean_returns` and
:func:`~trackbench_sonar.envelope_kernel.profile_arrays`) must give every
array of the profile to the last bit.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from trackbench_sonar.profile import Profile, resample_swath, spike_mask, upper_envelope

from benchmark.modalities.sonar.model import Swath


def old_resample_swath(swath: Swath, grid_m: float, spike_window: int, spike_m: float, min_beams: int) -> Profile:
    """The profile as the array form drew it (its error for an impossible span left out)."""
    valid = swath.valid
    across, depth = swath.across_m[valid], swath.depth_m[valid]
    keep = spike_mask(across, depth, spike_window, spike_m)
    across, depth = across[keep], depth[keep]
    if across.size < max(min_beams, 2):
        return Profile.empty(grid_m)
    ends = np.array([across.min(), across.max()]) / grid_m
    first, last = math.ceil(ends[0]), math.floor(ends[1])
    if last - first < 2:
        return Profile.empty(grid_m)
    envelope, segment = upper_envelope(across, depth, grid_m, first, last)
    order = np.argsort(across, kind="stable")
    gap = np.abs(np.diff(across))[segment]
    return Profile(np.arange(first, last + 1) * grid_m, envelope, grid_m, gap, across[order], depth[order])


FIELDS = ("across_m", "depth_m", "gap_m", "returns_across_m", "returns_depth_m")

beams = st.integers(0, 120)


@settings(max_examples=150, deadline=None)
@given(
    beams.flatmap(
        lambda n: st.tuples(
            arrays(float, n, elements=st.floats(-40, 40) | st.sampled_from([math.nan, math.inf])),
            arrays(float, n, elements=st.floats(0.5, 60.0) | st.sampled_from([math.nan, -math.inf])),
        )
    ),
    st.sampled_from([0, 1, 3, 5, 7, 9]),
    st.floats(0.0, 2.0) | st.just(math.inf),
    st.sampled_from([0.02, 0.05, 0.3]),
    st.integers(0, 8),
    st.booleans(),
)
def test_the_compiled_profile_is_the_array_form_to_the_last_bit(returns, window, spike_m, grid_m, min_beams, ordered):
    across, depth = returns
    if ordered:
        across = np.sort(across)
    swath = Swath(across, depth)
    new = resample_swath(swath, grid_m, spike_window=window, spike_m=spike_m, min_beams=min_beams)
    old = old_resample_swath(swath, grid_m, window, spike_m, min_beams)
    assert new.spacing_m == old.spacing_m
    for field in FIELDS:
        np.testing.assert_array_equal(getattr(new, field).view(np.int64), getattr(old, field).view(np.int64), field)
