"""Exploration probe: where each full stroke (b_l = 1, no abort) reads its peak under a physics version, which pairs
a tine parts at the insertion, and whether a rest between strokes changes the next one (docs/detangling.md,
*HairBrush-v5*: coily's second stroke).

    python scripts/probe_second_stroke.py WIG SEED [N_STROKES] [REST_S] [--physics v5]
    # e.g. coily 2 3          (three strokes, force along each pull)
    #      coily 2 2 2.0      (2 s rest with the brush out of the hair between strokes)
"""

import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import numpy as np

from hairbrush_env.physics import get_physics
from hairbrush_env.scene import BrushingSim

physics = get_physics("v5")
if "--physics" in sys.argv:
    i = sys.argv.index("--physics")
    physics = get_physics(sys.argv[i + 1])
    del sys.argv[i : i + 2]
wig, seed = sys.argv[1], int(sys.argv[2])
n = int(sys.argv[3]) if len(sys.argv) > 3 else 2
rest = float(sys.argv[4]) if len(sys.argv) > 4 else 0.0
sim = BrushingSim(physics.scene_config(wig))
sim.reset(seed)
np.set_printoptions(precision=2, suppress=True, linewidth=200)
for k in range(1, n + 1):
    rows = []

    def obs(s, sample, rows=rows):
        rows.append((float(s.brush_position()[2]), float(s.brush_position()[0]), sample.brushing_force(),
                     s.pairs_parted().copy()))  # fmt: skip

    sim.add_observer(obs)
    r = sim.stroke(1.0, abort_force=None)
    sim.remove_observer(obs)
    pull = [x for x in rows if x[1] > sim.depth_x - 1e-3]
    i = int(np.argmax([x[2] for x in pull]))
    print(f"stroke {k}: F {r.max_force:.2f} N, Σ|Lk| {sim.entanglement():.2f}; pairs parted at the first pull sample "
          f"{int(pull[0][3].sum())} of {pull[0][3].size}")  # fmt: skip
    print(f"   peak {1000 * (pull[0][0] - pull[i][0]):.0f} mm into the pull; force along it (every 2nd sample):",
          " ".join(f"{x[2]:.1f}" for x in pull[::2]))  # fmt: skip
    print("   pair Lk", sim.pair_links())
    if rest > 0 and k < n:
        for _ in range(round(rest / 0.1)):
            sim.step_velocity(0.0, 0.0, 0.1)  # brush parked out of the hair
        print(f"   rested {rest:g} s")
