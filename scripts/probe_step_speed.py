"""Exploration probe: how fast the strands move in each physics step of a full stroke (SceneConfig.max_step_travel).

    python scripts/probe_step_speed.py WIG MASS_SCALE SEED [SCENE_FIELDS_JSON]
    # e.g. with the real-mass contact patch:
    PATCH='{"solimp": [0.99, 0.999, 1e-4, 0.5, 2], "armature": 1.0}' python scripts/probe_patched.py \\
        scripts/probe_step_speed.py curly 1 0

One full stroke (b_l = 1, no abort) from the pre-brushed wig. After every physics step: the fastest strand point's
speed (its largest coordinate change over the step / the step), which strand point it is (the free end or not) and
when in the stroke. Prints the share of steps above each speed and where along the strands the fastest points are,
i.e. how many steps a speed limit of a given travel per step would split (docs/detangling.md).
"""

import json
import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import numpy as np

from hairbrush_env import hair
from hairbrush_env.scene import BrushingSim, SceneConfig

wig, scale, seed = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
scene_fields = json.loads(sys.argv[4]) if len(sys.argv) > 4 else {}
sim = BrushingSim(SceneConfig(wig=hair.PRESETS[wig].replace(mass_scale=scale), **scene_fields))
sim.reset(seed)
state = {"prev": sim.hair_curve_array()}
speeds, points = [], []


def observe(s):
    cur = s.hair_curve_array()
    travel = np.abs(cur - state["prev"]).max(axis=2)  # (strands, points)
    state["prev"] = cur
    dt = s.model.opt.timestep
    i = int(np.argmax(travel))
    speeds.append(travel.flat[i] / dt)
    points.append(np.unravel_index(i, travel.shape)[1])


sim.add_step_observer(observe)
result = sim.stroke(1.0, abort_force=None)
v = np.asarray(speeds)
pts = np.asarray(points)
n_points = state["prev"].shape[1]
print(
    f"{wig} mass_scale {scale:g} seed {seed} {scene_fields}: {len(v)} steps, max force {result.max_force:.2f} N"
)
for limit in (0.4, 0.8, 1.6, 3.2):
    fast = v > limit
    tip = fast & (pts >= n_points - 3)
    print(
        f"  v > {limit:.1f} m/s: {fast.mean():6.1%} of steps ({tip.sum()} of {fast.sum()} at the last three points)",
        flush=True,
    )
quarters = " ".join(f"{q.mean():.0%}" for q in np.array_split(v > 0.8, 4))
print(f"  share of steps above 0.8 m/s in each quarter of the stroke: {quarters}")
print(
    f"  median {np.median(v):.3f} m/s, 99th percentile {np.percentile(v, 99):.2f} m/s, max {v.max():.2f} m/s"
)
