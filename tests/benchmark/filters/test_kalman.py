"""Tests of the Kalman core: invariants of the steps, and FilterPy as an oracle.

The invariants hold for any model: the covariance stays symmetric (bit for
bit) and positive semi-definite, an update never increases it, a
prediction never decreases it below the noiseless one, and a linear model
gives the same belief whether it is passed as matrices or as functions
with Jacobians.  Random covariances are ``A A^T + eps I`` from random
``A``, over several orders of magnitude, and measurement matrices may be
rank-deficient.

The oracle runs the target filter of seeds/002 (constant velocity, eq. 5,
with the process noise of eq. 9, its ``T^(3/2)`` read as ``T^3 / 2``)
against ``filterpy.kalman.ExtendedKalmanFilter`` on the same inputs, with a
nonlinear measurement (range and bearing from the moving chase boat) and
with the rotation model of eq. (11), some measurements missing.  FilterPy's
update is the same Joseph form, so the two must agree to round-off.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest
from filterpy.kalman import ExtendedKalmanFilter
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.filters.kalman import Gaussian, predict, update

T = 0.2
SIGMA_A = 1.5
ACCELERATION = 0.05


def spd(rng: np.random.Generator, n: int, scale: float, rank: int | None = None) -> np.ndarray:
    """``A A^T + eps I``: symmetric positive definite, ill-conditioned when ``rank < n``."""
    A = rng.normal(size=(n, n if rank is None else rank)) * np.sqrt(scale)
    return A @ A.T + 1e-3 * scale * np.eye(n)


def min_eigenvalue(M: np.ndarray) -> float:
    return float(np.linalg.eigvalsh(0.5 * (M + M.T)).min())


def assert_psd(M: np.ndarray, scale: float, tol: float = 1e-9) -> None:
    assert min_eigenvalue(M) >= -tol * scale, f"not positive semi-definite: {np.linalg.eigvalsh(M)}"


def assert_symmetric(M: np.ndarray) -> None:
    assert np.array_equal(M, M.T)


systems = st.fixed_dictionaries(
    {
        "seed": st.integers(0, 2**32 - 1),
        "n": st.integers(1, 6),
        "m": st.integers(1, 4),
        "state_scale": st.integers(-3, 3).map(lambda e: 10.0**e),
        "noise_scale": st.integers(-3, 3).map(lambda e: 10.0**e),
        "h_rank": st.integers(0, 4),
        "p_rank": st.integers(0, 6),
    }
)


def draw_system(s: dict) -> dict:
    """A random belief, transition, measurement matrix and noises."""
    rng = np.random.default_rng(s["seed"])
    n, m = s["n"], s["m"]
    P = spd(rng, n, s["state_scale"], rank=min(s["p_rank"], n))
    rank = min(s["h_rank"], m, n)
    H = rng.normal(size=(m, rank)) @ rng.normal(size=(rank, n)) if rank < min(m, n) else rng.normal(size=(m, n))
    return {
        "belief": Gaussian(rng.normal(size=n) * np.sqrt(s["state_scale"]), P),
        "F": rng.normal(size=(n, n)),
        "H": H,
        "process_noise": spd(rng, n, s["noise_scale"] * s["state_scale"]),
        "measurement_noise": spd(rng, m, s["noise_scale"]),
        "z": rng.normal(size=m) * np.sqrt(s["noise_scale"]),
    }


# ---------------------------------------------------------------- invariants


@settings(max_examples=150, deadline=None)
@given(systems)
def test_covariance_stays_symmetric_and_psd(s: dict) -> None:
    d = draw_system(s)
    prior = predict(d["belief"], d["F"], None, d["process_noise"])
    posterior = update(prior, d["z"], d["H"], None, d["measurement_noise"])
    for belief in (prior, posterior):
        assert_symmetric(belief.covariance)
        assert_psd(belief.covariance, np.linalg.norm(prior.covariance, 2))
        assert np.all(np.isfinite(belief.mean))


@settings(max_examples=150, deadline=None)
@given(systems)
def test_update_never_increases_the_covariance(s: dict) -> None:
    d = draw_system(s)
    prior = d["belief"]
    posterior = update(prior, d["z"], d["H"], None, d["measurement_noise"])
    assert_psd(prior.covariance - posterior.covariance, np.linalg.norm(prior.covariance, 2))


@settings(max_examples=100, deadline=None)
@given(systems)
def test_prediction_adds_the_process_noise(s: dict) -> None:
    """``P_pred - F P F^T = Q``: the noise only adds; with ``F = I`` (a random walk) ``P_pred >= P``."""
    d = draw_system(s)
    n = d["belief"].mean.size
    noisy = predict(d["belief"], d["F"], None, d["process_noise"])
    noiseless = predict(d["belief"], d["F"], None, np.zeros((n, n)))
    scale = np.linalg.norm(noisy.covariance, 2)
    np.testing.assert_allclose(noisy.covariance - noiseless.covariance, d["process_noise"], atol=1e-12 * scale)
    np.testing.assert_array_equal(noisy.mean, noiseless.mean)
    assert_psd(noisy.covariance - noiseless.covariance, scale)

    walk = predict(d["belief"], np.eye(n), None, d["process_noise"])
    assert_psd(walk.covariance - d["belief"].covariance, scale)
    np.testing.assert_array_equal(walk.mean, d["belief"].mean)


@settings(max_examples=100, deadline=None)
@given(systems)
def test_linear_model_through_the_extended_path(s: dict) -> None:
    """Matrices, and functions with Jacobians (as arrays or as functions), give the same belief."""
    d = draw_system(s)
    F, H = d["F"], d["H"]
    by_matrix = predict(d["belief"], F, None, d["process_noise"])
    by_function = predict(d["belief"], lambda x: F @ x, F, d["process_noise"])
    by_functions = predict(d["belief"], lambda x: F @ x, lambda x: F, d["process_noise"])
    for other in (by_function, by_functions):
        np.testing.assert_array_equal(other.covariance, by_matrix.covariance)
        np.testing.assert_allclose(other.mean, by_matrix.mean, rtol=1e-12, atol=1e-12 * np.abs(by_matrix.mean).max())

    posterior = update(by_matrix, d["z"], H, None, d["measurement_noise"])
    others = (
        update(by_matrix, d["z"], lambda x: H @ x, H, d["measurement_noise"]),
        update(by_matrix, d["z"], lambda x: H @ x, lambda x: H, d["measurement_noise"]),
    )
    scale = np.abs(posterior.mean).max() + np.abs(by_matrix.mean).max()
    for other in others:
        np.testing.assert_array_equal(other.covariance, posterior.covariance)
        np.testing.assert_allclose(other.mean, posterior.mean, rtol=1e-9, atol=1e-9 * scale)


@settings(max_examples=100, deadline=None)
@given(systems)
def test_update_matches_the_textbook_equations(s: dict) -> None:
    """Table 2, lines 4-6 of seeds/002, computed here with plain numpy: the Joseph form equals ``(I - K H) P``."""
    d = draw_system(s)
    prior, H, Q, z = d["belief"], d["H"], d["measurement_noise"], d["z"]
    P, mu = prior.covariance, prior.mean
    K = np.linalg.solve(H @ P @ H.T + Q, H @ P).T
    expected_mean = mu + K @ (z - H @ mu)
    expected_covariance = (np.eye(mu.size) - K @ H) @ P

    posterior = update(prior, z, H, None, Q)
    scale = np.linalg.norm(P, 2)
    np.testing.assert_allclose(posterior.covariance, expected_covariance, atol=1e-8 * scale)
    mean_scale = np.abs(expected_mean).max() + np.abs(mu).max() + np.sqrt(scale)
    np.testing.assert_allclose(posterior.mean, expected_mean, atol=1e-8 * mean_scale)


@settings(max_examples=50, deadline=None)
@given(systems)
def test_steps_leave_their_inputs_alone(s: dict) -> None:
    """Beliefs, models and noises handed to the steps come back unchanged."""
    d = draw_system(s)
    copies = {k: (v.mean.copy(), v.covariance.copy()) if isinstance(v, Gaussian) else v.copy() for k, v in d.items()}
    prior = predict(d["belief"], d["F"], None, d["process_noise"], control=np.ones(d["F"].shape[0]))
    update(prior, d["z"], d["H"], None, d["measurement_noise"])
    prior_copy = prior.mean.copy(), prior.covariance.copy()
    update(prior, d["z"], lambda x: d["H"] @ x, d["H"], d["measurement_noise"])
    np.testing.assert_array_equal(prior.mean, prior_copy[0])
    np.testing.assert_array_equal(prior.covariance, prior_copy[1])
    for key, value in d.items():
        if isinstance(value, Gaussian):
            np.testing.assert_array_equal(value.mean, copies[key][0])
            np.testing.assert_array_equal(value.covariance, copies[key][1])
        else:
            np.testing.assert_array_equal(value, copies[key])


def test_control_input_shifts_only_the_mean() -> None:
    rng = np.random.default_rng(3)
    belief = Gaussian(rng.normal(size=4), spd(rng, 4, 1.0))
    A, R = stereo_transition(), stereo_process_noise()
    Bu = np.array([T**2 / 2, T**2 / 2, T, T]) * ACCELERATION
    plain = predict(belief, A, None, R)
    driven = predict(belief, A, None, R, control=Bu)
    np.testing.assert_array_equal(driven.covariance, plain.covariance)
    np.testing.assert_allclose(driven.mean - plain.mean, Bu, atol=1e-15)
    via_function = predict(belief, lambda x: A @ x, A, R, control=Bu)
    np.testing.assert_allclose(via_function.mean, driven.mean, rtol=1e-14)


def test_missing_measurements_only_predict() -> None:
    """During a gap the estimate follows the motion model (seeds/004 eq. 17) and its uncertainty grows."""
    rng = np.random.default_rng(11)
    A, R = stereo_transition(), stereo_process_noise()
    H = np.hstack([np.eye(2), np.zeros((2, 2))])
    Q = np.diag([0.5, 0.2])
    belief = Gaussian(np.zeros(4), 10.0 * np.eye(4))
    for _ in range(30):
        belief = update(predict(belief, A, None, R), rng.normal(size=2), H, None, Q)
    traces = [np.trace(belief.covariance)]
    for _ in range(20):
        prior = predict(belief, A, None, R)
        assert update(prior, None, H, None, Q) is prior
        np.testing.assert_allclose(prior.mean, A @ belief.mean, rtol=1e-14, atol=1e-14)
        assert np.all(np.diag(prior.covariance) > np.diag(belief.covariance))
        belief = prior
        traces.append(np.trace(belief.covariance))
    assert np.all(np.diff(traces) > 0)
    recovered = update(predict(belief, A, None, R), rng.normal(size=2), H, None, Q)
    assert np.trace(recovered.covariance) < traces[-1]


# ---------------------------------------------------------------- inputs


def test_gaussian_checks_and_converts() -> None:
    g = Gaussian([[1], [2]], [[1, 0], [0, 1]])
    assert g.mean.shape == (2,) and g.mean.dtype == float and g.covariance.dtype == float
    with pytest.raises(ValueError, match="covariance"):
        Gaussian(np.zeros(3), np.eye(2))


def test_integer_and_strided_inputs_are_accepted() -> None:
    rng = np.random.default_rng(5)
    belief = Gaussian(rng.normal(size=3), spd(rng, 3, 1.0))
    F = np.asfortranarray(rng.normal(size=(3, 3)))
    H = np.array([[1, 0, 0], [0, 1, 1]])
    Q = np.eye(2)
    reference = update(predict(belief, np.ascontiguousarray(F), None, np.eye(3)), [1.0, 2.0], H.astype(float), None, Q)
    other = update(predict(belief, F, None, np.eye(3, dtype=int)), [1, 2], H, None, np.eye(4)[::2, ::2])
    np.testing.assert_array_equal(other.mean, reference.mean)
    np.testing.assert_array_equal(other.covariance, reference.covariance)


@pytest.mark.parametrize(
    ("step", "match"),
    [
        (lambda b: predict(b, np.eye(2), None, np.eye(3)), "process_noise"),
        (lambda b: predict(b, np.eye(2), None, np.ones(2)), "process_noise"),
        (lambda b: predict(b, np.eye(3), None, np.eye(2)), "transition matrix"),
        (lambda b: predict(b, lambda x: x, None, np.eye(2)), "Jacobian"),
        (lambda b: predict(b, lambda x: x[:1], np.eye(2), np.eye(2)), "transition function"),
        (lambda b: predict(b, np.eye(2), None, np.eye(2), control=np.ones(3)), "control"),
        (lambda b: update(b, [1.0], np.ones((1, 2)), None, np.eye(2)), "measurement_noise"),
        (lambda b: update(b, [1.0, 2.0], np.ones((1, 2)), None, np.eye(1)), "measurement"),
        (lambda b: update(b, [1.0], np.ones(2), None, np.eye(1)), "measurement matrix"),
        (lambda b: update(b, [1.0], np.ones((1, 3)), None, np.eye(1)), "measurement matrix"),
        (lambda b: update(b, [1.0], lambda x: x[:1], None, np.eye(1)), "Jacobian"),
        (lambda b: update(b, [1.0], lambda x: x, np.ones((1, 2)), np.eye(1)), r"h\(mean\)"),
        (lambda b: update(b, [1.0], np.zeros((1, 2)), None, np.zeros((1, 1))), "positive definite"),
    ],
)
def test_bad_inputs_are_named(step: Callable[[Gaussian], Gaussian], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        step(Gaussian(np.zeros(2), np.eye(2)))


# ---------------------------------------------------------------- FilterPy oracle


def stereo_transition() -> np.ndarray:
    """``A_t`` of seeds/002 eq. (5)-(6), state ``(X, Y, X_dot, Y_dot)``."""
    return np.array([[1.0, 0.0, T, 0.0], [0.0, 1.0, 0.0, T], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])


def stereo_process_noise() -> np.ndarray:
    """``R_t`` of seeds/002 eq. (9), with ``T^3 / 2`` off the diagonal."""
    p, c, v = T**4 / 4, T**3 / 2, T**2
    return SIGMA_A**2 * np.array([[p, 0, c, 0], [0, p, 0, c], [c, 0, v, 0], [0, c, 0, v]])


def range_bearing(chase: np.ndarray, heading: float, distance: float) -> tuple[Callable, Callable, np.ndarray]:
    """Range and bearing (from the bow) of the target seen from the chase boat, their Jacobian and noise.

    The range deviation grows with the square of the distance, as stereo depth does (seeds/002, Table 3).
    """

    def h(x: np.ndarray) -> np.ndarray:
        dX, dY = x[0] - chase[0], x[1] - chase[1]
        return np.array([np.hypot(dX, dY), np.arctan2(dY, dX) - heading])

    def jacobian(x: np.ndarray) -> np.ndarray:
        dX, dY = x[0] - chase[0], x[1] - chase[1]
        r2 = dX * dX + dY * dY
        r = np.sqrt(r2)
        return np.array([[dX / r, dY / r, 0.0, 0.0], [-dY / r2, dX / r2, 0.0, 0.0]])

    sd_range, sd_bearing = 0.1 + 0.004 * distance**2, 0.01
    correlation = 0.3
    Q = np.array([[sd_range**2, correlation * sd_range * sd_bearing], [0.0, sd_bearing**2]])
    Q[1, 0] = Q[0, 1]
    return h, jacobian, Q


def rotation(chase: np.ndarray, heading: float, distance: float) -> tuple[Callable, Callable, np.ndarray]:
    """The relative position in the chase boat's frame, seeds/002 eq. (11), its Jacobian, eq. (12), and noise.

    The noise is larger along the line of sight (depth) than across it, both growing with the distance.
    """
    c, s = np.cos(heading), np.sin(heading)
    H = np.array([[c, s, 0.0, 0.0], [-s, c, 0.0, 0.0]])
    offset = H[:, :2] @ chase
    sd_depth, sd_lateral = 0.1 + 0.004 * distance**2, 0.02 + 0.005 * distance
    Q = np.array([[sd_depth**2, 0.2 * sd_depth * sd_lateral], [0.2 * sd_depth * sd_lateral, sd_lateral**2]])
    return (lambda x: H @ x - offset), (lambda x: H), Q


def simulate(rng: np.random.Generator, steps: int, model: Callable) -> list[tuple]:
    """A target run with a chase boat following it about 12 m behind, weaving a little.

    Per step: the measurement function, its Jacobian, the measurement noise, ``z`` (or None) and the truth.
    """
    A, B = stereo_transition(), np.array([T**2 / 2, T**2 / 2, T, T])
    target = np.array([20.0, 5.0, 3.0, 1.0])
    chase = np.array([10.0, 0.0])
    data = []
    for k in range(steps):
        target = A @ target + B * rng.normal(ACCELERATION, 0.3)
        line_of_sight = target[:2] - chase
        distance = np.hypot(*line_of_sight)
        heading = np.arctan2(line_of_sight[1], line_of_sight[0]) + 0.2 * np.sin(0.1 * k)
        speed = np.hypot(*target[2:]) + 0.5 * (distance - 12.0)
        chase = chase + T * speed * np.array([np.cos(heading), np.sin(heading)])
        h, jacobian, Q = model(chase, heading, np.hypot(*(target[:2] - chase)))
        z = None if rng.random() < 0.15 else h(target) + np.linalg.cholesky(Q) @ rng.normal(size=2)
        data.append((h, jacobian, Q, z, target.copy()))
    return data


@pytest.mark.parametrize("model", [range_bearing, rotation], ids=["range-bearing", "eq11-rotation"])
def test_matches_filterpy_extended_kalman_filter(model: Callable) -> None:
    rng = np.random.default_rng(2024)
    data = simulate(rng, 200, model)
    A, R = stereo_transition(), stereo_process_noise()
    B = np.array([[T**2 / 2], [T**2 / 2], [T], [T]])
    x0, P0 = np.array([19.0, 6.0, 2.0, 0.0]), np.diag([4.0, 4.0, 2.0, 2.0])
    assert any(z is None for *_, z, _ in data) and sum(z is not None for *_, z, _ in data) > 150

    # FilterPy's names are the other way round: its Q is the process noise, its R the measurement noise.
    oracle = ExtendedKalmanFilter(dim_x=4, dim_z=2, dim_u=1)
    oracle.x, oracle.P, oracle.F, oracle.B, oracle.Q = x0.reshape(4, 1), P0.copy(), A, B, R
    belief = Gaussian(x0, P0)
    means = []

    def agree(step: str, k: int) -> None:
        scale = np.abs(oracle.P).max()
        np.testing.assert_allclose(belief.mean, oracle.x.ravel(), rtol=1e-9, atol=1e-9, err_msg=f"{step} mean, {k}")
        np.testing.assert_allclose(
            belief.covariance, oracle.P, rtol=1e-9, atol=1e-9 * scale, err_msg=f"{step} covariance, step {k}"
        )

    for k, (h, jacobian, Q, z, _) in enumerate(data):
        oracle.predict(u=ACCELERATION)
        belief = predict(belief, A, None, R, control=B.ravel() * ACCELERATION)
        agree("predicted", k)
        oracle.update(
            None if z is None else z.reshape(2, 1),
            HJacobian=lambda x: jacobian(x.ravel()),
            Hx=lambda x: h(x.ravel()).reshape(2, 1),
            R=Q,
        )
        belief = update(belief, z, h, jacobian, Q)
        agree("updated", k)
        means.append(belief.mean)
    # Both filters tracked the target, not just agreed with each other.
    errors = [np.hypot(*(m[:2] - truth[:2])) for m, truth in zip(means, (d[-1] for d in data), strict=True)]
    assert np.median(errors[50:]) < 1.0
