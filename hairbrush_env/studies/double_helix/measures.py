"""Measures of a combing stroke: the jam flag of the force curve, the tine's break-throughs, the bend of the braid
below the tine (kinking) and the cost of combing (eq. 2.8)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

__all__ = [
    "COST_Q0",
    "KINK_ANGLE",
    "Breakthrough",
    "braid_bend",
    "breakthroughs",
    "combing_cost",
    "jam_metrics",
    "optimal_q",
]

COST_Q0 = 25.0
"""q0 of eq. 2.8: fixed number of pitches characteristic of the strategies compared."""

# [deg] bend of the braid below the tine that counts as a kink (a choice; the angle itself is reported)
KINK_ANGLE = 30.0
_BEND_MIN_PITCHES = 3


def _smooth(y: np.ndarray, window: int) -> np.ndarray:
    if window <= 1 or y.size < window:
        return y.copy()
    from scipy.ndimage import uniform_filter1d

    return uniform_filter1d(y, size=window, mode="nearest")


# the jam criterion's peak ratio and force smoothing, shared by the force-only flag and the break-through analysis
_JAM_RATIO = 1.25
_JAM_WINDOW = 9  # samples


def jam_metrics(
    x: np.ndarray, f: np.ndarray, *, ratio: float = _JAM_RATIO, window: int = _JAM_WINDOW
) -> tuple[bool, float]:
    """Detect tine jamming in a force curve f(x) (thesis §2.4): ``(jammed, peak / level after the peak)``.

    The force jams when it rises to a peak and falls once the tine breaks through, while combing goes on. The
    exit x_e is the last position where the smoothed force is still ≥ 1/4 of its maximum (beyond it the tine is
    leaving the free end, which every curve does). Jammed: the largest smoothed force at 0.05 ≤ x ≤ x_e − 0.15
    exceeds ``ratio`` × the median force between that peak and x_e. Loose helices rise to a plateau or keep
    rising (ratio ≈ 1).

    Parameters
    ----------
    x, f : np.ndarray
        Scaled tine position and force.
    ratio : float
        Minimal peak-to-later-level ratio of a jam.
    window : int
        Moving-average width (samples) applied to f first.
    """
    x = np.asarray(x, dtype=float)
    fs = _smooth(np.asarray(f, dtype=float), window)
    if fs.size == 0 or fs.max() <= 0:
        return False, float("nan")
    x_exit = float(x[np.flatnonzero(fs >= 0.25 * fs.max())[-1]])
    cand = np.flatnonzero((x >= 0.05) & (x <= x_exit - 0.15))
    if cand.size == 0:
        return False, float("nan")
    k = int(cand[np.argmax(fs[cand])])
    level = float(np.median(fs[(x >= x[k]) & (x <= x_exit)]))
    jam_ratio = float(fs[k]) / level if level > 0 else float("inf")
    return bool(jam_ratio >= ratio), jam_ratio


class Breakthrough(NamedTuple):
    """One drop of the smoothed force by at least the jam ratio: the tine breaking through (thesis §2.4)."""

    x_peak: float
    x_drop: float
    f_peak: float
    f_drop: float
    bend: float
    """Largest braid bend below the tine during the fall [deg]; NaN if it was not measured there."""

    @property
    def kinked(self) -> bool:
        return bool(self.bend >= KINK_ANGLE)


def breakthroughs(
    x: np.ndarray, f: np.ndarray, bend: np.ndarray, *, ratio: float = _JAM_RATIO, window: int = _JAM_WINDOW
) -> list[Breakthrough]:
    """Every break-through of the tine: the smoothed force falls from a local peak to below peak / ``ratio``.

    Thesis §2.4 describes the jam cycle: link density builds up ahead of the tine until "the relative shear often
    leads to the kinked configuration ... accompanied by a peak in applied force. ... eventually the tine breaks
    through and the force decreases, before the same cycle repeats again"; for loose helices "λ(s) never crosses the
    threshold needed for kinking, and the force required to comb never peaks". So each drop is returned with the
    largest bend of the braid below the tine (:func:`braid_bend`) during the fall (from the last sample within half
    the drop of the peak to the end of the drop), widened by half the smoothing window; a *kink jam* is a
    break-through with that bend ≥ :data:`KINK_ANGLE`. Peaks below a quarter of the largest force are ignored (the
    tine brushing released free ends). ``ratio`` and ``window`` are those of :func:`jam_metrics`.

    Parameters
    ----------
    x, f : np.ndarray
        Scaled tine position and force.
    bend : np.ndarray
        Braid bend [deg] per sample, NaN where it is not measured (it then counts as no kink).
    """
    x = np.asarray(x, dtype=float)
    fs = _smooth(np.asarray(f, dtype=float), window)
    bend = np.asarray(bend, dtype=float)
    if not (x.shape == fs.shape == bend.shape) or x.ndim != 1:
        raise ValueError(f"x, f and bend must be 1-D of one length, got {x.shape}, {fs.shape}, {bend.shape}")
    if not ratio > 1.0:
        raise ValueError(f"ratio must be > 1, got {ratio!r}")
    n = fs.size
    if n == 0 or fs.max() <= 0:
        return []
    floor = 0.25 * float(fs.max())
    half = window // 2
    out: list[Breakthrough] = []
    i = 0
    while i < n - 1:
        peak, j = i, i
        while j < n and fs[j] * ratio >= fs[peak]:  # walk on until the force has fallen below peak / ratio
            if fs[j] >= fs[peak]:  # the last of equal maxima: the drop starts there
                peak = j
            j += 1
        if j >= n:
            break
        if fs[peak] > floor:
            # the fall itself: from the last sample still within half the drop of the peak, ± half a window
            start = peak + int(np.flatnonzero(fs[peak:j] >= 0.5 * (1.0 + 1.0 / ratio) * fs[peak])[-1])
            part = bend[max(0, start - half) : min(n, j + half + 1)]
            b = float(np.nanmax(part)) if np.isfinite(part).any() else float("nan")
            out.append(Breakthrough(float(x[peak]), float(x[j]), float(fs[peak]), float(fs[j]), b))
        while j < n - 1 and fs[j + 1] < fs[j]:  # the next cycle starts at the bottom of this drop
            j += 1
        i = max(j, i + 1)
    return out


def braid_bend(frames, z_tine, points_per_pitch: int, *, min_pitches: int = _BEND_MIN_PITCHES) -> np.ndarray:
    """Bend of the braid below the tine [deg] for each frame: the kink of thesis Fig. 2.2a.

    The braid centerline is (a + b)/2 (the pairing of :func:`~hairbrush_env.topology.link_density`). Its part from the
    first vertex below the tine to one pitch above the free end is smoothed by a moving average over one pitch (the
    helical wiggle of the midpoint) and the largest angle between its tangent and the downward vertical is returned.
    A straight hanging braid gives ≈ 0°, a braid folded sideways 90°. The last pitch is left out because the free
    ends untwist and splay there, which moves their midpoint sideways without any bend of the braid.

    Parameters
    ----------
    frames : (n_frames, 2, n, 3) array_like
        The two strands' vertices (clamp first) per frame.
    z_tine : float or (n_frames,) array_like
        Height of the tine axis per frame [m].
    points_per_pitch : int
        Vertices per helix pitch along one strand (the smoothing window and the excluded free-end piece).
    min_pitches : int
        Frames with fewer pitches of braid below the tine give NaN (during the release the short rest folds over
        the tine, which is not a kink of the braid).
    """
    fr = np.asarray(frames, dtype=float)
    if fr.ndim != 4 or fr.shape[1] != 2 or fr.shape[3] != 3:
        raise ValueError(f"frames: expected shape (n_frames, 2, n, 3), got {fr.shape}")
    for name, v in (("points_per_pitch", points_per_pitch), ("min_pitches", min_pitches)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 2:
            raise ValueError(f"{name}: expected an integer >= 2, got {v!r}")
    z = np.broadcast_to(np.asarray(z_tine, dtype=float), (fr.shape[0],))
    from scipy.ndimage import uniform_filter1d

    w = int(points_per_pitch)
    half = w // 2
    out = np.full(fr.shape[0], np.nan)
    for k in range(fr.shape[0]):
        c = 0.5 * (fr[k, 0] + fr[k, 1])
        below = np.flatnonzero(c[:, 2] < z[k])
        if below.size == 0 or c.shape[0] - below[0] < min_pitches * w:
            continue
        piece = c[below[0] : c.shape[0] - w]
        smooth = uniform_filter1d(piece, size=w, axis=0, mode="nearest")[half : piece.shape[0] - half]
        t = np.diff(smooth, axis=0)
        norm = np.linalg.norm(t, axis=1)
        t = t[norm > 0] / norm[norm > 0, None]
        if t.size:
            out[k] = float(np.degrees(np.arccos(np.clip(-t[:, 2], -1.0, 1.0))).max())
    return out


def combing_cost(f_max, q, gamma, *, q0: float = COST_Q0):
    """Cost of combing, eq. 2.8: C(q) = γ f_max(q) + (1 − γ) q0 / q (element-wise)."""
    q = np.asarray(q, dtype=float)
    if np.any(q <= 0):
        raise ValueError(f"q must be > 0, got {q!r}")
    gamma = np.asarray(gamma, dtype=float)
    if np.any((gamma < 0) | (gamma > 1)):
        raise ValueError(f"gamma must lie in [0, 1], got {gamma!r}")
    return gamma * np.asarray(f_max, dtype=float) + (1.0 - gamma) * q0 / q


def optimal_q(q: Sequence[float], f_max: Sequence[float], gamma: float, *, q0: float = COST_Q0) -> float:
    """The q of a sweep that minimises C(q) (eq. 2.8) for one γ."""
    c = combing_cost(f_max, q, gamma, q0=q0)
    return float(np.asarray(q, dtype=float)[int(np.argmin(c))])
