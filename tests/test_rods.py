"""Physics and API tests of :mod:`hairbrush_env.rods`, both kinds (body chain and DER flex) where they share a claim.

Every physics claim is compared with a closed-form result; tolerances are the ones promised in the module docs, not
fitted to pass. Each static test also checks that the centerline length is preserved within 0.5 %.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from hairbrush_env import hair, rods
from hairbrush_env.studies import rod_validation

# Small-deflection cantilever: 0.2 m, r = 1 mm, E = 10 GPa, keratin density. Under gravity the Euler–Bernoulli tip
# deflection is 1.0 mm = 0.5 % of L, so geometric nonlinearity (relative O((δ/L)²)) is far below the tolerances.
# (With E = 1 GPa and steel density the deflection would be 31 % of L — not a linear-theory case.)
L = 0.2
R_WIRE = 1e-3
E = 10e9
RHO = 1300.0
G_ACC = 9.81
LENGTH_TOL = 5e-3
SETTLE_S = 1.5  # the implicit step damps the first mode to < 1e-6 of its amplitude within this time


KINDS = ("chain", "flex")


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
        ("kind", {"kind": "cable"}),
        ("quadratic_damping", {"quadratic_damping": -1e-4}),
        ("quadratic_damping", {"quadratic_damping": 1e-4, "kind": "flex"}),
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
def _assert_healthy(model: mujoco.MjModel, data: mujoco.MjData) -> None:
    assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))
    counts = {mujoco.mjtWarning(i).name: int(w.number) for i, w in enumerate(data.warning) if w.number}
    assert not counts, counts


def _settle(model: mujoco.MjModel, data: mujoco.MjData, seconds: float) -> None:
    for _ in range(round(seconds / model.opt.timestep)):
        mujoco.mj_step(model, data)
    mujoco.mj_forward(model, data)  # positions of the final state (mj_step leaves them one step stale)


def _curl(turns: float, per_turn: int, radius: float, rise: float) -> np.ndarray:
    psi = np.linspace(0.0, 2.0 * math.pi * turns, round(turns * per_turn) + 1)
    return np.stack([radius * np.cos(psi), radius * np.sin(psi), rise * psi], axis=1)


# ------------------------------------------------------------------------------------------- structure
def test_matches_flexcomp_expansion() -> None:
    """With flexcomp's uniform masses, our MjSpec rod is bit-identical to ``<flexcomp type="direct" dim="1">``."""
    n = 8
    k = np.arange(n + 1) / n
    pts = np.stack([0.2 * k, 0.01 * np.sin(3 * k), 0.02 * k**2], axis=1)  # curved and non-planar
    rod = rods.RodSpec(
        name="R", points=pts, radius=1e-3, young=1e9, poisson=0.3, density=1300.0, damping=0.01, kind="flex"
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
    rods.configure_rod_options(spec, kind="flex")
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


def test_chain_structure_stiffness_and_mass() -> None:
    """One body per edge, three hinges a vertex with ``E I / l̄`` and ``G J / l̄`` (root ``2 E I / ℓ₀``), rigid masses."""
    pts = _curl(1.5, 8, 0.01, 0.004)
    rod = rods.RodSpec(name="c", points=pts, radius=5e-4, young=1e9, poisson=0.4, density=RHO, damping=0.02)
    model = rods.build_rod_model([rod], gravity=(0.0, 0.0, 0.0))
    n = rod.n_edges
    assert model.opt.solver == mujoco.mjtSolver.mjSOL_PGS
    assert model.opt.iterations == rods.CHAIN_SOLVER_ITERATIONS
    assert (model.nbody - 1, model.njnt, model.nv) == (n, 3 * n, 3 * n)
    ell = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    lbar = np.concatenate([[ell[0] / 2], 0.5 * (ell[:-1] + ell[1:])])
    for k in range(n):
        kb = model.jnt_stiffness[model.joint(f"c_{k}_bend1").id]
        kt = model.jnt_stiffness[model.joint(f"c_{k}_twist").id]
        assert kb == pytest.approx(rod.bending_stiffness / lbar[k], rel=1e-12)
        assert kt == pytest.approx(rod.twisting_stiffness / lbar[k], rel=1e-12)
        assert model.dof_damping[model.joint(f"c_{k}_bend2").dofadr[0]] == pytest.approx(0.02 * kb, rel=1e-12)
    assert model.body_mass[1:].sum() == pytest.approx(rod.linear_density * rod.length, rel=1e-12)
    assert model.nexclude == (n - 1) * (n - 2) // 2  # no self-contact beyond the parent-child filter
    self_colliding = rods.build_rod_model([rods.RodSpec(**{**rod.__dict__, "selfcollide": True})])
    assert self_colliding.nexclude == 0


@pytest.mark.parametrize("bend", ["bend1", "bend2"])
def test_chain_bent_90_degrees_at_one_vertex_keeps_three_independent_axes(bend: str) -> None:
    """A vertex's three hinges are an Euler sequence, singular (two axes aligned, the mass matrix loses rank) when
    the middle angle is ±90°. That must be the twist, which consecutive segments rarely reach, not a bend: a wisp
    pressed against the clamp bends 90° at one vertex (with the twist first, a brush stroke through the wavy wig
    raised MuJoCo's singular-inertia warning and ended as diverged)."""
    pts = rods.straight_rod_points([0, 0, 0], [0, 0, -1], 0.03, 3)
    model = rods.build_rod_model([rods.RodSpec(name="k", points=pts, radius=5e-4, young=1e9)])
    data = mujoco.MjData(model)
    data.qpos[model.joint(f"k_1_{bend}").qposadr[0]] = 0.5 * math.pi
    mujoco.mj_kinematics(model, data)
    axes = np.array([data.xaxis[model.joint(f"k_1_{j}").id] for j in ("bend1", "twist", "bend2")])
    assert abs(np.linalg.det(axes)) > 0.99
    data.qpos[model.joint("k_1_twist").qposadr[0]] = 0.5 * math.pi  # the one singular pose left
    mujoco.mj_kinematics(model, data)
    axes = np.array([data.xaxis[model.joint(f"k_1_{j}").id] for j in ("bend1", "twist", "bend2")])
    assert abs(np.linalg.det(axes)) < 1e-9


@pytest.mark.parametrize("kind", KINDS)
def test_vertices_before_stepping_equal_rest_points(kind: str) -> None:
    pts = rods.straight_rod_points([0.01, -0.02, 0.3], [1.0, 0.5, -0.2], 0.15, 12)
    model = rods.build_rod_model(
        [rods.RodSpec(name="hair", points=pts, radius=1e-4, young=4e9, density=1300.0, kind=kind)]
    )
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    view = rods.RodView(model, "hair")
    assert view.kind == kind
    np.testing.assert_allclose(view.vertices(data), pts, atol=1e-12)
    assert rods.rod_length(model, data, "hair") == pytest.approx(rods.polyline_length(pts), rel=1e-12)
    lam = RHO * math.pi * 1e-8
    moving = model.body_mass[view.bodies].sum()
    if kind == "flex":  # consistent lumping: the whole rod minus the root's half edge
        assert moving == pytest.approx(lam * (0.15 - 0.15 / 24), rel=1e-12)
    else:  # rigid segments: the whole rod moves
        assert moving == pytest.approx(lam * 0.15, rel=1e-12)


@pytest.mark.parametrize("kind", KINDS)
def test_add_rod_to_moving_parent(kind: str) -> None:
    """The clamp follows a parent body with a joint, and the rod comes along as a rigid body."""
    spec = mujoco.MjSpec()
    rods.configure_rod_options(spec, kind=kind)
    spec.option.gravity = [0.0, 0.0, 0.0]
    carrier = spec.worldbody.add_body(name="carrier", pos=[0.0, 0.0, 0.5])
    carrier.add_joint(name="lift", type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[0.0, 0.0, 1.0])
    carrier.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[0.01, 0, 0], mass=0.1, contype=0, conaffinity=0)
    pts = rods.straight_rod_points([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.1, 10)
    rods.add_rod(
        spec,
        rods.RodSpec(name="h", points=pts, radius=5e-4, young=1e9, density=RHO, kind=kind),
        parent=carrier,
    )
    model = spec.compile()
    data = mujoco.MjData(model)
    data.qvel[model.joint("lift").dofadr[0]] = 0.1  # move the carrier up; the rod must come along
    _settle(model, data, 0.2)
    x = rods.rod_vertices(model, data, "h")
    lift = data.qpos[model.joint("lift").qposadr[0]]
    assert lift > 0.005
    np.testing.assert_allclose(x[0], [0.0, 0.0, 0.5 + lift], atol=1e-9)
    np.testing.assert_allclose(x[:, 2], 0.5 + lift, atol=2e-3)  # rigid-body translation, small dynamic sag
    assert abs(rods.polyline_length(x) / 0.1 - 1.0) < LENGTH_TOL
    _assert_healthy(model, data)


def test_free_chain_falls_like_a_rigid_body() -> None:
    """An unclamped chain (free joint at its first vertex) falls at g and keeps its shape."""
    pts = _curl(1.0, 10, 0.01, 0.003)
    rod = rods.RodSpec(name="f", points=pts, radius=5e-4, young=1e9, density=RHO, clamp=None)
    model = rods.build_rod_model([rod])
    data = mujoco.MjData(model)
    _settle(model, data, 0.2)
    x = rods.rod_vertices(model, data, "f")
    drop = pts[:, 2] - x[:, 2]
    np.testing.assert_allclose(drop, 0.5 * G_ACC * data.time**2, rtol=0.02)
    np.testing.assert_allclose(np.diff(x[:, :2], axis=0), np.diff(pts[:, :2], axis=0), atol=1e-9)


# ------------------------------------------------------------------------------------------- physics
@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("load", ["gravity", "tip"])
def test_cantilever_default_discretization(kind: str, load: str) -> None:
    """Gravity (``w L⁴ / 8 E I``) and end load (``F L³ / 3 E I``) within 3 % at 20 edges; length kept."""
    r = rod_validation.cantilever_study(rods.DEFAULT_N_EDGES, kind=kind, load=load, settle=SETTLE_S)
    assert r.expected / L < 0.01  # small-deflection regime, so linear theory is the right reference
    assert r.rel_error == pytest.approx(0.0, abs=0.03)  # measured chain +0.25 / +0.12 %, flex +0.35 / +0.20 %
    assert abs(r.length_error) < LENGTH_TOL


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("n_edges", [50, 100])
def test_cantilever_converges(kind: str, n_edges: int) -> None:
    r = rod_validation.cantilever_study(n_edges, kind=kind, settle=SETTLE_S)
    assert r.rel_error == pytest.approx(0.0, abs=0.005)  # measured flex +0.08 % / +0.03 %
    assert abs(r.length_error) < LENGTH_TOL


def test_helical_spring_at_the_wigs_edges_per_turn() -> None:
    """Close-coiled spring ``k = G d⁴ / (8 D³ N)`` within 10 % at the edges per curl turn every wig uses.

    The coil loads the wire mostly in torsion, the deformation that holds a curl; 5 edges per turn (the flex wigs')
    gave +21 % (chain) and +189 % (flex).
    """
    per_turn = math.floor(min(w.n_edges / w.turns for w in hair.PRESETS.values() if w.curliness > 0))
    assert per_turn >= 8
    r = rod_validation.helix_study(per_turn, kind="chain")
    assert abs(r.rel_error) < 0.10, r
    assert abs(r.length_error) < LENGTH_TOL


def test_helical_spring_flex_fine() -> None:
    # 32 edges per turn (11° per edge); measured +3.5 % at 30/turn, +2.0 % at 40/turn, -0.1 % at 80/turn.
    r = rod_validation.helix_study(32, kind="flex")
    assert abs(r.rel_error) < 0.10
    assert abs(r.length_error) < LENGTH_TOL


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
def test_helical_spring_converges(kind: str) -> None:
    r = rod_validation.helix_study(64, kind=kind, turns=5)
    assert abs(r.rel_error) < 0.02
    assert abs(r.length_error) < LENGTH_TOL


@pytest.mark.parametrize("kind", KINDS)
def test_curled_rest_shape_is_kept_without_gravity(kind: str) -> None:
    """A curl (3D helix, 30 edges per turn) stays put: rest shape = given points."""
    pts = _curl(2.0, 30, 0.008, 0.003)
    rod = rods.RodSpec(name="curl", points=pts, radius=5e-5, young=4e9, density=RHO, damping=0.01, kind=kind)
    model = rods.build_rod_model([rod], gravity=(0.0, 0.0, 0.0))
    data = mujoco.MjData(model)
    _settle(model, data, 0.5)
    x = rods.rod_vertices(model, data, "curl")
    np.testing.assert_allclose(x, pts, atol=1e-9)
    _assert_healthy(model, data)


def test_quadratic_damping_torque_is_k_omega_abs_omega() -> None:
    """``quadratic_damping`` adds ``−c_q k ω|ω|`` to the linear ``−c k ω`` of every hinge (MuJoCo's polynomial
    damping), both signs of ω; measured on MuJoCo's own damper force at a set velocity."""
    pts = _curl(1.0, 8, 0.01, 0.004)
    c, cq = 0.02, 5e-4
    rod = rods.RodSpec(
        name="c", points=pts, radius=5e-4, young=1e9, density=RHO, damping=c, quadratic_damping=cq
    )
    model = rods.build_rod_model([rod], gravity=(0.0, 0.0, 0.0))
    data = mujoco.MjData(model)
    for label, omega in (("bend1", 30.0), ("twist", -80.0)):
        dof = model.joint(f"c_3_{label}").dofadr[0]
        k = model.jnt_stiffness[model.joint(f"c_3_{label}").id]
        data.qvel[:] = 0.0
        data.qvel[dof] = omega
        mujoco.mj_forward(model, data)
        assert data.qfrc_damper[dof] == pytest.approx(-k * (c * omega + cq * omega * abs(omega)), rel=1e-9)


def test_quadratic_damping_calms_a_whip_more_than_a_slow_swing() -> None:
    """The quadratic term takes more energy out of a fast spring-back than of a slow one: the ratio of the
    speeds after release with and without it grows with the initial deflection."""
    pts = _curl(1.0, 16, 0.01, 0.004)

    def tip_speed(cq: float, force: float) -> float:
        rod = rods.RodSpec(name="c", points=pts, radius=3e-4, young=1e9, density=RHO, damping=0.0,
                           quadratic_damping=cq)  # fmt: skip
        model = rods.build_rod_model([rod], gravity=(0.0, 0.0, 0.0))
        data = mujoco.MjData(model)
        view = rods.RodView(model, "c")
        for _ in range(round(0.3 / model.opt.timestep)):
            view.set_tip_force(data, np.array([0.0, force, 0.0]))
            mujoco.mj_step(model, data)
        data.xfrc_applied[:] = 0.0
        peak = 0.0
        for _ in range(round(0.05 / model.opt.timestep)):
            mujoco.mj_step(model, data)
            peak = max(peak, float(np.abs(data.qvel).max()))
        return peak

    slow = tip_speed(2e-4, 1e-3) / tip_speed(0.0, 1e-3)
    fast = tip_speed(2e-4, 8e-3) / tip_speed(0.0, 8e-3)
    assert fast < slow < 1.0


@pytest.mark.parametrize("kind", KINDS)
def test_curl_springs_back_after_release(kind: str) -> None:
    """Pull a curl's tip sideways, release, and it returns to its rest shape (elastic, no drift)."""
    pts = _curl(1.0, 30, 0.01, 0.004)
    rod = rods.RodSpec(name="c", points=pts, radius=3e-4, young=1e9, density=RHO, damping=0.01, kind=kind)
    model = rods.build_rod_model([rod], gravity=(0.0, 0.0, 0.0))
    data = mujoco.MjData(model)
    view = rods.RodView(model, "c")
    for _ in range(round(0.3 / model.opt.timestep)):
        view.set_tip_force(data, np.array([0.0, 5e-3, 0.0]))
        mujoco.mj_step(model, data)
    mujoco.mj_forward(model, data)
    moved = np.abs(view.vertices(data) - pts).max()
    data.xfrc_applied[:] = 0.0
    _settle(model, data, 1.5)
    back = np.abs(view.vertices(data) - pts).max()
    assert moved > 1e-3
    assert back < 1e-3 * moved
    assert abs(view.length(data) / rod.length - 1.0) < LENGTH_TOL
    _assert_healthy(model, data)


def test_chain_state_roundtrip_is_bit_identical() -> None:
    """A chain's whole state is qpos/qvel (no plastic frames): save/restore continues bit-identically."""
    pts = _curl(1.5, 12, 0.01, -0.003)
    model = rods.build_rod_model([rods.RodSpec(name="h", points=pts, radius=2e-4, young=2e9, density=RHO)])
    data = mujoco.MjData(model)
    data.qvel[:] = 0.05 * np.cos(np.arange(model.nv))
    _settle(model, data, 0.1)
    assert model.nplastic == 0
    sig = mujoco.mjtState.mjSTATE_INTEGRATION
    state = np.empty(mujoco.mj_stateSize(model, sig))
    mujoco.mj_getState(model, data, state, sig)
    _settle(model, data, 0.1)
    reference = data.qpos.copy()
    fresh = mujoco.MjData(model)
    mujoco.mj_setState(model, fresh, state, sig)
    _settle(model, fresh, 0.1)
    np.testing.assert_array_equal(fresh.qpos, reference)


def test_flex_state_roundtrip_with_plastic_is_bit_identical() -> None:
    """Save/restore incl. ``mjSTATE_PLASTIC`` (DER reference frames) continues bit-identically."""
    psi = np.linspace(0.0, 3.0 * math.pi, 41)
    pts = np.stack([0.01 * np.cos(psi), 0.01 * np.sin(psi), -0.003 * psi], axis=1)
    model = rods.build_rod_model(
        [rods.RodSpec(name="h", points=pts, radius=2e-4, young=2e9, density=RHO, kind="flex")]
    )
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


def _turned_rod_model(pts: np.ndarray, turn: float, **fields) -> mujoco.MjModel:
    """A clamped chain ``r`` built in ``pts``, its root springs referenced to ``pts`` turned by ``turn``; no gravity."""
    spec = mujoco.MjSpec()
    rods.configure_rod_options(spec, timestep=1e-3, kind="chain")
    spec.option.gravity = [0.0, 0.0, 0.0]
    rods.add_rod(
        spec,
        rods.RodSpec(
            name="r", points=pts, radius=8e-4, young=5e8, damping=0.05, root_rest_turn=turn, **fields
        ),
    )
    return spec.compile()


def _assert_relaxes_into_the_turned_shape(
    pts: np.ndarray, turn: float, model: mujoco.MjModel | None = None
) -> None:
    """Released from its built shape, the rod settles exactly into ``pts`` turned by ``turn`` about the vertical
    through its root."""
    model = model if model is not None else _turned_rod_model(pts, turn)
    data = mujoco.MjData(model)
    for _ in range(6000):
        mujoco.mj_step(model, data)
    c, s = math.cos(turn), math.sin(turn)
    want = (pts - pts[0]) @ np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]).T + pts[0]
    np.testing.assert_allclose(rods.RodView(model, "r").vertices(data), want, atol=1e-9)


@pytest.mark.parametrize("turn", [math.pi / 2, -math.pi / 3])
def test_root_rest_turn_makes_the_turned_shape_stress_free(turn):
    """A chain built in one shape with its root springs referenced to the shape turned about the vertical relaxes,
    without gravity, exactly into the turned shape (wigs' prestressed entwining, WigConfig.rest_splay)."""
    t = np.linspace(0.0, 1.0, 25)
    pts = np.column_stack([0.012 * np.cos(4 * np.pi * t), 0.012 * np.sin(4 * np.pi * t), -0.048 * t])
    _assert_relaxes_into_the_turned_shape(pts, turn)
    with pytest.raises(ValueError, match="root_rest_turn"):
        rods.RodSpec(name="f", points=pts, radius=8e-4, young=5e8, kind="flex", root_rest_turn=0.1)


def _root_twist_rest_deg(points: np.ndarray, turn: float) -> float:
    spec = mujoco.MjSpec()
    rods.configure_rod_options(spec, timestep=1e-3, kind="chain")
    rods.add_rod(spec, rods.RodSpec(name="r", points=points, radius=8e-4, young=5e8, root_rest_turn=turn))
    model = spec.compile()
    return math.degrees(float(model.qpos_spring[model.jnt_qposadr[model.joint("r_0_twist").id]]))


@pytest.mark.parametrize("tilt_deg", [43.0, 54.0, 62.0, 68.0, 72.0, 79.0])
def test_turned_root_rests_far_from_gimbal_lock(tilt_deg):
    """The three root hinges are an Euler sequence, singular where the middle (twist) angle reaches ±90°. A root
    whose quarter-turned rest shape would twist it by more than 25° gets its frame rolled: 47° → ≤ 31° for a first
    edge tilted 43° from the vertical (wavy), 36° → ≤ 16° at 54° (held_out_wavy, which locked under the comb:
    docs/detangling.md); from 68° on (held_out_curly, curly and curlier) the frame stays unrolled."""
    a = math.radians(tilt_deg)
    t = np.linspace(0.0, 1.0, 9)
    pts = np.column_stack([0.03 * t * math.sin(a), 0.01 * t**2, -0.03 * t * math.cos(a)])
    twist = abs(_root_twist_rest_deg(pts, math.pi / 2))
    unrolled = 90.0 - math.degrees(math.atan2(math.hypot(*(pts[1] - pts[0])[:2]), -(pts[1] - pts[0])[2]))
    if unrolled <= 25.0:
        assert twist == pytest.approx(unrolled, abs=0.5)
    else:
        assert twist <= (31.0 if tilt_deg < 50 else 16.0), (twist, unrolled)


def _straight_then_curled(n: int = 25) -> np.ndarray:
    """12 mm straight down from the root, then two curl turns (a v5/v6 wig strand's top)."""
    t = np.linspace(0.0, 1.0, n)
    curl = np.column_stack(
        [0.012 * (np.cos(4 * np.pi * t) - 1), 0.012 * np.sin(4 * np.pi * t), -0.012 - 0.048 * t]
    )
    return np.vstack([[0.0, 0.0, 0.0], [0.0, 0.0, -0.006], curl])


def test_a_root_hanging_straight_is_turned_purely_in_twist_and_twist_first_keeps_it_off_the_lock():
    """A first edge along the vertical is turned about its own tangent, so the rest twist equals the turn and no roll
    helps: π/2 puts the default order's middle hinge (twist) on the gimbal lock (v6's ψ under v5's root). With the
    twist first the middle hinge (bend1) rests at 0 and the rod still relaxes exactly into the turned shape."""
    pts = _straight_then_curled()
    with pytest.warns(UserWarning, match="Gimbal lock"):
        assert abs(_root_twist_rest_deg(pts, math.pi / 2)) == pytest.approx(90.0, abs=1e-6)
    turn = math.pi / 2
    model = _turned_rod_model(pts, turn, root_twist_first=True)
    names = [model.joint(j).name for j in range(model.njnt)][:3]
    assert names == ["r_0_twist", "r_0_bend1", "r_0_bend2"]
    rest = [math.degrees(float(model.qpos_spring[model.jnt_qposadr[model.joint(n).id]])) for n in names]
    assert (
        abs(rest[0]) == pytest.approx(90.0, abs=1e-6) and abs(rest[1]) < 1e-6
    )  # the middle hinge rests at 0
    _assert_relaxes_into_the_turned_shape(pts, turn, model)
    with pytest.raises(ValueError, match="root_twist_first"):
        rods.RodSpec(name="f", points=pts, radius=8e-4, young=5e8, clamp=None, root_twist_first=True)


# ------------------------------------------------------------------------------------------- mass scaling
def test_mass_scale_multiplies_inertia_not_weight() -> None:
    pts = _curl(1.0, 8, 0.01, 0.004)
    plain = rods.RodSpec(name="c", points=pts, radius=5e-4, young=1e9, density=RHO)
    heavy = rods.RodSpec(name="c", points=pts, radius=5e-4, young=1e9, density=RHO, mass_scale=10.0)
    m1, m10 = rods.build_rod_model([plain]), rods.build_rod_model([heavy])
    np.testing.assert_allclose(m10.body_mass[1:], 10.0 * m1.body_mass[1:], rtol=1e-12)
    np.testing.assert_allclose(m10.body_inertia[1:], 10.0 * m1.body_inertia[1:], rtol=1e-12)
    weight = m10.body_mass[1:] * (1.0 - m10.body_gravcomp[1:])
    np.testing.assert_allclose(weight, m1.body_mass[1:], rtol=1e-12)
    for bad in (0.5, float("nan")):
        with pytest.raises(ValueError, match="mass_scale"):
            rods.RodSpec(name="c", points=pts, radius=5e-4, young=1e9, mass_scale=bad)
    with pytest.raises(ValueError, match="mass_scale"):
        rods.RodSpec(name="c", points=pts, radius=5e-4, young=1e9, mass_scale=2.0, kind="flex")
    with pytest.raises(ValueError, match="mass_scale"):
        hair.WigConfig(mass_scale=0.9)


def test_mass_scaled_cantilever_sags_as_euler_bernoulli() -> None:
    """Ten times the inertia at the same weight: the gravity sag is still ``w L⁴ / 8 E I`` (within 3 %) and within
    0.2 % of the real-mass chain's."""
    real = rod_validation.cantilever_study(rods.DEFAULT_N_EDGES, settle=SETTLE_S)
    heavy = rod_validation.cantilever_study(rods.DEFAULT_N_EDGES, settle=3.0 * SETTLE_S, mass_scale=10.0)
    assert heavy.rel_error == pytest.approx(0.0, abs=0.03)
    assert heavy.measured == pytest.approx(real.measured, rel=2e-3)
    assert abs(heavy.length_error) < LENGTH_TOL


def _sink_into_capsule(mass_scale: float, load: float = 0.2) -> float:
    """How far [m] a wisp-like cantilever (r = 0.8 mm, hair contact parameters) pressed down at its tip by ``load``
    [N] sinks into a fixed crossing capsule, past the point where the contact (with both margins) engages."""
    r, rc, length = 8e-4, 1e-3, 0.1
    rod = rods.RodSpec(
        name="w", points=rods.straight_rod_points([0, 0, 0], [1, 0, 0], length, 10), radius=r, young=125e6,
        density=RHO, damping=0.02, contact_solref=hair.CONTACT_SOLREF, contact_solimp=hair.CONTACT_SOLIMP,
        margin=hair.CONTACT_MARGIN, mass_scale=mass_scale,
    )  # fmt: skip
    x_c = 0.095

    def obstacle(spec: mujoco.MjSpec) -> None:
        g = spec.worldbody.add_geom(
            name="bar", type=mujoco.mjtGeom.mjGEOM_CAPSULE, size=[rc, 0.02, 0], pos=[x_c, 0, -(r + rc)],
            quat=[math.cos(math.pi / 4), math.sin(math.pi / 4), 0, 0], margin=hair.CONTACT_MARGIN,
            solref=list(hair.CONTACT_SOLREF), solimp=list(hair.CONTACT_SOLIMP),
        )  # fmt: skip
        g.contype = g.conaffinity = 1

    model = rods.build_rod_model([rod], timestep=1e-3, gravity=(0, 0, 0), extra=obstacle)
    data = mujoco.MjData(model)
    tip = model.body("w_9").id
    for _ in range(3000):
        data.xfrc_applied[tip, 2] = -load
        mujoco.mj_step(model, data)
    assert np.abs(data.qvel).max() < 1e-3  # at rest
    x = rods.rod_vertices(model, data, "w")[:, [0, 2]]
    axis = np.array([x_c, -(r + rc)])
    a, b = x[:-1], x[1:]
    t = np.clip(np.einsum("ij,ij->i", axis - a, b - a) / np.einsum("ij,ij->i", b - a, b - a), 0.0, 1.0)
    gap = np.linalg.norm(a + t[:, None] * (b - a) - axis, axis=1).min() - (
        r + rc
    )  # centreline to bar, less radii
    return 2.0 * hair.CONTACT_MARGIN - gap


def test_mass_scale_stiffens_hair_contact() -> None:
    """A soft contact holds ~``m_eff/τ²`` newton per metre of sinking at time constant ``τ``, so ten times the
    segment inertia sinks several times less under the same load (``hair`` module docstring, *Mass scaling*)."""
    real, heavy = _sink_into_capsule(1.0), _sink_into_capsule(10.0)
    assert real > 0.0 and heavy > 0.0
    assert real > 3.0 * heavy  # measured 34 µm against 7.1 µm (4.7×; 3×: 18 µm, 30×: 2.8 µm)
