"""Random packings of rigid rods ("bird's nest", thesis chapter 4): generation, structure and mechanics.

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

Other model choices (each changes dynamics only, not the statics of the final pile):

* the axial moment of inertia is raised to 5 % of the transverse one: a thin rod's true axial inertia (m d²/8) makes
  the spin DOF stiff enough to blow up the integrator at any practical step;
* while rods are deposited and jostled they feel linear drag with terminal speed 0.25 d per step
  (``terminal_speed``; plus a weak angular drag), so no rod tunnels through another; drag is switched off for the
  mechanical tests;
* rods are added in batches at non-overlapping random positions and isotropic orientations just above the current
  pile, and the model is recompiled per batch (only deposited rods are simulated);
* optional ``freeze_depth``: during deposition, rods buried deeper than ``freeze_depth·L`` below the pile top are
  static geoms (not simulated); all rods are released for the final jostle and drag-free settle.

Known model limitations: MuJoCo's soft friction lets loaded frictional contacts creep slowly. A "settled" 300-rod
pile (α = 76) run for 1 200 more steps without drag kept moving at ~0.1 √(g d) and its fastest rod end drifted
3.9 d (2.7 d with ``noslip_iterations = 10``), while ⟨|cos θ|⟩ changed by < 0.001
(``python scripts/benchmark_rodpile.py --skip-fields --skip-generate --solver-check PILE``). Placement:
new rods start at random positions fully inside the container (``placement``); with the default "centered" rule
flat rods start near the axis, which strengthens the radial inhomogeneity of φ in a 1.5 L container (docs/rod_piles.md).

Determinism: one process, one thread, fixed seed → bitwise identical packings (MuJoCo's pipeline is
deterministic for identical inputs; all randomness comes from ``numpy.random.default_rng(seed)``; wall time is
only recorded in ``meta``). Tested across calls and processes.

Measurements
------------
* :func:`packing_fraction` — φ_f in a bulk slab (central 60 % of the pile height; avoids the ordered floor layer
  and the rough top surface), thesis Fig. 4.5 (φ_f α ≈ const).
* :func:`contact_numbers` — rod–rod contacts per rod from ``data.contact`` after settling; compare
  :func:`philipse_contact_number` (random contact equation, Philipse 1996).
* :func:`orientations` — polar θ ∈ [0, π/2] from the vertical and azimuth ϕ ∈ [0, π) of each rod axis (Fig. 4.7).
* :func:`packing_fraction` with ``wall_margin`` — φ_f only in the inner cylinder R − margin (no wall layer);
  :func:`radial_packing_fraction` — φ in annuli; :func:`phi_seen` — that profile averaged along chosen rods (the
  φ around them, for a local Philipse comparison in radially inhomogeneous piles).
* :func:`mean_abs_sin` — ⟨|sin γ|⟩ of rod pairs; :func:`philipse_contact_number` accepts it to evaluate the random
  contact equation for the measured (non-isotropic) orientation distribution.
* :func:`compress` — piston load–strain loops (Fig. 4.2), repeated cycles (softening, Fig. 4.2d, with a fit
  max load = a + b ln(cycle)) and cycles of increasing amplitude (``strain_schedule``, Mullins-like softening,
  Fig. 4.6); :func:`tension` — glued top/bottom layers pulled apart until they separate (contact-graph criterion),
  disentanglement energy (Fig. 5.3).
"""

from __future__ import annotations

import csv
import json
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..io import atomic_path
from ..topology.proximity import segment_distances

__all__ = [
    "CompressionResult",
    "Packing",
    "TensionResult",
    "compress",
    "contact_numbers",
    "generate_packing",
    "load_packing",
    "mean_abs_sin",
    "orientations",
    "packing_fraction",
    "phi_seen",
    "philipse_contact_number",
    "pile_height",
    "radial_packing_fraction",
    "tension",
]

STEEL_DENSITY = 7850.0  # kg/m³
GRAVITY = 9.81  # m/s²


# ------------------------------------------------------------------------------------------------ Packing


@dataclass(frozen=True)
class Packing:
    """A pile of rods: polylines (2 vertices for rigid rods) of one diameter, optionally in a cylinder.

    Attributes
    ----------
    points : (m, 3) ndarray
        All vertices, rod after rod [m].
    offsets : (n + 1,) int ndarray
        Rod ``i`` is ``points[offsets[i]:offsets[i+1]]``.
    diameter : float
        Rod diameter d [m].
    container_diameter : float
        Inner diameter of the cylindrical container (axis = z through the origin, floor at z = 0); ``nan`` if
        unknown (e.g. CT data).
    meta : dict
        Free-form provenance (seed, generator settings, strain, ...), stored as JSON.
    """

    points: np.ndarray
    offsets: np.ndarray
    diameter: float
    container_diameter: float = float("nan")
    meta: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        pts = np.ascontiguousarray(self.points, dtype=np.float64)
        off = np.ascontiguousarray(self.offsets, dtype=np.int64)
        if pts.ndim != 2 or pts.shape[1] != 3 or not np.all(np.isfinite(pts)):
            raise ValueError(f"points: expected a finite (m, 3) array, got shape {pts.shape}")
        if off.ndim != 1 or off.size < 2 or off[0] != 0 or off[-1] != len(pts) or np.any(np.diff(off) < 2):
            raise ValueError("offsets: must run from 0 to len(points) with ≥ 2 vertices per rod")
        if not (math.isfinite(self.diameter) and self.diameter > 0):
            raise ValueError(f"diameter: must be > 0, got {self.diameter!r}")
        if not (math.isnan(self.container_diameter) or self.container_diameter > 0):
            raise ValueError(f"container_diameter: must be > 0 or nan, got {self.container_diameter!r}")
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "offsets", off)

    @classmethod
    def from_endpoints(cls, endpoints, diameter: float, container_diameter: float = float("nan"), meta=None):
        """Packing of straight rods from an ``(n, 2, 3)`` array of end points."""
        ep = np.asarray(endpoints, dtype=np.float64)
        if ep.ndim != 3 or ep.shape[1:] != (2, 3):
            raise ValueError(f"endpoints: expected shape (n, 2, 3), got {ep.shape}")
        return cls(ep.reshape(-1, 3), np.arange(0, 2 * len(ep) + 1, 2), float(diameter), float(container_diameter),
                   dict(meta or {}))  # fmt: skip

    @property
    def n_rods(self) -> int:
        return len(self.offsets) - 1

    @property
    def is_straight(self) -> bool:
        return bool(np.all(np.diff(self.offsets) == 2))

    @property
    def endpoints(self) -> np.ndarray:
        """``(n, 2, 3)`` first and last vertex of each rod."""
        return np.stack([self.points[self.offsets[:-1]], self.points[self.offsets[1:] - 1]], axis=1)

    @property
    def lengths(self) -> np.ndarray:
        seg = np.linalg.norm(np.diff(self.points, axis=0), axis=1)
        csum = np.concatenate([[0.0], np.cumsum(seg)])
        # segments crossing from one rod to the next are excluded by differencing at rod boundaries
        return csum[self.offsets[1:] - 1] - csum[self.offsets[:-1]]

    @property
    def aspect_ratio(self) -> float:
        return float(np.mean(self.lengths) / self.diameter)

    def segments(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """All polyline segments: start points, end points and the rod each belongs to."""
        keep = np.ones(len(self.points) - 1, dtype=bool)
        keep[self.offsets[1:-1] - 1] = False  # the gap between consecutive rods is not a segment
        owner = np.repeat(np.arange(self.n_rods), np.diff(self.offsets) - 1)
        return self.points[:-1][keep], self.points[1:][keep], owner

    def save(self, path: str | Path) -> Path:
        """Write the packing as NPZ (atomically)."""
        with atomic_path(path) as tmp, open(tmp, "wb") as fh:
            np.savez_compressed(
                fh, points=self.points, offsets=self.offsets, diameter=self.diameter,
                container_diameter=self.container_diameter, meta=json.dumps(self.meta, default=float),
            )  # fmt: skip
        return Path(path)

    def to_csv(self, path: str | Path) -> Path:
        """Write ``rod,x,y,z`` rows (one per vertex; loadable by :func:`load_packing`)."""
        rod = np.repeat(np.arange(self.n_rods), np.diff(self.offsets))
        with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
            fh.write(f"# diameter={self.diameter!r} container_diameter={self.container_diameter!r}\n")
            w = csv.writer(fh)
            w.writerow(["rod", "x", "y", "z"])
            for r, p in zip(rod, self.points, strict=True):
                w.writerow([int(r), f"{p[0]:.9g}", f"{p[1]:.9g}", f"{p[2]:.9g}"])
        return Path(path)


def load_packing(path: str | Path, *, diameter: float | None = None, container_diameter: float | None = None):
    """Load a :class:`Packing` from NPZ (:meth:`Packing.save`) or plain CSV.

    CSV: optional ``#`` comment lines (a ``# diameter=... container_diameter=...`` line is honoured) and an
    optional header; then either 6 columns ``x0,y0,z0,x1,y1,z1`` (one straight rod per row) or 4 columns
    ``rod,x,y,z`` (polylines, e.g. centerlines segmented from CT; vertices of a rod consecutive). ``diameter`` /
    ``container_diameter`` override the file's values; a CSV without a diameter line needs ``diameter``.
    """
    p = Path(path)
    if not p.exists():
        raise ValueError(f"path: packing file not found: {p}")
    if p.suffix == ".npz":
        with np.load(p, allow_pickle=False) as z:
            return Packing(
                z["points"], z["offsets"], float(diameter or z["diameter"]),
                float(container_diameter or z["container_diameter"]), json.loads(str(z["meta"])),
            )  # fmt: skip
    header: dict[str, float] = {}
    rows: list[list[float]] = []
    with open(p, newline="") as fh:
        for line in fh:
            s = line.strip()
            if not s:
                continue
            if s.startswith("#"):
                for tok in s[1:].split():
                    if "=" in tok:
                        k, v = tok.split("=", 1)
                        header[k.strip()] = float(v)
                continue
            try:
                rows.append([float(x) for x in s.replace(",", " ").split()])
            except ValueError:
                if rows:
                    raise ValueError(f"path: non-numeric row in {p}: {s!r}") from None
                continue  # header line
    if not rows:
        raise ValueError(f"path: no data rows in {p}")
    arr = np.asarray(rows)
    d = diameter if diameter is not None else header.get("diameter")
    if d is None:
        raise ValueError("diameter: not in the CSV header; pass diameter=")
    cd = (
        container_diameter
        if container_diameter is not None
        else header.get("container_diameter", float("nan"))
    )
    meta = {"source": str(p)}
    if arr.shape[1] == 6:
        return Packing.from_endpoints(arr.reshape(-1, 2, 3), d, cd, meta)
    if arr.shape[1] == 4:
        rod = arr[:, 0].astype(np.int64)
        starts = np.flatnonzero(np.r_[True, rod[1:] != rod[:-1]])
        if len(np.unique(rod)) != len(starts):
            raise ValueError("path: vertices of each rod must be consecutive in the CSV")
        return Packing(arr[:, 1:], np.r_[starts, len(arr)], float(d), float(cd), meta)
    raise ValueError(f"path: expected 6 (endpoint) or 4 (rod,x,y,z) columns, got {arr.shape[1]}")


# ------------------------------------------------------------------------------------------ measurements


def pile_height(packing: Packing, q: float = 95.0) -> float:
    """Pile height H: the ``q``-th percentile of rod tops (highest vertex + d/2) above the floor z = 0.

    A percentile rather than the maximum because a few rods stick up out of the rough top surface.
    """
    tops = np.maximum.reduceat(packing.points[:, 2], packing.offsets[:-1]) + packing.diameter / 2
    return float(np.percentile(tops, q))


def _clipped_length(packing: Packing, lo: float, hi: float, radius: float = math.inf) -> float:
    """Total centerline length inside the slab lo ≤ z ≤ hi and the cylinder x² + y² ≤ radius² (exact clipping)."""
    return float(np.sum(_clipped_segment_lengths(packing, lo, hi, radius)))


def _clipped_segment_lengths(packing: Packing, lo: float, hi: float, radius: float = math.inf) -> np.ndarray:
    """Per polyline segment (:meth:`Packing.segments`), its length inside the slab and the cylinder."""
    a, b, _ = packing.segments()
    d = b - a
    seg_len = np.linalg.norm(d, axis=1)
    za, dz = a[:, 2], d[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        inside_z = (za >= lo) & (za <= hi)
        t_lo = np.where(dz != 0, (lo - za) / dz, np.where(inside_z, -np.inf, np.inf))
        t_hi = np.where(dz != 0, (hi - za) / dz, np.inf)  # horizontal outside the slab: t0 = t1 = 1
    t0 = np.clip(np.minimum(t_lo, t_hi), 0, 1)
    t1 = np.clip(np.maximum(t_lo, t_hi), 0, 1)
    if math.isfinite(radius):
        # |a_xy + t d_xy|² ≤ r²  ⇔  A t² + B t + C ≤ 0
        qa = d[:, 0] ** 2 + d[:, 1] ** 2
        qb = 2 * (a[:, 0] * d[:, 0] + a[:, 1] * d[:, 1])
        qc = a[:, 0] ** 2 + a[:, 1] ** 2 - radius**2
        vertical = qa < 1e-30
        disc = qb * qb - 4 * qa * qc
        sq = np.sqrt(np.maximum(disc, 0))
        with np.errstate(divide="ignore", invalid="ignore"):
            r0 = np.where(vertical, np.where(qc <= 0, -np.inf, np.inf), (-qb - sq) / (2 * qa))
            r1 = np.where(vertical, np.where(qc <= 0, np.inf, -np.inf), (-qb + sq) / (2 * qa))
        miss = ~vertical & (disc < 0)
        r0, r1 = np.where(miss, np.inf, r0), np.where(miss, -np.inf, r1)
        t0 = np.maximum(t0, np.clip(r0, 0, 1))
        t1 = np.minimum(t1, np.clip(r1, 0, 1))
    return np.maximum(t1 - t0, 0) * seg_len


def packing_fraction(
    packing: Packing, *, slab: tuple[float, float] = (0.2, 0.8), wall_margin: float = 0.0
) -> float:
    """Bulk packing fraction φ_f: rod volume in the slab ``slab·H`` over the container volume of that slab.

    Rod volume = clipped centerline length × πd²/4 (cylindrical rods, as the experiments). H from
    :func:`pile_height`. Needs the container diameter. ``wall_margin`` [m] > 0 measures only in the inner
    cylinder of radius R − wall_margin (away from the wall layer, where rods align with the wall).
    """
    if math.isnan(packing.container_diameter):
        raise ValueError("container_diameter: needed for the packing fraction (unknown for this packing)")
    lo_f, hi_f = slab
    if not 0 <= lo_f < hi_f <= 1:
        raise ValueError(f"slab: expected 0 ≤ lo < hi ≤ 1, got {slab!r}")
    r = packing.container_diameter / 2 - wall_margin
    if not (math.isfinite(wall_margin) and wall_margin >= 0 and r > 0):
        raise ValueError(
            f"wall_margin: must be ≥ 0 and smaller than the container radius, got {wall_margin!r}"
        )
    h = pile_height(packing)
    lo, hi = lo_f * h, hi_f * h
    length = _clipped_length(packing, lo, hi, r if wall_margin > 0 else math.inf)
    return length * math.pi * packing.diameter**2 / 4 / (math.pi * r * r * (hi - lo))


def radial_packing_fraction(
    packing: Packing, n_annuli: int = 6, *, slab: tuple[float, float] = (0.2, 0.8)
) -> tuple[np.ndarray, np.ndarray]:
    """φ in ``n_annuli`` equal-width annuli of the container within the bulk slab: (edges [m], φ per annulus).

    Long rods in a container only a little wider than L cannot lie near the wall except tangentially, so φ is
    radially inhomogeneous; this profile quantifies it and gives the φ "seen" by rods at a given radius.
    """
    if math.isnan(packing.container_diameter):
        raise ValueError("container_diameter: needed for the radial profile (unknown for this packing)")
    if n_annuli < 1:
        raise ValueError(f"n_annuli: must be ≥ 1, got {n_annuli!r}")
    h = pile_height(packing)
    lo, hi = slab[0] * h, slab[1] * h
    if not 0 <= slab[0] < slab[1] <= 1:
        raise ValueError(f"slab: expected 0 ≤ lo < hi ≤ 1, got {slab!r}")
    edges = np.linspace(0, packing.container_diameter / 2, n_annuli + 1)
    cum = np.array([0.0] + [_clipped_length(packing, lo, hi, r) for r in edges[1:-1]]
                   + [_clipped_length(packing, lo, hi)])  # fmt: skip
    vol = math.pi * np.diff(edges**2) * (hi - lo)
    return edges, np.diff(cum) * math.pi * packing.diameter**2 / 4 / vol


def phi_seen(packing: Packing, mask: np.ndarray, n_annuli: int = 6, *, slab=(0.2, 0.8)) -> float:
    """Length-weighted mean of the radial φ profile (:func:`radial_packing_fraction`) along the rods in ``mask``
    (exact length of each rod in each annulus) — the packing fraction around those rods, to evaluate Philipse's
    equation locally in a radially inhomogeneous pile."""
    edges, phi = radial_packing_fraction(packing, n_annuli, slab=slab)
    mask = np.asarray(mask, bool)
    if not mask.any():
        raise ValueError("mask: selects no rods")
    _, _, owner = packing.segments()
    sel = mask[owner]
    cum = [np.zeros(sel.sum())]
    for r in edges[1:-1]:
        cum.append(_clipped_segment_lengths(packing, -math.inf, math.inf, r)[sel])
    cum.append(_clipped_segment_lengths(packing, -math.inf, math.inf)[sel])
    per_annulus = np.diff(np.array(cum), axis=0).sum(axis=1)  # length of the selected rods in each annulus
    return float(per_annulus @ phi / per_annulus.sum())


def random_rod_gas(
    n_rods: int, length: float, diameter: float, *, container_diameter: float, height: float, seed: int = 0
) -> Packing:
    """Geometric reference: isotropic rods with centres uniform in the cylinder, kept only if they lie fully inside
    (radius and z ≥ 0); rods may overlap. It has no mechanics, so its wall layer is purely geometric (a rod near the
    wall fits only when steep or as a chord) — the reference for how much a container lowers the averaged φ_f
    compared with the bulk (Freeman et al., Granular Matter 21, 84, 2019)."""
    if not (isinstance(n_rods, int | np.integer) and n_rods >= 1):
        raise ValueError(f"n_rods: must be a positive integer, got {n_rods!r}")
    radius = container_diameter / 2
    if not radius > length / 2:
        raise ValueError(f"container_diameter: must exceed the rod length, got {container_diameter!r}")
    if not height > 0:
        raise ValueError(f"height: must be > 0, got {height!r}")
    rng = np.random.default_rng(seed)
    ends: list[np.ndarray] = []
    while len(ends) < n_rods:
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        c = np.array([*rng.uniform(-radius, radius, 2), rng.uniform(0, height)])
        e = np.array([c - u * length / 2, c + u * length / 2])
        if np.hypot(e[:, 0], e[:, 1]).max() <= radius and e[:, 2].min() >= 0:
            ends.append(e)
    return Packing.from_endpoints(np.array(ends), diameter, container_diameter, {"generator": "random_rod_gas",
                                                                                  "seed": int(seed)})  # fmt: skip


def philipse_contact_number(phi: float, alpha: float, mean_abs_sin: float | None = None) -> float:
    """Random contact equation (Philipse 1996): ⟨c⟩ = φ (6α² + 24α + 16) / (3α + 2); → 2φα for α ≫ 1.

    It is ⟨c⟩ = φ V_ex / V_rod with the excluded volume of two spherocylinders V_ex = 4πd³/3 + 2πd²L + 2L²d
    ⟨|sin γ|⟩ (γ the angle between their axes), and ⟨|sin γ|⟩ = π/4 for isotropic rods. ``mean_abs_sin``
    replaces π/4 by a measured value (:func:`mean_abs_sin`), i.e. the same equation for a non-isotropic orientation
    distribution (6α² → (24/π) ⟨|sin γ|⟩ α²), still assuming uncorrelated positions.
    """
    s = math.pi / 4 if mean_abs_sin is None else float(mean_abs_sin)
    if not 0 <= s <= 1:
        raise ValueError(f"mean_abs_sin: must be in [0, 1], got {mean_abs_sin!r}")
    return phi * (24 / math.pi * s * alpha**2 + 24 * alpha + 16) / (3 * alpha + 2)


def mean_abs_sin(packing: Packing, mask: np.ndarray | None = None) -> float:
    """⟨|sin γ|⟩ over all pairs of distinct rods (γ = angle between their end-to-end axes; π/4 if isotropic)."""
    ep = packing.endpoints if mask is None else packing.endpoints[np.asarray(mask, bool)]
    if len(ep) < 2:
        raise ValueError("mask: need at least 2 rods")
    u = ep[:, 1] - ep[:, 0]
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    cos = np.clip(u @ u.T, -1, 1)
    sin = np.sqrt(1 - cos**2)
    n = len(u)
    return float((sin.sum() - np.trace(sin)) / (n * (n - 1)))


def orientations(packing: Packing) -> tuple[np.ndarray, np.ndarray]:
    """Polar angle θ ∈ [0, π/2] from the vertical and azimuth ϕ ∈ [0, π) of each rod's end-to-end axis.

    Rod axes are unsigned, so θ is folded onto the upper hemisphere and ϕ taken modulo π (thesis Fig. 4.7). For
    isotropic rods cos θ is uniform on [0, 1] and ϕ uniform.
    """
    ep = packing.endpoints
    u = ep[:, 1] - ep[:, 0]
    u = u / np.linalg.norm(u, axis=1, keepdims=True)
    theta = np.arccos(np.clip(np.abs(u[:, 2]), 0, 1))
    phi = np.mod(np.arctan2(u[:, 1], u[:, 0]), np.pi)
    return theta, phi


# ------------------------------------------------------------------------------------------- simulation


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


def _place_batch(rng, k: int, sp: SimParams, existing: np.ndarray, z_top: float, placement: str = "centered"):
    """Random isotropic rods fully inside the container, not overlapping each other or the pile's top.

    ``placement``: "centered" — the centre is uniform in a disk of radius R − (L/2)|u_xy| (fits for any azimuth,
    so flat rods start near the axis); "uniform" — (centre, direction) uniform over all configurations that fit
    (rejection sampling), so flat rods can also start as chords near the wall.
    """
    L, d = sp.length, sp.diameter
    r = sp.container_diameter / 2
    # new rods spread over a vertical band so they do not overlap; it holds ~6 rods per L of height in a 1.5 L
    # container, and proportionally more in wider containers (same layer density, so the same fall time)
    band = L * max(1.0, k / 6 * (1.5 * L / (2 * r)) ** 2)
    near = (
        existing[np.maximum(existing[:, 0, 2], existing[:, 1, 2]) > z_top - 2 * d]
        if len(existing)
        else existing
    )
    obst0 = list(near[:, 0]) if len(near) else []
    obst1 = list(near[:, 1]) if len(near) else []
    out = []
    for _ in range(k):
        for _attempt in range(200):
            u = rng.normal(size=3)
            u /= np.linalg.norm(u)
            if placement == "uniform":
                rin = r - 1.5 * d
                for _fit in range(1000):
                    rr, ph = math.sqrt(rng.random()) * rin, rng.random() * 2 * math.pi
                    cx, cy = rr * math.cos(ph), rr * math.sin(ph)
                    ex, ey = u[0] * L / 2, u[1] * L / 2
                    if max(math.hypot(cx + ex, cy + ey), math.hypot(cx - ex, cy - ey)) <= rin:
                        break
                    u = rng.normal(size=3)
                    u /= np.linalg.norm(u)
            else:
                rmax = max(r - L / 2 * math.hypot(u[0], u[1]) - 1.5 * d, 0.0)
                rr = math.sqrt(rng.random()) * rmax
                ph = rng.random() * 2 * math.pi
            ext = L / 2 * abs(u[2]) + d
            c = np.array([rr * math.cos(ph), rr * math.sin(ph), z_top + ext + 2 * d + rng.random() * band])
            a0, a1 = c - u * L / 2, c + u * L / 2
            if not obst0 or segment_distances(a0, a1, np.array(obst0), np.array(obst1)).min() > 2 * d:
                break
        else:  # pragma: no cover - only with absurd batch sizes
            c = c + np.array([0, 0, band])
            a0, a1 = c - u * L / 2, c + u * L / 2
        obst0.append(a0)
        obst1.append(a1)
        out.append((a0, a1))
    return np.array(out)


def _jostle(pile: Pile, rng, n_shakes: int, tilt_deg: float) -> None:
    """Shake and tilt the container, simulated in the container's frame (§4.5.1 "jostled ... inverted").

    In the frame of a container that translates with acceleration a(t) and tilts slowly, the rods feel the effective
    gravity g − a(t) rotated by the tilt; the fictitious rotational forces are negligible for slow tilts. So instead
    of moving the walls (a teleported mocap container pushes rods through each other), we vary gravity: magnitude
    g(1 + 1.2 sin ωt) — the pile is thrown up ~1 d each period — while its direction tilts by up to ``tilt_deg``
    about a random horizontal axis and back. Then everything settles under normal gravity.
    """
    sp = pile.sp
    opt = pile.model.opt
    period = 12.6 * math.sqrt(sp.diameter / GRAVITY)  # free-flight time of a ~1 d hop at 0.2 g net lift
    omega = 2 * math.pi / period
    nsteps = int(5 * period / sp.dt)
    for _ in range(n_shakes):
        ph = rng.random() * 2 * math.pi
        axis = np.array([math.cos(ph), math.sin(ph), 0.0])
        for k in range(nsteps):
            ang = math.radians(tilt_deg) * math.sin(math.pi * k / nsteps)
            mag = GRAVITY * (1 + 1.2 * math.sin(omega * k * sp.dt))
            down = np.array([0.0, 0.0, -1.0])
            # Rodrigues rotation of "down" about the horizontal axis
            g_dir = down * math.cos(ang) + np.cross(axis, down) * math.sin(ang)
            opt.gravity[:] = mag * g_dir
            pile.step()
        opt.gravity[:] = [0.0, 0.0, -GRAVITY]
        pile.settle(max_time=8 * math.sqrt(sp.length / GRAVITY), min_time=2 * period)


def generate_packing(
    n_rods: int,
    length: float,
    diameter: float,
    *,
    container_diameter: float | None = None,
    seed: int = 0,
    jostle: bool = True,
    batch_size: int = 10,
    n_shakes: int = 2,
    tilt_deg: float = 20.0,
    friction: float = 0.4,
    wall_friction: float | None = None,
    freeze_depth: float | None = None,
    terminal_speed: float = 0.25,
    placement: str = "centered",
    progress: bool = True,
) -> Packing:
    """Drop ``n_rods`` rigid rods in small batches into a cylinder, jostle and settle (thesis §4.5.1).

    Parameters
    ----------
    n_rods : int
        Number of rods.
    length, diameter : float
        Rod length L and diameter d [m]; α = L/d.
    container_diameter : float, optional
        Cylinder inner diameter (default 3 L, as in the experiments).
    seed : int
        Random seed (positions, orientations, shaking axes).
    jostle : bool
        Shake and tilt the container when half of the rods are in and at the end (§4.5.1), then settle.
    batch_size : int
        Rods dropped together (the experiments drop "steadily and in small numbers").
    n_shakes, tilt_deg : int, float
        Shakes per jostle episode and the tilt of the container during a shake.
    friction : float
        Coulomb friction coefficient (steel on steel ≈ 0.3–0.5).
    wall_friction : float, optional
        Friction of rods on the container wall (default: ``friction``; the floor always has ``friction``). The
        experiments used an acrylic container; frictional walls carry part of the pile's weight (Janssen effect).
    freeze_depth : float, optional
        Speed-up for tall piles, in rod lengths (e.g. 1.0): while rods are being added, rods lying entirely more
        than ``freeze_depth·L`` below the current pile top are made static (they carry the rods above but are not
        simulated), so the cost of a batch scales with the active top layer, not the whole pile. The jostle at
        half-filling then only shakes the active layer. At the end every rod is released and the whole pile is
        jostled (if ``jostle``) and settled without drag, so compaction under the full overburden is simulated.
        ``None`` (default): every rod is simulated all the time.
    terminal_speed : float
        Terminal speed of the deposition drag in rod diameters per time step (default 0.25, i.e. 2.5 √(g d));
        larger values let rods hit the pile faster (≤ 0.5 so that a rod cannot pass through another in one step).
    placement : {"centered", "uniform"}
        Where new rods start (see ``_place_batch``): "centered" (default) keeps the centre within R − (L/2)|u_xy|
        of the axis, so flat rods start near the axis; "uniform" samples (centre, direction) uniformly over all
        configurations inside the container.
    progress : bool
        Show a tqdm progress bar.

    Returns
    -------
    Packing
        Settled rods (end points), with the contact pairs and settings in ``meta``.
    """
    from tqdm import tqdm

    if not (isinstance(n_rods, int | np.integer) and n_rods >= 1):
        raise ValueError(f"n_rods: must be a positive integer, got {n_rods!r}")
    if not (math.isfinite(length) and length > 0):
        raise ValueError(f"length: must be > 0, got {length!r}")
    if not (math.isfinite(diameter) and 0 < diameter < length):
        raise ValueError(f"diameter: must be in (0, length), got {diameter!r}")
    cdia = 3 * length if container_diameter is None else float(container_diameter)
    if not cdia > length + 2 * diameter:
        raise ValueError(f"container_diameter: must exceed the rod length, got {cdia!r}")
    if batch_size < 1:
        raise ValueError(f"batch_size: must be ≥ 1, got {batch_size!r}")
    if placement not in ("centered", "uniform"):
        raise ValueError(f"placement: must be 'centered' or 'uniform', got {placement!r}")
    if not 0 < terminal_speed <= 0.5:
        raise ValueError(
            f"terminal_speed: must be in (0, 0.5] rod diameters per step, got {terminal_speed!r}"
        )
    if freeze_depth is not None and not (math.isfinite(freeze_depth) and freeze_depth > 0):
        raise ValueError(f"freeze_depth: must be > 0 (rod lengths) or None, got {freeze_depth!r}")
    t_wall = time.perf_counter()  # only reported in meta; never used in the simulation
    if wall_friction is not None and not (math.isfinite(wall_friction) and wall_friction >= 0):
        raise ValueError(f"wall_friction: must be ≥ 0 or None, got {wall_friction!r}")
    sp = SimParams(
        length, diameter, cdia, friction=friction, terminal_speed=terminal_speed, wall_friction=wall_friction
    )
    rng = np.random.default_rng(seed)
    ep = np.zeros((0, 2, 3))
    jostle_at = {round(n_rods * 0.5)} if jostle else set()
    pile = None
    t_fall = math.sqrt(2 * length / GRAVITY) * 4  # generous: drag slows the fall
    max_frozen = 0
    with tqdm(
        total=n_rods, desc=f"dropping rods (α={length / diameter:.0f})", unit="rod", disable=not progress
    ) as bar:
        while len(ep) < n_rods:
            k = min(batch_size, n_rods - len(ep))
            z_top = float(np.percentile(np.maximum(ep[:, 0, 2], ep[:, 1, 2]), 90)) if len(ep) else 0.0
            new = _place_batch(rng, k, sp, ep, z_top, placement)
            frozen = np.zeros(len(ep) + k, bool)
            if freeze_depth is not None and len(ep):
                frozen[: len(ep)] = ep[:, :, 2].max(axis=1) < z_top - freeze_depth * length
            ep = np.concatenate([ep, new])
            pos, quat, _ = poses_from_endpoints(ep)
            pile = Pile(sp, pos, quat, glued_bottom=frozen)
            max_frozen = max(max_frozen, int(frozen.sum()))
            pile.settle(max_time=1.5 * t_fall, min_time=0.2 * t_fall)
            ep = pile.endpoints()
            bar.update(k)
            if len(ep) in jostle_at:
                _jostle(pile, rng, n_shakes, tilt_deg)
                ep = pile.endpoints()
    if freeze_depth is not None and pile.glued_bottom.any():
        pos, quat, _ = poses_from_endpoints(ep)
        pile = Pile(sp, pos, quat)  # release every rod
    if jostle:
        _jostle(pile, rng, n_shakes, tilt_deg)
    pile.set_drag(False)
    pile.settle(max_time=2 * t_fall)
    ep = pile.endpoints()
    pairs = pile.contact_pairs()
    meta = {
        "generator": "hairbrush_env.studies.rod_pile.generate_packing",
        "seed": int(seed), "jostle": bool(jostle), "batch_size": int(batch_size), "friction": float(friction),
        "wall_friction": None if wall_friction is None else float(wall_friction),
        "freeze_depth": None if freeze_depth is None else float(freeze_depth),
        "terminal_speed": float(terminal_speed), "max_frozen": max_frozen, "placement": placement,
        "length": float(length), "contact_pairs": pairs.tolist(),
        "lost_rods": int(np.sum(ep[:, :, 2].min(axis=1) < -diameter)),
        "wall_time_s": time.perf_counter() - t_wall,
    }  # fmt: skip
    return Packing.from_endpoints(ep, diameter, cdia, meta)


def contact_numbers(packing: Packing, *, tol: float = 0.02, recompute: bool = False) -> np.ndarray:
    """Number of distinct rods touching each rod (surface gap < ``tol · d``).

    Uses the contact list stored by :func:`generate_packing` / :func:`compress` (MuJoCo contacts with a
    detection gap of 0.02 d) unless ``recompute`` or ``tol`` differs; otherwise recomputes from the geometry with
    an exact segment–segment distance between the rods' capsule axes (end points pulled in by d/2, as simulated).
    """
    n = packing.n_rods
    pairs = packing.meta.get("contact_pairs")
    if pairs is None or recompute or tol != 0.02:
        pairs = _geometric_contacts(packing, tol)
    pairs = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    return np.bincount(pairs.ravel(), minlength=n)


def _geometric_contacts(packing: Packing, tol: float) -> np.ndarray:
    from scipy.spatial import cKDTree

    if not packing.is_straight:
        raise ValueError("packing: contact detection from geometry needs straight rods")
    ep = packing.endpoints
    d = packing.diameter
    u = ep[:, 1] - ep[:, 0]
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    ep = np.stack([ep[:, 0] + u * d / 2, ep[:, 1] - u * d / 2], axis=1)  # capsule axis: caps round the ends
    centers = ep.mean(axis=1)
    half = np.linalg.norm(ep[:, 1] - ep[:, 0], axis=1).max() / 2
    cand = cKDTree(centers).query_pairs(2 * half + d * (1 + tol), output_type="ndarray")
    out = [
        (i, j) for i, j in cand
        if segment_distances(ep[i, 0], ep[i, 1], ep[j, 0:1], ep[j, 1:2])[0] < d * (1 + tol)
    ]  # fmt: skip
    return np.asarray(out, dtype=np.int64).reshape(-1, 2)


def bulk_rods(packing: Packing, *, slab: tuple[float, float] = (0.2, 0.8)) -> np.ndarray:
    """Rods whose center lies in the bulk slab and at least L/2 from the container wall (boolean mask)."""
    h = pile_height(packing)
    c = packing.endpoints.mean(axis=1)
    ok = (c[:, 2] >= slab[0] * h) & (c[:, 2] <= slab[1] * h)
    if not math.isnan(packing.container_diameter):
        L = float(np.mean(packing.lengths))
        ok &= np.hypot(c[:, 0], c[:, 1]) <= packing.container_diameter / 2 - L / 2
    return ok


# ------------------------------------------------------------------------------------------- mechanics


@dataclass(frozen=True)
class CompressionResult:
    """Piston test: load–strain per cycle (thesis Fig. 4.2, 4.6).

    Attributes
    ----------
    strain, load : list of (k,) ndarray
        Per cycle, strain ε = (H0 − z_piston)/H0 and piston load [N] (sum of contact normal forces), loading then
        unloading.
    loading : list of (k,) bool ndarray
        True on the loading branch.
    max_load : (cycles,) ndarray
        Maximum load of each cycle [N].
    dissipated : (cycles,) ndarray
        Loop area ∮ F dz [J] (loading work − unloading work) per cycle; > 0 means energy was dissipated.
    h0 : float
        Initial pile height H0 [m] (:func:`pile_height`), the reference of the strain.
    weight : float
        Weight of the pile [N].
    snapshots : dict[float, Packing]
        Packings at the requested strains (first loading branch).
    final : Packing
        Pile after the last unloading (``None`` when loaded from a file).
    cycle_strain_max : (cycles,) ndarray
        Maximum strain of each cycle (constant for repeated cycles, Fig. 4.2d; increasing for Fig. 4.6).
    """

    strain: list
    load: list
    loading: list
    max_load: np.ndarray
    dissipated: np.ndarray
    h0: float
    weight: float
    snapshots: dict
    final: Packing | None
    cycle_strain_max: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def softening_fit(self) -> tuple[float, float]:
        """Least-squares fit max_load ≈ a + b ln(cycle) over all cycles (the thesis's logarithmic softening,
        Fig. 4.2d inset): returns (a [N], b [N per e-fold of cycles]); b < 0 means softening. Needs ≥ 2 cycles."""
        if len(self.max_load) < 2:
            raise ValueError("cycles: the softening fit needs at least 2 cycles")
        x = np.log(np.arange(1, len(self.max_load) + 1))
        b, a = np.polyfit(x, self.max_load, 1)
        return float(a), float(b)

    def reload_load_at_previous_max(self) -> np.ndarray:
        """For cycles k ≥ 2: the load on loading branch k at the previous cycle's maximum strain (Mullins effect,
        Fig. 4.6: below that cycle's maximum load if the pile softened). ``nan`` for the first cycle."""
        out = np.full(len(self.strain), np.nan)
        for k in range(1, len(self.strain)):
            s, f, lo = self.strain[k], self.load[k], self.loading[k]
            out[k] = float(np.interp(self.cycle_strain_max[k - 1], s[lo], f[lo]))
        return out

    def save(self, path: str | Path) -> Path:
        arrays = {}
        for c, (s, f, lo) in enumerate(zip(self.strain, self.load, self.loading, strict=True)):
            arrays[f"strain_{c}"], arrays[f"load_{c}"], arrays[f"loading_{c}"] = s, f, lo
        with atomic_path(path) as tmp, open(tmp, "wb") as fh:
            np.savez_compressed(fh, max_load=self.max_load, dissipated=self.dissipated, h0=self.h0,
                                weight=self.weight, cycles=len(self.strain),
                                cycle_strain_max=self.cycle_strain_max, **arrays)  # fmt: skip
        return Path(path)

    @classmethod
    def load_file(cls, path: str | Path) -> CompressionResult:
        """Read :meth:`save` output (without the packings)."""
        p = Path(path)
        if not p.exists():
            raise ValueError(f"path: compression file not found: {p}")
        with np.load(p, allow_pickle=False) as z:
            n = int(z["cycles"])
            csm = z["cycle_strain_max"] if "cycle_strain_max" in z else np.array([z["strain_0"].max()] * n)
            return cls([z[f"strain_{c}"] for c in range(n)], [z[f"load_{c}"] for c in range(n)],
                       [z[f"loading_{c}"] for c in range(n)], z["max_load"], z["dissipated"], float(z["h0"]),
                       float(z["weight"]), {}, None, np.asarray(csm, float))  # fmt: skip


def _check_straight(packing: Packing) -> None:
    if not packing.is_straight:
        raise ValueError("packing: mechanical tests need straight rigid rods (2 vertices per rod)")
    if math.isnan(packing.container_diameter):
        raise ValueError("packing: container_diameter unknown; mechanical tests need the container")


def compress(
    packing: Packing,
    strain_max: float = 0.15,
    cycles: int = 1,
    rate: float | None = None,
    *,
    strain_schedule: Sequence[float] | None = None,
    snapshot_strains: Sequence[float] = (),
    friction: float | None = None,
    samples_per_cycle: int = 200,
    progress: bool = True,
) -> CompressionResult:
    """Compress the pile with a piston to ``strain_max`` and back, ``cycles`` times (thesis Fig. 4.2d, 4.6).

    The piston (a plate wider than the container, mocap) starts just above the highest rod and moves at constant
    speed down to z = (1 − ε_max) H0 and back, H0 = :func:`pile_height` (95th percentile of rod tops: the few rods
    sticking out of the surface do not define the height). Strain ε = (H0 − z)/H0, so the first samples have ε < 0
    (the piston meets the protruding rods). The load is the total contact force on the piston (vertical). Drag is
    off, so the only dissipation is frictional sliding and the (critically damped) contacts.

    Parameters
    ----------
    rate : float, optional
        Strain rate [1/s]. Default: piston speed 0.1 √(g d) (0.01 d per step), slow compared with free fall
        over a diameter, i.e. quasi-static.
    strain_schedule : sequence of float, optional
        Maximum strain of each cycle (overrides ``strain_max`` and ``cycles``). Fig. 4.6 protocol:
        ``np.arange(0.06, 0.301, 0.03)`` — cycles of increasing amplitude, to compare with one cycle to 0.30.
    snapshot_strains : sequence of float
        Strains (≤ the first cycle's maximum) at which to return the packing on the first loading branch.
    """
    from tqdm import tqdm

    _check_straight(packing)
    if strain_schedule is None:
        if not 0 < strain_max < 1:
            raise ValueError(f"strain_max: must be in (0, 1), got {strain_max!r}")
        if cycles < 1:
            raise ValueError(f"cycles: must be ≥ 1, got {cycles!r}")
        schedule = np.full(int(cycles), float(strain_max))
    else:
        schedule = np.asarray(strain_schedule, dtype=float).ravel()
        if schedule.size < 1 or not np.all((schedule > 0) & (schedule < 1)):
            raise ValueError(f"strain_schedule: need ≥ 1 strains in (0, 1), got {list(schedule)}")
    snaps_req = sorted(float(s) for s in snapshot_strains)
    if any(not 0 <= s <= schedule[0] for s in snaps_req):
        raise ValueError(f"snapshot_strains: must lie in [0, strain_max], got {snaps_req}")
    ep = packing.endpoints
    pos, quat, length = poses_from_endpoints(ep)
    d = packing.diameter
    fr = packing.meta.get("friction", 0.4) if friction is None else friction
    sp = SimParams(length, d, packing.container_diameter, friction=fr)
    h0 = pile_height(packing)
    z_start = float(ep[:, :, 2].max() + d)  # just above the highest rod: no initial overlap
    pile = Pile(sp, pos, quat, piston_z=z_start)
    pile.set_drag(False)
    pile.settle(max_time=0.5 * math.sqrt(length / GRAVITY))
    speed = 0.1 * math.sqrt(GRAVITY * d) if rate is None else rate * h0
    if not speed > 0:
        raise ValueError(f"rate: must be > 0, got {rate!r}")
    dz_step = speed * sp.dt
    travels = [z_start - (1 - e) * h0 for e in schedule]
    n_halves = [max(math.ceil(tr / dz_step), 2) for tr in travels]
    piston_mask = np.zeros(pile.model.ngeom, bool)
    piston_mask[pile.piston_geom] = True
    data = pile.data
    strains, loads, loadings, snaps = [], [], [], {}
    pending = list(snaps_req)
    with tqdm(total=2 * sum(n_halves), desc="compressing", unit="step", disable=not progress) as bar:
        for c, (travel, n_half) in enumerate(zip(travels, n_halves, strict=True)):
            every = max(n_half // samples_per_cycle, 1)
            s_list, f_list, l_list = [], [], []
            for branch in (0, 1):
                for k in range(n_half + 1):
                    frac = k / n_half if branch == 0 else 1 - k / n_half
                    z = z_start - travel * frac
                    data.mocap_pos[0] = [0.0, 0.0, z]
                    pile.step()
                    eps = (h0 - z) / h0
                    if k % every == 0 or k == n_half:
                        s_list.append(eps)
                        f_list.append(pile.geom_forces(piston_mask)[2])  # rods push the piston up
                        l_list.append(branch == 0)
                    while c == 0 and branch == 0 and pending and eps >= pending[0] - 1e-12:
                        snaps[pending.pop(0)] = _snapshot(pile, packing, eps)
                    if k % 200 == 0:
                        bar.update(min(200, n_half))
            strains.append(np.array(s_list))
            loads.append(np.array(f_list))
            loadings.append(np.array(l_list))
    max_load = np.array([f.max() for f in loads])
    dissipated = np.array(
        [_loop_area(s, f, lo) * h0 for s, f, lo in zip(strains, loads, loadings, strict=True)]
    )
    pile.settle(max_time=0.5 * math.sqrt(length / GRAVITY))
    final = _snapshot(pile, packing, 0.0)
    return CompressionResult(strains, loads, loadings, max_load, dissipated, h0, packing.n_rods * sp.mass * GRAVITY,
                             snaps, final, schedule)  # fmt: skip


def _snapshot(pile: Pile, packing: Packing, strain: float) -> Packing:
    meta = {k: v for k, v in packing.meta.items() if k != "contact_pairs"}
    meta["strain"] = float(strain)
    meta["contact_pairs"] = pile.contact_pairs().tolist()
    return Packing.from_endpoints(pile.endpoints(), packing.diameter, packing.container_diameter, meta)


def _loop_area(strain: np.ndarray, load: np.ndarray, loading: np.ndarray) -> float:
    """∫ F dε on loading minus ∫ F dε on unloading (trapezoid rule)."""
    up = np.trapezoid(load[loading], strain[loading])
    s_dn, f_dn = strain[~loading], load[~loading]
    down = -np.trapezoid(f_dn, s_dn)  # unloading runs from ε_max back to 0
    return float(up - down)


@dataclass(frozen=True)
class TensionResult:
    """Glued top/bottom layers pulled apart (thesis Fig. 5.3).

    Attributes
    ----------
    displacement : (k,) ndarray
        Lift of the top plate [m]; ``strain`` = displacement / H.
    load : (k,) ndarray
        Force holding the top plate [N] (weight of the glued top layer + what hangs on it + friction).
    lifted_weight : (k,) ndarray
        Weight of the lifted part [N]: glued top rods plus free rods that rose by more than half the plate lift.
    energy : float
        Disentanglement energy ∫ (load − lifted_weight) dz [J] from 0 to the separation lift (to the end of the
        run if the parts never separated) — the blue area of Fig. 5.3b.
    separation : float
        Plate lift at which the top and bottom parts separated [m] (Fig. 5.3c), ``nan`` if they had not separated
        by the maximum lift. Separation: the contact network no longer connects any rod of the lifted part (glued
        top rods and the free rods touching them, transitively) to the bottom part (glued bottom rods, the floor
        and the free rods touching them), and stays so for a further lift of 2 d.
    separated : bool
        Whether the parts separated before the maximum lift.
    hanging_weight : float
        Weight [N] of the part hanging from the plate at separation (glued top rods + free rods connected to them),
        which the load converges to (``nan`` if not separated).
    """

    displacement: np.ndarray
    strain: np.ndarray
    load: np.ndarray
    lifted_weight: np.ndarray
    energy: float
    separation: float
    n_glued_top: int
    n_glued_bottom: int
    separated: bool = False
    hanging_weight: float = float("nan")


def _components(n: int, pairs: np.ndarray) -> np.ndarray:
    """Connected-component label of each of ``n`` nodes given undirected edges ``pairs`` (k, 2)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    pairs = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    adj = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    return connected_components(adj, directed=False)[1]


def tension(
    packing: Packing,
    *,
    glue_depth: float = 0.15,
    strain_max: float = 2.0,
    rate: float | None = None,
    wall_friction: float = 0.0,
    samples: int = 300,
    stop_at_separation: bool = True,
    progress: bool = True,
) -> TensionResult:
    """Glue the top and bottom layers and pull them apart (thesis §4.5.2 tension test, Fig. 5.3).

    Rods reaching into the bottom ``glue_depth·H`` are fixed to the floor (epoxy in a petri dish); rods reaching
    into the top ``glue_depth·H`` (and not glued at the bottom) are fixed to a plate that rises at constant speed.
    The container walls stay to hold the loose middle in place but are frictionless by default (the experiment
    pulls a free-standing pile; walls with friction would carry load). The plate rises until the parts separate
    (see :class:`TensionResult`) plus a further 0.05 H to record the load settling on the hanging weight, or up to
    the maximum lift ``strain_max·H`` (default 2 H).
    """
    from tqdm import tqdm

    _check_straight(packing)
    if not 0 < glue_depth < 0.5:
        raise ValueError(f"glue_depth: must be in (0, 0.5), got {glue_depth!r}")
    if not strain_max > 0:
        raise ValueError(f"strain_max: must be > 0, got {strain_max!r}")
    ep = packing.endpoints
    d = packing.diameter
    h = float(ep[:, :, 2].max() + d / 2)
    zmin, zmax = ep[:, :, 2].min(axis=1), ep[:, :, 2].max(axis=1)
    bottom = zmin < glue_depth * h
    top = (zmax > (1 - glue_depth) * h) & ~bottom
    if not top.any() or not bottom.any():
        raise ValueError("glue_depth: no rods in the top or bottom glue layer")
    pos, quat, length = poses_from_endpoints(ep)
    fr = packing.meta.get("friction", 0.4)
    sp = SimParams(length, d, packing.container_diameter, friction=fr, wall_friction=wall_friction)
    pile = Pile(sp, pos, quat, glued_bottom=bottom, glued_top=top)
    pile.set_drag(False)
    pile.settle(max_time=0.5 * math.sqrt(length / GRAVITY))
    top_mask = np.zeros(pile.model.ngeom, bool)
    top_mask[np.isin(pile.geom_rod, np.flatnonzero(top))] = True
    mrod = sp.mass * GRAVITY
    w_top = top.sum() * mrod
    speed = 0.1 * math.sqrt(GRAVITY * d) if rate is None else rate * h
    if not speed > 0:
        raise ValueError(f"rate: must be > 0, got {rate!r}")
    dz_step = speed * sp.dt
    travel = strain_max * h
    nsteps = max(math.ceil(travel / dz_step), 2)
    every = max(min(nsteps // samples, round(0.5 * d / dz_step)), 1)  # sample at least every d/2 of lift
    data = pile.data
    mocap_top = pile.model.body_mocapid[pile.mj.mj_name2id(pile.model, pile.mj.mjtObj.mjOBJ_BODY, "top")]
    z0_free = data.xpos[pile.body_of_rod[pile.free], 2].copy()
    n = packing.n_rods
    # graph nodes: rods 0..n-1, the plate n, the floor (with the glued bottom rods) n + 1
    plate_edges = np.stack([np.flatnonzero(top), np.full(top.sum(), n)], axis=1)
    floor_edges = np.stack([np.flatnonzero(bottom), np.full(bottom.sum(), n + 1)], axis=1)
    floor_geom = pile.floor_geom
    disp, load, lifted = [], [], []
    sep_at, hanging, stop_at = math.nan, math.nan, nsteps
    with tqdm(total=nsteps, desc="pulling apart", unit="step", disable=not progress) as bar:
        k = 0
        while k <= stop_at:
            u = dz_step * k
            data.mocap_pos[mocap_top] = [0.0, 0.0, u]
            pile.step()
            if k % every == 0 or k == stop_at:
                rise = data.xpos[pile.body_of_rod[pile.free], 2] - z0_free
                n_lift = int(np.sum(rise > 0.5 * u)) if u > 2 * d else 0
                disp.append(u)
                load.append(w_top - pile.geom_forces(top_mask)[2])
                lifted.append(w_top + n_lift * mrod)
                if k < stop_at:
                    nc = data.ncon
                    g1, g2 = data.contact.geom1[:nc], data.contact.geom2[:nc]
                    touch = data.contact.dist[:nc] < sp.contact_tol * d
                    at_floor = touch & ((g1 == floor_geom) | (g2 == floor_geom))
                    on_floor = pile.geom_rod[np.where(g1 == floor_geom, g2, g1)[at_floor]]
                    on_floor = on_floor[on_floor >= 0]
                    edges = np.concatenate([pile.contact_pairs(), plate_edges, floor_edges,
                                            np.stack([on_floor, np.full(len(on_floor), n + 1)], axis=1)])  # fmt: skip
                    lab = _components(n + 2, edges)
                    connected = lab[n] == lab[n + 1]
                    if connected:
                        sep_at, hanging = math.nan, math.nan
                        stop_at = nsteps
                    elif math.isnan(sep_at) and u > 0:
                        sep_at = u
                        hanging = float(np.sum(lab[:n] == lab[n]) * mrod)
                        if stop_at_separation:
                            stop_at = min(nsteps, k + math.ceil(max(2 * d, 0.05 * h) / dz_step))
            if k % 200 == 0:
                bar.update(min(200, nsteps))
            k += 1
    disp_a, load_a, lift_a = np.array(disp), np.array(load), np.array(lifted)
    excess = load_a - lift_a
    sep_lift = sep_at if (not math.isnan(sep_at) and disp_a[-1] >= sep_at + 2 * d - 1e-12) else math.nan
    upto = disp_a <= (sep_lift if not math.isnan(sep_lift) else disp_a[-1]) + 1e-12
    energy = float(np.trapezoid(excess[upto], disp_a[upto]))
    separated = not math.isnan(sep_lift)
    return TensionResult(disp_a, disp_a / h, load_a, lift_a, energy, sep_lift, int(top.sum()), int(bottom.sum()),
                         separated, hanging if separated else math.nan)  # fmt: skip


# ------------------------------------------------------------------------------------------------ figures


def plot_compression(
    result: CompressionResult, path: str | Path, *, single: CompressionResult | None = None
) -> Path:
    """Load–strain loops of every cycle (Fig. 4.2e / 4.6) and the maximum load per cycle (Fig. 4.2d inset).

    ``single``: a one-cycle test to the largest strain on a fresh copy of the pile, drawn in red (Fig. 4.6).
    """
    from ..viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(2, 1, width=4.6, height=3.6)
    ax, ax2 = axes[0]
    for c, (s, f) in enumerate(zip(result.strain, result.load, strict=True)):
        col = PALETTE[0] if single is not None else PALETTE[c % len(PALETTE)]
        ax.plot(s, f, color=col, lw=1.0, label=f"cycle {c + 1}" if single is None else None)
    if single is not None:
        ax.plot(single.strain[0], single.load[0], color=PALETTE[1], lw=1.4,
                label=f"single cycle to ε = {single.cycle_strain_max[0]:.2g}")  # fmt: skip
        ax.plot([], [], color=PALETTE[0], label="cycles of increasing ε_max")
    ax.axhline(result.weight, color="0.5", ls=":", lw=1, label="pile weight")
    ax.set(xlabel="strain ε", ylabel="piston load [N]", title="compression cycles")
    ax.legend(fontsize=7)
    cyc = np.arange(1, len(result.max_load) + 1)
    ax2.plot(cyc, result.max_load, "o-", color=PALETTE[0], label="maximum load")
    varying = len(result.cycle_strain_max) > 1 and np.ptp(result.cycle_strain_max) > 0
    if len(cyc) >= 2 and not varying:
        a, b = result.softening_fit()
        x = np.linspace(1, cyc[-1], 50)
        ax2.plot(x, a + b * np.log(x), ":", color=PALETTE[1], label=f"{a:.3g} {b:+.3g} ln(cycle)")
    if varying:
        reload = result.reload_load_at_previous_max()
        ax2.plot(cyc, reload, "s", mfc="none", color=PALETTE[1], label="reload at previous ε_max")
    ax2.set(xlabel="cycle", ylabel="load [N]", title="softening over cycles")
    ax2.legend(fontsize=7)
    save_figure(fig, path)
    return Path(path)


def plot_tension(result: TensionResult, path: str | Path) -> Path:
    """Load and weight of the lifted part vs plate lift; the area between them is the disentanglement energy."""
    from ..viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(1, 1, width=5.0, height=3.8)
    ax = axes[0, 0]
    x = result.displacement * 1e3
    ax.plot(x, result.load, color=PALETTE[0], label="load")
    ax.plot(x, result.lifted_weight, color=PALETTE[1], label="weight of lifted part")
    upto = x <= (result.separation * 1e3 if result.separated else x[-1]) + 1e-9
    ax.fill_between(x[upto], result.lifted_weight[upto], result.load[upto],
                    where=result.load[upto] > result.lifted_weight[upto],
                    color=PALETTE[5], alpha=0.4, label=f"E = {result.energy * 1e3:.3g} mJ")  # fmt: skip
    if result.separated:
        ax.axvline(result.separation * 1e3, color="0.4", ls="--", lw=1, label="separation")
    ax.set(xlabel="plate lift [mm]", ylabel="force [N]", title="pulling glued layers apart (Fig. 5.3b)")
    ax.legend(fontsize=8)
    save_figure(fig, path)
    return Path(path)


def plot_structure(packings: dict, path: str | Path) -> Path:
    """Orientation distributions θ, ϕ (Fig. 4.7c–d) and contact-number distributions (Fig. 4.8) of packings."""
    from ..viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(3, 1, width=4.2, height=3.4)
    a_th, a_ph, a_c = axes[0]
    for k, (label, p) in enumerate(packings.items()):
        col = PALETTE[k % len(PALETTE)]
        th, ph = orientations(p)
        a_th.hist(
            np.degrees(th), bins=18, range=(0, 90), density=True, histtype="step", color=col, label=label
        )
        a_ph.hist(
            np.degrees(ph), bins=18, range=(0, 180), density=True, histtype="step", color=col, label=label
        )
        c = contact_numbers(p)
        a_c.hist(c, bins=np.arange(c.max() + 2) - 0.5, density=True, histtype="step", color=col,
                 label=f"{label}: ⟨c⟩={c.mean():.2f}")  # fmt: skip
    x = np.linspace(0, 90, 50)
    a_th.plot(x, np.sin(np.radians(x)) * np.pi / 180, "k:", lw=1, label="isotropic")
    a_th.set(xlabel="polar angle θ [deg]", ylabel="density")
    a_ph.set(xlabel="azimuth ϕ [deg]", ylabel="density")
    a_c.set(xlabel="contacts per rod c", ylabel="fraction")
    for a in (a_th, a_ph, a_c):
        a.legend(fontsize=7)
    save_figure(fig, path)
    return Path(path)


def plot_phi_alpha(alpha, phi, path: str | Path, *, contacts=None, phi_bulk=None) -> Path:
    """φ_f α vs α (Fig. 4.5: φ_f α ≈ const), and optionally ⟨c⟩ vs Philipse's equation.

    ``phi`` is the container-averaged φ_f; ``phi_bulk`` (optional) the bulk value away from the wall layer
    (inner cylinder R − L/2, :func:`packing_fraction` with ``wall_margin``). Philipse's prediction uses the bulk
    φ when given (the contacts are counted on bulk rods), else φ_f.
    """
    from ..viz import PALETTE, new_figure, save_figure

    alpha, phi = np.asarray(alpha, float), np.asarray(phi, float)
    order = np.argsort(alpha)
    ncols = 2 if contacts is not None else 1
    fig, axes = new_figure(ncols, 1, width=4.6, height=3.6)
    ax = axes[0, 0]
    ax.axhspan(3.0, 6.0, color="0.92", label="real random rod packings (3–6)")
    ax.axhline(3.2, ls=":", color=PALETTE[3], label="thesis Fig. 4.5 fit (3.2)")
    ax.plot(
        alpha[order], (phi * alpha)[order], "o--", mfc="none", color=PALETTE[0], label="container average"
    )
    if phi_bulk is not None:
        pb = np.asarray(phi_bulk, float)
        ax.plot(alpha[order], (pb * alpha)[order], "o-", color=PALETTE[1], label="bulk (≥ L/2 from the wall)")
    top = max(6.5, float(np.nanmax(phi * alpha)) * 1.1)
    ax.set(xlabel="aspect ratio α", ylabel="φ_f α", title="Fig. 4.5", ylim=(0, top))
    ax.legend(fontsize=7)
    if contacts is not None:
        ax2 = axes[0, 1]
        ref = phi if phi_bulk is None else np.asarray(phi_bulk, float)
        pred = np.array([philipse_contact_number(p, a) for p, a in zip(ref, alpha, strict=True)])
        c = np.asarray(contacts, float)
        ax2.fill_between(alpha[order], 0.7 * pred[order], 1.3 * pred[order], color="0.92", label="±30 %")
        ax2.plot(alpha[order], c[order], "o-", color=PALETTE[0], label="simulated ⟨c⟩ (bulk rods)")
        ax2.plot(alpha[order], pred[order], "s--", mfc="none", color=PALETTE[1],
                 label="Philipse φ(6α²+24α+16)/(3α+2)" + ("" if phi_bulk is None else " at bulk φ"))  # fmt: skip
        ax2.set(xlabel="aspect ratio α", ylabel="⟨c⟩", ylim=(0, 1.4 * max(np.nanmax(c), np.nanmax(pred))))
        ax2.legend(fontsize=7)
    save_figure(fig, path)
    return Path(path)
