"""Benchmark the rod-pile study (prints tables).

    python scripts/benchmark_rodpile.py [--quick] [--alpha 16] [--sizes 30 60 120] [--container 1.5]
                                        [--freeze-depth 1.0] [--skip-fields] [--solver-check PILE.npz]

1. ``local_fields`` for 3 000 rods of aspect ratio α = 76 in a container of diameter 3 L (target ≤ 2 s). The rods
   are placed uniformly at random (positions in the cylinder, isotropic directions) at a packing fraction close to
   the thesis's piles — the cost of the fields depends on the number of rods per cell, not on how they were packed.
2. ``generate_packing`` wall time versus the number of rods (MuJoCo drop, jostle and settle) at aspect ratio
   ``--alpha`` in a container of ``--container`` rod lengths, optionally with rods buried deeper than
   ``--freeze-depth`` rod lengths frozen during deposition; also the pile height and φ_f α reached.
3. ``--solver-check PILE``: on a saved pile, the cost of one MuJoCo step and how far the (drag-free) pile sinks in
   150 steps for several constraint solvers, and the frictional creep of the settled pile over 1 200 steps with
   the default solver and with ``noslip_iterations = 10``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from hairbrush_env.studies.rod_fields import local_fields
from hairbrush_env.studies.rod_pile import Packing, generate_packing


def random_packing(
    n: int, alpha: float, *, length: float = 0.05, phi: float = 0.05, seed: int = 0
) -> Packing:
    rng = np.random.default_rng(seed)
    d = length / alpha
    radius = 1.5 * length
    height = n * np.pi * d**2 / 4 * length / (phi * np.pi * radius**2)
    r = radius * np.sqrt(rng.uniform(0, 1, n))
    th = rng.uniform(0, 2 * np.pi, n)
    centre = np.column_stack([r * np.cos(th), r * np.sin(th), rng.uniform(0, height, n)])
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    ends = np.stack([centre - 0.5 * length * u, centre + 0.5 * length * u], axis=1)
    return Packing.from_endpoints(ends, d, container_diameter=2 * radius)


def solver_check(path: str) -> None:
    import math

    import mujoco

    from hairbrush_env.studies.rod_pile import Pile, SimParams, load_packing, poses_from_endpoints

    pk = load_packing(path)
    pos, quat, length = poses_from_endpoints(pk.endpoints)
    sp = SimParams(length, pk.diameter, pk.container_diameter, friction=pk.meta.get("friction", 0.4))
    d = sp.diameter
    print(f"\n{path}: {pk.n_rods} rods, α = {pk.aspect_ratio:.0f}")
    print("| solver | ms / step | contacts | mean sink in 150 steps [d] | lowest rod point [d] |")
    print("|---|---:|---:|---:|---:|")
    S = mujoco.mjtSolver
    for name, solver, iters in (("PGS 30 (used)", S.mjSOL_PGS, 30), ("PGS 10", S.mjSOL_PGS, 10),
                                ("CG 10", S.mjSOL_CG, 10), ("Newton 5", S.mjSOL_NEWTON, 5)):  # fmt: skip
        pile = Pile(sp, pos, quat)
        pile.model.opt.solver, pile.model.opt.iterations = solver, iters
        pile.set_drag(False)
        z0 = pile.data.xpos[pile.body_of_rod, 2].copy()
        t0 = time.perf_counter()
        pile.step(150)
        ms = (time.perf_counter() - t0) / 150 * 1e3
        sink = float(np.mean(z0 - pile.data.xpos[pile.body_of_rod, 2]) / d)
        print(f"| {name} | {ms:.1f} | {pile.data.ncon} | {sink:.3g} | {pile.endpoints()[..., 2].min() / d:.3g} |",
              flush=True)  # fmt: skip
    print("\n| creep of the settled pile | steps | max rod-end drift [d] | ⟨|cos θ|⟩ before → after "
          "| max speed / √(gd) |")  # fmt: skip
    print("|---|---:|---:|---:|---:|")

    def cos_mean(ep):
        u = ep[:, 1] - ep[:, 0]
        return float(np.mean(np.abs(u[:, 2]) / np.linalg.norm(u, axis=1)))

    for name, noslip in (("PGS 30", 0), ("PGS 30 + noslip 10", 10)):
        pile = Pile(sp, pos, quat)
        pile.model.opt.noslip_iterations = noslip
        pile.set_drag(False)
        pile.step(1200)
        ep = pile.endpoints()
        drift = float(np.abs(ep - pk.endpoints).max() / d)
        v = pile.max_speed() / math.sqrt(9.81 * d)
        print(f"| {name} | 1200 | {drift:.2f} | {cos_mean(pk.endpoints):.4f} → {cos_mean(ep):.4f} | {v:.3f} |",
              flush=True)  # fmt: skip


def main() -> None:
    from hairbrush_env.studies.rod_pile import packing_fraction, pile_height

    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--alpha", type=float, default=16.0)
    p.add_argument("--sizes", type=int, nargs="+", default=None, help="numbers of rods (default 30 60 120)")
    p.add_argument("--container", type=float, default=3.0, help="container diameter in rod lengths")
    p.add_argument("--freeze-depth", type=float, default=None)
    p.add_argument("--batch", type=int, default=10)
    p.add_argument("--skip-fields", action="store_true")
    p.add_argument("--skip-generate", action="store_true")
    p.add_argument(
        "--solver-check", default=None, metavar="PILE", help="saved pile (.npz) for the solver table"
    )
    a = p.parse_args()
    if a.solver_check:
        solver_check(a.solver_check)
    if not a.skip_fields:
        pk = random_packing(3000, 76.0)
        local_fields(pk)  # compile / warm caches
        times = []
        for _ in range(1 if a.quick else 3):
            t0 = time.perf_counter()
            f = local_fields(pk)
            times.append(time.perf_counter() - t0)
        print("| fields | rods | α | cells | best wall [s] | target |")
        print("|---|---:|---:|---:|---:|---|")
        cells = int(np.asarray(f.phi).size)
        print(f"| local_fields (cubes, l_s = 10 d) | 3000 | 76 | {cells} | {min(times):.2f} | ≤ 2 s: "
              f"{'met' if min(times) <= 2 else 'NOT met'} |")  # fmt: skip
    if a.skip_generate:
        return
    sizes = a.sizes or ((30, 60) if a.quick else (30, 60, 120))
    length = 0.05
    print(
        f"\n| generate_packing (α = {a.alpha:g}, container {a.container:g} L, batch {a.batch}, "
        f"freeze_depth {a.freeze_depth}) | rods | wall [s] | H / L | φ_f α |"
    )
    print("|---|---:|---:|---:|---:|")
    for n in sizes:
        t0 = time.perf_counter()
        pk = generate_packing(n, length, length / a.alpha, container_diameter=a.container * length, seed=0,
                              batch_size=a.batch, freeze_depth=a.freeze_depth, progress=False)  # fmt: skip
        wall = time.perf_counter() - t0
        print(f"| drop + jostle + settle | {n} | {wall:.1f} | {pile_height(pk) / length:.2f} | "
              f"{packing_fraction(pk) * a.alpha:.2f} |", flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
