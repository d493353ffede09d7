"""A lone curl of each curled preset, held by its root, with a comb's tine pulled down through it: the largest force
against E I κ₀² / 2, what drawing it straight would cost (:mod:`hairbrush_env.studies.root_held_curl`;
docs/detangling.md, *What carries coily's first stroke from the roots*).

    python scripts/root_held_curl_table.py [--physics v8]
"""

import argparse

from hairbrush_env.physics import PHYSICS, get_physics
from hairbrush_env.studies.root_held_curl import pull_tine_through_curl

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--physics", choices=list(PHYSICS), default="v8")
args = parser.parse_args()
physics = get_physics(args.physics)
print(
    f"| wig ({args.physics}) | R mm | P mm | E I κ₀² / 2 [N] | max force, μ = 0.15 / 0.3 / 1 [N] "
    "| fraction of E I κ₀² / 2 |"
)
print("|---|---:|---:|---:|---|---|")
for name in ("loose_curl", "curly", "tight_curl", "coily"):
    wig = physics.scene_config(name).wig
    common = dict(curl_radius=wig.curl_radius, pitch=wig.pitch, length=wig.length, run=wig.root_run_min,
                  edges_per_turn=wig.edges_per_turn, young=wig.young_modulus, strand_radius=wig.strand_radius,
                  density=wig.density, damping=wig.damping, mass_scale=wig.mass_scale)  # fmt: skip
    runs = [pull_tine_through_curl(friction=mu, **common) for mu in (0.15, 0.3, 1.0)]
    print(
        f"| {name} | {1e3 * wig.curl_radius:.0f} | {1e3 * wig.pitch:.1f} | {runs[0].peel:.3f} | "
        f"{' / '.join(f'{r.max_force:.3f}' for r in runs)} | {' / '.join(f'{r.peel_fraction:.2f}' for r in runs)} |",
        flush=True,
    )
