"""Exploration probe: where each entwined pair holds its link (upper / lower half of the strands) before and after two
full strokes, coily in a one-row curtain under a 23-tine comb (docs/detangling.md, "Why coily stalls")."""

import math

import numpy as np

from hairbrush_env import hair
from hairbrush_env.brush import BrushConfig
from hairbrush_env.scene import BrushingSim, SceneConfig
from hairbrush_env.topology import linking_number

base = hair.PRESETS["coily"]
w = base.replace(
    young=hair.wisp_young(8e-4, cohesion=12.5), min_spacing=0.04, rest_splay=math.pi / 2, group_rows=1
)
sim = BrushingSim(
    SceneConfig(
        wig=w,
        brush=BrushConfig(rows=1, columns=23, column_pitch=0.02, tine_length=0.06, hinged=False),
        scalp_clearance=0.005,
    )
)
sim.reset(0)


def report(tag):
    c = sim.hair_curve_array()
    top = sim.hair_top
    print(tag, "bottom below roots", round(top - c[..., 2].min(), 3))
    for i, j in sim.layout.pairs:
        a, b = c[i], c[j]
        lk = linking_number(a, b, closed=False)
        # link of the upper and lower halves (by vertex index)
        h = a.shape[0] // 2
        up = linking_number(a[: h + 1], b[: h + 1], closed=False)
        lo = linking_number(a[h:], b[h:], closed=False)
        dist = np.linalg.norm(a[:, :2] - b[:, :2], axis=1)
        print(
            f"  pair {i:2d},{j:2d} Lk {lk:+.2f} upper {up:+.2f} lower {lo:+.2f}",
            f"horizontal distance root/mid/tip mm {1e3 * dist[0]:.0f}/{1e3 * dist[h]:.0f}/{1e3 * dist[-1]:.0f}",
        )


report("pre-brushed")
for k in range(2):
    r = sim.stroke(1.0, abort_force=None)
    print("stroke", k + 1, "F", round(r.max_force, 2))
report("after 2")
