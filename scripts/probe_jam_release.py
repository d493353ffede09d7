"""Exploration probe: the same jam met by the default comb and by a variant brush (docs/detangling.md, *Jams*).

    python scripts/probe_jam_release.py WIG SEED N_BEFORE BRUSH_JSON
    python scripts/probe_jam_release.py curly 0 4 '{"hinged": true, "stiffness": 1.1, "damping": 0.004,
        "deflection_limit": 1.0}'

Brushes N_BEFORE full strokes (b_l = 1, no abort) with the default comb, then copies the hair's joint state into a
scene whose comb has the BRUSH_JSON fields (over the default comb's) and brushes the next full stroke from that same
state with both brushes (``deflection_limit`` [rad]: how far hinged tines bend, brush.xml's 0.35 by default).
Prints each stroke's maximum load-cell force, where in the pull it peaked, the largest tine deflection and the
entanglement.
"""

import json
import os
import sys
from dataclasses import asdict

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import mujoco
import numpy as np

from hairbrush_env.brush import BRUSH_PRESETS, BrushConfig
from hairbrush_env.scene import BrushingSim, SceneConfig
from hairbrush_env.scene_build import SCENE_TINE_PREFIX

wig, seed, n_before = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
variant = BrushConfig(**{**asdict(BRUSH_PRESETS["comb"]), **json.loads(sys.argv[4])})


def tine_joints(m: mujoco.MjModel) -> list[int]:
    return [j for j in range(m.njnt) if m.joint(j).name.startswith(SCENE_TINE_PREFIX)]


def stroke(sim: BrushingSim, label: str) -> None:
    deflection = [0.0]
    adr = [sim.model.jnt_qposadr[j] for j in tine_joints(sim.model)]

    def observe(s: BrushingSim) -> None:
        if adr:
            deflection[0] = max(deflection[0], float(np.abs(s.data.qpos[adr]).max()))

    sim.add_step_observer(observe)
    res = sim.stroke(1.0, abort_force=None)
    sim.remove_step_observer(observe)
    t, f = res.force_trace
    k = int(np.argmax(f)) if f.size else 0
    print(
        f"{label}: F_max {res.max_force:.1f} N at {t[k] if f.size else 0:.1f} s of the pull; "
        f"samples ≥ 10 N: {int((f >= 10).sum())}; largest tine deflection {deflection[0]:.2f} rad; "
        f"entanglement {sim.entanglement():.2f}; diverged {res.diverged}",
        flush=True,
    )


rigid = BrushingSim(SceneConfig(wig=wig))
rigid.reset(seed)
print(f"{wig} seed {seed}: entanglement {rigid.entanglement():.2f}; variant comb {variant}", flush=True)
for k in range(1, n_before + 1):
    stroke(rigid, f"stroke {k}, default comb")

soft = BrushingSim(SceneConfig(wig=wig, brush=variant))
soft.reset(seed)
names = tuple(rigid.layout.names)
for j in range(rigid.model.njnt):
    name = rigid.model.joint(j).name
    if name.rsplit("_", 2)[0] in names:
        js = soft.model.joint(name).id
        soft.data.qpos[soft.model.jnt_qposadr[js]] = rigid.data.qpos[rigid.model.jnt_qposadr[j]]
        soft.data.qvel[soft.model.jnt_dofadr[js]] = rigid.data.qvel[rigid.model.jnt_dofadr[j]]
mujoco.mj_forward(soft.model, soft.data)
soft.hair_bottom = rigid.hair_bottom
print(
    f"state copied: entanglement {soft.entanglement():.2f} (default comb's {rigid.entanglement():.2f})",
    flush=True,
)
stroke(rigid, f"stroke {n_before + 1}, default comb")
stroke(soft, f"stroke {n_before + 1}, variant comb")
