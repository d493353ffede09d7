"""Rods as chains of capsule bodies with three hinges a vertex (``RodSpec.kind = "chain"``, the default).

This is what MuJoCo's removed ``<composite type="cable">`` expanded to, written with :class:`mujoco.MjSpec`: one
body per edge, nested root to tip, each holding a capsule along its local x axis; the body of edge ``k`` sits at
``points[k]`` and turns against its parent through three hinges at that vertex,

* two **bending** hinges about the local y and z axes with stiffness ``E I / l̄_k``,
* a **twist** hinge about the edge tangent (local x), between them, with stiffness ``G J / l̄_k``,

where ``l̄_k = (ℓ_{k−1} + ℓ_k) / 2`` is the Voronoi length of vertex ``k`` (Bergou et al. 2008). At a clamped root
the spring stands for the curvature of the first half edge, ``l̄_0 = ℓ_0 / 2`` (stiffness ``2 E I / ℓ_0``), the
body-chain twin of the flex's ghost edge. The rest shape is ``qpos0``: body frames follow the rest centerline with
parallel-transported (twist-free) frames, so every spring is relaxed in the given curve and curls stay curled. A
root whose stress-free shape is turned (``RodSpec.root_rest_turn``) has its root springs referenced to the turned
frame, and its frames are rolled about the tangent so that this reference stays far from the hinges' gimbal lock
(:func:`_root_roll`).
Damping is stiffness-proportional (``damping · k``, in seconds like the flex's Rayleigh damping); armature
:data:`_ARMATURE`.

Why three hinges: a ball joint's one isotropic stiffness makes torsion ``1 + ν`` too stiff, and two bending hinges
alone make a coil rigid in torsion; with three, a helical spring converges to ``G d⁴ / (8 D³ N)`` several times faster
per edge than the DER flex (``docs/rods.md``). The twist sits between the two bends, see :data:`_JOINT_AXES`.

Solver: the ``discrete`` integrator with **PGS capped at** :data:`CHAIN_SOLVER_ITERATIONS` iterations
(:func:`hairbrush_env.rods.configure_rod_options`). Newton is slow on long chains, because a contact's Jacobian
spans every joint from the root to the contact; PGS needs no factorization of it.

Inextensibility is exact (the bodies are rigid), so there is no edge equality; masses and inertias are those of
the rigid segments (solid cylinders, centre of mass mid-edge).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
from scipy.spatial.transform import Rotation

from .flex import FRICTION_TORSION_ROLL
from .spec import RodSpec, resolve_body

__all__ = ["CHAIN_SOLVER_ITERATIONS", "add_chain_rod", "chain_frames"]

CHAIN_SOLVER_ITERATIONS = 50
"""PGS iteration cap for chain rods in contact. An unconverged PGS solve acts as a soft contact, so the cap sets how far
strands squeezed by the brush sink into each other. 30 sufficed for the soft paddle brush (``docs/rods.md``,
``scripts/benchmark_sim.py --section solver``); under the comb at the pain threshold it let curly strands sink to 0.32
of the sum of radii, 50 kept them at 0.52 for the same CPU time (the solve stops at its tolerance first in most
steps; ``docs/detangling.md``)."""

# MuJoCo refuses moving bodies whose mass or inertia is below mjMINVAL (1e-15): a 50 µm, 1.7 mm segment has a polar
# inertia of 2e-17 kg m². Floored, as the flex floors its twist inertias; it only slows the fastest twist mode.
_MIN_INERTIA = 4.0 * mujoco.mjMINVAL
# MuJoCo composes a body's hinges in order, each about its axis in the already-rotated frame, so three hinges are an
# Euler-angle sequence: singular (two axes aligned, the mass matrix loses rank) when the middle angle reaches ±90°.
# Twist sits in the middle: consecutive segments rarely twist by 90°, while a wisp pressed against the clamp does
# bend that far at one vertex — with the twist first, such a bend raised MuJoCo's singular-inertia warning. A root
# whose rest turn is a pure twist of about 90° (a strand hanging straight below it) may put the twist first instead
# (RodSpec.root_twist_first): then the rest reference, not a rare bend, decides which angle sits near the lock.
_JOINT_AXES = (("bend1", (0.0, 1.0, 0.0)), ("twist", (1.0, 0.0, 0.0)), ("bend2", (0.0, 0.0, 1.0)))
_ROOT_TWIST_FIRST_AXES = (_JOINT_AXES[1], _JOINT_AXES[0], _JOINT_AXES[2])
"""The root's hinges with the twist first (``RodSpec.root_twist_first``)."""
_ARMATURE = 0.1
"""Armature of every vertex's three hinges, as a fraction of the segment's moment of inertia about the vertex
(``m ℓ²/3``). The hinges are an Euler sequence: where a twist reaches ±90° two of their axes align and the joint-space
inertia matrix turns singular (MuJoCo's ``mjWARN_INERTIA``). Strands dragged by the comb took roots and interior
vertices there (coily seed 1, vertex 17, second full stroke). The armature keeps the matrix regular, and it slows the
twist mode (axial inertia ``m r²/2``, a ~1 ms period at the contact step) to one the step resolves, as discrete elastic
rods treat twist as quasi-static; statics do not see it."""
_MAX_REST_TWIST = math.radians(25.0)
"""Largest rest twist (middle Euler angle) of a turned root left unrolled: ≥ 65° from the lock (:func:`_root_roll`)."""


def _min_rotation(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The smallest rotation taking unit vector ``a`` to unit vector ``b`` (discrete parallel transport)."""
    axis = np.cross(a, b)
    s = float(np.linalg.norm(axis))
    if s < 1e-14:
        return np.eye(3)
    k = axis / s
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    angle = math.atan2(s, float(a @ b))
    return np.eye(3) + math.sin(angle) * kx + (1.0 - math.cos(angle)) * kx @ kx


def chain_frames(points: np.ndarray, roll: float = 0.0) -> np.ndarray:
    """Twist-free material frames of a polyline's edges, ``(n_edges, 3, 3)``, columns = (tangent, d1, d2).

    The first frame's ``d1`` is horizontal (or along world x for a near-vertical first edge), turned by ``roll``
    [rad] about the first tangent; the others follow by parallel transport.
    """
    seg = np.diff(np.asarray(points, dtype=float), axis=0)
    tang = seg / np.linalg.norm(seg, axis=1)[:, None]
    t0 = tang[0]
    helper = np.array([0.0, 0.0, 1.0]) if abs(t0[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    d1 = np.cross(helper, t0)
    d1 /= np.linalg.norm(d1)
    d2 = np.cross(t0, d1)
    c, s = math.cos(roll), math.sin(roll)
    frames = np.empty((len(tang), 3, 3))
    frames[0] = np.column_stack([t0, c * d1 + s * d2, c * d2 - s * d1])
    for i in range(1, len(tang)):
        frames[i] = _min_rotation(tang[i - 1], tang[i]) @ frames[i - 1]
    return frames


def _root_rest_angles(
    frame: np.ndarray, turn: float, *, twist_first: bool = False
) -> tuple[float, float, float]:
    """Root hinge angles, in the root's hinge order (bend1 y, twist x, bend2 z; with ``twist_first`` twist x, bend1
    y, bend2 z), applied in that order in the body frame as MuJoCo composes a body's hinges, that turn the root frame
    ``frame`` by ``turn`` about the parent's z axis. The middle angle is the one whose ±90° is the lock."""
    if turn == 0.0:
        return (0.0, 0.0, 0.0)
    c, s = math.cos(turn), math.sin(turn)
    rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    local = frame.T @ rz @ frame
    a, b, d = Rotation.from_matrix(local).as_euler("XYZ" if twist_first else "YXZ")
    return (float(a), float(b), float(d))


def _root_roll(frame: np.ndarray, turn: float, *, twist_first: bool = False) -> float:
    """Roll [rad] of the root frame about its tangent that keeps the stress-free root far from gimbal lock.

    The root's rest angles are an Euler decomposition of the rest turn; the hinges are singular where the middle
    (twist) angle reaches ±90°. With ``d1`` horizontal, the twist at rest is 90° minus the first edge's tilt from
    the vertical, so wigs of low curliness rest closest to the lock, and a comb twisted held_out_wavy's root (rest
    −37°) past it (``docs/detangling.md``). Where the unrolled rest twist exceeds :data:`_MAX_REST_TWIST`, the roll
    that minimizes it is taken; elsewhere the frame stays as it is. The roll changes which Euler decomposition the
    root springs use, not the rest shape; their quadratic energy agrees with a rotational spring only near the
    reference, so frames that were far from the lock are left alone.
    """
    if turn == 0.0 or abs(_root_rest_angles(frame, turn, twist_first=twist_first)[1]) <= _MAX_REST_TWIST:
        return 0.0

    def badness(roll: float) -> float:
        a, mid, d = _root_rest_angles(frame @ _roll_matrix(roll), turn, twist_first=twist_first)
        return abs(mid) + 1e-3 * max(abs(a), abs(d))  # the middle angle first, then the outer ones

    rolls = np.linspace(0.0, math.pi, 181)
    return float(rolls[int(np.argmin([badness(r) for r in rolls]))])


def _roll_matrix(roll: float) -> np.ndarray:
    c, s = math.cos(roll), math.sin(roll)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _quat(mat: np.ndarray) -> list[float]:
    q = np.zeros(4)
    mujoco.mju_mat2Quat(q, np.ascontiguousarray(mat, dtype=float).reshape(9))
    return [float(v) for v in q]


def add_chain_rod(
    spec: mujoco.MjSpec,
    rod: RodSpec,
    *,
    parent: mujoco.MjsBody | str | None = None,
) -> mujoco.MjsBody:
    """Add one rod to ``spec`` as a chain of capsule bodies (see the module docstring).

    Creates (``k`` indexes the edges, ``0 … n−1``) bodies ``<name>_<k>`` at ``points[k]`` with capsule geoms
    ``<name>_<k>`` and hinges ``<name>_<k>_twist``, ``<name>_<k>_bend1``, ``<name>_<k>_bend2``; a free rod
    (``clamp=None``) gets a free joint ``<name>_0_free`` at its first vertex instead of the three root hinges.

    Parameters
    ----------
    spec : mujoco.MjSpec
        Any spec; call :func:`hairbrush_env.rods.configure_rod_options` on it as well.
    rod : RodSpec
        The rod; ``rod.points`` are expressed in the frame of ``parent``.
    parent : mujoco.MjsBody or str or None
        Body holding the clamped root; ``None`` = world. A moving parent receives the rod's reaction.

    Returns
    -------
    mujoco.MjsBody
        The root body ``<name>_0``.
    """
    pbody = resolve_body(spec, parent)
    pts = rod.points
    lengths = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    frames = chain_frames(pts)
    if clamped := rod.clamp == "start":
        frames = chain_frames(
            pts, roll=_root_roll(frames[0], rod.root_rest_turn, twist_first=rod.root_twist_first)
        )
    ei, gj = rod.bending_stiffness, rod.twisting_stiffness
    r = rod.radius
    friction = [rod.friction, *FRICTION_TORSION_ROLL]
    body = pbody
    root = None
    for k, ell in enumerate(lengths):
        if k == 0:
            body = body.add_body(name=f"{rod.name}_0", pos=[float(v) for v in pts[0]], quat=_quat(frames[0]))
            root = body
        else:
            rel = frames[k - 1].T @ frames[k]
            body = body.add_body(
                name=f"{rod.name}_{k}", pos=[float(lengths[k - 1]), 0.0, 0.0], quat=_quat(rel)
            )
        mass = rod.linear_density * float(ell) * rod.mass_scale
        armature = _ARMATURE * mass * float(ell) ** 2 / 3.0  # see _ARMATURE
        if rod.mass_scale != 1.0:
            body.gravcomp = 1.0 - 1.0 / rod.mass_scale
        body.explicitinertial = True
        body.mass = mass
        body.ipos = [0.5 * float(ell), 0.0, 0.0]
        transverse = mass * (3.0 * r**2 + float(ell) ** 2) / 12.0
        body.inertia = [max(v, _MIN_INERTIA) for v in (0.5 * mass * r**2, transverse, transverse)]
        if k == 0 and not clamped:
            body.add_freejoint(name=f"{rod.name}_0_free")
        else:
            lbar = 0.5 * float(ell) if k == 0 else 0.5 * float(lengths[k - 1] + ell)
            rest = (
                _root_rest_angles(frames[0], rod.root_rest_turn, twist_first=rod.root_twist_first)
                if k == 0
                else (0.0, 0.0, 0.0)
            )
            if spec.compiler.degree:  # springref is read in the spec's angle unit
                rest = tuple(math.degrees(a) for a in rest)
            axes = _ROOT_TWIST_FIRST_AXES if k == 0 and rod.root_twist_first else _JOINT_AXES
            for (label, axis), ref in zip(axes, rest, strict=True):
                stiffness = (gj if label == "twist" else ei) / lbar
                body.add_joint(
                    springref=float(ref),
                    name=f"{rod.name}_{k}_{label}",
                    type=mujoco.mjtJoint.mjJNT_HINGE,
                    axis=list(axis),
                    stiffness=[stiffness, 0.0, 0.0],
                    # ×√s keeps every mode's damping ratio under mass scaling (c = 2ζ√(k m))
                    damping=[
                        rod.damping * stiffness * math.sqrt(rod.mass_scale),
                        rod.quadratic_damping * stiffness,  # the ω|ω| term of MuJoCo's damping polynomial
                        0.0,
                    ],
                    armature=armature,
                )
        geom = body.add_geom(
            name=f"{rod.name}_{k}",
            type=mujoco.mjtGeom.mjGEOM_CAPSULE,
            fromto=[0.0, 0.0, 0.0, float(ell), 0.0, 0.0],
            size=[r, 0.0, 0.0],
            contype=rod.contype,
            conaffinity=rod.conaffinity,
            condim=rod.condim,
            friction=friction,
            margin=rod.margin,
            rgba=list(rod.rgba),
            group=rod.group,
        )
        geom.mass = 0.0  # the body's explicit inertia is the segment's
        if rod.contact_solref is not None:
            geom.solref = [float(v) for v in rod.contact_solref]
        if rod.contact_solimp is not None:
            geom.solimp = [float(v) for v in rod.contact_solimp]
    if not rod.selfcollide and (rod.contype & rod.conaffinity):
        # Neighbours are parent and child (MuJoCo filters those); exclude the rest of the rod's own segments, as a
        # flex without self-collision does.
        n = len(lengths)
        for a in range(n):
            for b in range(a + 2, n):
                spec.add_exclude(bodyname1=f"{rod.name}_{a}", bodyname2=f"{rod.name}_{b}")
    assert root is not None
    return root
