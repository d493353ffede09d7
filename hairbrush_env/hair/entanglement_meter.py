"""Reading the entanglement of a compiled wig (ground-truth link of its strands) and their centerline distances."""

from __future__ import annotations

from collections.abc import Sequence

import mujoco
import numpy as np

from .. import rods
from ..topology import link_density, linking_number
from ..topology.proximity import close_pair_proximity, polyline_distance
from .layout import WigLayout

__all__ = ["CROSS_LINK_THRESHOLD", "Entanglement", "entanglement", "min_distance_matrix"]

CROSS_LINK_THRESHOLD = 0.4
"""``|Lk|`` from which two strands of different groups count as linked: the thesis's link-interaction threshold
(Fig. 2.5b), also the bound :func:`wig_layout` keeps every cross-group pair below at rest."""


class Entanglement:
    """Ground-truth entanglement of a compiled wig: ``Σ |open Lk|`` over its entwined pairs, plus the link made
    between any other two strands (``|Lk| ≥`` :data:`CROSS_LINK_THRESHOLD`).

    Parameters
    ----------
    model : mujoco.MjModel
    layout : WigLayout
        Layout returned by :func:`add_wig` (names and pairs).
    """

    def __init__(self, model: mujoco.MjModel, layout: WigLayout) -> None:
        self.layout = layout
        self.views = [rods.RodView(model, n) for n in layout.names]
        self.pairs = layout.pairs
        # Chains of one wig share their edge count: their vertices are one fancy-indexed read of data.xpos.
        self._chain_ids = (
            np.stack([v.bodies for v in self.views])
            if all(v.kind == "chain" for v in self.views) and len({v.n_points for v in self.views}) == 1
            else None
        )
        if self._chain_ids is not None:
            tips = np.array([2.0 * model.geom_size[model.body_geomadr[v.tip_body], 1] for v in self.views])
            self._tip_lengths = tips[:, None]
        # Strand pairs a < b that are not entwined, for the link the brush or the shake made (breakdown).
        n = len(self.views)
        entwined = np.zeros((n, n), dtype=bool)
        entwined[self.pairs[:, 0], self.pairs[:, 1]] = True
        self._other_pairs = np.nonzero(np.triu(~entwined, 1))
        # The sense of each pair's built-in link: combed-apart neighbours keep a small open-curve link of the other
        # sense (two same-handed curls side by side, +0.1 to +0.4 on curly against -2.7 built in).
        self.built_in_sign = np.sign(layout.pair_link)

    def curves(self, data: mujoco.MjData) -> list[np.ndarray]:
        """Current centerlines of all strands."""
        return (
            list(self.curve_array(data))
            if self._chain_ids is not None
            else [v.vertices(data) for v in self.views]
        )

    def curve_array(self, data: mujoco.MjData) -> np.ndarray:
        """Current centerlines stacked as ``(n_strands, n_points, 3)`` (every strand of a wig has the same edges)."""
        if self._chain_ids is None:
            return np.stack([v.vertices(data) for v in self.views])
        ids = self._chain_ids
        out = np.empty((ids.shape[0], ids.shape[1] + 1, 3))
        out[:, :-1] = data.xpos[ids]
        tip_axis = data.xmat[ids[:, -1]].reshape(-1, 3, 3)[:, :, 0]
        out[:, -1] = out[:, -2] + tip_axis * self._tip_lengths
        return out

    def pair_links(self, data: mujoco.MjData, curves: list[np.ndarray] | None = None) -> np.ndarray:
        """Open-curve Gauss link of every entwined pair (signed)."""
        c = self.curves(data) if curves is None else curves
        return np.array([linking_number(c[i], c[j], closed=False) for i, j in self.pairs])

    def still_entwined(self, data: mujoco.MjData, *, link: np.ndarray | None = None) -> int:
        """Entwined pairs still wound in their built-in sense by at least :data:`CROSS_LINK_THRESHOLD` turns: the
        tangles left, as distinct from the small link that strands combed apart keep hanging side by side.
        ``link``: this state's :meth:`link_matrix`, if already read."""
        mat = self.link_matrix(data) if link is None else link
        lk = mat[self.pairs[:, 0], self.pairs[:, 1]] * self.built_in_sign
        return int(np.count_nonzero(lk >= CROSS_LINK_THRESHOLD))

    def link_by_depth(self, data: mujoco.MjData, depths: Sequence[float]) -> np.ndarray:
        """Where along the strands the entwined pairs' link sits: :meth:`pair_link_by_depth` summed over the
        pairs, one value per depth band."""
        return self.pair_link_by_depth(data, depths).sum(axis=0)

    def pair_link_by_depth(self, data: mujoco.MjData, depths: Sequence[float]) -> np.ndarray:
        """Each entwined pair's link in its built-in sense (so undone or reversed turns count negative), split into
        bands of depth below the roots ``depths[k] ≤ depth < depths[k+1]`` [m] (ascending; a segment deeper than
        the last edge joins the last band): ``(n_pairs, n_bands)``. A pair's link is spread along it by its link
        density (``topology.link_density``), so its row sums to ``sign₀ Lk``. The roots' height is the highest
        root."""
        edges = np.asarray(depths, dtype=float)
        if edges.ndim != 1 or edges.size < 2 or np.any(np.diff(edges) <= 0):
            raise ValueError(f"depths: need >= 2 ascending band edges [m], got {depths!r}")
        curves = self.curve_array(data)
        top = float(curves[:, 0, 2].max())
        bands = np.zeros((len(self.pairs), edges.size - 1))
        for row, ((i, j), sign) in enumerate(zip(self.pairs, self.built_in_sign, strict=True)):
            a, b = curves[i], curves[j]
            _, lam = link_density(a, b)
            link = lam * np.linalg.norm(np.diff(0.5 * (a + b), axis=0), axis=1)
            depth = top - 0.25 * (a[:-1, 2] + a[1:, 2] + b[:-1, 2] + b[1:, 2])
            k = np.clip(np.searchsorted(edges, depth, side="right") - 1, 0, edges.size - 2)
            np.add.at(bands[row], k, sign * link)
        return bands

    def link_matrix(self, data: mujoco.MjData) -> np.ndarray:
        """Open-curve Gauss link of every pair of strands, ``(n, n)`` symmetric with a zero diagonal."""
        curves = self.curve_array(data)
        n = curves.shape[0]
        pairs, _, link = close_pair_proximity(curves, np.inf)
        out = np.zeros((n, n))
        out[pairs[:, 0], pairs[:, 1]] = link
        return out + out.T

    def breakdown(self, data: mujoco.MjData, *, link: np.ndarray | None = None) -> tuple[float, float]:
        """``(entwined, made)``: ``Σ |Lk|`` over the entwined pairs, and over all other strand pairs whose
        ``|Lk| ≥`` :data:`CROSS_LINK_THRESHOLD` (link a brush or the shaking made between different groups).
        ``link``: this state's :meth:`link_matrix`, if already read."""
        mat = np.abs(self.link_matrix(data) if link is None else link)
        other = mat[self._other_pairs]
        return float(mat[self.pairs[:, 0], self.pairs[:, 1]].sum()), float(
            other[other >= CROSS_LINK_THRESHOLD].sum()
        )

    def __call__(self, data: mujoco.MjData) -> float:
        """Entanglement of the wig: ``Σ |Lk|`` over the entwined pairs plus every other pair linked
        ``≥`` :data:`CROSS_LINK_THRESHOLD` (:meth:`breakdown`), so a brush that tangles strands is seen doing it."""
        return float(sum(self.breakdown(data)))


def entanglement(model: mujoco.MjModel, data: mujoco.MjData, layout: WigLayout) -> float:
    """One-off :class:`Entanglement` reading (build an :class:`Entanglement` once for loops)."""
    return Entanglement(model, layout)(data)


def min_distance_matrix(curves: Sequence[np.ndarray]) -> np.ndarray:
    """Symmetric matrix of minimum centerline (segment–segment) distances between polylines (inf diagonal)."""
    n = len(curves)
    out = np.full((n, n), np.inf)
    for a in range(n):
        for b in range(a + 1, n):
            out[a, b] = out[b, a] = polyline_distance(curves[a], curves[b])
    return out
