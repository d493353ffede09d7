"""One entwined pair of a wig, alone, combed by three tines: the per-pair force of a stroke in a second of CPU.

A stroke through the curled presets reads about the same force from every pair whose two strands straddle the
comb's middle tine (coily: 1.1–1.3 N a pair, ``docs/detangling.md``, *What carries coily's first stroke from the
roots*). :class:`PairOnComb` builds one such pair with the wig's own builder (:func:`~hairbrush_env.hair.add_wig`
with ``n_strands = 2``: the group axis under the middle tine, the roots across the tines, the physics version's rest
shapes, contacts, damping, mass scaling and air drag) and a rigid comb of the version's three middle tines, moved
kinematically, so that strokes from any depth below the roots, one after another, cost about a second each instead
of a minute for the whole wig. ``lone=True`` makes the second strand a ghost that touches nothing: what one curl held
by its root costs a tine by itself; ``curves`` replaces the wig's pair by any two strands (e.g. a braided pair,
``scripts/probe_braided_pair.py``) of the wig's material.

For scale, :func:`peel_force` is what drawing a curl straight over a tine would cost without friction, its bending
energy per length ``E I κ₀² / 2`` (``κ₀ = R / (R² + (P / 2π)²)``): the force of a curl that could neither turn round
the tine nor swing off it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import mujoco
import numpy as np

from .. import collision
from ..hair import CONTACT_SOLIMP, CONTACT_SOLREF, WigConfig, add_wig, strand_rod
from ..hair.drag import StrandDrag
from ..hair.shaking import shake
from ..physics import get_physics
from ..rods import RodView, add_rod, bending_stiffness, configure_rod_options
from ..scene_build import TOOL_CONTACT_MARGIN
from ..topology import linking_number

__all__ = ["LOAD_CELL_PERIOD", "PairOnComb", "PairStroke", "curl_curvature", "peel_force"]

LOAD_CELL_PERIOD = 0.1
"""Averaging window [s] of the force samples: the brush's load cell reads at 10 Hz."""


def curl_curvature(curl_radius: float, pitch: float) -> float:
    """Curvature κ₀ [1/m] of a helix of radius ``curl_radius`` and pitch ``pitch``."""
    b = pitch / (2.0 * math.pi)
    return curl_radius / (curl_radius**2 + b**2)


def peel_force(curl_radius: float, pitch: float, *, young: float, strand_radius: float) -> float:
    """``E I κ₀² / 2`` [N]: the frictionless force to draw a root-held curl straight over a tine."""
    return 0.5 * bending_stiffness(young, strand_radius) * curl_curvature(curl_radius, pitch) ** 2


@dataclass(frozen=True)
class PairStroke:
    """One stroke of :meth:`PairOnComb.stroke`: the comb's depth below the roots [m] and the vertical force of the
    hair on it [N], each averaged over 0.1 s (a 10 Hz load cell's samples), and the pair's link after the stroke."""

    start_depth: float
    depth: np.ndarray
    force: np.ndarray
    link_after: float

    @property
    def max_force(self) -> float:
        """Largest 10 Hz force sample [N] (0 if the stroke was shorter than one sample)."""
        return float(self.force.max()) if self.force.size else 0.0


class PairOnComb:
    """One entwined pair of ``wig`` under ``physics`` and a comb of three rigid tines (``docs/detangling.md``).

    Parameters
    ----------
    wig : str or WigConfig
        A preset (or held-out) name or config; its strand count is replaced by 2.
    physics : str
        Physics version (``HairBrush-vN``) whose wig fields, comb (column pitch, tine radius and length, friction),
        contact step and stroke speed are used.
    lone : bool
        Make the second strand touch nothing (one curl held by its root, alone with the comb).
    settle : float
        Seconds the pair hangs under gravity, the comb out of the way, before the first stroke.
    shake_seed : int or None
        Before that, shake the pair as the wig's pre-brushed preparation does with this seed
        (:func:`~hairbrush_env.hair.shaking.shake`); ``None``: start from the pair as built.
    stroke_speed : float or None
        Pull speed [m/s]; ``None``: the version's (0.1 m/s).
    curves : sequence of two (n, 3) arrays, optional
        Build these two strands (roots at z = 0, the comb's middle tine along x through the origin) with the wig's
        material, contacts and collision bits, stress-free as given, instead of the wig's own pair.
    """

    #: Depth of a full stroke's start below the roots [m] (the scene's tines go in 8 mm down at b_l = 1).
    TOP = 0.008

    def __init__(self, wig: str | WigConfig = "coily", *, physics: str = "v8", lone: bool = False,
                 settle: float = 1.0, shake_seed: int | None = None,
                 stroke_speed: float | None = None,
                 curves: Sequence[np.ndarray] | None = None) -> None:  # fmt: skip
        if not (math.isfinite(settle) and settle >= 0.0):
            raise ValueError(f"PairOnComb: settle must be a finite number >= 0 [s], got {settle!r}")
        version = get_physics(physics)
        scene = version.scene_config(wig)
        self.wig = scene.wig.replace(n_strands=2)
        if self.wig.curliness <= 0.0:
            raise ValueError(f"PairOnComb: wig {self.wig.name!r} is straight; the study needs a curled wig")
        brush = scene.brush
        self.speed = float(scene.stroke_speed if stroke_speed is None else stroke_speed)
        if not (math.isfinite(self.speed) and self.speed > 0.0):
            raise ValueError(f"PairOnComb: stroke_speed must be > 0 [m/s], got {stroke_speed!r}")
        self.approach_speed = float(scene.approach_speed)
        # Inserted along the tines (x) from where they clear the pair's coils, as the arm puts the comb in.
        self._clear_x = -(0.5 * brush.tine_length + self.wig.curl_radius + 0.01)
        spec = mujoco.MjSpec()
        configure_rod_options(spec, timestep=float(scene.contact_timestep), kind=self.wig.rod_kind)
        spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
        scalp = spec.worldbody.add_body(name="scalp")
        if curves is None:
            names = add_wig(spec, self.wig, parent_body=scalp).names
        else:
            if len(curves) != 2:
                raise ValueError(f"PairOnComb: curves must be two strands, got {len(curves)}")
            names = ("strand0", "strand1")
            for name, points in zip(names, curves, strict=True):
                add_rod(
                    spec,
                    strand_rod(self.wig, name, np.asarray(points, float), root_rest_turn=0.0),
                    parent=scalp,
                )
        comb = spec.worldbody.add_body(name="comb", mocap=True)
        half = 0.5 * brush.tine_length
        for k, y in enumerate((-brush.column_pitch, 0.0, brush.column_pitch)):
            geom = comb.add_geom(
                name=f"tine{k}",
                type=mujoco.mjtGeom.mjGEOM_CAPSULE,
                fromto=[-half, y, 0.0, half, y, 0.0],
                size=[brush.tine_radius, 0.0, 0.0],
                friction=[brush.friction, 0.005, 0.0001],
                margin=TOOL_CONTACT_MARGIN,
                solref=list(CONTACT_SOLREF),
                solimp=list(CONTACT_SOLIMP),
            )
            geom.contype, geom.conaffinity = collision.BRISTLE_GEOM
            geom.condim = 3
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        self._views = [RodView(self.model, name) for name in names]
        self._tines = frozenset(self.model.geom(f"tine{k}").id for k in range(3))
        if lone:
            ghost = np.isin(self.model.geom_bodyid, self._views[1].bodies)
            self.model.geom_contype[ghost] = 0
            self.model.geom_conaffinity[ghost] = 0
        bodies = np.concatenate([v.bodies for v in self._views])
        self._drag = StrandDrag.of_wig(self.model, bodies, self.wig)
        self._aside()
        if shake_seed is not None:
            shake(self.model, self.data, self.wig, int(shake_seed), strand_bodies=bodies)
        self._run(settle)

    def _aside(self) -> None:
        self.data.mocap_pos[0] = [0.0, 1.0, 0.0]  # a metre along the curtain: out of reach

    def _step(self) -> None:
        if self._drag is not None:
            self._drag.apply(self.data)
        mujoco.mj_step(self.model, self.data)

    def _run(self, seconds: float) -> None:
        for _ in range(round(seconds / self.model.opt.timestep)):
            self._step()

    def curves(self) -> list[np.ndarray]:
        """The two strands' centerlines (vertices, world frame; the roots at z = 0)."""
        return [view.vertices(self.data) for view in self._views]

    def link(self) -> float:
        """``|Lk|`` of the pair (open-curve Gauss integral)."""
        a, b = self.curves()
        return abs(linking_number(a, b, closed=False))

    def hanging_length(self) -> float:
        """Depth of the lowest vertex below the roots [m]."""
        return -min(float(c[:, 2].min()) for c in self.curves())

    def start_depth(self, b_l: float) -> float:
        """Where a stroke of normalized length ``b_l`` puts the comb in [m below the roots]: :attr:`TOP` at
        ``b_l = 1``, the lowest strand point at 0, linear between (as the scene's start heights)."""
        if not (math.isfinite(b_l) and 0.0 < b_l <= 1.0):
            raise ValueError(f"PairOnComb.start_depth: b_l must be in (0, 1], got {b_l!r}")
        return self.TOP + (1.0 - b_l) * (self.hanging_length() - self.TOP)

    def _tine_force(self, f6: np.ndarray) -> float:
        fz = 0.0
        for i in range(self.data.ncon):
            c = self.data.contact[i]
            if c.geom1 not in self._tines and c.geom2 not in self._tines:
                continue
            mujoco.mj_contactForce(self.model, self.data, i, f6)
            on_geom2 = c.frame.reshape(3, 3).T @ f6[:3]
            fz += on_geom2[2] if c.geom2 in self._tines else -on_geom2[2]
        return fz  # the hair's upward pull on the comb, which resists the descent

    def stroke(self, start_depth: float, *, rest: float = 0.5) -> PairStroke:
        """Insert the comb along its tines ``start_depth`` [m] below the roots at the version's approach speed, pull
        it down at its stroke speed until it is 1 cm below the lowest strand point (the curls it drags down
        included), take it out and let the pair hang ``rest`` seconds. The force is recorded during the pull."""
        if not (math.isfinite(start_depth) and start_depth > 0.0):
            raise ValueError(f"PairOnComb.stroke: start_depth must be > 0 [m], got {start_depth!r}")
        dt = self.model.opt.timestep
        window = max(1, round(LOAD_CELL_PERIOD / dt))
        floor = self.wig.length + 0.03  # below a fully straightened strand's end, as the scene's pull floor
        self.data.mocap_pos[0] = [self._clear_x, 0.0, -start_depth]
        while self.data.mocap_pos[0, 0] < 0.0:
            self.data.mocap_pos[0, 0] = min(0.0, self.data.mocap_pos[0, 0] + self.approach_speed * dt)
            self._step()
        f6 = np.zeros(6)
        depths, forces, acc, k = [], [], 0.0, 0
        while -self.data.mocap_pos[0, 2] < floor:
            # done once the comb is 1 cm below every strand point (the scene pulls on to its floor; nothing is left
            # on the tines by then)
            if k % window == 0 and -self.data.mocap_pos[0, 2] > self.hanging_length() + 0.01:
                break
            acc += self._tine_force(f6)
            k += 1
            if k % window == 0:
                forces.append(acc / window)
                depths.append(-float(self.data.mocap_pos[0, 2]))
                acc = 0.0
            self.data.mocap_pos[0, 2] -= self.speed * dt
            self._step()
        self._aside()
        self._run(rest)
        return PairStroke(float(start_depth), np.asarray(depths), np.asarray(forces), self.link())
