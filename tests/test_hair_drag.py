"""Quadratic drag on chain strands (:mod:`hairbrush_env.hair.drag`): terminal velocity against ``m g = ½ ρ ℓ d v²``."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from hairbrush_env import rods
from hairbrush_env.hair.drag import StrandDrag

RHO_HAIR = 1300.0


STRAND_RADIUS = 8e-4


def _free_rod(
    mass_scale: float, direction: tuple[float, float, float] = (1.0, 0.0, 0.0)
) -> tuple[mujoco.MjModel, rods.RodView, rods.RodSpec]:
    pts = rods.straight_rod_points([0.0, 0.0, 1.0], list(direction), 0.1, 10)
    rod = rods.RodSpec(
        name="r",
        points=pts,
        radius=STRAND_RADIUS,
        young=1e8,
        density=RHO_HAIR,
        clamp=None,
        mass_scale=mass_scale,
    )
    model = rods.build_rod_model([rod])
    return model, rods.RodView(model, "r"), rod


def _terminal_speed(rho: float) -> float:
    """The test strand's broadside terminal speed ``v_t = √(2 λ g / (ρ d))`` (λ its real mass per length)."""
    lam = RHO_HAIR * math.pi * STRAND_RADIUS**2
    return math.sqrt(2.0 * lam * 9.81 / (rho * 2.0 * STRAND_RADIUS))


def _fall(
    seconds: float,
    *,
    mass_scale: float,
    drag: dict | None,
    direction: tuple[float, float, float] = (1.0, 0.0, 0.0),
) -> np.ndarray:
    """Segment velocities of a free strand (along ``direction``) after falling ``seconds`` from rest under
    ``StrandDrag(**drag)``, or no drag at all (``None``)."""
    model, view, _ = _free_rod(mass_scale, direction)
    data = mujoco.MjData(model)
    strand_drag = StrandDrag(model, view.bodies, **drag) if drag is not None else None
    mujoco.mj_forward(model, data)
    for _ in range(round(seconds / model.opt.timestep)):
        if strand_drag is not None:
            strand_drag.apply(data)
        mujoco.mj_step(model, data)
    return StrandDrag(model, view.bodies, 1.0).velocity(data)


@pytest.mark.parametrize(("mass_scale", "normal_only"), [(1.0, False), (10.0, False), (10.0, True)])
def test_falling_strand_reaches_the_terminal_velocity(mass_scale: float, normal_only: bool) -> None:
    """A horizontal strand falling broadside settles at ``v_t = √(2 λ g / (ρ d))`` (λ its real mass per length):
    the drag balances the real weight, whatever the inertia the mass scaling adds. Broadside the whole velocity is
    normal to the strand, so the cross-flow drag (``normal_only``) settles at the same v_t."""
    rho = 1000.0
    v = _fall(0.5, mass_scale=mass_scale, drag={"density": rho, "normal_only": normal_only})
    v_t = _terminal_speed(rho)
    assert v[:, 2] == pytest.approx(-v_t, rel=0.02)
    assert np.abs(v[:, :2]).max() < 0.01 * v_t


def test_falling_strand_with_a_dead_zone_settles_above_it_by_the_terminal_velocity() -> None:
    """With the free speed v₀ the drag is ``½ ρ ℓ d (|v| − v₀)²``, so the broadside fall settles at ``v₀ + v_t``."""
    rho, v0 = 1000.0, 0.2
    v = _fall(1.5, mass_scale=10.0, drag={"density": rho, "free_speed": v0})
    assert v[:, 2] == pytest.approx(-(v0 + _terminal_speed(rho)), rel=0.02)


def test_drag_opposes_the_velocity_with_its_square() -> None:
    model, view, _ = _free_rod(1.0)
    data = mujoco.MjData(model)
    drag = StrandDrag(model, view.bodies, 500.0)
    data.qvel[:3] = [0.3, -0.4, 0.0]  # the free joint's linear velocity: every segment moves at 0.5 m/s
    mujoco.mj_forward(model, data)
    drag.apply(data)
    f = data.xfrc_applied[view.bodies, :3]
    expected = -drag.coefficient[:, None] * 0.5 * np.array([0.3, -0.4, 0.0])
    np.testing.assert_allclose(f, expected, rtol=1e-9, atol=1e-15)
    drag.clear(data)
    assert not data.xfrc_applied.any()


def test_dead_zone_drag_acts_on_the_speed_above_the_free_speed() -> None:
    """With ``free_speed`` v₀ the drag is ``−c (|v| − v₀)² v̂``: none below v₀, the plain drag's direction above."""
    model, view, _ = _free_rod(1.0)
    data = mujoco.MjData(model)
    drag = StrandDrag(model, view.bodies, 500.0, free_speed=0.3)
    data.qvel[:3] = [0.3, -0.4, 0.0]  # 0.5 m/s: 0.2 m/s above the free speed
    mujoco.mj_forward(model, data)
    drag.apply(data)
    f = data.xfrc_applied[view.bodies, :3]
    expected = -drag.coefficient[:, None] * 0.2**2 * np.array([0.6, -0.8, 0.0])
    np.testing.assert_allclose(f, expected, rtol=1e-9, atol=1e-15)
    data.qvel[:3] = [0.15, -0.2, 0.0]  # 0.25 m/s: inside the dead zone
    mujoco.mj_forward(model, data)
    drag.apply(data)
    assert not data.xfrc_applied.any()


@pytest.mark.parametrize("normal_only", [False, True])
def test_cross_flow_drag_leaves_a_strand_falling_end_on_in_free_fall(normal_only: bool) -> None:
    """A vertical strand falling along its own axis: the cross-flow drag (``normal_only``) has no normal velocity to
    act on, so it falls as it does without any drag, at g t; the drag of the whole velocity holds it at the
    broadside terminal speed v_t (that drag does not know the strand's orientation)."""

    rho, end_on = 1000.0, (0.0, 0.0, 1.0)  # real mass: free fall at g
    v_z = _fall(0.3, mass_scale=1.0, drag={"density": rho, "normal_only": normal_only}, direction=end_on)[
        :, 2
    ]
    if normal_only:
        free = _fall(0.3, mass_scale=1.0, drag=None, direction=end_on)[:, 2]
        assert free == pytest.approx(-9.81 * 0.3, rel=0.01)  # g t, read one step late
        np.testing.assert_allclose(v_z, free, rtol=1e-9)
    else:
        assert v_z == pytest.approx(-_terminal_speed(rho), rel=0.02)


def test_cross_flow_drag_acts_on_the_normal_velocity_only() -> None:
    """``−c |v_n| v_n`` with ``v_n = v − (v·t) t``: a strand along x moving at (0.3, −0.4, 0) m/s feels the drag of
    (0, −0.4, 0) only; with the dead zone as well, of |v_n| − v₀."""
    model, view, _ = _free_rod(1.0)
    data = mujoco.MjData(model)
    drag = StrandDrag(model, view.bodies, 500.0, normal_only=True)
    data.qvel[:3] = [0.3, -0.4, 0.0]
    mujoco.mj_forward(model, data)
    np.testing.assert_allclose(np.abs(drag.axes(data)[:, 0]), 1.0, rtol=1e-12)
    drag.apply(data)
    f = data.xfrc_applied[view.bodies, :3]
    expected = -drag.coefficient[:, None] * 0.4 * np.array([0.0, -0.4, 0.0])
    np.testing.assert_allclose(f, expected, rtol=1e-9, atol=1e-15)
    dead = StrandDrag(model, view.bodies, 500.0, free_speed=0.1, normal_only=True)
    dead.apply(data)
    expected = -dead.coefficient[:, None] * 0.3**2 * np.array([0.0, -1.0, 0.0])
    np.testing.assert_allclose(data.xfrc_applied[view.bodies, :3], expected, rtol=1e-9, atol=1e-15)


def test_bad_density_is_named() -> None:
    model, view, _ = _free_rod(1.0)
    with pytest.raises(ValueError, match="drag density"):
        StrandDrag(model, view.bodies, -1.0)
    with pytest.raises(ValueError, match="drag free speed"):
        StrandDrag(model, view.bodies, 1000.0, free_speed=-0.1)


def test_free_speed_needs_a_drag() -> None:
    from hairbrush_env import hair

    with pytest.raises(ValueError, match="drag_free_speed"):
        hair.PRESETS["curly"].replace(drag_free_speed=0.3)
    assert hair.PRESETS["curly"].replace(drag_density=1000.0, drag_free_speed=0.3).drag_free_speed == 0.3


def test_normal_only_needs_a_drag() -> None:
    from hairbrush_env import hair

    with pytest.raises(ValueError, match="drag_normal_only"):
        hair.PRESETS["curly"].replace(drag_normal_only=True)
    with pytest.raises(ValueError, match="drag_normal_only"):
        hair.PRESETS["curly"].replace(drag_density=1000.0, drag_normal_only=1)


def test_wig_digest_unchanged_by_unset_late_fields() -> None:
    """Cached pre-brushed states stay valid: ``quadratic_damping``, ``drag_density``, ``drag_free_speed``,
    ``drag_normal_only``, ``root_run`` and ``root_twist_first`` count in the digest only when set (the curly
    preset's digest before they existed: 01ed93b7c0f2bb45)."""
    from hairbrush_env import hair

    curly = hair.PRESETS["curly"]
    assert curly.digest() == "01ed93b7c0f2bb45"
    assert curly.replace(drag_density=1000.0).digest() != curly.digest()
    assert curly.replace(quadratic_damping=1e-3).digest() != curly.digest()
    assert curly.replace(root_run=0.5).digest() != curly.digest()
    assert curly.replace(root_twist_first=True).digest() != curly.digest()
    with_drag = curly.replace(drag_density=1000.0)
    assert with_drag.replace(drag_free_speed=0.3).digest() != with_drag.digest()
    assert with_drag.replace(drag_normal_only=True).digest() != with_drag.digest()
    assert with_drag.replace(drag_normal_only=False).digest() == with_drag.digest()


@pytest.mark.parametrize("normal_only", [False, True])
def test_a_curl_turning_about_its_axis_feels_sin3_of_the_drag_torque_across_it(normal_only: bool) -> None:
    """A helix (R 12 mm, P 24 mm: curly's R/P 0.5) turning rigidly about its axis at ω, as a curl does to let a tine
    through. Its wire moves at ωR along the turn, at the lead angle λ (tan λ = P / 2πR) to itself, so the drag of the
    whole velocity brakes it with the torque ``½ ρ d L R (ωR)²`` and the cross-flow drag with ``sin³ λ`` of that
    (``v_n = ωR sin λ``, and its share along the turn is ``sin λ``): 0.028 for curly. The chain is the helix's
    polygon, so R and λ are its chords' (midpoints at R cos(Δφ/2), lead tan λ = (P Δφ / 2π) / (2 R sin(Δφ/2))."""
    radius, pitch, turns, per_turn = 0.012, 0.024, 3, 16
    phi = np.linspace(0.0, 2.0 * math.pi * turns, turns * per_turn + 1)
    pts = np.column_stack([radius * np.cos(phi), radius * np.sin(phi), 1.0 - pitch * phi / (2.0 * math.pi)])
    rod = rods.RodSpec(name="h", points=pts, radius=8e-4, young=1e8, density=RHO_HAIR, clamp=None)
    model = rods.build_rod_model([rod])
    view = rods.RodView(model, "h")
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    omega = np.array([0.0, 0.0, 20.0])  # rad/s about the helix axis (the world z axis through x = y = 0)
    root = view.bodies[0]
    data.qvel[:3] = np.cross(
        omega, data.xpos[root]
    )  # the free joint: world linear velocity of the root's origin
    data.qvel[3:6] = data.xmat[root].reshape(3, 3).T @ omega  # and its angular velocity in the root's frame
    rho = 1000.0
    drag = StrandDrag(model, view.bodies, rho, normal_only=normal_only)
    mujoco.mj_forward(model, data)
    v = drag.velocity(data)
    np.testing.assert_allclose(v, np.cross(omega, data.xipos[view.bodies]), atol=1e-9)  # a rigid turn
    drag.apply(data)
    torque = np.cross(data.xipos[view.bodies], data.xfrc_applied[view.bodies, :3])[:, 2].sum()
    dphi = 2.0 * math.pi / per_turn
    r_mid = radius * math.cos(dphi / 2.0)
    lam = math.atan(pitch * dphi / (2.0 * math.pi) / (2.0 * radius * math.sin(dphi / 2.0)))
    full = -0.5 * rho * 2.0 * rod.radius * rod.length * r_mid * (omega[2] * r_mid) ** 2
    expected = full * math.sin(lam) ** 3 if normal_only else full
    assert torque == pytest.approx(expected, rel=1e-3)
