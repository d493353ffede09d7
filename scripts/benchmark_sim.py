"""Simulation benchmarks for hairbrush_env.

Run ``python scripts/benchmark_sim.py`` (or ``--quick``). Each section is a function taking the parsed arguments
and printing a markdown table; add new sections (e.g. wig strand-count scaling) to :data:`SECTIONS`. All physics
lives in :mod:`hairbrush_env.rods`; this script only sweeps parameters and formats results.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable, Sequence

import mujoco
import numpy as np

from hairbrush_env import hair, rods, scene


def _table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---:" for _ in header) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def section_rod_convergence(args: argparse.Namespace) -> None:
    """Cantilever (gravity and tip load) and helical-spring errors vs discretization."""
    edges = (10, 20, 50) if args.quick else (10, 20, 50, 100, 200)
    print("\n## Rod convergence: 0.2 m cantilever, r = 1 mm, E = 10 GPa, ρ = 1300 kg/m³, dt = 2 ms\n")
    rows = []
    for n in edges:
        g = rods.cantilever_study(n, load="gravity")
        t = rods.cantilever_study(n, load="tip")
        rows.append(
            [
                str(n),
                f"{100 * g.rel_error:+.3f}",
                f"{100 * t.rel_error:+.3f}",
                f"{100 * max(abs(g.length_error), abs(t.length_error)):.1e}",
                f"{g.steps_per_second:,.0f}",
            ]
        )
    print(
        _table(["edges", "gravity tip err %", "end-load tip err %", "max abs length err %", "steps/s"], rows)
    )

    per_turn = (10, 20, 30) if args.quick else (10, 20, 30, 40, 80)
    print("\n## Helical spring (3 turns, D = 20 mm, d = 2 mm, pitch 4 mm) vs k = G d⁴ / (8 D³ N)\n")
    rows = []
    for p in per_turn:
        h = rods.helix_study(p)
        rows.append(
            [
                str(p),
                str(h.n_edges),
                f"{100 * h.rel_error:+.2f}",
                f"{100 * abs(h.length_error):.1e}",
                f"{h.steps_per_second:,.0f}",
            ]
        )
    print(_table(["edges/turn", "edges", "stiffness err %", "abs length err %", "steps/s"], rows))


def _timed_sim(wig: hair.WigConfig, **cfg: object) -> tuple[scene.BrushingSim, float, float, float]:
    """Build a sim; return it with build time, cold (shake) reset time and cached reset time [s]."""
    t0 = time.perf_counter()
    sim = scene.BrushingSim(scene.SceneConfig(wig=wig, **cfg))
    t1 = time.perf_counter()
    sim.reset(0)
    t2 = time.perf_counter()
    sim.reset(0)
    t3 = time.perf_counter()
    return sim, t1 - t0, t2 - t1, t3 - t2


def _stroke_rtf(sim: scene.BrushingSim, fraction: float) -> tuple[float, float, scene.StrokeResult]:
    n0 = sim.n_steps
    t0 = time.perf_counter()
    res = sim.stroke(fraction, force_threshold=np.inf, rng=np.random.default_rng(0))
    wall = time.perf_counter() - t0
    steps = (
        sim.n_steps - n0
    )  # the step is 1 ms in the hair and 10 ms outside, so count the real mj_step calls
    return res.sim_time / wall, steps / wall, res


def section_wig_scaling(args: argparse.Namespace) -> None:
    """Real-time factor and steps/s of the full scene (arm + brush + head + wig) vs strand count and edges."""
    base = hair.PRESETS[hair.DEFAULT_WIG]
    counts = (8, 24) if args.quick else (8, 16, 24, 32, 48)
    dt = scene.SceneConfig().timestep
    print(
        f"\n## Scene speed vs strand count: wig '{base.name}' (R/P = {base.curliness}), "
        f"dt = {1e3 * dt:g} ms, one thread\n"
    )
    print(
        "RTF and steps/s over a full stroke (approach, insertion, pull at 0.1 m/s, retraction) with hair-hair"
    )
    print("contact; reset = pre-brushed shake + settle (cold) vs restoring the cached state.\n")
    rows = []
    for n in counts:
        wig = base.replace(n_strands=n, n_triples=2)
        sim, t_build, t_cold, t_cached = _timed_sim(wig)
        rtf, sps, res = _stroke_rtf(sim, 1.0)
        rows.append(
            [
                str(n),
                str(wig.n_edges + 1),
                str(sim.model.nv),
                f"{rtf:.2f}",
                f"{sps:,.0f}",
                f"{t_build:.1f}",
                f"{t_cold:.2f}",
                f"{1e3 * t_cached:.1f}",
                str(res.diverged),
            ]
        )
        sim.close()
    print(
        _table(
            [
                "strands",
                "vertices/strand",
                "nv",
                "RTF",
                "steps/s",
                "build s",
                "cold reset s",
                "cached reset ms",
                "diverged",
            ],
            rows,
        )
    )

    edges = (12, 16) if args.quick else (8, 12, 16, 20, 24)
    print(
        f"\n## Scene speed vs vertices per strand: {base.n_strands} strands of '{base.name}', "
        f"dt = {1e3 * dt:g} ms\n"
    )
    rows = []
    for e in edges:
        wig = base.replace(min_edges=e, max_edges=e)
        sim, _, t_cold, _ = _timed_sim(wig)
        rtf, sps, res = _stroke_rtf(sim, 1.0)
        rows.append(
            [str(e + 1), str(sim.model.nv), f"{rtf:.2f}", f"{sps:,.0f}", f"{t_cold:.2f}", str(res.diverged)]
        )
        sim.close()
    print(_table(["vertices/strand", "nv", "RTF", "steps/s", "cold reset s", "diverged"], rows))


def section_force_table(args: argparse.Namespace) -> None:
    """Maximum brushing force vs curliness and normalized stroke length b_l (thesis Fig. 3.7), with pass-through."""
    names = ["straight", "curly", "coily"] if args.quick else list(hair.PRESETS)
    fractions = (0.33, 1.0) if args.quick else (0.33, 0.67, 1.0)
    print("\n## Max brushing force [N] vs curliness and b_l (seed 0, 0.1 m/s, no abort; thesis F_T = 10 N)\n")
    print(
        "Cells: F_max (Σ|Lk| before→after) [min hair–hair / hair–bristle centerline distance mm, max |ΔLk| per"
    )
    print("0.1 s]; no pass-through needs hair–hair > r = 0.8 mm, hair–bristle > 1.15 mm and |ΔLk| ≤ 0.5.\n")
    rows = []
    for name in names:
        wig = hair.PRESETS[name]
        sim = scene.BrushingSim(scene.SceneConfig(wig=wig))
        row = [name, f"{wig.curliness:.2f}", f"{wig.length:.2f}"]
        for b in fractions:
            sim.reset(0)
            e0 = sim.entanglement()
            mon = scene.PassThroughMonitor(sim)
            sim.add_observer(mon)
            res = sim.stroke(b, force_threshold=np.inf, rng=np.random.default_rng(0))
            sim.remove_observer(mon)
            row.append(
                f"{res.max_force:.2f} ({e0:.1f}→{sim.entanglement():.1f}) "
                f"[{1e3 * mon.hair_hair:.2f} / {1e3 * mon.hair_bristle:.2f}, {mon.max_link_jump:.2f}]"
                + (" DIV" if res.diverged else "")
            )
        row.insert(3, f"{sim.hanging_length:.3f}")
        sim.close()
        rows.append(row)
    print(_table(["wig", "R/P", "length m", "hanging m"] + [f"b_l={b}" for b in fractions], rows))


def _step_cost(sim: scene.BrushingSim, dt: float, n: int) -> tuple[float, float, dict[str, float]]:
    """CPU ms per ``mj_step`` of the sim's current state at step ``dt``, mean Newton iterations, timer shares."""
    m, d = sim.model, sim.data
    m.opt.timestep = dt
    for _ in range(10):
        mujoco.mj_step(m, d)
    for t in d.timer:
        t.duration, t.number = 0.0, 0
    iters = 0
    t0 = time.process_time()
    for _ in range(n):
        mujoco.mj_step(m, d)
        iters += int(d.solver_niter[0])
    cpu = (time.process_time() - t0) / n
    stage = {
        name: d.timer[int(getattr(mujoco.mjtTimer, f"mjTIMER_{name.upper()}"))].duration
        for name in ("constraint", "position", "velocity", "pos_collision")
    }
    total = d.timer[int(mujoco.mjtTimer.mjTIMER_STEP)].duration
    return 1e3 * cpu, iters / n, {k: v / total for k, v in stage.items()}


def section_step_cost(args: argparse.Namespace) -> None:
    """Where the time goes: CPU cost of one physics step of the default wig, and pass-through vs contact step."""
    base = hair.PRESETS[hair.DEFAULT_WIG]
    print(
        f"\n## Step cost of the default scene ('{base.name}', {base.n_strands} strands), hair at rest, "
        "no contacts (CPU time, one thread)\n"
    )
    sim = scene.BrushingSim(scene.SceneConfig(wig=base))
    sim.reset(0)
    rows = []
    for dt in (0.01, 0.001):
        ms, it, share = _step_cost(sim, dt, 100 if args.quick else 300)
        rows.append(
            [
                f"{1e3 * dt:g}",
                str(sim.model.nv),
                str(sim.data.nefc),
                f"{it:.2f}",
                f"{ms:.2f}",
                f"{dt / (1e-3 * ms):.2f}",
                " / ".join(
                    f"{100 * share[k]:.0f}" for k in ("constraint", "position", "velocity", "pos_collision")
                ),
            ]
        )
    sim.close()
    # The same rods without arm, brush and head: the floor set by MuJoCo's discrete elastic rods themselves.
    wig_specs = [
        rods.RodSpec(
            name=f"r{i}",
            points=np.stack([np.full(base.n_edges + 1, 0.005 * i), np.zeros(base.n_edges + 1),
                             np.linspace(0.0, -base.length, base.n_edges + 1)], axis=1),
            radius=base.strand_radius,
            young=hair.wisp_young(base.strand_radius),
            clamp="start",
        )
        for i in range(base.n_strands)
    ]  # fmt: skip
    bare = rods.build_rod_model(wig_specs, timestep=0.001)
    bare_data = mujoco.MjData(bare)
    for _ in range(10):
        mujoco.mj_step(bare, bare_data)
    t0 = time.process_time()
    n_bare = 100 if args.quick else 300
    for _ in range(n_bare):
        mujoco.mj_step(bare, bare_data)
    bare_ms = 1e3 * (time.process_time() - t0) / n_bare
    rows.append(["1 (rods only)", str(bare.nv), str(bare_data.nefc), f"{bare_data.solver_niter[0]}",
                 f"{bare_ms:.2f}", f"{1.0 / bare_ms:.2f}", "—"])  # fmt: skip
    print(
        _table(
            [
                "dt ms",
                "nv",
                "constraint rows",
                "Newton iters",
                "CPU ms/step",
                "RTF ceiling",
                "% constraint / position / velocity / collision",
            ],
            rows,
        )
    )

    print("\n## Solver options on a full `curly` stroke at the 1 ms contact step (RTF on CPU time)\n")
    rows = []
    for label, tol, sleep in (("defaults (tolerance 1e-8)", None, False), ("tolerance 1e-6", 1e-6, False),
                              ("sleeping islands", None, True)):  # fmt: skip
        sim = scene.BrushingSim(scene.SceneConfig(wig=base))
        if tol is not None:
            sim.model.opt.tolerance = tol
        if sleep:  # the flag acts at data initialization
            sim.model.opt.enableflags |= int(mujoco.mjtEnableBit.mjENBL_SLEEP)
            mujoco.mj_resetData(sim.model, sim.data)
        sim.reset(0)
        stats = []
        sim.add_observer(
            lambda s, _, stats=stats: stats.append((int((s.data.tree_asleep >= 0).sum()), s.data.nefc))
        )
        t0 = time.process_time()
        res = sim.stroke(1.0, force_threshold=np.inf, rng=np.random.default_rng(0))
        cpu = time.process_time() - t0
        st = np.array(stats)
        rows.append([label, f"{res.sim_time / cpu:.3f}", f"{res.max_force:.2f}", f"{st[:, 0].mean():.0f}",
                     f"{st[:, 1].mean():.0f}"])  # fmt: skip
        sim.close()
    print(_table(["options", "RTF (CPU)", "F_max N", "trees asleep (mean)", "constraint rows (mean)"], rows))

    names = ["curly"] if args.quick else ["curly", "coily"]
    steps = (0.001, 0.005) if args.quick else (0.001, 0.0025, 0.005, 0.01)
    print(
        "\n## Pass-through and speed vs contact step (full stroke, b_l = 1, seed 0; RTF on CPU time; "
        "no pass-through needs hair–hair > 0.8 mm, hair–bristle > 1.15 mm, |ΔLk| ≤ 0.5)\n"
    )
    rows = []
    for name in names:
        for dt in steps:
            sim = scene.BrushingSim(scene.SceneConfig(wig=hair.PRESETS[name], contact_timestep=dt))
            sim.reset(0)
            mon = scene.PassThroughMonitor(sim)
            sim.add_observer(mon)
            t0 = time.process_time()
            res = sim.stroke(1.0, force_threshold=np.inf, rng=np.random.default_rng(0))
            cpu = time.process_time() - t0
            rows.append(
                [
                    name,
                    f"{1e3 * dt:g}",
                    f"{res.sim_time / cpu:.2f}",
                    f"{res.max_force:.2f}",
                    f"{1e3 * mon.hair_hair:.2f}",
                    f"{1e3 * mon.hair_bristle:.2f}",
                    f"{mon.max_link_jump:.2f}",
                    "yes" if mon.passed else "NO",
                ]
            )
            sim.close()
    print(
        _table(
            [
                "wig",
                "contact dt ms",
                "RTF (CPU)",
                "F_max N",
                "hair–hair mm",
                "hair–bristle mm",
                "max |ΔLk|",
                "no pass-through",
            ],
            rows,
        )
    )


SECTIONS: list[Callable[[argparse.Namespace], None]] = [
    section_rod_convergence,
    section_wig_scaling,
    section_force_table,
    section_step_cost,
]


def main(argv: Sequence[str] | None = None) -> None:
    """Parse arguments and run every section in :data:`SECTIONS`."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer / coarser cases (CI smoke run)")
    parser.add_argument(
        "--section",
        action="append",
        choices=[f.__name__.removeprefix("section_") for f in SECTIONS],
        help="run only this section (repeatable); default: all",
    )
    args = parser.parse_args(argv)
    for section in SECTIONS:
        if args.section is None or section.__name__.removeprefix("section_") in args.section:
            section(args)


if __name__ == "__main__":
    main()
