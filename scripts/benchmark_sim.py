"""Simulation benchmarks for hairbrush_env.

Run ``python scripts/benchmark_sim.py`` (or ``--quick``). Each section is a function taking the parsed arguments
and printing a markdown table; add new sections (e.g. wig strand-count scaling) to :data:`SECTIONS`. All physics
lives in :mod:`hairbrush_env.rods`; this script only sweeps parameters and formats results.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable, Sequence

import numpy as np

from hairbrush_env import hair, rods, scene


def _table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---:" for _ in header) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def section_rod_convergence(args: argparse.Namespace) -> None:
    """Cantilever (gravity and tip load) and helical-spring errors vs discretization."""
    edges = (10, 20, 50) if args.quick else (10, 20, 50, 100, 200)
    print("\n## Rod convergence: 0.2 m cantilever, r = 1 mm, E = 10 GPa, ρ = 1300 kg/m³, dt = 2 ms\n")
    rows = []
    for n in edges:
        g = rods.cantilever_study(n, load="gravity")
        t = rods.cantilever_study(n, load="tip")
        rows.append(
            [
                str(n),
                f"{100 * g.rel_error:+.3f}",
                f"{100 * t.rel_error:+.3f}",
                f"{100 * max(abs(g.length_error), abs(t.length_error)):.1e}",
                f"{g.steps_per_second:,.0f}",
            ]
        )
    print(
        _table(["edges", "gravity tip err %", "end-load tip err %", "max abs length err %", "steps/s"], rows)
    )

    per_turn = (10, 20, 30) if args.quick else (10, 20, 30, 40, 80)
    print("\n## Helical spring (3 turns, D = 20 mm, d = 2 mm, pitch 4 mm) vs k = G d⁴ / (8 D³ N)\n")
    rows = []
    for p in per_turn:
        h = rods.helix_study(p)
        rows.append(
            [
                str(p),
                str(h.n_edges),
                f"{100 * h.rel_error:+.2f}",
                f"{100 * abs(h.length_error):.1e}",
                f"{h.steps_per_second:,.0f}",
            ]
        )
    print(_table(["edges/turn", "edges", "stiffness err %", "abs length err %", "steps/s"], rows))


def _timed_sim(wig: hair.WigConfig, **cfg: object) -> tuple[scene.BrushingSim, float, float, float]:
    """Build a sim; return it with build time, cold (shake) reset time and cached reset time [s]."""
    t0 = time.perf_counter()
    sim = scene.BrushingSim(scene.SceneConfig(wig=wig, **cfg))
    t1 = time.perf_counter()
    sim.reset(0)
    t2 = time.perf_counter()
    sim.reset(0)
    t3 = time.perf_counter()
    return sim, t1 - t0, t2 - t1, t3 - t2


def _stroke_rtf(sim: scene.BrushingSim, fraction: float) -> tuple[float, float, scene.StrokeResult]:
    n0 = sim.n_steps
    t0 = time.perf_counter()
    res = sim.stroke(fraction, force_threshold=np.inf, rng=np.random.default_rng(0))
    wall = time.perf_counter() - t0
    steps = (
        sim.n_steps - n0
    )  # the step is 1 ms in the hair and 10 ms outside, so count the real mj_step calls
    return res.sim_time / wall, steps / wall, res


def section_wig_scaling(args: argparse.Namespace) -> None:
    """Real-time factor and steps/s of the full scene (arm + brush + head + wig) vs strand count and edges."""
    base = hair.PRESETS[hair.DEFAULT_WIG]
    counts = (8, 24) if args.quick else (8, 16, 24, 32, 48)
    dt = scene.SceneConfig().timestep
    print(
        f"\n## Scene speed vs strand count: wig '{base.name}' (R/P = {base.curliness}), "
        f"dt = {1e3 * dt:g} ms, one thread\n"
    )
    print(
        "RTF and steps/s over a full stroke (approach, insertion, pull at 0.1 m/s, retraction) with hair-hair"
    )
    print("contact; reset = pre-brushed shake + settle (cold) vs restoring the cached state.\n")
    rows = []
    for n in counts:
        wig = base.replace(n_strands=n, n_triples=2)
        sim, t_build, t_cold, t_cached = _timed_sim(wig)
        rtf, sps, res = _stroke_rtf(sim, 1.0)
        rows.append(
            [
                str(n),
                str(wig.n_edges + 1),
                str(sim.model.nv),
                f"{rtf:.2f}",
                f"{sps:,.0f}",
                f"{t_build:.1f}",
                f"{t_cold:.2f}",
                f"{1e3 * t_cached:.1f}",
                str(res.diverged),
            ]
        )
        sim.close()
    print(
        _table(
            [
                "strands",
                "vertices/strand",
                "nv",
                "RTF",
                "steps/s",
                "build s",
                "cold reset s",
                "cached reset ms",
                "diverged",
            ],
            rows,
        )
    )

    edges = (12, 16) if args.quick else (8, 12, 16, 20, 24)
    print(
        f"\n## Scene speed vs vertices per strand: {base.n_strands} strands of '{base.name}', "
        f"dt = {1e3 * dt:g} ms\n"
    )
    rows = []
    for e in edges:
        wig = base.replace(min_edges=e, max_edges=e)
        sim, _, t_cold, _ = _timed_sim(wig)
        rtf, sps, res = _stroke_rtf(sim, 1.0)
        rows.append(
            [str(e + 1), str(sim.model.nv), f"{rtf:.2f}", f"{sps:,.0f}", f"{t_cold:.2f}", str(res.diverged)]
        )
        sim.close()
    print(_table(["vertices/strand", "nv", "RTF", "steps/s", "cold reset s", "diverged"], rows))


def section_force_table(args: argparse.Namespace) -> None:
    """Maximum brushing force vs curliness and normalized stroke length b_l (thesis Fig. 3.7), with pass-through."""
    names = ["straight", "curly", "coily"] if args.quick else list(hair.PRESETS)
    fractions = (0.33, 1.0) if args.quick else (0.33, 0.67, 1.0)
    print("\n## Max brushing force [N] vs curliness and b_l (seed 0, 0.1 m/s, no abort; thesis F_T = 10 N)\n")
    print(
        "Cells: F_max (Σ|Lk| before→after) [min hair–hair / hair–bristle centerline distance mm, max |ΔLk| per"
    )
    print("0.1 s]; no pass-through needs hair–hair > r = 0.8 mm, hair–bristle > 1.15 mm and |ΔLk| ≤ 0.5.\n")
    rows = []
    for name in names:
        wig = hair.PRESETS[name]
        sim = scene.BrushingSim(scene.SceneConfig(wig=wig))
        row = [name, f"{wig.curliness:.2f}", f"{wig.length:.2f}"]
        for b in fractions:
            sim.reset(0)
            e0 = sim.entanglement()
            mon = scene.PassThroughMonitor(sim)
            sim.add_observer(mon)
            res = sim.stroke(b, force_threshold=np.inf, rng=np.random.default_rng(0))
            sim.remove_observer(mon)
            row.append(
                f"{res.max_force:.2f} ({e0:.1f}→{sim.entanglement():.1f}) "
                f"[{1e3 * mon.hair_hair:.2f} / {1e3 * mon.hair_bristle:.2f}, {mon.max_link_jump:.2f}]"
                + (" DIV" if res.diverged else "")
            )
        row.insert(3, f"{sim.hanging_length:.3f}")
        sim.close()
        rows.append(row)
    print(_table(["wig", "R/P", "length m", "hanging m"] + [f"b_l={b}" for b in fractions], rows))


SECTIONS: list[Callable[[argparse.Namespace], None]] = [
    section_rod_convergence,
    section_wig_scaling,
    section_force_table,
]


def main(argv: Sequence[str] | None = None) -> None:
    """Parse arguments and run every section in :data:`SECTIONS`."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer / coarser cases (CI smoke run)")
    args = parser.parse_args(argv)
    for section in SECTIONS:
        section(args)


if __name__ == "__main__":
    main()
