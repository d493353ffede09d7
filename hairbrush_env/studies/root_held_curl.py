"""What a lone curl held by its root costs a tine pulled down through it (the control for coily's stroke force).

A strand hangs from its root, straight for a short run and then coiled (radius ``R``, pitch ``P``, curvature
``κ₀ = R / (R² + (P / 2π)²)``). A horizontal tine through the coil's axis, pulled down, meets the wire where a turn
crosses under it. Near the root the curl cannot simply turn round the tine as a free one does
(:mod:`~hairbrush_env.studies.screw_lock`): its upper end is held. If it could do nothing else it would be drawn
straight over the tine, each length ``dz`` of travel straightening ``dz`` of curl, at the frictionless force

    F_peel = E I κ₀² / 2        (the curl's bending energy per length; more with friction on the tine)

:func:`pull_tine_through_curl` measures the force with the wig's rod model and contact settings. A lone curl is not
drawn straight: it swings aside and screws round the tine turn by turn, at a fraction of ``F_peel`` (measured in
``docs/detangling.md``, *What carries coily's first stroke from the roots*), so the force a comb meets in the wig's
pairs needs their second strand.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from ..hair import CONTACT_MARGIN, CONTACT_SOLIMP, CONTACT_SOLREF
from ..rods import RodSpec, RodView, bending_stiffness, build_rod_model, resample_polyline

LOAD_CELL_PERIOD = 0.1
"""Averaging window [s] of the force samples: the brush's load cell reads at 10 Hz."""

__all__ = ["LOAD_CELL_PERIOD", "CurlPullResult", "curl_curvature", "peel_force", "pull_tine_through_curl"]


def curl_curvature(curl_radius: float, pitch: float) -> float:
    """Curvature κ₀ [1/m] of a helix of radius ``curl_radius`` and pitch ``pitch``."""
    b = pitch / (2.0 * math.pi)
    return curl_radius / (curl_radius**2 + b**2)


def peel_force(curl_radius: float, pitch: float, *, young: float, strand_radius: float) -> float:
    """``E I κ₀² / 2`` [N]: the frictionless force to draw a root-held curl straight over a tine."""
    return 0.5 * bending_stiffness(young, strand_radius) * curl_curvature(curl_radius, pitch) ** 2


@dataclass(frozen=True)
class CurlPullResult:
    """Outcome of :func:`pull_tine_through_curl`: the tine's depth below the root [m] and the vertical force the wire
    puts on it [N], each averaged over every 0.1 s of the pull (a 10 Hz load cell's samples), and
    ``F_peel = E I κ₀² / 2`` [N], what drawing the curl straight would cost."""

    depth: np.ndarray
    force: np.ndarray
    peel: float
    friction: float

    @property
    def max_force(self) -> float:
        """Largest vertical force on the tine over the pull [N]."""
        return float(self.force.max())

    @property
    def peel_fraction(self) -> float:
        """``max_force / F_peel``: 1 or more if the curl were drawn straight; well below it if it lets the tine by."""
        return self.max_force / self.peel


def _curl_points(curl_radius: float, pitch: float, length: float, run: float, n_edges: int) -> np.ndarray:
    """A root at ``(R, 0, 0)``, a straight run down, then a coil about the z axis (turning from +x towards +y)."""
    b = pitch / (2.0 * math.pi)
    arc_per_rad = math.hypot(curl_radius, b)
    phi_end = (length - run) / arc_per_rad
    phi = np.linspace(0.0, phi_end, 64 * max(1, math.ceil(phi_end / (2 * math.pi))) + 1)
    coil = np.stack([curl_radius * np.cos(phi), curl_radius * np.sin(phi), -run - b * phi], axis=1)
    pts = np.vstack([[[curl_radius, 0.0, 0.0]], coil]) if run > 0 else coil
    return resample_polyline(pts, n_edges)


def pull_tine_through_curl(
    *,
    curl_radius: float = 0.009,
    pitch: float = 0.01125,
    length: float = 0.30,
    run: float = 0.012,
    edges_per_turn: int = 8,
    young: float = 1.6e8,
    strand_radius: float = 8e-4,
    density: float = 1300.0,
    damping: float = 0.002,
    mass_scale: float = 10.0,
    friction: float = 0.15,
    tine_radius: float = 1.5e-3,
    tine_length: float = 0.06,
    column_pitch: float | None = 0.02,
    start_turn: float = 0.25,
    speed: float = 0.1,
    travel: float | None = None,
    timestep: float = 1e-3,
) -> CurlPullResult:
    """Pull a horizontal tine down through a root-held curl at ``speed`` [m/s] and record its vertical load.

    The tine (length ``tine_length`` [m]) lies along x through the coil's axis, ``start_turn`` turns below the end
    of the straight ``run`` [m] (a quarter turn: inside the first turn, between the two crossings of the wire with
    its line), with the comb's neighbours ``column_pitch`` [m] to either side (``None``: the tine alone), and moves
    kinematically ``travel`` [m] down (default: the strand's arc length below the tine plus 2 cm, so the free end
    goes past it). Gravity on; contacts as in the wig (the hair's ``solref``/``solimp``/margin, elliptic cones,
    ``condim`` 3, or 1 when ``friction`` is 0); the strand's joint damping is ``damping`` [s] times each hinge's
    stiffness, its mass scaled by ``mass_scale`` as the wig's. The defaults are one strand of coily under
    ``HairBrush-v8`` (R 9 mm, R/P 0.8, 0.30 m, 8 edges a turn, the 12 mm root run, tine friction 0.15, the comb's
    1.5 mm tines 20 mm apart, 0.1 m/s) without the wig's air drag.
    """
    values = {"curl_radius": curl_radius, "pitch": pitch, "length": length, "young": young,
              "strand_radius": strand_radius, "speed": speed, "tine_radius": tine_radius}  # fmt: skip
    for name, value in values.items():
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"pull_tine_through_curl: {name} must be > 0, got {value!r}")
    if not (friction >= 0 and run >= 0 and start_turn > 0 and edges_per_turn >= 6):
        raise ValueError(
            f"pull_tine_through_curl: friction {friction!r} and run {run!r} must be >= 0, start_turn "
            f"{start_turn!r} > 0, edges_per_turn {edges_per_turn!r} >= 6"
        )
    arc_per_turn = math.hypot(2 * math.pi * curl_radius, pitch)
    if run + (start_turn + 1.0) * arc_per_turn > length:
        raise ValueError(f"pull_tine_through_curl: length {length!r} leaves less than a turn below the tine")
    n_edges = max(8, round(edges_per_turn * (length - run) / arc_per_turn) + (2 if run > 0 else 0))
    rod = RodSpec(
        name="curl",
        points=_curl_points(curl_radius, pitch, length, run, n_edges),
        radius=strand_radius,
        young=young,
        density=density,
        damping=damping,
        mass_scale=mass_scale,
        friction=friction,
        condim=3 if friction > 0 else 1,
        margin=CONTACT_MARGIN,
        contact_solref=CONTACT_SOLREF,
        contact_solimp=CONTACT_SOLIMP,
    )
    z0 = -run - (start_turn + 0.5) * pitch  # between the wire at the tine's line half a turn apart

    columns = [0.0] if column_pitch is None else [-column_pitch, 0.0, column_pitch]

    def add_tine(spec: mujoco.MjSpec) -> None:
        spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
        tine = spec.worldbody.add_body(name="tine", pos=[0.0, 0.0, z0], mocap=True)
        for k, y in enumerate(columns):
            geom = tine.add_geom(
                name=f"tine{k}",
                type=mujoco.mjtGeom.mjGEOM_CAPSULE,
                fromto=[-0.5 * tine_length, y, 0, 0.5 * tine_length, y, 0],
                size=[tine_radius, 0, 0],
                friction=[friction, 0.005, 0.0001],
                margin=CONTACT_MARGIN,
                solref=list(CONTACT_SOLREF),
                solimp=list(CONTACT_SOLIMP),
            )
            geom.condim = 3 if friction > 0 else 1

    model = build_rod_model([rod], timestep=timestep, extra=add_tine)
    data = mujoco.MjData(model)
    tine_geoms = {model.geom(f"tine{k}").id for k in range(len(columns))}
    below = length - run - start_turn * arc_per_turn
    travel = below + 0.02 if travel is None else float(travel)
    steps = round(travel / (speed * timestep))
    mujoco.mj_forward(model, data)
    root_z = float(RodView(model, "curl").vertices(data)[0, 2])
    f6 = np.zeros(6)
    depth, force = np.empty(steps + 1), np.empty(steps + 1)
    for k in range(steps + 1):
        fz = 0.0
        for i in range(data.ncon):
            c = data.contact[i]
            if c.geom1 not in tine_geoms and c.geom2 not in tine_geoms:
                continue
            mujoco.mj_contactForce(model, data, i, f6)
            f_on_geom2 = c.frame.reshape(3, 3).T @ f6[:3]
            fz += f_on_geom2[2] if c.geom2 in tine_geoms else -f_on_geom2[2]
        depth[k] = root_z - float(data.mocap_pos[0, 2])
        force[k] = fz  # upward pull of the wire on the tine (it resists the descent)
        data.mocap_pos[0, 2] = z0 - speed * timestep * (k + 1)
        mujoco.mj_step(model, data)
    # What a 10 Hz load cell reads: means over 0.1 s windows (a single step's contact force spikes when the springing
    # free end hits the tine).
    window = max(1, round(LOAD_CELL_PERIOD / timestep))
    n = (steps + 1) // window
    depth = depth[: n * window].reshape(n, window).mean(axis=1)
    force = force[: n * window].reshape(n, window).mean(axis=1)
    peel = peel_force(curl_radius, pitch, young=young, strand_radius=strand_radius)
    return CurlPullResult(depth, force, peel, friction)
