"""Structure of a packing, measured on its geometry (thesis Figs 4.5, 4.7, 4.8; no simulation needed).

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
* :func:`bulk_rods` — the rods away from the floor, the top surface and the wall layer, on which contacts are
  compared with Philipse; :func:`random_rod_gas` — a geometric reference packing (rods may overlap).
"""

from __future__ import annotations

import math

import numpy as np

from ...topology.proximity import segment_distances
from .packing import Packing, pile_height

__all__ = [
    "bulk_rods",
    "contact_numbers",
    "mean_abs_sin",
    "orientations",
    "packing_fraction",
    "phi_seen",
    "philipse_contact_number",
    "radial_packing_fraction",
    "random_rod_gas",
]


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
