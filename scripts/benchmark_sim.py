"""Simulation benchmarks for hairbrush_env.

Run ``python scripts/benchmark_sim.py`` (or ``--quick``). Each section is a function taking the parsed arguments
and printing a markdown table; add new sections (e.g. wig strand-count scaling) to :data:`SECTIONS`. All physics
lives in :mod:`hairbrush_env.rods`; this script only sweeps parameters and formats results.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence

from hairbrush_env import rods


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


SECTIONS: list[Callable[[argparse.Namespace], None]] = [section_rod_convergence]


def main(argv: Sequence[str] | None = None) -> None:
    """Parse arguments and run every section in :data:`SECTIONS`."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer / coarser cases (CI smoke run)")
    args = parser.parse_args(argv)
    for section in SECTIONS:
        section(args)


if __name__ == "__main__":
    main()
