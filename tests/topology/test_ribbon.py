"""Twist by parallel transport and the Călugăreanu–Fuller–White theorem (eq. 1.17)."""

from __future__ import annotations

import numpy as np
import pytest

from hairbrush_env.topology import helix, helix_twist_writhe, linking_number, pitch_angle, twist, writhe


def twisted_circle(k, n=400):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    x = np.column_stack([np.cos(t), np.sin(t), 0 * t])
    u = np.cos(k * t)[:, None] * x + np.sin(k * t)[:, None] * np.array([0, 0, 1.0])
    return x, u


def curvature_normals(x):
    d2 = np.roll(x, -1, 0) - 2 * x + np.roll(x, 1, 0)
    t = np.roll(x, -1, 0) - np.roll(x, 1, 0)
    t /= np.linalg.norm(t, axis=1)[:, None]
    u = d2 - np.sum(d2 * t, 1)[:, None] * t
    return u / np.linalg.norm(u, axis=1)[:, None]


@pytest.mark.parametrize("k", [-2, 0, 1, 3])
def test_cfw_twisted_circle(k):
    x, u = twisted_circle(k)
    lk = linking_number(x, x + 1e-3 * u)
    tw, wr = twist(x, u), writhe(x)
    assert wr == pytest.approx(0.0, abs=1e-12)
    assert abs(tw) == pytest.approx(abs(k), abs=1e-9)
    assert lk == pytest.approx(tw + wr, abs=1e-6)


@pytest.mark.parametrize("extra_turns", [0, 2])
def test_cfw_trefoil_ribbon(extra_turns):
    s = np.linspace(0, 2 * np.pi, 600, endpoint=False)
    x = np.column_stack([np.sin(s) + 2 * np.sin(2 * s), np.cos(s) - 2 * np.cos(2 * s), -np.sin(3 * s)])
    n0 = curvature_normals(x)
    t = np.gradient(x, axis=0)
    t /= np.linalg.norm(t, axis=1)[:, None]
    b0 = np.cross(t, n0)
    u = np.cos(extra_turns * s)[:, None] * n0 + np.sin(extra_turns * s)[:, None] * b0
    lk = linking_number(x, x + 1e-3 * u)
    tw, wr = twist(x, u), writhe(x)
    assert abs(wr) > 3  # a genuinely writhed curve: the test is not trivial
    assert lk == pytest.approx(round(lk), abs=1e-9)
    assert lk == pytest.approx(tw + wr, abs=1e-6)


def test_helix_frenet_twist_matches_eq_1_29():
    radius, pitch, turns = 1.0, 2 * np.pi * 0.3, 5
    h = helix(radius, pitch, turns, 4000)
    towards_axis = -np.column_stack([h[:, 0], h[:, 1], 0 * h[:, 0]])  # Frenet normal of a helix
    tw_expected, wr_expected = helix_twist_writhe(pitch_angle(radius, pitch), turns)
    assert twist(h, towards_axis, closed=False) == pytest.approx(tw_expected, rel=1e-4)
    assert tw_expected + wr_expected == pytest.approx(turns)


def test_twist_invariant_under_rigid_motion_and_normal_sign():
    x, u = twisted_circle(2)
    rot = np.linalg.qr(np.random.default_rng(0).normal(size=(3, 3)))[0]
    rot *= np.sign(np.linalg.det(rot))  # proper rotation
    assert twist(x @ rot.T + 3.0, u @ rot.T) == pytest.approx(twist(x, u), abs=1e-12)
    assert twist(x, -u) == pytest.approx(twist(x, u), abs=1e-12)


def test_twist_bad_input():
    x, u = twisted_circle(1)
    with pytest.raises(ValueError, match="normals: expected one vector per vertex"):
        twist(x, u[:-1])
    tangent = np.roll(x, -1, 0) - x
    with pytest.raises(ValueError, match="normals: normal is parallel"):
        twist(x, tangent)
    with pytest.raises(ValueError, match="curve: for closed=True"):
        twist(np.vstack([x, x[:1]]), np.vstack([u, u[:1]]))
