"""Gauss-integral invariants of polylines: linking number, writhe, average crossing number, link density.

Every quantity here is a sum of the exact segment-pair Gauss integral (see :mod:`._kernels`), so results are
exact for polylines up to floating-point rounding — no quadrature, no rounding to integers.

Sign convention: ``linking_number`` follows thesis eq. 1.15 with the usual right-hand rule — a closed curve ``b``
that threads the disk of ``a`` along the disk's right-handed normal has Lk = +1.
"""

from __future__ import annotations

import warnings

import numpy as np

from ._kernels import pair_matrix, pair_row_sums
from ._validate import as_curve

__all__ = [
    "TopologyWarning",
    "average_crossing_number",
    "link_current",
    "link_density",
    "linking_number",
    "pair_gauss_matrix",
    "writhe",
]


class TopologyWarning(UserWarning):
    """Curves touch or intersect, so the Gauss integral is undefined for some segment pairs."""


def _warn_degenerate(count: int, what: str) -> None:
    if count:
        warnings.warn(
            f"{what}: {count} segment pair(s) touch or intersect; Lk is undefined there and those pairs were "
            "counted as 0",
            TopologyWarning,
            stacklevel=3,
        )


def _rows(a: np.ndarray, b: np.ndarray, *, absolute=False, self_pairs=False, closed=False, what=""):
    rows, nbad = pair_row_sums(a, b, absolute, self_pairs, closed)
    _warn_degenerate(int(nbad.sum()), what)
    return rows


def linking_number(a, b, *, closed: bool = True) -> float:
    """Gauss linking integral of two polylines (thesis eq. 1.15), computed exactly.

    Parameters
    ----------
    a, b : (N, 3), (M, 3) array_like
        Vertices of the two curves.
    closed : bool
        If True, each curve is closed by a segment from its last vertex back to its first (skipped if the last
        vertex already repeats the first) and the result is the integer linking number (up to rounding, ~1e-12).
        If False, the open polylines are integrated and the real-valued Gauss integral is returned.

    Returns
    -------
    float
        Not rounded. Segment pairs that touch or intersect (Lk undefined) contribute 0 and raise a
        :class:`TopologyWarning`.
    """
    a = as_curve(a, "a", closed=closed)
    b = as_curve(b, "b", closed=closed)
    return float(_rows(a, b, what="linking_number").sum())


def writhe(curve, *, closed: bool = True) -> float:
    """Writhe of a polyline (thesis eq. 1.18): the Gauss integral of the curve with itself.

    Pairs of segments that share a vertex are excluded (their exact contribution is zero). Both orders of each
    pair are counted, as in the double integral, so Wr = 2 Σ_{i<j} G_ij.
    """
    x = as_curve(curve, "curve", closed=closed)
    return float(_rows(x, x, self_pairs=True, closed=closed, what="writhe").sum())


def average_crossing_number(a, b, *, closed: bool = False) -> float:
    """Absolute Gauss sum Σ_ij |G_ij| over segment pairs of ``a`` and ``b`` (thesis eq. 4.1, the entanglement ``e``).

    Convention: each (segment of ``a``, segment of ``b``) pair is counted once (unordered pairs between the two
    curves). |G_ij| is the fraction of the sphere of view directions from which the two segments appear to cross,
    counting each direction and its opposite as one view, divided by 2. Hence the *mean number of projected
    crossings* between the curves, averaged over all projection directions, is ``2 * average_crossing_number``.
    For ``closed=False`` (default) the curves are open polylines.
    """
    a = as_curve(a, "a", closed=closed)
    b = as_curve(b, "b", closed=closed)
    return float(_rows(a, b, absolute=True, what="average_crossing_number").sum())


def pair_gauss_matrix(a, b) -> np.ndarray:
    """Segment-pair Gauss matrix ``G[i, j]`` of two open polylines (shape ``(N-1, M-1)``); sums to the open Lk."""
    a = as_curve(a, "a")
    b = as_curve(b, "b")
    g, nbad = pair_matrix(a, b)
    _warn_degenerate(int(nbad), "pair_gauss_matrix")
    return g


def link_density(a, b, *, along: str = "centerline") -> tuple[np.ndarray, np.ndarray]:
    """Local link per unit length λ(s) of two strands (e.g. a double helix), thesis chapter 2.

    The open-curve segment-pair matrix ``G`` is summed by rows and columns: segment ``i`` carries
    ``ℓ_i = (Σ_j G_ij + Σ_j G_ji) / 2`` — half of the link its segment of ``a`` has with all of ``b`` and half of
    the link the matching segment of ``b`` has with all of ``a``. Dividing by the segment length ``ds_i`` gives
    λ_i, so that Σ_i λ_i ds_i (∫ λ ds) equals ``linking_number(a, b, closed=False)`` exactly.

    Parameters
    ----------
    a, b : (N, 3) array_like
        The two strands. With ``along="centerline"`` both must have the same number of vertices, and
        s is measured along the centerline (a + b) / 2 (for a double helix: λ → 1/pitch far from the ends).
    along : {"centerline", "a"}
        ``"a"``: rows only (λ_i = Σ_j G_ij / |a_{i+1} − a_i|), s along ``a``; any vertex counts.

    Returns
    -------
    s : (N-1,) array — arclength at segment midpoints.
    lam : (N-1,) array — link per unit length.
    """
    a = as_curve(a, "a")
    b = as_curve(b, "b")
    if along == "centerline":
        if a.shape != b.shape:
            raise ValueError(
                f"b: along='centerline' needs strands with equal vertex counts, got {a.shape[0]} and {b.shape[0]}"
            )
        rows = _rows(a, b, what="link_density")
        # The Gauss integrand is symmetric under swapping the curves, so column sums of G_ab are row sums of G_ba.
        cols = _rows(b, a, what="link_density")
        per_segment = 0.5 * (rows + cols)
        path = 0.5 * (a + b)
    elif along == "a":
        per_segment = _rows(a, b, what="link_density")
        path = a
    else:
        raise ValueError(f"along: expected 'centerline' or 'a', got {along!r}")
    ds = np.linalg.norm(np.diff(path, axis=0), axis=1)
    if np.any(ds <= 0.0):
        raise ValueError("a, b: the centerline has a zero-length segment (strands cross symmetrically)")
    s = np.concatenate([[0.0], np.cumsum(ds)])
    return 0.5 * (s[:-1] + s[1:]), per_segment / ds


def link_current(lk_values, positions, *, window: int = 1) -> np.ndarray:
    """Link current dLk/dx from a time series of Lk sampled at tine positions x (thesis Fig. 2.8).

    Second-order finite differences (``numpy.gradient``) on possibly non-uniform ``positions``, then an optional
    centered moving average over ``window`` samples (odd ``window`` keeps it centered).
    """
    lk = np.asarray(lk_values, dtype=np.float64)
    x = np.asarray(positions, dtype=np.float64)
    if lk.ndim != 1 or x.ndim != 1 or lk.shape != x.shape:
        raise ValueError(
            f"lk_values, positions: expected two 1-D arrays of equal length, got {lk.shape} and {x.shape}"
        )
    if lk.size < 2:
        raise ValueError(f"lk_values: need at least 2 samples, got {lk.size}")
    if not (np.all(np.isfinite(lk)) and np.all(np.isfinite(x))):
        raise ValueError("lk_values, positions: non-finite values")
    dx = np.diff(x)
    if not (np.all(dx > 0) or np.all(dx < 0)):
        raise ValueError("positions: must be strictly monotonic")
    if not isinstance(window, (int, np.integer)) or window < 1:
        raise ValueError(f"window: expected a positive integer, got {window!r}")
    current = np.gradient(lk, x, edge_order=2 if lk.size > 2 else 1)
    if window > 1:
        from scipy.ndimage import uniform_filter1d

        current = uniform_filter1d(current, size=int(window), mode="nearest")
    return current
