"""A tine pulled through a curl is a screw: it passes only if the curl can turn, and friction decides whether it can.

A curl of radius ``R`` and pitch ``P`` crosses a tine that lies across its axis at the thread's lead angle λ,
``tan λ = P / (2π R)``; the tine pressing down on the wire is a nut pressing on a screw's thread. A screw free to turn
is back-driven by an axial load only if ``tan λ > μ`` (its lead angle above the friction angle); otherwise it is
self-locking, however hard it is pushed. For a curl this decides how a comb goes through it: below the threshold the
curl turns and the tine threads down through its turns; above it the curl locks on the tine and can only be dragged
down with it and drawn straight, which is what sets the force of a stroke through the curliest presets under
``HairBrush-v7`` (tine friction 0.3 against ``tan λ`` 0.20 on coily, 0.25 on tight_curl, 0.32 on curly).

:func:`tine_through_helix` checks MuJoCo's contacts against that threshold with the hair's contact parameters: a rigid
helix of capsules free to turn about its axis (and nothing else), a horizontal capsule tine across the axis pushed
down by a constant force. ``docs/detangling.md``, *HairBrush-v8*, has what it changes on the wigs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from ..hair import CONTACT_SOLIMP, CONTACT_SOLREF

__all__ = ["ScrewResult", "lead_tangent", "tine_through_helix"]


def lead_tangent(curl_radius: float, pitch: float) -> float:
    """``tan λ = P / (2π R)``: the friction coefficient below which a curl turns round a tine pushed along its axis."""
    return pitch / (2.0 * math.pi * curl_radius)


@dataclass(frozen=True)
class ScrewResult:
    """Outcome of :func:`tine_through_helix`."""

    friction: float
    lead_tangent: float
    #: How far the tine went down [pitches] and how far the helix turned [turns] in the given time.
    descent: float
    turns: float

    @property
    def locked_expected(self) -> bool:
        """The analytic answer: the thread is self-locking when ``μ ≥ tan λ``."""
        return self.friction >= self.lead_tangent


def _helix_spec(
    curl_radius: float,
    pitch: float,
    turns: float,
    wire_radius: float,
    tine_radius: float,
    friction: float,
    push: float,
) -> mujoco.MjSpec:
    spec = mujoco.MjSpec()
    spec.option.timestep = 1e-3
    spec.option.gravity = [0.0, 0.0, 0.0]
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE  # the hair scenes' integrator
    world = spec.worldbody
    helix = world.add_body(name="helix")
    # A hinge about the axis and nothing else: the helix can turn, not fall or tilt (the clamp of a curl's upper part).
    helix.add_joint(name="turn", type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0, 0, 1], damping=1e-4)
    edges_per_turn = 24
    n = max(2, round(turns * edges_per_turn))
    phi = np.linspace(0.0, 2.0 * math.pi * turns, n + 1)
    pts = np.stack(
        [curl_radius * np.cos(phi), curl_radius * np.sin(phi), -pitch * phi / (2.0 * math.pi)], axis=1
    )
    for k in range(n):
        geom = helix.add_geom(
            type=mujoco.mjtGeom.mjGEOM_CAPSULE,
            fromto=[*pts[k], *pts[k + 1]],
            size=[wire_radius, 0, 0],
            density=1300.0,
            friction=[friction, 0.005, 0.0001],
            solref=list(CONTACT_SOLREF),
            solimp=list(CONTACT_SOLIMP),
            contype=1,
            conaffinity=2,
        )
        geom.condim = 3
    # The tine lies along x through the axis, between the first and second crossings of the plane y = 0 (at x = +R,
    # z = 0 and x = -R, z = -P/2), so that it rests on the wire at x = -R, half a pitch down.
    tine = world.add_body(name="tine", pos=[0.0, 0.0, -0.25 * pitch])
    # Damped so that a free tine sinks at push / damping = 0.05 m/s (a slow stroke) instead of tunnelling through the
    # wire in one step.
    tine.add_joint(name="slide", type=mujoco.mjtJoint.mjJNT_SLIDE, axis=[0, 0, 1], damping=push / 0.05)
    half = 1.5 * curl_radius
    tine_geom = tine.add_geom(
        type=mujoco.mjtGeom.mjGEOM_CAPSULE,
        fromto=[-half, 0, 0, half, 0, 0],
        size=[tine_radius, 0, 0],
        # A comb's tine is moved by an arm: heavy next to the hair, so that the contacts' impedance (which scales
        # with the bodies' masses) holds the wire instead of letting a light tine sink through it.
        mass=0.05,
        friction=[friction, 0.005, 0.0001],
        contype=2,
        conaffinity=1,
    )
    tine_geom.condim = 3
    spec.add_actuator(name="push", target="slide", trntype=mujoco.mjtTrn.mjTRN_JOINT, gear=[1, 0, 0, 0, 0, 0])
    return spec


def tine_through_helix(
    friction: float,
    *,
    curl_radius: float = 0.009,
    pitch: float = 0.01125,
    turns: float = 4.0,
    wire_radius: float = 8e-4,
    tine_radius: float = 1e-3,
    push: float = 1.0,
    seconds: float = 1.0,
) -> ScrewResult:
    """Push a horizontal tine down through a rigid helix free to turn about its axis, with a constant force ``push``
    [N], for ``seconds``; return how far it went (pitches) and how far the helix turned (turns).

    Friction ``friction`` on both geoms (MuJoCo takes the larger), the hair's contact ``solref``/``solimp``, elliptic
    cones, the ``discrete`` integrator at a 1 ms step: the settings of a stroke's hair contacts. The defaults are
    coily's curl under ``HairBrush-v7`` (R 9 mm, R/P 0.8, ``tan λ`` 0.199) with a wisp's radius. A turning helix lets
    the tine through at ``turns ≈ descent``; a locked one holds it within the contacts' softness.
    """
    if not (friction >= 0.0 and curl_radius > 0.0 and pitch > 0.0 and push > 0.0 and seconds > 0.0):
        raise ValueError(
            f"tine_through_helix: friction {friction!r} must be >= 0 and curl_radius {curl_radius!r}, pitch "
            f"{pitch!r}, push {push!r}, seconds {seconds!r} > 0"
        )
    if pitch < 2.0 * (wire_radius + tine_radius) + 1e-4:
        raise ValueError(f"tine_through_helix: pitch {pitch!r} leaves no room for the tine between the turns")
    model = _helix_spec(curl_radius, pitch, turns, wire_radius, tine_radius, friction, push).compile()
    data = mujoco.MjData(model)
    slide = model.joint("slide").qposadr[0]
    turn = model.joint("turn").qposadr[0]
    steps = round(seconds / model.opt.timestep)
    for _ in range(steps):
        data.ctrl[0] = -push
        mujoco.mj_step(model, data)
        # Stop before the tine runs out of the bottom of the helix (a turning helix threads it down).
        if -data.qpos[slide] > (turns - 1.0) * pitch:
            break
    descent = -float(data.qpos[slide]) / pitch
    turned = abs(float(data.qpos[turn])) / (2.0 * math.pi)
    return ScrewResult(friction, lead_tangent(curl_radius, pitch), descent, turned)
