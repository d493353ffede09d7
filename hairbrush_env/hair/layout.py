"""Where the strands of a wig hang at rest: the lattice of entwined groups and their rest curves
(:func:`wig_layout`; why the lattice keeps different groups unlinked: :mod:`hairbrush_env.hair`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..topology import linking_number
from ..topology.proximity import polyline_distance
from .config import WigConfig

__all__ = ["WigLayout", "wig_layout"]


@dataclass(frozen=True)
class WigLayout:
    """Rest geometry and ground-truth topology of a wig (coordinates in the root-plane frame: z up, roots at z=0).

    Attributes
    ----------
    wig : WigConfig
    names : tuple of str
        Rod name of every strand.
    groups : tuple of tuple of int
        Strand indices of each entwined group (pairs and triples).
    axes : np.ndarray
        ``(n_groups, 2)`` horizontal positions of the group axes.
    roots : np.ndarray
        ``(n_strands, 3)`` root positions.
    curves : tuple of np.ndarray
        Rest centerline of every strand, ``(n_edges + 1, 3)``.
    pairs : np.ndarray
        ``(n_pairs, 2)`` entwined strand pairs (all pairs within each group).
    pair_link : np.ndarray
        Open-curve Gauss link of each entwined pair in the rest shape (≈ ``± wig.turns``).
    spacing : float
        Lattice spacing of the group axes.
    turns : float
        Curl turns of the discretized (polygonal) strands, whose length is exactly ``wig.length``.
    min_cross_distance : float
        Smallest centerline distance between strands of different groups at rest.
    max_cross_link : float
        Largest ``|Lk|`` between strands of different groups at rest (should be ≪ 0.5).
    """

    wig: WigConfig
    names: tuple[str, ...]
    groups: tuple[tuple[int, ...], ...]
    axes: np.ndarray
    roots: np.ndarray
    curves: tuple[np.ndarray, ...]
    pairs: np.ndarray
    pair_link: np.ndarray
    spacing: float
    turns: float
    min_cross_distance: float
    max_cross_link: float

    @property
    def n_links(self) -> float:
        """Total ground-truth link ``Σ |Lk|`` over entwined pairs at rest."""
        return float(np.abs(self.pair_link).sum())

    @property
    def extent(self) -> tuple[np.ndarray, np.ndarray]:
        """Axis-aligned bounding box ``(lo, hi)`` of the rest curves."""
        allp = np.vstack(self.curves)
        return allp.min(axis=0), allp.max(axis=0)


def _strand_curve(
    axis: np.ndarray, phase: float, wig: WigConfig, radius: float, turns: float, run: float = 0.0
) -> np.ndarray:
    n = wig.n_edges
    if wig.curliness > 0 and run > 0.0:
        # Straight for ``run`` below the root, then the helix; points uniform in arc length. The helix part is as
        # long as a polygonal helix of ``turns`` turns would be over the rest of the strand (``_polygon_turns``).
        arc = wig.arc_per_turn
        helix_arc = (wig.length - run) * turns / wig.turns
        s = np.linspace(0.0, run + helix_arc, n + 1)
        along = np.clip(s - run, 0.0, None)  # arc length along the helix
        depth = np.minimum(s, run) + along * wig.pitch / arc
        phi = phase + wig.handedness * 2.0 * math.pi * along / arc
    elif wig.curliness > 0:
        # Uniform in z is uniform in arc length on a helix, so all edges have the same rest length.
        depth = np.linspace(0.0, turns * wig.pitch, n + 1)
        phi = phase + wig.handedness * 2.0 * math.pi * depth / wig.pitch
    else:
        depth = np.linspace(0.0, wig.length, n + 1)
        phi = np.full(n + 1, phase)
    return np.column_stack([axis[0] + radius * np.cos(phi), axis[1] + radius * np.sin(phi), -depth])


def _polygon_turns(wig: WigConfig) -> float:
    """Turns of the *polygonal* helix (``n_edges`` chords) whose length is ``wig.length``.

    Chords are shorter than the arcs they cut (by ~ (Δφ)²/24 per edge, 3 % at 6 edges per turn), so the polygon
    gets slightly more turns than :attr:`WigConfig.turns` to keep the configured strand length.
    """
    if wig.curliness == 0:
        return 0.0
    n, r, p = wig.n_edges, wig.curl_radius, wig.pitch
    turns = wig.turns
    for _ in range(50):
        dphi = 2.0 * math.pi * turns / n
        chord = math.hypot(2.0 * r * math.sin(0.5 * dphi), p * turns / n)
        new = turns * wig.length / (n * chord)
        if abs(new - turns) < 1e-13 * turns:
            break
        turns = new
    return turns


_STRAIGHT_GROUP_RADIUS = 4e-3

# A curtain's groups (one row) turn their roots across it, perpendicular to the comb's tines (which run along x):
# a tine parts two strands only by their y, so a pair whose roots lay along x, one behind the other on the tine's
# line, was never split near its roots. A full stroke through the checkerboard curtain left such pairs 2.65–2.88 of
# their 3.07 link and the pairs across it 0.63–0.72 (curly, seed 0; docs/detangling.md, *Root orientation*).
# Pairs: phase π/2 puts the roots at y ± R; triples: phase 0 spreads them to y 0, ± 0.87 R. Neighbouring groups then
# share their phases (c = 2R in the package docstring), which the spacing check below still keeps unlinked.
_CURTAIN_PHASE = {2: 0.5 * math.pi, 3: 0.0}


def _grid(n: int, rows: int | None = None) -> tuple[list[tuple[int, int]], int, int]:
    # Rows along x (towards the brush), columns along y (across the brush): wider than deep, so that the
    # bristles reach through the curtain.
    rows = max(1, round(math.sqrt(n / 1.5))) if rows is None else min(rows, n)
    cols = math.ceil(n / rows)
    return [divmod(k, cols) for k in range(n)], rows, cols


def wig_layout(wig: WigConfig, *, prefix: str = "hair") -> WigLayout:
    """Place the entwined groups on the scalp and compute the rest curves and ground-truth links.

    The lattice spacing starts at ``max(min_spacing, √2 R + 2r + root_gap)`` and grows by 5 % until every
    cross-group pair of rest curves is at least ``2r + root_gap`` apart and unlinked (``|Lk| < 0.4``, the
    thesis's link-interaction threshold of Fig. 2.5b).
    """
    groups: list[tuple[int, ...]] = []
    k = 0
    for g in range(wig.n_groups):
        size = 3 if g < wig.n_triples else 2
        groups.append(tuple(range(k, k + size)))
        k += size
    cells, rows, cols = _grid(len(groups), wig.group_rows)
    r = wig.strand_radius
    # Straight hair: the strands of a group hang side by side across the curtain (phase π/2: along y), 8 mm apart, so
    # a comb tine through the group axis passes between them instead of wedging into a gap narrower than itself
    # next to the clamp (a 3.2 mm gap diverged at the first insertion).
    radius = wig.curl_radius if wig.curliness > 0 else _STRAIGHT_GROUP_RADIUS
    phases: list[float] = []
    for g, members in enumerate(groups):
        i, j = cells[g]
        if wig.curliness <= 0:
            offset = 0.5 * math.pi  # straight groups have no link to keep apart
        elif rows == 1:
            offset = _CURTAIN_PHASE[len(members)]
        else:  # checkerboard: neighbours differ by π/2 (package docstring)
            offset = 0.5 * math.pi * ((i + j) % 2)
        phases.extend(offset + 2.0 * math.pi * m / len(members) for m in range(len(members)))
    owner = np.array([g for g, members in enumerate(groups) for _ in members])
    need = 2.0 * r + wig.root_gap
    turns = _polygon_turns(wig)
    spacing = max(wig.min_spacing, math.sqrt(2.0) * radius + need)
    for _ in range(60):
        axes = np.array(
            [[(i - 0.5 * (rows - 1)) * spacing, (j - 0.5 * (cols - 1)) * spacing] for i, j in cells]
        )
        curves = [
            _strand_curve(axes[owner[s]], phases[s], wig, radius, turns, wig.root_run_length(int(owner[s])))
            for s in range(wig.n_strands)
        ]
        dmin, lkmax = math.inf, 0.0
        for a in range(wig.n_strands):
            for b in range(a + 1, wig.n_strands):
                if (
                    owner[a] == owner[b]
                    or np.linalg.norm(axes[owner[a]] - axes[owner[b]]) > 2 * radius + 3 * need
                ):
                    continue  # far groups cannot touch or link
                dmin = min(dmin, polyline_distance(curves[a], curves[b]))
                if wig.curliness > 0:
                    lkmax = max(lkmax, abs(linking_number(curves[a], curves[b], closed=False)))
        if dmin >= need and lkmax < 0.4:
            break
        spacing *= 1.05
    else:  # pragma: no cover - the lattice always separates eventually
        raise RuntimeError("wig_layout: could not separate the groups")
    pairs = np.array(
        [(m[a], m[b]) for m in groups for a in range(len(m)) for b in range(a + 1, len(m))], dtype=int
    )
    links = np.array([linking_number(curves[i], curves[j], closed=False) for i, j in pairs])
    names = tuple(f"{prefix}{s}" for s in range(wig.n_strands))
    for c in curves:
        c.setflags(write=False)
    return WigLayout(
        wig=wig,
        names=names,
        groups=tuple(groups),
        axes=axes,
        roots=np.array([c[0] for c in curves]),
        curves=tuple(curves),
        pairs=pairs,
        pair_link=links,
        spacing=spacing,
        turns=turns,
        min_cross_distance=dmin,
        max_cross_link=lkmax,
    )
