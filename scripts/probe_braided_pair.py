"""Exploration probe: a braided pair (two wisps twisted round one curled centerline, R_pair ≈ r) alone with the
comb, against the wig's pairs entwined at the curl's radius (docs/detangling.md, *What carries coily's first
stroke from the roots*).

    python scripts/probe_braided_pair.py WIG PLY_PITCH [B_L,B_L,...] [--physics v8]
    # e.g. coily 1000 1,1;  coily 0.03 0.33,0.5,0.67,0.83,1,1

The centerline is WIG's strand (its root run, then its curl); the two wisps lie r + 0.5 mm either side of it (their
contact margins apart), turned about it once per PLY_PITCH [m] of arc (1000: not twisted, the plies curl side by
side; negative: the other sense), each stress-free in that shape, with the wig's material, contacts and drag, in
:class:`hairbrush_env.studies.pair_on_comb.PairOnComb` (its ``curves``): three middle tines put in along their
length and pulled down until they are 1 cm below every strand point, a stroke of b_l starting at its
``start_depth(b_l)``. Prints each stroke's largest 10 Hz force and the pair's |Lk| after it.
"""

import argparse
import math
import time

import numpy as np

from hairbrush_env.hair import CONTACT_MARGIN
from hairbrush_env.physics import PHYSICS, get_physics
from hairbrush_env.rods import resample_polyline
from hairbrush_env.studies.pair_on_comb import PairOnComb

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("wig")
parser.add_argument("ply_pitch", type=float)
parser.add_argument("brush_lengths", nargs="?", default="1,1")
parser.add_argument("--physics", choices=list(PHYSICS), default="v8")
args = parser.parse_args()
wig = get_physics(args.physics).scene_config(args.wig).wig


def braid_curves(rho: float) -> list[np.ndarray]:
    R, b, run = wig.curl_radius, wig.pitch / (2 * math.pi), wig.root_run_min
    s = np.linspace(0.0, wig.length, 4000)
    phi = math.pi / 2 + np.clip(s - run, 0.0, None) / math.hypot(R, b)  # roots across the tines, as the wig's
    centre = np.stack(
        [R * np.cos(phi), R * np.sin(phi), -np.minimum(s, run) - b * (phi - math.pi / 2)], axis=1
    )
    tangent = np.gradient(centre, axis=0)
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    normal = np.stack([-np.cos(phi), -np.sin(phi), np.zeros_like(phi)], axis=1)  # towards the curl's axis
    normal -= (normal * tangent).sum(1)[:, None] * tangent
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    binormal = np.cross(tangent, normal)
    turn = 2 * math.pi * s / args.ply_pitch
    offset = np.cos(turn)[:, None] * normal + np.sin(turn)[:, None] * binormal
    return [resample_polyline(centre + sign * rho * offset, wig.n_edges) for sign in (1, -1)]


t0 = time.process_time()
pair = PairOnComb(args.wig, physics=args.physics, curves=braid_curves(wig.strand_radius + CONTACT_MARGIN))
hanging = 1e3 * pair.hanging_length()
out = [f"{args.wig} ply pitch {args.ply_pitch:g} m: |Lk| {pair.link():.2f}, hanging {hanging:.0f} mm"]
for b_l in (float(b) for b in args.brush_lengths.split(",")):
    stroke = pair.stroke(pair.start_depth(b_l))
    out.append(f"b_l {b_l:g}: {stroke.max_force:.2f} N, |Lk| {stroke.link_after:.2f}")
print(" | ".join(out), f"| {time.process_time() - t0:.0f} CPU s", flush=True)
