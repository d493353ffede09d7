"""The MuJoCo model of a rod pile: :class:`SimParams` (physical and numerical parameters) and :class:`Pile` (a
compiled model of the rods, the container and optionally a piston or glued layers), shared by generation
(:mod:`.generate`) and the mechanical tests (:mod:`.mechanics`); :func:`poses_from_endpoints` converts rod end
points to MuJoCo poses.

Model (MuJoCo, SI units)
------------------------
Rods are rigid steel capsules (free bodies) of total length ``L`` and diameter ``d`` (cylinder part ``L − d``), so
the aspect ratio is α = L/d as in the thesis. The container is a ring of thin boxes plus a floor box, all on one
mocap body so it can be shaken and tilted (§4.5.1 "jostled by a motor"). Contacts: Coulomb friction μ (steel,
default 0.4), critically damped soft contacts whose time constant is ``2·dt``.

Why the time step scales with √(d/g): MuJoCo contacts are soft, and a rod resting on another sinks by ≈ 0.05 g τ²
(τ = contact time constant). With the default τ = 20 ms that is ~0.2 mm — comparable to a 0.5 mm rod, so thin rods
would pass through each other. We use dt = 0.1 √(d/g) and τ = 2 dt, which keeps steady penetrations at ~1 % of d
and the number of steps per rod length fallen independent of the rod size (dynamic similarity: only α and the
container/rod ratio matter).

Other model choices (each changes dynamics only, not the statics of the final pile; those of the deposition —
batches, ``freeze_depth``, placement — are described in :mod:`.generate`):

* the axial moment of inertia is raised to 5 % of the transverse one: a thin rod's true axial inertia (m d²/8) makes
  the spin DOF stiff enough to blow up the integrator at any practical step;
* while rods are deposited and jostled they feel linear drag with terminal speed 0.25 d per step
  (``terminal_speed``; plus a weak angular drag), so no rod tunnels through another; drag is switched off for the
  mechanical tests.

Known model limitations: MuJoCo's soft friction lets loaded frictional contacts creep slowly. A "settled" 300-rod
pile (α = 76) run for 1 200 more steps without drag kept moving at ~0.1 √(g d) and its fastest rod end drifted
3.9 d (2.7 d with ``noslip_iterations = 10``), while ⟨|cos θ|⟩ changed by < 0.001
(``python scripts/benchmark_rodpile.py --skip-fields --skip-generate --solver-check PILE``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .packing import GRAVITY, STEEL_DENSITY

__all__ = [
    "Pile",
    "SimParams",
    "poses_from_endpoints",
]


@dataclass(frozen=True)
class SimParams:
    """Physical and numerical parameters shared by generation and mechanical tests (see module docstring)."""

    length: float
    diameter: float
    container_diameter: float
    friction: float = 0.4
    density: float = STEEL_DENSITY
    dt_factor: float = 0.1  # dt = dt_factor · √(d/g)
    contact_tol: float = 0.02  # rod–rod "contact" if surfaces are closer than contact_tol · d
    wall_friction: float | None = None  # None → friction
    terminal_speed: float = 0.25  # deposition drag: terminal speed in rod diameters per time step

    @property
    def dt(self) -> float:
        return self.dt_factor * math.sqrt(self.diameter / GRAVITY)

    @property
    def mass(self) -> float:
        return self.density * math.pi * self.diameter**2 / 4 * self.length

    @property
    def inertia(self) -> tuple[float, float, float]:
        it = self.mass * self.length**2 / 12
        return it, it, max(self.mass * self.diameter**2 / 8, 0.05 * it)


class Pile:
    """A compiled MuJoCo model of the rods (free or glued), the container and optionally a piston."""

    def __init__(
        self,
        sp: SimParams,
        pos: np.ndarray,
        quat: np.ndarray,
        *,
        piston_z: float | None = None,
        glued_bottom: np.ndarray | None = None,
        glued_top: np.ndarray | None = None,
        walls: bool = True,
    ):
        import mujoco

        self.mj = mujoco
        self.sp = sp
        n = len(pos)
        glued_bottom = np.zeros(n, bool) if glued_bottom is None else glued_bottom
        glued_top = np.zeros(n, bool) if glued_top is None else glued_top
        spec = mujoco.MjSpec()
        spec.modelname = "rod_pile"
        opt = spec.option
        opt.timestep = sp.dt
        opt.gravity = [0.0, 0.0, -GRAVITY]
        # implicitfast: the deposition drag (dof damping) is integrated implicitly, so it never limits the step.
        opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
        # PGS: Newton factorizes a dense nv×nv Hessian (1000 rods → 6000 dofs) and CG with a small iteration cap
        # let rods sink through the floor; PGS with a fixed budget is the standard granular-media choice.
        opt.solver = mujoco.mjtSolver.mjSOL_PGS
        opt.iterations = 30
        opt.tolerance = 1e-7
        tau = 2 * sp.dt
        d = sp.diameter
        tol = sp.contact_tol * d
        fr = [sp.friction, 0.005, 0.0001]
        wfr = [sp.friction if sp.wall_friction is None else sp.wall_friction, 0.005, 0.0001]
        common = dict(
            solref=[tau, 1.0], margin=0.0, gap=tol
        )  # detect near-contacts (gap), push only when touching
        r = sp.container_diameter / 2
        wall_h = 4 * sp.length
        t = 0.2 * sp.length
        cont = spec.worldbody.add_body(name="container")  # static
        nwall = 64 if walls else 0
        # priority 1: MuJoCo otherwise gives a contact the larger of the two geoms' friction, so the rods' μ would
        # override a lower wall friction
        for k in range(nwall):
            a = 2 * math.pi * k / nwall
            cont.add_geom(
                name=f"wall{k}", type=mujoco.mjtGeom.mjGEOM_BOX,
                size=[t / 2, r * math.tan(math.pi / nwall) * 1.05, wall_h / 2],
                pos=[(r + t / 2) * math.cos(a), (r + t / 2) * math.sin(a), wall_h / 2],
                quat=[math.cos(a / 2), 0, 0, math.sin(a / 2)], friction=wfr, priority=1, **common,
            )  # fmt: skip
        cont.add_geom(name="floor", type=mujoco.mjtGeom.mjGEOM_BOX, size=[1.2 * r + t, 1.2 * r + t, t / 2],
                      pos=[0, 0, -t / 2], friction=fr, **common)  # fmt: skip
        half = (sp.length - d) / 2
        self.top_body = None
        if glued_top.any():
            self.top_body = spec.worldbody.add_body(name="top", mocap=True)
        self.piston_z0 = piston_z
        if piston_z is not None:
            pist = spec.worldbody.add_body(name="piston", mocap=True, pos=[0, 0, piston_z])
            # a box wider than the container: both are mocap (static) so they never collide with each other
            pist.add_geom(name="piston", type=mujoco.mjtGeom.mjGEOM_BOX, size=[1.2 * r, 1.2 * r, t / 2],
                          pos=[0, 0, t / 2], friction=fr, **common)  # fmt: skip
        mass = sp.mass
        inertia = sp.inertia
        self.free = np.flatnonzero(~glued_bottom & ~glued_top)
        self.rod_of_geom: dict[int, int] = {}
        geom_names = []
        for i in range(n):
            gname = f"rod{i}"
            q = [float(x) for x in quat[i]]
            if glued_bottom[i]:
                spec.worldbody.add_geom(name=gname, type=mujoco.mjtGeom.mjGEOM_CAPSULE, size=[d / 2, half, 0],
                                        pos=[float(x) for x in pos[i]], quat=q, friction=fr, **common)  # fmt: skip
            elif glued_top[i]:
                self.top_body.add_geom(name=gname, type=mujoco.mjtGeom.mjGEOM_CAPSULE, size=[d / 2, half, 0],
                                       pos=[float(x) for x in pos[i]], quat=q, friction=fr, **common)  # fmt: skip
            else:
                b = spec.worldbody.add_body(name=f"b{i}", pos=[float(x) for x in pos[i]], quat=q)
                b.add_freejoint()
                b.explicitinertial = True
                # ipos/iquat must be set explicitly: left unset they do not default to the body frame
                b.mass, b.inertia, b.ipos, b.iquat = mass, list(inertia), [0, 0, 0], [1, 0, 0, 0]
                b.add_geom(name=gname, type=mujoco.mjtGeom.mjGEOM_CAPSULE, size=[d / 2, half, 0], friction=fr,
                           **common)  # fmt: skip
            geom_names.append(gname)
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        m = self.model
        self.geom_rod = np.full(m.ngeom, -1, dtype=np.int64)
        for i, gname in enumerate(geom_names):
            self.geom_rod[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, gname)] = i
        self.floor_geom = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "floor")
        self.piston_geom = (
            mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "piston") if piston_z is not None else -1
        )
        self.body_of_rod = np.full(n, -1, dtype=np.int64)
        for i in self.free:
            self.body_of_rod[i] = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, f"b{i}")
        self.n = n
        self.pos0, self.quat0 = pos.copy(), quat.copy()
        self.glued_bottom, self.glued_top = glued_bottom, glued_top
        self.set_drag(True)
        mujoco.mj_forward(m, self.data)

    # -- state
    def set_drag(self, on: bool) -> None:
        """Deposition drag: terminal speed ``terminal_speed`` d per step (default 0.25); angular relaxation 50 ms."""
        sp = self.sp
        dof = self.model.dof_damping.reshape(-1, 6) if self.model.nv else np.zeros((0, 6))
        vt = sp.terminal_speed * sp.diameter / sp.dt
        dof[:, :3] = sp.mass * GRAVITY / vt if on else 0.0
        dof[:, 3:] = sp.inertia[0] / 0.05 if on else 0.0

    def poses(self) -> tuple[np.ndarray, np.ndarray]:
        """Centers and orientation quaternions of all rods (glued rods in world coordinates)."""
        pos, quat = self.pos0.copy(), self.quat0.copy()
        d = self.data
        fb = self.body_of_rod[self.free]
        pos[self.free] = d.xpos[fb]
        quat[self.free] = d.xquat[fb]
        if self.top_body is not None:
            top = np.flatnonzero(self.glued_top)
            for i in top:
                g = np.flatnonzero(self.geom_rod == i)[0]
                pos[i] = d.geom_xpos[g]
                q = np.empty(4)
                self.mj.mju_mat2Quat(q, d.geom_xmat[g])
                quat[i] = q
        return pos, quat

    def endpoints(self) -> np.ndarray:
        pos, quat = self.poses()
        return _endpoints(pos, quat, self.sp.length)

    def max_speed(self) -> float:
        if self.model.nv == 0:
            return 0.0
        v = self.data.qvel.reshape(-1, 6)
        # free-joint angular velocity is in the body frame: x, y tumble the rod (tips move ω L/2), z spins it
        spin = np.abs(v[:, 5]) * self.sp.diameter / 2
        tumble = np.hypot(v[:, 3], v[:, 4]) * self.sp.length / 2
        return float((np.linalg.norm(v[:, :3], axis=1) + tumble + spin).max(initial=0.0))

    def step(self, nsteps: int = 1) -> None:
        self.mj.mj_step(self.model, self.data, nsteps)

    def settle(self, max_time: float, v_tol: float | None = None, min_time: float = 0.0) -> float:
        """Step until every rod point moves slower than ``v_tol`` (default 0.05 √(g d)) or ``max_time`` passes."""
        sp = self.sp
        v_tol = 0.05 * math.sqrt(GRAVITY * sp.diameter) if v_tol is None else v_tol
        chunk = 25
        t = 0.0
        while t < max_time:
            self.step(chunk)
            t += chunk * sp.dt
            if t >= min_time and self.max_speed() < v_tol:
                break
        return t

    # -- contacts
    def contact_pairs(self) -> np.ndarray:
        """Unique rod–rod pairs whose surfaces are closer than ``contact_tol · d`` (``(k, 2)`` rod ids)."""
        d = self.data
        nc = d.ncon
        if nc == 0:
            return np.zeros((0, 2), dtype=np.int64)
        g1 = d.contact.geom1[:nc]
        g2 = d.contact.geom2[:nc]
        dist = d.contact.dist[:nc]
        r1, r2 = self.geom_rod[g1], self.geom_rod[g2]
        ok = (r1 >= 0) & (r2 >= 0) & (dist < self.sp.contact_tol * self.sp.diameter)
        pairs = np.sort(np.stack([r1[ok], r2[ok]], axis=1), axis=1)
        return np.unique(pairs, axis=0) if len(pairs) else pairs

    def geom_forces(self, geoms: np.ndarray) -> np.ndarray:
        """Total world-frame contact force exerted ON the geoms in the boolean mask ``geoms`` (by anything else)."""
        mj, d = self.mj, self.data
        nc = d.ncon
        total = np.zeros(3)
        if nc == 0:
            return total
        g1 = d.contact.geom1[:nc]
        g2 = d.contact.geom2[:nc]
        in1, in2 = geoms[g1], geoms[g2]
        f6 = np.zeros(6)
        for k in np.flatnonzero(in1 ^ in2):
            if d.contact.efc_address[k] < 0:
                continue
            mj.mj_contactForce(self.model, d, int(k), f6)
            fw = d.contact.frame[k].reshape(3, 3).T @ f6[:3]
            # the contact force acts on geom2 along +normal (normal points geom1 → geom2), on geom1 opposite
            total += fw if in2[k] else -fw
        return total


def _endpoints(pos: np.ndarray, quat: np.ndarray, length: float) -> np.ndarray:
    w, x, y, z = quat.T
    # third column of the rotation matrix = capsule axis
    ax = np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], axis=1)
    return np.stack([pos - ax * length / 2, pos + ax * length / 2], axis=1)


def poses_from_endpoints(ep: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    import mujoco

    pos = ep.mean(axis=1)
    u = ep[:, 1] - ep[:, 0]
    length = float(np.linalg.norm(u, axis=1).mean())
    u = u / np.linalg.norm(u, axis=1, keepdims=True)
    quat = np.zeros((len(ep), 4))
    for i, ui in enumerate(u):
        mujoco.mju_quatZ2Vec(quat[i], ui)
    return pos, quat, length
