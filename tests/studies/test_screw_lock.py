"""A tine pushed through a curl free to turn: MuJoCo's contacts against the screw's self-locking threshold
``μ = tan λ = P / (2π R)`` (hairbrush_env.studies.screw_lock)."""

from __future__ import annotations

import math

import pytest

from hairbrush_env.studies.screw_lock import lead_tangent, tine_through_helix

# (R [m], R/P): loose_curl, curly, tight_curl and coily under HairBrush-v7 / v8.
CURLS = [(0.013, 0.30), (0.012, 0.50), (0.010, 0.65), (0.009, 0.80)]


def test_lead_tangent_is_the_helix_angle() -> None:
    assert lead_tangent(0.012, 0.024) == pytest.approx(1 / math.pi)
    assert lead_tangent(0.009, 0.009 / 0.8) == pytest.approx(1 / (2 * math.pi * 0.8))


@pytest.mark.parametrize(("radius", "curliness"), CURLS)
def test_a_curl_turns_round_the_tine_below_its_lead_angle_and_locks_above(
    radius: float, curliness: float
) -> None:
    """Below the threshold (0.7 tan λ) the tine threads down through the curl, which turns one turn per pitch of
    descent; above it (1.1 tan λ) the curl holds the tine where it first touched, however long it is pushed. MuJoCo's
    soft contacts lock a little early (measured: between 0.85 and 1.0 tan λ), so the margins are asymmetric."""
    pitch = radius / curliness
    tan_lead = lead_tangent(radius, pitch)
    free = tine_through_helix(0.7 * tan_lead, curl_radius=radius, pitch=pitch)
    locked = tine_through_helix(1.1 * tan_lead, curl_radius=radius, pitch=pitch)
    assert not free.locked_expected and locked.locked_expected
    # The tine starts a quarter pitch above the wire's crossing and touches it (wire 0.8 mm + tine 1 mm) this far down.
    touch = 0.25 - 1.8e-3 / (pitch * math.cos(math.atan(tan_lead)))
    assert free.turns > 0.3, free
    assert free.descent - free.turns == pytest.approx(touch, abs=0.03), free  # threads: a pitch per turn
    assert locked.turns < 0.03 and locked.descent < touch + 0.03, locked


def test_frictionless_tine_threads_fastest_and_bad_input_is_named() -> None:
    r = tine_through_helix(0.0)
    assert r.turns > tine_through_helix(0.15).turns > 0.1
    with pytest.raises(ValueError, match=r"friction -0\.1"):
        tine_through_helix(-0.1)
    with pytest.raises(ValueError, match=r"pitch 0\.002"):
        tine_through_helix(0.1, pitch=0.002)
