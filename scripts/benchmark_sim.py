"""Simulation benchmarks: body-chain strands vs the wave-1 flex wig, side by side in one run.

    python scripts/benchmark_sim.py [--quick] [--section NAME ...]

Sections (each prints a markdown table; every row of a table comes from this one process, so compare ratios):

* ``validation`` — cantilever and helical-spring errors of both rod kinds against beam/spring theory;
* ``rest`` — CPU ms per physics step of the whole scene at the 1 ms contact step, hair settled;
* ``stroke`` — a full pull-through stroke (b_l = 1, no abort): CPU s, ms/step, real-time factor on CPU time,
  contacts and solver iterations, for 24 and 48 strands;
* ``solver`` — PGS iteration cap (and CG) of the chain wig: CPU vs how far squeezed strands sink into each other;
* ``pass_through`` — full strokes through straight, curly and coily at three seeds, every physics step checked;
* ``profile`` — where a stroke's CPU goes: MuJoCo's stages, the Python around them, the per-step pass-through check;
* ``levers`` — what solver options, sensors, the exclude list or a 2 ms contact step would save per stroke;
* ``force_table`` — maximum force vs curliness and b_l (thesis Fig. 3.7) with the per-step pass-through check;
* ``curliest`` — a full stroke through tight_curl and coily under v6 and v7 (v7's smaller curls need more edges).

Cases: ``chain (default)`` (the default wig and comb), ``flex wave 1`` (the first release's wig and scene,
``scene.wave1_scene``: DER flex, 5 edges per curl turn, ≤ 16 edges, κ = 50, compact lattice, paddle brush, short pull)
and ``chain, wave-1 wig`` (the same wig and scene as chains: the like-for-like comparison of strand models);
``pull_through`` adds ``chain, v1 physics`` (``HairBrush-v1``'s self-colliding strands, friction 0.15, soft comb) and
``chain, v2 physics`` (``HairBrush-v2``'s: v1 with less joint damping, stiffer wisps and drag on the strands) to
``chain, v6 physics`` (each version's wig fields and brush, ``hairbrush_env.physics``).
Single-thread physics costs use CPU time (``time.process_time``).
"""

from __future__ import annotations

import argparse
import dataclasses
import time
from collections.abc import Callable, Sequence

import mujoco
import numpy as np

from hairbrush_env import hair, rods, scene
from hairbrush_env.brush import get_brush
from hairbrush_env.pass_through import PassThroughMonitor
from hairbrush_env.physics import PHYSICS
from hairbrush_env.studies import rod_validation


def _table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---:" for _ in header) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def wig_cases(base: hair.WigConfig) -> dict[str, scene.SceneConfig]:
    """The compared scenes of one wig (see the module docstring): the default design, the wave-1 wig and scene
    (``scene.wave1_scene``) as chains at the wave-1 edges, and the wave-1 flex wig itself."""
    wave1 = scene.wave1_scene(base)
    # the default comb, widened to one tine per group axis and one between (48 strands: a 0.9 m curtain)
    comb = dataclasses.replace(
        get_brush("comb"), columns=max(get_brush("comb").columns, 2 * base.n_groups + 1)
    )
    return {
        "chain (default)": scene.SceneConfig(wig=base, brush=comb),
        "chain, wave-1 wig": dataclasses.replace(wave1, wig=wave1.wig_config.replace(rod_kind="chain")),
        "flex wave 1": wave1,
    }


def section_validation(args: argparse.Namespace) -> None:
    """Cantilever (gravity, end load) and helical spring vs theory, chain and flex."""
    print(
        "\n## Rod validation: 0.2 m cantilever (r = 1 mm, E = 10 GPa) and helical spring (3 turns, D = 20 mm)\n"
    )
    rows = []
    for n in (10, 20) if args.quick else (10, 20, 40):
        cells = [str(n)]
        for kind in ("chain", "flex"):
            g = rod_validation.cantilever_study(n, kind=kind)
            t = rod_validation.cantilever_study(n, kind=kind, load="tip")
            cells += [f"{100 * g.rel_error:+.2f}", f"{100 * t.rel_error:+.2f}"]
        rows.append(cells)
    print(_table(["edges", "chain gravity %", "chain end load %", "flex gravity %", "flex end load %"], rows))
    print()
    rows = []
    for per_turn in (5, 8, 10) if args.quick else (5, 6, 8, 10, 20, 30):
        cells = [str(per_turn)]
        for kind in ("chain", "flex"):
            h = rod_validation.helix_study(per_turn, kind=kind)
            cells += [f"{100 * h.rel_error:+.1f}", f"{100 * abs(h.length_error):.0e}"]
        rows.append(cells)
    print(
        _table(
            ["edges/turn", "chain k err %", "chain length err %", "flex k err %", "flex length err %"], rows
        )
    )


def section_rest(args: argparse.Namespace) -> None:
    """CPU per physics step of the settled scene at the contact step (brush parked)."""
    print("\n## Scene at rest, 1 ms contact step, CPU ms per physics step\n")
    rows = []
    for n in (24,) if args.quick else (24, 48):
        base = hair.PRESETS[hair.DEFAULT_WIG].replace(n_strands=n)
        ms_flex = None
        for label, cfg in wig_cases(base).items():
            wig = cfg.wig_config
            sim = scene.BrushingSim(cfg)
            sim.reset(0)
            sim.use_step(contact=True)
            m, d = sim.model, sim.data
            for _ in range(20):
                mujoco.mj_step(m, d)
            steps = 200 if args.quick else 1000
            ncon = iters = 0
            t0 = time.process_time()
            for _ in range(steps):
                mujoco.mj_step(m, d)
                ncon += d.ncon
                iters += int(d.solver_niter[0])
            ms = 1e3 * (time.process_time() - t0) / steps
            ms_flex = ms if label.startswith("flex") else ms_flex
            rows.append([label, str(n), str(wig.n_edges), str(m.nv), f"{ms:.2f}", f"{1.0 / ms:.2f}",
                         f"{ncon / steps:.0f}", f"{iters / steps:.1f}"])  # fmt: skip
            sim.close()
        for r in rows[-3:]:
            r.append(f"{ms_flex / float(r[4]):.2f}")
    print(_table(["model", "strands", "edges", "nv", "CPU ms/step", "RTF ceiling", "contacts", "solver iters",
                  "× faster than flex"], rows))  # fmt: skip


def stroke_stats(sim: scene.BrushingSim, seed: int) -> dict[str, float]:
    """One full pull-through stroke from the cached state ``seed``: CPU, steps, contacts, iterations, force."""
    sim.reset(seed)
    ncon: list[int] = []
    iters: list[int] = []

    def sample(s: scene.BrushingSim) -> None:
        ncon.append(s.data.ncon)
        iters.append(int(s.data.solver_niter[0]))

    sim.add_step_observer(sample)
    n0 = sim.n_steps
    t0 = time.process_time()
    res = sim.stroke(1.0, abort_force=None, rng=np.random.default_rng(seed))
    cpu = time.process_time() - t0
    sim.remove_step_observer(sample)
    steps = sim.n_steps - n0
    return dict(cpu=cpu, steps=steps, sim_time=res.sim_time, ncon=float(np.mean(ncon)), iters=float(np.mean(iters)),
                f_max=res.max_force, diverged=res.diverged)  # fmt: skip


def section_stroke(args: argparse.Namespace) -> None:
    """Full pull-through stroke (b_l = 1, no abort) through the default wig, 24 and 48 strands."""
    seeds = (0,) if args.quick else (0, 7, 11)
    print(
        f"\n## Full stroke through '{hair.DEFAULT_WIG}', b_l = 1, no abort, seeds {seeds} (mean), CPU time\n"
    )
    rows = []
    for n in (24,) if args.quick else (24, 48):
        base = hair.PRESETS[hair.DEFAULT_WIG].replace(n_strands=n)
        cells = []
        for label, cfg in wig_cases(base).items():
            wig = cfg.wig_config
            sim = scene.BrushingSim(cfg)
            st = [stroke_stats(sim, s) for s in seeds]
            sim.close()
            mean = {
                k: float(np.mean([s[k] for s in st]))
                for k in ("cpu", "steps", "sim_time", "ncon", "iters", "f_max")
            }
            cells.append((label, wig, mean, any(s["diverged"] for s in st)))
        flex_cpu = next(c[2]["cpu"] for c in cells if c[0].startswith("flex"))
        for label, wig, mean, div in cells:
            rows.append([label, str(n), str(wig.n_edges), f"{mean['cpu']:.2f}", f"{flex_cpu / mean['cpu']:.2f}",
                         f"{1e3 * mean['cpu'] / mean['steps']:.2f}", f"{mean['sim_time'] / mean['cpu']:.2f}",
                         f"{mean['ncon']:.0f}", f"{mean['iters']:.1f}", f"{mean['f_max']:.2f}",
                         "yes" if div else "no"])  # fmt: skip
    print(_table(["model", "strands", "edges", "CPU s/stroke", "× less CPU than flex", "CPU ms/step",
                  "RTF (CPU)", "contacts", "solver iters", "F_max N", "diverged"], rows))  # fmt: skip


def section_solver(args: argparse.Namespace) -> None:
    """Contact solver and iteration cap of the chain wig: stroke CPU vs how far squeezed strands sink in."""
    cases = [("PGS", 15, True), ("PGS", 30, True), ("PGS", 50, True), ("CG", 20, True), ("PGS", 30, False)]
    wigs = ("curly",) if args.quick else ("curly", "coily")
    print(
        "\n## Contact solver of chain strands: full stroke, b_l = 1, seed 0 (distances every physics step)\n"
    )
    rows = []
    for name in wigs:
        for solver, iters, speculative in cases:
            sim = scene.BrushingSim(scene.SceneConfig(wig=name))
            sim.model.opt.iterations = iters
            if not speculative:
                sim.model.opt.enableflags &= ~int(mujoco.mjtEnableBit.mjENBL_SPECULATIVE)
            sim.contact_solver = getattr(mujoco.mjtSolver, f"mjSOL_{solver}")
            cpu = stroke_stats(sim, 0)["cpu"]
            sim.reset(0)
            mon = PassThroughMonitor(sim)
            res = sim.stroke(1.0, abort_force=None)
            sim.close()
            rows.append([name, solver, str(iters), "yes" if speculative else "no", f"{cpu:.2f}",
                         f"{res.max_force:.2f}", f"{mon.hair_hair_fraction:.2f}", f"{mon.hair_bristle_fraction:.2f}",
                         str(len(mon.crossings))])  # fmt: skip
    print(_table(["wig", "solver", "iterations", "speculative", "CPU s/stroke", "F_max N", "hair–hair / Σr",
                  "hair–bristle / Σr", "crossings"], rows))  # fmt: skip


def section_pass_through(args: argparse.Namespace) -> None:
    """Full strokes through straight, curly and coily at three seeds, every physics step checked."""
    seeds = (0,) if args.quick else (0, 1, 2)
    print(f"\n## Pass-through: full strokes (b_l = 1, no abort), seeds {seeds}, every physics step checked\n")
    rows = []
    for name in ("straight", "curly", "coily"):
        sim = scene.BrushingSim(scene.SceneConfig(wig=name))
        for seed in seeds:
            sim.reset(seed)
            mon = PassThroughMonitor(sim)
            res = sim.stroke(1.0, abort_force=None, rng=np.random.default_rng(seed))
            mon.detach()
            rows.append([name, str(seed), str(mon.steps), f"{res.max_force:.2f}", f"{mon.hair_hair_fraction:.2f}",
                         f"{mon.hair_bristle_fraction:.2f}", str(len(mon.crossings)), f"{mon.max_link_jump:.3f}",
                         "yes" if mon.passed else "NO"])  # fmt: skip
        sim.close()
    print(_table(["wig", "seed", "steps checked", "F_max N", "hair–hair / Σr", "hair–bristle / Σr", "crossings",
                  "max one-step |ΔLk|", "passed"], rows))  # fmt: skip


def section_profile(args: argparse.Namespace) -> None:
    """Where one stroke's CPU goes (default wig, seed 0): MuJoCo stages, Python, the per-step check."""
    print(f"\n## Profile of one full stroke through '{hair.DEFAULT_WIG}' (seed 0)\n")
    sim = scene.BrushingSim(scene.SceneConfig(wig=hair.DEFAULT_WIG))
    sim.reset(0)
    d = sim.data
    for t in d.timer:
        t.duration, t.number = 0.0, 0
    t_wall, t_cpu = time.perf_counter(), time.process_time()
    res = sim.stroke(1.0, abort_force=None)
    wall, cpu = time.perf_counter() - t_wall, time.process_time() - t_cpu
    step = d.timer[int(mujoco.mjtTimer.mjTIMER_STEP)]
    rows = [["whole stroke", f"{1e3 * wall:.0f}", "100", str(step.number)]]

    def timer(name: str) -> float:
        return float(d.timer[int(getattr(mujoco.mjtTimer, f"mjTIMER_{name.upper()}"))].duration)

    top = ("position", "velocity", "actuation", "constraint", "advance")
    for name in ("step", *top):
        rows.append([f"mujoco {name}", f"{1e3 * timer(name):.0f}", f"{100 * timer(name) / wall:.0f}", ""])
        if name == "position":
            for sub in ("pos_kinematics", "pos_inertia", "pos_collision", "pos_make", "pos_project"):
                rows.append([f"  {sub}", f"{1e3 * timer(sub):.0f}", f"{100 * timer(sub) / wall:.0f}", ""])
    rest = timer("step") - sum(timer(n) for n in top)
    rows.append(["mujoco other (passive forces, sensors, smooth acceleration)", f"{1e3 * rest:.0f}",
                 f"{100 * rest / wall:.0f}", ""])  # fmt: skip
    rows.append(["outside mj_step (control, load cell, checks)", f"{1e3 * (wall - step.duration):.0f}",
                 f"{100 * (wall - step.duration) / wall:.0f}", "—"])  # fmt: skip
    sim.reset(0)
    mon = PassThroughMonitor(sim)
    t0 = time.process_time()
    sim.stroke(1.0, abort_force=None)
    checked = time.process_time() - t0
    rows.append(["per-step pass-through check (extra, tests/benchmarks only)", f"{1e3 * (checked - cpu):.0f}",
                 f"{100 * (checked - cpu) / cpu:.0f}", str(mon.steps)])  # fmt: skip
    sim.close()
    print(f"Stroke: {res.sim_time:.2f} s simulated, {cpu:.2f} s CPU, RTF {res.sim_time / cpu:.2f} (CPU); "
          "MuJoCo's timers are wall-clock.\n")  # fmt: skip
    print(_table(["part", "ms", "% of stroke", "calls"], rows))


def section_force_table(args: argparse.Namespace) -> None:
    """Maximum brushing force vs curliness and normalized stroke length b_l (thesis Fig. 3.7), checked per step."""
    names = ["straight", "curly", "coily"] if args.quick else list(hair.PRESETS)
    fractions = (0.33, 1.0) if args.quick else (0.33, 0.67, 1.0)
    print("\n## Max brushing force [N] vs curliness and b_l (seed 0, 0.1 m/s, no abort; thesis F_T = 10 N)\n")
    print(
        "Cells: F_max (Σ|Lk| before→after) [smallest hair–hair / hair–bristle distance as a fraction of the sum"
    )
    print("of radii, crossings], every physics step checked.\n")
    rows = []
    for name in names:
        wig = hair.PRESETS[name]
        sim = scene.BrushingSim(scene.SceneConfig(wig=wig))
        row = [name, f"{wig.curliness:.2f}", f"{wig.length:.2f}"]
        for b in fractions:
            sim.reset(0)
            e0 = sim.entanglement()
            mon = PassThroughMonitor(sim)
            res = sim.stroke(b, abort_force=None, rng=np.random.default_rng(0))
            mon.detach()
            row.append(
                f"{res.max_force:.2f} ({e0:.1f}→{sim.entanglement():.1f}) "
                f"[{mon.hair_hair_fraction:.2f} / {mon.hair_bristle_fraction:.2f}, {len(mon.crossings)}]"
                + (" DIV" if res.diverged else "")
            )
        row.insert(3, f"{sim.hanging_length:.3f}")
        sim.close()
        rows.append(row)
    print(_table(["wig", "R/P", "length m", "hanging m"] + [f"b_l={b}" for b in fractions], rows))


def section_pull_through(args: argparse.Namespace) -> None:
    """Pull-through stroke (b_l = 1, no abort) of the default wig and comb (v0) and of the v1–v6, v8 and v9 physics
    against the wave-1 flex wig and scene, seeds 7 and 11 (issue 21's reference: 5.5–6.8 CPU s for the flex wig)."""
    seeds = (7,) if args.quick else (7, 11)
    base = hair.PRESETS[hair.DEFAULT_WIG]
    cases = list(wig_cases(base).items())[::-1]  # flex first: the reference
    # HairBrush-vN's physics, the comb widened like the default's (v7 brushes curly as v6 does)
    for version in ("v1", "v2", "v3", "v4", "v5", "v6", "v8", "v9"):
        physics = PHYSICS[version]
        soft = dataclasses.replace(
            get_brush(physics.brush), columns=max(get_brush(physics.brush).columns, 2 * base.n_groups + 1)
        )
        cases.append((f"chain, {version} physics", scene.SceneConfig(wig=physics.wig(base), brush=soft)))
    print(
        f"\n## Pull-through stroke through '{hair.DEFAULT_WIG}', b_l = 1, no abort, seeds {seeds}, CPU time\n"
    )
    rows, flex_cpu = [], None
    for label, cfg in cases:
        sim = scene.BrushingSim(cfg)
        st = [stroke_stats(sim, s) for s in seeds]
        sim.close()
        cpu = [s["cpu"] for s in st]
        flex_cpu = float(np.mean(cpu)) if flex_cpu is None else flex_cpu
        steps = float(np.mean([s["steps"] for s in st]))
        rows.append([label, str(cfg.wig_config.n_edges), " / ".join(f"{c:.1f}" for c in cpu),
                     f"{flex_cpu / float(np.mean(cpu)):.2f}", f"{steps:.0f}", f"{1e3 * np.mean(cpu) / steps:.2f}",
                     " / ".join(f"{s['f_max']:.1f}" for s in st)])  # fmt: skip
    print(_table(["case", "edges", "CPU s/stroke per seed", "× less CPU than flex", "physics steps", "CPU ms/step",
                  "F_max N per seed"], rows))  # fmt: skip


def section_levers(args: argparse.Namespace) -> None:
    """What MuJoCo options would save per step in a stroke: mid-pull snapshots of the default wig (seed 0), each
    lever stepped from the same snapshots against the baseline of this run; then the 2 ms contact step."""
    print(f"\n## Per-step levers on mid-pull snapshots of '{hair.DEFAULT_WIG}' (seed 0)\n")
    sim = scene.BrushingSim(scene.SceneConfig(wig=hair.DEFAULT_WIG))
    sim.reset(0)
    spec_state = mujoco.mjtState.mjSTATE_INTEGRATION
    snaps: list[np.ndarray] = []
    count = [0]

    def grab(s: scene.BrushingSim) -> None:
        count[0] += 1
        if s.model.opt.timestep < 0.005 and count[0] % 400 == 0:
            st = np.empty(mujoco.mj_stateSize(s.model, spec_state))
            mujoco.mj_getState(s.model, s.data, st, spec_state)
            snaps.append(st)

    sim.add_step_observer(grab)
    sim.stroke(1.0, abort_force=None)
    sim.remove_step_observer(grab)
    sim.use_step(contact=True)
    snaps = snaps[1:6]
    n_steps = 50 if args.quick else 150

    def cost(m: mujoco.MjModel) -> tuple[float, float, float]:
        d = mujoco.MjData(m)
        cpu = iters = ncon = 0.0
        for st in snaps:
            mujoco.mj_setState(m, d, st, spec_state)
            t0 = time.process_time()
            for _ in range(n_steps):
                mujoco.mj_step(m, d)
                iters += d.solver_niter[0]
                ncon += d.ncon
            cpu += time.process_time() - t0
        n = n_steps * len(snaps)
        return 1e3 * cpu / n, iters / n, ncon / n

    m = sim.model
    base = cost(m)
    rows = [
        [
            "baseline (PGS ≤ 50, speculative, sparse)",
            f"{base[0]:.2f}",
            "1.00",
            f"{base[1]:.1f}",
            f"{base[2]:.0f}",
        ]
    ]

    def lever(label: str, model: mujoco.MjModel) -> None:
        c = cost(model)
        rows.append([label, f"{c[0]:.2f}", f"{base[0] / c[0]:.2f}", f"{c[1]:.1f}", f"{c[2]:.0f}"])

    speculative = int(mujoco.mjtEnableBit.mjENBL_SPECULATIVE)
    m.opt.enableflags &= ~speculative
    lever("speculative contacts off", m)
    m.opt.enableflags |= speculative
    for cap in (30, 15):
        m.opt.iterations = cap
        lever(f"PGS ≤ {cap} iterations", m)
    m.opt.iterations = rods.CHAIN_SOLVER_ITERATIONS
    m.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_SENSOR)
    lever("sensors off", m)
    m.opt.disableflags &= ~int(mujoco.mjtDisableBit.mjDSBL_SENSOR)
    m.opt.jacobian = mujoco.mjtJacobian.mjJAC_DENSE
    lever("dense Jacobian", m)
    m.opt.jacobian = mujoco.mjtJacobian.mjJAC_AUTO
    m.opt.enableflags &= ~speculative
    m.opt.iterations = 15
    lever("speculative off and PGS ≤ 15 together", m)
    m.opt.enableflags |= speculative
    m.opt.iterations = rods.CHAIN_SOLVER_ITERATIONS
    lever("baseline again (drift of this run)", m)
    spec = scene.build_scene(scene.SceneConfig(wig=hair.DEFAULT_WIG))
    for e in list(spec.excludes):
        spec.delete(e)
    bare = spec.compile()
    bare.opt.timestep, bare.opt.solver = m.opt.timestep, m.opt.solver
    lever(f"no exclude list ({m.nexclude} pairs; strands self-collide)", bare)
    sim.close()
    print(_table(["lever", "CPU ms/step", "× baseline speed", "PGS iterations", "contacts"], rows))

    print("\nThe contact step itself: one full stroke, every physics step checked for pass-through\n")
    rows = []
    for dt in (0.001, 0.002):
        sim = scene.BrushingSim(scene.SceneConfig(wig=hair.DEFAULT_WIG, contact_timestep=dt))
        sim.reset(0)
        mon = PassThroughMonitor(sim)
        t0 = time.process_time()
        sim.stroke(1.0, abort_force=None, rng=np.random.default_rng(0))
        cpu = time.process_time() - t0
        rows.append([f"{1e3 * dt:.0f} ms", f"{cpu:.1f}", str(mon.steps), str(len(mon.crossings)),
                     f"{mon.hair_hair_fraction:.2f}"])  # fmt: skip
        sim.close()
    print(_table(["contact step", "CPU s (with the check)", "steps", "crossings", "hair–hair / Σr"], rows))


def section_curliest(args: argparse.Namespace) -> None:
    """Full pull-through stroke through tight_curl and coily under v6, v7 and v8, side by side (v7's curls are smaller
    at the same R/P, so they need more edges for 8 per turn; v8 brushes v7's wigs with tines of friction 0.15)."""
    seeds = (7,) if args.quick else (7, 11)
    print(
        f"\n## The curliest presets under v6, v7 and v8: full stroke, b_l = 1, no abort, seeds {seeds}, CPU time\n"
    )
    rows = []
    for name in ("tight_curl", "coily"):
        cpu_v6 = None
        for version in ("v6", "v7", "v8"):
            physics = PHYSICS[version]
            wig = physics.wig(name)
            sim = scene.BrushingSim(physics.scene_config(name))
            st = [stroke_stats(sim, s) for s in seeds]
            sim.close()
            cpu = float(np.mean([s["cpu"] for s in st]))
            cpu_v6 = cpu if cpu_v6 is None else cpu_v6
            steps = float(np.mean([s["steps"] for s in st]))
            rows.append([name, version, f"{1e3 * wig.curl_radius:.0f}", str(wig.n_edges),
                         " / ".join(f"{s['cpu']:.1f}" for s in st), f"{cpu / cpu_v6:.2f}",
                         f"{1e3 * cpu / steps:.2f}", " / ".join(f"{s['f_max']:.1f}" for s in st)])  # fmt: skip
    print(_table(["wig", "physics", "R mm", "edges", "CPU s/stroke per seed", "× v6's CPU", "CPU ms/step",
                  "F_max N per seed"], rows))  # fmt: skip


SECTIONS: list[Callable[[argparse.Namespace], None]] = [
    section_validation,
    section_rest,
    section_stroke,
    section_pull_through,
    section_solver,
    section_pass_through,
    section_profile,
    section_levers,
    section_force_table,
    section_curliest,
]


def main(argv: Sequence[str] | None = None) -> None:
    """Parse arguments and run the chosen sections of :data:`SECTIONS`."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer / coarser cases (smoke run)")
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
