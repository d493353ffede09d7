"""The brushing scene (thesis §3.4, Fig. 3.5): arm + sensorized brush + head mount + wig + fixed webcam.

* :mod:`hairbrush_env.scene_build` assembles it (:class:`SceneConfig`, :func:`build_scene`, :func:`wave1_scene`,
  re-exported here): arm, brush, head on its variable-height mount, wig and webcam in one :class:`mujoco.MjSpec`.
* :class:`BrushingSim` compiles the scene **once**, owns model/data, the Cartesian controller and the 10 Hz load
  cell, restores cached pre-brushed states on :meth:`BrushingSim.reset` and runs thesis Algorithm 1's inner loop
  (:meth:`BrushingSim.stroke`) or 10 Hz velocity control (:meth:`BrushingSim.step_velocity`).

Stroke (Algorithm 1, inner loop): the brush waits level beside the hair (bristle tips 15 mm in front of the
wig) at the start height ``z_bottom + b_l·L_b`` (``b_l`` = normalized brush length measured up from the free ends,
``L_b`` = brushable length: from the settled free ends up to the highest start the brush head allows, 8 mm below
the roots with the default comb, :attr:`BrushingSim.brushable_length`), the load cell is tared, the brush is pushed
in to the brushing depth, then pulled straight down at constant speed until the whole brush is below every strand,
wherever it dragged them (down to ``SceneConfig.pull_floor_z``); the load cell is read at 10 Hz and the stroke stops
as soon as a reading reaches the abort force, if the policy set one (``BrushingSim.stroke(abort_force=...)``). With
``SceneConfig.read_in_hair`` (HairBrush-v10) only readings taken while the brush is above the bottom of the hair count,
as in Algorithm 1; the pull goes on all the same.
The speed is 0.1 m/s by default:
the thesis moved its arm at a fixed, slow speed and found the maximum force nearly speed-independent (Fig. 3.8).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass

import mujoco
import numpy as np

from . import hair as hairmod
from .arm_control import CartesianController, plan_stroke
from .constants import PAIN_THRESHOLD_N
from .hair.drag import StrandDrag
from .parting import pairs_parted
from .scene_build import (
    BRUSH_TCP,
    HEAD_POS,
    SCENE_TINE_PREFIX,
    TOOL_CONTACT_MARGIN,
    WORKSPACE_Z,
    SceneConfig,
    assemble_scene,
    build_scene,
    wave1_scene,
)
from .sensors import LoadCell

__all__ = [
    "BRUSH_TCP",
    "HEAD_POS",
    "MAX_STEP_SPLIT",
    "MAX_STROKE_Y",
    "PAIN_THRESHOLD",
    "TOOL_CONTACT_MARGIN",
    "BrushingSim",
    "SceneConfig",
    "StrokeResult",
    "VelocityStep",
    "build_scene",
    "wave1_scene",
]

PAIN_THRESHOLD = PAIN_THRESHOLD_N
"""``F_T`` [N] (thesis §3.5: pain threshold ≈ 10 N; :data:`hairbrush_env.constants.PAIN_THRESHOLD_N`)."""

#: Most substeps a speed-limited contact step is split into (SceneConfig.max_step_travel).
MAX_STEP_SPLIT = 16
_HEAD_PLATE = "arm/brush/head_plate"  # passes under the scalp patch: its half height limits the stroke start
_RETRACT_GAP = 0.015  # tine tips this far in front of the hair before the brush moves beside it
_QUIET_SECONDS = 0.3  # end of the pre-brushed settle, at the hair's own damping (BrushingSim.settled_state)
_STEADY_SECONDS, _STEADY_DAMPING = 1.0, 30.0  # hand-steadied rest after the shake (BrushingSim.settled_state)
# Free-space stepping (BrushingSim._needs_fine_step): the brush's box (BrushingSim.tool_box) and the box
# of the hair's centerlines at least the contact reach (wisp radius + both margins, which MuJoCo adds) plus this far
# apart [m] — a strand would have to move 0.3 m/s towards the brush to meet it within one 10 ms control period — and
# no strand point moving more than half a wisp radius per control period (4 cm/s).
_FREE_CLEARANCE = 0.003
_QUIET_MOTION = 4e-4
MAX_STROKE_Y = 0.03
"""Largest sideways offset of a stroke [m] (``BrushingSim.stroke(y=...)``): more than a comb's tine pitch."""


@dataclass(frozen=True)
class StrokeResult:
    """Outcome of one brush stroke.

    Attributes
    ----------
    force_trace : tuple of np.ndarray
        ``(times, forces)`` of the 10 Hz load-cell samples during the pull (time from the start of the pull [s],
        brushing force [N], positive = hair resisting).
    max_force : float
        Largest brushing force the stroke read (0 if none): every sample of the pull, or with
        ``SceneConfig.read_in_hair`` the first ``samples_read``, taken while the brush was above the bottom of the hair.
    aborted : bool
        A sample reached ``abort_force`` and the stroke was stopped.
    sim_time : float
        Simulated duration of the whole stroke (approach, insertion, pull, retraction) [s].
    diverged : bool
        The simulation produced NaN, warnings or runaway speeds (state is then unusable until :meth:`reset`).
    start_height : float
        World z of the TCP at the start of the pull.
    start_fraction : float
        Requested normalized start height ``b_l``.
    pull_max_force : float
        Largest sample of the whole pull (equal to ``max_force`` unless the stroke read only part of it).
    samples_read : int
        How many of the trace's samples (from its start) the stroke read for ``max_force`` and the abort.
    """

    force_trace: tuple[np.ndarray, np.ndarray]
    max_force: float
    aborted: bool
    sim_time: float
    diverged: bool
    start_height: float
    start_fraction: float
    pull_max_force: float = 0.0
    samples_read: int = 0


@dataclass(frozen=True)
class VelocityStep:
    """Outcome of :meth:`BrushingSim.step_velocity`.

    Attributes
    ----------
    force : float
        Latest 10 Hz brushing-force sample [N] (NaN if no sample fell into the interval).
    max_force : float
        Largest sample in the interval (NaN if none).
    position : np.ndarray
        TCP position at the end [m].
    diverged : bool
    """

    force: float
    max_force: float
    position: np.ndarray
    diverged: bool


class BrushingSim:
    """One compiled brushing scene with resettable pre-brushed wig states.

    Parameters
    ----------
    config : SceneConfig, optional
    cache : StateCache, optional
        Shared cache of settled states (pass one instance to several sims, or one with a ``directory`` to keep
        states across processes). Default: a fresh in-memory cache.
    seed : int
        Seed of the load-cell noise generator (strokes may pass their own ``rng``).
    """

    def __init__(
        self,
        config: SceneConfig | None = None,
        *,
        cache: hairmod.StateCache | None = None,
        seed: int = 0,
    ) -> None:
        self.config = config if config is not None else SceneConfig()
        self.wig = self.config.wig_config
        self.spec, info = assemble_scene(self.config)
        self.layout = info.layout
        self.root_origin = info.root_origin
        self.head_offset = info.head_offset
        self.model = self.spec.compile()
        self.data = mujoco.MjData(self.model)
        self.model_hash = hairmod.StateCache.model_hash(self.model)
        self.cache = cache if cache is not None else hairmod.StateCache()
        self.controller = CartesianController(self.model, site=BRUSH_TCP)
        self.load_cell = LoadCell(
            self.model, self.config.load_cell, rng=np.random.default_rng(seed), data=self.data
        )
        self.entanglement_meter = hairmod.Entanglement(self.model, self.layout)
        self._tcp_site = self.controller.site_id
        self._n_sub = max(1, round(self.config.control_dt / self.config.timestep))
        self._n_sub_contact = max(1, round(self.config.control_dt / self.config.contact_timestep))
        self._dt_contact = self.config.control_dt / self._n_sub_contact
        # Solver of the contact step: what the rods need (rods.configure_rod_options); settable for benchmarks.
        self.contact_solver = mujoco.mjtSolver(int(self.model.opt.solver))
        self.hair_bodies = np.concatenate([v.bodies for v in self.entanglement_meter.views])
        self._hair_dofs = np.flatnonzero(np.isin(self.model.dof_bodyid, self.hair_bodies))
        # Drag of the medium on the strands while they are brushed (WigConfig.drag_density; not in the preparation,
        # so the pre-brushed wigs are those without it).
        self._drag = StrandDrag.of_wig(self.model, self.hair_bodies, self.wig)
        # Divergence watch: every dof except the flex rods' twist hinges, whose tiny polar inertia lets them spin
        # at hundreds of rad/s in normal operation (measured: 85 rad/s during a plain pull).
        twist = {f"{n}_twist" for n in self.layout.names} if self.wig.rod_kind == "flex" else set()
        self._watch_dofs = np.array(
            [
                self.model.jnt_dofadr[j]
                for j in range(self.model.njnt)
                if self.model.joint(j).name.split("_twist")[0] + "_twist" not in twist
            ],
            dtype=int,
        )
        self._renderer: mujoco.Renderer | None = None
        self._observers: list = []
        self._step_observers: list = []
        self.n_steps = 0  # physics steps taken by strokes and velocity control (for benchmarks)
        self._bristle_geoms = np.array(
            [g for g in range(self.model.ngeom) if self.model.geom(g).name.startswith(SCENE_TINE_PREFIX)],
            dtype=int,
        )
        self.diverged = False

        # Wig geometry in the world: x range of the curtain (for the retracted brush) and the stroke depth.
        lo, hi = self.layout.extent
        self.hair_x_range = (float(self.root_origin[0] + lo[0]), float(self.root_origin[0] + hi[0]))
        self.depth_x = float(self.root_origin[0] + self.config.brush_depth)
        self.brush = self.config.brush_config
        self.retract_x = self.hair_x_range[0] - _RETRACT_GAP - 0.5 * self.brush.tine_length
        span = 0.5 * (self.brush.columns - 1) * self.brush.column_pitch + self.brush.tine_radius
        reach = max(-float(lo[1]), float(hi[1]))
        if reach > span + 0.01:
            warnings.warn(
                f"SceneConfig.brush: its tines span y ±{span:.3f} m of a wig that spans ±{reach:.3f} m, so the outer "
                f"groups are never combed; give the brush about {math.ceil(reach / self.brush.column_pitch) * 2 + 1} "
                "columns (BrushConfig.columns) or the wig more group_rows",
                stacklevel=2,
            )
        plate = self.model.geom(_HEAD_PLATE).id
        self.top_z = (
            float(self.root_origin[2]) - float(self.model.geom_size[plate, 2]) - self.config.scalp_clearance
        )
        self._tool_geoms = np.append(self._bristle_geoms, plate)
        self._is_hair = self.model.geom_group == hairmod.HAIR_GEOM_GROUP
        # Surface contact starts at the sum of the two geoms' margins (MuJoCo 4.0.1 adds them), i.e. this far
        # from a strand's centerline.
        self._contact_reach = self.wig.strand_radius + hairmod.CONTACT_MARGIN + TOOL_CONTACT_MARGIN
        self._last_curves: np.ndarray | None = None
        # Fastest strand point's speed over the last contact step [m/s] (SceneConfig.max_step_travel).
        self._step_speed = 0.0
        self.park = np.array([self.retract_x, 0.0, self.config.free_end_z - 0.02])

        # Base state: hair at rest (rest shape = qpos0), arm holding the park pose.
        mujoco.mj_resetData(self.model, self.data)
        self._q = self.controller.solve(self.data, self.park)
        self.data.qpos[self.controller.qpos_adr] = self._q
        self.controller.apply(self.data, self._q)
        mujoco.mj_forward(self.model, self.data)
        self._base_state = hairmod.get_state(self.model, self.data)
        self._target = self.park.copy()
        self.hair_bottom = self.config.free_end_z
        self.hair_top = float(self.root_origin[2])
        self._warn0 = 0

    # --------------------------------------------------------------------------------------- properties
    @property
    def curliness_true(self) -> float:
        """Ground-truth ``R/P`` of the wig (thesis eq. 3.1)."""
        return float(self.wig.curliness)

    @property
    def hanging_length(self) -> float:
        """Vertical extent root → lowest free end measured at the last reset [m]."""
        return self.hair_top - self.hair_bottom

    @property
    def brushable_length(self) -> float:
        """Free ends → highest stroke start the brush head allows below the scalp (``top_z``) [m].

        The normalized brush length ``b_l`` is a fraction of this span, so ``b_l = 1`` is the longest stroke the
        brush can make. Measured against the whole hanging length instead, every ``b_l`` above
        ``1 − clearance/L`` starts at the same clamped height: for tight_curl (L ≈ 6.4 cm) b_l = 0.67 and 1 began
        only 2–7 mm apart and their forces differed 2× by where the bristles caught a curl (docs/wigs.md).
        """
        return max(self.top_z - self.hair_bottom, 0.0)

    def start_height(self, b_l: float) -> float:
        """World height of the TCP at the start of a stroke with normalized brush length ``b_l``."""
        return self.hair_bottom + float(b_l) * self.brushable_length

    def brush_position(self) -> np.ndarray:
        """World position of the brush TCP (mid-bristle)."""
        return self.data.site_xpos[self._tcp_site].copy()

    @property
    def pull_end_z(self) -> float:
        """Lowest TCP height of a pull [m]: the pull floor (``SceneConfig.pull_floor_z``), or without one 1 cm below
        the brush's clearance of the rest free ends (at the workspace's bottom at the lowest)."""
        floor = self.config.pull_floor_z
        if floor is not None:
            return float(floor)
        return max(self.hair_bottom - self.brush.half_height - 0.01, WORKSPACE_Z[0])

    def brush_below_hair(self) -> bool:
        """Whether the whole brush (with the contact reach) is below every strand: a pull has gone through."""
        clear = self.brush.half_height + self._contact_reach + _FREE_CLEARANCE
        return bool(float(self.hair_curve_array()[..., 2].min()) > self.brush_position()[2] + clear)

    def entanglement(self) -> float:
        """``Σ |open Lk|`` over the entwined pairs (ground truth, :class:`hairbrush_env.hair.Entanglement`)."""
        return self.entanglement_meter(self.data)

    def pair_links(self) -> np.ndarray:
        """Signed open-curve link of each entwined pair (``layout.pairs``)."""
        return self.entanglement_meter.pair_links(self.data)

    def pairs_parted(self) -> np.ndarray:
        """Whether a tine of the brush, where it is now, lies between each entwined pair's two strands at the brush's
        height (:func:`hairbrush_env.parting.pairs_parted`, in ``layout.pairs`` order): the pairs a pull from here
        can comb out."""
        tcp = self.brush_position()
        b = self.brush
        tines_y = (np.arange(b.columns) - 0.5 * (b.columns - 1)) * b.column_pitch + tcp[1]
        room = b.tine_radius + self.wig.strand_radius
        return pairs_parted(
            self.hair_curve_array(), self.entanglement_meter.pairs, tines_y, float(tcp[2]), room
        )

    def hair_curves(self) -> list[np.ndarray]:
        """Current centerlines of all strands (world)."""
        return self.entanglement_meter.curves(self.data)

    def hair_curve_array(self) -> np.ndarray:
        """Current centerlines of all strands stacked as ``(n_strands, n_points, 3)`` (world)."""
        return self.entanglement_meter.curve_array(self.data)

    @property
    def bristle_radius(self) -> float:
        """Radius of the thinnest bristle capsule [m]."""
        return float(self.model.geom_size[self._bristle_geoms, 0].min())

    def bristle_segments(self) -> np.ndarray:
        """Current axis segments of the brush's bristle capsules, ``(n_bristles, 2, 3)`` (world)."""
        m, d = self.model, self.data
        g = self._bristle_geoms
        half_axis = d.geom_xmat[g].reshape(-1, 3, 3)[:, :, 2] * m.geom_size[g, 1][:, None]
        return np.stack([d.geom_xpos[g] - half_axis, d.geom_xpos[g] + half_axis], axis=1)

    # --------------------------------------------------------------------------------------- reset
    def settled_state(self, seed: int) -> np.ndarray:
        """The pre-brushed state for ``seed`` (from the cache, or prepared now and cached)."""
        state = self.cache.get(self.wig, seed, self.model_hash)
        if state is None:
            state = self.prepare(seed)
            self.cache.put(self.wig, seed, self.model_hash, state)
        return state

    def prepare(self, seed: int, *, contact_step: bool = True) -> np.ndarray:
        """Run the pre-brushed preparation for ``seed`` from the built wig, uncached, and return its state (step
        observers see every step).

        The whole preparation runs at the contact step. ``contact_step=False`` runs it at the 10 ms free step, as it
        was before the correction, for probes only: there the prestressed pairs passed through each other as soon as
        they were released (24 crossings in curly's preparation, 40 in coily's, seed 0) and lost a third (curly) to
        more than half (coily) of their link (``scripts/probe_preparation.py``, ``docs/detangling.md``,
        *Correction*).
        """
        self.use_step(contact=contact_step)
        hairmod.set_state(self.model, self.data, self._base_state)

        def observe(model: mujoco.MjModel, data: mujoco.MjData) -> None:
            for fn in self._step_observers:
                fn(self)

        hairmod.shake(self.model, self.data, self.wig, seed, strand_bodies=self.hair_bodies, on_step=observe)
        # A curtain one group deep swings as a pendulum after the shake (straight: ±12 cm along x, decaying to
        # ±5 cm only after 3.5 s under the hair's own damping), while a real wig is brushed once it hangs still:
        # let it come to rest under a heavy damping of the hair joints, as a hand steadying the wig would.
        dofs = self._hair_dofs
        damping = self.model.dof_damping[dofs].copy()
        self.model.dof_damping[dofs] = damping * _STEADY_DAMPING
        try:
            for _ in range(round(_STEADY_SECONDS / self.model.opt.timestep)):
                mujoco.mj_step(self.model, self.data)
                observe(self.model, self.data)
        finally:
            self.model.dof_damping[dofs] = damping
        for _ in range(round(_QUIET_SECONDS / self.model.opt.timestep)):
            mujoco.mj_step(self.model, self.data)
            observe(self.model, self.data)
        self.use_step(contact=False)
        return hairmod.get_state(self.model, self.data)

    def reset(self, seed: int = 0) -> None:
        """Restore the cached pre-brushed wig for ``seed`` with the brush parked beside the hair (time = 0)."""
        state = self.settled_state(seed)
        self.use_step(contact=False)
        hairmod.set_state(self.model, self.data, state)
        self.data.time = 0.0
        if self._drag is not None:  # the drag reads the velocities of the last forward pass: this state's
            mujoco.mj_forward(self.model, self.data)
        self._q = self.controller.arm_qpos(self.data)
        self._target = self.park.copy()
        self.diverged = False
        self._warn0 = self._warnings()
        self._last_curves = None
        self._step_speed = 0.0
        ends = np.array([c[-1] for c in self.hair_curves()])
        self.hair_bottom = float(ends[:, 2].min())
        self.load_cell.reset(self.data)
        self.load_cell.tare(self.data)

    # --------------------------------------------------------------------------------------- observers
    def add_observer(self, fn) -> None:
        """Call ``fn(sim, sample)`` at every load-cell sample (10 Hz of simulated time), e.g. to record frames."""
        self._observers.append(fn)

    def remove_observer(self, fn) -> None:
        self._observers.remove(fn)

    def add_step_observer(self, fn) -> None:
        """Call ``fn(sim)`` after every physics step of strokes, velocity control and a pre-brushed preparation that
        is not cached yet (e.g. a pass-through check: strands cross within one 1 ms step, which 10 Hz samples miss).
        Positions seen are those MuJoCo computed at the start of the step, so consecutive calls see consecutive
        states."""
        self._step_observers.append(fn)

    def remove_step_observer(self, fn) -> None:
        self._step_observers.remove(fn)

    # --------------------------------------------------------------------------------------- stepping
    def _warnings(self) -> int:
        return int(sum(int(w.number) for w in self.data.warning))

    def _check(self) -> bool:
        d = self.data
        if (
            not np.all(np.isfinite(d.qpos))
            or not np.all(np.isfinite(d.qvel))
            or float(np.abs(d.qvel[self._watch_dofs]).max(initial=0.0)) > self.config.max_speed
            or self._warnings() > self._warn0
        ):
            self.diverged = True
        return self.diverged

    def _needs_fine_step(self, target: np.ndarray) -> bool:
        """Whether the next control period must run at the contact step.

        It must while the brush's box (bristles and head plate, swept towards ``target``) is within the contact reach
        plus :data:`_FREE_CLEARANCE` of the hair's, while any strand point moved more than :data:`_QUIET_MOTION` in
        the last control period (at 10 ms, strands swinging after a stroke cross each other like strands under the
        brush), and while any two strands touch. Everything else — moves beside or below hair whose strands hang
        apart and at rest — is free space.
        """
        d = self.data
        curves = self.hair_curve_array()
        last, self._last_curves = self._last_curves, curves
        if last is not None and float(np.abs(curves - last).max()) > _QUIET_MOTION:
            return True
        # Hair–hair contacts soften 400-fold at the free step: their time constant (hair.CONTACT_SOLREF, 1 ms) is
        # clamped to twice the step, and entwined strands pressed together by their prestress sank through each
        # other at 10 ms (coily, seed 0, a quiet wig beside the comb between two strokes).
        ncon = d.ncon
        if ncon:
            g = d.contact.geom[:ncon]  # -1 for flex contacts (the wave-1 wig): no chain geoms
            if bool(((g >= 0).all(axis=1) & self._is_hair[g].all(axis=1)).any()):
                return True
        lo, hi = self.tool_box()
        sweep = np.abs(np.asarray(target, dtype=float) - d.site_xpos[self._tcp_site])
        lo, hi = lo - sweep, hi + sweep
        gap = np.maximum(lo - curves.max(axis=(0, 1)), curves.min(axis=(0, 1)) - hi).max()
        return bool(gap < self._contact_reach + _FREE_CLEARANCE)

    def tool_box(self) -> tuple[np.ndarray, np.ndarray]:
        """World axis-aligned box around the bristles and the head plate (corners ``lo``, ``hi``) [m].

        Each geom's own box (``geom_aabb``, in its frame) is turned into the world frame. Bounding spheres
        (``geom_rbound``) are no bound worth having here: the comb's head plate is 0.46 m wide, so its sphere reached
        23 cm in front of the tines and every free-space move near the hair ran at the contact step.
        """
        g = self._tool_geoms
        d = self.data
        rot = d.geom_xmat[g].reshape(-1, 3, 3)
        aabb = self.model.geom_aabb[g]
        centre = d.geom_xpos[g] + np.einsum("gij,gj->gi", rot, aabb[:, :3])
        half = np.einsum("gij,gj->gi", np.abs(rot), aabb[:, 3:])
        return (centre - half).min(axis=0), (centre + half).max(axis=0)

    def use_step(self, *, contact: bool) -> None:
        """Switch to the contact step (``contact_timestep``, :attr:`contact_solver`) or the free-space step.

        Chains are solved with PGS in contact (rods.configure_rod_options), but under the discrete integrator PGS
        integrates actuator gains explicitly: at the 10 ms free-space step the arm's servos (kv = 80, armature 0.2,
        explicit limit ≈ 5 ms) oscillated at 3 rad/s. Free-space steps therefore use Newton, which keeps the servos
        implicit; at the 1 ms contact step the explicit servos are stable.
        """
        m = self.model
        m.opt.timestep = self._dt_contact if contact else self.config.timestep
        m.opt.solver = self.contact_solver if contact else mujoco.mjtSolver.mjSOL_NEWTON

    def _tick(self, target: np.ndarray, vel: np.ndarray | None, samples: list | None) -> bool:
        """One control period: track ``target``, step the physics; returns False once diverged."""
        if self.diverged:
            return False
        self._q = self.controller.track(self.data, target, vel, q_init=self._q)
        # Fine physics step while the brush is (or is about to be) in the hair (SceneConfig.contact_timestep).
        in_hair = self._needs_fine_step(target)
        n_sub = self._n_sub_contact if in_hair else self._n_sub
        self.use_step(contact=in_hair)
        limit = self.config.max_step_travel if in_hair else None
        dt = self.model.opt.timestep
        for _ in range(n_sub):
            # Speed-limited step (SceneConfig.max_step_travel): split this step by the strands' speed in the last
            # one, so a free end snapping off a tine cannot jump through the strand it lies across.
            split = 1
            if limit is not None and self._step_speed > 0.0:
                split = min(MAX_STEP_SPLIT, math.ceil(self._step_speed * dt / limit))
            if split > 1:
                self.model.opt.timestep = dt / split
            before = self.hair_curve_array() if limit is not None else None
            for _ in range(split):
                self._physics_step(samples)
            if before is not None:
                travel = float(np.abs(self.hair_curve_array() - before).max(initial=0.0))
                self._step_speed = travel / dt
            if split > 1:
                self.model.opt.timestep = dt
        self._target = np.asarray(target, dtype=float).copy()
        return not self._check()

    def _physics_step(self, samples: list | None) -> None:
        if self._drag is not None:
            self._drag.apply(self.data)
        mujoco.mj_step(self.model, self.data)
        self.n_steps += 1
        for fn in self._step_observers:
            fn(self)
        s = self.load_cell.update(self.data)
        if s is not None:
            if samples is not None:
                samples.append(s)
            for fn in self._observers:
                fn(self, s)

    def _move(self, end: np.ndarray, speed: float) -> bool:
        path = plan_stroke(self._target, end, speed, self.config.control_dt)
        direction = end - self._target
        dist = float(np.linalg.norm(direction))
        vel = direction / dist * speed if dist > 0 else np.zeros(3)
        for p in path[1:]:
            if not self._tick(p, vel, None):
                return False
        return self._tick(end, None, None)

    def stroke(
        self,
        start_fraction: float,
        *,
        speed: float | None = None,
        abort_force: float | None = PAIN_THRESHOLD,
        rng: np.random.Generator | None = None,
        y: float = 0.0,
    ) -> StrokeResult:
        """One stroke of thesis Algorithm 1 (inner loop) from ``b_l = start_fraction``.

        Parameters
        ----------
        start_fraction : float
            Normalized start height ``b_l ∈ [0, 1]``: the pull starts ``b_l·L_b`` above the free ends, ``L_b`` =
            :attr:`brushable_length` (``b_l = 1``: the highest start the brush head allows below the scalp).
        speed : float, optional
            Pull speed [m/s]; default ``config.stroke_speed``.
        abort_force : float or None
            The stroke stops at the first load-cell sample ≥ this [N] (Algorithm 1's inner loop at the pain
            threshold ``F_T``, the default), among the samples it reads (with ``SceneConfig.read_in_hair`` those taken
            while the brush is above the bottom of the hair); ``None`` pulls through to the end whatever the force
            (a naive or human stroke, the thesis's Fig. 3.11).
        rng : np.random.Generator, optional
            Load-cell noise source for this stroke.
        y : float
            Sideways offset of the brush along the curtain [m] (within ±:data:`MAX_STROKE_Y`): a comb moved by part
            of its tine pitch passes between the strands of pairs its tines passed beside.

        Returns
        -------
        StrokeResult
        """
        if not (isinstance(start_fraction, (int, float)) and 0.0 <= start_fraction <= 1.0):
            raise ValueError(f"start_fraction must be in [0, 1], got {start_fraction!r}")
        speed = self.config.stroke_speed if speed is None else float(speed)
        if not (math.isfinite(speed) and speed > 0):
            raise ValueError(f"speed must be > 0, got {speed!r}")
        if abort_force is not None and not (isinstance(abort_force, (int, float)) and abort_force > 0):
            raise ValueError(f"abort_force must be > 0 or None, got {abort_force!r}")
        if not (isinstance(y, (int, float)) and abs(y) <= MAX_STROKE_Y):
            raise ValueError(f"y must be within ±{MAX_STROKE_Y} m, got {y!r}")
        y = float(y)
        abort_at = math.inf if abort_force is None else float(abort_force)
        if rng is not None:
            self.load_cell.rng = rng
        t0 = float(self.data.time)
        z_start = self.start_height(start_fraction)
        z_start = float(np.clip(z_start, WORKSPACE_Z[0], WORKSPACE_Z[1]))
        # The pull ends once the whole brush is below every strand. With a pull floor it goes on until then, wherever
        # the brush has dragged the free ends (curls straighten under a jammed brush and hang far lower than at
        # rest), down to that floor; without one it ends 1 cm below the rest free ends at the latest.
        z_end = self.pull_end_z
        clear = self.brush.half_height + self._contact_reach + _FREE_CLEARANCE
        fast = self.config.approach_speed
        free = self.config.free_speed
        empty = (np.zeros(0), np.zeros(0))

        def result(trace: tuple[np.ndarray, np.ndarray], aborted: bool, n_read: int) -> StrokeResult:
            forces = trace[1]
            return StrokeResult(
                force_trace=trace,
                max_force=float(forces[:n_read].max()) if n_read else 0.0,
                aborted=aborted,
                sim_time=float(self.data.time) - t0,
                diverged=self.diverged,
                start_height=z_start,
                start_fraction=float(start_fraction),
                pull_max_force=float(forces.max()) if forces.size else 0.0,
                samples_read=n_read,
            )

        # Free-space approach: out to the retract plane, to the start height, settle, tare. The plane clears the
        # hair where it hangs now: long straight strands swing centimetres out of their rest curtain after the
        # shake, and a comb moving up at free_speed past a stray free end whipped it into a divergence.
        hair_front = float(self.hair_curve_array()[..., 0].min())
        retract_x = min(self.retract_x, hair_front - _RETRACT_GAP - 0.5 * self.brush.tine_length)
        here = self._target
        ok = self._move(np.array([retract_x, here[1], here[2]]), fast)
        ok = ok and self._move(np.array([retract_x, y, z_start]), free)
        for _ in range(round(0.1 / self.config.control_dt)):
            ok = ok and self._tick(self._target, None, None)
        if not ok:
            return result(empty, False, 0)
        self.load_cell.tare(self.data)
        # Insertion to depth, then the pull.
        if not self._move(np.array([self.depth_x, y, z_start]), fast):
            return result(empty, False, 0)
        self.load_cell.reset(self.data)
        samples: list = []
        end = np.array([self.depth_x, y, z_end])
        path = plan_stroke(self._target, end, speed, self.config.control_dt)
        vel = np.array([0.0, 0.0, -speed])
        aborted = cleared = False
        t_pull = float(self.data.time)
        # Algorithm 1 reads the load cell while the brush is above the bottom of the hair (SceneConfig.read_in_hair):
        # the samples of the pull up to the tick that takes the TCP below the rest free ends of the last reset.
        reading = True
        n_read = 0
        for p in path[1:]:
            n_before = len(samples)
            if not self._tick(p, vel, samples):
                if reading:
                    n_read = len(samples)
                break
            if reading:
                n_read = len(samples)
                if any(s.brushing_force() >= abort_at for s in samples[n_before:]):
                    aborted = True
                    break
                if self.config.read_in_hair and self.brush_position()[2] < self.hair_bottom:
                    reading = False
            if self._last_curves is not None and float(self._last_curves[..., 2].min()) > p[2] + clear:
                cleared = True  # the whole brush is below every strand
                break
        trace = (
            np.array([s.time - t_pull for s in samples]),
            np.array([s.brushing_force() for s in samples]),
        )
        if not self.diverged:
            # below every strand the way out is free space; an aborted stroke backs out through the hair
            self._move(np.array([retract_x, y, self._target[2]]), free if cleared else fast)
        return result(trace, aborted, n_read)

    def step_velocity(self, v_z: float, v_depth: float, dt: float = 0.1) -> VelocityStep:
        """Move the TCP target with ``(v_depth, 0, v_z)`` [m/s] for ``dt`` seconds (velocity-level control).

        ``v_depth`` is along +x (into the hair). The target is clipped to the brushing workspace
        (x between the retract plane and 2 cm past the wig centre, z in the arm's workspace below the scalp).
        """
        if not (math.isfinite(v_z) and math.isfinite(v_depth) and math.isfinite(dt) and dt > 0):
            raise ValueError(f"v_z, v_depth, dt must be finite (dt > 0), got {v_z!r}, {v_depth!r}, {dt!r}")
        samples: list = []
        n = max(1, round(dt / self.config.control_dt))
        vel = np.array([v_depth, 0.0, v_z])
        lo = np.array([self.retract_x, -0.05, WORKSPACE_Z[0]])
        hi = np.array([self.root_origin[0] + 0.02, 0.05, min(self.top_z, WORKSPACE_Z[1])])
        for _ in range(n):
            target = np.clip(self._target + vel * self.config.control_dt, lo, hi)
            # feed forward the velocity the target really has: at a workspace limit it is zero, and feeding the
            # commanded one forward would push the servos past the limit
            actual = (target - self._target) / self.config.control_dt
            if not self._tick(target, actual, samples):
                break
        forces = np.array([s.brushing_force() for s in samples])
        return VelocityStep(
            force=float(forces[-1]) if forces.size else math.nan,
            max_force=float(forces.max()) if forces.size else math.nan,
            position=self.brush_position(),
            diverged=self.diverged,
        )

    # --------------------------------------------------------------------------------------- rendering
    def hair_window(
        self, camera: str = "webcam", *, skip_root: float = 0.2, margin: int = 2
    ) -> tuple[int, int, int, int]:
        """Pixel box ``(y0, y1, x0, x1)`` of the hanging hair in ``camera``'s image (size of :meth:`render`).

        The thesis crops the webcam image "to include only the hair" before computing R_c (§3.3): the rig fixes
        the free ends and the webcam, so an operator draws that box once. Here it is the projection of the
        strands' current centerlines, without the top ``skip_root`` fraction of the hanging height, where the
        scalp plate and the head are in view; their outlines are strong horizontal/vertical edges that would
        swamp the hair's own gradients. The box can still hold a little of the brush or plate at its edges.
        """
        if not 0.0 <= skip_root < 1.0:
            raise ValueError(f"skip_root: must be in [0, 1), got {skip_root!r}")
        m, d = self.model, self.data
        cam = m.camera(camera).id  # KeyError names an unknown camera
        pts = np.concatenate(self.hair_curves())
        top, bottom = float(pts[:, 2].max()), float(pts[:, 2].min())
        pts = pts[pts[:, 2] <= top - skip_root * (top - bottom)]
        # camera frame: x right, y up, looking along -z
        local = (pts - d.cam_xpos[cam]) @ d.cam_xmat[cam].reshape(3, 3)
        depth = -local[:, 2]
        if pts.size == 0 or np.any(depth <= 0.0):
            raise ValueError(f"camera: {camera!r} does not see the whole hair")
        w, h = self.config.width, self.config.height
        f = 0.5 * h / math.tan(math.radians(float(m.cam_fovy[cam])) / 2.0)
        u = w / 2.0 + f * local[:, 0] / depth
        v = h / 2.0 - f * local[:, 1] / depth
        y0, y1 = max(int(v.min()) - margin, 0), min(math.ceil(v.max()) + margin + 1, h)
        x0, x1 = max(int(u.min()) - margin, 0), min(math.ceil(u.max()) + margin + 1, w)
        if y1 - y0 < 3 or x1 - x0 < 3:
            raise ValueError(f"camera: the hair is outside {camera!r}'s {w}x{h} image")
        return y0, y1, x0, x1

    def render(self, camera: str = "webcam") -> np.ndarray:
        """RGB image ``(height, width, 3)`` uint8 from ``camera`` (renderer created on first use)."""
        if self._renderer is None:
            self._renderer = mujoco.Renderer(self.model, self.config.height, self.config.width)
        self._renderer.update_scene(self.data, camera=camera)
        return self._renderer.render().copy()

    def close(self) -> None:
        """Free the renderer (the sim stays usable; rendering re-creates it)."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None

    def __enter__(self) -> BrushingSim:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def replace_config(self, **changes: object) -> SceneConfig:
        """Convenience: a copy of this sim's config with ``changes`` (build a new sim from it)."""
        return dataclasses.replace(self.config, **changes)
