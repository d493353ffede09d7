"""Benchmark the exact Gauss-integral kernel (prints a table).

    python scripts/benchmark_topology.py [--segments 10000] [--repeats 3]

Reports segment pairs per second for ``linking_number`` on two closed curves of ``--segments`` segments each,
the time for a 200 × 200 hair pair (open curves), and the same with one thread, so the ratio of 2 threads to 1
is measured in one run (the machine is shared and noisy; compare ratios, not absolute numbers across runs).
Target: ≥ 5e7 pairs/s on 2 cores (10k × 10k in ≤ 2 s).
"""

from __future__ import annotations

import argparse
import time

import numba
import numpy as np

from hairbrush_env.topology import linking_number, writhe


def closed_curves(n: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Two interlinked closed random-ish curves (torus-knot-like) of n vertices each."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    rng = np.random.default_rng(seed)
    wobble = 0.05 * rng.standard_normal((n, 3))
    a = np.column_stack([np.cos(t), np.sin(t), 0.2 * np.sin(7 * t)]) + wobble * 0.1
    b = np.column_stack([1 + np.cos(t), 0.2 * np.sin(5 * t), np.sin(t)]) + wobble[::-1] * 0.1
    return a, b


def best_time(fn, repeats: int) -> float:
    fn()  # warm-up (JIT compile / cache load)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--segments", type=int, default=10_000)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()

    n = args.segments
    a, b = closed_curves(n)
    ha, hb = (np.cumsum(np.random.default_rng(s).normal(size=(201, 3)), axis=0) for s in (1, 2))
    rows = []
    threads_max = numba.get_num_threads()
    for threads in sorted({1, threads_max}):
        numba.set_num_threads(threads)
        t_big = best_time(lambda: linking_number(a, b), args.repeats)
        t_hair = best_time(lambda: linking_number(ha, hb, closed=False), max(args.repeats, 20))
        t_wr = best_time(lambda: writhe(a), args.repeats)
        rows.append((threads, n * n / t_big, t_big, t_hair * 1e6, t_wr))
    numba.set_num_threads(threads_max)
    print(f"Lk of the {n}-segment pair = {linking_number(a, b):.6f} (integer up to rounding)\n")
    print("| threads | Lk pairs/s | Lk 10k×10k [s] | 200×200 hair pair [µs] | writhe 10k [s] |")
    print("|--------:|-----------:|---------------:|-----------------------:|---------------:|")
    for threads, rate, t_big, t_hair, t_wr in rows:
        print(f"| {threads} | {rate:.3g} | {t_big:.3f} | {t_hair:.0f} | {t_wr:.3f} |")
    if len(rows) == 2:
        print(f"\nspeed-up {rows[1][0]} threads vs 1 (same run): {rows[1][1] / rows[0][1]:.2f}x")
    print(f"target ≥ 5e7 pairs/s: {'met' if rows[-1][1] >= 5e7 else 'NOT met'} ({rows[-1][1]:.3g})")


if __name__ == "__main__":
    main()
