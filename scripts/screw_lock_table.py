"""Where a curl locks on a tine pushed through it: turns of a rigid helix free to turn about its axis in 1 s of a
constant push, against the friction coefficient as a fraction of its lead-angle tangent tan λ = P / (2πR), and at
the tines' friction under v1–v7 (0.3) and v8 (0.15) (:mod:`hairbrush_env.studies.screw_lock`; docs/detangling.md,
*HairBrush-v8*).

    python scripts/screw_lock_table.py
"""

from hairbrush_env.hair import PRESETS
from hairbrush_env.physics import PHYSICS
from hairbrush_env.studies.screw_lock import lead_tangent, tine_through_helix

FRACTIONS = (0.5, 0.7, 0.8, 0.85, 0.9, 0.95, 1.0, 1.1)
print("| wig (v8) | R mm | R/P | tan λ | " + " | ".join(f"μ = {f} tan λ" for f in FRACTIONS)
      + " | μ = 0.3 (v1–v7) | μ = 0.15 (v8) |")  # fmt: skip
print("|---|---:|---:|---:|" + "---:|" * (len(FRACTIONS) + 2))
for name in PRESETS:
    wig = PHYSICS["v8"].wig(name)
    if wig.curliness == 0:
        continue
    tan_lead = lead_tangent(wig.curl_radius, wig.pitch)
    mus = [f * tan_lead for f in FRACTIONS] + [0.3, 0.15]
    turns = [tine_through_helix(mu, curl_radius=wig.curl_radius, pitch=wig.pitch).turns for mu in mus]
    print(f"| {name} | {1e3 * wig.curl_radius:.0f} | {wig.curliness:.2f} | {tan_lead:.3f} | "
          + " | ".join(f"{t:.2f}" for t in turns) + " |")  # fmt: skip
