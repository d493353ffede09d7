"""A kinematic tour of the topology library, used by ``hairbrush topology demo``.

A double helix is "combed" kinematically: a tine descends from the clamp; above it the strands keep their helix,
below it the link the tine has pushed down is carried by a shorter, tighter helix (link conserved until it reaches
the free end), then leaves. It exercises Lk, λ(s), the link current and the census on data whose answers are
known in closed form, and it is fast (no physics).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..topology.census import interaction_census
from ..topology.gauss import link_current, link_density, linking_number


@dataclass(frozen=True)
class DemoResult:
    x: np.ndarray  # tine position as a fraction of the helix height
    lk: np.ndarray  # open-curve Lk of the two strands at each x
    current: np.ndarray  # dLk/dx
    snapshots: dict[float, tuple[np.ndarray, np.ndarray]]  # x -> (s, λ/λ0)
    frames: list[dict[str, np.ndarray]]  # strand polylines per frame (for the recording)
    census: dict[str, dict[int, float]]  # criterion -> {N: interactions per metre}


def combed_double_helix(
    x: float, *, radius=1e-3, pitch=0.01, turns=10.0, n=801
) -> tuple[np.ndarray, np.ndarray]:
    """Strands hanging from the clamp (z = 0) down to z = −pitch·turns, with the tine at depth fraction ``x``.

    Behind the tine (between clamp and tine) the strands are combed: parallel, unlinked. Ahead of it the link
    not yet expelled, N (1 − x²), is squeezed into the remaining length h (1 − x): the link density there rises to
    λ0 (1 + x) (overwinding, Δλ/λ0 = x > 0) while behind the tine Δλ/λ0 = −1, and the link current through the
    free end, dLk/dx = −2 N x, grows as the tine descends — the qualitative picture of thesis Figs 2.2e and 2.8.
    """
    h = pitch * turns
    depth = np.linspace(0.0, h, n)
    z_tine = x * h
    ahead = depth > z_tine
    density = (1.0 + x) / pitch  # turns per metre ahead of the tine
    phi = np.where(ahead, 2 * np.pi * density * (depth - z_tine), 0.0)
    ra = np.column_stack([radius * np.cos(phi), -radius * np.sin(phi), -depth])
    rb = np.column_stack([radius * np.cos(phi + np.pi), -radius * np.sin(phi + np.pi), -depth])
    return ra, rb


def run_demo(n_frames: int = 21, *, seed: int = 0) -> DemoResult:
    xs = np.linspace(0.0, 1.0, n_frames)
    lks, frames, snaps = [], [], {}
    _, lam0 = link_density(*combed_double_helix(0.0))
    lam0 = float(np.median(lam0))
    for x in xs:
        a, b = combed_double_helix(float(x))
        lks.append(linking_number(a, b, closed=False))
        frames.append({"helix/strand_a": a, "helix/strand_b": b})
        if np.isclose(x, [0.0, 0.25, 0.5, 0.75]).any():
            s, lam = link_density(a, b)
            snaps[round(float(x), 2)] = (s, lam / lam0)
    lk = np.array(lks)
    rng = np.random.default_rng(seed)
    bundle = [
        np.column_stack(
            [
                np.cumsum(rng.normal(0, 4e-3, 60)) + 5e-3 * k,
                np.cumsum(rng.normal(0, 4e-3, 60)),
                -np.linspace(0, 0.2, 60),
            ]
        )
        for k in range(12)
    ]
    census = {c: interaction_census(bundle, criterion=c) for c in ("crossing", "link")}
    return DemoResult(xs, lk, link_current(lk, xs, window=3), snaps, frames, census)


def plot_demo(result: DemoResult, path) -> None:
    from ..viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(2, 2, width=5.2, height=4.0)
    a, b = result.frames[len(result.frames) // 2].values()
    ax = axes[0, 0]
    ax.plot(a[:, 0] * 1e3, a[:, 2], color=PALETTE[0], lw=1)
    ax.plot(b[:, 0] * 1e3, b[:, 2], color=PALETTE[1], lw=1)
    ax.set(xlabel="x [mm]", ylabel="z [m]", title="Double helix, tine at x = 0.5 (side view)")
    ax = axes[0, 1]
    for i, (x, (s, lam)) in enumerate(sorted(result.snapshots.items())):
        ax.plot(s, lam - 1.0, color=PALETTE[i], label=f"x = {x:.2f}")
    ax.set(xlabel="centerline arclength s [m]", ylabel="Δλ/λ0", title="Link density (thesis Fig. 2.2e)")
    ax.legend()
    ax = axes[1, 0]
    ax.plot(result.x, result.lk, "o-", color=PALETTE[0], label="Lk (open Gauss integral)")
    ax2 = ax.twinx()
    ax2.plot(result.x, result.current, color=PALETTE[1], label="dLk/dx")
    ax.set(xlabel="tine position x = d/D", ylabel="Lk", title="Link and link current (Fig. 2.8)")
    ax2.set_ylabel("dLk/dx")
    ax = axes[1, 1]
    width = 0.38
    for i, (crit, counts) in enumerate(result.census.items()):
        ns = np.array(sorted(counts))
        ax.bar(ns + (i - 0.5) * width, [counts[n] for n in ns], width, color=PALETTE[i], label=crit)
    ax.set(
        xlabel="N (strands per cluster)",
        ylabel="ρ [interactions / m]",
        title="N-body census, 12 random strands",
    )
    ax.legend()
    save_figure(fig, path)
