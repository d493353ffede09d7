"""Thesis-style figures of the combing study: one run (:func:`plot_run`), a sweep (:func:`plot_sweep`) and the
cost of combing (:func:`plot_cost`)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .measures import KINK_ANGLE, combing_cost, optimal_q
from .result import CombingResult

__all__ = ["plot_cost", "plot_run", "plot_sweep"]


def _bend_axis_top(bend: np.ndarray) -> float:
    """Upper y limit of bend plots: 95° unless a fold went further (a whirling kink can exceed 90°)."""
    finite = bend[np.isfinite(bend)]
    return max(95.0, 1.05 * float(finite.max())) if finite.size else 95.0


def plot_run(result: CombingResult, path) -> None:
    """Thesis-style figure of one run: f(x) with the Love curve (Fig. 2.2c), Δλ/λ0 snapshots (Fig. 2.2e), Lk and
    dLk/dx (Fig. 2.8)."""
    from ...viz import PALETTE, new_figure, save_figure

    st = result.setup
    fig, axes = new_figure(3, 1, width=4.6, height=3.6)
    ax = axes[0, 0]
    keep = result.x <= 1.0
    ax.plot(result.x[keep], result.f[keep], color="k", lw=1.2, label="simulation")
    ax.plot(result.x[keep], result.love_f[keep], "--", color=PALETTE[1], label="Love single helix, no slip")
    top = 1.3 * max(result.f_max, 1e-9)
    ax.set(xlabel="x = d/D", ylabel="f = F l0²/B", ylim=(min(0.0, float(result.f.min())), top), xlim=(0, 1))
    ax.set_title(f"P/r={st.P_over_r:g}, R/r={st.R_over_r:g}, t/r={st.t_over_r:g}, q={st.q_effective:.1f}")
    drops = [b for b in result.breakthroughs() if math.isfinite(b.bend) and b.x_peak <= 1.0]
    for kinked, style in ((True, {"color": "k"}), (False, {"facecolor": "none", "edgecolor": "k"})):
        pts = [(b.x_peak, b.f_peak) for b in drops if b.kinked == kinked]
        if pts:
            label = "break-through at a kink (kink jam)" if kinked else "break-through, braid straight"
            ax.scatter(*zip(*pts, strict=True), s=22, zorder=3, label=label, **style)
    bend = result.bend_per_sample()[keep]
    if np.isfinite(bend).any():
        axb = ax.twinx()
        axb.plot(result.x[keep], bend, color=PALETTE[2], lw=0.8, label="braid bend below the tine")
        axb.axhline(KINK_ANGLE, color=PALETTE[2], lw=0.6, ls=":")
        axb.set(ylabel="bend [deg]", ylim=(0, _bend_axis_top(bend)))
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = axb.get_legend_handles_labels()
        ax.legend(h1 + h2, l1 + l2, fontsize=8)
    else:
        ax.legend(fontsize=8)
    ax = axes[0, 1]
    for i, (x, (s, dl)) in enumerate(sorted(result.snapshots.items())):
        ax.plot(s / s[-1], dl, color=PALETTE[i % len(PALETTE)], lw=1, label=f"x = {x:.1f}")
    ax.axhline(0, color="0.6", lw=0.5)
    ax.set(xlabel="s / L (clamp → free end)", ylabel="Δλ/λ0", title="Link density (Fig. 2.2e)")
    ax.legend(fontsize=8)
    ax = axes[0, 2]
    ax.plot(result.x[keep], result.lk[keep] / result.lk0, color=PALETTE[0], label="Lk/Lk0")
    ax.set(xlabel="x = d/D", ylabel="Lk / Lk0", title="Link and link current (Fig. 2.8)", xlim=(0, 1))
    ax2 = ax.twinx()
    ax2.plot(result.x[keep], result.current[keep] / result.lk0, "--", color=PALETTE[1], label="(dLk/dx)/Lk0")
    ax2.set_ylabel("(dLk/dx) / Lk0")
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="lower left")
    save_figure(fig, path)


def plot_sweep(results: Sequence[CombingResult], vary: str, path) -> None:
    """f(x) for every point of a sweep, coloured by the varied parameter, with f_max vs the parameter (Figs 2.2c–d,
    2.4a–b, 2.6)."""
    from ...viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(3, 1, width=4.8, height=3.6)
    ax = axes[0, 0]
    values = sorted({_vary_value(r, vary) for r in results})
    for r in results:
        i = values.index(_vary_value(r, vary))
        keep = r.x <= 1.0
        ax.plot(r.x[keep], r.f[keep], color=PALETTE[i % len(PALETTE)], lw=1, label=f"{vary} = {values[i]:g}")
        ax.plot(r.x[keep], r.love_f[keep], ":", color=PALETTE[i % len(PALETTE)], lw=0.8)
    handles, labels = ax.get_legend_handles_labels()
    uniq = dict(zip(labels, handles, strict=True))
    ax.legend(uniq.values(), uniq.keys(), fontsize=8)
    fmax = max(r.f_max for r in results)
    ax.set(xlabel="x = d/D", ylabel="f = F l0²/B", ylim=(0, 1.3 * fmax), xlim=(0, 1),
           title="combing force (dotted: Love, no slip)")  # fmt: skip
    ax = axes[0, 1]
    v = np.array([_vary_value(r, vary) for r in results])
    fm = np.array([r.f_max for r in results])
    jam = np.array([r.jammed for r in results])
    ax.plot(v[~jam], fm[~jam], "o", color=PALETTE[0], label="no jam (force flag)")
    ax.plot(v[jam], fm[jam], "s", color=PALETTE[1], label="jammed (force flag)")
    kj = np.array([r.jammed_by_kink for r in results])
    if kj.any():  # the thesis's jam cycle: a break-through at a kink (§2.4)
        ax.plot(v[kj], fm[kj], "o", ms=13, mfc="none", mec="k", label="kink jam")
    passed = np.array([r.strand_crossings > 0 or r.tine_crossings > 0 for r in results])
    if passed.any():  # a contact gave way in these runs: their link accounting excludes the passage
        ax.plot(v[passed], fm[passed], "x", color="k", ms=9, label="strand passage")
    ax.set(xlabel=vary, ylabel="f_max", title=f"maximal force vs {vary}")
    ax.legend(fontsize=8)
    ax = axes[0, 2]
    bend = np.array([r.bend_max for r in results])
    ax.plot(v, bend, "o", color=PALETTE[2])
    ax.axhline(KINK_ANGLE, color="0.5", lw=0.8, ls="--", label=f"kink threshold {KINK_ANGLE:g}°")
    ax.set(xlabel=vary, ylabel="largest bend below the tine [deg]", title="kinking (Fig. 2.2a)",
           ylim=(0, _bend_axis_top(bend)))  # fmt: skip
    ax.legend(fontsize=8)
    save_figure(fig, path)


def _vary_value(result: CombingResult, vary: str) -> float:
    return float(result.setup.q_effective if vary == "q" else getattr(result.setup, vary))


def plot_cost(q: Sequence[float], f_max: Sequence[float], path, *, gammas=(0.0, 0.5, 1.0)) -> None:
    """C(q) of eq. 2.8 for several γ (thesis Fig. 2.4c), optimal q marked."""
    from ...viz import PALETTE, new_figure, save_figure

    order = np.argsort(q)
    q = np.asarray(q, dtype=float)[order]
    f_max = np.asarray(f_max, dtype=float)[order]
    fig, axes = new_figure(1, 1, width=5.0, height=3.8)
    ax = axes[0, 0]
    for i, g in enumerate(gammas):
        c = combing_cost(f_max, q, g)
        ax.plot(q, c, "o-", color=PALETTE[i], label=f"γ = {g:g} (optimal q = {optimal_q(q, f_max, g):g})")
    ax.set(xlabel="q (pitches between tine and free end)", ylabel="C(q) = γ f_max + (1−γ) q0/q",
           title="cost of combing (eq. 2.8, q0 = 25)")  # fmt: skip
    ax.legend(fontsize=8)
    save_figure(fig, path)
