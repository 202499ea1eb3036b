"""The system model f of seeds/004 (eqs. 7-10, 12) and its Jacobian F."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_foresti.measurement import PipeCamera
from trackbench_foresti.motion import advance, advance_jacobian, speed_vector

from benchmark.modalities.camera.model import VehicleSpeeds
from benchmark.modalities.camera.scenes.motion import Trajectory, psi_matrix, vehicle_speeds

CAMERA = PipeCamera(
    focal_px=380.0, size=(320, 240), diameter_m=0.2, nominal_tilt=math.radians(60.0), frame_interval_s=0.04
)

states = st.tuples(
    st.floats(-0.4, 0.4),
    st.floats(0.6, 2.5),
    st.floats(-0.2, 0.2),
    st.floats(0.6, 1.4),
    st.floats(-0.15, 0.15),
).map(np.array)
speeds = st.tuples(st.floats(-0.5, 0.5), st.floats(-0.3, 0.3), st.floats(0.0, 2.0)).map(np.array)


@settings(max_examples=50, deadline=None)
@given(states, speeds)
def test_advance_inverts_the_speeds_the_scenes_report(state, speed):
    """The scenes solve eq. (7) for the speeds from consecutive poses; f moves the camera back there."""
    moved = advance(state, speed, CAMERA)
    # C_z is not in the state: give the scene the C_z step eq. (7) makes.
    dz = (psi_matrix(state[2], state[3] - CAMERA.nominal_tilt, state[4]) @ speed)[2] * CAMERA.frame_interval_s
    angles = [np.array([value] * 2) for value in state[2:]]
    centres = np.array([state[0], moved[0]]), np.array([state[1], moved[1]]), np.array([0.0, dz])
    trajectory = Trajectory(*centres, *angles)
    recovered = vehicle_speeds(trajectory, CAMERA.frame_interval_s, CAMERA.nominal_tilt)[0]
    np.testing.assert_allclose(recovered, speed, atol=1e-9)
    np.testing.assert_array_equal(moved[2:], state[2:])


def test_a_level_vehicle_moving_forward_keeps_its_place_over_the_pipe():
    state = np.array([0.1, 1.5, 0.0, CAMERA.nominal_tilt])
    np.testing.assert_allclose(advance(state, np.array([0.0, 0.0, 1.5]), CAMERA), state, atol=1e-12)
    sideways = advance(state, np.array([0.5, 0.0, 0.0]), CAMERA)
    np.testing.assert_allclose(sideways, state + [0.5 * CAMERA.frame_interval_s, 0, 0, 0], atol=1e-12)


@settings(max_examples=50, deadline=None)
@given(states, speeds, st.booleans())
def test_the_jacobian_matches_central_differences(state, speed, with_roll):
    x = state if with_roll else state[:4]
    step = 1e-6
    numeric = np.stack(
        [
            (advance(x + step * e, speed, CAMERA) - advance(x - step * e, speed, CAMERA)) / (2 * step)
            for e in np.eye(len(x))
        ],
        axis=1,
    )
    np.testing.assert_allclose(advance_jacobian(x, speed, CAMERA), numeric, atol=1e-8)


def test_speed_vector_orders_lateral_vertical_frontal():
    np.testing.assert_array_equal(speed_vector(VehicleSpeeds(1.0, 2.0, 3.0)), [1.0, 2.0, 3.0])
