"""A rod pile as data: :class:`Packing` (rod polylines of one diameter, optionally in a cylinder), its NPZ/CSV I/O
(:meth:`Packing.save`, :meth:`Packing.to_csv`, :func:`load_packing`) and its height (:func:`pile_height`).

Every other module of the package reads or returns a :class:`Packing`: generated piles (:mod:`.generate`), piles
after a mechanical test (:mod:`.mechanics`) and rods segmented from X-ray CT (:mod:`hairbrush_env.studies.ct`).
SI units; the container is a cylinder about the z axis with its floor at z = 0. The physical constants shared by
the simulation (steel density, gravity) live here too, so that every module uses the same values.
"""

from __future__ import annotations

import csv
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...io import atomic_path

__all__ = [
    "GRAVITY",
    "STEEL_DENSITY",
    "Packing",
    "load_packing",
    "pile_height",
]

STEEL_DENSITY = 7850.0  # kg/m³
GRAVITY = 9.81  # m/s²


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


def pile_height(packing: Packing, q: float = 95.0) -> float:
    """Pile height H: the ``q``-th percentile of rod tops (highest vertex + d/2) above the floor z = 0.

    A percentile rather than the maximum because a few rods stick up out of the rough top surface.
    """
    tops = np.maximum.reduceat(packing.points[:, 2], packing.offsets[:-1]) + packing.diameter / 2
    return float(np.percentile(tops, q))
