"""Exploration probe: ``hairbrush repeat``'s study (six full strokes, every physics step checked) on HairBrush-v5's
wig fields with some replaced, before they become a version (docs/detangling.md, *HairBrush-v5*).

    python scripts/probe_repeat_fields.py WIG TAG FIELDS_JSON SEEDS [N_STROKES]
    # e.g. coily M3 '{"mass_scale": 3.0}' 0      -> runs/probe/M3_coily.csv, a summary table at the end
"""

import json
import sys
from pathlib import Path

from hairbrush_env.io import write_csv_rows
from hairbrush_env.physics import PHYSICS, PhysicsVersion
from hairbrush_env.scene import BrushingSim
from hairbrush_env.studies.repeated_strokes import COLUMNS, repeated_strokes, summary_markdown

wig, tag = sys.argv[1], sys.argv[2]
extra = json.loads(sys.argv[3])
seeds = [int(s) for s in sys.argv[4].split(",")]
n = int(sys.argv[5]) if len(sys.argv) > 5 else 6
ver = PhysicsVersion("candidate", brush=PHYSICS["v5"].brush, wig_fields={**PHYSICS["v5"].wig_fields, **extra})
out = Path(f"runs/probe/{tag}_{wig}.csv")
rows = []
with BrushingSim(ver.scene_config(wig)) as sim:
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
