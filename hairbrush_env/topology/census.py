"""N-body interaction census of a bundle of strands (thesis Fig. 2.1c–d, 2.3b and 2.5).

The bundle is cut into ``n_layers`` equal slabs along ``axis``. In each slab every strand is clipped to the slab,
two strands *interact* if their clipped pieces satisfy the criterion, and the connected clusters of the
interaction graph are counted by their size N (N ≥ 2): a cluster of N mutually connected strands is one N-body
interaction. Counts are summed over slabs and divided by the bundle's extent along ``axis``, giving interactions
per metre ρ_N (the thesis's ρ).

Criteria:

* ``"crossing"`` — the pieces cross when the bundle is viewed side-on, i.e. projected onto the plane spanned by
  ``axis`` and the next coordinate axis ``(axis + 1) % 3`` (the thesis's image-based count, an upper bound);
* ``"contact"`` — the pieces come closer than ``contact_distance`` (centerline distance, e.g. a hair diameter);
* ``"link"`` — |open Gauss integral of the two pieces| exceeds ``lk_threshold`` (0.4 in the thesis, Fig. 2.5b).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from ._kernels import min_segment_distance, pair_matrix
from ._validate import as_curve

__all__ = ["clip_to_slab", "interaction_census"]


def clip_to_slab(curve: np.ndarray, axis: int, lo: float, hi: float) -> list[np.ndarray]:
    """Pieces of a polyline inside ``lo <= curve[:, axis] <= hi`` (exact linear clipping; may be several)."""
    pieces: list[np.ndarray] = []
    current: list[np.ndarray] = []
    for p, q in itertools.pairwise(curve):
        zp, zq = p[axis], q[axis]
        dz = zq - zp
        if dz == 0.0:
            t0, t1 = (0.0, 1.0) if lo <= zp <= hi else (1.0, 0.0)
        else:
            ta, tb = (lo - zp) / dz, (hi - zp) / dz
            t0, t1 = max(0.0, min(ta, tb)), min(1.0, max(ta, tb))
        if t1 <= t0:  # segment outside the slab (or touching it at one point)
            if len(current) >= 2:
                pieces.append(np.array(current))
            current = []
            continue
        start, end = p + t0 * (q - p), p + t1 * (q - p)
        if current and t0 == 0.0:
            current.append(end)
        else:
            if len(current) >= 2:
                pieces.append(np.array(current))
            current = [start, end]
        if t1 < 1.0:  # leaves the slab inside this segment
            pieces.append(np.array(current))
            current = []
    if len(current) >= 2:
        pieces.append(np.array(current))
    # drop degenerate pieces (a segment grazing the slab boundary)
    return [pc for pc in pieces if np.linalg.norm(np.diff(pc, axis=0), axis=1).min() > 0.0]


def _segments_cross_2d(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether any segment of 2-D polyline ``a`` properly intersects any segment of ``b`` (vectorized)."""
    p, r = a[:-1, None, :], (a[1:] - a[:-1])[:, None, :]
    q, s = b[None, :-1, :], (b[1:] - b[:-1])[None, :, :]
    rxs = r[..., 0] * s[..., 1] - r[..., 1] * s[..., 0]
    qp = q - p
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (qp[..., 0] * s[..., 1] - qp[..., 1] * s[..., 0]) / rxs
        u = (qp[..., 0] * r[..., 1] - qp[..., 1] * r[..., 0]) / rxs
    hit = (rxs != 0.0) & (t >= 0.0) & (t <= 1.0) & (u >= 0.0) & (u <= 1.0)
    return bool(hit.any())


def _interact(pa, pb, criterion, axis, lk_threshold, contact_distance) -> bool:
    if criterion == "crossing":
        keep = [axis, (axis + 1) % 3]
        return any(_segments_cross_2d(x[:, keep], y[:, keep]) for x in pa for y in pb)
    if criterion == "contact":
        return any(min_segment_distance(x, y) < contact_distance for x in pa for y in pb)
    lk = sum(pair_matrix(x, y)[0].sum() for x in pa for y in pb)
    return abs(lk) > lk_threshold


def interaction_census(
    strands: Sequence[np.ndarray],
    *,
    n_layers: int = 20,
    criterion: str = "crossing",
    lk_threshold: float = 0.4,
    contact_distance: float | None = None,
    axis: int = 2,
) -> dict[int, float]:
    """Interactions per metre by cluster size N, ``{N: ρ_N}`` for N = 2 … largest cluster found.

    Parameters
    ----------
    strands : sequence of (n_i, 3) arrays — the bundle's centerlines.
    n_layers : number of equal slabs along ``axis`` (20 in the thesis).
    criterion : ``"crossing"`` | ``"contact"`` | ``"link"`` (see the module docstring).
    lk_threshold : |Lk| threshold for ``"link"``.
    contact_distance : distance threshold for ``"contact"`` (required there).
    axis : bundle axis (0, 1 or 2).
    """
    if criterion not in ("crossing", "contact", "link"):
        raise ValueError(f"criterion: expected 'crossing', 'contact' or 'link', got {criterion!r}")
    if axis not in (0, 1, 2):
        raise ValueError(f"axis: expected 0, 1 or 2, got {axis!r}")
    if int(n_layers) != n_layers or n_layers < 1:
        raise ValueError(f"n_layers: expected a positive integer, got {n_layers!r}")
    if criterion == "contact" and (contact_distance is None or not contact_distance > 0):
        raise ValueError(
            f"contact_distance: criterion='contact' needs a positive distance, got {contact_distance!r}"
        )
    if criterion == "link" and not lk_threshold >= 0:
        raise ValueError(f"lk_threshold: must be >= 0, got {lk_threshold!r}")
    curves = [as_curve(s, f"strands[{i}]") for i, s in enumerate(strands)]
    if len(curves) < 2:
        raise ValueError(f"strands: need at least 2 strands, got {len(curves)}")
    coords = np.concatenate([c[:, axis] for c in curves])
    z0, z1 = float(coords.min()), float(coords.max())
    if z1 <= z0:
        raise ValueError("strands: the bundle has zero extent along the axis")
    edges = np.linspace(z0, z1, int(n_layers) + 1)
    counts: dict[int, int] = {}
    for lo, hi in itertools.pairwise(edges):
        pieces = [clip_to_slab(c, axis, lo, hi) for c in curves]
        rows, cols = [], []
        for i in range(len(curves)):
            for j in range(i + 1, len(curves)):
                if (
                    pieces[i]
                    and pieces[j]
                    and _interact(pieces[i], pieces[j], criterion, axis, lk_threshold, contact_distance)
                ):
                    rows.append(i)
                    cols.append(j)
        if not rows:
            continue
        graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(curves),) * 2)
        _, labels = connected_components(graph, directed=False)
        sizes = np.bincount(labels)
        for size in sizes[sizes >= 2]:
            counts[int(size)] = counts.get(int(size), 0) + 1
    length = z1 - z0
    top = max(counts, default=1)
    return {n: counts.get(n, 0) / length for n in range(2, top + 1)}
