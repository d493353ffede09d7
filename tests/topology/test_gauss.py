"""Linking number, writhe, ACN, link density: known answers, quadrature cross-checks and invariances."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy import integrate
from scipy.spatial.transform import Rotation

from hairbrush_env.topology import (
    TopologyWarning,
    average_crossing_number,
    double_helix,
    link_current,
    link_density,
    linking_number,
    pair_gauss_matrix,
    writhe,
)


def circle(n=120, radius=1.0, center=(0, 0, 0), normal_axis=2, phase=0.0):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) + phase
    c, s = radius * np.cos(t), radius * np.sin(t)
    cols = {2: (c, s, 0 * t), 1: (c, 0 * t, s), 0: (0 * t, c, s)}[normal_axis]
    return np.column_stack(cols) + np.asarray(center, dtype=float)


def torus_knot(p, q, n=600, R=2.0, r=0.6, tube_phase=0.0):
    """(p, q) torus curve: p turns around the core axis, q turns around the tube."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    phi, theta = p * t, q * t + tube_phase
    return np.column_stack(
        [(R + r * np.cos(theta)) * np.cos(phi), (R + r * np.cos(theta)) * np.sin(phi), r * np.sin(theta)]
    )


def gauss_quadrature(a0, a1, b0, b1):
    """Eq. 1.15 for one pair of segments by adaptive 2-D quadrature (independent of the closed form)."""
    da, db = a1 - a0, b1 - b0
    cross = np.cross(da, db)

    def f(t, s):
        d = (a0 + s * da) - (b0 + t * db)
        return d @ cross / np.linalg.norm(d) ** 3 / (4 * np.pi)

    return integrate.dblquad(f, 0, 1, 0, 1, epsabs=1e-13, epsrel=1e-11)[0]


def test_segment_pair_matches_quadrature():
    rng = np.random.default_rng(1)
    for _ in range(6):
        a, b = rng.normal(size=(2, 3)), rng.normal(size=(2, 3)) + rng.normal(size=3)
        exact = pair_gauss_matrix(a, b)[0, 0]
        assert exact == pytest.approx(gauss_quadrature(a[0], a[1], b[0], b[1]), abs=1e-9)


def test_hopf_link_sign_and_reversal():
    a = circle()
    b = circle(center=(1, 0, 0), normal_axis=1)
    # b passes through a's disk at the origin moving along -z, against a's right-handed normal +z
    assert linking_number(a, b) == pytest.approx(-1.0, abs=1e-10)
    assert linking_number(a, b[::-1]) == pytest.approx(1.0, abs=1e-10)
    assert linking_number(a[::-1], b) == pytest.approx(1.0, abs=1e-10)
    assert linking_number(b, a) == pytest.approx(-1.0, abs=1e-10)  # symmetric


@pytest.mark.parametrize("k", [1, 2, 3])
def test_torus_links(k):
    # (2, 2k) torus link: two parallel (1, k) torus knots, half a turn apart around the torus core
    a = torus_knot(1, k, n=400)
    b = torus_knot(1, k, n=400, tube_phase=np.pi)
    assert abs(linking_number(a, b)) == pytest.approx(k, abs=1e-9)


def test_separated_circles_have_zero_link():
    assert linking_number(circle(), circle(center=(5, 0, 0))) == pytest.approx(0.0, abs=1e-12)
    assert linking_number(circle(), circle(center=(0.2, 0, 3), normal_axis=0)) == pytest.approx(
        0.0, abs=1e-12
    )


def test_borromean_rings_pairwise_zero():
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    c, s = np.cos(t), np.sin(t)
    # three mutually perpendicular ellipses (a classic Borromean embedding)
    r1 = np.column_stack([2 * c, s, 0 * t])
    r2 = np.column_stack([0 * t, 2 * c, s])
    r3 = np.column_stack([s, 0 * t, 2 * c])
    for p, q in [(r1, r2), (r2, r3), (r1, r3)]:
        assert linking_number(p, q) == pytest.approx(0.0, abs=1e-10)
    # and they are not split: each pair is genuinely interleaved (non-zero open pair terms in absolute value)
    assert average_crossing_number(r1, r2, closed=True) > 0.1


def test_whitehead_type_link_zero():
    # Whitehead link: the circle a threads both lobes of a figure-eight loop b. Each lobe clasps a's wire
    # (over, then under), the lobes turn in opposite senses, so Lk = 0 although the link is not split.
    a = circle(n=200)
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    b = np.column_stack([1.5 * np.sin(t), 0.4 * np.sin(2 * t), 0.3 * np.cos(t)])
    assert linking_number(a, b) == pytest.approx(0.0, abs=1e-10)
    assert average_crossing_number(a, b, closed=True) > 0.5


def test_planar_curve_writhe_zero():
    t = np.linspace(0, 2 * np.pi, 500, endpoint=False)
    r = 1 + 0.3 * np.cos(5 * t)
    flower = np.column_stack([r * np.cos(t), r * np.sin(t), 0 * t])
    assert writhe(flower) == pytest.approx(0.0, abs=1e-12)
    assert writhe(flower, closed=False) == pytest.approx(0.0, abs=1e-12)


def test_open_double_helix_link_per_turn():
    pitch, turns = 0.01, 12
    a, b = double_helix(1e-3, pitch, turns, 1201)
    lk = linking_number(a, b, closed=False)
    assert turns - 0.5 < lk < turns  # end effects lose less than half a turn
    s, lam = link_density(a, b)
    interior = (s > 2 * pitch) & (s < s[-1] - 2 * pitch)
    np.testing.assert_allclose(lam[interior] * pitch, 1.0, atol=5e-3)  # interior link per turn -> 1
    a_l, b_l = double_helix(1e-3, pitch, turns, 1201, handedness=-1)
    assert linking_number(a_l, b_l, closed=False) == pytest.approx(-lk, rel=1e-12)


def test_link_density_integrates_to_open_lk():
    rng = np.random.default_rng(3)
    a = np.cumsum(rng.normal(size=(80, 3)), axis=0)
    b = a + rng.normal(scale=0.5, size=a.shape) + 1.0
    lk = linking_number(a, b, closed=False)
    for along in ("centerline", "a"):
        s, lam = link_density(a, b, along=along)
        path = 0.5 * (a + b) if along == "centerline" else a
        ds = np.linalg.norm(np.diff(path, axis=0), axis=1)
        assert np.sum(lam * ds) == pytest.approx(lk, abs=1e-12)
        assert np.all(np.diff(s) > 0)


def test_acn_bounds_and_convention():
    a, b = double_helix(1e-3, 0.01, 5, 301)
    acn = average_crossing_number(a, b)
    assert acn >= abs(linking_number(a, b, closed=False)) - 1e-12
    # A crossing seen from almost every direction: two long perpendicular segments crossing at a tiny gap.
    x = np.array([[-1e3, 0, 0], [1e3, 0, 0]])
    y = np.array([[0, -1e3, 1e-6], [0, 1e3, 1e-6]])
    # solid angle -> 2π, i.e. |G| -> 1/2 and the mean projected crossing number 2|G| -> 1
    assert 2 * average_crossing_number(x, y) == pytest.approx(1.0, abs=1e-6)


def test_link_current_derivative_and_smoothing():
    x = np.linspace(0, 1, 41)
    lk = 10 * (1 - x**2)
    np.testing.assert_allclose(link_current(lk, x), -20 * x, atol=1e-9)
    sm = link_current(lk + 0.01 * np.cos(40 * np.pi * x), x, window=5)
    assert np.abs(sm[5:-5] + 20 * x[5:-5]).max() < 0.8
    with pytest.raises(ValueError, match="positions"):
        link_current(lk, x[::-1].copy() * 0 + 1)
    with pytest.raises(ValueError, match="window"):
        link_current(lk, x, window=0)


@pytest.mark.parametrize(
    ("arg", "match"),
    [
        (np.zeros((5, 2)), "shape"),
        (np.zeros((1, 3)), "at least 2"),
        (np.array([[0, 0, 0], [np.nan, 0, 0], [1, 1, 1]]), "non-finite"),
        (np.array([[0, 0, 0], [0, 0, 0], [1, 1, 1]]), "zero-length"),
        ("not a curve", "expected"),
    ],
)
def test_bad_input_names_argument(arg, match):
    good = circle()
    with pytest.raises(ValueError, match=f"a: .*{match}"):
        linking_number(arg, good)
    with pytest.raises(ValueError, match=f"b: .*{match}"):
        linking_number(good, arg)
    with pytest.raises(ValueError, match=f"curve: .*{match}"):
        writhe(arg)


def test_intersecting_curves_warn_and_stay_finite():
    a = circle()
    b = circle(center=(1, 0, 0), normal_axis=2)  # coplanar, crossing circles: Lk undefined
    with pytest.warns(TopologyWarning, match="touch or intersect"):
        lk = linking_number(a, b)
    assert np.isfinite(lk)
    x = np.array([[-1.0, 0, 0], [1.0, 0, 0]])
    y = np.array([[0, -1.0, 0], [0, 1.0, 0]])
    with pytest.warns(TopologyWarning):
        assert np.isfinite(linking_number(x, y, closed=False))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        linking_number(circle(), circle(center=(1, 0, 0), normal_axis=1))  # a genuine link: no warning


# --- property-based invariances ---------------------------------------------------------------------------------

coords = st.floats(-5, 5, allow_nan=False, allow_infinity=False)


@st.composite
def linked_pair(draw):
    """A Hopf-linked pair with random radii/offsets, and a random rigid motion + scale."""
    ra = draw(st.floats(0.5, 2.0))
    rb = draw(st.floats(0.5, 2.0))
    off = draw(st.floats(0.2, 0.8)) * min(ra, rb)
    a = circle(n=60, radius=ra)
    # b is centred on a's rim and threads a's disk at distance `off` inside the rim
    b = circle(n=60, radius=rb, center=(ra - off + rb, 0, 0), normal_axis=1)
    rot = Rotation.from_rotvec(draw(st.tuples(coords, coords, coords))).as_matrix()
    shift = np.array(draw(st.tuples(coords, coords, coords)))
    scale = draw(st.floats(0.01, 100.0))
    return a, b, rot, shift, scale


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(linked_pair())
def test_rigid_motion_and_scale_invariance(case):
    a, b, rot, shift, scale = case
    lk = linking_number(a, b)
    wr = writhe(torus_knot(2, 3, n=150))
    move = lambda x: scale * x @ rot.T + shift  # noqa: E731
    assert linking_number(move(a), move(b)) == pytest.approx(lk, abs=1e-9)
    assert writhe(move(torus_knot(2, 3, n=150))) == pytest.approx(wr, abs=1e-9)
    assert linking_number(move(a), move(b)[::-1]) == pytest.approx(-lk, abs=1e-9)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_open_curves_reversal_flips_sign_and_swap_is_symmetric(seed):
    rng = np.random.default_rng(seed)
    a = np.cumsum(rng.normal(size=(12, 3)), axis=0)
    b = np.cumsum(rng.normal(size=(9, 3)), axis=0) + rng.normal(size=3)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", TopologyWarning)
        lk = linking_number(a, b, closed=False)
        assert linking_number(a[::-1], b, closed=False) == pytest.approx(-lk, abs=1e-12)
        assert linking_number(b, a, closed=False) == pytest.approx(lk, abs=1e-12)
        assert average_crossing_number(a, b) >= abs(lk) - 1e-12


# ------------------------------------------------------------------------------------------ pass-through detection
def test_close_pair_proximity_matches_the_reference_functions():
    from hairbrush_env.topology._kernels import min_segment_distance
    from hairbrush_env.topology.proximity import close_pair_proximity

    rng = np.random.default_rng(3)
    base = np.cumsum(rng.normal(0.0, 1e-3, (6, 12, 3)), axis=1)
    curves = (
        base
        + np.array([[0.0, 0.0, 0.0], [2e-3, 0, 0], [0, 2e-3, 0], [0.05, 0, 0], [0, 0.05, 0], [0.051, 0, 0]])[
            :, None
        ]
    )
    pairs, dist, link = close_pair_proximity(curves, 4e-3)
    keys = {tuple(p) for p in pairs}
    assert (0, 1) in keys and (3, 5) in keys and (0, 3) not in keys
    for (a, b), d, lk in zip(pairs, dist, link, strict=True):
        assert d == pytest.approx(float(min_segment_distance(curves[a], curves[b])), rel=1e-12)
        assert lk == pytest.approx(linking_number(curves[a], curves[b], closed=False), abs=1e-12)


def test_crossing_detector_sees_one_strand_pass_through_another():
    from hairbrush_env.topology.proximity import CrossingDetector

    z = np.linspace(-0.02, 0.02, 21)
    still = np.stack([np.zeros_like(z), np.zeros_like(z), z], axis=1)
    det = CrossingDetector(gap=5e-3)
    # A strand winding once round the still one, then the still one sliding sideways out through the middle of one
    # of its segments in 0.2 mm steps: their link drops by ≈ 1 in the one step where the two centerlines meet.
    phi = np.linspace(0.0, 2.0 * np.pi, 21)
    wind = np.stack([2e-3 * np.cos(phi), 2e-3 * np.sin(phi), z], axis=1)
    out = np.array([np.cos(0.55 * np.pi), np.sin(0.55 * np.pi), 0.0])  # towards a segment's midpoint
    for k, shift in enumerate(np.arange(0.0, 4.01e-3, 2e-4)):
        moved = still + shift * out
        det.update(np.stack([moved, wind]), time=k * 1e-3)
    assert len(det.crossings) == 1
    assert det.crossings[0].a == 0 and det.crossings[0].b == 1 and det.crossings[0].jump > 0.8
    smooth = CrossingDetector(gap=5e-3)
    for k in range(10):  # the same pair moving apart along z (no passage) never jumps
        smooth.update(np.stack([still + np.array([0.0, 0.0, 1e-3 * k]), wind]), time=k * 1e-3)
    assert smooth.crossings == [] and smooth.max_jump < 0.2
