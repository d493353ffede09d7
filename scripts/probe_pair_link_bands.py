"""Exploration probe: where a wig pair's link sits, alone with the comb, before and after a climb from the free ends
(:mod:`hairbrush_env.studies.pair_on_comb`; docs/detangling.md, *What carries coily's first stroke from the roots*).

    python scripts/probe_pair_link_bands.py WIG [--seeds 0,1,2] [--physics v8]

For each pre-brushed seed: the pair's link in four quarters of its arc length from the roots (in the sense it was
built with, so reversed turns count negative), after the climb (b_l 0.33, 0.5, 0.67, 0.83), after the full stroke
that follows it (with its force), and after a fresh full stroke from the same seed (with its force).
"""

import argparse

import numpy as np

from hairbrush_env.physics import PHYSICS
from hairbrush_env.studies.pair_on_comb import PairOnComb
from hairbrush_env.topology import link_density, linking_number

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("wig")
parser.add_argument("--seeds", default="0,1,2")
parser.add_argument("--physics", choices=list(PHYSICS), default="v8")
args = parser.parse_args()


def quarters(pair: PairOnComb, sign: float) -> str:
    a, b = pair.curves()
    _, lam = link_density(a, b)
    link = sign * lam * np.linalg.norm(np.diff(0.5 * (a + b), axis=0), axis=1)  # per segment, sums to ± Lk
    parts = np.array_split(link, 4)
    return "[" + " ".join(f"{p.sum():+.2f}" for p in parts) + "]"


for seed in (int(s) for s in args.seeds.split(",")):
    pair = PairOnComb(args.wig, physics=args.physics, shake_seed=seed)
    sign = float(np.sign(linking_number(*pair.curves(), closed=False)))
    depths = [
        pair.start_depth(b_l) for b_l in (0.33, 0.5, 0.67, 0.83)
    ]  # from the hanging length before the climb
    out = [f"{args.wig} seed {seed}: start {quarters(pair, sign)}"]
    for depth in depths:
        pair.stroke(depth)
    out.append(f"after the climb {quarters(pair, sign)}")
    full = pair.stroke(PairOnComb.TOP)
    out.append(f"full {full.max_force:.2f} N → {quarters(pair, sign)}")
    fresh_pair = PairOnComb(args.wig, physics=args.physics, shake_seed=seed)
    fresh = fresh_pair.stroke(PairOnComb.TOP)
    out.append(f"| fresh full {fresh.max_force:.2f} N → {quarters(fresh_pair, sign)}")
    print("  ".join(out), flush=True)
