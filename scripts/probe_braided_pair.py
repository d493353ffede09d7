"""Exploration probe: a braided pair (two wisps twisted round one curled centerline, R_pair ≈ r) alone with the
comb, against the wig's pairs entwined at the curl's radius (docs/detangling.md, *What carries coily's first
stroke from the roots*).

    python scripts/probe_braided_pair.py WIG PLY_PITCH [B_L,B_L,...] [--physics v8]
    # e.g. coily 1000 1,1;  coily 0.03 0.33,0.5,0.67,0.83,1,1

The centerline is WIG's strand (its root run, then its curl); the two wisps lie r + 0.5 mm either side of it (their
contact margins apart), turned about it once per PLY_PITCH [m] of arc (1000: not twisted, the plies curl side by
side; negative: the other sense), each stress-free in that shape, with the wig's material, contacts and drag. The
comb is :mod:`hairbrush_env.studies.pair_on_comb`'s: three middle tines put in along their length and pulled down
until they are 1 cm below every strand point;
a stroke of b_l starts 8 mm + (1 − b_l)(hanging length − 8 mm) below the roots. Prints each stroke's largest 10 Hz
force and the pair's |Lk| after it.
"""

import argparse
import math
import time

import mujoco
import numpy as np

from hairbrush_env import collision
from hairbrush_env.hair import CONTACT_MARGIN, CONTACT_SOLIMP, CONTACT_SOLREF
from hairbrush_env.hair.drag import StrandDrag
from hairbrush_env.physics import PHYSICS, get_physics
from hairbrush_env.rods import RodSpec, RodView, add_rod, configure_rod_options, resample_polyline
from hairbrush_env.scene_build import TOOL_CONTACT_MARGIN
from hairbrush_env.topology import linking_number

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("wig")
parser.add_argument("ply_pitch", type=float)
parser.add_argument("brush_lengths", nargs="?", default="1,1")
parser.add_argument("--physics", choices=list(PHYSICS), default="v8")
args = parser.parse_args()
scene = get_physics(args.physics).scene_config(args.wig)
wig, brush, dt = scene.wig, scene.brush, 1e-3


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


spec = mujoco.MjSpec()
configure_rod_options(spec, timestep=dt, kind="chain")
spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
scalp = spec.worldbody.add_body(name="scalp")
contype, conaffinity = collision.HAIR_GEOM_SELF_COLLIDING
for k, curve in enumerate(braid_curves(wig.strand_radius + CONTACT_MARGIN)):
    add_rod(spec, RodSpec(name=f"ply{k}", points=curve, radius=wig.strand_radius, young=wig.young_modulus,
                          density=wig.density, mass_scale=wig.mass_scale, damping=wig.damping, friction=wig.friction,
                          contype=contype, conaffinity=conaffinity, condim=3, contact_solref=CONTACT_SOLREF,
                          contact_solimp=CONTACT_SOLIMP, margin=CONTACT_MARGIN, selfcollide=True,
                          root_twist_first=wig.root_twist_first), parent=scalp)  # fmt: skip
comb = spec.worldbody.add_body(name="comb", mocap=True)
half = 0.5 * brush.tine_length
for k, y in enumerate((-brush.column_pitch, 0.0, brush.column_pitch)):
    geom = comb.add_geom(
        name=f"tine{k}",
        type=mujoco.mjtGeom.mjGEOM_CAPSULE,
        fromto=[-half, y, 0, half, y, 0],
        size=[brush.tine_radius, 0, 0],
        friction=[brush.friction, 0.005, 1e-4],
        margin=TOOL_CONTACT_MARGIN,
        solref=list(CONTACT_SOLREF),
        solimp=list(CONTACT_SOLIMP),
    )
    geom.contype, geom.conaffinity = collision.BRISTLE_GEOM
    geom.condim = 3
model = spec.compile()
data = mujoco.MjData(model)
views = [RodView(model, f"ply{k}") for k in range(2)]
tines = {model.geom(f"tine{k}").id for k in range(3)}
drag = StrandDrag(model, np.concatenate([v.bodies for v in views]), wig.drag_density)


def step() -> None:
    drag.apply(data)
    mujoco.mj_step(model, data)


def hang(seconds: float) -> None:
    data.mocap_pos[0] = [0.0, 1.0, 0.0]
    for _ in range(round(seconds / dt)):
        step()


def link() -> float:
    a, b = (v.vertices(data) for v in views)
    return abs(linking_number(a, b, closed=False))


def hanging_length() -> float:
    return -min(float(v.vertices(data)[:, 2].min()) for v in views)


def stroke(depth: float) -> float:
    floor, f6, forces, acc = wig.length + 0.03, np.zeros(6), [], 0.0
    data.mocap_pos[0] = [-(half + wig.curl_radius + 0.01), 0.0, -depth]
    while data.mocap_pos[0, 0] < 0.0:
        data.mocap_pos[0, 0] = min(0.0, data.mocap_pos[0, 0] + scene.approach_speed * dt)
        step()
    k = 0
    while -data.mocap_pos[0, 2] < floor:
        if k % 100 == 0 and -data.mocap_pos[0, 2] > hanging_length() + 0.01:
            break  # 1 cm below every strand point, the curls it dragged down included
        for i in range(data.ncon):
            c = data.contact[i]
            if c.geom1 in tines or c.geom2 in tines:
                mujoco.mj_contactForce(model, data, i, f6)
                on_geom2 = c.frame.reshape(3, 3).T @ f6[:3]
                acc += on_geom2[2] if c.geom2 in tines else -on_geom2[2]
        k += 1
        if k % 100 == 0:
            forces.append(acc / 100)
            acc = 0.0
        data.mocap_pos[0, 2] -= scene.stroke_speed * dt
        step()
    hang(0.5)
    return max(forces) if forces else 0.0


t0 = time.process_time()
hang(1.0)
out = [
    f"{args.wig} ply pitch {args.ply_pitch:g} m: |Lk| {link():.2f}, hanging {1e3 * hanging_length():.0f} mm"
]
for b_l in (float(b) for b in args.brush_lengths.split(",")):
    f = stroke(0.008 + (1.0 - b_l) * (hanging_length() - 0.008))
    out.append(f"b_l {b_l:g}: {f:.2f} N, |Lk| {link():.2f}")
print(" | ".join(out), f"| {time.process_time() - t0:.0f} CPU s", flush=True)
