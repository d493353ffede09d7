"""Procedural wigs: curled, topologically entangled hair wisps as MuJoCo discrete elastic rods.

Model (thesis chapter 2 minimal model, used for the wigs of chapter 3)
----------------------------------------------------------------------
A wig is a set of *groups*, each a bundle of 2 (pair) or 3 (triple) strands that are **entwined**: they are
coaxial homochiral helices of the wig's curl radius ``R`` and pitch ``P``, phase-shifted by ``2π/k`` about a
common axis. Two such helices with ``N`` shared turns have open-curve link ``Lk ≈ N`` (one link per pitch, the
double helix of Fig. 2.2 / 3.2a), so the ground truth link of every entwined pair is the number of turns they
share, and ``q₀ = l₀ / P`` (eq. 3.2) per pair. The curliness of the wig is ``R_C = R / P`` (eq. 3.1).

Strands of *different* groups must not be linked. For two vertical helices of equal ``R, P`` with axes ``d``
apart and phase difference ``Δφ``, the horizontal vector between points at equal height is
``D + c·e(φ(z) + ψ)`` with ``|D| = d`` and ``c = 2R sin(Δφ/2)``: it winds around the origin (``Lk ≈ N``) iff
``c > d`` and otherwise only wobbles (``Lk ≈ 0``); its length never drops below ``|d − c|``. The group axes are
therefore put on a square lattice with alternating phase offsets (0, π/2 — a checkerboard, which lowers the
largest cross-group ``c`` from ``2R`` to ``√2 R``) and the lattice spacing is the smallest one for which every
cross-group pair of rest curves is unlinked and at least ``2r + root_gap`` apart (checked numerically by
:func:`wig_layout`). Entanglement is thus purely topological and known exactly at build time.

Wisp scaling (guide strands standing for a lock of hair)
--------------------------------------------------------
Real hair (``r_h ≈ 40 µm``, ``E_h ≈ 4 GPa``) is far too thin and stiff-per-mass for a millisecond step. A wisp
of radius ``r_w`` stands for ``n = (r_w / r_h)²`` hairs (same mass per length with the keratin density). Its bending
stiffness is ``B_w = κ · n · B_h`` (:func:`wisp_young`: ``E_w = κ E_h (r_h / r_w)²``), where the *cohesion* ``κ``
runs from 1 (``n`` uncoupled hairs) to ``n`` (hairs bonded into one solid fibre). ``κ`` is the force-scale
calibration (:data:`WISP_COHESION` = 12.5, ``E_w = 125 MPa`` at the default ``r_w = 0.8 mm`` = 400 hairs): chapter 2
scales the tine force as ``f = F l₀² / B`` with ``f_max ~ 5–70`` per double helix (Figs 2.2–2.4). A coarse wisp helix
(``R/r = 15``, one wisp turn standing for many real turns, few contacts per turn) jams far less than a real curl, so
``κ ≫ 1``; forces grow about linearly in ``κ``. The wave-1 wig used ``κ = 50`` (:data:`WAVE1_COHESION`) under a soft
paddle brush that pushed whole groups aside. Under the comb, whose tines split every pair, ``κ = 12.5`` puts the
first full stroke through the curled presets at 1.5–6.6 N (means over seeds 0–2; curly's single strokes up to 8.8 N),
below the thesis's pain threshold ``F_T = 10 N``. Stiffer
wisps read more (``κ = 16``: 7–11 N; 20: 8–10.5 N) but comb out less (curly, seed 0: 0.46 of the entanglement left
after six strokes at ``κ = 16``) and are squeezed into each other more (``docs/detangling.md``).

Brush and wig scale, chosen together (``docs/detangling.md``): the link of an entwined pair leaves through the free
ends only where a tine passes *between* its strands (chapter 2). The groups stand in a curtain one group deep
(``group_rows = 1``) at 40 mm spacing, and the default comb (:data:`hairbrush_env.brush.BRUSH_PRESETS`) has rigid
tines at half that spacing: one through every group axis, one between neighbouring groups, each 60 mm long (the
curtain's depth plus the splayed curls). The tine gap (20 mm − 2 × 1 mm) is ~10 wisp diameters and 0.8 of a curl
diameter, so a tine parts a pair without pinching a strand between two tines (a wisp needs
``2 r_w + 2 r_t + Σ margins ≈ 5 mm``), while every curl (diameter ``2R = 24–28 mm``) is wider than the gap and is
caught. The spacing is twice the diameter of the curl so that splayed strands (axes ``√2 R`` off the group's) of
neighbouring groups do not interleave.

Discretization and speed: strands are body chains by default (:mod:`hairbrush_env.rods`, ``rod_kind``), with
:attr:`WigConfig.edges_per_turn` = 8 edges per curl turn, capped at ``max_edges`` = 32 per strand. At 8 edges per turn
a chain helical spring is within 10 % of ``G d⁴ / (8 D³ N)`` (+8.3 %; the DER flex is +53 % at 8 and needs ~20),
so the curls hold their stiffness, and the link of an entwined pair equals its number of turns. The wave-1 flex wig
(``rod_kind="flex"``, 5 edges per turn, ≤ 16 edges) is kept for side-by-side benchmarks (``docs/rods.md``).
The 1 ms contact step that keeps strands from passing through each other sets the cost of a stroke
(``scripts/benchmark_sim.py``). Hanging length is ``≤ 4 P`` for curled presets: the curly presets use large curls
(R = 12 mm) so that they hang 6–8 cm and a stroke from 8 mm below the roots covers most of them (a wisp turn stands
for many real curl turns).

Prestress (``WigConfig.rest_splay``): built as coaxial helices with stress-free rest curves, the entwined state is
the *only* stress-free one (a helix is fixed by its root frame), so combed-apart strands wind themselves back up.
Turning each strand's stress-free shape about the vertical through its root moves its own helix axis off the group's,
and entwining becomes a prestressed state held by topology (``docs/detangling.md``).

Pre-brushed state (thesis §3.4: wigs are turned upside down and shaken for 10–15 s)
-----------------------------------------------------------------------------------
:func:`shake` moves the head in the hair's frame: shaking the scalp with acceleration ``a(t)`` is *exactly*
equivalent, in the head frame, to a uniform inertial body force ``−m a(t)`` on every hair vertex, applied through
``xfrc_applied``. ``a(t)`` is a seeded sum of sinusoids (mostly horizontal, with vertical components that
briefly unload gravity), followed by a settling phase. The result depends only on (wig, seed, model), so it is
cached (:class:`StateCache`, in memory and optionally on disk) as the full MuJoCo state
(``mjSTATE_INTEGRATION``, which includes ``mjSTATE_PLASTIC``, the rods' reference frames).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np

from . import collision, rods
from .topology import linking_number
from .topology.proximity import close_pair_proximity, polyline_distance

__all__ = [
    "CROSS_LINK_THRESHOLD",
    "DEFAULT_WIG",
    "HAIR_GEOM_GROUP",
    "HAIR_RGBA",
    "PRESETS",
    "WISP_COHESION",
    "Entanglement",
    "StateCache",
    "WigConfig",
    "WigLayout",
    "add_wig",
    "entanglement",
    "get_wig",
    "min_distance_matrix",
    "shake",
    "wave1_wig",
    "wig_layout",
    "wisp_young",
]

HAIR_GEOM_GROUP = 1
"""Visualisation group of the strands (visible by default; the scene's parts use groups 2–5)."""

HAIR_RGBA = (0.30, 0.17, 0.08, 1.0)
"""Medium brown: dark enough to stand out against the light backdrop of the scene's ``webcam``."""

REAL_HAIR_RADIUS = 40e-6
"""Radius of a human scalp hair [m] (thesis: r is approximately constant for human hair)."""

REAL_HAIR_YOUNG = 4e9
"""Young's modulus of keratin hair [Pa]."""

# Contact parameters for thin rods. rods.py measured rod-rod penetration ≤ 10 µm with solref 0.004 for free
# rods, but a wisp trapped between bristles is held by its (much stiffer, 1e-4) edge equality, and the solver then
# lets the 0.004 contact yield: strands were pulled through 1.5 mm bristles (centerline distance 0). With 1e-3
# (and refsafe disabled by the scene, which would otherwise soften it back to ~2 dt) the hair–bristle centerline
# distance stayed ≥ 0.7 mm (> the 1.15 mm half-sum of radii in most samples; see the scene tests).
CONTACT_SOLREF = (1e-3, 1.0)
CONTACT_SOLIMP = (0.95, 0.99, 1e-4, 0.5, 2.0)
# Contact margin of each wisp geom. MuJoCo 4.0.1 ADDS the margins of a contact's two geoms, so two wisps touch from
# 2 × 0.5 = 1 mm surface gap and a wisp and a bristle from 0.5 + 1 = 1.5 mm (scene.TOOL_CONTACT_MARGIN); contacts hold
# their load as a stiff spring about ``dist = margin``. Without it a coily wisp pair under full-stroke clamp loads sank
# 1.3 mm into each other (issue #3); with it the centerline distance stays above half the sum of radii
# (tests/test_scene.py::test_no_pass_through_*).
CONTACT_MARGIN = 5e-4


CROSS_LINK_THRESHOLD = 0.4
"""``|Lk|`` from which two strands of different groups count as linked: the thesis's link-interaction threshold
(Fig. 2.5b), also the bound :func:`wig_layout` keeps every cross-group pair below at rest."""

WISP_COHESION = 12.5
"""Force-scale calibration ``κ = B_w / (n B_h)`` of a wisp (module docstring, *Wisp scaling*).

``κ = 1``: the ``n`` hairs of a wisp bend independently; ``κ = n``: they are bonded into one solid keratin fibre. 12.5
(``E_w = 125 MPa`` at ``r_w = 0.8 mm``): the comb's first full stroke through the curled presets reads 1.5–6.6 N
(means over seeds) and repeated strokes comb most of curly's link out; stiffer wisps read more but comb out less
(``docs/detangling.md``)."""


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


# ------------------------------------------------------------------------------------------------ config
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
        Number of 3-strand groups (the thesis sees mostly pairs and a few triples, Fig. 2.1d).
    strand_radius : float
        Wisp radius ``r_w`` (contact, mass and stiffness).
    young : float or None
        Young's modulus of a wisp [Pa]; ``None`` = :func:`wisp_young` (``E_h (r_h / r_w)²``).
    density : float
        Mass density [kg/m³] (keratin ≈ 1300).
    damping : float
        Rayleigh damping of bending/torsion [s].
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
        whose follicles do not share an axis. Default ``π/2``: the splay with which repeated strokes remove the link
        and force falls stroke by stroke (``ψ = 0`` keeps re-winding, ``π/3`` stalls; ``docs/detangling.md``).
        Straight wigs ignore it; flex wigs need ``0``.
    group_rows : int or None
        Rows of groups along the brush's depth axis (x); the columns follow. ``None``: about ``√(n_groups/1.5)``
        (wider than deep). Default 1: a curtain one group deep, in which no tine collects strands of several groups
        along its length (deeper wigs let the brush wind neighbouring groups together).
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
    rest_splay: float = math.pi / 2
    group_rows: int | None = 1

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
        for f in ("damping", "friction", "root_gap", "shake_seconds", "settle_seconds", "shake_accel"):
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
        _require(len(self.rgba) == 4, "rgba", "must have 4 entries", self.rgba)
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
            self.rest_splay == 0.0 or self.rod_kind == "chain",
            "rest_splay",
            "needs rod_kind='chain'",
            self.rest_splay,
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

    @property
    def hanging_length(self) -> float:
        """Axial (vertical) extent of the rest shape [m]."""
        return self.turns * self.pitch if self.curliness > 0 else self.length

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
        blob = json.dumps(dataclasses.asdict(self), sort_keys=True, default=float)
        return hashlib.sha256(blob.encode()).hexdigest()[:16]


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
    """Wig names of ``text``: a set name from ``sets`` (``all`` presets, ``train``, ``held_out``) or comma-separated
    preset (and, with ``held_out``, held-out) names. ``ValueError`` lists the valid names."""
    if text in sets:
        return list(WIG_SETS[text])
    names = [w.strip() for w in text.split(",") if w.strip()]
    valid = [*PRESETS, *HELD_OUT_WIGS] if held_out else list(PRESETS)
    bad = [w for w in names if w not in valid]
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


# ------------------------------------------------------------------------------------------------ layout
@dataclass(frozen=True)
class WigLayout:
    """Rest geometry and ground-truth topology of a wig (coordinates in the root-plane frame: z up, roots at z=0).

    Attributes
    ----------
    wig : WigConfig
    names : tuple of str
        Rod name of every strand.
    groups : tuple of tuple of int
        Strand indices of each entwined group (pairs and triples).
    axes : np.ndarray
        ``(n_groups, 2)`` horizontal positions of the group axes.
    roots : np.ndarray
        ``(n_strands, 3)`` root positions.
    curves : tuple of np.ndarray
        Rest centerline of every strand, ``(n_edges + 1, 3)``.
    pairs : np.ndarray
        ``(n_pairs, 2)`` entwined strand pairs (all pairs within each group).
    pair_link : np.ndarray
        Open-curve Gauss link of each entwined pair in the rest shape (≈ ``± wig.turns``).
    spacing : float
        Lattice spacing of the group axes.
    turns : float
        Curl turns of the discretized (polygonal) strands, whose length is exactly ``wig.length``.
    min_cross_distance : float
        Smallest centerline distance between strands of different groups at rest.
    max_cross_link : float
        Largest ``|Lk|`` between strands of different groups at rest (should be ≪ 0.5).
    """

    wig: WigConfig
    names: tuple[str, ...]
    groups: tuple[tuple[int, ...], ...]
    axes: np.ndarray
    roots: np.ndarray
    curves: tuple[np.ndarray, ...]
    pairs: np.ndarray
    pair_link: np.ndarray
    spacing: float
    turns: float
    min_cross_distance: float
    max_cross_link: float

    @property
    def n_links(self) -> float:
        """Total ground-truth link ``Σ |Lk|`` over entwined pairs at rest."""
        return float(np.abs(self.pair_link).sum())

    @property
    def extent(self) -> tuple[np.ndarray, np.ndarray]:
        """Axis-aligned bounding box ``(lo, hi)`` of the rest curves."""
        allp = np.vstack(self.curves)
        return allp.min(axis=0), allp.max(axis=0)


def _strand_curve(axis: np.ndarray, phase: float, wig: WigConfig, radius: float, turns: float) -> np.ndarray:
    n = wig.n_edges
    if wig.curliness > 0:
        # Uniform in z is uniform in arc length on a helix, so all edges have the same rest length.
        depth = np.linspace(0.0, turns * wig.pitch, n + 1)
        phi = phase + wig.handedness * 2.0 * math.pi * depth / wig.pitch
    else:
        depth = np.linspace(0.0, wig.length, n + 1)
        phi = np.full(n + 1, phase)
    return np.column_stack([axis[0] + radius * np.cos(phi), axis[1] + radius * np.sin(phi), -depth])


def _polygon_turns(wig: WigConfig) -> float:
    """Turns of the *polygonal* helix (``n_edges`` chords) whose length is ``wig.length``.

    Chords are shorter than the arcs they cut (by ~ (Δφ)²/24 per edge, 3 % at 6 edges per turn), so the polygon
    gets slightly more turns than :attr:`WigConfig.turns` to keep the configured strand length.
    """
    if wig.curliness == 0:
        return 0.0
    n, r, p = wig.n_edges, wig.curl_radius, wig.pitch
    turns = wig.turns
    for _ in range(50):
        dphi = 2.0 * math.pi * turns / n
        chord = math.hypot(2.0 * r * math.sin(0.5 * dphi), p * turns / n)
        new = turns * wig.length / (n * chord)
        if abs(new - turns) < 1e-13 * turns:
            break
        turns = new
    return turns


_STRAIGHT_GROUP_RADIUS = 4e-3


def _grid(n: int, rows: int | None = None) -> tuple[list[tuple[int, int]], int, int]:
    # Rows along x (towards the brush), columns along y (across the brush): wider than deep, so that the
    # bristles reach through the curtain.
    rows = max(1, round(math.sqrt(n / 1.5))) if rows is None else min(rows, n)
    cols = math.ceil(n / rows)
    return [divmod(k, cols) for k in range(n)], rows, cols


def wig_layout(wig: WigConfig, *, prefix: str = "hair") -> WigLayout:
    """Place the entwined groups on the scalp and compute the rest curves and ground-truth links.

    The lattice spacing starts at ``max(min_spacing, √2 R + 2r + root_gap)`` and grows by 5 % until every
    cross-group pair of rest curves is at least ``2r + root_gap`` apart and unlinked (``|Lk| < 0.4``, the
    thesis's link-interaction threshold of Fig. 2.5b).
    """
    groups: list[tuple[int, ...]] = []
    k = 0
    for g in range(wig.n_groups):
        size = 3 if g < wig.n_triples else 2
        groups.append(tuple(range(k, k + size)))
        k += size
    cells, rows, cols = _grid(len(groups), wig.group_rows)
    r = wig.strand_radius
    # Straight hair: the strands of a group hang side by side across the curtain (phase π/2: along y), 8 mm apart, so
    # a comb tine through the group axis passes between them instead of wedging into a gap narrower than itself
    # next to the clamp (a 3.2 mm gap diverged at the first insertion).
    radius = wig.curl_radius if wig.curliness > 0 else _STRAIGHT_GROUP_RADIUS
    phases: list[float] = []
    for g, members in enumerate(groups):
        i, j = cells[g]
        # checkerboard: neighbours differ by π/2 (module docstring); straight groups have no link to keep apart
        offset = 0.5 * math.pi * ((i + j) % 2) if wig.curliness > 0 else 0.5 * math.pi
        phases.extend(offset + 2.0 * math.pi * m / len(members) for m in range(len(members)))
    owner = np.array([g for g, members in enumerate(groups) for _ in members])
    need = 2.0 * r + wig.root_gap
    turns = _polygon_turns(wig)
    spacing = max(wig.min_spacing, math.sqrt(2.0) * radius + need)
    for _ in range(60):
        axes = np.array(
            [[(i - 0.5 * (rows - 1)) * spacing, (j - 0.5 * (cols - 1)) * spacing] for i, j in cells]
        )
        curves = [_strand_curve(axes[owner[s]], phases[s], wig, radius, turns) for s in range(wig.n_strands)]
        dmin, lkmax = math.inf, 0.0
        for a in range(wig.n_strands):
            for b in range(a + 1, wig.n_strands):
                if (
                    owner[a] == owner[b]
                    or np.linalg.norm(axes[owner[a]] - axes[owner[b]]) > 2 * radius + 3 * need
                ):
                    continue  # far groups cannot touch or link
                dmin = min(dmin, polyline_distance(curves[a], curves[b]))
                if wig.curliness > 0:
                    lkmax = max(lkmax, abs(linking_number(curves[a], curves[b], closed=False)))
        if dmin >= need and lkmax < 0.4:
            break
        spacing *= 1.05
    else:  # pragma: no cover - the lattice always separates eventually
        raise RuntimeError("wig_layout: could not separate the groups")
    pairs = np.array(
        [(m[a], m[b]) for m in groups for a in range(len(m)) for b in range(a + 1, len(m))], dtype=int
    )
    links = np.array([linking_number(curves[i], curves[j], closed=False) for i, j in pairs])
    names = tuple(f"{prefix}{s}" for s in range(wig.n_strands))
    for c in curves:
        c.setflags(write=False)
    return WigLayout(
        wig=wig,
        names=names,
        groups=tuple(groups),
        axes=axes,
        roots=np.array([c[0] for c in curves]),
        curves=tuple(curves),
        pairs=pairs,
        pair_link=links,
        spacing=spacing,
        turns=turns,
        min_cross_distance=dmin,
        max_cross_link=lkmax,
    )


def add_wig(
    spec: mujoco.MjSpec,
    wig: str | WigConfig,
    *,
    parent_body: mujoco.MjsBody | str,
    root_offset: Sequence[float] = (0.0, 0.0, 0.0),
    prefix: str = "hair",
    hair_hair: bool = True,
) -> WigLayout:
    """Add every strand of ``wig`` as a clamped rod under ``parent_body``.

    Parameters
    ----------
    spec : mujoco.MjSpec
        Target spec (call :func:`hairbrush_env.rods.configure_rod_options` on it too, with the wig's ``rod_kind``).
    wig : str or WigConfig
        Preset name or config.
    parent_body : MjsBody or str
        Body holding the roots (e.g. the head's ``scalp``); its frame must have z up.
    root_offset : sequence of float
        Position of the root plane's centre in ``parent_body`` coordinates (e.g. the scalp site).
    prefix : str
        Strand names are ``<prefix><k>``.
    hair_hair : bool
        Hair–hair contact (``conaffinity`` includes HAIR). Without it strands pass through each other.

    Returns
    -------
    WigLayout
        The layout (in root-plane coordinates; add ``root_offset`` and the parent pose for world coordinates).
    """
    cfg = get_wig(wig)
    layout = wig_layout(cfg, prefix=prefix)
    off = np.asarray(root_offset, dtype=float).reshape(3)
    contype, conaffinity = collision.HAIR_GEOM_SELF_COLLIDING if hair_hair else collision.HAIR_GEOM
    for name, curve in zip(layout.names, layout.curves, strict=True):
        rods.add_rod(
            spec,
            rods.RodSpec(
                name=name,
                points=curve + off,
                radius=cfg.strand_radius,
                young=cfg.young_modulus,
                density=cfg.density,
                damping=cfg.damping,
                friction=cfg.friction,
                rgba=cfg.rgba,
                contype=contype,
                conaffinity=conaffinity,
                condim=3,
                contact_solref=CONTACT_SOLREF,
                contact_solimp=CONTACT_SOLIMP,
                margin=CONTACT_MARGIN,
                group=HAIR_GEOM_GROUP,
                kind=cfg.rod_kind,
                # straight strands have no curl whose axis could move: turning them would only twist the root
                root_rest_turn=float(cfg.rest_splay) if cfg.curliness > 0 else 0.0,
            ),
            parent=parent_body,
        )
    return layout


# ------------------------------------------------------------------------------------------ entanglement
class Entanglement:
    """Ground-truth entanglement of a compiled wig: ``Σ |open Lk|`` over its entwined pairs, plus the link made
    between any other two strands (``|Lk| ≥`` :data:`CROSS_LINK_THRESHOLD`).

    Parameters
    ----------
    model : mujoco.MjModel
    layout : WigLayout
        Layout returned by :func:`add_wig` (names and pairs).
    """

    def __init__(self, model: mujoco.MjModel, layout: WigLayout) -> None:
        self.layout = layout
        self.views = [rods.RodView(model, n) for n in layout.names]
        self.pairs = layout.pairs
        # Chains of one wig share their edge count: their vertices are one fancy-indexed read of data.xpos.
        self._chain_ids = (
            np.stack([v.bodies for v in self.views])
            if all(v.kind == "chain" for v in self.views) and len({v.n_points for v in self.views}) == 1
            else None
        )
        if self._chain_ids is not None:
            tips = np.array([2.0 * model.geom_size[model.body_geomadr[v.tip_body], 1] for v in self.views])
            self._tip_lengths = tips[:, None]
        # Strand pairs a < b that are not entwined, for the link the brush or the shake made (breakdown).
        n = len(self.views)
        entwined = np.zeros((n, n), dtype=bool)
        entwined[self.pairs[:, 0], self.pairs[:, 1]] = True
        self._other_pairs = np.nonzero(np.triu(~entwined, 1))

    def curves(self, data: mujoco.MjData) -> list[np.ndarray]:
        """Current centerlines of all strands."""
        return (
            list(self.curve_array(data))
            if self._chain_ids is not None
            else [v.vertices(data) for v in self.views]
        )

    def curve_array(self, data: mujoco.MjData) -> np.ndarray:
        """Current centerlines stacked as ``(n_strands, n_points, 3)`` (every strand of a wig has the same edges)."""
        if self._chain_ids is None:
            return np.stack([v.vertices(data) for v in self.views])
        ids = self._chain_ids
        out = np.empty((ids.shape[0], ids.shape[1] + 1, 3))
        out[:, :-1] = data.xpos[ids]
        tip_axis = data.xmat[ids[:, -1]].reshape(-1, 3, 3)[:, :, 0]
        out[:, -1] = out[:, -2] + tip_axis * self._tip_lengths
        return out

    def pair_links(self, data: mujoco.MjData, curves: list[np.ndarray] | None = None) -> np.ndarray:
        """Open-curve Gauss link of every entwined pair (signed)."""
        c = self.curves(data) if curves is None else curves
        return np.array([linking_number(c[i], c[j], closed=False) for i, j in self.pairs])

    def link_matrix(self, data: mujoco.MjData) -> np.ndarray:
        """Open-curve Gauss link of every pair of strands, ``(n, n)`` symmetric with a zero diagonal."""
        curves = self.curve_array(data)
        n = curves.shape[0]
        pairs, _, link = close_pair_proximity(curves, np.inf)
        out = np.zeros((n, n))
        out[pairs[:, 0], pairs[:, 1]] = link
        return out + out.T

    def breakdown(self, data: mujoco.MjData) -> tuple[float, float]:
        """``(entwined, made)``: ``Σ |Lk|`` over the entwined pairs, and over all other strand pairs whose
        ``|Lk| ≥`` :data:`CROSS_LINK_THRESHOLD` (link a brush or the shaking made between different groups)."""
        mat = np.abs(self.link_matrix(data))
        other = mat[self._other_pairs]
        return float(mat[self.pairs[:, 0], self.pairs[:, 1]].sum()), float(
            other[other >= CROSS_LINK_THRESHOLD].sum()
        )

    def __call__(self, data: mujoco.MjData) -> float:
        """Entanglement of the wig: ``Σ |Lk|`` over the entwined pairs plus every other pair linked
        ``≥`` :data:`CROSS_LINK_THRESHOLD` (:meth:`breakdown`), so a brush that tangles strands is seen doing it."""
        return float(sum(self.breakdown(data)))


def entanglement(model: mujoco.MjModel, data: mujoco.MjData, layout: WigLayout) -> float:
    """One-off :class:`Entanglement` reading (build an :class:`Entanglement` once for loops)."""
    return Entanglement(model, layout)(data)


def min_distance_matrix(curves: Sequence[np.ndarray]) -> np.ndarray:
    """Symmetric matrix of minimum centerline (segment–segment) distances between polylines (inf diagonal)."""
    n = len(curves)
    out = np.full((n, n), np.inf)
    for a in range(n):
        for b in range(a + 1, n):
            out[a, b] = out[b, a] = polyline_distance(curves[a], curves[b])
    return out


# ------------------------------------------------------------------------------------------ shake & cache
def shake_acceleration(wig: WigConfig, seed: int, t: np.ndarray) -> np.ndarray:
    """The seeded head acceleration ``a(t)`` [m/s²] of the pre-brushed preparation, shape ``(len(t), 3)``.

    Three sinusoids per axis with random frequencies around ``shake_frequency`` and random phases; the horizontal
    amplitude is ``shake_accel``, the vertical one half of it (it unloads gravity without turning the hair over,
    which would drive the strands into the skull). A raised-cosine envelope starts and ends the shake smoothly.
    """
    rng = np.random.default_rng(np.random.SeedSequence([int(seed), 0x5A4E]))
    t = np.asarray(t, dtype=float)
    out = np.zeros((t.size, 3))
    amp = wig.shake_accel * np.array([1.0, 1.0, 0.5]) / math.sqrt(3.0 / 2.0)
    for ax in range(3):
        f = wig.shake_frequency * rng.uniform(0.6, 1.6, 3)
        ph = rng.uniform(0.0, 2.0 * math.pi, 3)
        out[:, ax] = amp[ax] * np.sin(2.0 * math.pi * f[None, :] * t[:, None] + ph[None, :]).sum(axis=1)
    if wig.shake_seconds > 0:
        env = np.clip(np.minimum(t, wig.shake_seconds - t) / min(0.2, 0.5 * wig.shake_seconds), 0.0, 1.0)
        out *= (0.5 - 0.5 * np.cos(math.pi * env))[:, None]
    return out


def shake(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    wig: WigConfig,
    seed: int,
    *,
    strand_bodies: np.ndarray,
    on_step: object = None,
) -> None:
    """Run the seeded pre-brushed preparation in place (shake, then settle under gravity).

    Parameters
    ----------
    strand_bodies : np.ndarray
        Body ids of the moving hair vertices (they receive ``−m a(t)`` through ``xfrc_applied``).
    on_step : callable, optional
        ``on_step(model, data)`` after every step (e.g. to hold the arm's servo targets).
    """
    dt = model.opt.timestep
    n_shake = round(wig.shake_seconds / dt)
    n_settle = round(wig.settle_seconds / dt)
    acc = shake_acceleration(wig, seed, np.arange(n_shake) * dt)
    mass = model.body_mass[strand_bodies][:, None]
    for k in range(n_shake):
        data.xfrc_applied[strand_bodies, :3] = -mass * acc[k][None, :]
        mujoco.mj_step(model, data)
        if on_step is not None:
            on_step(model, data)  # type: ignore[operator]
    data.xfrc_applied[strand_bodies, :3] = 0.0
    for _ in range(n_settle):
        mujoco.mj_step(model, data)
        if on_step is not None:
            on_step(model, data)  # type: ignore[operator]


STATE_SPEC = mujoco.mjtState.mjSTATE_INTEGRATION
"""What is cached: the full integration state (time, qpos, qvel, act, ctrl, warm start, ..., incl. PLASTIC)."""


@dataclass
class StateCache:
    """Settled wig states per (wig digest, seed, model hash), in memory and optionally on disk.

    Parameters
    ----------
    directory : str or Path, optional
        If given, states are also written as ``<wig>-<digest>-s<seed>-<model>.npy`` (atomically) and read back by
        later processes.
    """

    directory: str | Path | None = None
    _memory: dict[tuple[str, int, str], np.ndarray] = field(default_factory=dict, repr=False)

    @staticmethod
    def model_hash(model: mujoco.MjModel) -> str:
        """SHA-256 (16 hex) of the compiled model's binary."""
        buf = np.zeros(mujoco.mj_sizeModel(model), dtype=np.uint8)
        mujoco.mj_saveModel(model, None, buf)
        return hashlib.sha256(buf.tobytes()).hexdigest()[:16]

    def _path(self, wig: WigConfig, seed: int, model_hash: str) -> Path | None:
        if self.directory is None:
            return None
        return Path(self.directory) / f"{wig.name}-{wig.digest()}-s{int(seed)}-{model_hash}.npy"

    def get(self, wig: WigConfig, seed: int, model_hash: str) -> np.ndarray | None:
        key = (wig.digest(), int(seed), model_hash)
        if key in self._memory:
            return self._memory[key]
        path = self._path(wig, seed, model_hash)
        if path is not None and path.is_file():
            state = np.load(path)
            self._memory[key] = state
            return state
        return None

    def put(self, wig: WigConfig, seed: int, model_hash: str, state: np.ndarray) -> None:
        state = np.array(state, dtype=float)
        state.setflags(write=False)
        self._memory[(wig.digest(), int(seed), model_hash)] = state
        path = self._path(wig, seed, model_hash)
        if path is not None:
            path.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".npy.tmp")
            with os.fdopen(fd, "wb") as fh:
                np.save(fh, state)
            os.replace(tmp, path)

    def clear(self) -> None:
        """Forget the in-memory states (files stay)."""
        self._memory.clear()


def get_state(model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
    """Full integration state (incl. plastic rod frames) of ``data``."""
    out = np.empty(mujoco.mj_stateSize(model, STATE_SPEC))
    mujoco.mj_getState(model, data, out, STATE_SPEC)
    return out


def set_state(model: mujoco.MjModel, data: mujoco.MjData, state: np.ndarray) -> None:
    """Restore a state from :func:`get_state` and recompute derived quantities (``mj_forward``)."""
    mujoco.mj_setState(model, data, np.asarray(state, dtype=float), STATE_SPEC)
    mujoco.mj_forward(model, data)
