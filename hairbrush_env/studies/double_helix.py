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
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any, NamedTuple

import numpy as np

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

COST_Q0 = 25.0
"""q0 of eq. 2.8: fixed number of pitches characteristic of the strategies compared."""

_CHECK_STEPS = 5
"""Steps between topology checks (10 ms at the default 2 ms step). A strand that passes through the other strand (or
the tine axis) makes the open Gauss integral of the pair jump by ±1; between checks the continuous part changed by
at most 0.37 in the fastest link bursts seen (P/r = 18–24, insertion at the clamp), so |ΔLk| > 0.5 counts as one."""

_TINE_HALF_LENGTH = 0.05  # [m], far wider than the strands' lateral excursions
_DAMPRATIO = 1.0  # contact solref = (CombingSetup.contact_timeconst, 1): critically damped
_SOLIMP = (0.99, 0.9999, 2e-5, 0.5, 2.0)


# ------------------------------------------------------------------------------------------------ setup
@dataclass(frozen=True)
class CombingSetup:
    """Geometry, material and numerics of one combing run (dimensionless ratios as in thesis Fig. 2.2b).

    Parameters
    ----------
    P_over_r, R_over_r, t_over_r : float
        π1 = P/r (pitch), π2 = R/r (helix radius, half the centerline distance; ≥ 1), π3 = t/r (tine radius).
        Thesis main-text runs use t/r = 0.9.
    q : float or None
        Pitches between the tine insertion point and the free end; ``None`` = insertion at mid-height (thesis
        Figs 2.2–2.3). Needs ``q * P < height``.
    speed : float
        Tine speed [m/s].
    friction : float
        Coulomb friction of all contacts (0 = frictionless, the thesis's simulations; > 0 uses condim 3).
    edges_per_pitch : int
        Discretization: rod edges per helix pitch (per turn of one strand around the other).
    radius, height, young, poisson, linear_density : float
        r [m], h [m], E [Pa], ν, mass per length [kg/m] of one filament.
    drag : float
        Viscous drag per unit length [N s/m²] on the strand vertices (quasi-static damping).
    bend_damping : float
        MuJoCo Rayleigh damping of bending/torsion [s].
    mass_scale : float
        Multiply mass by this and divide gravity by it (m·g constant; the thesis used 7.52e5 for stability).
    l0 : float
        Reference length of f = F l0²/B [m].
    timestep : float
        Simulation step [s].
    contact_timeconst : float
        Time constant of all contacts (``solref[0]``) [s]; stiffness ∝ mass / timeconst². MuJoCo needs ≥ 2
        ``timestep``. 4 ms (rods.py advice for thin hair) holds in the runs of docs/double_helix.md with P/r ≥ 24 but
        for the longest
        stroke (q = 12); the tight P/r = 18 helix overloads it (one strand is pinched through the other at the tine
        at release: ``strand_crossings``), and 2 ms at a 1 ms step holds.
    settle_time : float
        Relaxation under gravity around the inserted, fixed tine before it moves [s].
    samples : int
        Number of recorded samples along the stroke (force is averaged over the steps between samples).
    snapshot_x : tuple of float
        Tine positions x = d/D at which link-density snapshots Δλ(s)/λ0 are reported.
    max_stroke : float
        Safety limit of the tine stroke in units of the height.
    """

    P_over_r: float = 24.0
    R_over_r: float = 1.0
    t_over_r: float = 0.9
    q: float | None = None
    speed: float = 0.005
    friction: float = 0.0
    edges_per_pitch: int = 10
    radius: float = 4.25e-4
    height: float = 0.15
    young: float = 0.27e9 * 0.078
    poisson: float = 0.49
    linear_density: float = 6.65e-4
    drag: float = 0.02
    bend_damping: float = 0.0
    mass_scale: float = 100.0
    l0: float = 0.01
    timestep: float = 2e-3
    contact_timeconst: float = 4e-3
    settle_time: float = 0.4
    samples: int = 200
    snapshot_x: tuple[float, ...] = (0.0, 0.2, 0.4, 0.6, 0.8)
    max_stroke: float = 1.5

    def __post_init__(self) -> None:
        def check(name: str, lo: float | None = None, *, strict: bool = True) -> None:
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"CombingSetup.{name} must be a finite number, got {v!r}")
            if lo is not None and (v <= lo if strict else v < lo):
                raise ValueError(f"CombingSetup.{name} must be {'>' if strict else '>='} {lo}, got {v!r}")

        for name in ("P_over_r", "t_over_r", "speed", "radius", "height", "young", "linear_density"):
            check(name, 0.0)
        for name in ("l0", "timestep", "contact_timeconst", "mass_scale", "samples", "max_stroke"):
            check(name, 0.0)
        if self.contact_timeconst < 2.0 * self.timestep:
            raise ValueError(
                "CombingSetup.contact_timeconst must be >= 2 timestep (MuJoCo would silently raise it): "
                f"got {self.contact_timeconst!r} with timestep {self.timestep!r}"
            )
        for name in ("friction", "drag", "bend_damping", "settle_time"):
            check(name, 0.0, strict=False)
        check("R_over_r", 1.0, strict=False)
        check("poisson", 0.0, strict=False)
        if self.poisson >= 0.5:
            raise ValueError(f"CombingSetup.poisson must be < 0.5 (MuJoCo), got {self.poisson!r}")
        if int(self.edges_per_pitch) != self.edges_per_pitch or self.edges_per_pitch < 4:
            raise ValueError(
                f"CombingSetup.edges_per_pitch must be an integer >= 4, got {self.edges_per_pitch!r}"
            )
        if int(self.samples) != self.samples or self.samples < 10:
            raise ValueError(f"CombingSetup.samples must be an integer >= 10, got {self.samples!r}")
        if self.q is not None:
            check("q", 0.0)
            if self.q * self.pitch >= self.height - 0.5 * self.pitch:
                raise ValueError(
                    "CombingSetup.q must leave at least half a pitch above the tine: "
                    f"q·P = {self.q * self.pitch:.4g} m but height = {self.height:.4g} m (raise height)"
                )
        if not all(0.0 <= x < 1.0 for x in self.snapshot_x):
            raise ValueError(f"CombingSetup.snapshot_x must lie in [0, 1), got {self.snapshot_x!r}")
        object.__setattr__(self, "snapshot_x", tuple(float(x) for x in self.snapshot_x))

    # derived geometry ---------------------------------------------------------------------------------
    @property
    def pitch(self) -> float:
        """P [m]."""
        return self.P_over_r * self.radius

    @property
    def helix_radius(self) -> float:
        """R [m]."""
        return self.R_over_r * self.radius

    @property
    def tine_radius(self) -> float:
        """t [m]."""
        return self.t_over_r * self.radius

    @property
    def turns(self) -> float:
        """Pitches over the height, h/P (≈ the initial Lk)."""
        return self.height / self.pitch

    @property
    def insertion_depth(self) -> float:
        """Depth of the tine below the clamp at insertion [m]."""
        return 0.5 * self.height if self.q is None else self.height - self.q * self.pitch

    def q_near_clamp(self) -> float:
        """The largest q allowed: the tine enters just over half a pitch below the clamp.

        The thesis's simulations insert the tine "close to the clamped end" (§2.3); only then can one stroke expel
        nearly all the link, because the link between clamp and tine cannot pass the tine (``lk_above``, about
        half a link here). Half a pitch is as close as the insertion opening allows: it is a Gaussian of width
        P/4 (``_bulge``), so at the clamp it is down to 2 % and the clamped ends stay on the helix.
        """
        return self.height / self.pitch - 0.51

    @property
    def q_effective(self) -> float:
        """Pitches between insertion point and free end."""
        return (self.height - self.insertion_depth) / self.pitch

    @property
    def bending(self) -> float:
        """B = E π r⁴ / 4 of one filament [N m²]."""
        return self.young * math.pi * self.radius**4 / 4.0

    @property
    def twisting(self) -> float:
        """C = G π r⁴ / 2 with G = E / (2 (1 + ν)) [N m²]."""
        return self.young / (2.0 * (1.0 + self.poisson)) * math.pi * self.radius**4 / 2.0

    @property
    def force_scale(self) -> float:
        """B / l0² [N]: f = F / force_scale."""
        return self.bending / self.l0**2

    def key(self) -> dict[str, Any]:
        """All fields as a JSON-friendly dict (used as the cache key of sweeps)."""
        d = asdict(self)
        d["snapshot_x"] = list(self.snapshot_x)
        return d


# ----------------------------------------------------------------------------------------------- result
@dataclass(frozen=True)
class CombingResult:
    """Outcome of :func:`run_combing`. Arrays are per recorded sample along the stroke.

    Attributes
    ----------
    setup : CombingSetup
    d : np.ndarray
        Tine displacement from the insertion point [m].
    x : np.ndarray
        d / D.
    F : np.ndarray
        Tine force on the hair along the stroke (positive = pushing the hair down) [N], averaged between samples.
    f : np.ndarray
        F l0² / B.
    lk : np.ndarray
        Open-curve Gauss linking integral of the two centerlines.
    current : np.ndarray
        Link current dLk/dx (moving average over 5 samples).
    love_f : np.ndarray
        No-slip single-helix prediction (eqs 2.3, 2.5–2.7) in units of B/l0²; NaN where the helix would be
        straight.
    snapshots : dict
        ``{x: (s, Δλ/λ0)}``, s = arclength along the common centerline from the clamp [m].
    D : float
        Tine displacement at the last contact [m].
    f_max, x_at_f_max : float
    lk0, lk_end : float
        Lk after settling (x = 0) and at the end of the stroke.
    jammed : bool
        See the module docstring; ``jam_ratio`` = peak / plateau of the smoothed force.
    jam_ratio : float
    min_gap_tine, min_gap_strands : float
        Smallest tine–strand / strand–strand contact distance seen (negative = interpenetration) [m].
    lk_above : float
        Open Lk of the strand pieces between the clamp and the insertion depth at x = 0. A long tine cannot let link
        pass through it, so this link is trapped: the stroke can at best expel ``lk0 − lk_above``.
    max_stretch : float
        Largest relative change of strand length seen.
    strand_crossings, tine_crossings : int
        Topology violations: how often a strand passed through the other strand / through the tine axis (a contact
        that tunnelled or gave way), found as jumps of ±1 in the open Gauss integrals Lk(a, b) and Lk(strand, tine
        axis) between checks every few steps (see :func:`_passages`). 0 in a faithful run; a strand crossing
        changes Lk by ±1 that did not leave through the free end.
    crossing_d : tuple of float
        Tine displacements at which the violations happened [m].
    crossing_lk : float
        Signed change of Lk(a, b) made by the strand–strand passages (±1 each). ``lk_end − crossing_lk`` is the link
        a faithful run would have left; claim 3 is judged on it (:attr:`lk_end_faithful`).
    wall_time : float
        Seconds of wall clock.
    check_time : float
        Seconds of it spent in the topology check (the benchmark prints the share).
    bend : np.ndarray
        Bend of the braid below the tine [deg] per sample (:func:`braid_bend`); NaN where fewer than 3 pitches hang
        below the tine, all NaN for results cached before the measure existed.
    """

    setup: CombingSetup
    d: np.ndarray
    x: np.ndarray
    F: np.ndarray
    f: np.ndarray
    lk: np.ndarray
    current: np.ndarray
    love_f: np.ndarray
    snapshots: dict[float, tuple[np.ndarray, np.ndarray]]
    D: float
    f_max: float
    x_at_f_max: float
    lk0: float
    lk_end: float
    jammed: bool
    jam_ratio: float
    min_gap_tine: float
    min_gap_strands: float
    lk_above: float
    max_stretch: float
    wall_time: float
    strand_crossings: int = 0
    tine_crossings: int = 0
    crossing_d: tuple[float, ...] = ()
    crossing_lk: float = 0.0
    check_time: float = 0.0
    bend: np.ndarray = field(default_factory=lambda: np.zeros(0))
    frames: np.ndarray = field(repr=False, default_factory=lambda: np.zeros((0, 2, 0, 3)))

    @property
    def lk_end_faithful(self) -> float:
        """Lk at the end without the unit jumps of strand–strand passages: the link that did not leave the free end."""
        return self.lk_end - self.crossing_lk

    @property
    def combed_lk_end_fraction(self) -> float:
        """Link left at the end relative to the combable link, (Lk_end − Lk_above)/(Lk0 − Lk_above), with Lk_end
        taken without strand–strand passages (:attr:`lk_end_faithful`)."""
        den = self.lk0 - self.lk_above
        return (self.lk_end_faithful - self.lk_above) / den if den else float("nan")

    def bend_per_sample(self) -> np.ndarray:
        """:attr:`bend` aligned with :attr:`x` (all NaN when it was not measured)."""
        bend = np.asarray(self.bend, dtype=float)
        return bend if bend.shape == self.x.shape else np.full(self.x.shape, np.nan)

    def _bend_in_stroke(self) -> np.ndarray:
        bend = self.bend_per_sample()
        valid = self.x <= 1.0
        if self.crossing_d:  # after a strand passed through the other or the tine the geometry is unphysical
            valid &= self.d < min(self.crossing_d)
        return np.where(valid, bend, np.nan)

    @property
    def bend_max(self) -> float:
        """Largest bend of the braid below the tine during the stroke [deg], before any strand passage; NaN if
        never measured."""
        bend = self._bend_in_stroke()
        return float(np.nanmax(bend)) if np.isfinite(bend).any() else float("nan")

    @property
    def x_at_bend_max(self) -> float:
        bend = self._bend_in_stroke()
        return float(self.x[int(np.nanargmax(bend))]) if np.isfinite(bend).any() else float("nan")

    @property
    def kinked(self) -> bool:
        """The braid below the tine bent by at least :data:`KINK_ANGLE` (the thesis's kink, Fig. 2.2a)."""
        return bool(self.bend_max >= KINK_ANGLE)

    def breakthroughs(self) -> list[Breakthrough]:
        """The tine's break-throughs (:func:`breakthroughs`), each with the braid bend of the stroke (the bend is NaN
        after a strand passage and while fewer than 3 pitches hang below the tine)."""
        return breakthroughs(self.x, self.f, self._bend_in_stroke())

    @property
    def kink_jams(self) -> int:
        """Break-throughs at a kinked braid: the jam cycle of thesis §2.4 (force peak at a kink, then the drop)."""
        return sum(b.kinked for b in self.breakthroughs())

    @property
    def kink_free_drops(self) -> int:
        """Break-throughs with the braid below the tine measured and bent less than :data:`KINK_ANGLE`."""
        return sum(math.isfinite(b.bend) and not b.kinked for b in self.breakthroughs())

    @property
    def jammed_by_kink(self) -> bool:
        """Jammed by the thesis's mechanism: at least one kink jam (§2.4; the force-only flag is :attr:`jammed`)."""
        return self.kink_jams > 0

    def summary(self) -> dict[str, Any]:
        """Scalar results and the setup (JSON-friendly)."""
        return {
            "setup": self.setup.key(),
            "D": self.D,
            "f_max": self.f_max,
            "x_at_f_max": self.x_at_f_max,
            "lk0": self.lk0,
            "lk_end": self.lk_end,
            "lk_end_fraction": self.lk_end / self.lk0 if self.lk0 else float("nan"),
            "jammed": self.jammed,
            "jam_ratio": self.jam_ratio,
            "min_gap_tine": self.min_gap_tine,
            "min_gap_strands": self.min_gap_strands,
            "lk_above": self.lk_above,
            "combed_lk_end_fraction": self.combed_lk_end_fraction,
            "max_stretch": self.max_stretch,
            "strand_crossings": self.strand_crossings,
            "tine_crossings": self.tine_crossings,
            "crossing_d": list(self.crossing_d),
            "crossing_lk": self.crossing_lk,
            "lk_end_faithful": self.lk_end_faithful,
            "bend_max": _json_float(self.bend_max),
            "x_at_bend_max": _json_float(self.x_at_bend_max),
            "kinked": self.kinked,
            "kink_jams": self.kink_jams,
            "kink_free_drops": self.kink_free_drops,
            "wall_time": self.wall_time,
        }

    def to_dict(self) -> dict[str, Any]:
        """Everything but the frames, JSON-friendly (round-trips through :meth:`from_dict`)."""
        out = self.summary()
        for name in ("d", "x", "F", "f", "lk", "current", "love_f"):
            out[name] = np.asarray(getattr(self, name)).tolist()
        out["bend"] = [_json_float(v) for v in np.asarray(self.bend, dtype=float)]
        out["snapshots"] = {
            f"{x:.3f}": {"s": s.tolist(), "dlam": v.tolist()} for x, (s, v) in self.snapshots.items()
        }
        return out

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> CombingResult:
        """Inverse of :meth:`to_dict` (frames are not stored)."""
        setup_d = dict(data["setup"])
        setup_d["snapshot_x"] = tuple(setup_d["snapshot_x"])
        known = {f.name for f in fields(CombingSetup)}
        setup = CombingSetup(**{k: v for k, v in setup_d.items() if k in known})
        arr = {k: np.asarray(data[k], dtype=float) for k in ("d", "x", "F", "f", "lk", "current", "love_f")}
        snaps = {
            float(k): (np.asarray(v["s"], dtype=float), np.asarray(v["dlam"], dtype=float))
            for k, v in data["snapshots"].items()
        }
        scal = {
            k: data[k]
            for k in (
                "D", "f_max", "x_at_f_max", "lk0", "lk_end", "jammed", "jam_ratio", "min_gap_tine",
                "min_gap_strands", "lk_above", "max_stretch",
                "wall_time",
            )
        }  # fmt: skip
        # results cached before the topology check existed carry no counts: -1 = not checked
        scal["strand_crossings"] = int(data.get("strand_crossings", -1))
        scal["tine_crossings"] = int(data.get("tine_crossings", -1))
        scal["crossing_d"] = tuple(float(v) for v in data.get("crossing_d", ()))
        scal["crossing_lk"] = float(data.get("crossing_lk", 0.0))
        # results cached before the bend measure existed: NaN = not measured
        bend = data.get("bend")
        scal["bend"] = (
            np.full(arr["x"].shape, np.nan)
            if bend is None
            else np.array([np.nan if v is None else v for v in bend], dtype=float)
        )
        # jamming is post-processing: recompute it so cached runs follow the current criterion
        scal["jammed"], scal["jam_ratio"] = jam_metrics(arr["x"], arr["f"])
        return cls(setup=setup, snapshots=snaps, **arr, **scal)

    def csv_rows(self) -> tuple[list[str], np.ndarray]:
        """Header and ``(n, 8)`` table: d, x, F, f, Lk, dLk/dx, Love f, braid bend [deg] (NaN = not measured)."""
        header = ["d_m", "x", "F_N", "f", "Lk", "dLk_dx", "love_f", "bend_deg"]
        cols = [self.d, self.x, self.F, self.f, self.lk, self.current, self.love_f, self.bend_per_sample()]
        return header, np.column_stack(cols)


# ----------------------------------------------------------------------------------------------- model
def _strand_points(setup: CombingSetup) -> tuple[np.ndarray, np.ndarray]:
    """Rest centerlines, clamp first, hanging from z = 0 to z = −h; strands along ±x̂ at the insertion depth."""
    from ..topology import double_helix

    n = max(3, round(setup.turns * setup.edges_per_pitch) + 1)
    h, depth = setup.height, setup.insertion_depth
    # double_helix spans z ∈ [0, h] with azimuth phase + 2πz/P; we translate it down by h (a rigid motion keeps the
    # handedness) and choose the phase so that strand a is at azimuth 0 at the insertion height z = h − depth.
    phase = -2.0 * math.pi * (h - depth) / setup.pitch
    a, b = double_helix(setup.helix_radius, setup.pitch, setup.turns, n, phase=phase)
    a, b = a[::-1].copy(), b[::-1].copy()  # clamp (top) first; reversing both strands leaves Lk unchanged
    a[:, 2] -= h
    b[:, 2] -= h
    return a, b


def _bulge(points: np.ndarray, setup: CombingSetup) -> np.ndarray:
    """Radial displacement that opens a gap of t + small clearance for the tine at the insertion depth."""
    r, R, t = setup.radius, setup.helix_radius, setup.tine_radius
    target = t + r + 0.1 * r  # strand centre distance from the tine axis
    amp = max(0.0, target - R)
    depth = -points[:, 2]
    w = 0.25 * setup.pitch
    g = amp * np.exp(-(((depth - setup.insertion_depth) / w) ** 2))
    rho = np.hypot(points[:, 0], points[:, 1])
    disp = np.zeros_like(points)
    disp[:, 0] = g * points[:, 0] / rho
    disp[:, 1] = g * points[:, 1] / rho
    return disp


def _build(setup: CombingSetup):
    import mujoco

    from ..rods import RodSpec, build_rod_model

    a, b = _strand_points(setup)
    area = math.pi * setup.radius**2
    density = setup.linear_density * setup.mass_scale / area
    condim = 1 if setup.friction == 0.0 else 3
    common = dict(
        radius=setup.radius,
        young=setup.young,
        poisson=setup.poisson,
        density=density,
        damping=setup.bend_damping,
        friction=setup.friction,
        condim=condim,
        contact_solref=(setup.contact_timeconst, _DAMPRATIO),
        contact_solimp=_SOLIMP,
        # The combing claims (§2.4) were validated on DER flexes; chains would change the measured tables.
        kind="flex",
    )
    rods = [
        RodSpec("strand_a", a, rgba=(0.0, 0.45, 0.7, 1.0), **common),
        RodSpec("strand_b", b, rgba=(0.84, 0.37, 0.0, 1.0), **common),
    ]

    def extra(spec: mujoco.MjSpec) -> None:
        tine = spec.worldbody.add_body(name="tine", mocap=True, pos=[0.0, 0.0, -setup.insertion_depth])
        half = math.sqrt(0.5)
        # capsule axis is local z; rotate it onto ŷ (perpendicular to the helix axis and to the strands' offset)
        g = tine.add_geom(
            name="tine",
            type=mujoco.mjtGeom.mjGEOM_CAPSULE,
            size=[setup.tine_radius, _TINE_HALF_LENGTH, 0.0],
            quat=[half, half, 0.0, 0.0],
            rgba=[0.2, 0.2, 0.2, 1.0],
        )
        g.condim = condim
        g.friction = [setup.friction, 0.005, 0.0001]
        g.solref = [setup.contact_timeconst, _DAMPRATIO]
        g.solimp = list(_SOLIMP)

    gravity = (0.0, 0.0, -9.81 / setup.mass_scale)
    model = build_rod_model(rods, timestep=setup.timestep, gravity=gravity, extra=extra)
    return model, rods


def _tine_force(model, data, tine_geom: int, buf: np.ndarray) -> tuple[float, float, float]:
    """(z-force of the tine on the hair, smallest tine–strand and strand–strand contact distances)."""
    import mujoco

    fz = 0.0
    gap_tine = gap_strands = math.inf
    for i in range(data.ncon):
        con = data.contact[i]
        g1, g2 = int(con.geom[0]), int(con.geom[1])
        if tine_geom not in (g1, g2):
            gap_strands = min(gap_strands, float(con.dist))
            continue
        gap_tine = min(gap_tine, float(con.dist))
        mujoco.mj_contactForce(model, data, i, buf)
        world = con.frame.reshape(3, 3).T @ buf[:3]  # contact frame rows: normal, tangent1, tangent2
        # the force acts on geom2 along +normal (normal points from geom1 to geom2) and on geom1 along −normal
        on_hair = world if g1 == tine_geom else -world
        fz += float(on_hair[2])
    return -fz, gap_tine, gap_strands  # force positive = tine pushes the hair down


# ---------------------------------------------------------------------------------------------- analysis
# [deg] bend of the braid below the tine that counts as a kink (a choice; the angle itself is reported)
KINK_ANGLE = 30.0
_BEND_MIN_PITCHES = 3


def _bend_axis_top(bend: np.ndarray) -> float:
    """Upper y limit of bend plots: 95° unless a fold went further (a whirling kink can exceed 90°)."""
    finite = bend[np.isfinite(bend)]
    return max(95.0, 1.05 * float(finite.max())) if finite.size else 95.0


def _smooth(y: np.ndarray, window: int) -> np.ndarray:
    if window <= 1 or y.size < window:
        return y.copy()
    from scipy.ndimage import uniform_filter1d

    return uniform_filter1d(y, size=window, mode="nearest")


# the jam criterion's peak ratio and force smoothing, shared by the force-only flag and the break-through analysis
_JAM_RATIO = 1.25
_JAM_WINDOW = 9  # samples


def jam_metrics(
    x: np.ndarray, f: np.ndarray, *, ratio: float = _JAM_RATIO, window: int = _JAM_WINDOW
) -> tuple[bool, float]:
    """Detect tine jamming in a force curve f(x) (thesis §2.4): ``(jammed, peak / level after the peak)``.

    The force jams when it rises to a peak and falls once the tine breaks through, while combing goes on. The
    exit x_e is the last position where the smoothed force is still ≥ 1/4 of its maximum (beyond it the tine is
    leaving the free end, which every curve does). Jammed: the largest smoothed force at 0.05 ≤ x ≤ x_e − 0.15
    exceeds ``ratio`` × the median force between that peak and x_e. Loose helices rise to a plateau or keep
    rising (ratio ≈ 1).

    Parameters
    ----------
    x, f : np.ndarray
        Scaled tine position and force.
    ratio : float
        Minimal peak-to-later-level ratio of a jam.
    window : int
        Moving-average width (samples) applied to f first.
    """
    x = np.asarray(x, dtype=float)
    fs = _smooth(np.asarray(f, dtype=float), window)
    if fs.size == 0 or fs.max() <= 0:
        return False, float("nan")
    x_exit = float(x[np.flatnonzero(fs >= 0.25 * fs.max())[-1]])
    cand = np.flatnonzero((x >= 0.05) & (x <= x_exit - 0.15))
    if cand.size == 0:
        return False, float("nan")
    k = int(cand[np.argmax(fs[cand])])
    level = float(np.median(fs[(x >= x[k]) & (x <= x_exit)]))
    jam_ratio = float(fs[k]) / level if level > 0 else float("inf")
    return bool(jam_ratio >= ratio), jam_ratio


class Breakthrough(NamedTuple):
    """One drop of the smoothed force by at least the jam ratio: the tine breaking through (thesis §2.4)."""

    x_peak: float
    x_drop: float
    f_peak: float
    f_drop: float
    bend: float
    """Largest braid bend below the tine during the fall [deg]; NaN if it was not measured there."""

    @property
    def kinked(self) -> bool:
        return bool(self.bend >= KINK_ANGLE)


def breakthroughs(
    x: np.ndarray, f: np.ndarray, bend: np.ndarray, *, ratio: float = _JAM_RATIO, window: int = _JAM_WINDOW
) -> list[Breakthrough]:
    """Every break-through of the tine: the smoothed force falls from a local peak to below peak / ``ratio``.

    Thesis §2.4 describes the jam cycle: link density builds up ahead of the tine until "the relative shear often
    leads to the kinked configuration ... accompanied by a peak in applied force. ... eventually the tine breaks
    through and the force decreases, before the same cycle repeats again"; for loose helices "λ(s) never crosses the
    threshold needed for kinking, and the force required to comb never peaks". So each drop is returned with the
    largest bend of the braid below the tine (:func:`braid_bend`) during the fall (from the last sample within half
    the drop of the peak to the end of the drop), widened by half the smoothing window; a *kink jam* is a
    break-through with that bend ≥ :data:`KINK_ANGLE`. Peaks below a quarter of the largest force are ignored (the
    tine brushing released free ends). ``ratio`` and ``window`` are those of :func:`jam_metrics`.

    Parameters
    ----------
    x, f : np.ndarray
        Scaled tine position and force.
    bend : np.ndarray
        Braid bend [deg] per sample, NaN where it is not measured (it then counts as no kink).
    """
    x = np.asarray(x, dtype=float)
    fs = _smooth(np.asarray(f, dtype=float), window)
    bend = np.asarray(bend, dtype=float)
    if not (x.shape == fs.shape == bend.shape) or x.ndim != 1:
        raise ValueError(f"x, f and bend must be 1-D of one length, got {x.shape}, {fs.shape}, {bend.shape}")
    if not ratio > 1.0:
        raise ValueError(f"ratio must be > 1, got {ratio!r}")
    n = fs.size
    if n == 0 or fs.max() <= 0:
        return []
    floor = 0.25 * float(fs.max())
    half = window // 2
    out: list[Breakthrough] = []
    i = 0
    while i < n - 1:
        peak, j = i, i
        while j < n and fs[j] * ratio >= fs[peak]:  # walk on until the force has fallen below peak / ratio
            if fs[j] >= fs[peak]:  # the last of equal maxima: the drop starts there
                peak = j
            j += 1
        if j >= n:
            break
        if fs[peak] > floor:
            # the fall itself: from the last sample still within half the drop of the peak, ± half a window
            start = peak + int(np.flatnonzero(fs[peak:j] >= 0.5 * (1.0 + 1.0 / ratio) * fs[peak])[-1])
            part = bend[max(0, start - half) : min(n, j + half + 1)]
            b = float(np.nanmax(part)) if np.isfinite(part).any() else float("nan")
            out.append(Breakthrough(float(x[peak]), float(x[j]), float(fs[peak]), float(fs[j]), b))
        while j < n - 1 and fs[j + 1] < fs[j]:  # the next cycle starts at the bottom of this drop
            j += 1
        i = max(j, i + 1)
    return out


def _json_float(v: float) -> float | None:
    """NaN → None, so that the JSON files stay strict JSON."""
    return None if not math.isfinite(v) else float(v)


def braid_bend(frames, z_tine, points_per_pitch: int, *, min_pitches: int = _BEND_MIN_PITCHES) -> np.ndarray:
    """Bend of the braid below the tine [deg] for each frame: the kink of thesis Fig. 2.2a.

    The braid centerline is (a + b)/2 (the pairing of :func:`~hairbrush_env.topology.link_density`). Its part from the
    first vertex below the tine to one pitch above the free end is smoothed by a moving average over one pitch (the
    helical wiggle of the midpoint) and the largest angle between its tangent and the downward vertical is returned.
    A straight hanging braid gives ≈ 0°, a braid folded sideways 90°. The last pitch is left out because the free
    ends untwist and splay there, which moves their midpoint sideways without any bend of the braid.

    Parameters
    ----------
    frames : (n_frames, 2, n, 3) array_like
        The two strands' vertices (clamp first) per frame.
    z_tine : float or (n_frames,) array_like
        Height of the tine axis per frame [m].
    points_per_pitch : int
        Vertices per helix pitch along one strand (the smoothing window and the excluded free-end piece).
    min_pitches : int
        Frames with fewer pitches of braid below the tine give NaN (during the release the short rest folds over
        the tine, which is not a kink of the braid).
    """
    fr = np.asarray(frames, dtype=float)
    if fr.ndim != 4 or fr.shape[1] != 2 or fr.shape[3] != 3:
        raise ValueError(f"frames: expected shape (n_frames, 2, n, 3), got {fr.shape}")
    for name, v in (("points_per_pitch", points_per_pitch), ("min_pitches", min_pitches)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 2:
            raise ValueError(f"{name}: expected an integer >= 2, got {v!r}")
    z = np.broadcast_to(np.asarray(z_tine, dtype=float), (fr.shape[0],))
    from scipy.ndimage import uniform_filter1d

    w = int(points_per_pitch)
    half = w // 2
    out = np.full(fr.shape[0], np.nan)
    for k in range(fr.shape[0]):
        c = 0.5 * (fr[k, 0] + fr[k, 1])
        below = np.flatnonzero(c[:, 2] < z[k])
        if below.size == 0 or c.shape[0] - below[0] < min_pitches * w:
            continue
        piece = c[below[0] : c.shape[0] - w]
        smooth = uniform_filter1d(piece, size=w, axis=0, mode="nearest")[half : piece.shape[0] - half]
        t = np.diff(smooth, axis=0)
        norm = np.linalg.norm(t, axis=1)
        t = t[norm > 0] / norm[norm > 0, None]
        if t.size:
            out[k] = float(np.degrees(np.arccos(np.clip(-t[:, 2], -1.0, 1.0))).max())
    return out


def combing_cost(f_max, q, gamma, *, q0: float = COST_Q0):
    """Cost of combing, eq. 2.8: C(q) = γ f_max(q) + (1 − γ) q0 / q (element-wise)."""
    q = np.asarray(q, dtype=float)
    if np.any(q <= 0):
        raise ValueError(f"q must be > 0, got {q!r}")
    gamma = np.asarray(gamma, dtype=float)
    if np.any((gamma < 0) | (gamma > 1)):
        raise ValueError(f"gamma must lie in [0, 1], got {gamma!r}")
    return gamma * np.asarray(f_max, dtype=float) + (1.0 - gamma) * q0 / q


def optimal_q(q: Sequence[float], f_max: Sequence[float], gamma: float, *, q0: float = COST_Q0) -> float:
    """The q of a sweep that minimises C(q) (eq. 2.8) for one γ."""
    c = combing_cost(f_max, q, gamma, q0=q0)
    return float(np.asarray(q, dtype=float)[int(np.argmin(c))])


# -------------------------------------------------------------------------------------------------- run
def _passages(prev: np.ndarray, new: np.ndarray) -> np.ndarray:
    """Whole passages between two checks of open Gauss integrals: round(|Δ|) where |Δ| > 0.5, else 0."""
    delta = np.abs(np.asarray(new, dtype=float) - np.asarray(prev, dtype=float))
    return np.where(delta > 0.5, np.rint(delta), 0.0).astype(int)


def run_combing(
    setup: CombingSetup,
    seed: int = 0,
    *,
    progress: Callable[[float], None] | None = None,
    keep_frames: bool = False,
) -> CombingResult:
    """Simulate one combing stroke and analyse it (see the module docstring for the model and definitions).

    Parameters
    ----------
    setup : CombingSetup
    seed : int
        Seeds a tiny random perturbation (1e-3 r) of the initial vertex positions, so that repeated runs sample the
        symmetry breaking of kinking (thesis: runs are averaged).
    progress : callable, optional
        Called with the fraction of the maximal stroke done (for progress bars).
    keep_frames : bool
        Keep the strand centerlines of every sample in ``result.frames`` (``(samples, 2, n, 3)``).

    Returns
    -------
    CombingResult
    """
    import mujoco

    from ..rods import RodView
    from ..topology import link_current, link_density, linking_number, love_tine_force

    t_wall = time.perf_counter()
    model, rods = _build(setup)
    data = mujoco.MjData(model)
    views = [RodView(model, r.name) for r in rods]
    rest_len = [r.length for r in rods]
    tine_geom = model.geom("tine").id
    mocap = model.body("tine").mocapid[0]

    # open the gap for the tine (rest shape stays the uniform helix) + seeded symmetry-breaking noise
    rng = np.random.default_rng(seed)
    for rod in rods:
        disp = _bulge(rod.points, setup)
        disp += rng.normal(0.0, 1e-3 * setup.radius, disp.shape)
        for k in range(1, rod.n_edges + 1):
            jadr = model.body_jntadr[model.body(f"{rod.name}_{k}").id]
            qadr = model.jnt_qposadr[jadr]
            data.qpos[qadr : qadr + 3] = disp[k]
    mujoco.mj_forward(model, data)

    # Viscous drag γ per unit length lumped on the vertices (the thesis's damping γ). MuJoCo refuses joint damping
    # on flex vertex bodies, so it is applied explicitly through qfrc_applied; c·dt/m ≈ 0.06 at the defaults, far
    # inside the explicit stability limit (2).
    dofs, coef = [], []
    for rod in rods:
        seg = np.linalg.norm(np.diff(rod.points, axis=0), axis=1)
        share = 0.5 * (np.append(seg, 0.0)[1:] + seg)  # vertex k>=1 carries half of each adjacent edge
        for k in range(1, rod.n_edges + 1):
            dadr = model.jnt_dofadr[model.body_jntadr[model.body(f"{rod.name}_{k}").id]]
            dofs.extend(range(dadr, dadr + 3))
            coef.extend([setup.drag * share[k - 1]] * 3)
    dofs_arr, coef_arr = np.asarray(dofs), np.asarray(coef)

    def step() -> None:
        data.qfrc_applied[dofs_arr] = -coef_arr * data.qvel[dofs_arr]
        mujoco.mj_step(model, data)

    def gauss_pairs(z_tine: float) -> np.ndarray:
        """Open Gauss integrals Lk(a, b), Lk(a, tine axis), Lk(b, tine axis) of the current state."""
        va, vb = (v.vertices(data) for v in views)
        axis = np.array(
            [[0.0, -_TINE_HALF_LENGTH, z_tine], [0.0, _TINE_HALF_LENGTH, z_tine]]
        )  # capsule segment
        return np.array([
            linking_number(va, vb, closed=False),
            linking_number(va, axis, closed=False),
            linking_number(vb, axis, closed=False),
        ])  # fmt: skip

    crossings = np.zeros(3, dtype=int)
    crossing_d: list[float] = []
    crossing_lk = [0.0]  # signed Lk(a, b) carried by the strand–strand passages
    check_time = [0.0]

    def check(z_tine: float, d: float, prev: np.ndarray) -> np.ndarray:
        t0 = time.perf_counter()
        new = gauss_pairs(z_tine)
        check_time[0] += time.perf_counter() - t0
        jumps = _passages(prev, new)
        if jumps.any():
            crossings[:] += jumps
            crossing_d.append(d)
            crossing_lk[0] += float(np.sign(new[0] - prev[0]) * jumps[0])
        return new

    buf = np.zeros(6)
    min_gap_tine = min_gap_strands = math.inf
    max_stretch = 0.0
    z0 = -setup.insertion_depth
    topo = gauss_pairs(z0)
    for i_settle in range(max(0, round(setup.settle_time / setup.timestep))):
        step()
        if (i_settle + 1) % _CHECK_STEPS == 0:
            topo = check(z0, 0.0, topo)

    max_d = setup.max_stroke * setup.height
    n_steps = math.ceil(max_d / (setup.speed * setup.timestep))
    est_D = setup.height - setup.insertion_depth  # distance to the free end, for the sampling interval
    sample_every = max(1, round(est_D / setup.samples / (setup.speed * setup.timestep)))

    ds, fs, frames = [], [], []
    mujoco.mj_forward(model, data)  # flexvert_xpos of the current state (it is one step stale after mj_step)
    acc_f, acc_n = 0.0, 0
    last_contact_d = 0.0
    done_after = None
    for i_step in range(n_steps + 1):
        d = i_step * setup.speed * setup.timestep
        if i_step % sample_every == 0:
            mujoco.mj_forward(model, data)
            verts = [v.vertices(data) for v in views]
            frames.append(np.stack(verts))
            ds.append(d)
            fs.append(acc_f / acc_n if acc_n else 0.0)
            acc_f, acc_n = 0.0, 0
            for v, L in zip(verts, rest_len, strict=True):
                max_stretch = max(
                    max_stretch, abs(float(np.linalg.norm(np.diff(v, axis=0), axis=1).sum()) / L - 1)
                )
            if progress is not None:
                progress(d / max_d)
            lowest = min(float(v[:, 2].min()) for v in verts)
            if done_after is None and z0 - d < lowest - 2.0 * (setup.tine_radius + setup.radius):
                done_after = len(ds) + 3  # the tine is below both free ends: a few more samples, then stop
            if done_after is not None and len(ds) >= done_after:
                break
        data.mocap_pos[mocap] = [0.0, 0.0, z0 - d]
        step()
        force, gap_tine, gap_strands = _tine_force(model, data, tine_geom, buf)
        min_gap_tine = min(min_gap_tine, gap_tine)
        min_gap_strands = min(min_gap_strands, gap_strands)
        acc_f += force
        acc_n += 1
        if math.isfinite(gap_tine):  # the tine touches a strand
            last_contact_d = d
        if (i_step + 1) % _CHECK_STEPS == 0:
            topo = check(z0 - d, d, topo)

    d_arr = np.asarray(ds)
    F = np.asarray(fs)
    frames_arr = np.asarray(frames)
    D = float(last_contact_d) if last_contact_d > 0 else float(d_arr[-1])
    x = d_arr / D
    f = F / setup.force_scale
    lk = np.array([linking_number(fr[0], fr[1], closed=False) for fr in frames_arr])
    current = link_current(lk, x, window=5)
    clamped_turns = setup.insertion_depth / setup.pitch
    love = love_tine_force(
        d_arr,
        radius=setup.helix_radius,
        pitch=setup.pitch,
        turns=clamped_turns,
        bending=setup.bending,
        twisting=setup.twisting,
        tightly_wound=setup.R_over_r <= 1.0,
    )
    love_f = np.asarray(love) / setup.force_scale

    s0, lam_init = link_density(frames_arr[0, 0], frames_arr[0, 1])
    lam0 = lk[0] / s0[-1] if s0.size else 1.0
    lam0 = lk[0] / (s0[-1] + 0.5 * (s0[1] - s0[0])) if s0.size > 1 else lam0
    snapshots = {}
    for xs in setup.snapshot_x:
        k = int(np.argmin(np.abs(x - xs)))
        s, lam = link_density(frames_arr[k, 0], frames_arr[k, 1])
        snapshots[float(xs)] = (s, (lam - lam_init) / lam0)

    above = [frames_arr[0, i][frames_arr[0, i][:, 2] >= z0] for i in (0, 1)]
    lk_above = float(linking_number(above[0], above[1], closed=False)) if min(map(len, above)) >= 2 else 0.0

    bend = braid_bend(frames_arr, z0 - d_arr, setup.edges_per_pitch)

    in_stroke = x <= 1.0
    kmax = int(np.argmax(np.where(in_stroke, f, -np.inf)))
    jammed, jam_ratio = jam_metrics(x, f)
    return CombingResult(
        setup=setup,
        d=d_arr,
        x=x,
        F=F,
        f=f,
        lk=lk,
        current=current,
        love_f=love_f,
        snapshots=snapshots,
        D=D,
        f_max=float(f[kmax]),
        x_at_f_max=float(x[kmax]),
        lk0=float(lk[0]),
        lk_end=float(lk[-1]),
        jammed=jammed,
        jam_ratio=float(jam_ratio),
        min_gap_tine=float(min_gap_tine),
        min_gap_strands=float(min_gap_strands),
        lk_above=lk_above,
        max_stretch=float(max_stretch),
        wall_time=time.perf_counter() - t_wall,
        strand_crossings=int(crossings[0]),
        tine_crossings=int(crossings[1] + crossings[2]),
        crossing_d=tuple(crossing_d),
        crossing_lk=crossing_lk[0],
        check_time=check_time[0],
        bend=bend,
        frames=frames_arr if keep_frames else np.zeros((0, 2, 0, 3)),
    )


def replace_setup(setup: CombingSetup, **changes: Any) -> CombingSetup:
    """``dataclasses.replace`` that accepts string values from the CLI.

    For ``q``: ``"none"`` / ``"mid"`` → ``None`` (mid-height insertion); ``"clamp"`` → :meth:`CombingSetup.q_near_clamp`
    of the setup after the other changes.
    """
    typed: dict[str, Any] = {}
    near_clamp = False
    for k, v in changes.items():
        if k not in {f.name for f in fields(CombingSetup)}:
            raise ValueError(f"CombingSetup has no field {k!r}")
        if isinstance(v, str):
            if k == "q" and v.lower() == "clamp":
                near_clamp, v = True, None
            elif k == "q" and v.lower() in ("none", "mid", "midpoint"):
                v = None
            elif k in ("edges_per_pitch", "samples"):
                v = int(v)
            elif k == "snapshot_x":
                v = tuple(float(s) for s in v.split(";"))
            else:
                v = float(v)
        typed[k] = v
    if near_clamp:
        out = replace(setup, **typed)
        return replace(out, q=out.q_near_clamp())
    return replace(setup, **typed)


# ----------------------------------------------------------------------------------------- sweeps and I/O
def run_point(point: dict[str, Any]) -> dict[str, Any]:
    """Sweep worker: ``{"setup": CombingSetup.key(), "seed": int}`` → :meth:`CombingResult.to_dict` (picklable)."""
    setup_d = dict(point["setup"])
    setup_d["snapshot_x"] = tuple(setup_d.get("snapshot_x", CombingSetup.snapshot_x))
    return run_combing(CombingSetup(**setup_d), seed=int(point.get("seed", 0))).to_dict()


def write_run(result: CombingResult, out_dir, *, stem: str = "combing") -> list:
    """Write ``<stem>.csv`` (curves), ``<stem>_snapshots.csv``, ``<stem>.json`` (summary) and ``<stem>.png``."""
    from pathlib import Path

    from ..io import csv_text, write_json, write_text

    out = Path(out_dir)
    header, table = result.csv_rows()
    paths = [write_text(out / f"{stem}.csv", csv_text(header, table.tolist()))]
    rows = [
        [x, float(si), float(v)]
        for x, (s, dl) in result.snapshots.items()
        for si, v in zip(s, dl, strict=True)
    ]
    paths.append(
        write_text(out / f"{stem}_snapshots.csv", csv_text(["x", "s_m", "dlambda_over_lambda0"], rows))
    )
    paths.append(write_json(out / f"{stem}.json", result.summary()))
    plot_run(result, out / f"{stem}.png")
    paths.append(out / f"{stem}.png")
    return paths


def plot_run(result: CombingResult, path) -> None:
    """Thesis-style figure of one run: f(x) with the Love curve (Fig. 2.2c), Δλ/λ0 snapshots (Fig. 2.2e), Lk and
    dLk/dx (Fig. 2.8)."""
    from ..viz import PALETTE, new_figure, save_figure

    st = result.setup
    fig, axes = new_figure(3, 1, width=4.6, height=3.6)
    ax = axes[0, 0]
    keep = result.x <= 1.0
    ax.plot(result.x[keep], result.f[keep], color="k", lw=1.2, label="simulation")
    ax.plot(result.x[keep], result.love_f[keep], "--", color=PALETTE[1], label="Love single helix, no slip")
    top = 1.3 * max(result.f_max, 1e-9)
    ax.set(xlabel="x = d/D", ylabel="f = F l0²/B", ylim=(min(0.0, float(result.f.min())), top), xlim=(0, 1))
    ax.set_title(f"P/r={st.P_over_r:g}, R/r={st.R_over_r:g}, t/r={st.t_over_r:g}, q={st.q_effective:.1f}")
    drops = [b for b in result.breakthroughs() if math.isfinite(b.bend) and b.x_peak <= 1.0]
    for kinked, style in ((True, {"color": "k"}), (False, {"facecolor": "none", "edgecolor": "k"})):
        pts = [(b.x_peak, b.f_peak) for b in drops if b.kinked == kinked]
        if pts:
            label = "break-through at a kink (kink jam)" if kinked else "break-through, braid straight"
            ax.scatter(*zip(*pts, strict=True), s=22, zorder=3, label=label, **style)
    bend = result.bend_per_sample()[keep]
    if np.isfinite(bend).any():
        axb = ax.twinx()
        axb.plot(result.x[keep], bend, color=PALETTE[2], lw=0.8, label="braid bend below the tine")
        axb.axhline(KINK_ANGLE, color=PALETTE[2], lw=0.6, ls=":")
        axb.set(ylabel="bend [deg]", ylim=(0, _bend_axis_top(bend)))
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = axb.get_legend_handles_labels()
        ax.legend(h1 + h2, l1 + l2, fontsize=8)
    else:
        ax.legend(fontsize=8)
    ax = axes[0, 1]
    for i, (x, (s, dl)) in enumerate(sorted(result.snapshots.items())):
        ax.plot(s / s[-1], dl, color=PALETTE[i % len(PALETTE)], lw=1, label=f"x = {x:.1f}")
    ax.axhline(0, color="0.6", lw=0.5)
    ax.set(xlabel="s / L (clamp → free end)", ylabel="Δλ/λ0", title="Link density (Fig. 2.2e)")
    ax.legend(fontsize=8)
    ax = axes[0, 2]
    ax.plot(result.x[keep], result.lk[keep] / result.lk0, color=PALETTE[0], label="Lk/Lk0")
    ax.set(xlabel="x = d/D", ylabel="Lk / Lk0", title="Link and link current (Fig. 2.8)", xlim=(0, 1))
    ax2 = ax.twinx()
    ax2.plot(result.x[keep], result.current[keep] / result.lk0, "--", color=PALETTE[1], label="(dLk/dx)/Lk0")
    ax2.set_ylabel("(dLk/dx) / Lk0")
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="lower left")
    save_figure(fig, path)


def plot_sweep(results: Sequence[CombingResult], vary: str, path) -> None:
    """f(x) for every point of a sweep, coloured by the varied parameter, with f_max vs the parameter (Figs 2.2c–d,
    2.4a–b, 2.6)."""
    from ..viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(3, 1, width=4.8, height=3.6)
    ax = axes[0, 0]
    values = sorted({_vary_value(r, vary) for r in results})
    for r in results:
        i = values.index(_vary_value(r, vary))
        keep = r.x <= 1.0
        ax.plot(r.x[keep], r.f[keep], color=PALETTE[i % len(PALETTE)], lw=1, label=f"{vary} = {values[i]:g}")
        ax.plot(r.x[keep], r.love_f[keep], ":", color=PALETTE[i % len(PALETTE)], lw=0.8)
    handles, labels = ax.get_legend_handles_labels()
    uniq = dict(zip(labels, handles, strict=True))
    ax.legend(uniq.values(), uniq.keys(), fontsize=8)
    fmax = max(r.f_max for r in results)
    ax.set(xlabel="x = d/D", ylabel="f = F l0²/B", ylim=(0, 1.3 * fmax), xlim=(0, 1),
           title="combing force (dotted: Love, no slip)")  # fmt: skip
    ax = axes[0, 1]
    v = np.array([_vary_value(r, vary) for r in results])
    fm = np.array([r.f_max for r in results])
    jam = np.array([r.jammed for r in results])
    ax.plot(v[~jam], fm[~jam], "o", color=PALETTE[0], label="no jam (force flag)")
    ax.plot(v[jam], fm[jam], "s", color=PALETTE[1], label="jammed (force flag)")
    kj = np.array([r.jammed_by_kink for r in results])
    if kj.any():  # the thesis's jam cycle: a break-through at a kink (§2.4)
        ax.plot(v[kj], fm[kj], "o", ms=13, mfc="none", mec="k", label="kink jam")
    passed = np.array([r.strand_crossings > 0 or r.tine_crossings > 0 for r in results])
    if passed.any():  # a contact gave way in these runs: their link accounting excludes the passage
        ax.plot(v[passed], fm[passed], "x", color="k", ms=9, label="strand passage")
    ax.set(xlabel=vary, ylabel="f_max", title=f"maximal force vs {vary}")
    ax.legend(fontsize=8)
    ax = axes[0, 2]
    bend = np.array([r.bend_max for r in results])
    ax.plot(v, bend, "o", color=PALETTE[2])
    ax.axhline(KINK_ANGLE, color="0.5", lw=0.8, ls="--", label=f"kink threshold {KINK_ANGLE:g}°")
    ax.set(xlabel=vary, ylabel="largest bend below the tine [deg]", title="kinking (Fig. 2.2a)",
           ylim=(0, _bend_axis_top(bend)))  # fmt: skip
    ax.legend(fontsize=8)
    save_figure(fig, path)


def _vary_value(result: CombingResult, vary: str) -> float:
    return float(result.setup.q_effective if vary == "q" else getattr(result.setup, vary))


def plot_cost(q: Sequence[float], f_max: Sequence[float], path, *, gammas=(0.0, 0.5, 1.0)) -> None:
    """C(q) of eq. 2.8 for several γ (thesis Fig. 2.4c), optimal q marked."""
    from ..viz import PALETTE, new_figure, save_figure

    order = np.argsort(q)
    q = np.asarray(q, dtype=float)[order]
    f_max = np.asarray(f_max, dtype=float)[order]
    fig, axes = new_figure(1, 1, width=5.0, height=3.8)
    ax = axes[0, 0]
    for i, g in enumerate(gammas):
        c = combing_cost(f_max, q, g)
        ax.plot(q, c, "o-", color=PALETTE[i], label=f"γ = {g:g} (optimal q = {optimal_q(q, f_max, g):g})")
    ax.set(xlabel="q (pitches between tine and free end)", ylabel="C(q) = γ f_max + (1−γ) q0/q",
           title="cost of combing (eq. 2.8, q0 = 25)")  # fmt: skip
    ax.legend(fontsize=8)
    save_figure(fig, path)
