"""The descriptors' pixels and grid densities equal those of their straightforward formulation, bit for bit.

:func:`pixel_kinds` works only at edge pixels where it can (one compiled
pass over them), counts edge pixels with integer box sums, finds specks
with saturated ``uint8`` differences, and :func:`densities_at` sums the
grid's squares exactly with compiled running sums.  The oracles here are
the first, whole-image ``float32`` formulations.
"""

from __future__ import annotations

import types

import cv2
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from trackbench_texture.descriptors import _rounded_grey, densities_at, pixel_kinds
from trackbench_texture.params import DescriptorParams

_NEIGHBOURS = np.array([[1, 1, 1], [1, 0, 1], [1, 1, 1]], np.float32)


def _odd(size: int) -> int:
    return size if size % 2 else size + 1


def _box(values: np.ndarray, size: int, normalize: bool) -> np.ndarray:
    return cv2.boxFilter(values, cv2.CV_32F, (size, size), normalize=normalize, borderType=cv2.BORDER_REFLECT)


def _filter(values: np.ndarray, mask: np.ndarray) -> np.ndarray:
    return cv2.filter2D(values, cv2.CV_32F, mask, borderType=cv2.BORDER_REFLECT)


def _coherence(edges, cos2, sin2, size):
    count, c, s = (_box(layer, _odd(size), False) for layer in (edges, cos2, sin2))
    return count, np.clip(np.sqrt(c * c + s * s) / np.maximum(count, 1.0), 0.0, 1.0)


def _first_pixel_kinds(image: np.ndarray, params: DescriptorParams) -> tuple[np.ndarray, ...]:
    """edges, straight, abrupt, ends, specks, soft as ``float32`` maps, every one computed over the whole image."""
    grey = image.astype(np.float32)
    if params.smoothing_sigma > 0:
        grey = cv2.GaussianBlur(grey, (0, 0), params.smoothing_sigma, borderType=cv2.BORDER_REFLECT)
    smooth8 = np.clip(np.rint(grey), 0, 255).astype(np.uint8)
    edges = (cv2.Canny(smooth8, params.edge_low, params.edge_high, L2gradient=True) > 0).astype(np.float32)
    gu = cv2.Sobel(grey, cv2.CV_32F, 1, 0, ksize=3, borderType=cv2.BORDER_REFLECT)
    gv = cv2.Sobel(grey, cv2.CV_32F, 0, 1, ksize=3, borderType=cv2.BORDER_REFLECT)
    power = gu * gu + gv * gv + np.float32(1e-6)
    cos2 = edges * (gu * gu - gv * gv) / power
    sin2 = edges * (2.0 * gu * gv) / power
    line_count, line_coherence = _coherence(edges, cos2, sin2, params.line_length_px)
    straight = edges * (
        (line_count >= params.straight_fill * _odd(params.line_length_px))
        & (line_coherence >= params.straight_coherence)
    )
    _, turn_coherence = _coherence(edges, cos2, sin2, params.turn_window_px)
    abrupt = edges * np.clip(1.0 - turn_coherence, 0.0, 1.0)
    ends = edges * (np.abs(_filter(edges, _NEIGHBOURS) - 1.0) < 0.5)
    raw = image.astype(np.float32)
    brightest = cv2.dilate(raw, _NEIGHBOURS.astype(np.uint8), borderType=cv2.BORDER_REFLECT)
    darkest = cv2.erode(raw, _NEIGHBOURS.astype(np.uint8), borderType=cv2.BORDER_REFLECT)
    specks = ((raw - brightest > params.granular_step) | (darkest - raw > params.granular_step)).astype(np.float32)
    soft = (np.abs(raw - _filter(raw, _NEIGHBOURS / 8.0)) < params.soft_step).astype(np.float32)
    return edges, straight, abrupt, ends, specks, soft


@st.composite
def images(draw) -> np.ndarray:
    """Grey images down to 1 x 1: noise, blurred relief with lines and specks, or saturated patches."""
    height, width = draw(st.integers(1, 64)), draw(st.integers(1, 64))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    kind = draw(st.sampled_from(["noise", "scene", "saturated"]))
    if kind == "noise":
        return rng.integers(0, 256, (height, width), dtype=np.uint8)
    if kind == "saturated":
        return np.where(rng.random((height, width)) < 0.3, 0, 255).astype(np.uint8)
    relief = cv2.GaussianBlur(rng.normal(120.0, 40.0, (height, width)).astype(np.float32), (0, 0), 2.0)
    image = np.clip(relief, 0, 255).astype(np.uint8)
    for _ in range(int(rng.integers(0, 6))):
        a, b = rng.integers(0, max(width, height), 2), rng.integers(0, max(width, height), 2)
        cv2.line(image, (int(a[0]), int(a[1])), (int(b[0]), int(b[1])), int(rng.integers(0, 256)), 1)
    specks = rng.random((height, width)) < 0.02
    image[specks] = rng.integers(0, 256, int(specks.sum()))
    return image


def _steps() -> st.SearchStrategy[float]:
    """Grey-level steps, often whole numbers or their neighbours, where float32 rounding matters."""
    whole = st.integers(0, 40).map(float)
    near = st.tuples(st.integers(0, 40), st.sampled_from([-1e-9, -1e-7, 1e-7, 1e-9])).map(
        lambda pair: max(0.0, pair[0] + pair[1])
    )
    return st.one_of(whole, near, st.floats(0.0, 300.0))


@st.composite
def descriptor_params(draw) -> DescriptorParams:
    low = draw(st.floats(0.0, 120.0))
    return DescriptorParams(
        smoothing_sigma=draw(st.sampled_from([0.0, 0.7, 1.0, 2.5])),
        edge_low=low,
        edge_high=low + draw(st.floats(0.0, 120.0)),
        line_length_px=draw(st.integers(3, 21)),
        straight_fill=draw(st.floats(0.0, 1.0)),
        straight_coherence=draw(st.floats(0.0, 1.0)),
        turn_window_px=draw(st.integers(3, 15)),
        granular_step=draw(_steps()),
        soft_step=draw(_steps()),
    )


@settings(max_examples=150, deadline=None)
@given(image=images(), params=descriptor_params())
def test_the_pixel_kinds_are_those_of_the_whole_image_formulation(image, params):
    kinds = pixel_kinds(image, params)
    expected = _first_pixel_kinds(image, params)
    actual = (kinds.edges, kinds.straight, kinds.abrupt, kinds.ends, kinds.specks, kinds.soft)
    for name, new, old in zip(("edges", "straight", "abrupt", "ends", "specks", "soft"), actual, expected):
        if name == "abrupt":
            assert new.dtype == np.float32 and new.tobytes() == old.tobytes(), name
        else:
            assert new.dtype == bool and np.array_equal(new, old > 0) and set(np.unique(old)) <= {0.0, 1.0}, name


@st.composite
def layers(draw) -> tuple[list[np.ndarray], np.ndarray]:
    """Four random 0/1 layers of one size, and an abruptness layer of multiples of 2**-24 in [0, 1]."""
    height, width = draw(st.integers(1, 70)), draw(st.integers(1, 70))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    shares = rng.random(4) ** 2
    counted = [rng.random((height, width)) < share for share in shares]
    abrupt = np.where(rng.random((height, width)) < 0.2, rng.integers(0, 2**24 + 1, (height, width)), 0)
    return counted, (abrupt / 2**24).astype(np.float32)


@settings(max_examples=150, deadline=None)
@given(data=layers(), window=st.integers(1, 45), step=st.integers(1, 9), offset=st.integers(0, 8))
def test_the_grid_densities_are_the_normalised_box_filters_of_the_layers(data, window, step, offset):
    (straight, ends, specks, soft), abrupt = data
    height, width = straight.shape
    kinds = types.SimpleNamespace(straight=straight, abrupt=abrupt, ends=ends, specks=specks, soft=soft)
    rows = np.arange(min(offset, height - 1), height, step)
    cols = np.arange(min(offset, width - 1), width, step)
    size = _odd(window)
    in_order = (straight, abrupt, ends, specks, soft)
    expected = np.stack([_box(layer.astype(np.float32), size, True)[np.ix_(rows, cols)] for layer in in_order], axis=-1)
    actual = densities_at(kinds, window, rows, cols)
    assert actual.dtype == np.float32
    assert actual.tobytes() == np.clip(expected, 0.0, 1.0).tobytes()


@settings(max_examples=150, deadline=None)
@given(
    values=st.lists(
        st.one_of(
            st.floats(-300.0, 600.0, width=32),
            st.integers(-2, 257).map(lambda k: k + 0.5),
            st.integers(-2, 257).map(float),
        ),
        min_size=1,
        max_size=200,
    ),
    width=st.integers(1, 7),
)
def test_the_smoothed_image_is_rounded_and_saturated_as_numpy_rounds_and_clips_it(values, width):
    grey = np.array(values * width, np.float32).reshape(width, -1)
    expected = np.clip(np.rint(grey), 0, 255).astype(np.uint8)
    assert _rounded_grey(grey).tobytes() == expected.tobytes()
