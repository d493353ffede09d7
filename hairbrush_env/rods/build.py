"""Putting rods into a spec: one entry point for both kinds, the options they need, a bare rod model."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import mujoco

from .chain import CHAIN_SOLVER_ITERATIONS, add_chain_rod
from .flex import add_flex_rod
from .spec import ROD_KINDS, RodKind, RodSpec

__all__ = ["DEFAULT_TIMESTEP", "add_rod", "build_rod_model", "configure_rod_options"]

DEFAULT_TIMESTEP = 2e-3
"""Step [s] of bare rod models; rod statics are step-independent from 1 to 10 ms (chain) and 32 ms (flex)."""


def add_rod(
    spec: mujoco.MjSpec,
    rod: RodSpec,
    *,
    parent: mujoco.MjsBody | str | None = None,
) -> mujoco.MjsBody | mujoco.MjsFlex:
    """Add ``rod`` to ``spec`` as its ``kind`` says: a body chain (:func:`~hairbrush_env.rods.chain.add_chain_rod`,
    returns the root body) or a DER flex (:func:`~hairbrush_env.rods.flex.add_flex_rod`, returns the flex)."""
    if rod.kind == "chain":
        return add_chain_rod(spec, rod, parent=parent)
    return add_flex_rod(spec, rod, parent=parent)


def configure_rod_options(
    spec: mujoco.MjSpec, *, timestep: float = DEFAULT_TIMESTEP, kind: RodKind = "chain"
) -> None:
    """Set the global options the rods of ``kind`` need.

    * ``integrator = discrete`` for both: it integrates the rod elasticity implicitly in position, so statics do
      not depend on the step (the ``implicit`` integrators reject flex elasticity).
    * ``"chain"``: ``solver = PGS`` capped at :data:`~hairbrush_env.rods.chain.CHAIN_SOLVER_ITERATIONS`; Newton's
      contact Jacobians span whole chains and cost ~8× more per step in a stroke (``docs/rods.md``).
    * ``"flex"``: ``solver = Newton`` (PGS does not support flex; 0–1 iterations per step on rods).
    * ``refsafe`` is left as is here (the scene disables it for its stiff hair contacts, see ``scene_build.py``).

    Parameters
    ----------
    spec : mujoco.MjSpec
        Spec to modify in place.
    timestep : float
        Simulation step [s].
    kind : {"chain", "flex"}
        Rod representation of the spec's rods.
    """
    if not (math.isfinite(timestep) and timestep > 0):
        raise ValueError(f"timestep must be > 0, got {timestep!r}")
    if kind not in ROD_KINDS:
        raise ValueError(f"kind must be one of {ROD_KINDS}, got {kind!r}")
    spec.option.timestep = timestep
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    if kind == "chain":
        spec.option.solver = mujoco.mjtSolver.mjSOL_PGS
        spec.option.iterations = CHAIN_SOLVER_ITERATIONS
    else:
        spec.option.solver = mujoco.mjtSolver.mjSOL_NEWTON


def build_rod_model(
    rods: Sequence[RodSpec],
    *,
    timestep: float = DEFAULT_TIMESTEP,
    gravity: Sequence[float] = (0.0, 0.0, -9.81),
    extra: Callable[[mujoco.MjSpec], None] | None = None,
) -> mujoco.MjModel:
    """Compile a bare model containing only ``rods`` (clamped to the world), for studies and tests.

    The solver follows the rods' kind (:func:`configure_rod_options`); a model with any flex rod uses the flex
    settings, which chains also run under.

    Parameters
    ----------
    rods : sequence of RodSpec
        Rods to add (names must be unique).
    timestep : float
        Simulation step [s].
    gravity : sequence of float
        Gravity vector [m/s²].
    extra : callable, optional
        ``extra(spec)`` is called after the rods are added and before compiling (add obstacles, loads, ...).

    Returns
    -------
    mujoco.MjModel
    """
    spec = mujoco.MjSpec()
    spec.modelname = "rods"
    kind: RodKind = "flex" if any(r.kind == "flex" for r in rods) else "chain"
    configure_rod_options(spec, timestep=timestep, kind=kind)
    spec.option.gravity = [float(g) for g in gravity]
    for rod in rods:
        add_rod(spec, rod)
    if extra is not None:
        extra(spec)
    return spec.compile()
