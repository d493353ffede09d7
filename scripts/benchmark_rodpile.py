"""Benchmark the rod-pile study (prints tables).

    python scripts/benchmark_rodpile.py [--quick]

1. ``local_fields`` for 3 000 rods of aspect ratio α = 76 in a container of diameter 3 L (target ≤ 2 s). The rods
   are placed uniformly at random (positions in the cylinder, isotropic directions) at a packing fraction close to
   the thesis's piles — the cost of the fields depends on the number of rods per cell, not on how they were packed.
2. ``generate_packing`` wall time versus the number of rods (MuJoCo drop, jostle and settle).
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


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true")
    a = p.parse_args()
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
    print("\n| generate_packing | rods | α | wall [s] |")
    print("|---|---:|---:|---:|")
    for n in (30, 60) if a.quick else (30, 60, 120):
        t0 = time.perf_counter()
        generate_packing(n, 0.05, 0.05 / 16, seed=0)
        print(f"| drop + jostle + settle | {n} | 16 | {time.perf_counter() - t0:.1f} |", flush=True)


if __name__ == "__main__":
    main()
