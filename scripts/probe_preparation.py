"""Exploration probe: the pre-brushed preparation (shake, steady, settle) watched for crossings at every step.

    python scripts/probe_preparation.py WIG SEED [--free-step] [--mass-scale S]

``--free-step`` runs the shake and the steadying at the 10 ms free step, as the preparation did before it moved to
the contact step (docs/detangling.md, *Correction*). Prints the crossings, the smallest hair–hair distance (fraction
of the sum of radii) and Σ|Lk| of the entwined pairs after the shake and at the end.
"""

import argparse
import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import mujoco

from hairbrush_env import hair
from hairbrush_env.scene import BrushingSim, SceneConfig
from hairbrush_env.topology.proximity import CrossingDetector

p = argparse.ArgumentParser()
p.add_argument("wig")
p.add_argument("seed", type=int)
p.add_argument("--free-step", action="store_true")
p.add_argument("--mass-scale", type=float, default=hair.MASS_SCALE)
a = p.parse_args()
wig = hair.PRESETS[a.wig].replace(mass_scale=a.mass_scale)
sim = BrushingSim(SceneConfig(wig=wig))
det = CrossingDetector(gap=5e-3)


def watch(model: mujoco.MjModel, data: mujoco.MjData) -> None:
    det.update(sim.hair_curve_array(), float(data.time))


def report(when: str) -> None:
    print(
        f"{a.wig} seed {a.seed} mass_scale {a.mass_scale:g} {'10 ms' if a.free_step else 'contact step'} {when}:",
        f"crossings {len(det.crossings)}, min hair-hair {det.min_distance / (2 * wig.strand_radius):.3f},",
        f"entwined {sim.entanglement_meter.breakdown(sim.data)[0]:.1f} (built {sim.layout.n_links:.1f})",
        flush=True,
    )


sim.use_step(contact=not a.free_step)
hair.set_state(sim.model, sim.data, sim._base_state)  # the built wig, as BrushingSim.settled_state starts
hair.shake(sim.model, sim.data, wig, a.seed, strand_bodies=sim.hair_bodies, on_step=watch)
report("after the shake")
dofs = sim._hair_dofs
sim.model.dof_damping[dofs] *= 30.0  # the steadying of BrushingSim.settled_state
for _ in range(round(1.0 / sim.model.opt.timestep)):
    mujoco.mj_step(sim.model, sim.data)
    watch(sim.model, sim.data)
report("after steadying")
if det.crossings:
    print("first crossings:", det.crossings[:3])
