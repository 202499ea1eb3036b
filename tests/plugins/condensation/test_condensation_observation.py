"""Tests of the observation model, eq. (4.11) and the brighter-centre term."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_condensation.measure import border_scores
from trackbench_condensation.observation import BorderObservation, as_grey_image

from benchmark.errors import DataError
from benchmark.modalities.camera.model import CableState

TRUTH = CableState(12.0, math.radians(8.0), 34.0, math.radians(1.5))


def eq_4_11(scores: np.ndarray, epsilon: float) -> np.ndarray:
    """Unnormalised weights from the two border counts, written out as the thesis states them.

    Parameters
    ----------
    scores : numpy.ndarray
        ``(N, 2)`` border counts ``c_l``, ``c_r``.
    epsilon : float
        The weight of a particle whose counts do not have opposite signs.

    Returns
    -------
    numpy.ndarray
        ``(N,)`` weights ``pi'``: ``|c_l - c_r|`` where the counts have
        strictly opposite signs, ``epsilon`` elsewhere.

    References
    ----------
    seeds/000, eq. (4.11).
    """
    left, right = scores[:, 0], scores[:, 1]
    opposite = ((left > 0) & (right < 0)) | ((left < 0) & (right > 0))
    return np.where(opposite, np.abs(left - right), epsilon)


def border_counts(model: BorderObservation, states: np.ndarray, image: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The border counts ``(N, 2)`` of ``states`` and their numbers of sample points, as ``model`` measures them."""
    return border_scores(
        np.ascontiguousarray(states, dtype=float),
        as_grey_image(image),
        model.taps,
        float(model.sample_distance_px),
        model.interpolation == "bilinear",
    )


def particle(state: CableState, **shift: float) -> np.ndarray:
    values = dict(d=state.d, alpha=state.alpha, w=state.w, beta=state.beta)
    for key, delta in shift.items():
        values[key] += delta
    return np.array([values["d"], values["alpha"], values["w"], values["beta"], 0.0, 0.0])


def test_eq_4_11_accepts_opposite_signs_only():
    counts = np.array([[300.0, -200.0], [-300.0, 200.0], [300.0, 200.0], [-1.0, -5.0], [0.0, -50.0]])
    np.testing.assert_array_equal(eq_4_11(counts, 0.5), [500.0, 500.0, 0.5, 0.5, 0.5])


@pytest.mark.parametrize("contrast", [-60.0, 60.0], ids=["dark", "bright"])
def test_true_state_outweighs_shifted_and_rotated_states(scene, contrast):
    image = scene.draw_cable(TRUTH, contrast=contrast)
    model = BorderObservation()
    states = np.array(
        [
            particle(TRUTH),
            particle(TRUTH, d=4.0),
            particle(TRUTH, d=-4.0),
            particle(TRUTH, alpha=math.radians(3.0)),
            particle(TRUTH, alpha=math.radians(-3.0)),
            particle(TRUTH, w=8.0),
            particle(TRUTH, w=-8.0),
        ]
    )
    weights = model.likelihood(states, image)
    assert weights[0] > model.epsilon
    assert np.all(weights[0] > weights[1:])


def test_each_border_sees_its_polarity(scene):
    model = BorderObservation()
    dark, _ = border_counts(model, particle(TRUTH)[None], scene.draw_cable(TRUTH, contrast=-60.0))
    bright, _ = border_counts(model, particle(TRUTH)[None], scene.draw_cable(TRUTH, contrast=60.0))
    # Dark inside: bright behind the left border's filter (outside), dark behind the right one's (inside).
    assert dark[0, 0] > 0 > dark[0, 1]
    assert bright[0, 0] < 0 < bright[0, 1]


def test_borders_of_the_same_polarity_get_epsilon(scene):
    # Two steps that both brighten to the right: one border matches a dark
    # cable, the other a bright one.
    image = scene.staircase(steps=(-40.0, 40.0))
    model = BorderObservation()
    on_steps = np.array([[0.0, 0.0, 80.0, 0.0, 0.0, 0.0]])
    counts, _ = border_counts(model, on_steps, image)
    assert counts[0, 0] < 0 and counts[0, 1] < 0
    assert model.likelihood(on_steps, image)[0] == model.epsilon
    # A band on the same image, between a darkening and a brightening step, is accepted.
    band = scene.staircase(steps=(-40.0, 40.0), levels=(160, 60, 160))
    assert model.likelihood(on_steps, band)[0] > 1000


def test_particles_outside_the_image_or_with_no_width_get_epsilon(scene):
    image = scene.draw_cable(TRUTH)
    model = BorderObservation(epsilon=0.25)
    states = np.array([particle(TRUTH, d=1000.0), particle(TRUTH, d=-5000.0), particle(TRUTH, w=-TRUTH.w - 5.0)])
    np.testing.assert_array_equal(model.likelihood(states, image), 0.25)


@settings(max_examples=40, deadline=None)
@given(
    d=st.floats(-150, 150),
    alpha=st.floats(-45, 45),
    w=st.floats(5, 100),
    beta=st.floats(0, 10),
    exponent=st.sampled_from([1.0, 6.0]),
    interpolation=st.sampled_from(["nearest", "bilinear"]),
)
def test_weights_of_table_5_2_states_are_finite_and_at_least_epsilon(scene, d, alpha, w, beta, exponent, interpolation):
    image = scene.draw_cable(TRUTH, seed=3)
    model = BorderObservation(exponent=exponent, interpolation=interpolation)
    state = np.array([[d, math.radians(alpha), w, math.radians(beta), 0.0, 0.0]])
    weight = model.likelihood(state, image)
    assert weight.shape == (1,)
    assert np.isfinite(weight[0]) and weight[0] >= model.epsilon**exponent


def test_exponent_sharpens_the_weights(scene):
    image = scene.draw_cable(TRUTH)
    states = np.array([particle(TRUTH), particle(TRUTH, d=2.0)])
    plain = BorderObservation(exponent=1.0).likelihood(states, image)
    sharp = BorderObservation(exponent=6.0).likelihood(states, image)
    assert sharp[1] / sharp[0] == pytest.approx((plain[1] / plain[0]) ** 6)


def test_centre_term_adds_only_to_accepted_particles(scene):
    width, height = scene.SIZE
    x = np.arange(width) - (width - 1) / 2.0
    profile = np.where(np.abs(x) < 20, 60 + 50 * np.cos(np.pi * x / 40.0), 170)
    image = np.tile(profile, (height, 1)).astype(np.uint8)
    states = np.array([[0.0, 0.0, 40.0, 0.0, 0.0, 0.0], [300.0, 0.0, 40.0, 0.0, 0.0, 0.0]])
    plain = BorderObservation().score(states, image)
    centred = BorderObservation(centre_weight=2.0).score(states, image)
    assert centred[0] > plain[0]
    assert centred[1] == plain[1] == BorderObservation().epsilon


@pytest.mark.parametrize("bad", [np.zeros((3, 4, 3), np.uint8), np.zeros((0, 5), np.uint8), np.zeros(7)])
def test_non_grey_images_are_a_data_error(bad):
    with pytest.raises(DataError, match="grey image"):
        as_grey_image(bad)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"sample_distance_px": 0.0},
        {"epsilon": 0.0},
        {"interpolation": "cubic"},
        {"filter_size_px": 4},
        {"exponent": 0.0},
    ],
)
def test_bad_settings_are_rejected(kwargs):
    with pytest.raises(ValueError):
        BorderObservation(**kwargs)


@pytest.mark.parametrize("contrast", [-60.0, 60.0])
def test_compiled_weights_follow_eq_4_11_of_the_border_counts(scene, contrast):
    image = scene.draw_cable(TRUTH, contrast=contrast, seed=5)
    rng = np.random.default_rng(0)
    states = np.column_stack(
        [rng.uniform(-60, 60, 300), rng.uniform(-0.3, 0.3, 300), rng.uniform(-10, 60, 300), rng.uniform(0, 0.1, 300)]
    )
    model = BorderObservation(epsilon=0.01)
    counts, _ = border_counts(model, states, image)
    expected = np.where(states[:, 2] > 0, eq_4_11(counts, 0.01), 0.01)
    np.testing.assert_allclose(model.score(states, image), np.maximum(expected, 0.01))
    assert 0 < np.mean(expected > 0.01) < 1
