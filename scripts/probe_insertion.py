"""Exploration probe: does the comb go in *between* each pair's strands, against the stroke's start height?

    python scripts/probe_insertion.py WIG SEED B_L[,B_L...] [--physics VERSION] [--scene JSON]
    # e.g. curly 0 0.8,0.9,1 --physics v3;  coily 0 1 --physics v4 --scene '{"approach_speed": 0.1}'

A comb's tines run along x (into the curtain) and part a pair only if they enter with one strand on each side. An
entwined pair is a double helix about its axis, and a tine through that axis meets the two strands side by side
(parted) or one behind the other (head on) depending on the helix phase at the start height. For each b_l, one
stroke (no abort) from the pre-brushed wig ``SEED``; at two moments it asks ``BrushingSim.pairs_parted`` which pairs
have a tine between their strands at the tines' height:

- *before*: the brush at the retract plane at the start height, the hair as the insertion will meet it;
- *inserted*: the first physics step of the pull, after the tines went in.

Prints per b_l: the tines' depth below the roots, pairs parted before / after insertion (of all pairs), the stroke's
maximum force and the fraction of the entanglement left (docs/detangling.md, *Where the comb goes in*).
"""

import json
import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
from hairbrush_env.physics import get_physics
from hairbrush_env.scene import BrushingSim

wig, seed = sys.argv[1], int(sys.argv[2])
lengths = [float(v) for v in sys.argv[3].split(",")]
version = sys.argv[sys.argv.index("--physics") + 1] if "--physics" in sys.argv else "v0"
scene = json.loads(sys.argv[sys.argv.index("--scene") + 1]) if "--scene" in sys.argv else {}
sim = BrushingSim(get_physics(version).scene_config(wig, **scene))
pairs = sim.entanglement_meter.pairs

for b_l in lengths:
    sim.reset(seed)
    z0 = sim.start_height(b_l)
    seen: dict[str, list[bool]] = {}

    def observe(s: BrushingSim, seen: dict = seen, z0: float = z0) -> None:
        tcp = s.brush_position()
        if "inserted" in seen:
            return
        if tcp[0] < s.retract_x + 1e-3 and abs(tcp[2] - z0) < 2e-3:
            seen["before"] = list(s.pairs_parted())  # the last such step wins
        elif abs(tcp[0] - s.depth_x) < 2e-3 and tcp[2] < z0 - 1e-3:
            seen["inserted"] = list(s.pairs_parted())

    start = sim.entanglement()
    sim.add_step_observer(observe)
    res = sim.stroke(b_l, abort_force=None)
    sim.remove_step_observer(observe)
    before, inserted = seen.get("before", []), seen.get("inserted", [])
    print(
        f"{wig} seed {seed} b_l {b_l:.3f}: tines {1e3 * (sim.hair_top - z0):5.1f} mm below the roots, "
        f"parted before {sum(before):2d} / inserted {sum(inserted):2d} of {len(pairs)} "
        f"(not parted after insertion: {[k for k, ok in enumerate(inserted) if not ok]}), "
        f"F_max {res.max_force:5.2f} N, left {sim.entanglement() / start:.2f}",
        flush=True,
    )
