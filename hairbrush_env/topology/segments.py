"""Gauss integrals of many independent straight-segment pairs (rod piles, thesis chapter 4, eq. 4.1).

:mod:`.gauss` integrates two polylines against each other. A pile of rigid rods instead needs the Gauss term of
*many unrelated* segment pairs — every pair of rods clipped to a sub-volume Ω — so these kernels evaluate the same
exact pair term (:func:`._kernels._pair_term`, the signed solid angle of the difference parallelogram / 4π) over
flat arrays of segments, in parallel, without building curves.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ._kernels import _pair_term

__all__ = ["grouped_pair_acn", "segment_pair_gauss"]


@nb.njit(cache=True, inline="always")
def _gauss_of(a0x, a0y, a0z, a1x, a1y, a1z, b0x, b0y, b0z, b1x, b1y, b1z):  # pragma: no cover - compiled
    px, py, pz = b0x - a0x, b0y - a0y, b0z - a0z
    qx, qy, qz = b1x - a0x, b1y - a0y, b1z - a0z
    rx, ry, rz = b1x - a1x, b1y - a1y, b1z - a1z
    sx, sy, sz = b0x - a1x, b0y - a1y, b0z - a1z
    pn = math.sqrt(px * px + py * py + pz * pz)
    qn = math.sqrt(qx * qx + qy * qy + qz * qz)
    rn = math.sqrt(rx * rx + ry * ry + rz * rz)
    sn = math.sqrt(sx * sx + sy * sy + sz * sz)
    return _pair_term(px, py, pz, pn, qx, qy, qz, qn, rx, ry, rz, rn, sx, sy, sz, sn)


@nb.njit(cache=True, parallel=True)
def _pairs_kernel(a0, a1, b0, b1):  # pragma: no cover - compiled
    m = a0.shape[0]
    out = np.empty(m)
    bad = np.zeros(m, dtype=np.bool_)
    for k in nb.prange(m):
        g, b = _gauss_of(
            a0[k, 0], a0[k, 1], a0[k, 2], a1[k, 0], a1[k, 1], a1[k, 2],
            b0[k, 0], b0[k, 1], b0[k, 2], b1[k, 0], b1[k, 1], b1[k, 2],
        )  # fmt: skip
        out[k] = 0.0 if b else g
        bad[k] = b
    return out, bad


@nb.njit(cache=True, parallel=True)
def _grouped_kernel(p0, p1, owner, starts):  # pragma: no cover - compiled
    ngroups = starts.shape[0] - 1
    out = np.zeros(ngroups)
    nbad = np.zeros(ngroups, dtype=np.int64)
    for g in nb.prange(ngroups):
        lo, hi = starts[g], starts[g + 1]
        total = 0.0
        # runs of equal owner are contiguous (caller sorts by group, then owner)
        i = lo
        while i < hi:
            iend = i + 1
            while iend < hi and owner[iend] == owner[i]:
                iend += 1
            j = iend
            while j < hi:
                jend = j + 1
                while jend < hi and owner[jend] == owner[j]:
                    jend += 1
                acc = 0.0
                for s in range(i, iend):
                    for t in range(j, jend):
                        v, b = _gauss_of(
                            p0[s, 0], p0[s, 1], p0[s, 2], p1[s, 0], p1[s, 1], p1[s, 2],
                            p0[t, 0], p0[t, 1], p0[t, 2], p1[t, 0], p1[t, 1], p1[t, 2],
                        )  # fmt: skip
                        if b:
                            nbad[g] += 1
                        else:
                            acc += v
                total += abs(acc)
                j = jend
            i = iend
        out[g] = total
    return out, nbad


def _segments(x, name: str) -> np.ndarray:
    arr = np.ascontiguousarray(x, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"{name}: expected shape (m, 3), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name}: non-finite coordinates")
    return arr


def segment_pair_gauss(a0, a1, b0, b1) -> tuple[np.ndarray, np.ndarray]:
    """Exact open Gauss integral of each segment pair ``(a0[k]→a1[k], b0[k]→b1[k])``.

    Parameters
    ----------
    a0, a1, b0, b1 : (m, 3) array_like
        Start and end points of the first and second segment of each pair.

    Returns
    -------
    g : (m,) ndarray
        Gauss integral of each pair (thesis eq. 1.15 / 4.1 on one pair); its absolute value is the pair's average
        crossing number. Degenerate pairs (segments touching or intersecting) are set to 0.
    degenerate : (m,) bool ndarray
        Which pairs were degenerate.
    """
    arrs = [_segments(x, n) for x, n in ((a0, "a0"), (a1, "a1"), (b0, "b0"), (b1, "b1"))]
    if len({a.shape[0] for a in arrs}) != 1:
        raise ValueError(f"a0, a1, b0, b1: lengths differ {[a.shape[0] for a in arrs]}")
    return _pairs_kernel(*arrs)


def grouped_pair_acn(p0, p1, owner, starts) -> tuple[np.ndarray, np.ndarray]:
    """Per group, Σ over distinct owner pairs of |Gauss integral between their segments| (eq. 4.1 per Ω).

    Segments ``p0[k]→p1[k]`` are sorted by group and, within a group, by ``owner`` (a rod id); group ``g`` holds
    segments ``starts[g]:starts[g+1]``. For each group the result is ``Σ_{i<j} |Σ_{s∈i, t∈j} G(s, t)|`` — the
    average crossing number of every pair of curves in the group, with each curve's pieces summed *before* the
    absolute value (a straight rod clipped to a convex cell is one segment).

    Returns
    -------
    acn : (n_groups,) ndarray
    degenerate : (n_groups,) int ndarray
        Number of touching/intersecting segment pairs per group (counted as 0).
    """
    p0, p1 = _segments(p0, "p0"), _segments(p1, "p1")
    owner = np.ascontiguousarray(owner, dtype=np.int64)
    starts = np.ascontiguousarray(starts, dtype=np.int64)
    if p0.shape != p1.shape or owner.shape != (p0.shape[0],):
        raise ValueError(f"p0, p1, owner: inconsistent shapes {p0.shape}, {p1.shape}, {owner.shape}")
    if (
        starts.ndim != 1
        or starts.size < 1
        or starts[0] != 0
        or starts[-1] != p0.shape[0]
        or np.any(np.diff(starts) < 0)
    ):
        raise ValueError("starts: must be non-decreasing offsets from 0 to the number of segments")
    return _grouped_kernel(p0, p1, owner, starts)
