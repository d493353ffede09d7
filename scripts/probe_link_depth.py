"""Exploration probe: where the entwined link sits along the strands, before and after repeated full strokes.

    python scripts/probe_link_depth.py WIG SEED STROKES [--pairs] [--physics VERSION] [--scene JSON]
    # e.g. curly 0 6 --physics v2 --scene '{"scalp_clearance": 0.001}'

Prints, after each stroke (b_l = 1, no abort), Σ|Lk| of the entwined pairs split by depth below the roots
(``Entanglement.link_by_depth``: each pair's link density summed in its built-in sense) and, at the end, every
pair's signed link next to the link it was built with (docs/detangling.md, *What holds the link*). ``--pairs`` also
prints every pair's signed link by depth with its root positions, after each stroke (*Root orientation and splay*).
"""

import json
import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import numpy as np

from hairbrush_env.physics import get_physics
from hairbrush_env.scene import BrushingSim

wig, seed, n = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
per_pair_rows = "--pairs" in sys.argv[4:]
version = sys.argv[sys.argv.index("--physics") + 1] if "--physics" in sys.argv else "v0"
scene = json.loads(sys.argv[sys.argv.index("--scene") + 1]) if "--scene" in sys.argv else {}
sim = BrushingSim(get_physics(version).scene_config(wig, **scene))
sim.reset(seed)
print(f"roots z {sim.hair_top:.3f} m, highest stroke start {sim.start_height(1.0):.3f} m")
edges = np.array([0, 0.008, 0.02, 0.04, 0.06, 0.08, 0.12, 0.2, 1.0])  # depth below the roots [m]


def report(tag: str) -> None:
    meter = sim.entanglement_meter
    per_pair = meter.pair_link_by_depth(sim.data, edges)
    band = per_pair.sum(axis=0)
    entwined, made = meter.breakdown(sim.data)
    if per_pair_rows:
        for (i, j), mine in zip(meter.pairs, per_pair, strict=True):
            r = 1e3 * sim.layout.roots[[i, j]]
            print(
                f"  pair ({i},{j}) roots x {r[0, 0]:+.1f} {r[1, 0]:+.1f} y {r[0, 1]:+.1f} {r[1, 1]:+.1f} mm:",
                f"Lk (built-in sense) {mine.sum():+.2f};",
                " ".join(
                    f"{1e3 * edges[q]:.0f}-{1e3 * edges[q + 1]:.0f}:{mine[q]:+.2f}"
                    for q in range(len(mine))
                    if mine[q]
                ),
            )
    bands = " ".join(f"{1e3 * edges[q]:.0f}-{1e3 * edges[q + 1]:.0f}:{band[q]:.2f}" for q in range(len(band)))
    print(
        f"{tag}: Σ|Lk| entwined {entwined:.2f}, made between groups {made:.2f}; "
        f"built-in-sense link by depth below the roots [mm] {bands}",
        flush=True,
    )


report("pre-brushed")
for k in range(1, n + 1):
    res = sim.stroke(1.0, abort_force=None)
    report(f"stroke {k} (F_max {res.max_force:.1f} N)")
print("pair Lk now:    ", " ".join(f"{v:+.2f}" for v in sim.pair_links()))
print("pair Lk built:  ", " ".join(f"{v:+.2f}" for v in sim.layout.pair_link))
print("still entwined: ", sim.entanglement_meter.still_entwined(sim.data), "of", len(sim.layout.pairs))
