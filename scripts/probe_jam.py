"""Exploration probe: what holds the brush when a full stroke jams (docs/detangling.md, *Jams*).

    python scripts/probe_jam.py WIG SEED STROKES [SCENE_FIELDS_JSON] [TIP_STIFFNESS]   # e.g. curly 0 6
    python scripts/probe_jam.py curly 0 6 '{}' 0.3,0.1   # a trial taper: last two vertices' hinges x0.3, x0.1
    python scripts/probe_jam.py curly 0 6 '{"brush": {"hinged": true, "stiffness": 1.1, "damping": 0.004,
        "deflection_limit": 1.0}}'                         # the comb with hinged (soft) tines

SCENE_FIELDS_JSON: SceneConfig fields; "wig" may be a dict of WigConfig fields over WIG's preset (e.g.
{"wig": {"self_collision": true}}), "brush" a preset name or a dict of BrushConfig fields over the default comb's
(``deflection_limit`` [rad]: how far hinged tines bend).

TIP_STIFFNESS scales the stiffness (and damping, so the time constants stay) of the hinges at the last vertices of
every strand, root side first (a trial of tapered wisp tips, set on the compiled model before the wig is shaken).

Repeated full strokes (b_l = 1, no abort) from the pre-brushed wig. In every stroke, at the physics step where the
tines carry the largest vertical contact force, it prints the strands the tines hold hardest: per strand the tine
force [N] and on which edges (counted from the root), the strand's free-end height below the brush, the hair–hair
contact force on its last three edges and from which strands, and the signed link of the strand with its entwined
partners below and above the tine height. That separates a hook (a free end bent round a tine), a knot (the
partners' remaining link pushed down onto the free ends) and a pinch (strands pressed together between tines).
"""

import json
import os
import re
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
from dataclasses import asdict

import mujoco
import numpy as np

from hairbrush_env.brush import BRUSH_PRESETS, BrushConfig
from hairbrush_env.hair import get_wig
from hairbrush_env.scene import BrushingSim, SceneConfig
from hairbrush_env.scene_build import SCENE_TINE_PREFIX
from hairbrush_env.topology.gauss import link_density

wig, seed, n = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
scene_fields = json.loads(sys.argv[4]) if len(sys.argv) > 4 else {}
tip_scale = [float(v) for v in sys.argv[5].split(",")] if len(sys.argv) > 5 else []
fields = dict(scene_fields)
# "wig": WigConfig fields over the WIG preset's, e.g. {"self_collision": true}
if isinstance(fields.get("wig"), dict):
    fields["wig"] = get_wig(wig).replace(**fields["wig"])
else:
    fields["wig"] = wig
if isinstance(fields.get("brush"), dict):
    fields["brush"] = BrushConfig(**{**asdict(BRUSH_PRESETS["comb"]), **fields["brush"]})
sim = BrushingSim(SceneConfig(**fields))
m = sim.model
names = list(sim.layout.names)
n_vertices = sim.wig.n_edges
for name in names:
    for q, factor in enumerate(tip_scale):
        k = n_vertices - len(tip_scale) + q
        for label in ("twist", "bend1", "bend2"):
            j = m.joint(f"{name}_{k}_{label}").id
            m.jnt_stiffness[j] *= factor
            m.dof_damping[m.jnt_dofadr[j]] *= factor
sim.reset(seed)
tines = {g for g in range(m.ngeom) if m.geom(g).name.startswith(SCENE_TINE_PREFIX)}
strand_of = np.full(m.ngeom, -1)
edge_of = np.full(m.ngeom, -1)
pattern = re.compile(r"^(.*)_(\d+)$")
for g in range(m.ngeom):
    match = pattern.match(m.body(m.geom_bodyid[g]).name)
    if match and match.group(1) in names:
        strand_of[g] = names.index(match.group(1))
        edge_of[g] = int(match.group(2))
n_edges = int(edge_of.max()) + 1
partners: dict[int, list[int]] = {}
for i, j in sim.entanglement_meter.pairs:
    partners.setdefault(i, []).append(j)
    partners.setdefault(j, []).append(i)
force6 = np.zeros(6)


def snapshot(s: BrushingSim) -> dict:
    d = s.data
    tine_f: dict[int, dict[int, float]] = {}
    tip_hh: dict[int, dict[int, float]] = {}
    total = 0.0
    for c in range(d.ncon):
        con = d.contact[c]
        g1, g2 = int(con.geom1), int(con.geom2)
        mujoco.mj_contactForce(m, d, c, force6)
        frame = con.frame.reshape(3, 3)
        f_world = frame.T @ force6[:3]  # force on geom2 from geom1, world frame
        if (g1 in tines) != (g2 in tines):
            h = g2 if g1 in tines else g1
            if strand_of[h] >= 0:
                fz = abs(float(f_world[2]))
                total += fz
                tine_f.setdefault(int(strand_of[h]), {}).setdefault(int(edge_of[h]), 0.0)
                tine_f[int(strand_of[h])][int(edge_of[h])] += fz
        elif strand_of[g1] >= 0 and strand_of[g2] >= 0 and strand_of[g1] != strand_of[g2]:
            fn = abs(float(force6[0]))
            for a, b in ((g1, g2), (g2, g1)):
                if edge_of[a] >= n_edges - 3:
                    tip_hh.setdefault(int(strand_of[a]), {}).setdefault(int(strand_of[b]), 0.0)
                    tip_hh[int(strand_of[a])][int(strand_of[b])] += fn
    return {
        "total": total,
        "tine": tine_f,
        "tip_hh": tip_hh,
        "curves": s.hair_curve_array().copy(),
        "brush_z": float(s.brush_position()[2]),
        "t": float(d.time),
    }


best: dict = {}


def observe(s: BrushingSim) -> None:
    snap = snapshot(s)
    if snap["total"] > best.get("total", -1.0):
        best.clear()
        best.update(snap)


sim.add_step_observer(observe)
start = sim.entanglement()
print(f"{wig} seed {seed} {scene_fields} tip stiffness {tip_scale}: entanglement {start:.2f}", flush=True)
for k in range(1, n + 1):
    best.clear()
    res = sim.stroke(1.0, abort_force=None)
    curves = best["curves"]
    print(
        f"stroke {k}: F_max {res.max_force:.1f} N (load cell), entanglement {sim.entanglement():.2f} "
        f"(start {start:.2f}), still entwined {sim.entanglement_meter.still_entwined(sim.data)}; "
        f"largest tine force {best['total']:.1f} N "
        f"at t {best['t']:.2f} s, brush z {best['brush_z']:.3f} m",
        flush=True,
    )
    ranked = sorted(best["tine"].items(), key=lambda kv: -sum(kv[1].values()))[:4]
    for strand, per_edge in ranked:
        f = sum(per_edge.values())
        edges = ",".join(f"{e}:{v:.1f}" for e, v in sorted(per_edge.items()))
        tip_below = best["brush_z"] - float(curves[strand, -1, 2])
        hh = ", ".join(f"{names[o]} {v:.1f}" for o, v in sorted(best["tip_hh"].get(strand, {}).items()))
        links = []
        for o in partners.get(strand, []):
            _, lam = link_density(curves[strand], curves[o])
            mid = 0.5 * (curves[strand] + curves[o])
            ell = lam * np.linalg.norm(np.diff(mid, axis=0), axis=1)
            below = 0.5 * (mid[:-1, 2] + mid[1:, 2]) < best["brush_z"]
            links.append(f"{names[o]} below {ell[below].sum():+.2f} above {ell[~below].sum():+.2f}")
        print(
            f"  {names[strand]}: tine {f:.1f} N on edges {edges} (of {n_edges}); free end {tip_below * 1e3:+.0f} mm "
            f"below the brush; tip hair-hair [{hh}]; link {'; '.join(links) or '-'}",
            flush=True,
        )
