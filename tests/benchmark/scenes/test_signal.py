"""Signals: a mean, a slope, waves, events and smoothed noise, sampled at every frame."""

from __future__ import annotations

import numpy as np
import pytest

from benchmark.scenes.signal import Event, Signal, Wave, evaluate_signal


def _rng(seed: int = 0) -> np.random.Generator:
    return np.random.default_rng(seed)


def test_step_event_moves_the_signal_and_stays() -> None:
    signal = Signal(mean=1.0, events=(Event(frame=20.0, amplitude=3.0, duration_frames=6.0),))
    values = evaluate_signal(signal, 40, _rng())
    assert np.all(values[:17] == 1.0)
    assert np.all(values[24:] == pytest.approx(4.0))
    assert np.all(np.diff(values) >= 0)


def test_pulse_event_goes_out_and_comes_back() -> None:
    signal = Signal(events=(Event(frame=10.0, amplitude=-2.0, duration_frames=8.0, shape="pulse"),))
    values = evaluate_signal(signal, 30, _rng())
    assert values.min() == pytest.approx(-2.0)
    assert int(np.argmin(values)) == 10
    assert np.all(values[15:] == pytest.approx(0.0))


def test_wave_is_silent_outside_its_window() -> None:
    signal = Signal(waves=(Wave(amplitude=5.0, period_frames=7.0, start_frame=10.0, stop_frame=30.0),))
    values = evaluate_signal(signal, 50, _rng())
    assert np.all(values[:10] == 0.0) and np.all(values[31:] == 0.0)
    assert np.max(np.abs(values[10:31])) > 4.0


def test_mean_and_slope_without_noise_are_exact_and_draw_the_same_for_a_seed() -> None:
    values = evaluate_signal(Signal(mean=2.0, slope_per_frame=0.5), 5, _rng())
    np.testing.assert_array_equal(values, [2.0, 2.5, 3.0, 3.5, 4.0])
    noisy = Signal(noise_std=0.3)
    np.testing.assert_array_equal(evaluate_signal(noisy, 20, _rng(4)), evaluate_signal(noisy, 20, _rng(4)))
    assert not np.array_equal(evaluate_signal(noisy, 20, _rng(4)), evaluate_signal(noisy, 20, _rng(5)))


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: Wave(amplitude=1.0, period_frames=0.0), r"period_frames\n  Input should be greater than 0"),
        (lambda: Wave(1.0, 5.0, start_frame=10.0, stop_frame=5.0), "start_frame must not exceed stop_frame"),
        (lambda: Wave(1.0, 5.0, taper_frames=-1.0), r"taper_frames\n  Input should be greater than or equal to 0"),
        (lambda: Event(frame=3.0, amplitude=1.0, shape="ramp"), "'step' or 'pulse'"),
        (lambda: Event(frame=3.0, amplitude=1.0, duration_frames=0.0), r"duration_frames\n  Input should be greater"),
        (lambda: Signal(noise_std=-1.0), r"noise_std\n  Input should be greater than or equal to 0"),
        (lambda: Signal(mean="1"), r"mean\n  Input should be a valid number"),
    ],
)
def test_invalid_definitions_are_refused(make, message) -> None:
    with pytest.raises(ValueError, match=message):
        make()
