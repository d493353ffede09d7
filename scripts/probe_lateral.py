"""Exploration probe: repeated full strokes whose sideways offset cycles (docs/detangling.md).

    python scripts/probe_lateral.py NAME WIG SEED STROKES Y1,Y2,...   # e.g. L10 curly 0 6 0,0.01

Stroke k is pulled at ``y = Y[k mod len(Y)]`` (``BrushingSim.stroke(y=...)``); prints per stroke the maximum force,
the entanglement left, the entwined pairs still wound and the pass-through check, and writes runs/probe/NAME.jsonl.
"""

import json
import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
from hairbrush_env.pass_through import PassThroughMonitor
from hairbrush_env.scene import BrushingSim, SceneConfig

name, wig, seed, n = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
ys = [float(v) for v in sys.argv[5].split(",")]
sim = BrushingSim(SceneConfig(wig=wig))
sim.reset(seed)
e0 = sim.entanglement()
os.makedirs("runs/probe", exist_ok=True)
with open(f"runs/probe/{name}.jsonl", "w") as f:
    for k in range(n):
        mon = PassThroughMonitor(sim)
        t0 = time.process_time()
        res = sim.stroke(1.0, abort_force=None, y=ys[k % len(ys)])
        mon.detach()
        row = dict(stroke=k + 1, y=ys[k % len(ys)], max_force=res.max_force, left=sim.entanglement() / e0,
                   still_entwined=sim.entanglement_meter.still_entwined(sim.data), crossings=len(mon.crossings),
                   min_hair_hair=mon.hair_hair_fraction, cpu_s=time.process_time() - t0,
                   diverged=res.diverged)  # fmt: skip
        print(name, row, flush=True)
        f.write(json.dumps(row) + "\n")
        f.flush()
        if res.diverged:
            break
