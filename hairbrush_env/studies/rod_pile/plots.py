"""Figures of the rod-pile study, drawn with :mod:`hairbrush_env.viz`: compression loops and softening (Figs 4.2,
4.6), the tension test (Fig. 5.3), orientation and contact-number distributions (Figs 4.7, 4.8) and φ_f α vs α
(Fig. 4.5)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .mechanics import CompressionResult, TensionResult
from .structure import contact_numbers, orientations, philipse_contact_number

__all__ = [
    "plot_compression",
    "plot_phi_alpha",
    "plot_structure",
    "plot_tension",
]


def plot_compression(
    result: CompressionResult, path: str | Path, *, single: CompressionResult | None = None
) -> Path:
    """Load–strain loops of every cycle (Fig. 4.2e / 4.6) and the maximum load per cycle (Fig. 4.2d inset).

    ``single``: a one-cycle test to the largest strain on a fresh copy of the pile, drawn in red (Fig. 4.6).
    """
    from ...viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(2, 1, width=4.6, height=3.6)
    ax, ax2 = axes[0]
    for c, (s, f) in enumerate(zip(result.strain, result.load, strict=True)):
        col = PALETTE[0] if single is not None else PALETTE[c % len(PALETTE)]
        ax.plot(s, f, color=col, lw=1.0, label=f"cycle {c + 1}" if single is None else None)
    if single is not None:
        ax.plot(single.strain[0], single.load[0], color=PALETTE[1], lw=1.4,
                label=f"single cycle to ε = {single.cycle_strain_max[0]:.2g}")  # fmt: skip
        ax.plot([], [], color=PALETTE[0], label="cycles of increasing ε_max")
    ax.axhline(result.weight, color="0.5", ls=":", lw=1, label="pile weight")
    ax.set(xlabel="strain ε", ylabel="piston load [N]", title="compression cycles")
    ax.legend(fontsize=7)
    cyc = np.arange(1, len(result.max_load) + 1)
    ax2.plot(cyc, result.max_load, "o-", color=PALETTE[0], label="maximum load")
    varying = len(result.cycle_strain_max) > 1 and np.ptp(result.cycle_strain_max) > 0
    if len(cyc) >= 2 and not varying:
        a, b = result.softening_fit()
        x = np.linspace(1, cyc[-1], 50)
        ax2.plot(x, a + b * np.log(x), ":", color=PALETTE[1], label=f"{a:.3g} {b:+.3g} ln(cycle)")
    if varying:
        reload = result.reload_load_at_previous_max()
        ax2.plot(cyc, reload, "s", mfc="none", color=PALETTE[1], label="reload at previous ε_max")
    ax2.set(xlabel="cycle", ylabel="load [N]", title="softening over cycles")
    ax2.legend(fontsize=7)
    save_figure(fig, path)
    return Path(path)


def plot_tension(result: TensionResult, path: str | Path) -> Path:
    """Load and weight of the lifted part vs plate lift; the area between them is the disentanglement energy."""
    from ...viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(1, 1, width=5.0, height=3.8)
    ax = axes[0, 0]
    x = result.displacement * 1e3
    ax.plot(x, result.load, color=PALETTE[0], label="load")
    ax.plot(x, result.lifted_weight, color=PALETTE[1], label="weight of lifted part")
    upto = x <= (result.separation * 1e3 if result.separated else x[-1]) + 1e-9
    ax.fill_between(x[upto], result.lifted_weight[upto], result.load[upto],
                    where=result.load[upto] > result.lifted_weight[upto],
                    color=PALETTE[5], alpha=0.4, label=f"E = {result.energy * 1e3:.3g} mJ")  # fmt: skip
    if result.separated:
        ax.axvline(result.separation * 1e3, color="0.4", ls="--", lw=1, label="separation")
    ax.set(xlabel="plate lift [mm]", ylabel="force [N]", title="pulling glued layers apart (Fig. 5.3b)")
    ax.legend(fontsize=8)
    save_figure(fig, path)
    return Path(path)


def plot_structure(packings: dict, path: str | Path) -> Path:
    """Orientation distributions θ, ϕ (Fig. 4.7c–d) and contact-number distributions (Fig. 4.8) of packings."""
    from ...viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(3, 1, width=4.2, height=3.4)
    a_th, a_ph, a_c = axes[0]
    for k, (label, p) in enumerate(packings.items()):
        col = PALETTE[k % len(PALETTE)]
        th, ph = orientations(p)
        a_th.hist(
            np.degrees(th), bins=18, range=(0, 90), density=True, histtype="step", color=col, label=label
        )
        a_ph.hist(
            np.degrees(ph), bins=18, range=(0, 180), density=True, histtype="step", color=col, label=label
        )
        c = contact_numbers(p)
        a_c.hist(c, bins=np.arange(c.max() + 2) - 0.5, density=True, histtype="step", color=col,
                 label=f"{label}: ⟨c⟩={c.mean():.2f}")  # fmt: skip
    x = np.linspace(0, 90, 50)
    a_th.plot(x, np.sin(np.radians(x)) * np.pi / 180, "k:", lw=1, label="isotropic")
    a_th.set(xlabel="polar angle θ [deg]", ylabel="density")
    a_ph.set(xlabel="azimuth ϕ [deg]", ylabel="density")
    a_c.set(xlabel="contacts per rod c", ylabel="fraction")
    for a in (a_th, a_ph, a_c):
        a.legend(fontsize=7)
    save_figure(fig, path)
    return Path(path)


def plot_phi_alpha(alpha, phi, path: str | Path, *, contacts=None, phi_bulk=None) -> Path:
    """φ_f α vs α (Fig. 4.5: φ_f α ≈ const), and optionally ⟨c⟩ vs Philipse's equation.

    ``phi`` is the container-averaged φ_f; ``phi_bulk`` (optional) the bulk value away from the wall layer
    (inner cylinder R − L/2, :func:`packing_fraction` with ``wall_margin``). Philipse's prediction uses the bulk
    φ when given (the contacts are counted on bulk rods), else φ_f.
    """
    from ...viz import PALETTE, new_figure, save_figure

    alpha, phi = np.asarray(alpha, float), np.asarray(phi, float)
    order = np.argsort(alpha)
    ncols = 2 if contacts is not None else 1
    fig, axes = new_figure(ncols, 1, width=4.6, height=3.6)
    ax = axes[0, 0]
    ax.axhspan(3.0, 6.0, color="0.92", label="real random rod packings (3–6)")
    ax.axhline(3.2, ls=":", color=PALETTE[3], label="thesis Fig. 4.5 fit (3.2)")
    ax.plot(
        alpha[order], (phi * alpha)[order], "o--", mfc="none", color=PALETTE[0], label="container average"
    )
    if phi_bulk is not None:
        pb = np.asarray(phi_bulk, float)
        ax.plot(alpha[order], (pb * alpha)[order], "o-", color=PALETTE[1], label="bulk (≥ L/2 from the wall)")
    top = max(6.5, float(np.nanmax(phi * alpha)) * 1.1)
    ax.set(xlabel="aspect ratio α", ylabel="φ_f α", title="Fig. 4.5", ylim=(0, top))
    ax.legend(fontsize=7)
    if contacts is not None:
        ax2 = axes[0, 1]
        ref = phi if phi_bulk is None else np.asarray(phi_bulk, float)
        pred = np.array([philipse_contact_number(p, a) for p, a in zip(ref, alpha, strict=True)])
        c = np.asarray(contacts, float)
        ax2.fill_between(alpha[order], 0.7 * pred[order], 1.3 * pred[order], color="0.92", label="±30 %")
        ax2.plot(alpha[order], c[order], "o-", color=PALETTE[0], label="simulated ⟨c⟩ (bulk rods)")
        ax2.plot(alpha[order], pred[order], "s--", mfc="none", color=PALETTE[1],
                 label="Philipse φ(6α²+24α+16)/(3α+2)" + ("" if phi_bulk is None else " at bulk φ"))  # fmt: skip
        ax2.set(xlabel="aspect ratio α", ylabel="⟨c⟩", ylim=(0, 1.4 * max(np.nanmax(c), np.nanmax(pred))))
        ax2.legend(fontsize=7)
    save_figure(fig, path)
    return Path(path)
