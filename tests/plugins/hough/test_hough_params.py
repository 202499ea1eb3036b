"""Tests of the Hough baseline's parameters: declared domains and the rules between fields."""

from __future__ import annotations

import pydantic
import pytest
from trackbench_hough.params import HoughParams


def test_the_partner_border_may_not_need_more_votes_than_the_stronger_one():
    with pytest.raises(pydantic.ValidationError, match="partner_fraction must not exceed vote_fraction"):
        HoughParams(vote_fraction=0.2, partner_fraction=0.25)
    assert HoughParams(vote_fraction=0.3, partner_fraction=0.3).partner_fraction == 0.3


def test_widths_form_a_range():
    with pytest.raises(pydantic.ValidationError, match="min_width_px must not exceed max_width_px"):
        HoughParams(min_width_px=170.0)


def test_sizes_may_be_absolute_pixels_but_not_a_zero_reference():
    assert HoughParams(reference_side_px=None).reference_side_px is None
    with pytest.raises(pydantic.ValidationError, match="reference_side_px"):
        HoughParams(reference_side_px=0.0)


def test_an_unknown_edge_rule_is_refused():
    with pytest.raises(pydantic.ValidationError, match="edge_rule"):
        HoughParams(edge_rule="otsu")
