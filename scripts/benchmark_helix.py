"""Benchmark the double-helix combing study (prints a table).

    python scripts/benchmark_helix.py [--pr 18,24,48]

Wall time of one full combing run per P/r at the thesis defaults (`CombingSetup`), single-threaded (MuJoCo steps on
one core). Target (issue #7): one run at P/r = 18 in ≤ 60 s.
"""

from __future__ import annotations

import argparse
import time

from hairbrush_env.studies.double_helix import CombingSetup, run_combing


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--pr", default="18,24,48", help="comma-separated P/r values")
    a = p.parse_args()
    print("| P/r | wall [s] | f_max | D [m] | jammed |")
    print("|---:|---:|---:|---:|---|")
    for pr in (float(x) for x in a.pr.split(",")):
        t0 = time.perf_counter()
        r = run_combing(CombingSetup(P_over_r=pr))
        wall = time.perf_counter() - t0
        print(f"| {pr:g} | {wall:.1f} | {r.f_max:.2f} | {r.D:.4f} | {r.jammed} |", flush=True)
        if pr == 18:
            print(f"target ≤ 60 s at P/r = 18: {'met' if wall <= 60 else 'NOT met'}", flush=True)


if __name__ == "__main__":
    main()
