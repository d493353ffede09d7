"""The brush's tines as a typed config: rows × columns of capsules on the head plate of ``assets/brush``.

``assets/brush/brush.xml`` is the standalone part (load cell, mount, head plate, the default 3 × 8 soft bristles).
:func:`brush_spec` loads it and, for any :class:`BrushConfig`, replaces its tines with the configured ones and
sizes the head plate and the tool centre point to them, so scenes, studies and tests use one brush definition.
``BrushConfig()`` reproduces the XML's tines exactly (``tests/test_brush.py``).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import mujoco
import numpy as np

from .assets import load_part

__all__ = [
    "BRUSH_PRESETS",
    "NYLON_YOUNG",
    "PLATE_FRONT_X",
    "TINE_PREFIX",
    "BrushConfig",
    "brush_spec",
    "get_brush",
    "tine_hinge_stiffness",
]

PLATE_FRONT_X = 0.065
"""x of the head plate's front face in the brush frame [m]: the tines' roots."""

TINE_PREFIX = "tine_"
"""Name prefix of tine bodies and geoms (``tine_<row>_<column>``)."""

NYLON_YOUNG = 2.8e9
"""Young's modulus of nylon 6,6 [Pa] (2.5–3.5 GPa)."""

_PLATE_HALF_DEPTH = 0.005
# The plate extends this far beyond the outermost tines (brush.xml: 9 mm across the rows, 3 mm above/below them).
_PLATE_RIM_Y, _PLATE_RIM_Z = 0.009, 0.003


@dataclass(frozen=True)
class BrushConfig:
    """Tines of the brush (lengths in metres, brush frame: x along the tines, y along a row, z up).

    Parameters
    ----------
    rows : int
        Tine rows, stacked in z ``row_pitch`` apart and centred on the TCP height.
    row_pitch : float
        Vertical distance between rows.
    columns : int
        Tines per row, ``column_pitch`` apart in y and centred.
    column_pitch : float
        Horizontal distance between neighbouring tines of a row (the bristle gap is this minus ``2 tine_radius``).
    tine_length : float
        Length of a tine from the plate face to its tip (the TCP sits at mid-tine).
    tine_radius : float
        Capsule radius of a tine.
    hinged : bool
        Each tine hinges about y at its root (its tip deflects along the pull) with ``stiffness`` and ``damping``;
        ``False`` = rigid tines, fixed to the head.
    stiffness : float
        Hinge stiffness [N m/rad] (brush.xml: a 0.05 N tip load on a 25 mm bristle bends it ≈ 3.6°).
    damping : float
        Hinge damping [N m s/rad].
    deflection_limit : float
        Largest hinge angle [rad] either way (brush.xml's 0.35 for the paddle's short bristles). Above
        ``stiffness · deflection_limit`` of moment a hinged tine stops bending and holds like a rigid one.
    density : float
        Tine material density [kg/m³] (nylon).
    friction : float
        Sliding friction coefficient of the tines (brush.xml: 0.3). MuJoCo uses the larger of two geoms'
        coefficients, so hair slides on a tine with ``max(friction, WigConfig.friction)``.
    """

    rows: int = 3
    row_pitch: float = 0.008
    columns: int = 8
    column_pitch: float = 0.006
    tine_length: float = 0.025
    tine_radius: float = 0.0015
    hinged: bool = True
    stiffness: float = 0.02
    damping: float = 3e-4
    deflection_limit: float = 0.35
    density: float = 1150.0
    friction: float = 0.3

    def __post_init__(self) -> None:
        for name in ("rows", "columns"):
            v = getattr(self, name)
            if not (isinstance(v, int) and not isinstance(v, bool) and 1 <= v <= 64):
                raise ValueError(f"BrushConfig.{name} must be an integer in [1, 64], got {v!r}")
        for name in (
            "row_pitch",
            "column_pitch",
            "tine_length",
            "tine_radius",
            "stiffness",
            "damping",
            "deflection_limit",
            "density",
            "friction",
        ):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"BrushConfig.{name} must be a finite number > 0, got {v!r}")
        if self.deflection_limit >= 0.5 * math.pi:
            raise ValueError(
                f"BrushConfig.deflection_limit must be below pi/2 rad, got {self.deflection_limit!r}"
            )
        if self.column_pitch <= 2 * self.tine_radius and self.columns > 1:
            raise ValueError(
                f"BrushConfig.column_pitch must exceed the tine diameter {2 * self.tine_radius:g}, "
                f"got {self.column_pitch!r}"
            )
        if self.row_pitch <= 2 * self.tine_radius and self.rows > 1:
            raise ValueError(
                f"BrushConfig.row_pitch must exceed the tine diameter {2 * self.tine_radius:g}, got {self.row_pitch!r}"
            )
        if self.tine_length <= 2 * self.tine_radius:
            raise ValueError(
                f"BrushConfig.tine_length must exceed the tine diameter, got {self.tine_length!r}"
            )

    @property
    def row_z(self) -> np.ndarray:
        """z of each row (brush frame), top row first (brush.xml: row 0 at +8 mm)."""
        return (0.5 * (self.rows - 1) - np.arange(self.rows)) * self.row_pitch

    @property
    def column_y(self) -> np.ndarray:
        """y of each column (brush frame)."""
        return (np.arange(self.columns) - 0.5 * (self.columns - 1)) * self.column_pitch

    @property
    def half_height(self) -> float:
        """Vertical half extent of the tines (outermost row axis + radius) [m]."""
        return float(self.row_z.max()) + self.tine_radius

    @property
    def half_width(self) -> float:
        """Horizontal half extent of the tines across a row [m]."""
        return float(self.column_y.max()) + self.tine_radius

    @property
    def plate_half_size(self) -> tuple[float, float, float]:
        """Half sizes of the head plate box (x, y, z) that carries these tines."""
        return (
            _PLATE_HALF_DEPTH,
            float(self.column_y.max()) + _PLATE_RIM_Y,
            float(self.row_z.max()) + _PLATE_RIM_Z,
        )

    @property
    def tcp_x(self) -> float:
        """x of the tool centre point (mid-tine) in the brush frame [m]."""
        return PLATE_FRONT_X + 0.5 * self.tine_length


def tine_hinge_stiffness(
    length: float, radius: float, *, young: float = NYLON_YOUNG, load_at: float = 0.5
) -> float:
    """Root-hinge stiffness [N m/rad] of a tine that deflects like a clamped solid rod under a load ``load_at`` of
    its length from the root: a cantilever moves the loaded point by ``F a³ / (3 E I)``, a hinge by ``F a² / K``, so
    ``K = 3 E I / a`` with ``I = π r⁴ / 4``. The comb's hair hangs at mid-tine (the TCP), hence ``load_at = 0.5``."""
    for name, v in (("length", length), ("radius", radius), ("young", young), ("load_at", load_at)):
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"tine_hinge_stiffness: {name} must be a finite number > 0, got {v!r}")
    return 3.0 * young * math.pi * radius**4 / 4.0 / (load_at * length)


_COMB = {"rows": 1, "columns": 23, "column_pitch": 0.02, "tine_length": 0.06}
BRUSH_PRESETS: dict[str, BrushConfig] = {
    "comb": BrushConfig(**_COMB, hinged=False),
    "soft_comb": BrushConfig(
        **_COMB,
        hinged=True,
        stiffness=tine_hinge_stiffness(_COMB["tine_length"], BrushConfig.tine_radius),
        damping=0.004,  # ζ ≈ 0.75 with the tine's rotor inertia and brush.xml's armature scaled to 60 mm
        # A nylon tine has no stop: at brush.xml's 0.35 rad it held like a rigid one above 13 N at the curtain, and a
        # curl wrapped on it jammed the comb at 24 N; 1.2 rad (K·1.2 ≈ 44 N at the curtain) freed it.
        deflection_limit=1.2,
    ),
    "paddle": BrushConfig(),
}
# The soft comb two tines wider (±240 mm): it spans a curtain of twelve pairs (24 strands without triples, 40 mm
# apart: group axes at ±220 mm, curls out to ±232 mm), with a tine through every group axis and between neighbours.
BRUSH_PRESETS["wide_soft_comb"] = dataclasses.replace(BRUSH_PRESETS["soft_comb"], columns=25)
# MuJoCo takes the larger of two geoms' friction coefficients, so hair slides on a tine at the tine's coefficient
# unless it is the lower one: at 0.15 (the conditioned hair's, HairBrush-v1 on) hair slides on the tines as on hair.
# A curl through which a tine is pulled along its axis is a screw: it turns and lets the tine through only while
# μ < tan λ = P / (2π R) (its lead angle), else it locks and is drawn straight. At 0.3, curly (0.32) is just free and
# tight_curl (0.25) and coily (0.20) lock; at 0.15 every preset's curl turns (docs/detangling.md, *HairBrush-v8*).
BRUSH_PRESETS["smooth_comb"] = dataclasses.replace(BRUSH_PRESETS["wide_soft_comb"], friction=0.15)
# The smooth comb with a tenth of the hinge damping, ζ ≈ 0.075 instead of 0.75: a nylon tine springs back and rings.
# A tine bent by a curl turning round it gives way faster at a faster pull, and the damping read that rate as force
# (curly's full stroke, cross-flow drag: +27 % for 4× the speed at v8's damping, +15 % at a tenth; docs/detangling.md,
# *HairBrush-v9*).
BRUSH_PRESETS["springy_comb"] = dataclasses.replace(BRUSH_PRESETS["smooth_comb"], damping=0.0004)
"""Named brushes. ``comb`` (the scenes' default): one row of 23 rigid 60 mm tines at 20 mm (±220 mm), spanning the
default one-group-deep curtain (``WigConfig.group_rows = 1``, 40 mm group spacing): every group axis has a tine
through it and a tine between neighbouring groups, so each stroke parts the strands of every pair; 60 mm crosses a
curtain one group deep with room to spare. ``paddle``: ``assets/brush/brush.xml``'s own 3 × 8 soft 25 mm bristles
at 6 mm, kept for the wave-1 benchmarks; it pushes whole groups aside and winds neighbouring groups together
(``docs/detangling.md``). ``soft_comb``: the comb with nylon tines that bend (a root hinge of
:func:`tine_hinge_stiffness`, 1.1 N m/rad: 0.03 rad under 1 N at the curtain, up to 1.2 rad), like the thesis's
soft-bristled brush, for studies of bristle compliance: it frees a pair whose wound free ends lock on a rigid tine,
but over repeated strokes jams occur elsewhere and it combs out no better (``docs/detangling.md``, *Jams,
soft tines*). ``wide_soft_comb``: ``soft_comb`` with 25 tines (±240 mm), for the twelve-pair curtain of
``HairBrush-v3``. ``smooth_comb``: ``wide_soft_comb`` with tines of friction 0.15, the conditioned hair's, for
``HairBrush-v8``: curls turn round a tine pulled through them instead of locking on it. ``springy_comb``:
``smooth_comb`` with a tenth of the hinge damping (ζ ≈ 0.075), for ``HairBrush-v9``."""


def get_brush(brush: str | BrushConfig) -> BrushConfig:
    """Resolve a preset name (or pass a :class:`BrushConfig` through); ValueError lists the valid names."""
    if isinstance(brush, BrushConfig):
        return brush
    if isinstance(brush, str) and brush in BRUSH_PRESETS:
        return BRUSH_PRESETS[brush]
    raise ValueError(f"brush: unknown preset {brush!r}; valid names: {', '.join(BRUSH_PRESETS)}")


def brush_spec(config: BrushConfig | None = None) -> mujoco.MjSpec:
    """``assets/brush`` with its tines replaced by ``config``'s (plate, visual head and TCP sized to them)."""
    config = config if config is not None else BrushConfig()
    spec = load_part("brush")
    for body in [b for b in spec.bodies if b.name.startswith(TINE_PREFIX)]:
        spec.delete(body)
    for key in list(spec.keys):
        spec.delete(key)
    half = list(config.plate_half_size)
    for name in ("head_plate", "head_visual"):
        spec.geom(name).size = half
    spec.site("brush_tcp").pos = [config.tcp_x, 0.0, 0.0]
    root = spec.body("brush")
    # brush.xml's "bristle" class holds what every tine shares (contact bits, friction, colour, joint axis and range);
    # the config sets the rest
    bristle = spec.find_default("bristle")
    for i, z in enumerate(config.row_z):
        for j, y in enumerate(config.column_y):
            name = f"{TINE_PREFIX}{i}_{j}"
            parent = root
            pos = [PLATE_FRONT_X, float(y), float(z)]
            if config.hinged:
                parent = root.add_body(name=name, pos=pos)
                joint = parent.add_joint(bristle, name=name)
                joint.stiffness = [config.stiffness, 0.0, 0.0]
                joint.damping = [config.damping, 0.0, 0.0]
                joint.range = [-config.deflection_limit, config.deflection_limit]
                # brush.xml's numerical regularization, scaled with the tine's rotor inertia (∝ length²)
                joint.armature = bristle.joint.armature * (config.tine_length / 0.025) ** 2
                pos = [0.0, 0.0, 0.0]
            geom = parent.add_geom(bristle, name=name)
            geom.size = [config.tine_radius, 0.0, 0.0]
            geom.fromto = [pos[0], pos[1], pos[2], pos[0] + config.tine_length, pos[1], pos[2]]
            geom.density = config.density
            geom.friction = [config.friction, *bristle.geom.friction[1:]]
    return spec
