"""Hair strands and other slender rods in MuJoCo 4.0 (which removed ``<composite>`` and the cable plugin).

One contract, two representations, chosen per rod by :attr:`RodSpec.kind`:

* ``"chain"`` (default, :mod:`.chain`): a chain of capsule bodies with three hinges a vertex (twist + two bending
  axes), solved with PGS under an iteration cap — what the cable composite expanded to.
* ``"flex"`` (:mod:`.flex`): a 1D flex with DER elasticity and an edge equality, solved with Newton — the first
  representation, kept for side-by-side benchmarks and the studies validated on it.

:func:`add_rod` builds either into any :class:`mujoco.MjSpec`, :func:`configure_rod_options` sets the solver the
kind needs, :func:`build_rod_model` compiles a bare rod model for studies and tests, and :class:`RodView` reads
the centerline of either. Validation against beam and spring theory: :mod:`hairbrush_env.studies.rod_validation`;
measured accuracy and cost of both kinds: ``docs/rods.md``.

Rod reference frames of flexes live in ``data.plastic``; save/restore with ``mjtState.mjSTATE_INTEGRATION``
(which includes ``mjSTATE_PLASTIC``) or resets are not exact.
"""

from .build import DEFAULT_TIMESTEP, add_rod, build_rod_model, configure_rod_options
from .chain import CHAIN_SOLVER_ITERATIONS, add_chain_rod, chain_frames
from .flex import FRICTION_TORSION_ROLL, GHOST_FRACTION, add_flex_rod
from .spec import (
    DEFAULT_N_EDGES,
    EDGE_SOLREF,
    ROD_KINDS,
    RodKind,
    RodSpec,
    bending_stiffness,
    polyline_length,
    resample_polyline,
    resolve_body,
    shear_modulus,
    straight_rod_points,
    twisting_stiffness,
)
from .view import RodView, rod_length, rod_vertices

__all__ = [
    "CHAIN_SOLVER_ITERATIONS",
    "DEFAULT_N_EDGES",
    "DEFAULT_TIMESTEP",
    "EDGE_SOLREF",
    "FRICTION_TORSION_ROLL",
    "GHOST_FRACTION",
    "ROD_KINDS",
    "RodKind",
    "RodSpec",
    "RodView",
    "add_chain_rod",
    "add_flex_rod",
    "add_rod",
    "bending_stiffness",
    "build_rod_model",
    "chain_frames",
    "configure_rod_options",
    "polyline_length",
    "resample_polyline",
    "resolve_body",
    "rod_length",
    "rod_vertices",
    "shear_modulus",
    "straight_rod_points",
    "twisting_stiffness",
]
