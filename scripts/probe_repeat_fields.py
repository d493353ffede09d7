"""Exploration probe: ``hairbrush repeat``'s study (six full strokes, every physics step checked) on a version's wig
fields with some replaced, before they become a version (docs/detangling.md, *HairBrush-v5*).

    python scripts/probe_repeat_fields.py WIG TAG FIELDS_JSON SEEDS [N_STROKES] [--physics vN] [--brush JSON]
        [--scene JSON]
    # e.g. coily M3 '{"mass_scale": 3.0}' 0      -> runs/probe/M3_coily.csv, a summary table at the end
    # or   curly M3 '{"mass_scale": 3.0}' 0,1 6 --physics v8 --brush '{"damping": 4e-4}'

``--physics``: the version whose wig (preset fields included) and comb are the base (default v5); FIELDS_JSON is
set over that wig.
``--brush``: BrushConfig fields changed over that comb. ``--scene``: SceneConfig fields (e.g. ``contact_timestep``).
"""

import dataclasses
import json
import sys
from pathlib import Path

from hairbrush_env.brush import get_brush
from hairbrush_env.io import write_csv_rows
from hairbrush_env.physics import PHYSICS
from hairbrush_env.scene import BrushingSim
from hairbrush_env.studies.repeated_strokes import COLUMNS, repeated_strokes, summary_markdown

base, brush_fields, scene_fields = "v5", {}, {}
for flag in ("--physics", "--brush", "--scene"):
    if flag in sys.argv:
        i = sys.argv.index(flag)
        if flag == "--physics":
            base = sys.argv[i + 1]
        elif flag == "--brush":
            brush_fields = json.loads(sys.argv[i + 1])
        else:
            scene_fields = json.loads(sys.argv[i + 1])
        del sys.argv[i : i + 2]
wig, tag = sys.argv[1], sys.argv[2]
extra = json.loads(sys.argv[3])
seeds = [int(s) for s in sys.argv[4].split(",")]
n = int(sys.argv[5]) if len(sys.argv) > 5 else 6
out = Path(f"runs/probe/{tag}_{wig}.csv")
rows = []
config = PHYSICS[base].scene_config(wig, **scene_fields)
# FIELDS win over the version's fields, a preset's own (e.g. v7's curl radii) included, as in probe_speed.py
config = dataclasses.replace(
    config,
    wig=config.wig.replace(**extra),
    brush=dataclasses.replace(get_brush(config.brush), **brush_fields),
)
with BrushingSim(config) as sim:
    for seed in seeds:

        def rec(r, seed=seed):
            rows.append(dict(r, wig=wig, seed=seed, brush_length=1.0))
            write_csv_rows(out, rows, COLUMNS)
            print(
                wig,
                seed,
                r["stroke"],
                f"{r['max_force']:.2f}",
                f"{r['entanglement']:.2f}",
                r["crossings"],
                f"{r['cpu_s']:.1f}",
                flush=True,
            )

        repeated_strokes(sim, seed=seed, brush_length=1.0, n_strokes=n, on_stroke=rec)
print(summary_markdown(rows))
