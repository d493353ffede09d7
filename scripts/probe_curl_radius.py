"""Exploration probe: a stroke's maximum force against the curl radius R of a preset at its own R/P, and where the
full stroke's force peaks (docs/detangling.md, *HairBrush-v7*: the full-stroke force follows the curls' curvature).

    python scripts/probe_curl_radius.py WIG R [--seeds 0,1] [--brush-lengths 1,0.67,0.33] [--physics v6]
                                        [--max-edges 48] [--trace]
    # e.g. curly 0.010;  coily 0.009 --max-edges 48;  curly 0.012 --seeds 0 --brush-lengths 1 --trace

Prints one line per stroke (from the pre-brushed wig of each seed, no abort): max force, entanglement before → after,
CPU s. ``--trace`` prints the load-cell samples around the peak with the brush's depth below the roots, the largest
tine deflection and the largest arm actuator force as a fraction of its range.
"""

import argparse
import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import numpy as np

from hairbrush_env import hair
from hairbrush_env.physics import PHYSICS, get_physics
from hairbrush_env.scene import BrushingSim


def _floats(text: str) -> list[float]:
    return [float(x) for x in text.split(",") if x.strip()]


parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("wig", choices=list(hair.PRESETS))
parser.add_argument("radius", type=float, help="curl radius R [m] (R/P stays the preset's)")
parser.add_argument("--seeds", default="0,1")
parser.add_argument("--brush-lengths", default="1,0.67,0.33")
parser.add_argument("--physics", choices=list(PHYSICS), default="v6")
parser.add_argument(
    "--max-edges", type=int, default=None, help="WigConfig.max_edges (8 edges per turn needs it)"
)
parser.add_argument("--trace", action="store_true", help="print the samples around each stroke's peak")
args = parser.parse_args()
extra = {} if args.max_edges is None else {"max_edges": args.max_edges}
wig = hair.PRESETS[args.wig].replace(
    curl_radius=args.radius, name=f"{args.wig}_R{1000 * args.radius:.1f}", **extra
)
sim = BrushingSim(get_physics(args.physics).scene_config(wig))
m, d = sim.model, sim.data
cfg = sim.config.wig_config
print(f"{wig.name} under {args.physics}: R/P {cfg.curliness}, {cfg.n_edges} edges ({cfg.turns:.2f} turns), "
      f"hanging {sim.hanging_length:.3f} m", flush=True)  # fmt: skip
tines = [j for j in range(m.njnt) if "tine" in m.joint(j).name]
tine_q = m.jnt_qposadr[tines]
span = np.maximum(np.abs(m.actuator_forcerange[:, 1]), 1e-9)
for seed in [int(s) for s in args.seeds.split(",")]:
    for b_l in _floats(args.brush_lengths):
        sim.reset(seed)
        top = float(sim.hair_curve_array()[..., 2].max())
        rows: list[tuple[float, float, float, float, float]] = []

        def observe(s: BrushingSim, sample, rows=rows, top=top) -> None:
            bend = float(np.abs(d.qpos[tine_q]).max()) if tines else 0.0
            rows.append((d.time, sample.brushing_force(), top - s.brush_position()[2], bend,
                         float(np.max(np.abs(d.actuator_force) / span))))  # fmt: skip

        sim.add_observer(observe)
        e0 = sim.entanglement()
        t0 = time.process_time()
        res = sim.stroke(b_l, abort_force=None, rng=np.random.default_rng(seed))
        cpu = time.process_time() - t0
        sim.remove_observer(observe)
        print(f"  seed {seed} b_l {b_l}: F_max {res.max_force:.2f} N, entanglement {e0:.1f} -> "
              f"{sim.entanglement():.1f}, diverged {res.diverged}, {cpu:.0f} CPU s", flush=True)  # fmt: skip
        if args.trace and rows:
            r = np.array(rows)
            peak = int(np.argmax(r[:, 1]))
            for k in range(max(0, peak - 4), min(len(r), peak + 4)):
                t, f, depth, bend, act = r[k]
                print(f"    t {t:6.2f} s  F {f:6.2f} N  brush {1e3 * depth:5.1f} mm below the roots  "
                      f"tine {bend:.2f} rad  arm {act:.2f} of range" + ("  <- peak" if k == peak else ""))  # fmt: skip
sim.close()
