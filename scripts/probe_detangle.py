"""Exploration probe: repeated pull-through strokes with a custom wig and brush (docs/detangling.md).

    python scripts/probe_detangle.py NAME '{"wig": {"base": "curly", "cohesion": 12.5, ...WigConfig fields},
        "brush": "comb" or {...BrushConfig fields} or {"preset": "soft_comb", ...fields changed},
        "scene": {...SceneConfig fields},
        "strokes": 6, "seed": 0, "b_l": 1.0, "y": 0.0 or [y1, y2, ...], "iterations": 50, "physics": "v8"}'

"y": the brush's sideways offset [m], or offsets that the strokes cycle through. "iterations": the contact solver's
iteration cap (default ``rods.CHAIN_SOLVER_ITERATIONS``). "physics": start from that version's wig and comb instead of
the bare preset and the default comb (the "wig" fields and a "brush" dict then change those).

Writes runs/probe/NAME.jsonl, one line per stroke (hairbrush_env.studies.repeated_strokes rows).
"""

import dataclasses
import json
import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
from hairbrush_env import hair
from hairbrush_env.brush import BrushConfig, get_brush
from hairbrush_env.physics import get_physics
from hairbrush_env.scene import BrushingSim, SceneConfig
from hairbrush_env.studies.repeated_strokes import repeated_strokes

name, cfg = sys.argv[1], json.loads(sys.argv[2])
w = dict(cfg.get("wig", {}))
physics = get_physics(cfg["physics"]) if "physics" in cfg else None
base_name = w.pop("base", "curly")
base = physics.wig(base_name) if physics is not None else hair.PRESETS[base_name]
if "cohesion" in w:
    w["young"] = hair.wisp_young(w.get("strand_radius", base.strand_radius), cohesion=w.pop("cohesion"))
wig = base.replace(**w)
b = cfg.get("brush", physics.brush if physics is not None else "comb")
if isinstance(b, str):  # a preset name (the scene default "comb")
    brush = b
elif physics is not None and "preset" not in b:  # fields changed over the version's comb
    brush = dataclasses.replace(get_brush(physics.brush), **b)
elif "preset" in b:  # a preset with some fields changed: {"preset": "soft_comb", "friction": 0.15}
    brush = dataclasses.replace(get_brush(b["preset"]), **{k: v for k, v in b.items() if k != "preset"})
else:
    brush = BrushConfig(**b)
sc = SceneConfig(wig=wig, brush=brush, **cfg.get("scene", {}))
t0 = time.process_time()
sim = BrushingSim(sc)
if cfg.get("iterations"):
    sim.model.opt.iterations = int(cfg["iterations"])
print(
    f"{name}: edges {wig.n_edges} turns {wig.turns:.2f} hang {wig.hanging_length:.3f}",
    f"spacing {sim.layout.spacing:.4f} extent {sim.layout.extent} Lk {sim.layout.n_links:.2f}",
    flush=True,
)
out = f"runs/probe/{name}.jsonl"
os.makedirs(os.path.dirname(out), exist_ok=True)
with open(out, "w") as f:

    def rec(row):
        row = dict(row, wall=time.time())
        f.write(json.dumps(row) + "\n")
        f.flush()
        print(name, {k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}, flush=True)

    repeated_strokes(
        sim,
        seed=cfg.get("seed", 0),
        brush_length=cfg.get("b_l", 1.0),
        n_strokes=cfg.get("strokes", 6),
        on_stroke=rec,
        y=cfg.get("y", 0.0),
    )
print(name, "total CPU", time.process_time() - t0)
