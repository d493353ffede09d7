"""Local fields of a rod pile on a grid of sub-volumes Ω(r; l_s) (thesis §4.3.3–4.3.4, Figs 4.3–4.4, eqs 4.1–4.2).

For every cell Ω (a cube of side l_s centred on a grid point — default l_s = 10 d, grid spacing l_s — or
optionally a sphere of diameter l_s) each rod is clipped exactly to Ω and:

* volume fraction φ = Σ clipped length × πd²/4 / |Ω|;
* orientational order, length-weighted over the clipped pieces, two versions:

  - ``S_vertical`` = ⟨(3 cos²θ − 1)/2⟩ with θ the angle to the vertical (gravity/compression axis): 1 for
    vertical rods, −1/2 for horizontal ones, 0 for isotropic;
  - ``S_director`` = the same about the local mean director n of Ω (the thesis's definition: "θ the angle between
    the i-th rod and the average angle of every rod in Ω"). The mean direction of unsigned axes is the principal
    eigenvector of Q = ⟨(3 u⊗u − I)/2⟩ and then S = λ_max(Q) ∈ [0, 1] — 1 for one rod or parallel rods, → 0
    for many isotropic rods (a finite sample gives S ≈ 1/√N above 0);

  Empty cells get S = ``empty_order`` (default 1, the thesis's convention: "where the volume fraction is null,
  orientational order would be unity", the S = 1 peak of Fig. 4.4b);
* entanglement e = Σ over rod pairs in Ω of |Gauss integral of their clipped pieces| (eq. 4.1; exact segment
  formula, :mod:`hairbrush_env.topology.segments`);
* rod count n.

Cells are analysed only if they lie in the pile (``mask``): centre within the container radius minus l_s/2 and
below the pile height minus l_s/2 (cells cut by the wall or the top surface would read artificially low φ).

Correlations (eq. 4.2) are computed with FFTs over masked cells: R(Δ) = Σ_x A'(x) B'(x+Δ) / #pairs(Δ) with
A' = A − ⟨A⟩ (the thesis's (N − ijk) normalisation), spherically averaged in shells of one grid spacing and
normalised by σ_A σ_B (so auto-correlations start at 1). The correlation length ξ is where |C(r)/C(0)| first drops
below 1/e (linear interpolation) — for an exponential decay exp(−r/ξ) that is exactly ξ.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numba as nb
import numpy as np

from ..io import atomic_path
from ..topology.segments import grouped_pair_acn
from .rod_pile import Packing, pile_height

__all__ = [
    "FIELD_NAMES",
    "Fields",
    "correlation",
    "correlation_length",
    "correlations",
    "depth_average",
    "local_fields",
]

FIELD_NAMES = ("phi", "S_vertical", "S_director", "e", "n")


@nb.njit(cache=True)
def _clip_cells(
    p0, p1, origin, h, dims, half, sphere, fill, cell_out, seg_out, t0_out, t1_out
):  # pragma: no cover
    """Clip every segment to every candidate cell; pass 1 counts (``fill`` False), pass 2 writes."""
    _nx, ny, nz = dims[0], dims[1], dims[2]
    k = 0
    for s in range(p0.shape[0]):
        lo_i = np.empty(3, np.int64)
        hi_i = np.empty(3, np.int64)
        for a in range(3):
            bmin = min(p0[s, a], p1[s, a]) - half
            bmax = max(p0[s, a], p1[s, a]) + half
            lo_i[a] = max(math.ceil((bmin - origin[a]) / h - 0.5), 0)
            hi_i[a] = min(math.floor((bmax - origin[a]) / h - 0.5), dims[a] - 1)
        dx = p1[s, 0] - p0[s, 0]
        dy = p1[s, 1] - p0[s, 1]
        dz = p1[s, 2] - p0[s, 2]
        for i in range(lo_i[0], hi_i[0] + 1):
            cx = origin[0] + (i + 0.5) * h
            for j in range(lo_i[1], hi_i[1] + 1):
                cy = origin[1] + (j + 0.5) * h
                for kk in range(lo_i[2], hi_i[2] + 1):
                    cz = origin[2] + (kk + 0.5) * h
                    t0 = 0.0
                    t1 = 1.0
                    if sphere:
                        fx = p0[s, 0] - cx
                        fy = p0[s, 1] - cy
                        fz = p0[s, 2] - cz
                        qa = dx * dx + dy * dy + dz * dz
                        qb = fx * dx + fy * dy + fz * dz
                        qc = fx * fx + fy * fy + fz * fz - half * half
                        disc = qb * qb - qa * qc
                        if disc <= 0.0 or qa == 0.0:
                            continue
                        sq = math.sqrt(disc)
                        t0 = max(t0, (-qb - sq) / qa)
                        t1 = min(t1, (-qb + sq) / qa)
                    else:
                        ok = True
                        for a in range(3):
                            c = cx if a == 0 else (cy if a == 1 else cz)
                            p = p0[s, a]
                            dp = dx if a == 0 else (dy if a == 1 else dz)
                            if dp == 0.0:
                                if p < c - half or p > c + half:
                                    ok = False
                                    break
                            else:
                                ta = (c - half - p) / dp
                                tb = (c + half - p) / dp
                                if ta > tb:
                                    ta, tb = tb, ta
                                t0 = max(t0, ta)
                                t1 = min(t1, tb)
                        if not ok:
                            continue
                    if t1 - t0 <= 1e-12:
                        continue
                    if fill:
                        cell_out[k] = (i * ny + j) * nz + kk
                        seg_out[k] = s
                        t0_out[k] = t0
                        t1_out[k] = t1
                    k += 1
    return k


@dataclass(frozen=True)
class Fields:
    """Local fields on a grid (arrays of shape ``dims``; x, y, z order) and the cell geometry.

    Attributes
    ----------
    phi, S_vertical, S_director, e, n : ndarray
        Volume fraction, order parameters (see module docstring), entanglement (eq. 4.1) and rod count per cell.
    mask : bool ndarray
        Cells inside the pile (the statistics use only these).
    origin, spacing, cell_size, shape :
        Cell (i, j, k) is centred at ``origin + (i+½, j+½, k+½)·spacing``; side (or sphere diameter)
        ``cell_size``; ``shape`` is ``"cube"`` or ``"sphere"``.
    height : float
        Pile height used for the mask.
    degenerate : int
        Touching/intersecting segment pairs met in the Gauss sums (counted as 0).
    meta : dict
        Provenance (e.g. strain of the packing).
    """

    phi: np.ndarray
    S_vertical: np.ndarray
    S_director: np.ndarray
    e: np.ndarray
    n: np.ndarray
    mask: np.ndarray
    origin: np.ndarray
    spacing: float
    cell_size: float
    shape: str
    height: float
    degenerate: int = 0
    meta: dict = field(default_factory=dict)

    def field(self, name: str) -> np.ndarray:
        if name not in FIELD_NAMES:
            raise ValueError(f"name: unknown field {name!r}; expected one of {FIELD_NAMES}")
        return getattr(self, name)

    def values(self, name: str) -> np.ndarray:
        """The field's values in the pile's cells (flat)."""
        return self.field(name)[self.mask]

    def means(self) -> dict[str, float]:
        return {k: float(np.mean(self.values(k))) for k in FIELD_NAMES}

    def save(self, path: str | Path) -> Path:
        import json

        with atomic_path(path) as tmp, open(tmp, "wb") as fh:
            np.savez_compressed(
                fh, **{k: getattr(self, k) for k in FIELD_NAMES}, mask=self.mask, origin=self.origin,
                spacing=self.spacing, cell_size=self.cell_size, shape=self.shape, height=self.height,
                degenerate=self.degenerate, meta=json.dumps(self.meta, default=float),
            )  # fmt: skip
        return Path(path)

    @classmethod
    def load(cls, path: str | Path) -> Fields:
        import json

        with np.load(path, allow_pickle=False) as z:
            return cls(
                *(z[k] for k in FIELD_NAMES), z["mask"], z["origin"], float(z["spacing"]), float(z["cell_size"]),
                str(z["shape"]), float(z["height"]), int(z["degenerate"]), json.loads(str(z["meta"])),
            )  # fmt: skip


def local_fields(
    packing: Packing,
    l_s: float | None = None,
    *,
    spacing: float | None = None,
    shape: str = "cube",
    height: float | None = None,
    empty_order: float = 1.0,
) -> Fields:
    """φ, S, e and n on a grid of sub-volumes Ω(r; l_s) (thesis §4.3.3; see the module docstring).

    Parameters
    ----------
    packing : Packing
        Straight rods or polylines.
    l_s : float, optional
        Cube side (or sphere diameter) [m]; default 10 d (thesis Fig. 4.4).
    spacing : float, optional
        Grid spacing; default ``l_s`` (non-overlapping cubes tiling the pile). Smaller values give overlapping
        cells (a smoother field, more cost).
    shape : {"cube", "sphere"}
        Shape of Ω.
    height : float, optional
        Pile height for the mask; default :func:`~.rod_pile.pile_height`.
    empty_order : float
        S assigned to empty cells (thesis convention 1).
    """
    d = packing.diameter
    l_s = 10 * d if l_s is None else float(l_s)
    if not (math.isfinite(l_s) and l_s > 0):
        raise ValueError(f"l_s: must be > 0, got {l_s!r}")
    h = l_s if spacing is None else float(spacing)
    if not (math.isfinite(h) and h > 0):
        raise ValueError(f"spacing: must be > 0, got {spacing!r}")
    if shape not in ("cube", "sphere"):
        raise ValueError(f"shape: expected 'cube' or 'sphere', got {shape!r}")
    H = pile_height(packing) if height is None else float(height)
    half = l_s / 2
    pts = packing.points
    if math.isnan(packing.container_diameter):
        lo_xy, hi_xy = pts[:, :2].min(axis=0), pts[:, :2].max(axis=0)
        R = None
    else:
        R = packing.container_diameter / 2
        lo_xy, hi_xy = np.array([-R, -R]), np.array([R, R])
    nx, ny = (math.ceil((hi_xy[a] - lo_xy[a]) / h) for a in range(2))
    nz = max(math.ceil(H / h), 1)
    origin = np.array([(lo_xy[0] + hi_xy[0] - nx * h) / 2, (lo_xy[1] + hi_xy[1] - ny * h) / 2, 0.0])
    dims = np.array([nx, ny, nz], dtype=np.int64)
    p0, p1, owner = packing.segments()
    p0, p1 = np.ascontiguousarray(p0), np.ascontiguousarray(p1)
    sphere = shape == "sphere"
    empty_i, empty_f = np.zeros(0, np.int64), np.zeros(0)
    count = _clip_cells(p0, p1, origin, h, dims, half, sphere, False, empty_i, empty_i, empty_f, empty_f)
    cell = np.empty(count, np.int64)
    seg = np.empty(count, np.int64)
    t0 = np.empty(count)
    t1 = np.empty(count)
    _clip_cells(p0, p1, origin, h, dims, half, sphere, True, cell, seg, t0, t1)
    ncell = int(nx * ny * nz)
    vec = p1 - p0
    seg_len = np.linalg.norm(vec, axis=1)
    u = vec / seg_len[:, None]
    ell = (t1 - t0) * seg_len[seg]
    vol = l_s**3 if not sphere else math.pi / 6 * l_s**3
    length = np.bincount(cell, ell, minlength=ncell)
    phi = length * math.pi * d * d / 4 / vol
    us = u[seg]
    filled = length > 0
    S_v = np.full(ncell, float(empty_order))
    S_v[filled] = (
        np.bincount(cell, ell * (1.5 * us[:, 2] ** 2 - 0.5), minlength=ncell)[filled] / length[filled]
    )
    Q = np.zeros((ncell, 3, 3))
    for a in range(3):
        for b in range(a, 3):
            q = np.bincount(cell, ell * 1.5 * us[:, a] * us[:, b], minlength=ncell)
            Q[:, a, b] = Q[:, b, a] = q
    Q[filled] /= length[filled, None, None]
    Q[filled] -= 0.5 * np.eye(3)
    S_d = np.full(ncell, float(empty_order))
    if filled.any():
        S_d[filled] = np.linalg.eigvalsh(Q[filled])[:, -1]
    # entanglement: sort clipped pieces by (cell, rod) so each cell's pieces are contiguous, grouped by rod
    rod = owner[seg]
    order = np.lexsort((rod, cell))
    cs, rs = cell[order], rod[order]
    q0 = p0[seg[order]] + t0[order, None] * vec[seg[order]]
    q1 = p0[seg[order]] + t1[order, None] * vec[seg[order]]
    starts = np.searchsorted(cs, np.arange(ncell + 1))
    e, nbad = grouped_pair_acn(q0, q1, rs, starts)
    first = np.r_[True, (cs[1:] != cs[:-1]) | (rs[1:] != rs[:-1])] if len(cs) else np.zeros(0, bool)
    n_rods = np.bincount(cs[first], minlength=ncell).astype(np.float64)
    # mask: cells within the pile
    ii, jj, kk = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    cx, cy, cz = (origin[a] + ((ii, jj, kk)[a] + 0.5) * h for a in range(3))
    mask = cz <= max(H - half, half)
    if R is not None:
        mask &= np.hypot(cx, cy) <= R - half
    else:
        mask &= (
            (cx >= lo_xy[0] + half)
            & (cx <= hi_xy[0] - half)
            & (cy >= lo_xy[1] + half)
            & (cy <= hi_xy[1] - half)
        )
    shp = (nx, ny, nz)
    return Fields(
        phi.reshape(shp), S_v.reshape(shp), S_d.reshape(shp), e.reshape(shp), n_rods.reshape(shp), mask, origin,
        h, l_s, shape, H, int(nbad.sum()), {"strain": packing.meta.get("strain", 0.0)},
    )  # fmt: skip


def correlation(
    a: np.ndarray, b: np.ndarray, mask: np.ndarray, spacing: float, *, r_max: float | None = None
):
    """Spherically averaged, normalised correlation C_AB(r) of two gridded fields over masked cells (eq. 4.2).

    Returns
    -------
    r : (k,) ndarray
        Shell radii (multiples of the grid spacing, starting at 0).
    c : (k,) ndarray
        C_AB(r) / (σ_A σ_B); NaN where no pairs exist. For A = B, c[0] = 1.
    """
    a, b, mask = np.asarray(a, float), np.asarray(b, float), np.asarray(mask, bool)
    if a.shape != b.shape or a.shape != mask.shape or a.ndim != 3:
        raise ValueError(f"a, b, mask: need equal 3-D shapes, got {a.shape}, {b.shape}, {mask.shape}")
    if mask.sum() < 2:
        raise ValueError("mask: fewer than 2 cells")
    m = mask.astype(float)
    am = np.where(mask, a - a[mask].mean(), 0.0)
    bm = np.where(mask, b - b[mask].mean(), 0.0)
    sa, sb = a[mask].std(), b[mask].std()
    shape = [2 * s for s in a.shape]  # zero padding: no wrap-around
    axes = (0, 1, 2)
    fa, fb, fm = (np.fft.rfftn(x, shape, axes=axes) for x in (am, bm, m))
    num = np.fft.irfftn(np.conj(fa) * fb, shape, axes=axes)  # Σ_x A'(x) B'(x + Δ)
    cnt = np.fft.irfftn(np.conj(fm) * fm, shape, axes=axes)
    idx = [np.fft.fftfreq(s, 1.0 / s) for s in shape]  # integer shifts, negative ones wrapped
    dist = np.sqrt(sum(np.meshgrid(*[i**2 for i in idx], indexing="ij"))) * 1.0
    shell = np.rint(dist).astype(np.int64)
    ok = cnt > 0.5
    kmax = int(shell[ok].max())
    if r_max is not None:
        kmax = min(kmax, int(r_max / spacing))
    sel = ok & (shell <= kmax)
    tot = np.bincount(shell[sel], num[sel], minlength=kmax + 1)
    pairs = np.bincount(shell[sel], cnt[sel], minlength=kmax + 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        c = tot / pairs / (sa * sb)
    return np.arange(kmax + 1) * spacing, c


def correlation_length(r: np.ndarray, c: np.ndarray) -> float:
    """First r where |C(r)/C(0)| drops below 1/e (linear interpolation); NaN if it never does or C(0) = 0."""
    if len(c) < 2 or not np.isfinite(c[0]) or c[0] == 0:
        return float("nan")
    y = np.abs(c / c[0])
    target = math.exp(-1)
    for k in range(1, len(y)):
        if np.isfinite(y[k]) and y[k] < target:
            y0 = y[k - 1]
            return float(r[k - 1] + (y0 - target) / (y0 - y[k]) * (r[k] - r[k - 1]))
    return float("nan")


CORRELATION_PAIRS = (("phi", "phi"), ("S_director", "S_director"), ("e", "e"), ("phi", "S_director"),
                     ("phi", "e"), ("S_director", "e"))  # fmt: skip


def correlations(fields: Fields, pairs=CORRELATION_PAIRS, *, r_max: float | None = None) -> dict:
    """C_AB(r) and ξ for the auto- and cross-correlations of Fig. 4.4d–i: ``{"A×B": (r, c, xi)}``."""
    out = {}
    for a, b in pairs:
        r, c = correlation(fields.field(a), fields.field(b), fields.mask, fields.spacing, r_max=r_max)
        out[f"{a}×{b}"] = (r, c, correlation_length(r, c))
    return out


def depth_average(fields: Fields, name: str) -> np.ndarray:
    """Column mean over the pile's cells, ``(nx, ny)`` (Fig. 4.3; the thesis's ∫ · dz divided by the height)."""
    f = fields.field(name)
    m = fields.mask
    cnt = m.sum(axis=2)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(cnt > 0, np.where(m, f, 0.0).sum(axis=2) / cnt, np.nan)


# ------------------------------------------------------------------------------------------------ figures

_LABELS = {"phi": "volume fraction φ", "S_vertical": "S (about vertical)", "S_director": "S (about local director)",
           "e": "entanglement e", "n": "rods per cell n"}  # fmt: skip


def plot_fields(fields: dict, prefix: str | Path) -> list[Path]:
    """Histograms (Fig. 4.4a–c), depth-averaged maps (Fig. 4.3) and correlations (Fig. 4.4d–i).

    ``fields`` maps a label (e.g. ``"ε = 0"``, ``"ε = 0.15"``) to :class:`Fields`; writes
    ``<prefix>_hist.png``, ``<prefix>_maps.png`` and ``<prefix>_corr.png``.
    """
    from ..viz import PALETTE, new_figure, save_figure

    prefix = Path(prefix)
    out = []
    names = ("phi", "S_director", "e")
    fig, axes = new_figure(3, 1, width=4.0, height=3.3)
    for k, name in enumerate(names):
        ax = axes[0, k]
        allv = np.concatenate([f.values(name) for f in fields.values()])
        bins = np.linspace(allv.min(), allv.max() + 1e-12, 25)
        for c, (label, f) in enumerate(fields.items()):
            ax.hist(f.values(name), bins=bins, density=True, histtype="step", lw=1.4,
                    color=PALETTE[c % len(PALETTE)], label=f"{label} (mean {f.values(name).mean():.3g})")  # fmt: skip
        ax.set(xlabel=_LABELS[name], ylabel="density")
        ax.legend(fontsize=7)
    p = prefix.with_name(prefix.name + "_hist.png")
    save_figure(fig, p)
    out.append(p)
    fig, axes = new_figure(len(names), len(fields), width=3.4, height=3.0)
    for r, (label, f) in enumerate(fields.items()):
        for k, name in enumerate(names):
            ax = axes[r, k]
            img = depth_average(f, name)
            im = ax.imshow(img.T, origin="lower", cmap="viridis")
            fig.colorbar(im, ax=ax, shrink=0.8)
            ax.set(title=f"{label}: depth-avg {name}", xticks=[], yticks=[])
    p = prefix.with_name(prefix.name + "_maps.png")
    save_figure(fig, p)
    out.append(p)
    fig, axes = new_figure(3, 2, width=3.8, height=3.0)
    for c, (label, f) in enumerate(fields.items()):
        corr = correlations(f)
        for k, (key, (r, cc, xi)) in enumerate(corr.items()):
            ax = axes[k // 3, k % 3]
            ax.plot(r / f.cell_size, cc, "o-", ms=3, color=PALETTE[c % len(PALETTE)],
                    label=f"{label}: ξ = {xi / f.cell_size:.2f} l_s")  # fmt: skip
            ax.axhline(0, color="0.7", lw=0.8)
            ax.set(xlabel="r / l_s", ylabel=f"C({key})")
            ax.legend(fontsize=7)
    p = prefix.with_name(prefix.name + "_corr.png")
    save_figure(fig, p)
    out.append(p)
    return out
