"""Twist of a discrete ribbon (thesis eq. 1.16) via parallel transport.

A ribbon is a polyline ``x`` (N, 3) with one unit vector ``u_i`` per **vertex** (the second edge of the ribbon is
``x + ε u``). The vectors need not be exactly perpendicular to the curve: at every use they are projected onto the
plane normal to the relevant edge tangent, and they must not be parallel to it.

The twist is the total rotation of the projected normal about the tangent, measured against the parallel-transport
(Bishop) frame, in turns. It has two parts:

* along edge ``i`` the tangent is fixed; the normal turns from ``P_i u_i`` to ``P_i u_{i+1}`` (``P_i`` = projection
  normal to ``t_i``), contributing the signed angle between them about ``t_i``;
* at vertex ``k`` the tangent turns from ``t_{k-1}`` to ``t_k``; the frame is parallel-transported by the minimal
  rotation about ``t_{k-1} × t_k`` and the normal's extra rotation about ``t_k`` is the contribution.

Because discrete parallel transport around a closed polyline has holonomy equal to the area enclosed by its
(geodesic) tantrix, ``twist + writhe`` is an integer for every closed ribbon, and it equals
``linking_number(x, x + ε u)`` for small ε (Călugăreanu–Fuller–White, eq. 1.17). Each individual step must turn by
less than π (resolve the ribbon finely enough).
"""

from __future__ import annotations

import numpy as np

from ._validate import as_curve, as_normals

__all__ = ["parallel_transport", "twist"]


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _project(u: np.ndarray, t: np.ndarray, name: str) -> np.ndarray:
    p = u - np.sum(u * t, axis=-1, keepdims=True) * t
    norm = np.linalg.norm(p, axis=-1)
    if np.any(norm < 1e-9):
        k = int(np.flatnonzero(norm < 1e-9)[0])
        raise ValueError(f"{name}: normal is parallel to the curve tangent near vertex {k}")
    return p / norm[:, None]


def _signed_angle(v0: np.ndarray, v1: np.ndarray, axis: np.ndarray) -> np.ndarray:
    return np.arctan2(np.sum(axis * np.cross(v0, v1), axis=-1), np.sum(v0 * v1, axis=-1))


def parallel_transport(v: np.ndarray, t0: np.ndarray, t1: np.ndarray) -> np.ndarray:
    """Rotate vectors ``v`` by the minimal rotation taking unit tangents ``t0`` to ``t1`` (row-wise, Rodrigues)."""
    axis = np.cross(t0, t1)
    sin = np.linalg.norm(axis, axis=-1, keepdims=True)
    cos = np.sum(t0 * t1, axis=-1, keepdims=True)
    k = np.divide(axis, sin, out=np.zeros_like(axis), where=sin > 1e-300)
    return v * cos + np.cross(k, v) * sin + k * np.sum(k * v, axis=-1, keepdims=True) * (1.0 - cos)


def twist(curve, normals, *, closed: bool = True) -> float:
    """Total twist (in turns) of the ribbon ``(curve, normals)``; ``normals`` has one vector per vertex.

    For ``closed=True`` the closing edge (last → first vertex) and the corners at both of its ends are included
    (pass the curve without repeating the first vertex). For open ribbons the end vertices contribute no corner.
    """
    x = as_curve(curve, "curve")
    if closed and np.array_equal(x[0], x[-1]):
        raise ValueError(
            "curve: for closed=True pass each vertex once (do not repeat the first vertex at the end)"
        )
    u = as_normals(normals, "normals", x.shape[0])
    if closed:
        x_next = np.roll(x, -1, axis=0)
        u_next = np.roll(u, -1, axis=0)
        seg = x_next - x
        if np.any(np.linalg.norm(seg, axis=1) == 0.0):
            raise ValueError("curve: the closing segment has zero length")
        t = _unit(seg)  # edge k joins vertex k and k+1 (mod N)
        edge_part = _signed_angle(_project(u, t, "normals"), _project(u_next, t, "normals"), t)
        t_in = np.roll(t, 1, axis=0)  # edge ending at vertex k
        corner_u, t_out = u, t
    else:
        t = _unit(np.diff(x, axis=0))
        edge_part = _signed_angle(_project(u[:-1], t, "normals"), _project(u[1:], t, "normals"), t)
        t_in, t_out, corner_u = t[:-1], t[1:], u[1:-1]
    w_in = parallel_transport(_project(corner_u, t_in, "normals"), t_in, t_out)
    corner_part = _signed_angle(w_in, _project(corner_u, t_out, "normals"), t_out)
    return float((edge_part.sum() + corner_part.sum()) / (2.0 * np.pi))
