"""Exploration probe: run another probe script with hair contact / chain constants patched (docs/detangling.md,
*Real mass with a harder contact impedance*).

    PATCH='{"solimp": [0.99, 0.999, 1e-4, 0.5, 2], "armature": 1.0}' \\
        python scripts/probe_patched.py scripts/probe_detangle.py NAME '{"wig": {"mass_scale": 1}, "strokes": 3}'

PATCH keys: ``solimp`` / ``solref`` (``hair.CONTACT_SOLIMP`` / ``CONTACT_SOLREF``, hair–hair and tool contacts) and
``armature`` (``rods.chain._ARMATURE``, in units of the segment's ``m ℓ²/3``).
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

patch = json.loads(os.environ.get("PATCH", "{}"))
if "solimp" in patch:
    hair_build.CONTACT_SOLIMP = hair_pkg.CONTACT_SOLIMP = tuple(patch["solimp"])
if "solref" in patch:
    hair_build.CONTACT_SOLREF = hair_pkg.CONTACT_SOLREF = tuple(patch["solref"])
if "armature" in patch:
    chain._ARMATURE = float(patch["armature"])
script = sys.argv[1]
sys.argv = sys.argv[1:]
runpy.run_path(script, run_name="__main__")
