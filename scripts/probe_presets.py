"""Exploration probe: the detangling design of docs/detangling.md (2 group rows, 40 mm spacing, rest_splay π/2, comb,
5 mm scalp clearance) applied to presets at cohesion κ. Usage: python scripts/probe_presets.py NAMES KAPPA [STROKES]."""

import math
import sys

from hairbrush_env import hair
from hairbrush_env.scene import BrushingSim, SceneConfig
from hairbrush_env.studies.repeated_strokes import repeated_strokes

kappa = float(sys.argv[2])
n = int(sys.argv[3]) if len(sys.argv) > 3 else 1
for name in sys.argv[1].split(","):
    base = hair.PRESETS[name]
    w = base.replace(
        young=hair.wisp_young(base.strand_radius, cohesion=kappa),
        min_spacing=0.04,
        group_rows=2,
        rest_splay=math.pi / 2 if base.curliness > 0 else 0.0,
    )
    sim = BrushingSim(SceneConfig(wig=w, brush="comb", scalp_clearance=0.005))
    rows = repeated_strokes(sim, seed=0, n_strokes=n)
    e0 = rows[0]["entanglement"]
    print(
        f"{name} k{kappa} edges {w.n_edges} start {e0:.1f} (entw {rows[0]['entwined']:.1f} made {rows[0]['made']:.1f})",
        "F",
        " ".join(f"{r['max_force']:.1f}" for r in rows[1:]),
        "left",
        " ".join(f"{r['entanglement'] / max(e0, 1e-9):.2f}" for r in rows[1:]),
        "X",
        sum(r["crossings"] for r in rows[1:]),
        "hh",
        f"{min(r['min_hair_hair'] for r in rows[1:]):.2f}",
        "cpu",
        " ".join(f"{r['cpu_s']:.0f}" for r in rows[1:]),
        flush=True,
    )
