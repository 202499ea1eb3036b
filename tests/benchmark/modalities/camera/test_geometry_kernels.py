"""The compiled geometry helpers equal the standard library and the Python geometry bit for bit."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from benchmark.modalities.camera.geometry import Line, cable_from_borders
from benchmark.modalities.camera.geometry_kernels import cable_of_borders, python_hypot

finite = st.floats(allow_nan=False, allow_infinity=False)


@settings(max_examples=2000, deadline=None)
@given(x=st.floats(), y=st.floats())
def test_python_hypot_is_math_hypot(x, y):
    expected = math.hypot(x, y)
    assert python_hypot(x, y) == expected or (math.isnan(expected) and math.isnan(python_hypot(x, y)))


@settings(max_examples=1000, deadline=None)
@given(x=st.floats(-(2.0**-1024), 2.0**-1024), y=st.floats(-(2.0**-1024), 2.0**-1024))
def test_python_hypot_is_math_hypot_below_the_scaled_range(x, y):
    assert python_hypot(x, y) == math.hypot(x, y)


def test_python_hypot_of_subnormals_and_its_extremes():
    for x, y in [(5e-324, 5e-324), (1e-310, 3e-310), (0.0, -0.0), (1e308, 1e308), (math.inf, math.nan), (3.0, 4.0)]:
        assert python_hypot(x, y) == math.hypot(x, y) or math.isnan(math.hypot(x, y))


@settings(max_examples=500, deadline=None)
@given(
    first=st.tuples(finite.filter(lambda v: abs(v) < 1e4), finite.filter(lambda v: abs(v) < 1e4),
                    st.floats(-1.0, 1.0), st.floats(-1.0, 1.0)),
    second=st.tuples(finite.filter(lambda v: abs(v) < 1e4), finite.filter(lambda v: abs(v) < 1e4),
                     st.floats(-1.0, 1.0), st.floats(-1.0, 1.0)),
)
def test_the_compiled_state_of_two_borders_is_cable_from_borders(first, second):
    if math.hypot(*first[2:]) < 1e-6 or math.hypot(*second[2:]) < 1e-6:
        return
    one, two = Line(*first), Line(*second)
    try:
        expected = cable_from_borders(one, two)
    except ZeroDivisionError:
        return
    got = cable_of_borders(one.x0, one.y0, one.dx, one.dy, two.x0, two.y0, two.dx, two.dy)
    assert np.array_equal(np.array(got), np.array([expected.d, expected.alpha, expected.w, expected.beta]), equal_nan=True)
