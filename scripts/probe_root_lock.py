"""Exploration probe: a strand's root hinge angles over repeated full strokes (gimbal lock, docs/detangling.md).

    python scripts/probe_root_lock.py WIG SEED STRAND [STROKES]

WIG is a preset or held-out wig name, STRAND a strand body prefix such as ``hair14``. Prints the root's rest
(spring reference) angles, then per full stroke (b_l = 1, no abort) the largest |angle| of each root hinge and
whether the stroke diverged; on a divergence, MuJoCo's warnings and the angles of the last steps. The three root
hinges (bend1, twist, bend2) are an Euler sequence, singular where the twist reaches ±90°.
"""

import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import numpy as np

from hairbrush_env import hair
from hairbrush_env.scene import BrushingSim, SceneConfig

wig, seed, strand = sys.argv[1], int(sys.argv[2]), sys.argv[3]
n_strokes = int(sys.argv[4]) if len(sys.argv) > 4 else 3
sim = BrushingSim(SceneConfig(wig=hair.get_wig(wig)))
sim.reset(seed)
m = sim.model
adr = [m.jnt_qposadr[m.joint(f"{strand}_0_{label}").id] for label in ("bend1", "twist", "bend2")]
print(
    f"{wig} seed {seed} {strand}: rest angles (bend1, twist, bend2) [deg]",
    np.degrees(m.qpos_spring[adr]).round(1),
)
angles: list[np.ndarray] = []
sim.add_step_observer(lambda s: angles.append(np.degrees(s.data.qpos[adr])))
for k in range(n_strokes):
    angles.clear()
    res = sim.stroke(1.0, abort_force=None)
    a = np.array(angles)
    print(
        f"stroke {k + 1}: F_max {res.max_force:.2f} N, largest |angle| {np.abs(a).max(axis=0).round(1)},",
        f"diverged {res.diverged}",
    )
    if res.diverged:
        for i, w in enumerate(sim.data.warning):
            if w.number:
                print(f"  warning {i}: {w.number}x, last info {w.lastinfo}")
        print("  last angles", a[-3:].round(1).tolist())
        break
