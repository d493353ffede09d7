"""Generating a pile (thesis §4.5.1): :func:`generate_packing` drops rods in batches into the container, jostles
and settles them in the MuJoCo model of :mod:`.pile`.

Model choices of the deposition (like those of :mod:`.pile`, each changes dynamics only, not the statics of the
final pile):

* rods are added in batches at non-overlapping random positions and isotropic orientations just above the current
  pile, and the model is recompiled per batch (only deposited rods are simulated);
* optional ``freeze_depth``: during deposition, rods buried deeper than ``freeze_depth·L`` below the pile top are
  static geoms (not simulated); all rods are released for the final jostle and drag-free settle.

Placement: new rods start at random positions fully inside the container (``placement``); with the default
"centered" rule flat rods start near the axis, which strengthens the radial inhomogeneity of φ in a 1.5 L container
(docs/rod_piles.md).

Determinism: one process, one thread, fixed seed → bitwise identical packings (MuJoCo's pipeline is
deterministic for identical inputs; all randomness comes from ``numpy.random.default_rng(seed)``; wall time is
only recorded in ``meta``). Tested across calls and processes.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ...topology.proximity import segment_distances
from .packing import GRAVITY, Packing
from .pile import Pile, SimParams, poses_from_endpoints

__all__ = [
    "generate_packing",
    "sweep_pile",
]


def _place_batch(rng, k: int, sp: SimParams, existing: np.ndarray, z_top: float, placement: str = "centered"):
    """Random isotropic rods fully inside the container, not overlapping each other or the pile's top.

    ``placement``: "centered" — the centre is uniform in a disk of radius R − (L/2)|u_xy| (fits for any azimuth,
    so flat rods start near the axis); "uniform" — (centre, direction) uniform over all configurations that fit
    (rejection sampling), so flat rods can also start as chords near the wall.
    """
    L, d = sp.length, sp.diameter
    r = sp.container_diameter / 2
    # new rods spread over a vertical band so they do not overlap; it holds ~6 rods per L of height in a 1.5 L
    # container, and proportionally more in wider containers (same layer density, so the same fall time)
    band = L * max(1.0, k / 6 * (1.5 * L / (2 * r)) ** 2)
    near = (
        existing[np.maximum(existing[:, 0, 2], existing[:, 1, 2]) > z_top - 2 * d]
        if len(existing)
        else existing
    )
    obst0 = list(near[:, 0]) if len(near) else []
    obst1 = list(near[:, 1]) if len(near) else []
    out = []
    for _ in range(k):
        for _attempt in range(200):
            u = rng.normal(size=3)
            u /= np.linalg.norm(u)
            if placement == "uniform":
                rin = r - 1.5 * d
                for _fit in range(1000):
                    rr, ph = math.sqrt(rng.random()) * rin, rng.random() * 2 * math.pi
                    cx, cy = rr * math.cos(ph), rr * math.sin(ph)
                    ex, ey = u[0] * L / 2, u[1] * L / 2
                    if max(math.hypot(cx + ex, cy + ey), math.hypot(cx - ex, cy - ey)) <= rin:
                        break
                    u = rng.normal(size=3)
                    u /= np.linalg.norm(u)
            else:
                rmax = max(r - L / 2 * math.hypot(u[0], u[1]) - 1.5 * d, 0.0)
                rr = math.sqrt(rng.random()) * rmax
                ph = rng.random() * 2 * math.pi
            ext = L / 2 * abs(u[2]) + d
            c = np.array([rr * math.cos(ph), rr * math.sin(ph), z_top + ext + 2 * d + rng.random() * band])
            a0, a1 = c - u * L / 2, c + u * L / 2
            if not obst0 or segment_distances(a0, a1, np.array(obst0), np.array(obst1)).min() > 2 * d:
                break
        else:  # pragma: no cover - only with absurd batch sizes
            c = c + np.array([0, 0, band])
            a0, a1 = c - u * L / 2, c + u * L / 2
        obst0.append(a0)
        obst1.append(a1)
        out.append((a0, a1))
    return np.array(out)


def _jostle(pile: Pile, rng, n_shakes: int, tilt_deg: float) -> None:
    """Shake and tilt the container, simulated in the container's frame (§4.5.1 "jostled ... inverted").

    In the frame of a container that translates with acceleration a(t) and tilts slowly, the rods feel the effective
    gravity g − a(t) rotated by the tilt; the fictitious rotational forces are negligible for slow tilts. So instead
    of moving the walls (a teleported mocap container pushes rods through each other), we vary gravity: magnitude
    g(1 + 1.2 sin ωt) — the pile is thrown up ~1 d each period — while its direction tilts by up to ``tilt_deg``
    about a random horizontal axis and back. Then everything settles under normal gravity.
    """
    sp = pile.sp
    opt = pile.model.opt
    period = 12.6 * math.sqrt(sp.diameter / GRAVITY)  # free-flight time of a ~1 d hop at 0.2 g net lift
    omega = 2 * math.pi / period
    nsteps = int(5 * period / sp.dt)
    for _ in range(n_shakes):
        ph = rng.random() * 2 * math.pi
        axis = np.array([math.cos(ph), math.sin(ph), 0.0])
        for k in range(nsteps):
            ang = math.radians(tilt_deg) * math.sin(math.pi * k / nsteps)
            mag = GRAVITY * (1 + 1.2 * math.sin(omega * k * sp.dt))
            down = np.array([0.0, 0.0, -1.0])
            # Rodrigues rotation of "down" about the horizontal axis
            g_dir = down * math.cos(ang) + np.cross(axis, down) * math.sin(ang)
            opt.gravity[:] = mag * g_dir
            pile.step()
        opt.gravity[:] = [0.0, 0.0, -GRAVITY]
        pile.settle(max_time=8 * math.sqrt(sp.length / GRAVITY), min_time=2 * period)


def generate_packing(
    n_rods: int,
    length: float,
    diameter: float,
    *,
    container_diameter: float | None = None,
    seed: int = 0,
    jostle: bool = True,
    batch_size: int = 10,
    n_shakes: int = 2,
    tilt_deg: float = 20.0,
    friction: float = 0.4,
    wall_friction: float | None = None,
    freeze_depth: float | None = None,
    terminal_speed: float = 0.25,
    placement: str = "centered",
    progress: bool = True,
) -> Packing:
    """Drop ``n_rods`` rigid rods in small batches into a cylinder, jostle and settle (thesis §4.5.1).

    Parameters
    ----------
    n_rods : int
        Number of rods.
    length, diameter : float
        Rod length L and diameter d [m]; α = L/d.
    container_diameter : float, optional
        Cylinder inner diameter (default 3 L, as in the experiments).
    seed : int
        Random seed (positions, orientations, shaking axes).
    jostle : bool
        Shake and tilt the container when half of the rods are in and at the end (§4.5.1), then settle.
    batch_size : int
        Rods dropped together (the experiments drop "steadily and in small numbers").
    n_shakes, tilt_deg : int, float
        Shakes per jostle episode and the tilt of the container during a shake.
    friction : float
        Coulomb friction coefficient (steel on steel ≈ 0.3–0.5).
    wall_friction : float, optional
        Friction of rods on the container wall (default: ``friction``; the floor always has ``friction``). The
        experiments used an acrylic container; frictional walls carry part of the pile's weight (Janssen effect).
    freeze_depth : float, optional
        Speed-up for tall piles, in rod lengths (e.g. 1.0): while rods are being added, rods lying entirely more
        than ``freeze_depth·L`` below the current pile top are made static (they carry the rods above but are not
        simulated), so the cost of a batch scales with the active top layer, not the whole pile. The jostle at
        half-filling then only shakes the active layer. At the end every rod is released and the whole pile is
        jostled (if ``jostle``) and settled without drag, so compaction under the full overburden is simulated.
        ``None`` (default): every rod is simulated all the time.
    terminal_speed : float
        Terminal speed of the deposition drag in rod diameters per time step (default 0.25, i.e. 2.5 √(g d));
        larger values let rods hit the pile faster (≤ 0.5 so that a rod cannot pass through another in one step).
    placement : {"centered", "uniform"}
        Where new rods start (see ``_place_batch``): "centered" (default) keeps the centre within R − (L/2)|u_xy|
        of the axis, so flat rods start near the axis; "uniform" samples (centre, direction) uniformly over all
        configurations inside the container.
    progress : bool
        Show a tqdm progress bar.

    Returns
    -------
    Packing
        Settled rods (end points), with the contact pairs and settings in ``meta``.
    """
    from tqdm import tqdm

    if not (isinstance(n_rods, int | np.integer) and n_rods >= 1):
        raise ValueError(f"n_rods: must be a positive integer, got {n_rods!r}")
    if not (math.isfinite(length) and length > 0):
        raise ValueError(f"length: must be > 0, got {length!r}")
    if not (math.isfinite(diameter) and 0 < diameter < length):
        raise ValueError(f"diameter: must be in (0, length), got {diameter!r}")
    cdia = 3 * length if container_diameter is None else float(container_diameter)
    if not cdia > length + 2 * diameter:
        raise ValueError(f"container_diameter: must exceed the rod length, got {cdia!r}")
    if batch_size < 1:
        raise ValueError(f"batch_size: must be ≥ 1, got {batch_size!r}")
    if placement not in ("centered", "uniform"):
        raise ValueError(f"placement: must be 'centered' or 'uniform', got {placement!r}")
    if not 0 < terminal_speed <= 0.5:
        raise ValueError(
            f"terminal_speed: must be in (0, 0.5] rod diameters per step, got {terminal_speed!r}"
        )
    if freeze_depth is not None and not (math.isfinite(freeze_depth) and freeze_depth > 0):
        raise ValueError(f"freeze_depth: must be > 0 (rod lengths) or None, got {freeze_depth!r}")
    t_wall = time.perf_counter()  # only reported in meta; never used in the simulation
    if wall_friction is not None and not (math.isfinite(wall_friction) and wall_friction >= 0):
        raise ValueError(f"wall_friction: must be ≥ 0 or None, got {wall_friction!r}")
    sp = SimParams(
        length, diameter, cdia, friction=friction, terminal_speed=terminal_speed, wall_friction=wall_friction
    )
    rng = np.random.default_rng(seed)
    ep = np.zeros((0, 2, 3))
    jostle_at = {round(n_rods * 0.5)} if jostle else set()
    pile = None
    t_fall = math.sqrt(2 * length / GRAVITY) * 4  # generous: drag slows the fall
    max_frozen = 0
    with tqdm(
        total=n_rods, desc=f"dropping rods (α={length / diameter:.0f})", unit="rod", disable=not progress
    ) as bar:
        while len(ep) < n_rods:
            k = min(batch_size, n_rods - len(ep))
            z_top = float(np.percentile(np.maximum(ep[:, 0, 2], ep[:, 1, 2]), 90)) if len(ep) else 0.0
            new = _place_batch(rng, k, sp, ep, z_top, placement)
            frozen = np.zeros(len(ep) + k, bool)
            if freeze_depth is not None and len(ep):
                frozen[: len(ep)] = ep[:, :, 2].max(axis=1) < z_top - freeze_depth * length
            ep = np.concatenate([ep, new])
            pos, quat, _ = poses_from_endpoints(ep)
            pile = Pile(sp, pos, quat, glued_bottom=frozen)
            max_frozen = max(max_frozen, int(frozen.sum()))
            pile.settle(max_time=1.5 * t_fall, min_time=0.2 * t_fall)
            ep = pile.endpoints()
            bar.update(k)
            if len(ep) in jostle_at:
                _jostle(pile, rng, n_shakes, tilt_deg)
                ep = pile.endpoints()
    if freeze_depth is not None and pile.glued_bottom.any():
        pos, quat, _ = poses_from_endpoints(ep)
        pile = Pile(sp, pos, quat)  # release every rod
    if jostle:
        _jostle(pile, rng, n_shakes, tilt_deg)
    pile.set_drag(False)
    pile.settle(max_time=2 * t_fall)
    ep = pile.endpoints()
    pairs = pile.contact_pairs()
    meta = {
        "generator": "hairbrush_env.studies.rod_pile.generate_packing",
        "seed": int(seed), "jostle": bool(jostle), "batch_size": int(batch_size), "friction": float(friction),
        "wall_friction": None if wall_friction is None else float(wall_friction),
        "freeze_depth": None if freeze_depth is None else float(freeze_depth),
        "terminal_speed": float(terminal_speed), "max_frozen": max_frozen, "placement": placement,
        "length": float(length), "contact_pairs": pairs.tolist(),
        "lost_rods": int(np.sum(ep[:, :, 2].min(axis=1) < -diameter)),
        "wall_time_s": time.perf_counter() - t_wall,
    }  # fmt: skip
    return Packing.from_endpoints(ep, diameter, cdia, meta)


def sweep_pile(n_rods: int, alpha: float, generate: dict):
    """One cell of an aspect-ratio sweep (Fig. 4.5): ``generate_packing(n_rods, L, L / alpha, **generate)`` (seeded by
    ``generate["seed"]``, whichever worker builds it) and its :func:`~.summary.pile_summary`. Returns
    ``(packing, summary)``; the caller saves the packing, so piles land where the command runs, not on a cluster
    node's disk."""
    from .summary import pile_summary

    length = generate["length"]
    kwargs = {k: v for k, v in generate.items() if k != "length"}
    p = generate_packing(n_rods, length, length / alpha, progress=False, **kwargs)
    return p, pile_summary(p)
