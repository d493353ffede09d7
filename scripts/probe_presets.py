"""Exploration probe: the curtain design of docs/detangling.md applied to presets (one group row, 40 mm spacing,
rest_splay π/2, 23 rigid 60 mm tines at 20 mm, 5 mm scalp clearance, pulled through to z = 0.4 m).

    python scripts/probe_presets.py NAMES '{"kappa": 12.5, "hang": null, "strokes": 2, "seed": 0,
        "wig": {...WigConfig fields}, "brush": {...}, "scene": {...}}'

``hang`` [m] rescales every curled preset's arc length to that hanging length (null keeps the preset's). One line
per preset; with ``"out"`` each stroke row is also appended to that JSONL file.
"""

import json
import math
import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
from hairbrush_env import hair
from hairbrush_env.brush import BrushConfig
from hairbrush_env.scene import BrushingSim, SceneConfig
from hairbrush_env.studies.repeated_strokes import repeated_strokes

cfg = json.loads(sys.argv[2]) if len(sys.argv) > 2 else {}
kappa = cfg.get("kappa", 12.5)
for name in sys.argv[1].split(","):
    base = hair.PRESETS[name]
    w = dict(
        min_spacing=0.04,
        group_rows=1,
        rest_splay=math.pi / 2 if base.curliness > 0 else 0.0,
    )
    if cfg.get("hang") and base.curliness > 0:
        w["length"] = cfg["hang"] * math.sqrt(1 + (2 * math.pi * base.curliness) ** 2)
    w.update(cfg.get("wig", {}))
    w["young"] = hair.wisp_young(w.get("strand_radius", base.strand_radius), cohesion=kappa)
    wig = base.replace(**w)
    brush = BrushConfig(
        **{
            "rows": 1,
            "columns": 23,
            "column_pitch": 0.02,
            "tine_length": 0.06,
            "hinged": False,
            **cfg.get("brush", {}),
        }
    )
    scene = {"scalp_clearance": 0.005, "pull_floor_z": 0.4, **cfg.get("scene", {})}
    sim = BrushingSim(SceneConfig(wig=wig, brush=brush, **scene))
    if cfg.get("iterations"):
        sim.model.opt.iterations = int(cfg["iterations"])
    rows = repeated_strokes(
        sim, seed=cfg.get("seed", 0), n_strokes=cfg.get("strokes", 2), brush_length=cfg.get("b_l", 1.0)
    )
    if cfg.get("out"):
        with open(cfg["out"], "a") as f:
            for r in rows:
                f.write(json.dumps(dict(r, wig=name, cfg=cfg)) + "\n")
    e0 = rows[0]["entanglement"]
    print(
        f"{name} k{kappa} seed {cfg.get('seed', 0)} edges {wig.n_edges} turns {wig.turns:.2f}"
        f" hang {wig.hanging_length:.3f} start {e0:.1f} (entw {rows[0]['entwined']:.1f} made {rows[0]['made']:.1f})",
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
