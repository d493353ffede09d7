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

The thesis chose 0.4 as "roughly the smallest linking threshold that provides nontrivial segregation of interaction
types" for its curls. :func:`empirical_lk_threshold` applies that rule to other bundles: the smallest threshold at
which no layer's strands all fall into one cluster (computed exactly from the layers' |Lk| matrices,
:func:`layer_link_matrices`, as the largest maximum-spanning-tree bottleneck over the layers);
:func:`link_census_from_matrices` then counts clusters at any threshold without recomputing the integrals.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components, minimum_spanning_tree

from ._kernels import min_segment_distance, pair_matrix
from ._validate import as_curve

__all__ = [
    "clip_to_slab",
    "empirical_lk_threshold",
    "interaction_census",
    "layer_link_matrices",
    "link_census_from_matrices",
]


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


def _interact(pa, pb, criterion, axis, contact_distance) -> bool:
    """The ``"crossing"`` and ``"contact"`` criteria for two strands' pieces in one layer (``"link"`` goes through
    :func:`layer_link_matrices`)."""
    if criterion == "crossing":
        keep = [axis, (axis + 1) % 3]
        return any(_segments_cross_2d(x[:, keep], y[:, keep]) for x in pa for y in pb)
    return any(min_segment_distance(x, y) < contact_distance for x in pa for y in pb)


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
    if criterion == "contact" and (contact_distance is None or not contact_distance > 0):
        raise ValueError(
            f"contact_distance: criterion='contact' needs a positive distance, got {contact_distance!r}"
        )
    if criterion == "link":
        if not lk_threshold >= 0:
            raise ValueError(f"lk_threshold: must be >= 0, got {lk_threshold!r}")
        mats, extent = layer_link_matrices(strands, n_layers=n_layers, axis=axis)
        return link_census_from_matrices(mats, lk_threshold, extent)
    curves, edges, extent = _layered_curves(strands, n_layers, axis)
    counts: dict[int, int] = {}
    for lo, hi in itertools.pairwise(edges):
        pieces = [clip_to_slab(c, axis, lo, hi) for c in curves]
        rows, cols = [], []
        for i in range(len(curves)):
            for j in range(i + 1, len(curves)):
                if (
                    pieces[i]
                    and pieces[j]
                    and _interact(pieces[i], pieces[j], criterion, axis, contact_distance)
                ):
                    rows.append(i)
                    cols.append(j)
        _count_clusters(rows, cols, len(curves), counts)
    return _per_metre(counts, extent)


def _count_clusters(rows: list[int], cols: list[int], n: int, counts: dict[int, int]) -> None:
    """Add the connected clusters (size ≥ 2) of one layer's interaction graph to ``counts``."""
    if not rows:
        return
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    sizes = np.bincount(labels)
    for size in sizes[sizes >= 2]:
        counts[int(size)] = counts.get(int(size), 0) + 1


def _per_metre(counts: dict[int, int], length: float) -> dict[int, float]:
    top = max(counts, default=1)
    return {n: counts.get(n, 0) / length for n in range(2, top + 1)}


def _layered_curves(
    strands: Sequence[np.ndarray], n_layers: int, axis: int
) -> tuple[list[np.ndarray], np.ndarray, float]:
    """Validated curves, the layer edges along ``axis`` and the bundle's extent."""
    if axis not in (0, 1, 2):
        raise ValueError(f"axis: expected 0, 1 or 2, got {axis!r}")
    if int(n_layers) != n_layers or n_layers < 1:
        raise ValueError(f"n_layers: expected a positive integer, got {n_layers!r}")
    curves = [as_curve(s, f"strands[{i}]") for i, s in enumerate(strands)]
    if len(curves) < 2:
        raise ValueError(f"strands: need at least 2 strands, got {len(curves)}")
    coords = np.concatenate([c[:, axis] for c in curves])
    z0, z1 = float(coords.min()), float(coords.max())
    if z1 <= z0:
        raise ValueError("strands: the bundle has zero extent along the axis")
    return curves, np.linspace(z0, z1, int(n_layers) + 1), z1 - z0


def layer_link_matrices(
    strands: Sequence[np.ndarray], *, n_layers: int = 20, axis: int = 2
) -> tuple[np.ndarray, float]:
    """|Lk| of every strand pair's pieces in every layer, and the bundle's extent along ``axis``.

    Returns ``(mats, extent)``: ``mats[k, i, j]`` = |Σ Gauss integrals of strand i's and strand j's pieces in layer
    k| (symmetric; NaN where strand i or j has no piece in the layer, 0 on the diagonal), the quantity that the
    ``"link"`` criterion of :func:`interaction_census` compares with its threshold.
    """
    curves, edges, extent = _layered_curves(strands, n_layers, axis)
    n = len(curves)
    mats = np.full((int(n_layers), n, n), np.nan)
    for k, (lo, hi) in enumerate(itertools.pairwise(edges)):
        pieces = [clip_to_slab(c, axis, lo, hi) for c in curves]
        for i in range(n):
            if not pieces[i]:
                continue
            mats[k, i, i] = 0.0
            for j in range(i + 1, n):
                if pieces[j]:
                    lk = sum(pair_matrix(x, y)[0].sum() for x in pieces[i] for y in pieces[j])
                    mats[k, i, j] = mats[k, j, i] = abs(lk)
    return mats, extent


def _check_mats(mats) -> np.ndarray:
    mats = np.asarray(mats, dtype=float)
    if mats.ndim != 3 or mats.shape[1] != mats.shape[2]:
        raise ValueError(f"mats: expected shape (layers, n, n), got {mats.shape}")
    return mats


def link_census_from_matrices(mats: np.ndarray, threshold: float, extent: float) -> dict[int, float]:
    """``{N: ρ_N}`` of the ``"link"`` criterion at ``threshold`` from :func:`layer_link_matrices` output."""
    mats = _check_mats(mats)
    if not threshold >= 0:
        raise ValueError(f"threshold: must be >= 0, got {threshold!r}")
    if not extent > 0:
        raise ValueError(f"extent: must be > 0, got {extent!r}")
    counts: dict[int, int] = {}
    for m in mats:
        rows, cols = np.nonzero(np.triu(np.nan_to_num(m, nan=-1.0) > threshold, 1))
        _count_clusters(rows.tolist(), cols.tolist(), m.shape[0], counts)
    return _per_metre(counts, extent)


def empirical_lk_threshold(mats: np.ndarray) -> float:
    """Smallest threshold m at which no layer's strands all join one ``"link"`` cluster (|Lk| > m).

    For each layer with ≥ 2 strands present, the interaction graph {|Lk| > m} connects all of them exactly when m is
    below the layer's bottleneck: the smallest edge of a maximum spanning tree of the |Lk| weights. The returned m is
    the largest bottleneck over the layers (0 if no layer has 2 strands), so at m the census shows no all-strand
    cluster, and just below m at least one layer does. ``mats`` may hold several bundles' layers stacked along axis
    0 (one threshold for all, as the thesis chose one for all its curls).
    """
    mats = _check_mats(mats)
    best = 0.0
    for m in mats:
        present = ~np.isnan(np.diag(m))
        w = m[np.ix_(present, present)]
        if len(w) < 2:
            continue
        # maximum spanning tree = minimum spanning tree of (top − w); zero entries mean "no edge" to scipy
        top = float(np.nanmax(w)) + 1.0
        cost = np.triu(top - np.nan_to_num(w, nan=0.0), 1)
        tree = minimum_spanning_tree(cost)
        best = max(best, top - float(tree.data.max()))
    return best
