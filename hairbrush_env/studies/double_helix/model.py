"""The MuJoCo model of one combing run: the strands' rest centerlines, the opening for the tine, the two DER
strands with the mocap tine, and the tine's contact force on the hair."""

from __future__ import annotations

import math

import numpy as np

from .setup import CombingSetup

__all__ = ["TINE_HALF_LENGTH", "build_model", "bulge", "strand_points", "tine_force"]

TINE_HALF_LENGTH = 0.05  # [m], far wider than the strands' lateral excursions
_DAMPRATIO = 1.0  # contact solref = (CombingSetup.contact_timeconst, 1): critically damped
_SOLIMP = (0.99, 0.9999, 2e-5, 0.5, 2.0)


def strand_points(setup: CombingSetup) -> tuple[np.ndarray, np.ndarray]:
    """Rest centerlines, clamp first, hanging from z = 0 to z = −h; strands along ±x̂ at the insertion depth."""
    from ...topology import double_helix

    n = max(3, round(setup.turns * setup.edges_per_pitch) + 1)
    h, depth = setup.height, setup.insertion_depth
    # double_helix spans z ∈ [0, h] with azimuth phase + 2πz/P; we translate it down by h (a rigid motion keeps the
    # handedness) and choose the phase so that strand a is at azimuth 0 at the insertion height z = h − depth.
    phase = -2.0 * math.pi * (h - depth) / setup.pitch
    a, b = double_helix(setup.helix_radius, setup.pitch, setup.turns, n, phase=phase)
    a, b = a[::-1].copy(), b[::-1].copy()  # clamp (top) first; reversing both strands leaves Lk unchanged
    a[:, 2] -= h
    b[:, 2] -= h
    return a, b


def bulge(points: np.ndarray, setup: CombingSetup) -> np.ndarray:
    """Radial displacement that opens a gap of t + small clearance for the tine at the insertion depth."""
    r, R, t = setup.radius, setup.helix_radius, setup.tine_radius
    target = t + r + 0.1 * r  # strand centre distance from the tine axis
    amp = max(0.0, target - R)
    depth = -points[:, 2]
    w = 0.25 * setup.pitch
    g = amp * np.exp(-(((depth - setup.insertion_depth) / w) ** 2))
    rho = np.hypot(points[:, 0], points[:, 1])
    disp = np.zeros_like(points)
    disp[:, 0] = g * points[:, 0] / rho
    disp[:, 1] = g * points[:, 1] / rho
    return disp


def build_model(setup: CombingSetup):
    import mujoco

    from ...rods import RodSpec, build_rod_model

    a, b = strand_points(setup)
    area = math.pi * setup.radius**2
    density = setup.linear_density * setup.mass_scale / area
    condim = 1 if setup.friction == 0.0 else 3
    common = dict(
        radius=setup.radius,
        young=setup.young,
        poisson=setup.poisson,
        density=density,
        damping=setup.bend_damping,
        friction=setup.friction,
        condim=condim,
        contact_solref=(setup.contact_timeconst, _DAMPRATIO),
        contact_solimp=_SOLIMP,
        # The combing claims (§2.4) were validated on DER flexes; chains would change the measured tables.
        kind="flex",
    )
    rods = [
        RodSpec("strand_a", a, rgba=(0.0, 0.45, 0.7, 1.0), **common),
        RodSpec("strand_b", b, rgba=(0.84, 0.37, 0.0, 1.0), **common),
    ]

    def extra(spec: mujoco.MjSpec) -> None:
        tine = spec.worldbody.add_body(name="tine", mocap=True, pos=[0.0, 0.0, -setup.insertion_depth])
        half = math.sqrt(0.5)
        # capsule axis is local z; rotate it onto ŷ (perpendicular to the helix axis and to the strands' offset)
        g = tine.add_geom(
            name="tine",
            type=mujoco.mjtGeom.mjGEOM_CAPSULE,
            size=[setup.tine_radius, TINE_HALF_LENGTH, 0.0],
            quat=[half, half, 0.0, 0.0],
            rgba=[0.2, 0.2, 0.2, 1.0],
        )
        g.condim = condim
        g.friction = [setup.friction, 0.005, 0.0001]
        g.solref = [setup.contact_timeconst, _DAMPRATIO]
        g.solimp = list(_SOLIMP)

    gravity = (0.0, 0.0, -9.81 / setup.mass_scale)
    model = build_rod_model(rods, timestep=setup.timestep, gravity=gravity, extra=extra)
    return model, rods


def tine_force(model, data, tine_geom: int, buf: np.ndarray) -> tuple[float, float, float]:
    """(z-force of the tine on the hair, smallest tine–strand and strand–strand contact distances)."""
    import mujoco

    fz = 0.0
    gap_tine = gap_strands = math.inf
    for i in range(data.ncon):
        con = data.contact[i]
        g1, g2 = int(con.geom[0]), int(con.geom[1])
        if tine_geom not in (g1, g2):
            gap_strands = min(gap_strands, float(con.dist))
            continue
        gap_tine = min(gap_tine, float(con.dist))
        mujoco.mj_contactForce(model, data, i, buf)
        world = con.frame.reshape(3, 3).T @ buf[:3]  # contact frame rows: normal, tangent1, tangent2
        # the force acts on geom2 along +normal (normal points from geom1 to geom2) and on geom1 along −normal
        on_hair = world if g1 == tine_geom else -world
        fz += float(on_hair[2])
    return -fz, gap_tine, gap_strands  # force positive = tine pushes the hair down
