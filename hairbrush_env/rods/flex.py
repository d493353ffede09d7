"""Rods as 1D flexes: discrete elastic rods (DER) in MuJoCo 4.0 (``RodSpec.kind = "flex"``).

Kept beside the default body chains (:mod:`hairbrush_env.rods.chain`) for side-by-side benchmarks and for the
studies whose validation was done on it (double helix, curl census).

MuJoCo 4.0 removed ``<composite>`` and the cable plugin; a rod is now a 1D flex (``dim=1``) with
``<elasticity young=... poisson=... shear=...>`` (DER bending + torsion, per-edge twist hinge joints) plus an edge
equality constraint for inextensibility. This module builds such rods directly through :class:`mujoco.MjSpec`
(``spec.add_flex`` + vertex bodies + twist bodies + an ``mjEQ_FLEX`` equality) instead of the ``<flexcomp>`` XML
macro, because

* ``MjsBody.make_flex`` (the MjSpec flexcomp) cannot take explicit points or pins, and XML snippets would have to be
  re-attached into the scene spec;
* we need per-vertex masses (see *mass lumping*), which ``flexcomp mass=`` cannot express;
* the same :func:`add_flex_rod` then works on any spec and any parent body.

The raw flex built here is bit-identical to what ``<flexcomp type="direct" dim="1">`` expands into when given the same
masses (checked in ``tests/test_rods.py::test_matches_flexcomp_expansion``): vertex bodies ``<name>_<k>`` with three
world-aligned slide joints, twist bodies/hinges ``<name>_twist_<e>`` ... ``<name>_twist`` under the world body (their
names bind them to the flex edges, so they must follow that scheme), and twist-body polar inertia ``m_e r² / 2``.

Design decisions and the evidence behind them (0.2 m cantilever, r = 1 mm, E = 10 GPa, ρ = 1300 kg/m³, measured with
MuJoCo 4.0.1, see ``docs/rods.md``):

Integrator ``discrete`` + solver ``Newton`` (PGS does not support flex)
    1D rod elasticity is rejected by ``implicit``/``implicitfast``; ``discrete`` integrates it implicitly in position
    and is stable at large steps (static deflection identical to 4 digits from dt = 1 ms to 32 ms). Newton needs 0–1
    iterations per step here; CG was reported by the team to stop at its iteration cap with wrong statics.
Edge equality ``solref = (1e-4, 1)``
    The default edge equality (``solref = 0.02``) is soft: at 100 edges the cantilever stretched by 4.6 % and deflected
    +10.6 % too much. With ``1e-4`` the length error is 1e-6 (100 edges) and ≤ 1e-4 in a 970-dof helix.
``refsafe`` left ENABLED
    Under ``discrete`` the flag does not touch equality rows (documented for the flag; we checked that disabling it
    changes the cantilever results by exactly 0.0 at dt = 2 ms and 8 ms), while it still protects contact and limit rows
    of the scene whose ``solref`` the step cannot resolve. The team's "disable refsafe" advice predates ``discrete``.
Clamp through a short ghost edge
    A clamp pins both points of the first flex edge to the parent. DER places the slope of an edge at its midpoint, so
    pinning the real first edge clamps the rod at ``points[0] + ℓ/2``: the cantilever was 2/n too stiff (-19.0 % at 10
    edges, -2.0 % at 100). We therefore prepend a pinned ghost vertex at ``points[0] - GHOST_FRACTION·(points[1] -
    points[0])``; the clamp is then (up to 0.5 % of one edge) at ``points[0]`` with the tangent of the first segment,
    and convergence becomes second order (+1.2 % at 10 edges, +0.35 % at 20, +0.08 % at 50). ``points[0]`` is pinned,
    ``points[1]`` onwards move. :class:`RodView` hides the ghost vertex.
Consistent mass lumping
    ``flexcomp mass=`` gives every point ``M/(n+1)``, so the free tip carries a double share. We give point ``k`` the
    mass ``ρA(ℓ_{k-1} + ℓ_k)/2`` (ends get half shares), which is what the ``wL⁴/8EI`` comparison assumes.
Discretization: 20 edges per straight rod (:data:`~hairbrush_env.rods.DEFAULT_N_EDGES`)
    Gravity cantilever +0.35 %, end-loaded cantilever +0.20 %. Curved rods need finer edges: a helical spring's axial
    stiffness is +32 % / +7.7 % / +3.5 % / +2.0 % / -0.1 % off at 10 / 20 / 30 / 40 / 80 edges per turn, i.e. keep
    ≤ ~12° of turning per edge (≥ 30 edges per curl turn) for < 5 % stiffness error.
Timestep 2 ms (:data:`~hairbrush_env.rods.DEFAULT_TIMESTEP`)
    Statics do not depend on it (above). Dynamics: the first cantilever mode (19.4 Hz) is simulated at 18.9 Hz
    (-2.6 %); the implicit step damps it numerically (amplitude ×0.23 per 0.1 s; ×0.48 at 1 ms, ×0.05 at 4 ms).

Reading positions: flex vertex positions are ``data.flexvert_xpos`` (valid after ``mj_forward``/``mj_step``), see
:class:`RodView`. Rod reference frames live in ``data.plastic``; save/restore with
``mjtState.mjSTATE_INTEGRATION`` (which includes ``mjSTATE_PLASTIC``) or resets are not exact.
"""

from __future__ import annotations

import mujoco
import numpy as np

from .spec import RodSpec, resolve_body

__all__ = ["FRICTION_TORSION_ROLL", "GHOST_FRACTION", "add_flex_rod"]

GHOST_FRACTION = 0.01
"""Length of the pinned ghost edge behind a clamped root, as a fraction of the first edge (see module docstring)."""

_TWIST_BODY_MASS = 1e-9  # what flexcomp uses: the twist bodies only carry the polar inertia of their edge
# MuJoCo refuses moving bodies whose mass or inertia is below mjMINVAL (1e-15). A 40 µm hair edge of 1 cm has a polar
# inertia of ~5e-17 kg m², so twist inertias are floored here; this overestimates the rolling inertia of very thin
# hair (irrelevant for statics, and the twist dof is integrated implicitly, so stability is unaffected).
_MIN_INERTIA = 4.0 * mujoco.mjMINVAL
FRICTION_TORSION_ROLL = (0.005, 0.0001)
"""MuJoCo's default torsional / rolling friction coefficients, used by both rod kinds."""


def add_flex_rod(
    spec: mujoco.MjSpec,
    rod: RodSpec,
    *,
    parent: mujoco.MjsBody | str | None = None,
) -> mujoco.MjsFlex:
    """Add one rod to ``spec`` as a raw 1D flex with DER elasticity.

    Creates (``k`` indexes ``rod.points``)

    * bodies ``<name>_<k>`` (children of ``parent``, placed at ``points[k]``) with three slide joints and the
      consistently lumped mass ``ρA(ℓ_{k-1} + ℓ_k)/2`` — for every moving point (``k ≥ 1`` if clamped);
    * twist bodies + hinge joints ``<name>_twist_<e>`` / ``<name>_twist`` under the world body (names fixed by
      MuJoCo; ``e`` counts flex edges, which include the ghost edge of a clamped rod);
    * the flex ``<name>`` (no self-collision unless ``rod.selfcollide``) and its edge equality constraint.

    Parameters
    ----------
    spec : mujoco.MjSpec
        Any spec; call :func:`configure_rod_options` on it as well (rods require the ``discrete`` integrator).
    rod : RodSpec
        The rod; ``rod.points`` are expressed in the frame of ``parent``.
    parent : mujoco.MjsBody or str or None
        Body holding the clamped root (and the parent of the vertex bodies); ``None`` = world. A moving parent
        (with joints) receives the rod's reaction force and torque. Unclamped rods need a jointless parent.

    Returns
    -------
    mujoco.MjsFlex
        The flex (its properties may still be edited before compiling).
    """
    pbody = resolve_body(spec, parent)
    pname = pbody.name or "world"
    given = rod.points
    clamped = rod.clamp == "start"
    if clamped:
        # Pinned ghost vertex just behind the root: with the first *flex* edge that short, DER's built-in end sits at
        # points[0] instead of half an edge further out (see module docstring: -2/n error -> second order).
        ghost = given[0] - GHOST_FRACTION * (given[1] - given[0])
        pts = np.vstack([ghost, given])
    else:
        pts = np.asarray(given)
    offset = len(pts) - len(given)  # flex vertex index = point index + offset
    n_flex_edges = len(pts) - 1

    seg_given = np.linalg.norm(np.diff(given, axis=0), axis=1)
    lam = rod.linear_density
    point_mass = np.zeros(len(given))
    point_mass[:-1] += 0.5 * lam * seg_given
    point_mass[1:] += 0.5 * lam * seg_given

    vertbody: list[str] = []
    vert: list[float] = []
    for i, p in enumerate(pts):
        k = i - offset
        if clamped and k <= 0:  # ghost and root: part of the parent body
            vertbody.append(pname)
            vert.extend(float(c) for c in p)
            continue
        body = pbody.add_body(name=f"{rod.name}_{k}", pos=[float(c) for c in p])
        body.explicitinertial = True
        body.ipos = [0.0, 0.0, 0.0]  # unset ipos would not default to the body origin
        body.mass = float(point_mass[k])
        # A point mass: rotational inertia never enters (slide joints only) but must be positive. Same formula
        # as flexcomp (inertia box of 1 cm), floored for MuJoCo's mjMINVAL check.
        body.inertia = [max(float(point_mass[k]) * 1e-4 / 6.0, _MIN_INERTIA)] * 3
        for axis in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)):
            body.add_joint(type=mujoco.mjtJoint.mjJNT_SLIDE, axis=list(axis))
        vertbody.append(f"{rod.name}_{k}")
        vert.extend([0.0, 0.0, 0.0])

    if n_flex_edges >= 2:
        seg_flex = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        first = 1 if clamped else 0  # a clamped first edge has no twist dof
        for e in range(first, n_flex_edges):
            jname = f"{rod.name}_twist" if e == n_flex_edges - 1 else f"{rod.name}_twist_{e}"
            tbody = spec.worldbody.add_body(name=jname)
            tbody.explicitinertial = True
            tbody.ipos = [0.0, 0.0, 0.0]
            tbody.mass = _TWIST_BODY_MASS
            polar = 0.5 * lam * float(seg_flex[e]) * rod.radius**2  # polar inertia m_e r²/2 of the edge
            tbody.inertia = [max(polar, _MIN_INERTIA)] * 3
            tbody.add_joint(name=jname, type=mujoco.mjtJoint.mjJNT_HINGE, axis=[1.0, 0.0, 0.0])

    contact_kwargs: dict[str, list[float]] = {}
    if rod.contact_solref is not None:
        contact_kwargs["solref"] = [float(v) for v in rod.contact_solref]
    if rod.contact_solimp is not None:
        contact_kwargs["solimp"] = [float(v) for v in rod.contact_solimp]
    flex = spec.add_flex(
        name=rod.name,
        dim=1,
        radius=rod.radius,
        vertbody=vertbody,
        vert=vert,
        elem=[v for e in range(n_flex_edges) for v in (e, e + 1)],
        young=rod.young,
        poisson=rod.poisson,
        shear=0.0 if rod.shear is None else rod.shear,  # 0 means "isotropic from young/poisson" in MuJoCo
        damping=rod.damping,
        friction=[rod.friction, *FRICTION_TORSION_ROLL],
        rgba=list(rod.rgba),
        contype=rod.contype,
        conaffinity=rod.conaffinity,
        condim=rod.condim,
        group=rod.group,
        margin=rod.margin,
        selfcollide=mujoco.mjtFlexSelf.mjFLEXSELF_AUTO
        if rod.selfcollide
        else mujoco.mjtFlexSelf.mjFLEXSELF_NONE,
        **contact_kwargs,
    )
    spec.add_equality(type=mujoco.mjtEq.mjEQ_FLEX, name1=rod.name, solref=list(rod.edge_solref))
    return flex
