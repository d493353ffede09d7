"""Exploration probe: what carries a stroke's maximum — which strands the tines hold there, on which edges, and how far
below their rest free ends those strands have been dragged (docs/detangling.md, *HairBrush-v9*).

    python scripts/probe_stroke_peak.py WIG B_L SEEDS [--physics vN] [--climb B1,B2,...]   # e.g. curly 0.33 0,1,2

One stroke per seed from the pre-brushed wig, no abort (with ``--climb``, after strokes from those b_l first, e.g. a
sigmoid episode's ``brush_length``s from ``hairbrush rollout --json``; "rest" is then the wig before the climb). At
each 10 Hz load-cell sample it sums the normal contact force of the tines on every strand; at the sample of the
maximum it prints the tines' depth below the roots, the four strands they press hardest (force, edges touched counted
from the root, free end and lowest point against the strand's rest ones) and how many strands the tines touch; then
the force profile over the pull (depth: N) and the maximum read while the brush is above the bottom of the hair.
Only samples with the comb at its brushing depth count (the pull, not the approach or the backing out).
"""

import argparse
import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import mujoco
import numpy as np

from hairbrush_env import hair
from hairbrush_env.physics import PHYSICS, get_physics
from hairbrush_env.scene import BrushingSim
from hairbrush_env.scene_build import SCENE_TINE_PREFIX

_AT_DEPTH = 0.003  # [m] how near its brushing depth the comb counts as pulling

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("wig", choices=list(hair.PRESETS))
parser.add_argument("b_l", type=float)
parser.add_argument("seeds", help="comma-separated seeds")
parser.add_argument("--physics", choices=list(PHYSICS), default="v9")
parser.add_argument("--climb", default="", help="comma-separated b_l of strokes brushed first (no abort)")
args = parser.parse_args()

sim = BrushingSim(get_physics(args.physics).scene_config(args.wig))
m = sim.model
tines = {g for g in range(m.ngeom) if m.geom(g).name.startswith(SCENE_TINE_PREFIX)}
strand_edge = {}  # hair geom -> (strand, edge counted from the root)
for strand, view in enumerate(sim.entanglement_meter.views):
    for edge, body in enumerate(view.bodies):
        for g in np.flatnonzero(m.geom_bodyid == body):
            strand_edge[int(g)] = (strand, edge)
n_strands = sim.wig.n_strands
f6 = np.zeros(6)

for seed in (int(s) for s in args.seeds.split(",")):
    sim.reset(seed)
    rest = sim.hair_curve_array()
    rest_end, rest_low = rest[:, -1, 2], rest[..., 2].min(axis=1)
    roots_z = float(rest[:, 0, 2].max())
    climb = [sim.stroke(float(b), abort_force=None).max_force for b in args.climb.split(",") if b]
    if climb:
        print(
            f"climb ({len(climb)} strokes):",
            " ".join(f"{f:.1f}" for f in climb),
            f"N; entanglement {sim.entanglement():.2f}",
        )
    samples = []

    def observe(s: BrushingSim, sample, samples: list = samples) -> None:
        d = s.data
        per, edges = np.zeros(n_strands), [set() for _ in range(n_strands)]
        for i in range(d.ncon):
            g1, g2 = (int(g) for g in d.contact[i].geom)
            if (g1 in tines) == (g2 in tines):
                continue
            h = g2 if g1 in tines else g1
            if h not in strand_edge:
                continue
            mujoco.mj_contactForce(m, d, i, f6)
            strand, edge = strand_edge[h]
            per[strand] += f6[0]
            edges[strand].add(edge)
        curves = s.hair_curve_array()
        tcp = s.brush_position()
        if abs(float(tcp[0]) - s.depth_x) < _AT_DEPTH:  # the pull: not the approach, insertion or backing out
            samples.append((sample.brushing_force(), float(tcp[2]), per, edges, curves))

    sim.add_observer(observe)
    res = sim.stroke(args.b_l, abort_force=None)
    sim.remove_observer(observe)
    f, z, per, edges, curves = samples[int(np.argmax([x[0] for x in samples]))]
    print(
        f"{args.wig} seed {seed} b_l {args.b_l} ({args.physics}): max {res.max_force:.2f} N with the tines "
        f"{1000 * (roots_z - z):.0f} mm below the roots (rest free ends {1000 * (roots_z - rest_end.max()):.0f}–"
        f"{1000 * (roots_z - rest_end.min()):.0f} mm); the tines touch {int((per > 0).sum())} strands, "
        f"{per.sum():.2f} N normal force in all"
    )
    for s in np.argsort(per)[::-1][:4]:
        if per[s] <= 0:
            break
        print(
            f"  strand {s}: {per[s]:.2f} N on edges {sorted(edges[s])} of {sim.wig.n_edges}; free end "
            f"{1000 * (curves[s, -1, 2] - rest_end[s]):+.0f} mm, lowest point "
            f"{1000 * (curves[s, :, 2].min() - rest_low[s]):+.0f} mm from rest"
        )
    print(
        "  profile (mm below the roots: N):",
        " ".join(f"{1000 * (roots_z - x[1]):.0f}: {x[0]:.1f}" for x in samples[::3]),
    )
    # Algorithm 1 collects its f only while the brush is above the bottom of the hair (the lowest rest free end)
    inside = [x[0] for x in samples if x[1] >= sim.hair_bottom]
    print(f"  max while the brush is above the bottom of the hair: {max(inside, default=0.0):.2f} N")
