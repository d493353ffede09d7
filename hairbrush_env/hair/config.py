"""What a wig is and which wigs there are: wisp material (:func:`wisp_young`), :class:`WigConfig`, the presets,
the held-out wigs and the wave-1 benchmark wig (model: :mod:`hairbrush_env.hair`)."""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from .. import rods

__all__ = [
    "DEFAULT_WIG",
    "HAIR_RGBA",
    "HELD_OUT_SEEDS",
    "HELD_OUT_WIGS",
    "MASS_SCALE",
    "PRESETS",
    "REAL_HAIR_RADIUS",
    "REAL_HAIR_YOUNG",
    "TRAIN_WIGS",
    "TRAIN_WIG_SEEDS",
    "WAVE1_COHESION",
    "WIG_SETS",
    "WISP_COHESION",
    "WigConfig",
    "brushing_seeds",
    "get_wig",
    "wave1_wig",
    "wig_names",
    "wisp_young",
]

HAIR_RGBA = (0.30, 0.17, 0.08, 1.0)
"""Medium brown: dark enough to stand out against the light backdrop of the scene's ``webcam``."""

REAL_HAIR_RADIUS = 40e-6
"""Radius of a human scalp hair [m] (thesis: r is approximately constant for human hair)."""

REAL_HAIR_YOUNG = 4e9
"""Young's modulus of keratin hair [Pa]."""

WISP_COHESION = 12.5
"""Force-scale calibration ``κ = B_w / (n B_h)`` of a wisp (:mod:`hairbrush_env.hair`, *Wisp scaling*).

``κ = 1``: the ``n`` hairs of a wisp bend independently; ``κ = n``: they are bonded into one solid keratin fibre. 12.5
(``E_w = 125 MPa`` at ``r_w = 0.8 mm``): the comb's first full stroke through the curled presets reads 5.3–13.7 N
(means over seeds, ``docs/wigs.md``) and leaves 0.37–0.41 of curly's entanglement; stiffer wisps read more but combed
out less on the wigs before the preparation was corrected (``docs/detangling.md``)."""

MASS_SCALE = 10.0
"""Default inertia multiplier of chain strands (:attr:`WigConfig.mass_scale`; *Mass scaling* in
:mod:`hairbrush_env.hair`). 10 keeps taut strands ≥ 0.86 of the sum of radii apart through six full strokes of the deep
pull on curly and coily (seeds 0–2) at the 1 ms step, where the real mass let them sink to 0.04."""


def wisp_young(
    strand_radius: float,
    *,
    cohesion: float = WISP_COHESION,
    hair_radius: float = REAL_HAIR_RADIUS,
    hair_young: float = REAL_HAIR_YOUNG,
):
    """Young's modulus of a wisp of radius ``strand_radius`` standing for ``n = (r_w/r_h)²`` hairs.

    ``E_w π r_w⁴/4 = κ · n · E_h π r_h⁴/4``, i.e. ``E_w = κ E_h (r_h / r_w)²`` with ``κ = cohesion``
    (:data:`WISP_COHESION`; ``κ = 1`` = uncoupled hairs of equal mass per length and total bending stiffness).
    """
    return cohesion * hair_young * (hair_radius / strand_radius) ** 2


def _require(cond: bool, field_name: str, msg: str, value: object) -> None:
    if not cond:
        raise ValueError(f"WigConfig.{field_name} {msg}, got {value!r}")


def _finite(x: object) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(float(x))


@dataclass(frozen=True)
class WigConfig:
    """Geometry, material and preparation of one wig (all lengths in metres).

    Parameters
    ----------
    name : str
        Preset name or a label for a custom wig (part of the cache key).
    curliness : float
        ``R_C = R / P`` (thesis eq. 3.1), in ``[0, 1]``; 0 = straight strands.
    curl_radius : float
        Helix radius ``R`` of every strand's rest shape (ignored for ``curliness = 0``). The pitch is
        ``P = R / R_C``.
    length : float
        Arc length of a strand (hair length pulled straight). The hanging (axial) length of the rest shape is
        ``length / √(1 + (2π R_C)²)``.
    n_strands : int
        Number of wisps (≥ 2); ``n_strands − 3·n_triples`` must be even (the rest are pairs).
    n_triples : int
        Number of 3-strand groups (the thesis sees mostly pairs and a few triples, Fig. 2.1d). A comb parts strands
        only by where they hang across it, so one tine through a triple parts one strand from the other two, whose
        link stays; ``HairBrush-v3`` sets 0 (docs/detangling.md, *What holds the link under v2*).
    strand_radius : float
        Wisp radius ``r_w`` (contact, mass and stiffness).
    young : float or None
        Young's modulus of a wisp [Pa]; ``None`` = :func:`wisp_young` (``E_h (r_h / r_w)²``).
    density : float
        Mass density [kg/m³] (keratin ≈ 1300).
    damping : float
        Rayleigh damping of bending/torsion [s].
    quadratic_damping : float
        Quadratic damping of bending/torsion [s²] (chain strands; :class:`hairbrush_env.rods.RodSpec`): a hinge
        turning at ω feels ``−quadratic_damping · k · ω|ω|``. Damps a curl whipping off a tine, barely a pull.
    drag_density : float
        Density ρ [kg/m³] of a medium whose quadratic drag ``−½ ρ ℓ d |v| v`` acts on every strand segment while
        it is brushed (:class:`hairbrush_env.hair.drag.StrandDrag`; chain strands; 0 = none, the default). Takes
        out the momentum mass scaling gives a curl springing off a tine.
    drag_free_speed : float
        Dead zone of that drag [m/s] (≥ 0): it acts only on the part of a segment's speed above this, leaving a
        pull slower than it alone (0 = none, the default).
    drag_normal_only : bool
        Let that drag act on the velocity component across each segment only (the cross-flow principle of a
        slender cylinder's pressure drag), not along it: a curl turning about its own axis to let a tine through then
        feels only ``sin² λ`` of it (λ its lead angle), a strand sliding along itself none (False, the default: on
        the whole velocity).
    friction : float
        Sliding friction of hair contacts (hair on hair / nylon ≈ 0.2–0.4).
    edges_per_turn : int
        Edges per curl turn (≥ 4; the Gauss link of polygonal helices equals the turn count from 4 on; a chain's curl
        stiffness is within 10 % from 8 on, :mod:`hairbrush_env.studies.rod_validation`).
    min_edges, max_edges : int
        Bounds of the per-strand edge count (straight strands use ``min_edges``).
    handedness : {+1, -1}
        Chirality shared by all strands (homochiral, thesis chapter 2).
    root_gap : float
        Minimum surface gap between strands of different groups in the rest layout.
    min_spacing : float
        Minimum lattice spacing of group axes. 40 mm (default): twice the comb's 20 mm tine pitch, so that a tine
        passes through every group axis and one between neighbouring groups, and wide enough that splayed curls of
        neighbouring groups do not interleave (``docs/detangling.md``).
    shake_seconds : float
        Simulated shaking time of the pre-brushed preparation (thesis: 10–15 s by hand; see :func:`shake`).
    settle_seconds : float
        Simulated settling time after shaking.
    shake_accel : float
        RMS-scale amplitude of the horizontal shaking acceleration [m/s²].
    shake_frequency : float
        Mean shaking frequency [Hz].
    rgba : tuple of float
        Hair colour.
    rod_kind : {"chain", "flex"}
        MuJoCo representation of the strands (:data:`hairbrush_env.rods.ROD_KINDS`); ``"flex"`` only for
        benchmarks against the wave-1 wig.
    rest_splay : float
        Angle [rad] by which every strand's stress-free shape is turned about the vertical through its root
        (chains with curls only, :attr:`hairbrush_env.rods.RodSpec.root_rest_turn`). 0: the entwined rest curves are
        stress-free, so the elastic energy pulls combed-apart strands back into their double helix. ``ψ > 0`` moves
        each strand's own helix axis off the group's, ``2R sin(ψ/2)`` from where it is built (two strands of a pair
        then rest ``4R sin(ψ/2)`` apart): entwining becomes a prestressed state held by topology, as for real curls
        whose follicles do not share an axis. Default ``π/3``: the two strands of a pair rest side by side, just
        touching. ``ψ = 0`` keeps re-winding; with ``π/2`` each strand rests √2 R off its group axis, among the
        curls of the neighbouring groups, and repeated strokes wound the pairs up again (curly, seed 0: 0.25 of
        the link left after one full stroke, 0.56 after six; ``π/3``: 0.31 and 0.27; ``docs/detangling.md``,
        *Root orientation and splay*; that was a layout with triples and every pair curling from its roots). Under
        ``HairBrush-v5``'s layout (pairs only, straight below the roots) ``π/3`` rests a pair's two coils only R apart
        across the tines, and a full stroke leaves them hanging on one axis, interleaved; ``HairBrush-v6`` sets
        ``π/2`` (2R across the tines), after which repeated full strokes read less than the first on every series
        (``docs/detangling.md``, *HairBrush-v6*). Straight wigs ignore it; flex wigs need ``0``.
    root_twist_first : bool
        Root hinges in the order twist, bend1, bend2 (:attr:`hairbrush_env.rods.RodSpec.root_twist_first`; default
        ``False``: bend1, twist, bend2 as at every vertex). A strand that hangs straight below its root
        (:attr:`root_run_min` > 0) is turned by ``rest_splay`` purely about its own tangent, so its rest twist is
        ``rest_splay``; the default order puts ``π/2`` on the hinges' gimbal lock (two bending axes aligned, one
        bending direction lost at the root), the twist-first order at zero middle angle.
    group_rows : int or None
        Rows of groups along the brush's depth axis (x); the columns follow. ``None``: about ``√(n_groups/1.5)``
        (wider than deep). Default 1: a curtain one group deep, in which no tine collects strands of several groups
        along its length (deeper wigs let the brush wind neighbouring groups together).
    mass_scale : float
        Inertia multiplier ``s >= 1`` of chain strands (:attr:`hairbrush_env.rods.RodSpec.mass_scale`; flex wigs
        ignore it): ``s`` times the mass and rotational inertia at the same weight, so that taut strands do not sink
        into each other (*Mass scaling* in :mod:`hairbrush_env.hair`). The preparation's shake forces the real mass
        (``density``), not the scaled one.
    root_run : float
        Straight run of curled strands below their roots, in curl pitches, spread over the groups: group ``g`` hangs
        straight for ``root_run · u_g · P`` of its length, ``u_g = frac(g φ)`` (φ the golden ratio: neighbouring
        groups far apart in ``[0, 1)``), before its helix starts, as locks whose curl sets in at different
        distances from the scalp. Default 0: every group curls from its roots. In a curtain one group deep the groups
        then share one helix phase at every height, so a comb inserted at some heights meets every pair head on and
        parts none of them (curly, seed 0: 0 of 12 parted at 29.7 mm below the roots, 12 of 12 at 27.9 mm;
        ``scripts/probe_insertion.py``, ``docs/detangling.md``, *Where the comb goes in*). ``0.5`` spreads the pairs'
        phases over half a turn, every phase a pair can take (its two strands are half a turn apart). A group's
        helix is shorter by its run, so its link is lower by up to ``root_run`` turns.
    root_run_min : float
        Straight run [m] every curled group has below its roots before the spread of :attr:`root_run` (default 0).
        A full stroke's tines go in some 8 mm below the roots; a group that curls above them holds link no stroke
        combs, and its top coils meet the tines head on as they go in (coily under ``HairBrush-v4``: 7 of 12 pairs
        parted at the insertion; with 12 mm here, 12 of 12: ``docs/detangling.md``, *HairBrush-v5*).
    self_collision : bool
        Contacts between non-adjacent segments of the same strand (:attr:`hairbrush_env.rods.RodSpec.selfcollide`).
        Off by default: then a strand's own segments can pass through each other, and brushing makes them (curly,
        seed 0: 5–99 segment pairs on 1–12 strands overlapping by more than half a diameter in five of six full
        strokes, ``scripts/probe_self_contact.py``; ``docs/detangling.md``, *Strands pass through themselves*).
    """

    name: str = "custom"
    curliness: float = 0.5
    curl_radius: float = 0.008
    length: float = 0.20
    n_strands: int = 24
    n_triples: int = 2
    strand_radius: float = 8e-4
    young: float | None = None
    density: float = 1300.0
    damping: float = 0.02
    quadratic_damping: float = 0.0
    drag_density: float = 0.0
    drag_free_speed: float = 0.0
    drag_normal_only: bool = False
    friction: float = 0.3
    edges_per_turn: int = 8
    min_edges: int = 12
    max_edges: int = 32
    handedness: int = 1
    root_gap: float = 1.5e-3
    min_spacing: float = 0.04
    shake_seconds: float = 1.0
    settle_seconds: float = 1.0
    shake_accel: float = 6.0
    shake_frequency: float = 3.0
    rgba: tuple[float, float, float, float] = HAIR_RGBA
    rod_kind: rods.RodKind = "chain"
    rest_splay: float = math.pi / 3
    root_twist_first: bool = False
    group_rows: int | None = 1
    mass_scale: float = MASS_SCALE
    self_collision: bool = False
    root_run: float = 0.0
    root_run_min: float = 0.0

    def __post_init__(self) -> None:
        _require(
            isinstance(self.name, str) and bool(self.name), "name", "must be a non-empty string", self.name
        )
        for f in (
            "curliness",
            "curl_radius",
            "length",
            "strand_radius",
            "density",
            "damping",
            "quadratic_damping",
            "drag_density",
            "drag_free_speed",
            "friction",
            "root_gap",
            "min_spacing",
            "shake_seconds",
            "settle_seconds",
            "shake_accel",
            "shake_frequency",
        ):
            _require(_finite(getattr(self, f)), f, "must be a finite number", getattr(self, f))
        _require(0.0 <= self.curliness <= 1.0, "curliness", "(R/P) must be in [0, 1]", self.curliness)
        _require(self.curl_radius > 0.0, "curl_radius", "must be > 0", self.curl_radius)
        _require(self.length > 0.0, "length", "must be > 0", self.length)
        _require(self.strand_radius > 0.0, "strand_radius", "must be > 0", self.strand_radius)
        if self.young is not None:
            _require(_finite(self.young) and self.young > 0.0, "young", "must be > 0 or None", self.young)
        _require(self.density > 0.0, "density", "must be > 0", self.density)
        _require(
            _finite(self.mass_scale) and self.mass_scale >= 1.0, "mass_scale", "must be >= 1", self.mass_scale
        )
        for f in (
            "damping",
            "quadratic_damping",
            "drag_density",
            "drag_free_speed",
            "friction",
            "root_gap",
            "shake_seconds",
            "settle_seconds",
            "shake_accel",
        ):
            _require(getattr(self, f) >= 0.0, f, "must be >= 0", getattr(self, f))
        _require(self.min_spacing > 0.0, "min_spacing", "must be > 0", self.min_spacing)
        _require(self.shake_frequency > 0.0, "shake_frequency", "must be > 0", self.shake_frequency)
        for f in ("n_strands", "n_triples", "edges_per_turn", "min_edges", "max_edges"):
            v = getattr(self, f)
            _require(isinstance(v, (int, np.integer)) and not isinstance(v, bool), f, "must be an integer", v)
        _require(self.n_strands >= 2, "n_strands", "must be >= 2", self.n_strands)
        _require(
            self.group_rows is None
            or (
                isinstance(self.group_rows, (int, np.integer))
                and not isinstance(self.group_rows, bool)
                and self.group_rows >= 1
            ),
            "group_rows",
            "must be an integer >= 1 or None",
            self.group_rows,
        )
        _require(self.n_triples >= 0, "n_triples", "must be >= 0", self.n_triples)
        rest = self.n_strands - 3 * self.n_triples
        _require(
            rest >= 0 and rest % 2 == 0,
            "n_triples",
            f"must leave an even, non-negative number of strands for pairs (n_strands={self.n_strands})",
            self.n_triples,
        )
        _require(self.edges_per_turn >= 4, "edges_per_turn", "must be >= 4", self.edges_per_turn)
        _require(self.min_edges >= 2, "min_edges", "must be >= 2", self.min_edges)
        _require(self.max_edges >= self.min_edges, "max_edges", "must be >= min_edges", self.max_edges)
        _require(self.handedness in (1, -1), "handedness", "must be +1 or -1", self.handedness)
        _require(
            isinstance(self.self_collision, bool),
            "self_collision",
            "must be True or False",
            self.self_collision,
        )
        _require(len(self.rgba) == 4, "rgba", "must have 4 entries", self.rgba)
        _require(
            _finite(self.root_run) and 0.0 <= self.root_run <= 1.0,
            "root_run",
            "must be in [0, 1] curl pitches",
            self.root_run,
        )
        _require(
            _finite(self.root_run_min) and 0.0 <= self.root_run_min < self.length,
            "root_run_min",
            "must be in [0, length) m",
            self.root_run_min,
        )
        _require(
            self.rod_kind in rods.ROD_KINDS, "rod_kind", f"must be one of {rods.ROD_KINDS}", self.rod_kind
        )
        _require(
            _finite(self.rest_splay) and abs(self.rest_splay) <= math.pi,
            "rest_splay",
            "must be in [-π, π]",
            self.rest_splay,
        )
        _require(
            isinstance(self.root_twist_first, bool),
            "root_twist_first",
            "must be a bool",
            self.root_twist_first,
        )
        _require(
            not self.root_twist_first or self.rod_kind == "chain",
            "root_twist_first",
            "needs rod_kind='chain'",
            self.root_twist_first,
        )
        _require(
            self.rest_splay == 0.0 or self.rod_kind == "chain",
            "rest_splay",
            "needs rod_kind='chain'",
            self.rest_splay,
        )
        _require(
            self.quadratic_damping == 0.0 or self.rod_kind == "chain",
            "quadratic_damping",
            "needs rod_kind='chain'",
            self.quadratic_damping,
        )
        _require(
            self.drag_density == 0.0 or self.rod_kind == "chain",
            "drag_density",
            "needs rod_kind='chain'",
            self.drag_density,
        )
        _require(
            self.drag_free_speed == 0.0 or self.drag_density > 0.0,
            "drag_free_speed",
            "needs drag_density > 0 (it is the dead zone of that drag)",
            self.drag_free_speed,
        )
        _require(
            isinstance(self.drag_normal_only, bool),
            "drag_normal_only",
            "must be True or False",
            self.drag_normal_only,
        )
        _require(
            not self.drag_normal_only or self.drag_density > 0.0,
            "drag_normal_only",
            "needs drag_density > 0 (it says which velocity that drag acts on)",
            self.drag_normal_only,
        )
        if self.curliness > 0.0:
            # A curl tighter than the wisp itself cannot exist (neighbouring turns would overlap).
            _require(
                self.pitch > 4.0 * self.strand_radius,
                "curl_radius",
                f"gives a pitch P = R/R_C = {self.pitch:.4g} m below 4 strand radii",
                self.curl_radius,
            )
            _require(
                self.curl_radius > 2.0 * self.strand_radius,
                "curl_radius",
                "must exceed 2 strand radii (entwined strands sit 2R apart)",
                self.curl_radius,
            )

    # ---------------------------------------------------------------------------------------- derived
    @property
    def pitch(self) -> float:
        """Helix pitch ``P = R / R_C`` [m] (``inf`` for straight hair)."""
        return self.curl_radius / self.curliness if self.curliness > 0 else math.inf

    @property
    def arc_per_turn(self) -> float:
        """Arc length of one curl turn ``√((2πR)² + P²)``."""
        return math.hypot(2.0 * math.pi * self.curl_radius, self.pitch) if self.curliness > 0 else math.inf

    @property
    def turns(self) -> float:
        """Curl turns per strand = link of every entwined pair (``q₀ = l₀/P``, eq. 3.2, with the axial length)."""
        return self.length / self.arc_per_turn if self.curliness > 0 else 0.0

    def root_run_length(self, group: int) -> float:
        """Length [m] for which ``group`` hangs straight below its roots before it curls (:attr:`root_run`)."""
        if self.curliness <= 0 or (self.root_run == 0.0 and self.root_run_min == 0.0):
            return 0.0
        return self.root_run_min + self.root_run * self.pitch * ((group * _GOLDEN) % 1.0)

    @property
    def hanging_length(self) -> float:
        """Axial (vertical) extent of the rest shape [m] (of the longest-hanging group with :attr:`root_run`)."""
        if self.curliness <= 0:
            return self.length
        run = max((self.root_run_length(g) for g in range(self.n_groups)), default=0.0)
        return run + (self.length - run) / self.arc_per_turn * self.pitch

    @property
    def n_edges(self) -> int:
        """Edges per strand: ``edges_per_turn`` per turn, clipped to ``[min_edges, max_edges]``."""
        return int(min(self.max_edges, max(self.min_edges, math.ceil(self.edges_per_turn * self.turns))))

    @property
    def n_groups(self) -> int:
        return self.n_triples + (self.n_strands - 3 * self.n_triples) // 2

    @property
    def young_modulus(self) -> float:
        """Young's modulus actually used [Pa]."""
        return wisp_young(self.strand_radius) if self.young is None else float(self.young)

    def replace(self, **changes: object) -> WigConfig:
        """A copy with ``changes`` applied (validated)."""
        return dataclasses.replace(self, **changes)

    def digest(self) -> str:
        """Stable hash of all fields (for cache keys)."""
        fields = dataclasses.asdict(self)
        # Fields added after states were first cached count only when set, so caches of older wigs stay valid.
        for name in _LATE_FIELDS:
            if fields[name] == 0.0:
                del fields[name]
        blob = json.dumps(fields, sort_keys=True, default=float)
        return hashlib.sha256(blob.encode()).hexdigest()[:16]


_LATE_FIELDS = (
    "quadratic_damping",
    "drag_density",
    "drag_free_speed",
    "drag_normal_only",
    "root_run",
    "root_run_min",
    "root_twist_first",
)
_GOLDEN = 0.5 * (1.0 + math.sqrt(5.0))

# Presets: straightest first. Lengths differ like the thesis's wig set (Fig. 3.10): curlier wigs are shorter when
# hanging (curl "shrinkage" = 1 − 1/√(1 + (2πR_C)²)) even where the pulled-straight length is similar.
PRESETS: Mapping[str, WigConfig] = {
    "straight": WigConfig(name="straight", curliness=0.0, length=0.31, n_triples=0),
    "wavy": WigConfig(name="wavy", curliness=0.15, curl_radius=0.014, length=0.28),
    "loose_curl": WigConfig(name="loose_curl", curliness=0.3, curl_radius=0.013, length=0.26),
    "curly": WigConfig(name="curly", curliness=0.5, curl_radius=0.012, length=0.25),
    "tight_curl": WigConfig(name="tight_curl", curliness=0.65, curl_radius=0.012, length=0.27),
    "coily": WigConfig(name="coily", curliness=0.8, curl_radius=0.012, length=0.30),
}
"""Named wigs, ordered straightest → curliest (``R_C`` 0 → 0.8)."""

DEFAULT_WIG = "curly"

# The train / held-out split of RL (issue #12): agents train on presets at shake seeds 0-3 and are evaluated on wigs
# they never saw, each between two presets in curliness R/P and in length, at shake seeds no training env uses.
TRAIN_WIGS: tuple[str, ...] = ("wavy", "loose_curl", "curly", "tight_curl", "coily")
TRAIN_WIG_SEEDS: tuple[int, ...] = (0, 1, 2, 3)
HELD_OUT_WIGS: Mapping[str, WigConfig] = {
    # between wavy (0.15, 0.28 m) and loose_curl (0.30, 0.26 m)
    "held_out_wavy": WigConfig(name="held_out_wavy", curliness=0.22, curl_radius=0.0135, length=0.27),
    # between loose_curl (0.30, 0.26 m) and curly (0.50, 0.25 m)
    "held_out_curly": WigConfig(name="held_out_curly", curliness=0.4, curl_radius=0.0125, length=0.255),
    # between curly (0.50, 0.25 m) and tight_curl (0.65, 0.27 m)
    "held_out_tight": WigConfig(name="held_out_tight", curliness=0.58, curl_radius=0.012, length=0.26),
}
"""Custom wigs no training run sees (resolved by name like the presets: ``get_wig("held_out_curly")``)."""
HELD_OUT_SEEDS: tuple[int, ...] = (100, 101, 102)
"""Shake seeds of the held-out evaluation (pre-brushed states no training env draws)."""

WIG_SETS: Mapping[str, tuple[str, ...]] = {
    "all": tuple(PRESETS),
    "train": TRAIN_WIGS,
    "held_out": tuple(HELD_OUT_WIGS),
}
"""Named sets of wigs accepted wherever a comma-separated list of wig names is."""


def wig_names(text: str, *, sets: Sequence[str] = tuple(WIG_SETS), held_out: bool = True) -> list[str]:
    """Wig names of ``text``: comma-separated preset (and, with ``held_out``, held-out) names or set names from
    ``sets`` (``all`` presets, ``train``, ``held_out``), e.g. ``all,held_out``; repeats are dropped, order kept.
    ``ValueError`` lists the valid names."""
    valid = [*PRESETS, *HELD_OUT_WIGS] if held_out else list(PRESETS)
    names: list[str] = []
    bad: list[str] = []
    for item in (w.strip() for w in text.split(",")):
        if not item:
            continue
        expanded = list(WIG_SETS[item]) if item in sets else [item]
        bad += [w for w in expanded if w not in valid]
        names += [w for w in expanded if w in valid and w not in names]
    if not names or bad:
        extra = "".join(f", or {s!r}" for s in sets)
        raise ValueError(f"unknown wig {', '.join(bad) or repr(text)}; valid: {', '.join(valid)}{extra}")
    return names


def brushing_seeds(wigs: Sequence[str | WigConfig]) -> tuple[int, ...]:
    """Pre-brushed states (shake seeds) a set of wigs is brushed from: the held-out seeds when every wig is a
    held-out one (RL's test set, never seen in training), the training seeds otherwise."""
    names = [w for w in wigs if isinstance(w, str)]
    return HELD_OUT_SEEDS if names and all(w in HELD_OUT_WIGS for w in names) else TRAIN_WIG_SEEDS


WAVE1_COHESION = 50.0
"""``κ`` of the first release's wigs (calibrated on its paddle brush, whose strokes pushed whole groups aside)."""


def wave1_wig(wig: str | WigConfig) -> WigConfig:
    """The first release's version of a wig, kept as a benchmark case: DER flex strands at 5 edges per curl turn
    (≤ 16), ``κ = 50``, the compact lattice (6 mm minimum spacing, about ``√(n_groups/1.5)`` rows) and the entwined
    rest curves stress-free (``rest_splay = 0``). Brushed with :func:`hairbrush_env.scene.wave1_scene`."""
    w = get_wig(wig)
    return w.replace(
        rod_kind="flex",
        edges_per_turn=5,
        max_edges=16,
        young=wisp_young(w.strand_radius, cohesion=WAVE1_COHESION),
        min_spacing=6e-3,
        group_rows=None,
        rest_splay=0.0,
        mass_scale=1.0,
    )


def get_wig(wig: str | WigConfig) -> WigConfig:
    """Resolve a preset or held-out wig name (or pass a :class:`WigConfig` through).

    Raises
    ------
    ValueError
        Unknown name (the message lists the valid names).
    """
    if isinstance(wig, WigConfig):
        return wig
    if isinstance(wig, str) and wig in PRESETS:
        return PRESETS[wig]
    if isinstance(wig, str) and wig in HELD_OUT_WIGS:
        return HELD_OUT_WIGS[wig]
    raise ValueError(f"wig: unknown preset {wig!r}; valid names: {', '.join([*PRESETS, *HELD_OUT_WIGS])}")
