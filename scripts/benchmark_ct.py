"""Benchmark the CT pipeline: time of ``synthetic_tomogram`` + ``segment_rods`` versus the number of rods (table).

    python scripts/benchmark_ct.py [--sizes 100 300 1000] [--alpha 16] [--phi 0.1] [--piles a.npz b.npz ...]

By default the rods are placed at random without overlaps (random sequential addition in a cylinder of diameter
3 L, isotropic directions, packing fraction ``--phi``; few contacts, so recovery is higher than in real piles).
``--piles`` times packings from files instead (e.g. MuJoCo piles from ``hairbrush rodpile generate``). Recovery
(both ends within 1 d, Hungarian matching) is printed for information; the validated numbers are in docs/ct.md
and ``tests/studies/test_ct.py``.
"""

from __future__ import annotations

import argparse
import resource
import time

import numpy as np

from hairbrush_env.studies.ct import match_rods, segment_rods, synthetic_tomogram
from hairbrush_env.studies.rod_pile import Packing, load_packing


def random_packing(n: int, alpha: float, *, length: float = 0.05, phi: float = 0.1, seed: int = 0) -> Packing:
    """Random sequential addition: uniform centres in a cylinder of diameter 3 L, isotropic directions, rods
    rejected if they would come closer than 1.05 d to an accepted rod (no overlaps; contacts are rare)."""
    rng = np.random.default_rng(seed)
    d = length / alpha
    radius = 1.5 * length
    height = n * np.pi * d**2 / 4 * length / (phi * np.pi * radius**2)
    s = np.linspace(-0.5, 0.5, int(2 * alpha) + 1)[:, None] * length  # candidate sampled every d/2
    centres, dirs = np.zeros((n, 3)), np.zeros((n, 3))
    k = 0
    while k < n:
        r = (radius - length / 2) * np.sqrt(rng.uniform())
        th = rng.uniform(0, 2 * np.pi)
        c = np.array([r * np.cos(th), r * np.sin(th), rng.uniform(d, height)])
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        near = np.flatnonzero(np.linalg.norm(centres[:k] - c, axis=1) < length + d)
        if len(near):
            q = c + s * u  # (m, 3) points vs the near rods' axes (point–segment distances)
            rel = q[:, None, :] - centres[near][None]
            t = np.clip(np.einsum("mkj,kj->mk", rel, dirs[near]), -length / 2, length / 2)
            gap = np.linalg.norm(rel - t[..., None] * dirs[near][None], axis=-1)
            if gap.min() < 1.05 * d:
                continue
        centres[k], dirs[k] = c, u
        k += 1
    c, u = centres, dirs
    return Packing.from_endpoints(np.stack([c - length / 2 * u, c + length / 2 * u], 1), d, 2 * radius)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sizes", type=int, nargs="+", default=[100, 300, 1000], help="numbers of random rods")
    p.add_argument("--alpha", type=float, default=16.0)
    p.add_argument("--phi", type=float, default=0.1, help="packing fraction of the random rods")
    p.add_argument("--piles", nargs="*", default=None, help="packing files to time instead of random rods")
    a = p.parse_args()
    cases = (
        ((str(f), load_packing(f)) for f in a.piles)
        if a.piles
        else ((f"random n={n}", random_packing(n, a.alpha, phi=a.phi)) for n in a.sizes)
    )
    print(f"{'packing':<34} {'rods':>5} {'α':>4} {'volume':>16} {'Mvox':>6} {'render s':>9} {'segment s':>10} "
          f"{'found':>6} {'recovered':>9}")  # fmt: skip
    for label, pk in cases:
        t0 = time.perf_counter()
        tom = synthetic_tomogram(pk)
        t1 = time.perf_counter()
        seg = segment_rods(tom, diameter=pk.diameter, container_diameter=pk.container_diameter)
        t2 = time.perf_counter()
        m = match_rods(pk, seg)
        shape = "×".join(str(s) for s in tom.volume.shape)
        print(f"{label[-34:]:<34} {pk.n_rods:>5} {pk.aspect_ratio:>4.0f} {shape:>16} {tom.volume.size / 1e6:>6.1f} "
              f"{t1 - t0:>9.1f} {t2 - t1:>10.1f} {seg.n_rods:>6} {m.recovery:>9.1%}", flush=True)  # fmt: skip
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak resident memory {peak:.0f} MiB")


if __name__ == "__main__":
    main()
