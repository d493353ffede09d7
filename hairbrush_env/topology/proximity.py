"""Pass-through detection for many polylines at once: close pairs, their distance and their Gauss link.

Two centerlines that pass through each other change their open Gauss integral by ≈ 1 at the instant of passage (the
sign of one crossing in every projection flips), while any continuous motion that keeps them apart changes it
smoothly — a few hundredths per millisecond step for brushed hair. Sampled at every physics step, a jump of the
integral of a *close* pair above ½ therefore marks a topological crossing, whichever two strands they are
(:class:`CrossingDetector`). The kernels take stacked ``(S, V, 3)`` polylines of equal vertex count.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ._kernels import (
    _segment_distance,
    close_pairs,
    curves_to_segments_distance,
    min_segment_distance,
    min_self_segment_distance,
    pair_distance_and_link,
)

__all__ = [
    "Crossing",
    "CrossingDetector",
    "close_pair_proximity",
    "min_distance_to_segments",
    "min_self_distance",
    "polyline_distance",
    "segment_distances",
]


def _stack(curves) -> np.ndarray:
    arr = np.ascontiguousarray(curves, dtype=float)
    if arr.ndim != 3 or arr.shape[2] != 3 or arr.shape[1] < 2:
        raise ValueError(f"curves must be an (S, V>=2, 3) array, got shape {arr.shape}")
    return arr


def close_pair_proximity(
    curves, gap: float, *, link_within: float = np.inf
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pairs of polylines whose bounding boxes are closer than ``gap``, with their distance and open Gauss link.

    Parameters
    ----------
    curves : (S, V, 3) array_like
        Stacked polylines.
    gap : float
        Bounding-box gap [m] below which a pair is evaluated.
    link_within : float
        The Gauss integral is computed only for pairs closer than this [m] (NaN for the others).

    Returns
    -------
    pairs : (P, 2) int array
        ``(a, b)`` with ``a < b``.
    distance : (P,) array
        Minimum segment–segment distance of each pair.
    link : (P,) array
        Open-curve Gauss integral of each pair (= :func:`~hairbrush_env.topology.linking_number` with
        ``closed=False``; touching segment pairs contribute 0), NaN beyond ``link_within``.
    """
    arr = _stack(curves)
    pairs = close_pairs(arr, float(gap))
    dist, link = pair_distance_and_link(arr, pairs, float(link_within))
    return pairs, dist, link


def min_distance_to_segments(curves, segments) -> float:
    """Smallest distance between any of the stacked ``curves`` and any of the ``(K, 2, 3)`` ``segments``."""
    segs = np.ascontiguousarray(segments, dtype=float).reshape(-1, 2, 3)
    return float(curves_to_segments_distance(_stack(curves), segs)) if len(segs) else float("inf")


def min_self_distance(curves, *, skip: int = 2) -> np.ndarray:
    """Per polyline, the smallest distance between two of its own segments ``skip`` or more segments apart.

    Neighbouring segments share a vertex, so ``skip`` must be ≥ 2. A strand with no self-collision can pass through
    itself: this distance then falls towards 0 where one of its segments crosses another.
    """
    if not (isinstance(skip, int) and skip >= 2):
        raise ValueError(f"skip must be an integer >= 2, got {skip!r}")
    return min_self_segment_distance(_stack(curves), skip)


@dataclass(frozen=True)
class Crossing:
    """One detected passage: strands ``a`` and ``b`` changed their Gauss link by ``jump`` in one sample."""

    time: float
    a: int
    b: int
    jump: float


@dataclass
class CrossingDetector:
    """Follows the Gauss link of every close pair from one sample to the next and reports jumps above ``threshold``.

    Parameters
    ----------
    gap : float
        Pairs are candidates while their bounding boxes are closer than this [m].
    follow_factor, follow_floor : float
        A pair's link is followed while its centerlines are closer than ``max(follow_floor, follow_factor · δ)``,
        ``δ`` the largest vertex displacement of the last sample interval (capped at ``gap``): two strands approach
        each other by at most ``2 δ`` per interval, so a pair that crosses was already followed one sample earlier
        unless the strands suddenly move twice as fast as before.
    threshold : float
        Jump of the Gauss integral between two samples that counts as a crossing (a passage jumps by ≈ 1).
    """

    gap: float = 5e-3
    threshold: float = 0.5
    follow_factor: float = 4.0
    follow_floor: float = 1e-3
    crossings: list[Crossing] = field(default_factory=list)
    max_jump: float = 0.0
    min_distance: float = float("inf")
    _previous: np.ndarray | None = field(default=None, repr=False)
    _last_curves: np.ndarray | None = field(default=None, repr=False)

    def update(self, curves, time: float = 0.0) -> None:
        """Take one sample of the stacked ``(S, V, 3)`` centerlines."""
        arr = _stack(curves)
        last, self._last_curves = self._last_curves, arr.copy()
        moved = float(np.abs(arr - last).max()) if last is not None and last.shape == arr.shape else self.gap
        follow = min(self.gap, max(self.follow_floor, self.follow_factor * moved))
        pairs, dist, link = close_pair_proximity(arr, self.gap, link_within=follow)
        if len(dist):
            self.min_distance = min(self.min_distance, float(dist.min()))
        current = np.full((arr.shape[0], arr.shape[0]), np.nan)
        current[pairs[:, 0], pairs[:, 1]] = link
        if self._previous is not None and self._previous.shape == current.shape and len(pairs):
            jump = np.abs(link - self._previous[pairs[:, 0], pairs[:, 1]])
            seen = np.isfinite(jump)
            if seen.any():
                self.max_jump = max(self.max_jump, float(jump[seen].max()))
                for k in np.flatnonzero(seen & (jump > self.threshold)):
                    self.crossings.append(
                        Crossing(float(time), int(pairs[k, 0]), int(pairs[k, 1]), float(jump[k]))
                    )
        self._previous = current

    def restart(self) -> None:
        """Forget the previous sample (e.g. after a reset), keep what was recorded."""
        self._previous = None
        self._last_curves = None


def polyline_distance(a, b) -> float:
    """Minimum distance between two polylines ``(N, 3)`` and ``(M, 3)`` (exact segment–segment distances)."""
    return float(
        min_segment_distance(np.ascontiguousarray(a, dtype=float), np.ascontiguousarray(b, dtype=float))
    )


def segment_distances(a0, a1, b0s, b1s) -> np.ndarray:
    """Distance from the segment ``a0``–``a1`` to each segment ``b0s[i]``–``b1s[i]``."""
    a0, a1 = np.asarray(a0, dtype=float), np.asarray(a1, dtype=float)
    return np.array(
        [
            _segment_distance(a0, a1, np.asarray(b0, float), np.asarray(b1, float))
            for b0, b1 in zip(b0s, b1s, strict=True)
        ]
    )
