"""Exploration probe: does working up from the free ends lower the force of the first full stroke?

    python scripts/probe_climb.py WIG SEED [--physics VERSION] [--climb 0.33,0.5,0.67,0.83]

On the pre-brushed wig of SEED, one full stroke (b_l = 1, no abort) fresh; then, from the same state again, the
climb's strokes (no abort) followed by two full strokes. Prints every stroke's maximum force, the entwined Σ|Lk| left
and how much of it lies above the climb's highest start (which only a full stroke combs), then one summary line
(docs/detangling.md, *Why coily's sigmoid runs into the stroke cap*).
"""

import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import numpy as np

from hairbrush_env.physics import get_physics
from hairbrush_env.scene import BrushingSim

wig, seed = sys.argv[1], int(sys.argv[2])
version = sys.argv[sys.argv.index("--physics") + 1] if "--physics" in sys.argv else "v8"
climb = (
    [float(b) for b in sys.argv[sys.argv.index("--climb") + 1].split(",")]
    if "--climb" in sys.argv
    else [0.33, 0.5, 0.67, 0.83]
)
sim = BrushingSim(get_physics(version).scene_config(wig))
top_depth = sim.hair_top - sim.start_height(max(climb))  # depth of the climb's highest start below the roots
edges = np.array([0.0, top_depth, 1.0])


def link_state() -> tuple[float, float]:
    meter = sim.entanglement_meter
    entwined, _ = meter.breakdown(sim.data)
    above = float(np.abs(meter.pair_link_by_depth(sim.data, edges)[:, 0]).sum())
    return entwined, above


def stroke(tag: str, b_l: float) -> float:
    res = sim.stroke(b_l, abort_force=None)
    entwined, above = link_state()
    print(
        f"{wig} seed {seed} {tag} b_l {b_l:.2f}: F_max {res.max_force:.2f} N, entwined {entwined:.2f}, "
        f"above {1e3 * top_depth:.0f} mm {above:.2f}",
        flush=True,
    )
    return res.max_force


sim.reset(seed)
e0, above0 = link_state()
print(
    f"{wig} seed {seed} ({version}): entwined {e0:.2f}, above {1e3 * top_depth:.0f} mm {above0:.2f}",
    flush=True,
)
fresh = stroke("fresh full", 1.0)
sim.reset(seed)
climbed = [stroke("climb", b) for b in climb]
after = [stroke("after climb", 1.0) for _ in range(2)]
print(
    f"SUMMARY {wig} seed {seed}: fresh full {fresh:.2f} N | climb {' '.join(f'{f:.2f}' for f in climbed)} | "
    f"full after climb {after[0]:.2f}, {after[1]:.2f} N",
    flush=True,
)
sim.close()
