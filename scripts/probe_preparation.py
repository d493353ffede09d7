"""Exploration probe: the pre-brushed preparation (shake, steady, settle) watched for crossings at every step.

    python scripts/probe_preparation.py WIG SEED [--free-step] [--mass-scale S]

``--free-step`` runs the preparation at the 10 ms free step, as it ran before it moved to the contact step
(``BrushingSim.prepare``; docs/detangling.md, *Correction*). Prints the crossings, the smallest hair–hair distance
(fraction of the sum of radii) and Σ|Lk| of the entwined pairs at the end.
"""

import argparse
import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
from hairbrush_env import hair
from hairbrush_env.pass_through import PassThroughMonitor
from hairbrush_env.scene import BrushingSim, SceneConfig

p = argparse.ArgumentParser()
p.add_argument("wig")
p.add_argument("seed", type=int)
p.add_argument("--free-step", action="store_true")
p.add_argument("--mass-scale", type=float, default=hair.MASS_SCALE)
a = p.parse_args()
sim = BrushingSim(SceneConfig(wig=hair.PRESETS[a.wig].replace(mass_scale=a.mass_scale)))
mon = PassThroughMonitor(sim)
sim.prepare(a.seed, contact_step=not a.free_step)
print(
    f"{a.wig} seed {a.seed} mass_scale {a.mass_scale:g} {'10 ms step' if a.free_step else 'contact step'}:",
    f"crossings {len(mon.crossings)}, min hair-hair {mon.hair_hair_fraction:.3f},",
    f"entwined {sim.entanglement_meter.breakdown(sim.data)[0]:.1f} (built {sim.layout.n_links:.1f})",
)
if mon.crossings:
    print("first crossings:", mon.crossings[:3])
