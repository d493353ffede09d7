"""Mechanical tests on a settled pile, simulated without drag in the MuJoCo model of :mod:`.pile`.

* :func:`compress` — piston load–strain loops (Fig. 4.2), repeated cycles (softening, Fig. 4.2d, with a fit
  max load = a + b ln(cycle)) and cycles of increasing amplitude (``strain_schedule``, Mullins-like softening,
  Fig. 4.6); the result is a :class:`CompressionResult`.
* :func:`tension` — glued top/bottom layers pulled apart until they separate (contact-graph criterion),
  disentanglement energy (Fig. 5.3); the result is a :class:`TensionResult`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...io import atomic_path
from .packing import GRAVITY, Packing, pile_height
from .pile import Pile, SimParams, poses_from_endpoints

__all__ = [
    "CompressionResult",
    "TensionResult",
    "compress",
    "tension",
]


@dataclass(frozen=True)
class CompressionResult:
    """Piston test: load–strain per cycle (thesis Fig. 4.2, 4.6).

    Attributes
    ----------
    strain, load : list of (k,) ndarray
        Per cycle, strain ε = (H0 − z_piston)/H0 and piston load [N] (sum of contact normal forces), loading then
        unloading.
    loading : list of (k,) bool ndarray
        True on the loading branch.
    max_load : (cycles,) ndarray
        Maximum load of each cycle [N].
    dissipated : (cycles,) ndarray
        Loop area ∮ F dz [J] (loading work − unloading work) per cycle; > 0 means energy was dissipated.
    h0 : float
        Initial pile height H0 [m] (:func:`pile_height`), the reference of the strain.
    weight : float
        Weight of the pile [N].
    snapshots : dict[float, Packing]
        Packings at the requested strains (first loading branch).
    final : Packing
        Pile after the last unloading (``None`` when loaded from a file).
    cycle_strain_max : (cycles,) ndarray
        Maximum strain of each cycle (constant for repeated cycles, Fig. 4.2d; increasing for Fig. 4.6).
    """

    strain: list
    load: list
    loading: list
    max_load: np.ndarray
    dissipated: np.ndarray
    h0: float
    weight: float
    snapshots: dict
    final: Packing | None
    cycle_strain_max: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def softening_fit(self) -> tuple[float, float]:
        """Least-squares fit max_load ≈ a + b ln(cycle) over all cycles (the thesis's logarithmic softening,
        Fig. 4.2d inset): returns (a [N], b [N per e-fold of cycles]); b < 0 means softening. Needs ≥ 2 cycles."""
        if len(self.max_load) < 2:
            raise ValueError("cycles: the softening fit needs at least 2 cycles")
        x = np.log(np.arange(1, len(self.max_load) + 1))
        b, a = np.polyfit(x, self.max_load, 1)
        return float(a), float(b)

    def reload_load_at_previous_max(self) -> np.ndarray:
        """For cycles k ≥ 2: the load on loading branch k at the previous cycle's maximum strain (Mullins effect,
        Fig. 4.6: below that cycle's maximum load if the pile softened). ``nan`` for the first cycle."""
        out = np.full(len(self.strain), np.nan)
        for k in range(1, len(self.strain)):
            s, f, lo = self.strain[k], self.load[k], self.loading[k]
            out[k] = float(np.interp(self.cycle_strain_max[k - 1], s[lo], f[lo]))
        return out

    def save(self, path: str | Path) -> Path:
        arrays = {}
        for c, (s, f, lo) in enumerate(zip(self.strain, self.load, self.loading, strict=True)):
            arrays[f"strain_{c}"], arrays[f"load_{c}"], arrays[f"loading_{c}"] = s, f, lo
        with atomic_path(path) as tmp, open(tmp, "wb") as fh:
            np.savez_compressed(fh, max_load=self.max_load, dissipated=self.dissipated, h0=self.h0,
                                weight=self.weight, cycles=len(self.strain),
                                cycle_strain_max=self.cycle_strain_max, **arrays)  # fmt: skip
        return Path(path)

    @classmethod
    def load_file(cls, path: str | Path) -> CompressionResult:
        """Read :meth:`save` output (without the packings)."""
        p = Path(path)
        if not p.exists():
            raise ValueError(f"path: compression file not found: {p}")
        with np.load(p, allow_pickle=False) as z:
            n = int(z["cycles"])
            csm = z["cycle_strain_max"] if "cycle_strain_max" in z else np.array([z["strain_0"].max()] * n)
            return cls([z[f"strain_{c}"] for c in range(n)], [z[f"load_{c}"] for c in range(n)],
                       [z[f"loading_{c}"] for c in range(n)], z["max_load"], z["dissipated"], float(z["h0"]),
                       float(z["weight"]), {}, None, np.asarray(csm, float))  # fmt: skip


def _check_straight(packing: Packing) -> None:
    if not packing.is_straight:
        raise ValueError("packing: mechanical tests need straight rigid rods (2 vertices per rod)")
    if math.isnan(packing.container_diameter):
        raise ValueError("packing: container_diameter unknown; mechanical tests need the container")


def compress(
    packing: Packing,
    strain_max: float = 0.15,
    cycles: int = 1,
    rate: float | None = None,
    *,
    strain_schedule: Sequence[float] | None = None,
    snapshot_strains: Sequence[float] = (),
    friction: float | None = None,
    samples_per_cycle: int = 200,
    progress: bool = True,
) -> CompressionResult:
    """Compress the pile with a piston to ``strain_max`` and back, ``cycles`` times (thesis Fig. 4.2d, 4.6).

    The piston (a plate wider than the container, mocap) starts just above the highest rod and moves at constant
    speed down to z = (1 − ε_max) H0 and back, H0 = :func:`pile_height` (95th percentile of rod tops: the few rods
    sticking out of the surface do not define the height). Strain ε = (H0 − z)/H0, so the first samples have ε < 0
    (the piston meets the protruding rods). The load is the total contact force on the piston (vertical). Drag is
    off, so the only dissipation is frictional sliding and the (critically damped) contacts.

    Parameters
    ----------
    rate : float, optional
        Strain rate [1/s]. Default: piston speed 0.1 √(g d) (0.01 d per step), slow compared with free fall
        over a diameter, i.e. quasi-static.
    strain_schedule : sequence of float, optional
        Maximum strain of each cycle (overrides ``strain_max`` and ``cycles``). Fig. 4.6 protocol:
        ``np.arange(0.06, 0.301, 0.03)`` — cycles of increasing amplitude, to compare with one cycle to 0.30.
    snapshot_strains : sequence of float
        Strains (≤ the first cycle's maximum) at which to return the packing on the first loading branch.
    """
    from tqdm import tqdm

    _check_straight(packing)
    if strain_schedule is None:
        if not 0 < strain_max < 1:
            raise ValueError(f"strain_max: must be in (0, 1), got {strain_max!r}")
        if cycles < 1:
            raise ValueError(f"cycles: must be ≥ 1, got {cycles!r}")
        schedule = np.full(int(cycles), float(strain_max))
    else:
        schedule = np.asarray(strain_schedule, dtype=float).ravel()
        if schedule.size < 1 or not np.all((schedule > 0) & (schedule < 1)):
            raise ValueError(f"strain_schedule: need ≥ 1 strains in (0, 1), got {list(schedule)}")
    snaps_req = sorted(float(s) for s in snapshot_strains)
    if any(not 0 <= s <= schedule[0] for s in snaps_req):
        raise ValueError(f"snapshot_strains: must lie in [0, strain_max], got {snaps_req}")
    ep = packing.endpoints
    pos, quat, length = poses_from_endpoints(ep)
    d = packing.diameter
    fr = packing.meta.get("friction", 0.4) if friction is None else friction
    sp = SimParams(length, d, packing.container_diameter, friction=fr)
    h0 = pile_height(packing)
    z_start = float(ep[:, :, 2].max() + d)  # just above the highest rod: no initial overlap
    pile = Pile(sp, pos, quat, piston_z=z_start)
    pile.set_drag(False)
    pile.settle(max_time=0.5 * math.sqrt(length / GRAVITY))
    speed = 0.1 * math.sqrt(GRAVITY * d) if rate is None else rate * h0
    if not speed > 0:
        raise ValueError(f"rate: must be > 0, got {rate!r}")
    dz_step = speed * sp.dt
    travels = [z_start - (1 - e) * h0 for e in schedule]
    n_halves = [max(math.ceil(tr / dz_step), 2) for tr in travels]
    piston_mask = np.zeros(pile.model.ngeom, bool)
    piston_mask[pile.piston_geom] = True
    data = pile.data
    strains, loads, loadings, snaps = [], [], [], {}
    pending = list(snaps_req)
    with tqdm(total=2 * sum(n_halves), desc="compressing", unit="step", disable=not progress) as bar:
        for c, (travel, n_half) in enumerate(zip(travels, n_halves, strict=True)):
            every = max(n_half // samples_per_cycle, 1)
            s_list, f_list, l_list = [], [], []
            for branch in (0, 1):
                for k in range(n_half + 1):
                    frac = k / n_half if branch == 0 else 1 - k / n_half
                    z = z_start - travel * frac
                    data.mocap_pos[0] = [0.0, 0.0, z]
                    pile.step()
                    eps = (h0 - z) / h0
                    if k % every == 0 or k == n_half:
                        s_list.append(eps)
                        f_list.append(pile.geom_forces(piston_mask)[2])  # rods push the piston up
                        l_list.append(branch == 0)
                    while c == 0 and branch == 0 and pending and eps >= pending[0] - 1e-12:
                        snaps[pending.pop(0)] = _snapshot(pile, packing, eps)
                    if k % 200 == 0:
                        bar.update(min(200, n_half))
            strains.append(np.array(s_list))
            loads.append(np.array(f_list))
            loadings.append(np.array(l_list))
    max_load = np.array([f.max() for f in loads])
    dissipated = np.array(
        [_loop_area(s, f, lo) * h0 for s, f, lo in zip(strains, loads, loadings, strict=True)]
    )
    pile.settle(max_time=0.5 * math.sqrt(length / GRAVITY))
    final = _snapshot(pile, packing, 0.0)
    return CompressionResult(strains, loads, loadings, max_load, dissipated, h0, packing.n_rods * sp.mass * GRAVITY,
                             snaps, final, schedule)  # fmt: skip


def _snapshot(pile: Pile, packing: Packing, strain: float) -> Packing:
    meta = {k: v for k, v in packing.meta.items() if k != "contact_pairs"}
    meta["strain"] = float(strain)
    meta["contact_pairs"] = pile.contact_pairs().tolist()
    return Packing.from_endpoints(pile.endpoints(), packing.diameter, packing.container_diameter, meta)


def _loop_area(strain: np.ndarray, load: np.ndarray, loading: np.ndarray) -> float:
    """∫ F dε on loading minus ∫ F dε on unloading (trapezoid rule)."""
    up = np.trapezoid(load[loading], strain[loading])
    s_dn, f_dn = strain[~loading], load[~loading]
    down = -np.trapezoid(f_dn, s_dn)  # unloading runs from ε_max back to 0
    return float(up - down)


@dataclass(frozen=True)
class TensionResult:
    """Glued top/bottom layers pulled apart (thesis Fig. 5.3).

    Attributes
    ----------
    displacement : (k,) ndarray
        Lift of the top plate [m]; ``strain`` = displacement / H.
    load : (k,) ndarray
        Force holding the top plate [N] (weight of the glued top layer + what hangs on it + friction).
    lifted_weight : (k,) ndarray
        Weight of the lifted part [N]: glued top rods plus free rods that rose by more than half the plate lift.
    energy : float
        Disentanglement energy ∫ (load − lifted_weight) dz [J] from 0 to the separation lift (to the end of the
        run if the parts never separated) — the blue area of Fig. 5.3b.
    separation : float
        Plate lift at which the top and bottom parts separated [m] (Fig. 5.3c), ``nan`` if they had not separated
        by the maximum lift. Separation: the contact network no longer connects any rod of the lifted part (glued
        top rods and the free rods touching them, transitively) to the bottom part (glued bottom rods, the floor
        and the free rods touching them), and stays so for a further lift of 2 d.
    separated : bool
        Whether the parts separated before the maximum lift.
    hanging_weight : float
        Weight [N] of the part hanging from the plate at separation (glued top rods + free rods connected to them),
        which the load converges to (``nan`` if not separated).
    """

    displacement: np.ndarray
    strain: np.ndarray
    load: np.ndarray
    lifted_weight: np.ndarray
    energy: float
    separation: float
    n_glued_top: int
    n_glued_bottom: int
    separated: bool = False
    hanging_weight: float = float("nan")


def _components(n: int, pairs: np.ndarray) -> np.ndarray:
    """Connected-component label of each of ``n`` nodes given undirected edges ``pairs`` (k, 2)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    pairs = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    adj = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    return connected_components(adj, directed=False)[1]


def tension(
    packing: Packing,
    *,
    glue_depth: float = 0.15,
    strain_max: float = 2.0,
    rate: float | None = None,
    wall_friction: float = 0.0,
    samples: int = 300,
    stop_at_separation: bool = True,
    progress: bool = True,
) -> TensionResult:
    """Glue the top and bottom layers and pull them apart (thesis §4.5.2 tension test, Fig. 5.3).

    Rods reaching into the bottom ``glue_depth·H`` are fixed to the floor (epoxy in a petri dish); rods reaching
    into the top ``glue_depth·H`` (and not glued at the bottom) are fixed to a plate that rises at constant speed.
    The container walls stay to hold the loose middle in place but are frictionless by default (the experiment
    pulls a free-standing pile; walls with friction would carry load). The plate rises until the parts separate
    (see :class:`TensionResult`) plus a further 0.05 H to record the load settling on the hanging weight, or up to
    the maximum lift ``strain_max·H`` (default 2 H).
    """
    from tqdm import tqdm

    _check_straight(packing)
    if not 0 < glue_depth < 0.5:
        raise ValueError(f"glue_depth: must be in (0, 0.5), got {glue_depth!r}")
    if not strain_max > 0:
        raise ValueError(f"strain_max: must be > 0, got {strain_max!r}")
    ep = packing.endpoints
    d = packing.diameter
    h = float(ep[:, :, 2].max() + d / 2)
    zmin, zmax = ep[:, :, 2].min(axis=1), ep[:, :, 2].max(axis=1)
    bottom = zmin < glue_depth * h
    top = (zmax > (1 - glue_depth) * h) & ~bottom
    if not top.any() or not bottom.any():
        raise ValueError("glue_depth: no rods in the top or bottom glue layer")
    pos, quat, length = poses_from_endpoints(ep)
    fr = packing.meta.get("friction", 0.4)
    sp = SimParams(length, d, packing.container_diameter, friction=fr, wall_friction=wall_friction)
    pile = Pile(sp, pos, quat, glued_bottom=bottom, glued_top=top)
    pile.set_drag(False)
    pile.settle(max_time=0.5 * math.sqrt(length / GRAVITY))
    top_mask = np.zeros(pile.model.ngeom, bool)
    top_mask[np.isin(pile.geom_rod, np.flatnonzero(top))] = True
    mrod = sp.mass * GRAVITY
    w_top = top.sum() * mrod
    speed = 0.1 * math.sqrt(GRAVITY * d) if rate is None else rate * h
    if not speed > 0:
        raise ValueError(f"rate: must be > 0, got {rate!r}")
    dz_step = speed * sp.dt
    travel = strain_max * h
    nsteps = max(math.ceil(travel / dz_step), 2)
    every = max(min(nsteps // samples, round(0.5 * d / dz_step)), 1)  # sample at least every d/2 of lift
    data = pile.data
    mocap_top = pile.model.body_mocapid[pile.mj.mj_name2id(pile.model, pile.mj.mjtObj.mjOBJ_BODY, "top")]
    z0_free = data.xpos[pile.body_of_rod[pile.free], 2].copy()
    n = packing.n_rods
    # graph nodes: rods 0..n-1, the plate n, the floor (with the glued bottom rods) n + 1
    plate_edges = np.stack([np.flatnonzero(top), np.full(top.sum(), n)], axis=1)
    floor_edges = np.stack([np.flatnonzero(bottom), np.full(bottom.sum(), n + 1)], axis=1)
    floor_geom = pile.floor_geom
    disp, load, lifted = [], [], []
    sep_at, hanging, stop_at = math.nan, math.nan, nsteps
    with tqdm(total=nsteps, desc="pulling apart", unit="step", disable=not progress) as bar:
        k = 0
        while k <= stop_at:
            u = dz_step * k
            data.mocap_pos[mocap_top] = [0.0, 0.0, u]
            pile.step()
            if k % every == 0 or k == stop_at:
                rise = data.xpos[pile.body_of_rod[pile.free], 2] - z0_free
                n_lift = int(np.sum(rise > 0.5 * u)) if u > 2 * d else 0
                disp.append(u)
                load.append(w_top - pile.geom_forces(top_mask)[2])
                lifted.append(w_top + n_lift * mrod)
                if k < stop_at:
                    nc = data.ncon
                    g1, g2 = data.contact.geom1[:nc], data.contact.geom2[:nc]
                    touch = data.contact.dist[:nc] < sp.contact_tol * d
                    at_floor = touch & ((g1 == floor_geom) | (g2 == floor_geom))
                    on_floor = pile.geom_rod[np.where(g1 == floor_geom, g2, g1)[at_floor]]
                    on_floor = on_floor[on_floor >= 0]
                    edges = np.concatenate([pile.contact_pairs(), plate_edges, floor_edges,
                                            np.stack([on_floor, np.full(len(on_floor), n + 1)], axis=1)])  # fmt: skip
                    lab = _components(n + 2, edges)
                    connected = lab[n] == lab[n + 1]
                    if connected:
                        sep_at, hanging = math.nan, math.nan
                        stop_at = nsteps
                    elif math.isnan(sep_at) and u > 0:
                        sep_at = u
                        hanging = float(np.sum(lab[:n] == lab[n]) * mrod)
                        if stop_at_separation:
                            stop_at = min(nsteps, k + math.ceil(max(2 * d, 0.05 * h) / dz_step))
            if k % 200 == 0:
                bar.update(min(200, nsteps))
            k += 1
    disp_a, load_a, lift_a = np.array(disp), np.array(load), np.array(lifted)
    excess = load_a - lift_a
    sep_lift = sep_at if (not math.isnan(sep_at) and disp_a[-1] >= sep_at + 2 * d - 1e-12) else math.nan
    upto = disp_a <= (sep_lift if not math.isnan(sep_lift) else disp_a[-1]) + 1e-12
    energy = float(np.trapezoid(excess[upto], disp_a[upto]))
    separated = not math.isnan(sep_lift)
    return TensionResult(disp_a, disp_a / h, load_a, lift_a, energy, sep_lift, int(top.sum()), int(bottom.sum()),
                         separated, hanging if separated else math.nan)  # fmt: skip
