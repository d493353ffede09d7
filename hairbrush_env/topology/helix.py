"""Helices, double helices and their analytic mechanics (thesis §1.3 and chapter 2 appendix).

Geometry: a helix of radius ``R`` and pitch ``P`` has pitch angle θ with tan θ = P / (2πR) (the angle between
tangent and the plane normal to the axis; the thesis's α in eq. 1.26 is tan θ, in eqs 1.31–1.34 and 2.3–2.7 it is
θ itself). Arclength per turn is √((2πR)² + P²).

Topology (eqs 1.29–1.30, with the printed slip of eq. 1.29 corrected): the Frenet ribbon of an N-turn helix has
Tw = N sin θ (= Nα/√(1+α²) with α = tan θ) and, closed with the axis so that Lk = N, Wr = N (1 − sin θ).

Mechanics (Love, *Treatise on the Mathematical Theory of Elasticity*, §270–271): bending stiffness B = E π r⁴/4,
twisting stiffness C = G π r⁴/2 for a filament of radius r.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "double_helix",
    "helix",
    "helix_arclength",
    "helix_twist_writhe",
    "love_helix_load",
    "love_small_extension",
    "love_tine_force",
    "pitch_angle",
]


def _positive(name: str, value: float) -> float:
    v = float(value)
    if not math.isfinite(v) or v <= 0.0:
        raise ValueError(f"{name}: must be a positive finite number, got {value!r}")
    return v


def helix(
    radius: float, pitch: float, turns: float, n: int, phase: float = 0.0, handedness: int = +1
) -> np.ndarray:
    """``n`` vertices of a helix about the z axis from z = 0 to z = pitch·turns.

    ``handedness=+1`` is right-handed (counter-clockwise seen from +z while rising); ``phase`` is the azimuth of
    the first vertex. Returns an ``(n, 3)`` array.
    """
    _positive("radius", radius)
    _positive("pitch", pitch)
    _positive("turns", turns)
    if int(n) != n or n < 2:
        raise ValueError(f"n: need an integer >= 2, got {n!r}")
    if handedness not in (-1, 1):
        raise ValueError(f"handedness: expected +1 or -1, got {handedness!r}")
    z = np.linspace(0.0, pitch * turns, int(n))
    phi = phase + handedness * 2.0 * np.pi * z / pitch
    return np.column_stack([radius * np.cos(phi), radius * np.sin(phi), z])


def double_helix(
    radius: float, pitch: float, turns: float, n: int, phase: float = 0.0, handedness: int = +1
) -> tuple[np.ndarray, np.ndarray]:
    """Two homochiral entwined helices on a common axis, half a turn apart (thesis chapter 2 minimal model).

    ``radius`` is the helix radius R = half the distance between the two filament centerlines. Their open-curve
    linking number tends to ``turns`` (one link per pitch of shared length; sign = handedness).
    """
    a = helix(radius, pitch, turns, n, phase, handedness)
    b = helix(radius, pitch, turns, n, phase + np.pi, handedness)
    return a, b


def pitch_angle(radius: float, pitch: float) -> float:
    """Pitch angle θ = atan(P / 2πR) in radians."""
    return math.atan2(_positive("pitch", pitch), 2.0 * math.pi * _positive("radius", radius))


def helix_arclength(radius: float, pitch: float, turns: float) -> float:
    """Arclength S = N √((2πR)² + P²) of an N-turn helix."""
    return _positive("turns", turns) * math.hypot(
        2.0 * math.pi * _positive("radius", radius), _positive("pitch", pitch)
    )


def helix_twist_writhe(pitch_angle: float, turns: float) -> tuple[float, float]:
    """Twist and writhe of an N-turn helix's Frenet ribbon (eqs 1.29–1.30, corrected): (N sin θ, N (1 − sin θ))."""
    theta = float(pitch_angle)
    if not (0.0 < theta < math.pi / 2):
        raise ValueError(f"pitch_angle: expected 0 < θ < π/2 radians, got {pitch_angle!r}")
    tw = turns * math.sin(theta)
    return tw, turns - tw


def love_small_extension(
    force: float, *, pitch_angle: float, radius: float, arclength: float, bending: float, twisting: float
) -> tuple[float, float]:
    """Linear response of a helical spring to an axial force F with zero end torque (eqs 1.33–1.34).

    Returns ``(δL, δN)``: change of axial length and of the number of turns. For small pitch angle the axial
    stiffness F/δL reduces to C / (S R²) = G d⁴ / (8 D³ N), the textbook coil-spring formula.
    """
    s, c = math.sin(pitch_angle), math.cos(pitch_angle)
    b = _positive("bending", bending)
    cc = _positive("twisting", twisting)
    r = _positive("radius", radius)
    S = _positive("arclength", arclength)
    dL = S * r**2 * (s**2 / b + c**2 / cc) * force
    dN = S * r / (2.0 * math.pi) * s * c * (1.0 / cc - 1.0 / b) * force
    return dL, dN


def love_helix_load(alpha, radius, alpha1, radius1, *, bending: float, twisting: float):
    """Axial force F and torque M that hold a helix (α, R) deformed to (α₁, R₁) (Love; thesis eqs 2.3–2.4).

    Angles are pitch angles in radians (sin α = axial length / arclength). Works element-wise on arrays.
    """
    B, C = bending, twisting
    sa, ca = np.sin(alpha), np.cos(alpha)
    s1, c1 = np.sin(alpha1), np.cos(alpha1)
    twist_change = s1 * c1 / radius1 - sa * ca / radius
    bend_change = c1**2 / radius1 - ca**2 / radius
    force = C * c1 / radius1 * twist_change - B * s1 / radius1 * bend_change
    moment = C * s1 * twist_change + B * c1 * bend_change
    return force, moment


def love_tine_force(
    d,
    *,
    radius: float,
    pitch: float,
    turns: float,
    bending: float,
    twisting: float,
    tightly_wound: bool = False,
) -> np.ndarray:
    """No-slip single-helix prediction of the combing force F(d) (thesis eqs 2.3, 2.5–2.7).

    The tine sticks to the filaments: the clamped side (``turns`` pitches of a helix of radius ``radius``) keeps
    its arclength S while its axial length grows from L to L + d, so sin α₁ = (L + d)/S (eq. 2.5). For a
    tightly wound double helix (R = r) the radius cannot change (R₁ = R); otherwise the filament's azimuthal
    sweep χ = S cos α / R is conserved and R₁ = R cos α₁ / cos α (eqs 2.6–2.7). Returns F from eq. 2.3; NaN where
    d ≥ S − L (the filament would be straight).
    """
    d = np.asarray(d, dtype=np.float64)
    length = _positive("pitch", pitch) * _positive("turns", turns)
    S = helix_arclength(radius, pitch, turns)
    alpha0 = math.asin(length / S)
    ratio = (length + d) / S
    alpha1 = np.arcsin(np.where(ratio < 1.0, ratio, np.nan))
    r1 = np.full_like(alpha1, radius) if tightly_wound else radius * np.cos(alpha1) / math.cos(alpha0)
    force, _ = love_helix_load(alpha0, radius, alpha1, r1, bending=bending, twisting=twisting)
    return force
