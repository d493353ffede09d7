"""Fitting the sigmoid steepness k in simulation, the way the thesis did on real wigs (Fig. 3.9).

1. For every wig preset, find the largest normalized brush length b_l whose first stroke stays below F_T:
   bisection on b_l, every trial on a *fresh* pre-brushed wig (env reset with the same seed), for several seeds;
   the safe length of a wig is the minimum over seeds.
2. Choose k so the sigmoid b_l0(R_c) = 1/(1 + exp(k (R_c − c))) (eq. 3.3, sign corrected) lies below every
   (R_c, safe length) point: each point with R_c > c gives a lower bound on k, each point with R_c < c and safe
   length < 1 gives an upper bound. The smallest feasible k is the fit (the longest strokes that stay safe).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SafePoint:
    wig: str
    rp: float  # true R/P
    rc: float  # vision R_c of the first observation (mean over seeds)
    safe_length: float  # largest b_l whose stroke stayed below F_T on every seed
    trials: int


def first_stroke_force(env, b_l: float, seed: int) -> float:
    """Max force of one stroke of length ``b_l`` on the fresh pre-brushed wig of ``seed``."""
    env.reset(seed=seed)
    base = env.unwrapped
    _, _, _, _, info = env.step(base.brush_length_to_action(b_l))
    return float(info["max_force"])


def max_safe_length(env, seeds: Sequence[int], *, tol: float = 0.05) -> tuple[float, int]:
    """Bisection for the largest b_l ∈ [min_brush_length, 1] with max force < F_T on all ``seeds``."""
    base = env.unwrapped
    f_t = base.force_threshold
    trials = 0

    def safe(b: float) -> bool:
        nonlocal trials
        for s in seeds:
            trials += 1
            if first_stroke_force(env, b, s) >= f_t:
                return False
        return True

    lo, hi = base.min_brush_length, 1.0
    if safe(hi):
        return 1.0, trials
    if not safe(lo):
        return lo, trials
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if safe(mid) else (lo, mid)
    return lo, trials


def safe_point(
    wig: str, seeds: Sequence[int], tol: float, width: int, height: int, physics: str = "v0"
) -> SafePoint:
    """One wig of the fit under ``HairBrush-{physics}``: its vision R_c (mean over ``seeds``) and its largest safe
    b_l (one cell of ``scripts/fit_sigmoid.py``, run by :mod:`hairbrush_env.executor` in this process, local
    workers or Ray)."""
    from controllers.vision import curliness
    from hairbrush_env.envs import make_version

    env = make_version(f"HairBrush-{physics}", wig=wig, obs_mode="state+image", width=width, height=height)
    try:
        rc = float(
            np.mean([curliness(env.reset(seed=s)[0]["image"], roi=env.unwrapped.hair_roi()) for s in seeds])
        )
        safe, trials = max_safe_length(env, seeds, tol=tol)
        return SafePoint(wig, env.unwrapped.sim.curliness_true, rc, safe, trials)
    finally:
        env.close()


def fit_k(rc: Sequence[float], safe: Sequence[float], *, c: float = 0.5) -> tuple[float, float, float]:
    """Smallest k > 0 with 1/(1 + exp(k (R_c − c))) ≤ safe length at every point.

    Returns ``(k, k_lower, k_upper)``; ``k = nan`` if the bounds conflict (then no sigmoid with midpoint ``c``
    stays below all points).
    """
    lower, upper = 0.0, math.inf
    for r, s in zip(rc, safe, strict=True):
        s = min(max(float(s), 1e-9), 1.0)
        if s >= 1.0:
            continue  # a full stroke is safe: no constraint
        logit = math.log(1.0 / s - 1.0)  # k (R_c − c) must be ≥ this
        if r > c:
            lower = max(lower, logit / (r - c))
        elif r < c:
            upper = min(upper, logit / (r - c))
        elif logit > 0:  # r == c needs s ≥ 0.5
            return math.nan, lower, upper
    k = max(lower, 1e-6)
    return (k if k <= upper else math.nan), lower, upper


def plot_fit(points: Sequence[SafePoint], k: float, path, *, thesis_k: float = 8.5, c: float = 0.5) -> None:
    from hairbrush_env.viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(1, 1, width=5.5, height=4.2)
    ax = axes[0, 0]
    r = np.linspace(0, 1, 200)
    ax.scatter([p.rc for p in points], [p.safe_length for p in points], color=PALETTE[0], zorder=3,
               label="largest safe b_l (simulation)")  # fmt: skip
    for p in points:
        ax.annotate(p.wig, (p.rc, p.safe_length), textcoords="offset points", xytext=(4, 4), fontsize=8)
    if math.isfinite(k):
        ax.plot(r, 1 / (1 + np.exp(k * (r - c))), color=PALETTE[1], label=f"fit: k = {k:.2f}")
    ax.plot(r, 1 / (1 + np.exp(thesis_k * (r - c))), "--", color=PALETTE[2], label=f"thesis: k = {thesis_k}")
    ax.set(xlabel="vision curliness R_c", ylabel="normalized brush length b_l", ylim=(0, 1.05))
    ax.set_title("Sigmoid start height (eq. 3.3) fitted in simulation (Fig. 3.9)")
    ax.legend(fontsize=8)
    save_figure(fig, path)
