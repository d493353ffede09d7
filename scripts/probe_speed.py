"""Exploration probe: max force of one stroke at several pull speeds, for a given strand mass scale (Fig. 3.8).

    python scripts/probe_speed.py WIG MASS_SCALE B_L SPEED[,SPEED...] [SEEDS] [WIG_FIELDS_JSON] [SCENE_FIELDS_JSON] \
        [--physics vN]
    # e.g. curly 1 0.67 0.05,0.2 3 '{"damping": 0.0632}' '{"max_step_travel": 0.0008}'
    # or   curly 3 1 0.05,0.2 3 '{}' '{}' --physics v5      (HairBrush-v5's wig and brush, a third of the mass scale)
    # or   curly 10 1 0.05,0.2 3 '{}' '{"brush": {"hinged": false}}' --physics v8   (the version's comb, rigid tines)

One stroke per (seed, speed) from the pre-brushed wig, no abort; prints the max force per seed, the mean per speed and
how far into the pull each seed's max was sampled
(docs/detangling.md, *Correction*: is the mass-scaled stroke still quasi-static?). A "brush" dict in
SCENE_FIELDS_JSON holds BrushConfig fields over the version's comb.
"""

import dataclasses
import json
import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import numpy as np

from hairbrush_env.brush import get_brush
from hairbrush_env.physics import get_physics
from hairbrush_env.scene import BrushingSim, SceneConfig

physics = get_physics("v0")  # the defaults: no wig fields, the rigid comb
if "--physics" in sys.argv:
    i = sys.argv.index("--physics")
    physics = get_physics(sys.argv[i + 1])
    del sys.argv[i : i + 2]
wig, scale, b_l = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
speeds = [float(v) for v in sys.argv[4].split(",")]
n_seeds = int(sys.argv[5]) if len(sys.argv) > 5 else 3
extra = json.loads(sys.argv[6]) if len(sys.argv) > 6 else {}
scene_fields = json.loads(sys.argv[7]) if len(sys.argv) > 7 else {}
w = physics.wig(wig).replace(mass_scale=scale, **extra)  # the extra fields win over the version's
if isinstance(scene_fields.get("brush"), dict):
    scene_fields["brush"] = dataclasses.replace(get_brush(physics.brush), **scene_fields["brush"])
scene_fields.setdefault("brush", physics.brush)
sim = BrushingSim(SceneConfig(wig=w, **scene_fields))
for speed in speeds:
    forces, where = [], []
    for seed in range(n_seeds):
        sim.reset(seed)
        res = sim.stroke(b_l, speed=speed, abort_force=None)
        forces.append(res.max_force)
        t, f = res.force_trace
        where.append(1000.0 * speed * float(t[np.argmax(f)]) if f.size else np.nan)
        if res.diverged:
            print(f"seed {seed} at {speed:g} m/s diverged: its force is cut short", flush=True)
    print(
        f"{wig} mass_scale {scale:g} b_l {b_l:g} speed {speed:g} m/s: max force",
        " ".join(f"{f:.2f}" for f in forces),
        f"mean {np.mean(forces):.2f} ± {np.std(forces):.2f} N;",
        "at",
        " ".join(f"{w:.0f}" for w in where),
        "mm of pull",
        flush=True,
    )
