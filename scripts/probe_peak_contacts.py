"""Exploration probe: what carries the brush force at each full stroke's peak — which pairs press on the tines, how
high on the strands, and how hard the strands press on each other (within a pair, between pairs) — under a physics
version (docs/detangling.md, *HairBrush-v5*: coily's second stroke).

    python scripts/probe_peak_contacts.py WIG SEED [N_STROKES] [--physics v5] [--y Y] [--climb B_L,...]
    # e.g. coily 2 2;  coily 0 2 --y 0.01   (every stroke with the comb moved 10 mm along the curtain)
    # coily 0 1 --physics v8 --climb 0.33,0.5,0.67,0.83   (the full stroke after a climb from the free ends)

``--climb`` brushes those strokes (no abort) first and prints each pair's entwined link above the climb's highest
start before the analysed full strokes (docs/detangling.md, *Why coily's sigmoid runs into the stroke cap*).
"""

import argparse
import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import mujoco
import numpy as np

from hairbrush_env.physics import PHYSICS, get_physics
from hairbrush_env.scene import BrushingSim

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("wig")
parser.add_argument("seed", type=int)
parser.add_argument("n_strokes", type=int, nargs="?", default=2)
parser.add_argument("--physics", choices=list(PHYSICS), default="v5")
parser.add_argument("--y", type=float, default=0.0, help="comb offset along the curtain [m] for every stroke")
parser.add_argument(
    "--climb", default="", help="comma-separated b_l of strokes brushed before the analysed ones"
)
args = parser.parse_args()
physics, wig, seed, n, y = get_physics(args.physics), args.wig, args.seed, args.n_strokes, args.y
sim = BrushingSim(physics.scene_config(wig))
sim.reset(seed)
m = sim.model
strand_of_body = np.full(m.nbody, -1)
for s, view in enumerate(sim.entanglement_meter.views):
    strand_of_body[view.bodies] = s
pairs = np.asarray(sim.entanglement_meter.pairs)
pair_of_strand = np.full(len(sim.entanglement_meter.views), -1)
for p, (a, b) in enumerate(pairs):
    pair_of_strand[[a, b]] = p
tine = np.zeros(m.ngeom, bool)
tine[sim._bristle_geoms] = True
roots_z = float(np.mean([sim.data.xpos[v.bodies[0], 2] for v in sim.entanglement_meter.views]))


def snapshot(s: BrushingSim):
    d = s.data
    f6 = np.zeros(6)
    per_pair_tine = np.zeros(len(pairs))
    depth_w = np.zeros(len(pairs))
    within = np.zeros(len(pairs))
    between = 0.0
    for i in range(d.ncon):
        c = d.contact[i]
        g1, g2 = c.geom1, c.geom2
        b1, b2 = m.geom_bodyid[g1], m.geom_bodyid[g2]
        mujoco.mj_contactForce(m, d, i, f6)
        fw = c.frame.reshape(3, 3).T @ f6[:3]  # world force on geom2 from geom1
        mag = float(np.linalg.norm(fw))
        s1, s2 = strand_of_body[b1], strand_of_body[b2]
        if tine[g1] or tine[g2]:
            st = s2 if tine[g1] else s1
            if st >= 0 and pair_of_strand[st] >= 0:
                p = pair_of_strand[st]
                per_pair_tine[p] += abs(fw[2])
                depth_w[p] += abs(fw[2]) * (roots_z - c.pos[2])
        elif s1 >= 0 and s2 >= 0 and s1 != s2:
            if pair_of_strand[s1] == pair_of_strand[s2] and pair_of_strand[s1] >= 0:
                within[pair_of_strand[s1]] += mag
            else:
                between += mag
    depth = np.where(per_pair_tine > 0, depth_w / np.maximum(per_pair_tine, 1e-12), np.nan)
    return per_pair_tine, depth, within, between


def pair_geometry(s: BrushingSim) -> None:
    """Where the two strands of each pair hang (upper half of each strand, by arc): the offset of strand A's centroid
    from strand B's [mm] (x along the tines, y across them), and each strand's y-span about its group axis (midway
    between the roots) [mm], which tells which tines lie inside its coils."""
    curves = s.hair_curves()
    offsets, spans = [], []
    for a, b in pairs:
        axis_y = 0.5 * (curves[a][0, 1] + curves[b][0, 1]) + y  # about the comb's tine through the group axis
        top = [c[: len(c) // 2] for c in (curves[a], curves[b])]
        offsets.append(1000 * (top[0].mean(0) - top[1].mean(0))[:2])
        spans.append(
            [1000 * (t[:, 1].min() - axis_y) for t in top] + [1000 * (t[:, 1].max() - axis_y) for t in top]
        )
    offsets, spans = np.array(offsets), np.array(spans)
    dist = np.linalg.norm(offsets, axis=1)
    print(f"   A-B centroid offset per pair [mm]: {dist}  (mean {dist.mean():.1f}; mean |dx| "
          f"{np.abs(offsets[:, 0]).mean():.1f}, |dy| {np.abs(offsets[:, 1]).mean():.1f})")  # fmt: skip
    print(f"   y-span about the group axis [mm], mean over pairs: A {spans[:, [0, 2]].mean(0)}, "
          f"B {spans[:, [1, 3]].mean(0)}; tines at 0 and ±{1000 * s.brush.column_pitch:.0f}")  # fmt: skip


np.set_printoptions(precision=2, suppress=True, linewidth=220)
if args.climb:
    climb = [float(b) for b in args.climb.split(",")]
    top_depth = sim.hair_top - sim.start_height(max(climb))
    for b_l in climb:
        r = sim.stroke(b_l, abort_force=None, y=y)
        print(f"climb stroke b_l {b_l:.2f}: F_max {r.max_force:.2f} N; Σ|Lk| after {sim.entanglement():.2f}")
    band = sim.entanglement_meter.pair_link_by_depth(sim.data, np.array([0.0, top_depth, 1.0]))[:, 0]
    print(f"   pair link above {1000 * top_depth:.0f} mm (signed)", band, f" Σ|.| {np.abs(band).sum():.2f}")
for k in range(1, n + 1):
    print(f"before stroke {k}:")
    pair_geometry(sim)
    rows = []

    def obs(s, sample, rows=rows):
        rows.append((float(s.brush_position()[2]), sample.brushing_force(), snapshot(s)))

    sim.add_observer(obs)
    r = sim.stroke(1.0, abort_force=None, y=y)
    sim.remove_observer(obs)
    i = int(np.argmax([x[1] for x in rows]))
    z, f, (pt, depth, within, between) = rows[i]
    print(f"stroke {k}: F_max {r.max_force:.2f} N at brush z {z:.3f} m; Σ|Lk| after {sim.entanglement():.2f}")
    print("   tine |F_z| per pair [N]     ", pt, " sum", f"{pt.sum():.2f}")
    print("   mean contact depth below roots [mm]", 1000 * depth)
    print("   hair-hair within pair [N]   ", within, f" between pairs {between:.2f}")
    print("   pair Lk after", sim.pair_links())
