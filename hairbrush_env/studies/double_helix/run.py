"""One combing stroke: :func:`run_combing` (simulation, topology check and analysis) and the sweep worker
:func:`run_point`."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from .measures import braid_bend, jam_metrics
from .model import TINE_HALF_LENGTH, build_model, bulge, tine_force
from .result import CombingResult
from .setup import CombingSetup

__all__ = ["passages", "run_combing", "run_point"]

_CHECK_STEPS = 5
"""Steps between topology checks (10 ms at the default 2 ms step). A strand that passes through the other strand (or
the tine axis) makes the open Gauss integral of the pair jump by ±1; between checks the continuous part changed by
at most 0.37 in the fastest link bursts seen (P/r = 18–24, insertion at the clamp), so |ΔLk| > 0.5 counts as one."""


def passages(prev: np.ndarray, new: np.ndarray) -> np.ndarray:
    """Whole passages between two checks of open Gauss integrals: round(|Δ|) where |Δ| > 0.5, else 0."""
    delta = np.abs(np.asarray(new, dtype=float) - np.asarray(prev, dtype=float))
    return np.where(delta > 0.5, np.rint(delta), 0.0).astype(int)


def run_combing(
    setup: CombingSetup,
    seed: int = 0,
    *,
    progress: Callable[[float], None] | None = None,
    keep_frames: bool = False,
) -> CombingResult:
    """Simulate one combing stroke and analyse it (see the package docstring for the model and definitions).

    Parameters
    ----------
    setup : CombingSetup
    seed : int
        Seeds a tiny random perturbation (1e-3 r) of the initial vertex positions, so that repeated runs sample the
        symmetry breaking of kinking (thesis: runs are averaged).
    progress : callable, optional
        Called with the fraction of the maximal stroke done (for progress bars).
    keep_frames : bool
        Keep the strand centerlines of every sample in ``result.frames`` (``(samples, 2, n, 3)``).

    Returns
    -------
    CombingResult
    """
    import mujoco

    from ...rods import RodView
    from ...topology import link_current, link_density, linking_number, love_tine_force

    t_wall = time.perf_counter()
    model, rods = build_model(setup)
    data = mujoco.MjData(model)
    views = [RodView(model, r.name) for r in rods]
    rest_len = [r.length for r in rods]
    tine_geom = model.geom("tine").id
    mocap = model.body("tine").mocapid[0]

    # open the gap for the tine (rest shape stays the uniform helix) + seeded symmetry-breaking noise
    rng = np.random.default_rng(seed)
    for rod in rods:
        disp = bulge(rod.points, setup)
        disp += rng.normal(0.0, 1e-3 * setup.radius, disp.shape)
        for k in range(1, rod.n_edges + 1):
            jadr = model.body_jntadr[model.body(f"{rod.name}_{k}").id]
            qadr = model.jnt_qposadr[jadr]
            data.qpos[qadr : qadr + 3] = disp[k]
    mujoco.mj_forward(model, data)

    # Viscous drag γ per unit length lumped on the vertices (the thesis's damping γ). MuJoCo refuses joint damping
    # on flex vertex bodies, so it is applied explicitly through qfrc_applied; c·dt/m ≈ 0.06 at the defaults, far
    # inside the explicit stability limit (2).
    dofs, coef = [], []
    for rod in rods:
        seg = np.linalg.norm(np.diff(rod.points, axis=0), axis=1)
        share = 0.5 * (np.append(seg, 0.0)[1:] + seg)  # vertex k>=1 carries half of each adjacent edge
        for k in range(1, rod.n_edges + 1):
            dadr = model.jnt_dofadr[model.body_jntadr[model.body(f"{rod.name}_{k}").id]]
            dofs.extend(range(dadr, dadr + 3))
            coef.extend([setup.drag * share[k - 1]] * 3)
    dofs_arr, coef_arr = np.asarray(dofs), np.asarray(coef)

    def step() -> None:
        data.qfrc_applied[dofs_arr] = -coef_arr * data.qvel[dofs_arr]
        mujoco.mj_step(model, data)

    def gauss_pairs(z_tine: float) -> np.ndarray:
        """Open Gauss integrals Lk(a, b), Lk(a, tine axis), Lk(b, tine axis) of the current state."""
        va, vb = (v.vertices(data) for v in views)
        axis = np.array(
            [[0.0, -TINE_HALF_LENGTH, z_tine], [0.0, TINE_HALF_LENGTH, z_tine]]
        )  # capsule segment
        return np.array([
            linking_number(va, vb, closed=False),
            linking_number(va, axis, closed=False),
            linking_number(vb, axis, closed=False),
        ])  # fmt: skip

    crossings = np.zeros(3, dtype=int)
    crossing_d: list[float] = []
    crossing_lk = [0.0]  # signed Lk(a, b) carried by the strand–strand passages
    check_time = [0.0]

    def check(z_tine: float, d: float, prev: np.ndarray) -> np.ndarray:
        t0 = time.perf_counter()
        new = gauss_pairs(z_tine)
        check_time[0] += time.perf_counter() - t0
        jumps = passages(prev, new)
        if jumps.any():
            crossings[:] += jumps
            crossing_d.append(d)
            crossing_lk[0] += float(np.sign(new[0] - prev[0]) * jumps[0])
        return new

    buf = np.zeros(6)
    min_gap_tine = min_gap_strands = math.inf
    max_stretch = 0.0
    z0 = -setup.insertion_depth
    topo = gauss_pairs(z0)
    for i_settle in range(max(0, round(setup.settle_time / setup.timestep))):
        step()
        if (i_settle + 1) % _CHECK_STEPS == 0:
            topo = check(z0, 0.0, topo)

    max_d = setup.max_stroke * setup.height
    n_steps = math.ceil(max_d / (setup.speed * setup.timestep))
    est_D = setup.height - setup.insertion_depth  # distance to the free end, for the sampling interval
    sample_every = max(1, round(est_D / setup.samples / (setup.speed * setup.timestep)))

    ds, fs, frames = [], [], []
    mujoco.mj_forward(model, data)  # flexvert_xpos of the current state (it is one step stale after mj_step)
    acc_f, acc_n = 0.0, 0
    last_contact_d = 0.0
    done_after = None
    for i_step in range(n_steps + 1):
        d = i_step * setup.speed * setup.timestep
        if i_step % sample_every == 0:
            mujoco.mj_forward(model, data)
            verts = [v.vertices(data) for v in views]
            frames.append(np.stack(verts))
            ds.append(d)
            fs.append(acc_f / acc_n if acc_n else 0.0)
            acc_f, acc_n = 0.0, 0
            for v, L in zip(verts, rest_len, strict=True):
                max_stretch = max(
                    max_stretch, abs(float(np.linalg.norm(np.diff(v, axis=0), axis=1).sum()) / L - 1)
                )
            if progress is not None:
                progress(d / max_d)
            lowest = min(float(v[:, 2].min()) for v in verts)
            if done_after is None and z0 - d < lowest - 2.0 * (setup.tine_radius + setup.radius):
                done_after = len(ds) + 3  # the tine is below both free ends: a few more samples, then stop
            if done_after is not None and len(ds) >= done_after:
                break
        data.mocap_pos[mocap] = [0.0, 0.0, z0 - d]
        step()
        force, gap_tine, gap_strands = tine_force(model, data, tine_geom, buf)
        min_gap_tine = min(min_gap_tine, gap_tine)
        min_gap_strands = min(min_gap_strands, gap_strands)
        acc_f += force
        acc_n += 1
        if math.isfinite(gap_tine):  # the tine touches a strand
            last_contact_d = d
        if (i_step + 1) % _CHECK_STEPS == 0:
            topo = check(z0 - d, d, topo)

    d_arr = np.asarray(ds)
    F = np.asarray(fs)
    frames_arr = np.asarray(frames)
    D = float(last_contact_d) if last_contact_d > 0 else float(d_arr[-1])
    x = d_arr / D
    f = F / setup.force_scale
    lk = np.array([linking_number(fr[0], fr[1], closed=False) for fr in frames_arr])
    current = link_current(lk, x, window=5)
    clamped_turns = setup.insertion_depth / setup.pitch
    love = love_tine_force(
        d_arr,
        radius=setup.helix_radius,
        pitch=setup.pitch,
        turns=clamped_turns,
        bending=setup.bending,
        twisting=setup.twisting,
        tightly_wound=setup.R_over_r <= 1.0,
    )
    love_f = np.asarray(love) / setup.force_scale

    s0, lam_init = link_density(frames_arr[0, 0], frames_arr[0, 1])
    lam0 = lk[0] / s0[-1] if s0.size else 1.0
    lam0 = lk[0] / (s0[-1] + 0.5 * (s0[1] - s0[0])) if s0.size > 1 else lam0
    snapshots = {}
    for xs in setup.snapshot_x:
        k = int(np.argmin(np.abs(x - xs)))
        s, lam = link_density(frames_arr[k, 0], frames_arr[k, 1])
        snapshots[float(xs)] = (s, (lam - lam_init) / lam0)

    above = [frames_arr[0, i][frames_arr[0, i][:, 2] >= z0] for i in (0, 1)]
    lk_above = float(linking_number(above[0], above[1], closed=False)) if min(map(len, above)) >= 2 else 0.0

    bend = braid_bend(frames_arr, z0 - d_arr, setup.edges_per_pitch)

    in_stroke = x <= 1.0
    kmax = int(np.argmax(np.where(in_stroke, f, -np.inf)))
    jammed, jam_ratio = jam_metrics(x, f)
    return CombingResult(
        setup=setup,
        d=d_arr,
        x=x,
        F=F,
        f=f,
        lk=lk,
        current=current,
        love_f=love_f,
        snapshots=snapshots,
        D=D,
        f_max=float(f[kmax]),
        x_at_f_max=float(x[kmax]),
        lk0=float(lk[0]),
        lk_end=float(lk[-1]),
        jammed=jammed,
        jam_ratio=float(jam_ratio),
        min_gap_tine=float(min_gap_tine),
        min_gap_strands=float(min_gap_strands),
        lk_above=lk_above,
        max_stretch=float(max_stretch),
        wall_time=time.perf_counter() - t_wall,
        strand_crossings=int(crossings[0]),
        tine_crossings=int(crossings[1] + crossings[2]),
        crossing_d=tuple(crossing_d),
        crossing_lk=crossing_lk[0],
        check_time=check_time[0],
        bend=bend,
        frames=frames_arr if keep_frames else np.zeros((0, 2, 0, 3)),
    )


def run_point(point: dict[str, Any]) -> dict[str, Any]:
    """Sweep worker: ``{"setup": CombingSetup.key(), "seed": int}`` → :meth:`CombingResult.to_dict` (picklable)."""
    setup_d = dict(point["setup"])
    setup_d["snapshot_x"] = tuple(setup_d.get("snapshot_x", CombingSetup.snapshot_x))
    return run_combing(CombingSetup(**setup_d), seed=int(point.get("seed", 0))).to_dict()
