"""Combing a double helix with one tine (thesis chapter 2: Figs 2.2(c–e), 2.3(c–e), 2.4, 2.6, 2.8; eqs 2.3–2.8).

The minimal model of a hair curl: two homochiral entwined helical filaments (pitch P, helix radius R = half the
distance between the filament centerlines, filament radius r, height h) clamped at the top and hanging free under
gravity, pierced between the strands by one stiff tine (radius t) that moves down quasi-statically to the free end.

Model (MuJoCo 4.0 discrete elastic rods from :mod:`hairbrush_env.rods`, topology from :mod:`hairbrush_env.topology`)

* Strands: two :class:`~hairbrush_env.rods.RodSpec` whose *rest shape* is the uniform double helix (the thesis's
  molded nylon helices), clamped at z = 0 and hanging towards −z. Defaults are the thesis tables (Fig. 2.9):
  r = 4.25e-4 m, h = 0.15 m, E = 0.27 GPa × 0.078 (the thesis's simulation scaling), ν = 0.5 → 0.49 (MuJoCo
  rejects 0.5), mass per length 6.65e-4 kg/m (nylon). Mass is scaled up and gravity down by ``mass_scale`` = 100
  (m·g constant, as the thesis did with 7.52e5): MuJoCo's soft contacts are stiff per unit mass, and at the
  physical mass the tine sank 0.2 r into the strands from the insertion bump alone.
* Insertion: the rods are built in their rest shape; before settling, both strands are pushed radially apart by a
  smooth bump (width ≈ P/4) centred at the insertion depth so that the full-size tine fits between them (for
  R = r the strands touch and there is no gap). The strands then relax under gravity around the fixed tine
  (``settle_time``), like the experiment where the rod pierces the braid before moving.
* Tine: a kinematic (mocap) capsule of radius t along ŷ, perpendicular to the helix axis, through the axis, at the
  depth where the strands lie along ±x̂. It moves down at constant ``speed``.
* Force: F is the z-component of the sum of all tine–strand contact forces (``mj_contactForce`` rotated to the
  world frame), i.e. the force the tine exerts on the hair, positive downwards. A mocap body has no actuator; the
  contact sum is the exact constraint force acting on it.
* Quasi-static: the tine moves at 5 mm/s (``speed``). On the reduced P/r = 36 helix (6 cm) f_max is 4.13, 3.77,
  3.05, 2.85, 2.77 and 2.74 at 40, 20, 10, 5, 2.5 and 1.25 mm/s (``hairbrush helix sweep --vary speed=...``,
  docs/double_helix.md), so at 5 mm/s the force is within ~4 % of its slow limit; the earlier 20 mm/s default carried
  a ~35 %
  dynamic part, about half of it inertia of the mass-scaled strands (mass ×10 instead of ×100 halves it). Viscous
  drag ``drag`` [N s/m²] on every vertex (≈ critical for the hanging pendulum mode) removes swinging; f_max does
  not depend on it (×0.25 … ×4 changed it by < 0.3 % at 20 mm/s). ``tests/studies/test_double_helix.py`` checks
  that halving the speed changes f_max by < 5 %.
* D, the total tine displacement needed to unlink, is the displacement at the last tine–strand contact; x = d/D.
* f = F l0²/B (l0 = 0.01 m, B = E π r⁴/4 of one filament), as in thesis Figs 2.3 and 2.6.
* Lk(x): open-curve Gauss linking integral of the two centerlines (exact for polylines); link density λ(s) from
  :func:`~hairbrush_env.topology.link_density` along the strands' common centerline, Δλ/λ0 = (λ(s, x) − λ(s, 0))/λ0
  with λ0 = Lk0 / (centerline length); link current dLk/dx from :func:`~hairbrush_env.topology.link_current`.
* Love prediction: the no-slip single-helix force of eqs 2.3, 2.5–2.7 for the clamped-side helix (from the clamp to
  the insertion point), :func:`~hairbrush_env.topology.love_tine_force`, tightly wound when R/r ≤ 1.
* Jamming (thesis: "a sharp increase in the force extension curve" that falls "once the tine breaks through"):
  the largest smoothed force before the exit is at least ``ratio`` = 1.25 × the median force between that peak and
  the exit (:func:`jam_metrics`).
* Kinking (thesis Fig. 2.2a: "it forms a kink about which the helix whirls"; Fig. 2.4: "below a certain link
  threshold, combing finishes without kink formation"): :func:`braid_bend` measures, per sample, how far the braid
  below the tine bends away from the vertical: the largest angle between the downward vertical and the centerline
  (a + b)/2, smoothed over one pitch, from the tine to one pitch above the free end (where the free ends untwist and
  splay), while at least ``_BEND_MIN_PITCHES`` = 3 pitches hang below the tine (later, the release folds the short
  rest over the tine). ``bend_max`` is its largest value in the stroke before any strand passage. A run counts as
  kinked when it reaches ``KINK_ANGLE`` = 30°, a choice; the angle itself is reported so that other thresholds
  can be applied.
* Kink jams (thesis §2.4: a kink "accompanied by a peak in applied force", then "the tine breaks through and the
  force decreases, before the same cycle repeats again"): :func:`breakthroughs` finds each drop of the smoothed
  force by the jam ratio and pairs it with the braid bend during the fall; ``kink_jams`` counts those at a bend
  ≥ ``KINK_ANGLE`` and ``kink_free_drops`` those with a straighter braid.
* Topology check: every 5 steps the open Gauss integrals Lk(a, b) and Lk(strand, tine axis) are recomputed. A strand
  pinched through the other strand or through the tine (a contact that gave way) makes one of them jump by ±1; such
  passages are counted (``strand_crossings``, ``tine_crossings``) and their link is taken out of the claim-3
  accounting (``lk_end_faithful``). Link may only leave through the free end.

Cost of combing (eq. 2.8): C(q) = γ f_max(q) + (1 − γ) q0/q, q0 = 25, see :func:`combing_cost`.

Modules: :mod:`.setup` (:class:`CombingSetup`, :func:`replace_setup`), :mod:`.result` (:class:`CombingResult`),
:mod:`.model` (the MuJoCo model of the strands and the tine, the tine's contact force), :mod:`.measures` (jamming,
break-throughs, braid bend, cost of combing), :mod:`.run` (:func:`run_combing`, the sweep worker :func:`run_point`),
:mod:`.output` (:func:`write_run`) and :mod:`.plots` (thesis-style figures).
"""

from .measures import (
    COST_Q0,
    KINK_ANGLE,
    Breakthrough,
    braid_bend,
    breakthroughs,
    combing_cost,
    jam_metrics,
    optimal_q,
)
from .output import write_run
from .plots import plot_cost, plot_run, plot_sweep
from .result import CombingResult
from .run import run_combing, run_point
from .setup import CombingSetup, replace_setup

__all__ = [
    "COST_Q0",
    "KINK_ANGLE",
    "Breakthrough",
    "CombingResult",
    "CombingSetup",
    "braid_bend",
    "breakthroughs",
    "combing_cost",
    "jam_metrics",
    "optimal_q",
    "plot_cost",
    "plot_run",
    "plot_sweep",
    "replace_setup",
    "run_combing",
    "run_point",
    "write_run",
]
