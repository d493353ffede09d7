"""Exploration probe: what a stroke reads against how far below the roots its tines go in (docs/detangling.md,
*Why coily's sigmoid cycles below the roots*).

    python scripts/probe_band_entry.py WIG SEED B1,B2,... [--physics v10] [--climb] [--set FIELD=VALUE ...]
    # e.g. coily 2 0.88,0.91,0.93; --set root_run=1 changes a WigConfig field on top of the version's

One stroke per b_l, no abort, each from the pre-brushed wig SEED (with ``--climb``: one after another on the same
wig, as a policy's strokes are). Per stroke: the depth below the roots at which the tines go in, the first four
10 Hz load-cell samples of the pull (the abort of Algorithm 1 reads them in this order), the maximum read in the
hair and over the whole pull, and the fraction of the wig's entanglement left.
"""

import argparse
import dataclasses
import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from hairbrush_env import hair
from hairbrush_env.commands.checks import wig_field
from hairbrush_env.physics import PHYSICS, get_physics
from hairbrush_env.scene import BrushingSim

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("wig", choices=list(hair.PRESETS))
parser.add_argument("seed", type=int)
parser.add_argument("b_l", help="comma-separated normalized start heights")
parser.add_argument("--physics", choices=list(PHYSICS), default="v10")
parser.add_argument("--climb", action="store_true", help="brush the strokes one after another on one wig")
parser.add_argument(
    "--set", action="append", type=wig_field, default=[], help="WigConfig FIELD=VALUE (JSON value)"
)
args = parser.parse_args()
fractions = [float(b) for b in args.b_l.split(",")]
if not all(0.0 < b <= 1.0 for b in fractions):
    parser.error(f"b_l: every start height must be in (0, 1], got {args.b_l!r}")

physics = get_physics(args.physics)
fields = dict(args.set)
wig = dataclasses.replace(physics.wig(args.wig), **fields)
sim = BrushingSim(dataclasses.replace(physics.scene_config(args.wig), wig=wig))
print(f"{args.wig} under {args.physics}{''.join(f', {k}={v!r}' for k, v in fields.items())}: "
      f"hanging {wig.hanging_length * 1e3:.1f} mm")  # fmt: skip
sim.reset(args.seed)
start = sim.entanglement()
roots = float(sim.hair_curve_array()[:, 0, 2].max())  # the roots are fixed
for b in fractions:
    if not args.climb:
        sim.reset(args.seed)
    res = sim.stroke(b, abort_force=None)
    first = " ".join(f"{f:.1f}" for f in res.force_trace[1][:4])
    print(
        f"b_l {b:.2f}: in {1e3 * (roots - res.start_height):.1f} mm below the roots | first samples {first} N | "
        f"read {res.max_force:.2f} N, pull {res.pull_max_force:.2f} N | left {sim.entanglement() / start:.2f}",
        flush=True,
    )
sim.close()
