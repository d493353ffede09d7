"""Random packings of rigid rods ("bird's nest", thesis chapter 4): generation, structure and mechanics.

Rigid steel rods of length L and diameter d (aspect ratio α = L/d) are dropped into a cylindrical container in
MuJoCo, jostled and settled (thesis §4.5.1); the packings are measured (packing fraction, contact numbers,
orientations; Figs 4.5, 4.7, 4.8) and loaded mechanically (piston compression, Figs 4.2, 4.6; pulling glued layers
apart, Fig. 5.3). One concept a module:

* :mod:`.packing` — :class:`Packing`, the rods as data, with NPZ/CSV I/O (:func:`load_packing`),
  :func:`pile_height` and the physical constants;
* :mod:`.structure` — measurements on the geometry: :func:`packing_fraction` and its radial profile,
  :func:`contact_numbers`, :func:`orientations`, Philipse's random contact equation;
* :mod:`.pile` — the MuJoCo model (:class:`SimParams`, :class:`Pile`): its model choices and their reasons;
* :mod:`.generate` — :func:`generate_packing`: deposition in batches, jostling, settling; determinism;
  :func:`sweep_pile`, one pile of an aspect-ratio sweep (``hairbrush rodpile sweep``);
* :mod:`.mechanics` — :func:`compress` and :func:`tension` with their results;
* :mod:`.plots` — the figures (``plot_*``);
* :mod:`.summary` — :func:`pile_summary`, a pile's structure in numbers (``hairbrush rodpile summary``).

The study, its results and their comparison with the thesis: ``docs/rod_piles.md``.
"""

from .generate import generate_packing, sweep_pile
from .mechanics import CompressionResult, TensionResult, compress, tension
from .packing import GRAVITY, STEEL_DENSITY, Packing, load_packing, pile_height
from .pile import Pile, SimParams, poses_from_endpoints
from .plots import plot_compression, plot_phi_alpha, plot_structure, plot_tension
from .structure import (
    bulk_rods,
    contact_numbers,
    mean_abs_sin,
    orientations,
    packing_fraction,
    phi_seen,
    philipse_contact_number,
    radial_packing_fraction,
    random_rod_gas,
)
from .summary import pile_summary

__all__ = [
    "GRAVITY",
    "STEEL_DENSITY",
    "CompressionResult",
    "Packing",
    "Pile",
    "SimParams",
    "TensionResult",
    "bulk_rods",
    "compress",
    "contact_numbers",
    "generate_packing",
    "load_packing",
    "mean_abs_sin",
    "orientations",
    "packing_fraction",
    "phi_seen",
    "philipse_contact_number",
    "pile_height",
    "pile_summary",
    "plot_compression",
    "plot_phi_alpha",
    "plot_structure",
    "plot_tension",
    "poses_from_endpoints",
    "radial_packing_fraction",
    "random_rod_gas",
    "sweep_pile",
    "tension",
]
