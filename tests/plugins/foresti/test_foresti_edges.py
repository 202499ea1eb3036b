"""Tests of the Canny edges with modulus and phase (seeds/004, section IV)."""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from trackbench_foresti.edges import as_grey, canny_edges, gradient_modulus

SHAPE = (60, 80)


def vertical_step(dark: int, bright: int, column: int = 40) -> np.ndarray:
    """Columns ``< column`` at ``dark``, the others at ``bright``."""
    image = np.full(SHAPE, dark, np.uint8)
    image[:, column:] = bright
    return image


def test_a_vertical_step_gives_one_edge_per_row_at_the_step():
    edges = canny_edges(vertical_step(80, 140), sigma=1.5, low=20.0, high=60.0)
    rows, columns = np.nonzero(edges.mask[2:-2])
    assert set(np.unique(columns)) <= {39, 40}
    assert rows.size == SHAPE[0] - 4 and np.unique(rows).size == SHAPE[0] - 4


@pytest.mark.parametrize(
    ("image", "expected"),
    [
        (vertical_step(80, 140), 0.0),  # brighter to the right: gradient along +x
        (vertical_step(140, 80), math.pi),  # brighter to the left: along -x
        (vertical_step(80, 140).T.copy(), -math.pi / 2),  # brighter below: along -y (y is up)
        (vertical_step(140, 80).T.copy(), math.pi / 2),  # brighter above: along +y
    ],
    ids=["right", "left", "down", "up"],
)
def test_phase_is_the_gradient_direction_in_model_coordinates(image, expected):
    edges = canny_edges(image, sigma=1.5, low=20.0, high=60.0)
    phases = edges.phase
    assert phases.size > 0
    # Compare on the circle: pi and -pi are the same direction.
    assert np.all(np.abs(np.angle(np.exp(1j * (phases - expected)))) < math.radians(1.0))


def test_modulus_grows_with_the_step_and_is_about_twice_its_height():
    low_step = canny_edges(vertical_step(100, 130), sigma=1.5, low=10.0, high=20.0)
    high_step = canny_edges(vertical_step(100, 160), sigma=1.5, low=10.0, high=20.0)
    low_modulus = float(np.median(low_step.modulus))
    high_modulus = float(np.median(high_step.modulus))
    assert math.isclose(high_modulus / low_modulus, 2.0, rel_tol=0.05)
    assert 1.6 * 60 < high_modulus < 2.4 * 60


def test_hysteresis_thresholds_drop_weak_steps():
    weak = vertical_step(100, 110)  # modulus about 20
    assert not canny_edges(weak, sigma=1.5, low=20.0, high=60.0).mask.any()
    assert canny_edges(weak, sigma=1.5, low=5.0, high=10.0).mask.any()


def test_a_flat_image_has_no_edges_and_the_arrays_match_the_image():
    edges = canny_edges(np.full(SHAPE, 90, np.uint8), sigma=1.5, low=20.0, high=60.0)
    assert not edges.mask.any()
    assert edges.mask.shape == SHAPE and edges.pixels.shape == edges.modulus.shape == edges.phase.shape == (0,)
    assert edges.mask.dtype == bool and edges.modulus.dtype == np.float32 and edges.phase.dtype == np.float32
    assert edges.size == (SHAPE[1], SHAPE[0])


def test_the_edge_arrays_follow_the_mask_in_row_major_order():
    edges = canny_edges(vertical_step(80, 140), sigma=1.5, low=20.0, high=60.0)
    assert np.array_equal(edges.pixels, np.flatnonzero(edges.mask))
    assert edges.pixels.size == edges.modulus.size == edges.phase.size > 0


@pytest.mark.parametrize(
    "image",
    [np.zeros(SHAPE, np.float32), np.zeros((*SHAPE, 3), np.uint8), np.zeros((0, 5), np.uint8), [[1, 2], [3, 4]]],
    ids=["float", "colour", "empty", "list"],
)
def test_bad_images_are_refused(image):
    with pytest.raises(ValueError, match="image"):
        canny_edges(image, sigma=1.5, low=20.0, high=60.0)


def test_bad_thresholds_are_refused():
    with pytest.raises(ValueError, match="Canny thresholds"):
        canny_edges(vertical_step(80, 140), sigma=1.5, low=70.0, high=60.0)
    with pytest.raises(ValueError, match="sigma"):
        canny_edges(vertical_step(80, 140), sigma=-1.0, low=20.0, high=60.0)


def test_as_grey_accepts_grey_and_opencv_colour_images():
    grey = vertical_step(80, 140)
    assert as_grey(grey) is grey
    assert np.array_equal(as_grey(grey[:, :, None]), grey)
    bgr = np.repeat(grey[:, :, None], 3, axis=2)
    assert np.array_equal(as_grey(bgr), grey)
    bgra = np.concatenate([bgr, np.full((*SHAPE, 1), 255, np.uint8)], axis=2)
    assert np.array_equal(as_grey(bgra), grey)
    blue = np.zeros((*SHAPE, 3), np.uint8)
    blue[:, :, 0] = 255  # OpenCV's channel order is BGR: pure blue is dark
    assert int(as_grey(blue)[0, 0]) == 29
    for bad in (grey.astype(np.float32), np.zeros((*SHAPE, 2), np.uint8), np.zeros(5, np.uint8)):
        with pytest.raises(ValueError, match="image"):
            as_grey(bad)


@contextmanager
def opencv_without_ipp() -> Iterator[None]:
    """OpenCV's own kernels instead of Intel IPP's: ``cv2.magnitude`` then rounds the exact modulus."""
    used = cv2.ipp.useIPP()
    cv2.ipp.setUseIPP(False)
    try:
        yield
    finally:
        cv2.ipp.setUseIPP(used)


def reference_edges(image: np.ndarray, sigma: float, low: float, high: float):
    """:func:`canny_edges` as it was: mask, and ``cv2.magnitude`` and ``np.arctan2`` over the whole image."""
    smooth = image if sigma == 0 else cv2.GaussianBlur(image, (0, 0), sigmaX=sigma, borderType=cv2.BORDER_REPLICATE)
    gu = cv2.Sobel(smooth, cv2.CV_16S, 1, 0, ksize=3, borderType=cv2.BORDER_REPLICATE)
    gv = cv2.Sobel(smooth, cv2.CV_16S, 0, 1, ksize=3, borderType=cv2.BORDER_REPLICATE)
    mask = cv2.Canny(gu, gv, float(low), float(high), L2gradient=True) > 0
    gu_f, gv_f = gu.astype(np.float32), gv.astype(np.float32)
    modulus = cv2.magnitude(gu_f, gv_f)
    phase = np.arctan2(np.negative(gv_f, out=gv_f), gu_f)
    return mask, modulus, phase


images = st.tuples(st.integers(3, 40), st.integers(3, 40)).flatmap(lambda shape: hnp.arrays(np.uint8, shape))


@settings(max_examples=150, deadline=None)
@given(images, st.sampled_from([0.0, 0.8, 1.5]), st.sampled_from([(5.0, 10.0), (20.0, 60.0)]))
def test_edges_equal_the_whole_image_formulation_at_their_pixels(image, sigma, thresholds):
    edges = canny_edges(image, sigma, *thresholds)
    mask, modulus, phase = reference_edges(image, sigma, *thresholds)
    assert np.array_equal(edges.mask, mask) and np.array_equal(edges.pixels, np.flatnonzero(mask))
    assert np.array_equal(edges.phase.view(np.int32), phase[mask].view(np.int32))  # -0.0 and 0.0 told apart
    # cv2.magnitude's IPP kernel is approximate (within one unit in the last place); OpenCV's own rounds exactly.
    assert np.all(np.abs(edges.modulus - modulus[mask]) <= np.spacing(modulus[mask]))
    with opencv_without_ipp():
        assert np.array_equal(edges.modulus, reference_edges(image, sigma, *thresholds)[1][mask])


sobel = hnp.arrays(np.int16, st.integers(1, 300), elements=st.integers(-1020, 1020))


@settings(max_examples=200, deadline=None)
@given(
    sobel.flatmap(lambda gu: st.tuples(st.just(gu), hnp.arrays(np.int16, gu.shape, elements=st.integers(-1020, 1020))))
)
def test_gradient_modulus_is_the_exact_modulus_rounded_once(gradients):
    gu, gv = gradients
    modulus = gradient_modulus(gu, gv)
    exact = np.sqrt(gu.astype(np.float64) ** 2 + gv.astype(np.float64) ** 2).astype(np.float32)
    assert modulus.dtype == np.float32 and np.array_equal(modulus, exact)
    with opencv_without_ipp():
        assert np.array_equal(modulus, cv2.magnitude(gu.astype(np.float32), gv.astype(np.float32)).reshape(-1))
