"""Benchmark the double-helix combing study (prints a table).

    python scripts/benchmark_helix.py [--pr 18,24,48] [--timestep 0.001 --contact-timeconst 0.002]

Wall time of one full combing run per P/r at the thesis defaults (`CombingSetup`), single-threaded (MuJoCo steps on
one core), with the topology check on (strand–strand / strand–tine passages are listed). Target (issue #7): one run
at P/r = 18 in ≤ 60 s at the defaults.
"""

from __future__ import annotations

import argparse
import time

from hairbrush_env.studies.double_helix import CombingSetup, run_combing


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--pr", default="18,24,48", help="comma-separated P/r values")
    p.add_argument("--timestep", type=float, default=CombingSetup.timestep, help="simulation step [s]")
    p.add_argument(
        "--contact-timeconst",
        type=float,
        default=CombingSetup.contact_timeconst,
        help="contact solref[0] [s]",
    )
    a = p.parse_args()
    print(f"timestep {a.timestep * 1e3:g} ms, contact time constant {a.contact_timeconst * 1e3:g} ms")
    print("| P/r | wall [s] | topology check | f_max | D [m] | jammed | passages (strand/tine) |")
    print("|---:|---:|---:|---:|---:|---|---|")
    for pr in (float(x) for x in a.pr.split(",")):
        t0 = time.perf_counter()
        r = run_combing(CombingSetup(P_over_r=pr, timestep=a.timestep, contact_timeconst=a.contact_timeconst))
        wall = time.perf_counter() - t0
        print(
            f"| {pr:g} | {wall:.1f} | {100 * r.check_time / wall:.0f} % | {r.f_max:.2f} | {r.D:.4f} | {r.jammed} | "
            f"{r.strand_crossings}/{r.tine_crossings} |",
            flush=True,
        )
        if pr == 18:
            print(f"target ≤ 60 s at P/r = 18: {'met' if wall <= 60 else 'NOT met'}", flush=True)


if __name__ == "__main__":
    main()
