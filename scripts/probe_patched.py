"""Exploration probe: run another probe script with hair contact / chain constants patched (docs/detangling.md,
*Real mass with a harder contact impedance*).

    PATCH='{"solimp": [0.99, 0.999, 1e-4, 0.5, 2], "armature": 1.0}' \\
        python scripts/probe_patched.py scripts/probe_detangle.py NAME '{"wig": {"mass_scale": 1}, "strokes": 3}'

PATCH keys: ``solimp`` / ``solref`` (``hair.CONTACT_SOLIMP`` / ``CONTACT_SOLREF``, hair–hair and tool contacts),
``armature`` (``rods.chain._ARMATURE``, in units of the segment's ``m ℓ²/3``) and ``fluid_density`` /
``fluid_viscosity`` (``mjOption.density`` / ``viscosity`` of every ``BrushingSim``: MuJoCo's inertia-box drag, set
after the pre-brushed states are looked up, so they are shaken without it) and ``explicit_drag``: quadratic drag
``−½ ρ ℓ d |v| v`` [ρ in kg/m³] on every strand segment's centre of mass, ℓ × d its side area, applied as
``xfrc_applied`` from the velocity before each brushing step (explicit, so it adds no cost to the step; not during
the preparation). (The dead-zone drag once patched here as ``drag_free_speed`` is ``WigConfig.drag_free_speed``.)
"""

import json
import os
import runpy
import sys

# Before numba is imported (by hairbrush_env): the probe scripts set it too, and numba refuses a change once its
# threads run.
os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import hairbrush_env.hair as hair_pkg
import hairbrush_env.hair.build as hair_build
import hairbrush_env.rods.chain as chain
import hairbrush_env.scene as scene

patch = json.loads(os.environ.get("PATCH", "{}"))
if "solimp" in patch:
    hair_build.CONTACT_SOLIMP = hair_pkg.CONTACT_SOLIMP = tuple(patch["solimp"])
if "solref" in patch:
    hair_build.CONTACT_SOLREF = hair_pkg.CONTACT_SOLREF = tuple(patch["solref"])
if "armature" in patch:
    chain._ARMATURE = float(patch["armature"])
if "fluid_density" in patch or "fluid_viscosity" in patch:
    _init = scene.BrushingSim.__init__

    def _init_with_fluid(self, *args, **kwargs):
        _init(self, *args, **kwargs)
        self.model.opt.density = float(patch.get("fluid_density", 0.0))
        self.model.opt.viscosity = float(patch.get("fluid_viscosity", 0.0))

    scene.BrushingSim.__init__ = _init_with_fluid
if "explicit_drag" in patch:
    import mujoco
    import numpy as np

    rho = float(patch["explicit_drag"])
    _step = scene.BrushingSim._physics_step

    def _drag_step(self, samples):
        if not hasattr(self, "_drag_c"):
            m = self.model
            bodies = self.hair_bodies
            geoms = np.array([np.flatnonzero(m.geom_bodyid == b)[0] for b in bodies])
            length = 2.0 * m.geom_size[geoms, 1]
            diameter = 2.0 * m.geom_size[geoms, 0]
            self._drag_c = 0.5 * rho * length * diameter
        d = self.data
        b = self.hair_bodies
        cvel = d.cvel[b]
        arm = d.xipos[b] - d.subtree_com[self.model.body_rootid[b]]
        v = cvel[:, 3:] + np.cross(cvel[:, :3], arm)
        d.xfrc_applied[b, :3] = -(self._drag_c * np.linalg.norm(v, axis=1))[:, None] * v
        _step(self, samples)

    scene.BrushingSim._physics_step = _drag_step
    del mujoco
script = sys.argv[1]
sys.argv = sys.argv[1:]
runpy.run_path(script, run_name="__main__")
