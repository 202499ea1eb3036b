"""Measurement model of seeds/002, eqs. (10)-(12), on the filter's state."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from trackbench_stereo_ekf.measurement import observation_jacobian, observe

from benchmark.modalities.stereo.geometry import to_north_east
from benchmark.modalities.stereo.model import ChaseNavigation

coordinate = st.floats(-200.0, 200.0)
heading = st.floats(-math.pi, math.pi)


@given(x=coordinate, y=coordinate, X=coordinate, Y=coordinate, psi=heading)
def test_observe_inverts_eq_10(x, y, X, Y, psi):
    navigation = ChaseNavigation((X, Y), psi)
    position = to_north_east(x, y, navigation.position_m, navigation.heading)
    state = np.array([*position, 1.0, -2.0])
    np.testing.assert_allclose(observe(state, navigation), [x, y], atol=1e-9)


@given(X=coordinate, Y=coordinate, psi=heading)
def test_jacobian_is_the_rotation_on_positions_and_zero_on_velocities(X, Y, psi):
    navigation = ChaseNavigation((X, Y), psi)
    state = np.array([X + 7.0, Y - 3.0, 2.0, 1.0])
    h = 1e-6
    numeric = np.column_stack(
        [(observe(state + h * e, navigation) - observe(state - h * e, navigation)) / (2 * h) for e in np.eye(4)]
    )
    H = observation_jacobian(navigation)
    np.testing.assert_allclose(H, numeric, atol=1e-7)
    assert np.all(H[:, 2:] == 0.0)
    np.testing.assert_allclose(H[:, :2] @ H[:, :2].T, np.eye(2), atol=1e-12)
