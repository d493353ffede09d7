"""Assembling the brushing scene (thesis §3.4, Fig. 3.5) into one :class:`mujoco.MjSpec`; it is simulated by
:class:`hairbrush_env.scene.BrushingSim` (which re-exports this module's public names).

* :func:`build_scene` composes the MJCF parts (``assets/arm``, ``assets/brush``, ``assets/head``) and a wig
  (:mod:`hairbrush_env.hair`) into one :class:`mujoco.MjSpec`.
* The head stands on a **variable-height mount** (thesis: "the head is mounted on a variable height mount such that
  the bottom of the hair is kept in a fixed location relative to the robot and camera"): it is shifted vertically
  so that the rest shape's free ends sit at ``SceneConfig.free_end_z`` whatever the wig's hanging length.
* The ``webcam`` is fixed in the world, looking at the hair from the side (−y) against a light backdrop, so the
  same framing holds for every wig (thesis: the webcam is fixed relative to the free ends).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import mujoco
import numpy as np

from . import hair as hairmod
from .assets import load_part
from .brush import TINE_PREFIX, BrushConfig, brush_spec, get_brush
from .rods import configure_rod_options
from .sensors import LoadCellConfig

__all__ = [
    "BRUSH_TCP",
    "HEAD_POS",
    "SCENE_TINE_PREFIX",
    "TOOL_CONTACT_MARGIN",
    "WORKSPACE_Z",
    "SceneConfig",
    "SceneInfo",
    "assemble_scene",
    "build_scene",
    "wave1_scene",
]

BRUSH_TCP = "arm/brush/brush_tcp"
HEAD_POS = np.array([0.62, 0.0, 0.0])  # recommended head placement (assets/head/head.xml)
WORKSPACE_Z = (0.55, 0.93)  # arm README: brushing workspace
# The arm holds the brush level below its brushing workspace too (IK residual < 0.01 mm down to 0.35 m), so a pull may
# go on below 0.55 m (SceneConfig.pull_floor_z, 0.40 by default).
_PULL_FLOOR_MIN = 0.35
SCENE_TINE_PREFIX = "arm/brush/" + TINE_PREFIX
"""Name prefix of the brush's tine geoms in the scene (:data:`hairbrush_env.brush.TINE_PREFIX` under ``arm/brush/``)."""

TOOL_CONTACT_MARGIN = 1e-3
"""Contact margin [m] of the bristles and head plate. MuJoCo 4.0.1 adds it to the wisp's own margin
(``hair.CONTACT_MARGIN``), so a hair–tool contact acts from 1.5 mm surface gap: a wisp wrapped round a bristle near the
clamp carries ~10 N on one contact and sank ~2 mm into it without a margin (1 ms step, flex wig, issue #3)."""


@dataclass(frozen=True)
class SceneConfig:
    """Scene and simulation settings.

    Parameters
    ----------
    wig : str or WigConfig
        Preset name (see :data:`hairbrush_env.hair.PRESETS`) or custom wig.
    brush : str or BrushConfig
        Tines of the brush (:data:`hairbrush_env.brush.BRUSH_PRESETS` or a custom :class:`BrushConfig`).
    timestep : float
        Physics step [s] outside the hair (shake, settling, free-space moves). 10 ms: the ``discrete`` integrator is
        implicit and rods are step-independent in statics. Contact with the brush uses ``contact_timestep``.
    contact_timestep : float
        Physics step [s] while the brush is within contact reach of the hair or any strand still moves
        (``BrushingSim._needs_fine_step``: insertion, pull, retraction through the hair, velocity control). Above
        1 ms strands cross each other during a stroke (strand speeds reach ~2 m/s; ``docs/rods.md``). Shake,
        settling and free-space moves keep ``timestep`` (the cached pre-brushed states do not depend on this
        setting), so ``model.opt.timestep`` changes at run time.
    control_dt : float
        Period of the Cartesian tracking loop [s] (IK + servo set-points).
    width, height : int
        Webcam resolution [px].
    camera_distance : float
        Distance of the webcam from the hair plane [m].
    free_end_z : float
        World height of the rest shape's free ends (the head mount height follows from it).
    brush_depth : float
        TCP x offset from the wig centre during a stroke [m] (0: bristles span the middle 25 mm of the curtain).
    stroke_speed : float
        Default pulling speed [m/s]. The thesis finds that speed has minimal effect on the maximum force (Fig. 3.8;
        here a 4× change moves it by a few per cent), but it does change how much a stroke combs out: six full
        strokes at 0.2 m/s left 0.34–0.40 of curly's entanglement (seeds 0–2) against 0.20–0.27 at 0.1, for 0.7×
        the CPU (``docs/detangling.md``, *Cost*).
    approach_speed : float
        Speed of insertion into and withdrawal through the hair [m/s]. 0.3 combed out as much as 0.15 (wave 1)
        for 0.85× the CPU of a stroke.
    free_speed : float
        Speed of moves beside or below the hair (up the retract plane to the start height, out from under the
        hair after a stroke that went through) [m/s]: while the hair still swings these run at the contact step.
    load_cell : LoadCellConfig
        Instrument (sensor names of the nested brush).
    hair_hair : bool
        Hair–hair contact (off only for benchmarks).
    max_speed : float
        Any dof speed above this [m/s or rad/s] flags divergence (rod twist hinges excluded). A curl whipping free
        of a jam turns a chain hinge at up to ~60 rad/s (a 9 mm edge at 0.5 m/s; free ends reach ~2 m/s) and the
        run goes on sanely, so 50 flagged healthy strokes (curly, seed 2, second stroke: 54 rad/s at a root
        vertex, then four more strokes without a crossing); a blow-up passes 500 within a few steps.
    pull_floor_z : float or None
        A float [m] (≥ 0.35, where the arm still holds the brush level): the pull goes on until the brush is below
        every strand, however far it dragged the curls, down to this height. Default 0.40, 22 cm below the rest free
        ends (``free_end_z``) and about a coily strand's arc length below its roots: a curl hooked on a tine
        stretches rather than slides, and a pull that stops before the strand is pulled straight withdraws sideways
        with the curls still on the tines, so their link springs back (ending at 0.55 m left 11–14 of coily's 15
        pairs wound after six strokes). The pull stops earlier once the whole brush is below every strand, so the
        floor costs nothing where the hair lets go. ``None``: a pull ends 1 cm below the rest free ends, or earlier
        once the whole brush is below every strand (the wave-1 stroke, kept for benchmarks; ``docs/detangling.md``).
    max_step_travel : float or None
        A float [m]: contact steps are split so that no strand point travels more than this in one physics step
        (a speed-limited, CFL-like step; the split comes from the speed of the step before, up to
        ``MAX_STEP_SPLIT`` substeps). Meant for free ends snapping off a tine (~3 m/s, 3 mm per 1 ms step, about
        twice a wisp's diameter). With real-mass strands most steps of a stroke are that fast, so it costs about as
        much as a finer step everywhere and does not stop every crossing (docs/detangling.md, *A speed-limited
        contact step*). ``None`` (default): fixed steps.
    scalp_clearance : float
        Gap [m] between the head plate's top and the scalp at the highest stroke start (``b_l = 1``). 5 mm (default):
        with the comb's plate the tines enter 8 mm below the roots; link above the highest tine is never combed
        (starting 12 mm below the roots left twice the link after a stroke). The soft paddle brush needs ~9 mm:
        closer starts bent the stiff wisps sharply around its bristles at the clamp.
    read_in_hair : bool
        ``True``: a stroke reads the load cell as thesis Algorithm 1 does, only while the brush is above the bottom
        of the hair (the TCP at or above the rest free ends of the last reset, the fixed point the thesis's rig keeps
        the free ends at): the abort and ``StrokeResult.max_force`` see those samples only. The pull itself goes on
        as before, and ``StrokeResult.pull_max_force`` keeps the largest sample of the whole pull, which pain counts
        use. ``False`` (default): every sample of the pull is read. Below the rest free ends the tines hold only
        strands they have hooked and dragged down (a short stroke through tight_curl read its maximum 110 mm below
        them); the thesis's robot had stopped reading by then (docs/detangling.md, *HairBrush-v10*).
    """

    wig: str | hairmod.WigConfig = hairmod.DEFAULT_WIG
    brush: str | BrushConfig = "comb"
    timestep: float = 0.01
    contact_timestep: float = 0.001
    control_dt: float = 0.01
    width: int = 320
    height: int = 240
    camera_distance: float = 0.42
    free_end_z: float = 0.62
    brush_depth: float = 0.0
    stroke_speed: float = 0.1
    approach_speed: float = 0.3
    free_speed: float = 0.4
    load_cell: LoadCellConfig = field(
        default_factory=lambda: LoadCellConfig(
            force_sensor="arm/brush/brush_force", torque_sensor="arm/brush/brush_torque"
        )
    )
    hair_hair: bool = True
    max_speed: float = 500.0
    scalp_clearance: float = 0.005
    pull_floor_z: float | None = 0.40
    max_step_travel: float | None = None
    read_in_hair: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "wig", hairmod.get_wig(self.wig))  # ValueError naming 'wig' if unknown
        if isinstance(self.read_in_hair, np.bool_):  # e.g. from a numpy array of settings
            object.__setattr__(self, "read_in_hair", bool(self.read_in_hair))
        object.__setattr__(self, "brush", get_brush(self.brush))
        for name in (
            "timestep",
            "contact_timestep",
            "control_dt",
            "camera_distance",
            "stroke_speed",
            "approach_speed",
            "free_speed",
            "max_speed",
            "scalp_clearance",
        ):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"SceneConfig.{name} must be a finite number > 0, got {v!r}")
        v = self.max_step_travel
        if v is not None and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"SceneConfig.max_step_travel must be None or a finite number > 0, got {v!r}")
        if self.control_dt < self.timestep:
            raise ValueError(f"SceneConfig.control_dt must be >= timestep, got {self.control_dt!r}")
        if self.contact_timestep > self.timestep:
            raise ValueError(
                f"SceneConfig.contact_timestep must be <= timestep, got {self.contact_timestep!r}"
            )
        for name in ("width", "height"):
            v = getattr(self, name)
            if not (isinstance(v, int) and 16 <= v <= 4096):
                raise ValueError(f"SceneConfig.{name} must be an int in [16, 4096], got {v!r}")
        if not (math.isfinite(self.free_end_z) and WORKSPACE_Z[0] < self.free_end_z < WORKSPACE_Z[1]):
            raise ValueError(f"SceneConfig.free_end_z must be inside {WORKSPACE_Z}, got {self.free_end_z!r}")
        if self.pull_floor_z is not None and not (
            isinstance(self.pull_floor_z, (int, float))
            and math.isfinite(self.pull_floor_z)
            and _PULL_FLOOR_MIN <= self.pull_floor_z < self.free_end_z
        ):
            raise ValueError(
                f"SceneConfig.pull_floor_z must be in [{_PULL_FLOOR_MIN}, free_end_z), got {self.pull_floor_z!r}"
            )
        if not isinstance(self.read_in_hair, bool):
            raise ValueError(f"SceneConfig.read_in_hair must be True or False, got {self.read_in_hair!r}")
        if not (math.isfinite(self.brush_depth) and abs(self.brush_depth) <= 0.03):
            raise ValueError(f"SceneConfig.brush_depth must be within ±0.03 m, got {self.brush_depth!r}")

    @property
    def wig_config(self) -> hairmod.WigConfig:
        assert isinstance(self.wig, hairmod.WigConfig)
        return self.wig

    @property
    def brush_config(self) -> BrushConfig:
        assert isinstance(self.brush, BrushConfig)
        return self.brush


def wave1_scene(wig: str | hairmod.WigConfig = hairmod.DEFAULT_WIG, **changes) -> SceneConfig:
    """The first release's scene for a wig, kept as a benchmark case: :func:`hairbrush_env.hair.wave1_wig`, the soft
    ``paddle`` brush with a 9 mm scalp clearance, the short pull (``pull_floor_z = None``) and its speeds (pull at
    0.1 m/s, insertion and withdrawal at 0.15 m/s)."""
    kw = dict(
        wig=hairmod.wave1_wig(wig),
        brush="paddle",
        scalp_clearance=0.009,
        pull_floor_z=None,
        stroke_speed=0.1,
        approach_speed=0.15,
    )
    return SceneConfig(**(kw | changes))


@dataclass(frozen=True)
class SceneInfo:
    """Where :func:`assemble_scene` put the wig."""

    layout: hairmod.WigLayout
    root_origin: np.ndarray  # world position of the root-plane centre (scalp site)
    head_offset: float


def _head_offset(wig: hairmod.WigConfig, free_end_z: float, scalp_site_z: float) -> float:
    # Variable-height mount: rest free ends at free_end_z, but never lift the scalp above its design height
    # (the arm's top reach) — long wigs then simply hang lower.
    return min(0.0, free_end_z + wig.hanging_length - scalp_site_z)


def assemble_scene(config: SceneConfig) -> tuple[mujoco.MjSpec, SceneInfo]:
    """The spec of :func:`build_scene` and where it put the wig (:class:`SceneInfo`), for
    :class:`hairbrush_env.scene.BrushingSim`."""
    wig = config.wig_config
    spec = mujoco.MjSpec()
    spec.modelname = f"hairbrush_{wig.name}"
    configure_rod_options(spec, timestep=config.timestep, kind=wig.rod_kind)
    # Elliptic cones: the rods docstring's contact settings were validated with them (pyramidal cones make thin
    # rods stick-slip on the bristles).
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    # refsafe would replace the 1 ms hair contacts by ~2·dt ones, which let bristles pull wisps through themselves
    # (hair.CONTACT_SOLREF); the discrete integrator treats the stiff rows implicitly, so they stay stable.
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_REFSAFE
    # Speculative contacts widen each geom pair's contact range by how far the pair closes within the step. Strand
    # tips whip at up to ~2 m/s when the brush lets go of them; without it, a tip closing faster than the 1 mm
    # hair–hair contact margin per step reached a neighbour before its contact existed and sank into it to 0.12 of
    # the sum of radii (curly, full stroke; docs/rods.md). Body-chain hair only: MuJoCo does not apply it to flexes.
    spec.option.enableflags |= mujoco.mjtEnableBit.mjENBL_SPECULATIVE
    spec.visual.global_.offwidth = max(640, config.width)
    spec.visual.global_.offheight = max(480, config.height)
    spec.visual.headlight.ambient = [0.35, 0.35, 0.35]
    spec.visual.headlight.diffuse = [0.5, 0.5, 0.5]

    arm = load_part("arm")
    arm.attach(brush_spec(config.brush_config), site="attachment_site", prefix="brush/")
    arm.compile()  # required before nesting (assets/brush/README.md: pending keyframes)
    spec.attach(arm, frame=spec.worldbody.add_frame(), prefix="arm/")
    # Tool geoms get the thin-rod contact parameters of the hair (rods.py: with MuJoCo's default 1 mm impedance
    # width and 20 ms time constant a strand sinks into — and is pulled through — a 1.5 mm bristle). Contact
    # parameters of a geom–flex pair are mixed, so both sides must be stiff.
    for geom in spec.geoms:
        if geom.name.startswith(SCENE_TINE_PREFIX) or geom.name == "arm/brush/head_plate":
            geom.solref = list(hairmod.CONTACT_SOLREF)
            geom.solimp = list(hairmod.CONTACT_SOLIMP)
            geom.margin = TOOL_CONTACT_MARGIN

    head = load_part("head")
    scalp_local = np.asarray(head.body("scalp").pos) + np.asarray(head.site("scalp").pos)
    dz = _head_offset(wig, config.free_end_z, float(HEAD_POS[2] + scalp_local[2]))
    mount = HEAD_POS + np.array([0.0, 0.0, dz])
    spec.attach(head, frame=spec.worldbody.add_frame(pos=[float(v) for v in mount]), prefix="head/")
    root_origin = mount + scalp_local

    layout = hairmod.add_wig(
        spec,
        wig,
        parent_body="head/scalp",
        root_offset=np.array(spec.site("head/scalp").pos),
        hair_hair=config.hair_hair,
    )

    # Webcam: fixed, level, looking along +y at the hair plane x = root_origin.x, framing the workspace heights.
    # A light, untextured backdrop behind the hair gives the curls contrast for the vision pipeline.
    look = np.array([root_origin[0], 0.0, 0.74])
    cam = spec.worldbody.add_camera(name="webcam", pos=list(look - [0.0, config.camera_distance, 0.0]))
    cam.quat = [math.sqrt(0.5), math.sqrt(0.5), 0.0, 0.0]  # camera -z along world +y, camera y = world z
    cam.fovy = 50.0
    backdrop = spec.worldbody.add_body(name="backdrop", pos=[float(root_origin[0]), 0.3, 0.75])
    backdrop.add_geom(
        type=mujoco.mjtGeom.mjGEOM_BOX,
        size=[0.5, 0.005, 0.5],
        rgba=[0.92, 0.92, 0.9, 1.0],
        contype=0,
        conaffinity=0,
        group=2,
    )
    key_light = spec.worldbody.add_light(name="key", pos=[float(root_origin[0]) - 0.5, -0.6, 1.6])
    key_light.dir = [0.5, 0.6, -1.0]
    key_light.diffuse = [0.6, 0.6, 0.6]
    key_light.castshadow = False
    fill = spec.worldbody.add_light(name="fill", pos=[float(root_origin[0]) + 0.3, -0.8, 0.9])
    fill.dir = [-0.2, 1.0, -0.1]
    fill.diffuse = [0.35, 0.35, 0.35]
    fill.castshadow = False
    return spec, SceneInfo(layout=layout, root_origin=root_origin, head_offset=dz)


def build_scene(config: SceneConfig | None = None) -> mujoco.MjSpec:
    """Compose arm + brush + head mount + wig + webcam + lights into one (uncompiled) spec.

    Names: arm ``arm/...``, brush ``arm/brush/...`` (TCP site :data:`BRUSH_TCP`), head ``head/...``, strands
    ``hair0 ... hair{n-1}`` (rods), camera ``webcam``.
    """
    return assemble_scene(config if config is not None else SceneConfig())[0]
