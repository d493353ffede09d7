"""Exploration probe: does a full stroke's force converge in the edge count?

Fig. 3.7; docs/detangling.md, *HairBrush-v2*.

    python scripts/probe_edges.py OUT.jsonl WIGS EDGES_PER_TURN SEEDS [WIG_FIELDS_JSON]
    # e.g. runs/probes/edges.jsonl wavy,loose_curl,curly 8,12 0,1,2
    #      runs/probes/edges.jsonl loose_curl 8 0 '{"min_edges": 26}'

One full stroke (b_l = 1, no abort) per (edges per turn, wig, seed) under ``HairBrush-v2``'s physics with
``WigConfig.edges_per_turn`` set (and ``max_edges`` raised to 64, so no preset is capped), plus any other WigConfig
fields given. Each wig is shaken anew (a new edge count is a new pre-brushed wig). Appends one JSON line per stroke to
OUT (max force, entanglement left, CPU s) and skips strokes already there, so a rerun resumes.
"""

import json
import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from hairbrush_env.physics import PHYSICS, PhysicsVersion
from hairbrush_env.scene import BrushingSim

out, wigs = sys.argv[1], sys.argv[2].split(",")
per_turn = [int(v) for v in sys.argv[3].split(",")]
seeds = [int(v) for v in sys.argv[4].split(",")]
extra = json.loads(sys.argv[5]) if len(sys.argv) > 5 else {}
v2 = PHYSICS["v2"]
done = set()
if os.path.exists(out):
    with open(out) as f:
        done = {(r["wig"], r["edges_per_turn"], r["seed"]) for r in map(json.loads, f)}
os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
for ept in per_turn:
    physics = PhysicsVersion(
        "v2-edges", v2.brush, {**v2.wig_fields, "edges_per_turn": ept, "max_edges": 64, **extra}
    )
    for wig in wigs:
        for seed in seeds:
            if (wig, ept, seed) in done:
                continue
            sim = BrushingSim(physics.scene_config(wig))
            sim.reset(seed)
            start = sim.entanglement()
            cpu = time.process_time()
            res = sim.stroke(1.0, abort_force=None)
            row = {
                "wig": wig,
                "edges_per_turn": ept,
                "seed": seed,
                "extra": extra,
                "edges": sim.wig.n_edges,
                "max_force": res.max_force,
                "left": sim.entanglement() / start if start > 0.01 else None,  # straight hair has no link
                "cpu_s": time.process_time() - cpu,
                "diverged": res.diverged,
            }
            sim.close()
            with open(out, "a") as f:  # one line a stroke: an interrupt loses at most the stroke running
                f.write(json.dumps(row) + "\n")
            print(row, flush=True)
