"""Exploration probe: single strokes (Fig. 3.7) under a candidate physics (docs/detangling.md, *Tines that bend on*).

    python scripts/probe_candidate_strokes.py OUT.jsonl '{"self_collision": true, "friction": 0.15}' soft_comb \
        straight,wavy,loose_curl,curly,coily 0.33,0.67 0,1,2

WIG_FIELDS_JSON: WigConfig fields applied to every preset; BRUSH: a preset name. One scene per wig; from each seed's
pre-brushed state (prepared once, kept in memory) one stroke per b_l, no abort. Appends one JSON line per stroke
(wig, seed, b_l, max_force, cpu_s) to OUT.jsonl as it goes.
"""

import json
import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
from hairbrush_env.hair import get_wig
from hairbrush_env.scene import BrushingSim, SceneConfig

out, fields, brush = sys.argv[1], json.loads(sys.argv[2]), sys.argv[3]
wigs = sys.argv[4].split(",")
lengths = [float(v) for v in sys.argv[5].split(",")]
seeds = [int(v) for v in sys.argv[6].split(",")]
with open(out, "a") as f:
    for wig in wigs:
        with BrushingSim(SceneConfig(wig=get_wig(wig).replace(**fields), brush=brush)) as sim:
            for seed in seeds:
                for b_l in lengths:
                    sim.reset(seed)
                    t0 = time.process_time()
                    res = sim.stroke(b_l, abort_force=None)
                    row = dict(wig=wig, seed=seed, b_l=b_l, max_force=res.max_force, cpu_s=time.process_time() - t0,
                               diverged=res.diverged)  # fmt: skip
                    f.write(json.dumps(row) + "\n")
                    f.flush()
                    print(row, flush=True)
