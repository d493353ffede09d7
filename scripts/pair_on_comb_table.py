"""One entwined pair of each curled preset, alone with three tines (:mod:`hairbrush_env.studies.pair_on_comb`):
a lone curl held by its root, the pair's fresh full stroke, and a climb from the free ends followed by two full
strokes (docs/detangling.md, *What carries coily's first stroke from the roots*).

    python scripts/pair_on_comb_table.py [--physics v8] [--wigs loose_curl,curly,tight_curl,coily] [--seeds 0,1,2]
    python scripts/pair_on_comb_table.py --speeds 0.05,0.2 --wigs curly,coily   # Fig. 3.8 for one pair

A stroke of b_l starts at ``PairOnComb.start_depth(b_l)``: 8 mm + (1 − b_l)(hanging length − 8 mm) below the roots
(b_l = 1: 8 mm, as the scene's full stroke). Each pair is shaken as the wig's pre-brushed preparation with each seed;
every cell is the mean over the seeds. Forces are 10 Hz means [N]; Lk is the pair's |Lk| after the stroke.
"""

import argparse
import time

import numpy as np

from hairbrush_env.physics import PHYSICS, get_physics
from hairbrush_env.studies.pair_on_comb import PairOnComb, peel_force

CLIMB = (0.33, 0.5, 0.67, 0.83)

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--physics", choices=list(PHYSICS), default="v8")
parser.add_argument("--wigs", default="loose_curl,curly,tight_curl,coily")
parser.add_argument("--seeds", default="0,1,2", help="pre-brushed preparation seeds")
parser.add_argument(
    "--speeds", default="", help="instead: the full and b_l 0.67 strokes at these pull speeds [m/s]"
)
args = parser.parse_args()
seeds = [int(x) for x in args.seeds.split(",")]


if args.speeds:
    speeds = [float(v) for v in args.speeds.split(",")]
    print(
        f"| wig ({args.physics}) | b_l | "
        + " | ".join(f"{v:g} m/s [N]" for v in speeds)
        + " | last / first |"
    )
    print("|---|---:|" + "---:|" * len(speeds) + "---:|")
    for name in args.wigs.split(","):
        for b_l in (1.0, 0.67):
            means = []
            for v in speeds:
                forces = []
                for seed in seeds:
                    pair = PairOnComb(name, physics=args.physics, shake_seed=seed, stroke_speed=v)
                    forces.append(pair.stroke(pair.start_depth(b_l)).max_force)
                means.append(float(np.mean(forces)))
            cells = " | ".join(f"{f:.3f}" for f in means)
            print(f"| {name} | {b_l:g} | {cells} | {100 * (means[-1] / means[0] - 1):+.0f} % |", flush=True)
    raise SystemExit(0)

print(
    f"| wig ({args.physics}) | E I κ₀² / 2 [N] | lone curl, full [N] | pair, fresh full [N] (Lk before → after) "
    f"| climb b_l {' / '.join(map(str, CLIMB))} [N] (Lk after) | full, full after the climb [N] (Lk after) | CPU s |"
)
print("|---|---:|---:|---|---|---|---:|")
for name in args.wigs.split(","):
    t0 = time.process_time()
    wig = get_physics(args.physics).scene_config(name).wig
    peel = peel_force(wig.curl_radius, wig.pitch, young=wig.young_modulus, strand_radius=wig.strand_radius)
    rows = []
    for seed in seeds:
        lone = (
            PairOnComb(name, physics=args.physics, lone=True, shake_seed=seed)
            .stroke(PairOnComb.TOP)
            .max_force
        )
        pair = PairOnComb(name, physics=args.physics, shake_seed=seed)
        lk0 = pair.link()
        fresh = pair.stroke(PairOnComb.TOP)
        pair = PairOnComb(name, physics=args.physics, shake_seed=seed)
        climb = [pair.stroke(pair.start_depth(b)) for b in CLIMB]
        after = [pair.stroke(PairOnComb.TOP) for _ in range(2)]
        rows.append([lone, fresh.max_force, lk0, fresh.link_after, *(c.max_force for c in climb),
                     climb[-1].link_after, after[0].max_force, after[1].max_force, after[1].link_after])  # fmt: skip
    m = np.mean(rows, axis=0)
    print(
        f"| {name} | {peel:.3f} | {m[0]:.3f} | {m[1]:.2f} ({m[2]:.2f} → {m[3]:.2f}) | "
        f"{' / '.join(f'{x:.2f}' for x in m[4:8])} ({m[8]:.2f}) | {m[9]:.2f}, {m[10]:.2f} ({m[11]:.2f}) | "
        f"{time.process_time() - t0:.0f} |",
        flush=True,
    )
