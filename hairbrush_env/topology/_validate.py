"""Input checks shared by the topology functions: clear ``ValueError`` messages that name the argument."""

from __future__ import annotations

import numpy as np


def as_curve(x, name: str, *, closed: bool = False) -> np.ndarray:
    """Return ``x`` as a C-contiguous float64 ``(N, 3)`` polyline, checked.

    For ``closed=True`` the closing segment (last → first vertex) is appended, unless the caller already repeated
    the first vertex at the end. Raises ``ValueError`` naming ``name`` for wrong shapes, fewer than 2 vertices,
    non-finite coordinates or zero-length segments.
    """
    try:
        arr = np.ascontiguousarray(x, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name}: expected an (N, 3) array of vertex coordinates ({exc})") from exc
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"{name}: expected shape (N, 3), got {arr.shape}")
    if arr.shape[0] < 2:
        raise ValueError(f"{name}: a polyline needs at least 2 vertices, got {arr.shape[0]}")
    if not np.all(np.isfinite(arr)):
        bad = np.argwhere(~np.isfinite(arr))[0]
        raise ValueError(f"{name}: non-finite coordinate at vertex {bad[0]} (value {arr[bad[0], bad[1]]!r})")
    if closed:
        if arr.shape[0] < 3:
            raise ValueError(f"{name}: a closed curve needs at least 3 vertices, got {arr.shape[0]}")
        if not np.array_equal(arr[0], arr[-1]):
            arr = np.vstack([arr, arr[:1]])
    seg = np.linalg.norm(np.diff(arr, axis=0), axis=1)
    scale = max(float(np.ptp(arr, axis=0).max()), np.finfo(float).tiny)
    zero = np.flatnonzero(seg <= 1e-14 * scale)
    if zero.size:
        i = int(zero[0])
        raise ValueError(f"{name}: zero-length segment between vertices {i} and {i + 1}")
    return arr


def as_normals(u, name: str, n_vertices: int) -> np.ndarray:
    """Return per-vertex unit normals ``(n_vertices, 3)``, normalized; errors name ``name``."""
    arr = np.asarray(u, dtype=np.float64)
    if arr.shape != (n_vertices, 3):
        raise ValueError(f"{name}: expected one vector per vertex, shape ({n_vertices}, 3), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name}: non-finite entries")
    norm = np.linalg.norm(arr, axis=1)
    if np.any(norm == 0.0):
        raise ValueError(f"{name}: zero vector at vertex {int(np.flatnonzero(norm == 0.0)[0])}")
    return arr / norm[:, None]
