"""Static validation of the rod models against beam and spring theory (both rod kinds, side by side).

* :func:`cantilever_study`: tip deflection of a clamped straight rod under gravity (``w L⁴ / 8 E I``) or an end
  load (``F L³ / 3 E I``), Euler–Bernoulli.
* :func:`helix_study`: axial stiffness of a close-coiled helical spring, ``k = G d⁴ / (8 D³ N)`` (Wahl), the test
  that matters for curls: it loads the coil mostly in torsion.

Measured tables: ``docs/rods.md`` (``python scripts/benchmark_sim.py --only validation``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Literal

import mujoco
import numpy as np

from ..rods import (
    DEFAULT_TIMESTEP,
    RodKind,
    RodSpec,
    RodView,
    bending_stiffness,
    build_rod_model,
    straight_rod_points,
)

__all__ = ["StudyResult", "cantilever_study", "helix_points", "helix_study"]


@dataclass(frozen=True)
class StudyResult:
    """Outcome of a static validation study (see :func:`cantilever_study`, :func:`helix_study`).

    Attributes
    ----------
    n_edges : int
        Edges of the simulated rod.
    measured, expected : float
        Simulated and analytic quantity (tip deflection [m] or spring stiffness [N/m]).
    rel_error : float
        ``measured / expected - 1``.
    length_error : float
        Relative change of the centerline length at the end of the run.
    steps_per_second : float
        Simulation speed of the run, steps per CPU second (single thread).
    """

    n_edges: int
    measured: float
    expected: float
    rel_error: float
    length_error: float
    steps_per_second: float


def _settle(
    model: mujoco.MjModel, data: mujoco.MjData, seconds: float, view: RodView, tip_force: np.ndarray | None
) -> float:
    steps = max(1, round(seconds / model.opt.timestep))
    t0 = time.process_time()
    for _ in range(steps):
        if tip_force is not None:
            view.set_tip_force(data, tip_force)
        mujoco.mj_step(model, data)
    mujoco.mj_forward(model, data)  # positions of the final state (mj_step leaves them one step stale)
    return steps / max(time.process_time() - t0, 1e-9)


def cantilever_study(
    n_edges: int,
    *,
    kind: RodKind = "chain",
    load: Literal["gravity", "tip"] = "gravity",
    length: float = 0.2,
    radius: float = 1e-3,
    young: float = 10e9,
    density: float = 1300.0,
    tip_force: float = 3e-3,
    timestep: float = DEFAULT_TIMESTEP,
    settle: float = 1.5,
    mass_scale: float = 1.0,
) -> StudyResult:
    """Static tip deflection of a clamped straight rod vs Euler–Bernoulli.

    ``load="gravity"``: ``w L⁴ / (8 E I)`` with ``w = ρ g π r²``; ``load="tip"``: force ``tip_force`` at the free end
    (gravity off), ``F L³ / (3 E I)``. The defaults give 1.0 mm = 0.5 % of ``L`` (small-deflection regime).
    ``mass_scale``: :attr:`hairbrush_env.rods.RodSpec.mass_scale` (the weight, and so the deflection, stay the same).
    """
    g = 9.81
    rod = RodSpec(
        name="cantilever",
        points=straight_rod_points([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], length, n_edges),
        radius=radius,
        young=young,
        density=density,
        kind=kind,
        mass_scale=mass_scale,
    )
    gravity = (0.0, 0.0, -g) if load == "gravity" else (0.0, 0.0, 0.0)
    model = build_rod_model([rod], timestep=timestep, gravity=gravity)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    view = RodView(model, "cantilever")
    ei = bending_stiffness(young, radius)
    if load == "gravity":
        expected = rod.linear_density * g * length**4 / (8.0 * ei)
        force = None
    else:
        expected = tip_force * length**3 / (3.0 * ei)
        force = np.array([0.0, 0.0, -tip_force])
    sps = _settle(model, data, settle, view, force)
    measured = -float(view.vertices(data)[-1, 2])
    return StudyResult(
        n_edges, measured, expected, measured / expected - 1.0, view.length(data) / length - 1.0, sps
    )


def helix_points(
    edges_per_turn: int, *, turns: int = 3, coil_radius: float = 0.01, pitch: float = 0.004
) -> np.ndarray:
    """The test spring: ``turns`` coil turns, then a straight 3-edge arm radially in to the spring axis."""
    psi = np.linspace(0.0, 2.0 * math.pi * turns, turns * edges_per_turn + 1)
    coil = np.stack(
        [coil_radius * np.cos(psi), coil_radius * np.sin(psi), pitch * psi / (2.0 * math.pi)], axis=1
    )
    s = np.linspace(1.0, 0.0, 4)[1:]
    arm = np.stack([coil[-1, 0] * s, coil[-1, 1] * s, np.full(3, coil[-1, 2])], axis=1)
    return np.vstack([coil, arm])


def helix_study(
    edges_per_turn: int,
    *,
    kind: RodKind = "chain",
    turns: int = 3,
    coil_radius: float = 0.01,
    pitch: float = 0.004,
    radius: float = 1e-3,
    young: float = 1e9,
    poisson: float = 0.49,
    density: float = 1300.0,
    timestep: float = DEFAULT_TIMESTEP,
    settle: float = 1.0,
) -> StudyResult:
    """Axial stiffness of a close-coiled helical spring vs ``k = G d⁴ / (8 D³ N)`` (gravity off).

    The coil is clamped at its first edge; its far end turns radially inward into a straight 3-edge arm so that the
    axial force (1 % of the coil height worth of extension) acts on the spring axis — a force at the wire would also
    tilt the spring. The arm's own cantilever compliance ``R³ / (3 E I)`` is subtracted from the measured extension.
    """
    pts = helix_points(edges_per_turn, turns=turns, coil_radius=coil_radius, pitch=pitch)
    rod = RodSpec(
        name="helix", points=pts, radius=radius, young=young, poisson=poisson, density=density, kind=kind
    )
    model = build_rod_model([rod], timestep=timestep, gravity=(0.0, 0.0, 0.0))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    view = RodView(model, "helix")
    expected = rod.shear_modulus * (2.0 * radius) ** 4 / (8.0 * (2.0 * coil_radius) ** 3 * turns)
    force = 0.01 * pitch * turns * expected
    sps = _settle(model, data, settle, view, np.array([0.0, 0.0, force]))
    x = view.vertices(data)
    extension = float(x[-1, 2] - pts[-1, 2]) - force * coil_radius**3 / (
        3.0 * bending_stiffness(young, radius)
    )
    measured = force / extension
    return StudyResult(
        rod.n_edges, measured, expected, measured / expected - 1.0, view.length(data) / rod.length - 1.0, sps
    )
