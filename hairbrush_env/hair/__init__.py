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
:func:`wig_layout`). Entanglement is thus purely topological and known exactly at build time. A curtain one group
deep (``group_rows = 1``, the default) is the exception: there every group turns its roots across the curtain,
perpendicular to the comb's tines (pairs at ``y ± R``), because a tine parts two strands only by their ``y``; its
groups share one phase (``c = 2R``, still well below the 40 mm spacing).

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
first full stroke through the curled presets at 5.3–13.7 N (means over seeds 0–2; curly's, tight_curl's and
coily's above the thesis's pain threshold ``F_T = 10 N``, ``docs/wigs.md``). Stiffer
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

Mass scaling (``WigConfig.mass_scale``, default :data:`MASS_SCALE` = 10): a stroke is quasi-static (Fig. 3.8: a 4×
change of speed moves the maximum force by a few per cent), so the strands' inertia can be raised without changing
the forces that matter, as finite-element codes do for quasi-static problems. It matters for contact: a MuJoCo soft
contact of time constant ``τ`` acts like a spring of stiffness ``~ m_eff / τ²`` (``m_eff`` the effective mass of the
contact), and a wisp segment weighs ~25 mg, ``m/τ² ≈ 25 N/m`` at the 1 ms step (``τ`` cannot go below twice the
step). Strands taut between the roots and a tine sank into each other to 0.04 of the sum of radii; ten times the
inertia keeps them ≥ 0.86 apart at the same step and cost. MuJoCo's ``gravcomp`` takes the extra weight off again,
so strands hang and bend as ``density`` and ``young`` say (the static validations are unchanged), and the shake of
the preparation forces the real mass. A 2 ms step with ``s = 10`` halves the CPU but diverged in 2 of 6 series.
Caveat: at the default 0.1 m/s pull the mass-scaled stroke is *not* quasi-static (curly, b_l 0.67: 4.77, 5.15, 6.76,
8.98 N at 0.025, 0.05, 0.1, 0.2 m/s, against +12 to +23 % for 4× with the real mass), and the comb splits pairs
only with the scaled inertia: with the real mass the pairs near the roots are pushed aside between two tines and
nothing combs out (``docs/detangling.md``, *What the real mass does with the same comb*, *Fig. 3.8*).

Prestress (``WigConfig.rest_splay``): built as coaxial helices with stress-free rest curves, the entwined state is
the *only* stress-free one (a helix is fixed by its root frame), so combed-apart strands wind themselves back up.
Turning each strand's stress-free shape about the vertical through its root moves its own helix axis off the group's,
and entwining becomes a prestressed state held by topology (``docs/detangling.md``).

Pre-brushed state (thesis §3.4: wigs are turned upside down and shaken for 10–15 s)
-----------------------------------------------------------------------------------
:func:`shake` moves the head in the hair's frame: shaking the scalp with acceleration ``a(t)`` is *exactly*
equivalent, in the head frame, to a uniform inertial body force ``−m a(t)`` on every hair vertex, applied through
``xfrc_applied``. ``a(t)`` is a seeded sum of sinusoids (mostly horizontal, with vertical components that
briefly unload gravity), followed by a settling phase, all at the 1 ms contact step
(:meth:`hairbrush_env.scene.BrushingSim.settled_state`: at the 10 ms step the prestressed pairs passed through each
other and lost a third to two thirds of their link). The result depends only on (wig, seed, model), so it is
cached (:class:`StateCache`, in memory and optionally on disk) as the full MuJoCo state
(``mjSTATE_INTEGRATION``, which includes ``mjSTATE_PLASTIC``, the rods' reference frames).

Modules: :mod:`.config` (wisp material, :class:`WigConfig`, presets and wig sets), :mod:`.layout` (rest lattice and
curves), :mod:`.build` (:func:`add_wig`, contact parameters), :mod:`.entanglement_meter` (:class:`Entanglement`),
:mod:`.shaking` (the pre-brushed preparation) and :mod:`.state` (:class:`StateCache`). Every public name is
re-exported here: use ``hair.WigConfig``, ``from hairbrush_env.hair import get_wig``.
"""

from .build import CONTACT_MARGIN, CONTACT_SOLIMP, CONTACT_SOLREF, HAIR_GEOM_GROUP, add_wig, strand_rod
from .config import (
    DEFAULT_WIG,
    HAIR_RGBA,
    HELD_OUT_SEEDS,
    HELD_OUT_WIGS,
    MASS_SCALE,
    PRESETS,
    REAL_HAIR_RADIUS,
    REAL_HAIR_YOUNG,
    TRAIN_WIG_SEEDS,
    TRAIN_WIGS,
    WAVE1_COHESION,
    WIG_SETS,
    WISP_COHESION,
    WigConfig,
    brushing_seeds,
    get_wig,
    wave1_wig,
    wig_names,
    wisp_young,
)
from .entanglement_meter import CROSS_LINK_THRESHOLD, Entanglement, entanglement, min_distance_matrix
from .layout import WigLayout, wig_layout
from .shaking import shake, shake_acceleration
from .state import STATE_SPEC, StateCache, get_state, set_state

__all__ = [
    "CONTACT_MARGIN",
    "CONTACT_SOLIMP",
    "CONTACT_SOLREF",
    "CROSS_LINK_THRESHOLD",
    "DEFAULT_WIG",
    "HAIR_GEOM_GROUP",
    "HAIR_RGBA",
    "HELD_OUT_SEEDS",
    "HELD_OUT_WIGS",
    "MASS_SCALE",
    "PRESETS",
    "REAL_HAIR_RADIUS",
    "REAL_HAIR_YOUNG",
    "STATE_SPEC",
    "TRAIN_WIGS",
    "TRAIN_WIG_SEEDS",
    "WAVE1_COHESION",
    "WIG_SETS",
    "WISP_COHESION",
    "Entanglement",
    "StateCache",
    "WigConfig",
    "WigLayout",
    "add_wig",
    "brushing_seeds",
    "entanglement",
    "get_state",
    "get_wig",
    "min_distance_matrix",
    "set_state",
    "shake",
    "shake_acceleration",
    "strand_rod",
    "wave1_wig",
    "wig_layout",
    "wig_names",
    "wisp_young",
]
