"""Physics and API tests of :mod:`hairbrush_env.rods` (DER hair in MuJoCo 4.0).

Every physics claim is compared with a closed-form result; tolerances are the ones promised in the module docs, not
fitted to pass. Each static test also checks that the centerline length is preserved within 0.5 %.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from hairbrush_env import rods

# Small-deflection cantilever: 0.2 m, r = 1 mm, E = 10 GPa, keratin density. Under gravity the Euler–Bernoulli tip
# deflection is 1.0 mm = 0.5 % of L, so geometric nonlinearity (relative O((δ/L)²)) is far below the tolerances.
# (With E = 1 GPa and steel density the deflection would be 31 % of L — not a linear-theory case.)
L = 0.2
R_WIRE = 1e-3
E = 10e9
RHO = 1300.0
G_ACC = 9.81
LENGTH_TOL = 5e-3
SETTLE_S = 1.5  # the implicit step damps the 19 Hz first mode to < 1e-6 of its amplitude within this time


def _straight_rod(n_edges: int, **kw: object) -> rods.RodSpec:
    pts = rods.straight_rod_points([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], L, n_edges)
    return rods.RodSpec(name="R", points=pts, radius=R_WIRE, young=E, density=RHO, **kw)


def _assert_healthy(model: mujoco.MjModel, data: mujoco.MjData) -> None:
    assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))
    counts = {mujoco.mjtWarning(i).name: int(w.number) for i, w in enumerate(data.warning) if w.number}
    assert not counts, counts


def _settle(model: mujoco.MjModel, data: mujoco.MjData, seconds: float) -> None:
    for _ in range(round(seconds / model.opt.timestep)):
        mujoco.mj_step(model, data)


def _cantilever_tip(n_edges: int, *, tip_force: float = 0.0, gravity: bool = True) -> tuple[float, float]:
    """Static tip deflection (positive down) and relative length change of the clamped straight rod."""
    rod = _straight_rod(n_edges)
    model = rods.build_rod_model([rod], gravity=(0.0, 0.0, -G_ACC if gravity else 0.0))
    data = mujoco.MjData(model)
    if tip_force:
        data.xfrc_applied[model.body(f"R_{n_edges}").id, 2] = -tip_force
    _settle(model, data, SETTLE_S)
    view = rods.RodView(model, "R")
    x = view.vertices(data)
    _assert_healthy(model, data)
    return -float(x[-1, 2]), view.length(data) / rod.length - 1.0


# ------------------------------------------------------------------------------------------- validation
def test_material_helpers() -> None:
    assert rods.bending_stiffness(2.0, 1.0) == pytest.approx(math.pi / 2)
    assert rods.twisting_stiffness(2.0, 1.0) == pytest.approx(math.pi)
    assert rods.shear_modulus(2.6, 0.3) == pytest.approx(1.0)
    assert rods.polyline_length(np.array([[0, 0, 0], [3, 4, 0], [3, 4, 1]])) == pytest.approx(6.0)


@pytest.mark.parametrize(
    ("field", "kwargs"),
    [
        ("radius", {"radius": -1e-3}),
        ("radius", {"radius": float("nan")}),
        ("young", {"young": -1.0}),
        ("young", {"young": float("inf")}),
        ("density", {"density": -5.0}),
        ("density", {"density": float("nan")}),
        ("points", {"points": np.zeros((1, 3))}),
        ("points", {"points": np.zeros((4, 2))}),
        ("points", {"points": np.array([[0, 0, 0], [1, 0, 0], [np.nan, 0, 0]])}),
        ("points", {"points": np.array([[0, 0, 0], [1, 0, 0], [1, 0, 0]])}),
        ("clamp", {"clamp": "end"}),
        ("poisson", {"poisson": 0.5}),
        ("shear", {"shear": -1.0}),
    ],
)
def test_bad_input_names_field(field: str, kwargs: dict[str, object]) -> None:
    base: dict[str, object] = {
        "name": "R",
        "points": rods.straight_rod_points([0, 0, 0], [1, 0, 0], 0.1, 4),
        "radius": 1e-3,
        "young": 1e9,
        "density": 1300.0,
    }
    base.update(kwargs)
    with pytest.raises(ValueError, match=field):
        rods.RodSpec(**base)  # type: ignore[arg-type]


def test_points_are_frozen_copy() -> None:
    pts = rods.straight_rod_points([0, 0, 0], [1, 0, 0], 0.1, 4)
    rod = rods.RodSpec(name="R", points=pts, radius=1e-3, young=1e9, density=1300.0)
    pts[1, 0] = 99.0
    assert rod.points[1, 0] == pytest.approx(0.025)
    with pytest.raises(ValueError):
        rod.points[0, 0] = 1.0


# ------------------------------------------------------------------------------------------- structure
def test_matches_flexcomp_expansion() -> None:
    """With flexcomp's uniform masses, our MjSpec rod is bit-identical to ``<flexcomp type="direct" dim="1">``."""
    n = 8
    k = np.arange(n + 1) / n
    pts = np.stack([0.2 * k, 0.01 * np.sin(3 * k), 0.02 * k**2], axis=1)  # curved and non-planar
    rod = rods.RodSpec(
        name="R", points=pts, radius=1e-3, young=1e9, poisson=0.3, density=1300.0, damping=0.01
    )
    ghost = pts[0] - rods.GHOST_FRACTION * (pts[1] - pts[0])
    allpts = np.vstack([ghost, pts])
    total = 0.05
    xml = f"""<mujoco><option integrator="discrete" solver="Newton"/><worldbody>
      <flexcomp name="R" type="direct" dim="1" radius="0.001" mass="{total}" rgba="{" ".join(map(str, rod.rgba))}"
                point="{" ".join(map(repr, allpts.ravel().tolist()))}"
                element="{" ".join(f"{i} {i + 1}" for i in range(n + 1))}">
        <edge equality="true" solref="{rod.edge_solref[0]} {rod.edge_solref[1]}"/>
        <elasticity young="1e9" poisson="0.3" damping="0.01"/>
        <contact selfcollide="none" friction="{rod.friction}"/>
        <pin id="0 1"/>
      </flexcomp></worldbody></mujoco>"""
    ref = mujoco.MjSpec.from_string(xml).compile()

    spec = mujoco.MjSpec()
    rods.configure_rod_options(spec)
    rods.add_rod(spec, rod)
    for body in spec.bodies:  # impose flexcomp's mass model: M/(points) per vertex, M/(edges) per twist edge
        if body.name.startswith("R_twist"):
            body.inertia = [0.5 * total / (n + 1) * 1e-6] * 3
        elif body.name.startswith("R_"):
            body.mass = total / (n + 2)
            body.inertia = [total / (n + 2) * 1e-4 / 6.0] * 3  # flexcomp's inertiabox default
    ours = spec.compile()
    assert (ours.nq, ours.nv, ours.nbody, ours.nplastic) == (ref.nq, ref.nv, ref.nbody, ref.nplastic)
    np.testing.assert_array_equal(ours.flex_bending, ref.flex_bending)

    d1, d2 = mujoco.MjData(ref), mujoco.MjData(ours)
    d1.qvel[:] = d2.qvel[:] = 0.1 * np.sin(np.arange(ref.nv))
    for _ in range(200):
        mujoco.mj_step(ref, d1)
        mujoco.mj_step(ours, d2)
    np.testing.assert_array_equal(d1.flexvert_xpos, d2.flexvert_xpos)
    np.testing.assert_array_equal(d1.plastic, d2.plastic)


def test_vertices_before_stepping_equal_rest_points() -> None:
    pts = rods.straight_rod_points([0.01, -0.02, 0.3], [1.0, 0.5, -0.2], 0.15, 12)
    model = rods.build_rod_model(
        [rods.RodSpec(name="hair", points=pts, radius=1e-4, young=4e9, density=1300.0)]
    )
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    np.testing.assert_allclose(rods.rod_vertices(model, data, "hair"), pts, atol=1e-12)
    assert rods.rod_length(model, data, "hair") == pytest.approx(rods.polyline_length(pts), rel=1e-12)
    # Consistent lumping: total moving mass = the whole rod minus the root's half edge.
    lam = RHO * math.pi * 1e-8
    seg = 0.15 / 12
    moving = sum(model.body(f"hair_{k}").mass[0] for k in range(1, 13))
    assert moving == pytest.approx(lam * (0.15 - seg / 2), rel=1e-12)
    assert model.body("hair_12").mass[0] == pytest.approx(lam * seg / 2, rel=1e-12)


def test_add_rod_to_moving_parent() -> None:
    """The clamp follows a parent body with a joint, and the parent carries the rod's weight."""
    spec = mujoco.MjSpec()
    rods.configure_rod_options(spec)
    spec.option.gravity = [0.0, 0.0, 0.0]
    carrier = spec.worldbody.add_body(name="carrier", pos=[0.0, 0.0, 0.5])
    carrier.add_joint(name="lift", type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[0.0, 0.0, 1.0])
    carrier.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.01, 0, 0], mass=0.1, contype=0, conaffinity=0)
    pts = rods.straight_rod_points([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.1, 10)
    rods.add_rod(
        spec, rods.RodSpec(name="h", points=pts, radius=5e-4, young=1e9, density=RHO), parent=carrier
    )
    model = spec.compile()
    data = mujoco.MjData(model)
    data.qvel[model.joint("lift").dofadr[0]] = 0.1  # move the carrier up; the rod must come along
    _settle(model, data, 0.2)
    mujoco.mj_forward(
        model, data
    )  # after mj_step, flexvert_xpos is one step stale (kinematics of the old qpos)
    x = rods.rod_vertices(model, data, "h")
    lift = data.qpos[model.joint("lift").qposadr[0]]
    assert lift > 0.005
    np.testing.assert_allclose(x[0], [0.0, 0.0, 0.5 + lift], atol=1e-9)
    np.testing.assert_allclose(x[:, 2], 0.5 + lift, atol=2e-3)  # rigid-body translation, small dynamic sag
    assert abs(rods.polyline_length(x) / 0.1 - 1.0) < LENGTH_TOL
    _assert_healthy(model, data)


# ------------------------------------------------------------------------------------------- physics
def test_cantilever_gravity_default_discretization() -> None:
    w = RHO * math.pi * R_WIRE**2 * G_ACC
    expected = w * L**4 / (8.0 * rods.bending_stiffness(E, R_WIRE))
    assert expected / L < 0.01  # small-deflection regime, so linear theory is the right reference
    tip, stretch = _cantilever_tip(rods.DEFAULT_N_EDGES)
    assert tip == pytest.approx(expected, rel=0.03)
    assert abs(stretch) < LENGTH_TOL


def test_cantilever_end_load_default_discretization() -> None:
    force = 3e-3  # N; tip deflection 1.0 mm = 0.5 % of L
    expected = force * L**3 / (3.0 * rods.bending_stiffness(E, R_WIRE))
    assert expected / L < 0.01
    tip, stretch = _cantilever_tip(rods.DEFAULT_N_EDGES, tip_force=force, gravity=False)
    assert tip == pytest.approx(expected, rel=0.03)
    assert abs(stretch) < LENGTH_TOL


@pytest.mark.slow
@pytest.mark.parametrize("n_edges", [50, 100])
def test_cantilever_converges(n_edges: int) -> None:
    w = RHO * math.pi * R_WIRE**2 * G_ACC
    expected = w * L**4 / (8.0 * rods.bending_stiffness(E, R_WIRE))
    tip, stretch = _cantilever_tip(n_edges)
    assert tip == pytest.approx(expected, rel=0.005)  # measured +0.08 % / +0.03 %
    assert abs(stretch) < LENGTH_TOL


def _helix_stiffness_error(turns: int, per_turn: int, seconds: float) -> tuple[float, float]:
    """Relative error of a close-coiled spring's axial stiffness vs ``G d⁴ / (8 D³ N)``, and the length change.

    The coil (axis z, pitch angle 3.6°) is clamped at its first edge; its far end turns radially inward into a
    straight 3-edge arm so that the axial force is applied ON the axis (a force at the coil wire would also tilt the
    spring). The arm's own cantilever compliance ``R³ / (3 E I)`` (≈ 1 % of the coil's) is subtracted.
    """
    coil_r, pitch, wire_r, young, poisson = 0.01, 0.004, 1e-3, 1e9, 0.49
    psi = np.linspace(0.0, 2.0 * math.pi * turns, turns * per_turn + 1)
    coil = np.stack([coil_r * np.cos(psi), coil_r * np.sin(psi), pitch * psi / (2.0 * math.pi)], axis=1)
    s = np.linspace(1.0, 0.0, 4)[1:]
    arm = np.stack([coil[-1, 0] * s, coil[-1, 1] * s, np.full(3, coil[-1, 2])], axis=1)
    pts = np.vstack([coil, arm])
    rod = rods.RodSpec(name="H", points=pts, radius=wire_r, young=young, poisson=poisson, density=RHO)
    model = rods.build_rod_model([rod], gravity=(0.0, 0.0, 0.0))
    data = mujoco.MjData(model)
    k_expected = rods.shear_modulus(young, poisson) * (2 * wire_r) ** 4 / (8.0 * (2 * coil_r) ** 3 * turns)
    force = 0.01 * pitch * turns * k_expected  # extension = 1 % of the coil height: linear regime
    data.xfrc_applied[model.body(f"H_{len(pts) - 1}").id, 2] = force
    _settle(model, data, seconds)
    _assert_healthy(model, data)
    view = rods.RodView(model, "H")
    x = view.vertices(data)
    dz = x[-1, 2] - pts[-1, 2]
    arm_compliance = coil_r**3 / (3.0 * rods.bending_stiffness(young, wire_r))
    k_measured = force / (dz - force * arm_compliance)
    return k_measured / k_expected - 1.0, view.length(data) / rod.length - 1.0


def test_helical_spring_stiffness_fast() -> None:
    # 32 edges per turn (11° per edge); measured +3.5 % at 30/turn, +2.0 % at 40/turn, -0.1 % at 80/turn.
    err, stretch = _helix_stiffness_error(turns=3, per_turn=32, seconds=1.0)
    assert abs(err) < 0.10
    assert abs(stretch) < LENGTH_TOL


@pytest.mark.slow
def test_helical_spring_stiffness_fine() -> None:
    err, stretch = _helix_stiffness_error(turns=5, per_turn=64, seconds=1.0)
    assert abs(err) < 0.02
    assert abs(stretch) < LENGTH_TOL


def test_curled_rest_shape_is_kept_without_gravity() -> None:
    """A curl (3D helix, 30 edges per turn) stays put: rest shape = given points."""
    psi = np.linspace(0.0, 4.0 * math.pi, 61)
    pts = np.stack([0.008 * np.cos(psi), 0.008 * np.sin(psi), 0.003 * psi], axis=1)
    rod = rods.RodSpec(name="curl", points=pts, radius=5e-5, young=4e9, density=RHO, damping=0.01)
    model = rods.build_rod_model([rod], gravity=(0.0, 0.0, 0.0))
    data = mujoco.MjData(model)
    _settle(model, data, 0.5)
    x = rods.rod_vertices(model, data, "curl")
    np.testing.assert_allclose(x, pts, atol=1e-9)
    assert abs(rods.polyline_length(x) / rod.length - 1.0) < LENGTH_TOL
    _assert_healthy(model, data)


def test_curl_springs_back_after_release() -> None:
    """Pull a free curl's tip sideways, release, and it returns to its rest shape (elastic, no drift)."""
    psi = np.linspace(0.0, 2.0 * math.pi, 31)
    pts = np.stack([0.01 * np.cos(psi), 0.01 * np.sin(psi), 0.004 * psi], axis=1)
    rod = rods.RodSpec(name="c", points=pts, radius=3e-4, young=1e9, density=RHO, damping=0.01)
    model = rods.build_rod_model([rod], gravity=(0.0, 0.0, 0.0))
    data = mujoco.MjData(model)
    tip = model.body("c_30").id
    data.xfrc_applied[tip, 1] = 5e-3
    _settle(model, data, 0.3)
    moved = np.abs(rods.rod_vertices(model, data, "c") - pts).max()
    data.xfrc_applied[tip] = 0.0
    _settle(model, data, 1.5)
    back = np.abs(rods.rod_vertices(model, data, "c") - pts).max()
    assert moved > 1e-3
    assert back < 1e-3 * moved
    _assert_healthy(model, data)


def test_state_roundtrip_with_plastic_is_bit_identical() -> None:
    """Save/restore incl. ``mjSTATE_PLASTIC`` (DER reference frames) continues bit-identically."""
    psi = np.linspace(0.0, 3.0 * math.pi, 41)
    pts = np.stack([0.01 * np.cos(psi), 0.01 * np.sin(psi), -0.003 * psi], axis=1)
    model = rods.build_rod_model([rods.RodSpec(name="h", points=pts, radius=2e-4, young=2e9, density=RHO)])
    data = mujoco.MjData(model)
    data.qvel[:] = 0.05 * np.cos(np.arange(model.nv))  # excite twist as well
    _settle(model, data, 0.1)
    assert model.nplastic > 0
    sig = mujoco.mjtState.mjSTATE_INTEGRATION
    assert int(sig) & int(mujoco.mjtState.mjSTATE_PLASTIC)
    state = np.empty(mujoco.mj_stateSize(model, sig))
    mujoco.mj_getState(model, data, state, sig)

    _settle(model, data, 0.1)
    reference = data.flexvert_xpos.copy(), data.qpos.copy(), data.plastic.copy()

    fresh = mujoco.MjData(model)
    mujoco.mj_setState(model, fresh, state, sig)
    _settle(model, fresh, 0.1)
    np.testing.assert_array_equal(fresh.flexvert_xpos, reference[0])
    np.testing.assert_array_equal(fresh.qpos, reference[1])
    np.testing.assert_array_equal(fresh.plastic, reference[2])
    _assert_healthy(model, fresh)
