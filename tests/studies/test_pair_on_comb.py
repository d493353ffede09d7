"""One wig pair alone with the comb: the second strand carries the force; a lone root-held curl is not drawn
straight; shorter strokes read less than the full one."""

import math

import pytest

from hairbrush_env.studies.pair_on_comb import PairOnComb, curl_curvature, peel_force


def test_curl_curvature_and_peel_force():
    # A flat circle (pitch 0) has curvature 1/R; a helix R/(R² + b²) with b = P/2π.
    assert curl_curvature(0.01, 1e-12) == pytest.approx(100.0, rel=1e-9)
    b = 0.02 / (2 * math.pi)
    assert curl_curvature(0.01, 0.02) == pytest.approx(0.01 / (0.01**2 + b**2), rel=1e-12)
    # E I κ₀² / 2 with I = π r⁴ / 4: coily's wisp (E 1.6e8 Pa, r 0.8 mm, R 9 mm, P 11.25 mm) → 0.294 N
    assert peel_force(0.009, 0.01125, young=1.6e8, strand_radius=8e-4) == pytest.approx(0.294, abs=0.001)


@pytest.fixture(scope="module")
def coily_lone_and_pair():
    lone = PairOnComb("coily", lone=True).stroke(PairOnComb.TOP)
    pair = PairOnComb("coily")
    link0 = pair.link()
    fresh = pair.stroke(PairOnComb.TOP)
    return lone, link0, fresh


def test_a_lone_root_held_curl_is_not_drawn_straight(coily_lone_and_pair):
    lone, _, _ = coily_lone_and_pair
    wig = PairOnComb("coily", settle=0.0).wig
    assert 0.0 < lone.max_force < peel_force(wig.curl_radius, wig.pitch, young=wig.young_modulus,
                                             strand_radius=wig.strand_radius)  # fmt: skip


def test_the_second_strand_carries_a_pairs_force(coily_lone_and_pair):
    lone, link0, fresh = coily_lone_and_pair
    assert link0 == pytest.approx(5.0, abs=0.3)  # built entwined: one turn of link per curl turn
    assert fresh.max_force > 5.0 * lone.max_force
    assert fresh.link_after < link0 - 0.5  # the full stroke takes link out


def test_shorter_strokes_read_less_than_the_full_one():
    pair = PairOnComb("coily")
    hang = pair.hanging_length()
    assert pair.start_depth(1.0) == pytest.approx(PairOnComb.TOP)
    assert pair.start_depth(0.5) == pytest.approx(0.5 * (PairOnComb.TOP + hang))
    short = [pair.stroke(pair.start_depth(b)).max_force for b in (0.33, 0.67)]
    full = pair.stroke(PairOnComb.TOP).max_force
    assert max(short) < full


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match="settle"):
        PairOnComb("coily", settle=-1.0)
    with pytest.raises(ValueError, match="straight"):
        PairOnComb("straight", settle=0.0)
    with pytest.raises(ValueError, match="start_depth"):
        PairOnComb("coily", settle=0.0).stroke(0.0)
    with pytest.raises(ValueError, match="stroke_speed"):
        PairOnComb("coily", settle=0.0, stroke_speed=-0.1)
    with pytest.raises(ValueError, match="curves"):
        PairOnComb("coily", settle=0.0, curves=[PairOnComb("coily", settle=0.0).curves()[0]])
    with pytest.raises(ValueError, match="b_l"):
        PairOnComb("coily", settle=0.0).start_depth(0.0)
