"""Which entwined pairs the comb has gone in *between*: the condition for a stroke to comb a pair's link out.

The link of an entwined pair leaves through the free ends only where a tine passes between its two strands (thesis
chapter 2). A comb's tines run along x, into the curtain, so whether a tine lies between the two strands is decided
by their positions across the curtain (y) where they cross the tines' height. An entwined pair is a double helix
about its axis, and a tine through that axis meets its strands side by side or one behind the other depending on the
helix phase at the brush's height; when every pair curls from its roots the pairs share one phase, and a comb put in
at some heights parts none of them (``WigConfig.root_run``; docs/detangling.md, *Where the comb goes in*).
"""

from __future__ import annotations

import numpy as np


def crossing_y(curve: np.ndarray, z: float) -> float:
    """y where ``curve`` (root first, shape ``(n, 3)``) first comes down to height ``z``; nan if it never does."""
    below = np.nonzero(curve[:, 2] <= z)[0]
    if below.size == 0 or below[0] == 0:
        return float("nan")
    k = int(below[0])
    a, b = curve[k - 1], curve[k]
    t = (a[2] - z) / (a[2] - b[2])
    return float(a[1] + t * (b[1] - a[1]))


def pairs_parted(
    curves: np.ndarray, pairs: np.ndarray, tines_y: np.ndarray, z: float, room: float
) -> np.ndarray:
    """For each pair ``(i, j)`` of strands: whether a tine (at the y of ``tines_y``, running along x at height
    ``z``) lies between the two strands where they first come down to ``z``, with ``room`` [m] (tine radius plus
    strand radius) on either side. A strand that does not reach ``z`` leaves its pair unparted."""
    tines_y = np.asarray(tines_y, dtype=float)
    out = np.zeros(len(pairs), dtype=bool)
    for k, (i, j) in enumerate(pairs):
        ya, yb = crossing_y(curves[i], z), crossing_y(curves[j], z)
        if np.isfinite(ya) and np.isfinite(yb):
            lo, hi = min(ya, yb), max(ya, yb)
            out[k] = bool(np.any((tines_y > lo + room) & (tines_y < hi - room)))
    return out
