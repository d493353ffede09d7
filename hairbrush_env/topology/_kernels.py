"""Numba kernels: the exact Gauss integral of a pair of straight segments.

For segments ``a0→a1`` and ``b0→b1`` the difference vectors ``b(t) − a(s)`` sweep a planar parallelogram with
corners ``b0−a0, b1−a0, b1−a1, b0−a1``. The Gauss integral of the pair (thesis eq. 1.15) is the signed solid angle
Ω that parallelogram subtends at the origin, divided by 4π (Banchoff 1976; Klenin & Langowski 2000). We split it
into two triangles and evaluate each with the Van Oosterom–Strackee formula::

    tan(Ω_T / 2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|)

which is the robust two-atan2 form of Arai (2013). Because the parallelogram never contains the origin unless the
segments intersect, |Ω| < 2π, so the two half-angles can be summed by multiplying the complex numbers
``D + iN`` of the two triangles and taking ONE atan2 of the product — exact, with no branch cut inside the domain.

Hot-loop design (≥ 5e7 pairs/s on 2 cores): rows (segments of the first curve) run in parallel; inside a row the
vertex differences and their norms for vertex ``j+1`` are carried over to segment ``j+1``, so each segment pair
costs two new difference vectors, two square roots, one atan2 and ~60 flops, with no temporaries.
"""

from __future__ import annotations

import math
import os

import numba as nb
import numpy as np

# GNU OpenMP (numba's usual default here) aborts a forked child once the parent has used its thread pool, which
# breaks fork-based vectorized envs (AsyncVectorEnv, SubprocVecEnv). Unless the user chose a threading layer,
# prefer TBB, then the fork-safe workqueue, over OpenMP.
if "NUMBA_THREADING_LAYER" not in os.environ and "NUMBA_THREADING_LAYER_PRIORITY" not in os.environ:
    nb.config.THREADING_LAYER_PRIORITY = ["tbb", "workqueue", "omp"]

_INV_2PI = 1.0 / (2.0 * math.pi)


@nb.njit(cache=True, fastmath=False, inline="always")
def _pair_term(
    px,
    py,
    pz,
    pn,  # b_j - a_i       (corner 1) and its norm
    qx,
    qy,
    qz,
    qn,  # b_{j+1} - a_i   (corner 2)
    rx,
    ry,
    rz,
    rn,  # b_{j+1} - a_{i+1} (corner 3)
    sx,
    sy,
    sz,
    sn,  # b_j - a_{i+1}   (corner 4)
):  # pragma: no cover - compiled
    # Triangle 1: (p, q, r)
    cx = qy * rz - qz * ry
    cy = qz * rx - qx * rz
    cz = qx * ry - qy * rx
    n1 = px * cx + py * cy + pz * cz
    m1 = pn * qn * rn
    d1 = (
        m1
        + (px * qx + py * qy + pz * qz) * rn
        + (px * rx + py * ry + pz * rz) * qn
        + (qx * rx + qy * ry + qz * rz) * pn
    )
    # Triangle 2: (p, r, s)
    cx = ry * sz - rz * sy
    cy = rz * sx - rx * sz
    cz = rx * sy - ry * sx
    n2 = px * cx + py * cy + pz * cz
    m2 = pn * rn * sn
    d2 = (
        m2
        + (px * rx + py * ry + pz * rz) * sn
        + (px * sx + py * sy + pz * sz) * rn
        + (rx * sx + ry * sy + rz * sz) * pn
    )
    # Ω/2 = arg((d1 + i n1)(d2 + i n2)); Gauss integral = Ω / 4π = arg / 2π. The minus sign orients the result
    # like eq. 1.15, (1/4π)∮∮ (r1−r2)·(dr1×dr2)/|r1−r2|³ (checked against quadrature in the tests).
    g = -math.atan2(n1 * d2 + n2 * d1, d1 * d2 - n1 * n2) * _INV_2PI
    # Degenerate pair (segments touch or intersect: the origin lies on the parallelogram, Lk undefined).
    # Only possible when a triangle's solid angle reaches π (D ≤ 0 up to rounding), so the cheap test guards the
    # exact one: the origin is then coplanar with both triangles (N ≈ 0).
    bad = False
    tol = 1e-12
    if d1 <= tol * m1 or d2 <= tol * m2:
        bad = abs(n1) <= tol * m1 + 1e-300 and abs(n2) <= tol * m2 + 1e-300
    return g, bad


@nb.njit(cache=True, fastmath=False, inline="always")
def _row_sum(a, b, i, absolute, skip_adjacent, closed_self):  # pragma: no cover - compiled
    """Σ_j G_ij (or Σ_j |G_ij|) for segment ``i`` of ``a`` against all segments of ``b``, and its degenerate count."""
    n = a.shape[0] - 1
    m = b.shape[0] - 1
    a0x, a0y, a0z = a[i, 0], a[i, 1], a[i, 2]
    a1x, a1y, a1z = a[i + 1, 0], a[i + 1, 1], a[i + 1, 2]
    # corner vectors for vertex j = 0
    px = b[0, 0] - a0x
    py = b[0, 1] - a0y
    pz = b[0, 2] - a0z
    sx = b[0, 0] - a1x
    sy = b[0, 1] - a1y
    sz = b[0, 2] - a1z
    pn = math.sqrt(px * px + py * py + pz * pz)
    sn = math.sqrt(sx * sx + sy * sy + sz * sz)
    acc = 0.0
    nbad = 0
    for j in range(m):
        qx = b[j + 1, 0] - a0x
        qy = b[j + 1, 1] - a0y
        qz = b[j + 1, 2] - a0z
        rx = b[j + 1, 0] - a1x
        ry = b[j + 1, 1] - a1y
        rz = b[j + 1, 2] - a1z
        qn = math.sqrt(qx * qx + qy * qy + qz * qz)
        rn = math.sqrt(rx * rx + ry * ry + rz * rz)
        use = True
        if skip_adjacent:
            d = i - j
            if d >= -1 and d <= 1:
                use = False
            elif closed_self and (d == n - 1 or d == 1 - n):
                use = False
        if use:
            g, bad = _pair_term(px, py, pz, pn, qx, qy, qz, qn, rx, ry, rz, rn, sx, sy, sz, sn)
            if bad:
                nbad += 1
            else:
                acc += abs(g) if absolute else g
        # vertex j+1 becomes vertex j of the next segment
        px, py, pz, pn = qx, qy, qz, qn
        sx, sy, sz, sn = rx, ry, rz, rn
    return acc, nbad


@nb.njit(cache=True, parallel=True, fastmath=False)
def _pair_row_sums_parallel(a, b, absolute, skip_adjacent, closed_self):  # pragma: no cover - compiled
    n = a.shape[0] - 1
    out = np.zeros(n)
    nbad = np.zeros(n, dtype=np.int64)
    for i in nb.prange(n):
        out[i], nbad[i] = _row_sum(a, b, i, absolute, skip_adjacent, closed_self)
    return out, nbad


@nb.njit(cache=True, fastmath=False)
def _pair_row_sums_serial(a, b, absolute, skip_adjacent, closed_self):  # pragma: no cover - compiled
    n = a.shape[0] - 1
    out = np.zeros(n)
    nbad = np.zeros(n, dtype=np.int64)
    for i in range(n):
        out[i], nbad[i] = _row_sum(a, b, i, absolute, skip_adjacent, closed_self)
    return out, nbad


#: Below this many segment pairs the serial kernel is used: starting worker threads costs more than it saves,
#: and processes that only do small problems (e.g. an env computing its wig's entanglement) never start a
#: thread pool, so they can fork safely (vectorized RL envs).
PARALLEL_MIN_PAIRS = 200_000


def pair_row_sums(a, b, absolute, skip_adjacent, closed_self):
    """Row sums of the segment-pair Gauss matrix.

    ``a`` (n+1, 3) and ``b`` (m+1, 3) are polylines whose consecutive vertices form the segments. Returns
    ``out[i] = Σ_j G_ij`` (or ``Σ_j |G_ij|`` if ``absolute``) and the number of degenerate (touching or
    intersecting) pairs per row, which contribute 0. With ``skip_adjacent`` (a and b are the same curve) pairs
    sharing a vertex — j ∈ {i−1, i, i+1}, and the wrap-around pair if ``closed_self`` — are skipped; their exact
    contribution is zero anyway (coplanar), but skipping avoids 0/0 at the shared vertex.
    """
    pairs = (a.shape[0] - 1) * (b.shape[0] - 1)
    kernel = _pair_row_sums_parallel if pairs >= PARALLEL_MIN_PAIRS else _pair_row_sums_serial
    return kernel(a, b, absolute, skip_adjacent, closed_self)


@nb.njit(cache=True, parallel=True, fastmath=False)
def pair_matrix(a, b):  # pragma: no cover - compiled
    """Full segment-pair Gauss matrix ``G[i, j]`` and the count of degenerate pairs (set to 0)."""
    n = a.shape[0] - 1
    m = b.shape[0] - 1
    out = np.empty((n, m))
    nbad = np.zeros(n, dtype=np.int64)
    for i in nb.prange(n):
        a0x, a0y, a0z = a[i, 0], a[i, 1], a[i, 2]
        a1x, a1y, a1z = a[i + 1, 0], a[i + 1, 1], a[i + 1, 2]
        px = b[0, 0] - a0x
        py = b[0, 1] - a0y
        pz = b[0, 2] - a0z
        sx = b[0, 0] - a1x
        sy = b[0, 1] - a1y
        sz = b[0, 2] - a1z
        pn = math.sqrt(px * px + py * py + pz * pz)
        sn = math.sqrt(sx * sx + sy * sy + sz * sz)
        for j in range(m):
            qx = b[j + 1, 0] - a0x
            qy = b[j + 1, 1] - a0y
            qz = b[j + 1, 2] - a0z
            rx = b[j + 1, 0] - a1x
            ry = b[j + 1, 1] - a1y
            rz = b[j + 1, 2] - a1z
            qn = math.sqrt(qx * qx + qy * qy + qz * qz)
            rn = math.sqrt(rx * rx + ry * ry + rz * rz)
            g, bad = _pair_term(px, py, pz, pn, qx, qy, qz, qn, rx, ry, rz, rn, sx, sy, sz, sn)
            out[i, j] = 0.0 if bad else g
            nbad[i] += bad
            px, py, pz, pn = qx, qy, qz, qn
            sx, sy, sz, sn = rx, ry, rz, rn
    return out, nbad.sum()


@nb.njit(cache=True, parallel=True)
def min_segment_distance(a, b):  # pragma: no cover - compiled
    """Minimum distance between any segment of ``a`` and any segment of ``b`` (for touching checks)."""
    n = a.shape[0] - 1
    m = b.shape[0] - 1
    best = np.empty(n)
    for i in nb.prange(n):
        lo = np.inf
        for j in range(m):
            d = _segment_distance(a[i], a[i + 1], b[j], b[j + 1])
            if d < lo:
                lo = d
        best[i] = lo
    return best.min()


@nb.njit(cache=True)
def min_self_segment_distance(curves, skip):  # pragma: no cover - compiled
    """Per polyline of ``(S, V, 3)`` curves, the minimum distance between two of its segments at least ``skip``
    segments apart (``skip = 2``: every pair but neighbours, which share a vertex)."""
    s_n = curves.shape[0]
    n = curves.shape[1] - 1
    out = np.full(s_n, np.inf)
    for s in range(s_n):
        c = curves[s]
        lo = np.inf
        for i in range(n - skip):
            for j in range(i + skip, n):
                d = _segment_distance(c[i], c[i + 1], c[j], c[j + 1])
                if d < lo:
                    lo = d
        out[s] = lo
    return out


@nb.njit(cache=True, inline="always")
def _segment_distance(p0, p1, q0, q1):  # pragma: no cover - compiled
    return _segdist_scalar(p0[0], p0[1], p0[2], p1[0], p1[1], p1[2], q0[0], q0[1], q0[2], q1[0], q1[1], q1[2])


@nb.njit(cache=True, inline="always")
def _segdist_scalar(ax, ay, az, bx, by, bz, cx, cy, cz, dx, dy, dz):  # pragma: no cover - compiled
    # Closest points of segments a→b and c→d (Ericson, Real-Time Collision Detection §5.1.9), degenerate-safe, on
    # scalars so that hot loops allocate nothing.
    d1x, d1y, d1z = bx - ax, by - ay, bz - az
    d2x, d2y, d2z = dx - cx, dy - cy, dz - cz
    rx, ry, rz = ax - cx, ay - cy, az - cz
    a = d1x * d1x + d1y * d1y + d1z * d1z
    e = d2x * d2x + d2y * d2y + d2z * d2z
    f = d2x * rx + d2y * ry + d2z * rz
    eps = 1e-300
    if a <= eps and e <= eps:
        return math.sqrt(rx * rx + ry * ry + rz * rz)
    if a <= eps:
        s = 0.0
        t = min(max(f / e, 0.0), 1.0)
    else:
        c = d1x * rx + d1y * ry + d1z * rz
        if e <= eps:
            t = 0.0
            s = min(max(-c / a, 0.0), 1.0)
        else:
            bb = d1x * d2x + d1y * d2y + d1z * d2z
            den = a * e - bb * bb
            s = min(max((bb * f - c * e) / den, 0.0), 1.0) if den > eps else 0.0
            t = (bb * s + f) / e
            if t < 0.0:
                t = 0.0
                s = min(max(-c / a, 0.0), 1.0)
            elif t > 1.0:
                t = 1.0
                s = min(max((bb - c) / a, 0.0), 1.0)
    qx = (ax + d1x * s) - (cx + d2x * t)
    qy = (ay + d1y * s) - (cy + d2y * t)
    qz = (az + d1z * s) - (cz + d2z * t)
    return math.sqrt(qx * qx + qy * qy + qz * qz)


@nb.njit(cache=True)
def close_pairs(curves, gap):  # pragma: no cover - compiled
    """Index pairs ``(a, b)``, ``a < b``, of ``(S, V, 3)`` polylines whose bounding boxes are closer than ``gap``."""
    s_n = curves.shape[0]
    lo = np.empty((s_n, 3))
    hi = np.empty((s_n, 3))
    for s in range(s_n):
        for k in range(3):
            lo[s, k] = curves[s, :, k].min()
            hi[s, k] = curves[s, :, k].max()
    out = np.empty((s_n * (s_n - 1) // 2, 2), dtype=np.int64)
    count = 0
    for a in range(s_n):
        for b in range(a + 1, s_n):
            g = -np.inf
            for k in range(3):
                g = max(g, lo[a, k] - hi[b, k], lo[b, k] - hi[a, k])
            if g < gap:
                out[count, 0] = a
                out[count, 1] = b
                count += 1
    return out[:count]


@nb.njit(cache=True, parallel=True)
def pair_distance_and_link(curves, pairs, link_within):  # pragma: no cover - compiled
    """Minimum segment distance of each pair, and its open Gauss integral (= ``linking_number(closed=False)``) where
    that distance is below ``link_within`` (NaN elsewhere: the integral costs an atan2 per segment pair)."""
    n = pairs.shape[0]
    v = curves.shape[1]
    dist = np.empty(n)
    link = np.full(n, np.nan)
    for p in nb.prange(n):
        a = curves[pairs[p, 0]]
        b = curves[pairs[p, 1]]
        best = np.inf
        for i in range(v - 1):
            for j in range(v - 1):
                # Segment bounding boxes farther apart than the best distance so far cannot improve it.
                g = 0.0
                for k in range(3):
                    g = max(
                        g,
                        min(b[j, k], b[j + 1, k]) - max(a[i, k], a[i + 1, k]),
                        min(a[i, k], a[i + 1, k]) - max(b[j, k], b[j + 1, k]),
                    )
                if g >= best:
                    continue
                d = _segdist_scalar(
                    a[i, 0], a[i, 1], a[i, 2], a[i + 1, 0], a[i + 1, 1], a[i + 1, 2],
                    b[j, 0], b[j, 1], b[j, 2], b[j + 1, 0], b[j + 1, 1], b[j + 1, 2],
                )  # fmt: skip
                if d < best:
                    best = d
        dist[p] = best
        if best >= link_within:
            continue
        total = 0.0
        for i in range(v - 1):
            for j in range(v - 1):
                px, py, pz = b[j, 0] - a[i, 0], b[j, 1] - a[i, 1], b[j, 2] - a[i, 2]
                qx, qy, qz = b[j + 1, 0] - a[i, 0], b[j + 1, 1] - a[i, 1], b[j + 1, 2] - a[i, 2]
                rx, ry, rz = b[j + 1, 0] - a[i + 1, 0], b[j + 1, 1] - a[i + 1, 1], b[j + 1, 2] - a[i + 1, 2]
                sx, sy, sz = b[j, 0] - a[i + 1, 0], b[j, 1] - a[i + 1, 1], b[j, 2] - a[i + 1, 2]
                g, bad = _pair_term(
                    px, py, pz, math.sqrt(px * px + py * py + pz * pz),
                    qx, qy, qz, math.sqrt(qx * qx + qy * qy + qz * qz),
                    rx, ry, rz, math.sqrt(rx * rx + ry * ry + rz * rz),
                    sx, sy, sz, math.sqrt(sx * sx + sy * sy + sz * sz),
                )  # fmt: skip
                if not bad:
                    total += g
        link[p] = total
    return dist, link


@nb.njit(cache=True)
def curves_to_segments_distance(curves, segs):  # pragma: no cover - compiled
    """Smallest distance between any polyline of ``(S, V, 3)`` ``curves`` and any ``(K, 2, 3)`` segment."""
    best = np.inf
    for s in range(curves.shape[0]):
        c = curves[s]
        for i in range(c.shape[0] - 1):
            for t in range(segs.shape[0]):
                d = _segdist_scalar(
                    c[i, 0], c[i, 1], c[i, 2], c[i + 1, 0], c[i + 1, 1], c[i + 1, 2],
                    segs[t, 0, 0], segs[t, 0, 1], segs[t, 0, 2], segs[t, 1, 0], segs[t, 1, 1], segs[t, 1, 2],
                )  # fmt: skip
                if d < best:
                    best = d
    return best
