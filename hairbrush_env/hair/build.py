"""Building a wig into a MuJoCo spec: every strand a clamped rod with the wisps' contact parameters."""

from __future__ import annotations

from collections.abc import Sequence

import mujoco
import numpy as np

from .. import collision, rods
from .config import WigConfig, get_wig
from .layout import WigLayout, wig_layout

__all__ = ["CONTACT_MARGIN", "CONTACT_SOLIMP", "CONTACT_SOLREF", "HAIR_GEOM_GROUP", "add_wig", "strand_rod"]

HAIR_GEOM_GROUP = 1
"""Visualisation group of the strands (visible by default; the scene's parts use groups 2–5)."""

# Contact parameters for thin rods. rods.py measured rod-rod penetration ≤ 10 µm with solref 0.004 for free
# rods, but a wisp trapped between bristles is held by its (much stiffer, 1e-4) edge equality, and the solver then
# lets the 0.004 contact yield: strands were pulled through 1.5 mm bristles (centerline distance 0). With 1e-3
# (and refsafe disabled by the scene, which would otherwise soften it back to ~2 dt) the hair–bristle centerline
# distance stayed ≥ 0.7 mm (> the 1.15 mm half-sum of radii in most samples; see the scene tests).
CONTACT_SOLREF = (1e-3, 1.0)
CONTACT_SOLIMP = (0.95, 0.99, 1e-4, 0.5, 2.0)
# Contact margin of each wisp geom. MuJoCo 4.0.1 ADDS the margins of a contact's two geoms, so two wisps touch from
# 2 × 0.5 = 1 mm surface gap and a wisp and a bristle from 0.5 + 1 = 1.5 mm (scene.TOOL_CONTACT_MARGIN); contacts hold
# their load as a stiff spring about ``dist = margin``. Without it a coily wisp pair under full-stroke clamp loads sank
# 1.3 mm into each other (issue #3); with it the centerline distance stays above half the sum of radii
# (tests/test_scene.py::test_no_pass_through_*).
CONTACT_MARGIN = 5e-4


def add_wig(
    spec: mujoco.MjSpec,
    wig: str | WigConfig,
    *,
    parent_body: mujoco.MjsBody | str,
    root_offset: Sequence[float] = (0.0, 0.0, 0.0),
    prefix: str = "hair",
    hair_hair: bool = True,
) -> WigLayout:
    """Add every strand of ``wig`` as a clamped rod under ``parent_body``.

    Parameters
    ----------
    spec : mujoco.MjSpec
        Target spec (call :func:`hairbrush_env.rods.configure_rod_options` on it too, with the wig's ``rod_kind``).
    wig : str or WigConfig
        Preset name or config.
    parent_body : MjsBody or str
        Body holding the roots (e.g. the head's ``scalp``); its frame must have z up.
    root_offset : sequence of float
        Position of the root plane's centre in ``parent_body`` coordinates (e.g. the scalp site).
    prefix : str
        Strand names are ``<prefix><k>``.
    hair_hair : bool
        Hair–hair contact (``conaffinity`` includes HAIR). Without it strands pass through each other.

    Returns
    -------
    WigLayout
        The layout (in root-plane coordinates; add ``root_offset`` and the parent pose for world coordinates).
    """
    cfg = get_wig(wig)
    layout = wig_layout(cfg, prefix=prefix)
    off = np.asarray(root_offset, dtype=float).reshape(3)
    for name, curve in zip(layout.names, layout.curves, strict=True):
        rods.add_rod(spec, strand_rod(cfg, name, curve + off, hair_hair=hair_hair), parent=parent_body)
    return layout


def strand_rod(
    cfg: WigConfig,
    name: str,
    points: np.ndarray,
    *,
    hair_hair: bool = True,
    root_rest_turn: float | None = None,
) -> rods.RodSpec:
    """One strand of ``cfg`` along ``points`` (in its parent's frame): the wig's material, damping, mass scaling,
    contacts and collision bits. ``root_rest_turn``: the turn of its stress-free shape about the root (``None``: the
    wig's ``rest_splay`` for curled strands, 0 for straight ones; 0: stress-free as built)."""
    if root_rest_turn is None:
        # straight strands have no curl whose axis could move: turning them would only twist the root
        root_rest_turn = float(cfg.rest_splay) if cfg.curliness > 0 else 0.0
    contype, conaffinity = collision.HAIR_GEOM_SELF_COLLIDING if hair_hair else collision.HAIR_GEOM
    return rods.RodSpec(
        name=name,
        points=points,
        radius=cfg.strand_radius,
        young=cfg.young_modulus,
        density=cfg.density,
        mass_scale=cfg.mass_scale if cfg.rod_kind == "chain" else 1.0,
        damping=cfg.damping,
        quadratic_damping=cfg.quadratic_damping,
        friction=cfg.friction,
        rgba=cfg.rgba,
        contype=contype,
        conaffinity=conaffinity,
        condim=3,
        contact_solref=CONTACT_SOLREF,
        contact_solimp=CONTACT_SOLIMP,
        margin=CONTACT_MARGIN,
        group=HAIR_GEOM_GROUP,
        kind=cfg.rod_kind,
        selfcollide=cfg.self_collision,
        root_rest_turn=float(root_rest_turn),
        root_twist_first=cfg.root_twist_first,  # WigConfig allows it on chains only
    )
