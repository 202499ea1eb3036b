"""The simulated camera: Table 3 of seeds/002 and the extent of the image."""

from __future__ import annotations

import numpy as np
import pytest

from benchmark.scenes.stereo_projection import depth_accuracy, depth_from_disparity, in_view
from benchmark.scenes.stereo_spec import StereoCameraSpec

BUMBLEBEE = StereoCameraSpec().calibration()

TABLE_3 = [  # disparity px, Z m, Z accuracy m (seeds/002, Table 3)
    (1.0, 16.896, 3.3792),
    (1.5, 11.264, 1.5019),
    (2.0, 8.448, 0.8448),
    (2.5, 6.7584, 0.5407),
    (3.5, 4.82742857, 0.2759),
    (4.5, 3.75466667, 0.1669),
    (7.0, 2.41371429, 0.0690),
    (33.0, 0.512, 0.0031),
]


@pytest.mark.parametrize(("disparity", "depth", "accuracy"), TABLE_3)
def test_table_3_is_reproduced(disparity, depth, accuracy) -> None:
    assert float(depth_from_disparity(disparity, BUMBLEBEE)) == pytest.approx(depth, rel=1e-6)
    assert float(depth_accuracy(depth, BUMBLEBEE, 0.2)) == pytest.approx(accuracy, abs=6e-5)


def test_image_spans_half_a_pixel_beyond_the_outer_pixel_centres() -> None:
    inside = in_view(np.array([-0.5, 0.0, 319.0, 319.5]), BUMBLEBEE)
    outside = in_view(np.array([-0.51, 319.51, np.nan]), BUMBLEBEE)
    assert inside.all() and not outside.any()
