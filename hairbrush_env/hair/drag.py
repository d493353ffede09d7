"""Quadratic drag of the surrounding medium on chain strands, applied explicitly as body forces.

Mass scaling (:data:`hairbrush_env.hair.MASS_SCALE`) gives every strand segment ten times its inertia at its real
weight, so a curl springing back off a tine carries ten times the momentum of a real one and swings into the
neighbouring groups' curls. A drag on the segments' *translation* takes that momentum out; the joint damping
(``WigConfig.damping``) acts on their bending only, and any of it strong enough to keep the groups apart also
makes the brushing force grow with the pull speed (docs/detangling.md, *What makes v1's force depend on the pull
speed*). Each segment of length ``ℓ`` and diameter ``d`` feels ``F = −½ ρ ℓ d |v| v`` at its centre of mass, ``v``
its velocity, ``ρ`` = ``WigConfig.drag_density``. MuJoCo's own fluid model (``mjOption.density``) does the same
with implicit derivatives, which under the ``discrete`` integrator enter the effective inertia body by body and
cost 2.5× a brushing step; here the force is computed from the velocities of the last forward pass (the start of
the step before: one step late) and written to ``mjData.xfrc_applied``: 0.14 ms a step on the default wig, ~3 % of
a brushing step. It stays stable while ``ρ ℓ d |v| Δt / m ≪ 1`` (0.03 per m/s for the default wisp at ``ρ = 1000``
and the 1 ms step).

With a free speed ``v₀ > 0`` (``WigConfig.drag_free_speed``) the drag acts only on the part of a segment's speed above
it, ``F = −½ ρ ℓ d (|v| − v₀)² v̂`` (none below ``v₀``): a dead zone. Put above the brush's fastest pull, it leaves the
pull itself alone, so the brushing force does not grow with the pull speed as ``v²`` (Fig. 3.8), and still damps a
curl whipping off a tine, which moves several times faster than the brush.

With ``normal_only`` (``WigConfig.drag_normal_only``) the drag acts on the velocity across each segment only,
``v_n = v − (v·t) t`` with ``t`` the segment's axis: the cross-flow principle, by which a slender cylinder's pressure
drag depends on the normal component of the flow alone (its skin friction along the axis is one to two orders
smaller and left out). A curl that lets a tine through turns about its own helix axis, and its wire then moves
nearly along itself (the wire's angle to the turning direction is the lead angle λ, tan λ = P / (2π R)), so it
feels ``sin² λ`` of the drag of the whole velocity: 0.09 for curly, 0.04 for coily.
"""

from __future__ import annotations

import mujoco
import numpy as np

from .config import WigConfig

__all__ = ["StrandDrag"]


class StrandDrag:
    """Drag ``−½ ρ ℓ d |v| v`` on the centre of mass of every capsule body in ``bodies``.

    Parameters
    ----------
    model : mujoco.MjModel
        Model holding the strands (chain rods: one capsule geom per body).
    bodies : array of int
        Ids of the strand segment bodies.
    density : float
        Density of the medium ``ρ`` [kg/m³] (> 0).
    free_speed : float
        Dead zone ``v₀`` [m/s] (≥ 0): the drag acts on ``|v| − v₀`` only; 0 = the plain ``−½ ρ ℓ d |v| v``.
    normal_only : bool
        Act on the velocity component normal to each segment's axis only (``v`` above is then ``v_n``).
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        bodies: np.ndarray,
        density: float,
        free_speed: float = 0.0,
        *,
        normal_only: bool = False,
    ) -> None:
        if not (np.isfinite(density) and density > 0.0):
            raise ValueError(f"drag density must be a finite number > 0, got {density!r}")
        if not (np.isfinite(free_speed) and free_speed >= 0.0):
            raise ValueError(f"drag free speed must be a finite number >= 0, got {free_speed!r}")
        self.free_speed = float(free_speed)
        self.normal_only = bool(normal_only)
        self.bodies = np.asarray(bodies, dtype=int)
        geoms = []
        for b in self.bodies:
            ids = np.flatnonzero(
                (model.geom_bodyid == b) & (model.geom_type == int(mujoco.mjtGeom.mjGEOM_CAPSULE))
            )
            if ids.size == 0:
                raise ValueError(f"drag: body {b} has no capsule geom (drag needs chain strands)")
            geoms.append(ids[0])
        geoms = np.array(geoms)
        self._geoms = geoms
        side_area = (2.0 * model.geom_size[geoms, 1]) * (2.0 * model.geom_size[geoms, 0])
        self.coefficient = 0.5 * float(density) * side_area
        self._root = model.body_rootid[self.bodies]

    @classmethod
    def of_wig(cls, model: mujoco.MjModel, bodies: np.ndarray, wig: WigConfig) -> StrandDrag | None:
        """The drag ``wig`` asks for (``drag_density``, ``drag_free_speed``) on ``bodies``; ``None`` if it has none."""
        if not wig.drag_density:
            return None
        return cls(model, bodies, wig.drag_density, wig.drag_free_speed, normal_only=wig.drag_normal_only)

    def velocity(self, data: mujoco.MjData) -> np.ndarray:
        """World linear velocity of each body's centre of mass (from ``cvel``, as of the last forward pass)."""
        cvel = data.cvel[self.bodies]
        arm = data.xipos[self.bodies] - data.subtree_com[self._root]
        return cvel[:, 3:] + np.cross(cvel[:, :3], arm)

    def axes(self, data: mujoco.MjData) -> np.ndarray:
        """World unit axis of each body's capsule (its local z)."""
        return data.geom_xmat[self._geoms][:, [2, 5, 8]]

    def apply(self, data: mujoco.MjData) -> None:
        """Write the drag of the current velocities to ``data.xfrc_applied`` (forces; torques left as they are)."""
        v = self.velocity(data)
        if self.normal_only:
            t = self.axes(data)
            v = v - np.einsum("ij,ij->i", v, t)[:, None] * t
        speed = np.linalg.norm(v, axis=1)
        if self.free_speed == 0.0:  # kept as it was: v2-v8 stay bit for bit what they were (v9 takes it too)
            data.xfrc_applied[self.bodies, :3] = -(self.coefficient * speed)[:, None] * v
            return
        excess = np.maximum(speed - self.free_speed, 0.0)
        unit = v / np.maximum(speed, 1e-12)[:, None]
        data.xfrc_applied[self.bodies, :3] = -(self.coefficient * excess**2)[:, None] * unit

    def clear(self, data: mujoco.MjData) -> None:
        """Remove the drag forces from ``data.xfrc_applied``."""
        data.xfrc_applied[self.bodies, :3] = 0.0
