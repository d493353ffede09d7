"""A lone curl held by its root lets a tine through below the force of drawing it straight (E I κ₀² / 2)."""

import math

import pytest

from hairbrush_env.studies.root_held_curl import curl_curvature, peel_force, pull_tine_through_curl


def test_curl_curvature_is_the_helix_curvature():
    # A flat circle (pitch 0) has curvature 1/R; a helix R/(R² + b²) with b = P/2π.
    assert curl_curvature(0.01, 1e-12) == pytest.approx(100.0, rel=1e-9)
    b = 0.02 / (2 * math.pi)
    assert curl_curvature(0.01, 0.02) == pytest.approx(0.01 / (0.01**2 + b**2), rel=1e-12)
    # E I κ₀² / 2 with I = π r⁴ / 4
    expected = 0.5 * 1.6e8 * math.pi * (8e-4) ** 4 / 4 * curl_curvature(0.009, 0.01125) ** 2
    assert peel_force(0.009, 0.01125, young=1.6e8, strand_radius=8e-4) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("friction", [0.15, 1.0])
def test_a_lone_root_held_coily_curl_is_not_drawn_straight(friction):
    res = pull_tine_through_curl(friction=friction)
    # The tine meets the wire (a force), but the curl swings and screws round it instead of being peeled straight.
    assert res.max_force > 0.02
    assert res.max_force < res.peel
    assert res.peel == pytest.approx(0.294, abs=0.002)


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match="curl_radius"):
        pull_tine_through_curl(curl_radius=-1.0)
    with pytest.raises(ValueError, match="length"):
        pull_tine_through_curl(length=0.03)
