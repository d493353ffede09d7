"""Helix geometry and Love's helix mechanics against closed-form limits."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hairbrush_env.topology import (
    double_helix,
    helix,
    helix_arclength,
    helix_twist_writhe,
    love_helix_load,
    love_small_extension,
    love_tine_force,
    pitch_angle,
)


def test_helix_geometry():
    h = helix(0.002, 0.01, 3, 3001)
    length = np.linalg.norm(np.diff(h, axis=0), axis=1).sum()
    # chords of 1000 vertices per turn are shorter than the arc by ~(2π/1000)²/24 ≈ 1.6e-6
    assert length == pytest.approx(helix_arclength(0.002, 0.01, 3), rel=3e-6)
    np.testing.assert_allclose(np.hypot(h[:, 0], h[:, 1]), 0.002)
    assert h[-1, 2] == pytest.approx(0.03)
    a, b = double_helix(0.002, 0.01, 3, 301)
    np.testing.assert_allclose(np.linalg.norm(a - b, axis=1), 0.004)  # filament centerlines 2R apart


def test_twist_writhe_limits():
    tw, wr = helix_twist_writhe(math.pi / 2 - 1e-9, 4)  # straight: all twist
    assert tw == pytest.approx(4) and wr == pytest.approx(0, abs=1e-6)
    tw, wr = helix_twist_writhe(1e-9, 4)  # flat coil: all writhe
    assert wr == pytest.approx(4)
    # corrected eq. 1.29: N α/√(1+α²) with α = tan θ
    alpha = 0.7
    assert helix_twist_writhe(math.atan(alpha), 2)[0] == pytest.approx(2 * alpha / math.sqrt(1 + alpha**2))


def test_love_small_pitch_reduces_to_coil_spring_formula():
    G, d, D, N = 8e10, 1e-3, 1e-2, 10  # steel spring
    r = d / 2
    B = 2.1e11 * math.pi * r**4 / 4
    C = G * math.pi * r**4 / 2
    pitch = 1.05 * d
    theta = pitch_angle(D / 2, pitch)
    S = helix_arclength(D / 2, pitch, N)
    dL, dN = love_small_extension(1.0, pitch_angle=theta, radius=D / 2, arclength=S, bending=B, twisting=C)
    k_textbook = G * d**4 / (8 * D**3 * N)
    assert 1.0 / dL == pytest.approx(k_textbook, rel=2e-3)
    assert dN > 0  # eq. 1.34: B > C (ν > 0) so a spring stretched with zero end torque gains turns


def test_love_load_consistent_with_small_extension():
    # eq. 2.3 at (α0 + δα, R fixed-arclength helix) must agree with eq. 1.33 to first order.
    B, C, R, N, P = 2e-6, 1.5e-6, 2e-3, 5, 4e-3
    S = helix_arclength(R, P, N)
    a0 = pitch_angle(R, P)
    L = S * math.sin(a0)
    dL = 1e-7
    a1 = math.asin((L + dL) / S)
    # zero-torque path: solve M(α1, R1) = 0 for R1 by bisection around R
    f = lambda r1: love_helix_load(a0, R, a1, r1, bending=B, twisting=C)[1]  # noqa: E731
    lo, hi = R * 0.99, R * 1.01
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(lo) * f(mid) > 0 else (lo, mid)
    F, _ = love_helix_load(a0, R, a1, 0.5 * (lo + hi), bending=B, twisting=C)
    dL_lin, _ = love_small_extension(F, pitch_angle=a0, radius=R, arclength=S, bending=B, twisting=C)
    assert dL_lin == pytest.approx(dL, rel=1e-3)


def test_love_tine_force_monotone_and_domain():
    r = 4.25e-4
    B = 0.27e9 * math.pi * r**4 / 4
    C = B / 1.49
    d = np.linspace(0, 0.02, 50)
    F = love_tine_force(d, radius=3 * r, pitch=48 * r, turns=5, bending=B, twisting=C)
    ok = np.isfinite(F)
    assert F[0] == pytest.approx(0.0, abs=1e-12)
    assert np.all(np.diff(F[ok]) > 0)  # stiffening force-extension
    tight = love_tine_force(0.001, radius=r, pitch=24 * r, turns=5, bending=B, twisting=C, tightly_wound=True)
    loose = love_tine_force(0.001, radius=3 * r, pitch=24 * r, turns=5, bending=B, twisting=C)
    assert tight > loose  # R/r = 1 stiffens much faster (thesis appendix discussion)
    assert np.isnan(love_tine_force(1.0, radius=r, pitch=24 * r, turns=5, bending=B, twisting=C))


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"radius": -1}, "radius"),
        ({"pitch": 0}, "pitch"),
        ({"turns": float("nan")}, "turns"),
        ({"n": 1}, "n"),
    ],
)
def test_helix_bad_input(kwargs, field):
    args = {"radius": 1.0, "pitch": 1.0, "turns": 2.0, "n": 10} | kwargs
    with pytest.raises(ValueError, match=f"^{field}:"):
        helix(**args)
