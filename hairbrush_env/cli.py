"""``hairbrush`` — one command-line tool with subcommands.

Each subcommand group lives in a ``_add_<group>`` function that registers its parser; the handlers import their
heavy dependencies lazily so ``hairbrush --help`` is instant.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from pathlib import Path

from . import __version__


def _load_curve(path: str):
    import numpy as np

    p = Path(path)
    if not p.exists():
        raise SystemExit(f"hairbrush: curve file not found: {path}")
    if p.suffix == ".npy":
        return np.load(p)
    return np.loadtxt(p, delimiter="," if p.suffix == ".csv" else None, ndmin=2)


def _cmd_topology_demo(args: argparse.Namespace) -> int:
    from .io import write_json
    from .topology.demo import plot_demo, run_demo
    from .viz import record_curves

    out = Path(args.out)
    res = run_demo(args.frames, seed=args.seed)
    plot_demo(res, out / "topology_demo.png")
    record_curves(out / "topology_demo.rrd", res.frames, times=res.x, scalars={"metrics/Lk": res.lk})
    summary = {
        "x": res.x,
        "lk": res.lk,
        "link_current": res.current,
        "census_per_metre": {k: {str(n): v for n, v in c.items()} for k, c in res.census.items()},
    }
    write_json(out / "topology_demo.json", summary)
    print(f"Lk at x=0: {res.lk[0]:.4f}, at x=1: {res.lk[-1]:.4f}")
    print(f"wrote {out / 'topology_demo.png'}, {out / 'topology_demo.rrd'}, {out / 'topology_demo.json'}")
    return 0


def _cmd_topology_lk(args: argparse.Namespace) -> int:
    from .topology import linking_number, writhe

    a, b = _load_curve(args.curve_a), _load_curve(args.curve_b)
    try:
        lk = linking_number(a, b, closed=not args.open)
        wa, wb = writhe(a, closed=not args.open), writhe(b, closed=not args.open)
    except ValueError as exc:
        raise SystemExit(f"hairbrush topology lk: {exc}") from exc
    print(f"Lk = {lk:.6f}\nWr(a) = {wa:.6f}\nWr(b) = {wb:.6f}")
    return 0


def _add_topology(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("topology", help="curve topology: linking number, writhe, link density, census")
    tsub = p.add_subparsers(dest="action", required=True, metavar="ACTION")
    demo = tsub.add_parser(
        "demo", help="kinematic combing demo: writes a PNG figure, a rerun recording and JSON"
    )
    demo.add_argument("--out", default="runs/demo", help="output directory (default: runs/demo)")
    demo.add_argument("--frames", type=int, default=21, help="number of tine positions (default: 21)")
    demo.add_argument("--seed", type=int, default=0, help="seed of the random bundle for the census")
    demo.set_defaults(func=_cmd_topology_demo)
    lk = tsub.add_parser(
        "lk", help="linking number and writhes of two curves from .npy/.csv/.txt (N x 3) files"
    )
    lk.add_argument("curve_a")
    lk.add_argument("curve_b")
    lk.add_argument("--open", action="store_true", help="treat curves as open (real-valued Gauss integral)")
    lk.set_defaults(func=_cmd_topology_lk)


def _cmd_rollout(args: argparse.Namespace) -> int:
    import gymnasium as gym
    from tqdm import tqdm

    from .io import write_json
    from .policies import make_policy
    from .rollout import run_episode
    from .viz import EpisodeRecorder, VideoWriter, plot_rollout

    if args.episodes < 1:
        raise SystemExit(f"hairbrush rollout: --episodes must be >= 1, got {args.episodes}")
    try:
        env = gym.make(
            args.env,
            wig=args.wig,
            obs_mode=args.obs_mode,
            render_mode="rgb_array",
            width=args.width,
            height=args.height,
        )
        policy = make_policy(args.policy, env)
    except ValueError as exc:
        raise SystemExit(f"hairbrush rollout: {exc}") from exc
    sim = env.unwrapped.sim
    recorder = EpisodeRecorder(args.rerun) if args.rerun else None
    video = VideoWriter(args.video) if args.video else None
    offset = 0.0

    # colour strands by their entwined group
    group_of = {i: g for g, members in enumerate(sim.layout.groups) for i in members}
    groups = [group_of.get(i, 0) for i in range(len(sim.layout.names))]

    def observe(sim_, sample) -> None:
        # called by the simulation at every load-cell sample (10 Hz), with the episode's simulated time
        if recorder is not None:
            recorder.frame(sample.time, sim_.hair_curves(), groups, sim_.brush_position())
            recorder.force(sample.time, sample.brushing_force())
        if video is not None:
            video.add(sim_.render())

    if recorder is not None or video is not None:
        sim.add_observer(observe)
    logs = []
    bar = tqdm(total=args.episodes, desc=f"{args.policy} on {args.wig}", unit="episode", disable=args.quiet)
    try:
        for ep in range(args.episodes):
            if recorder is not None:
                recorder.new_episode(ep, offset)

            def on_step(log, step, info) -> None:
                if recorder is not None:
                    t_end = info["sim_time"]
                    recorder.stroke(t_end, step.index, step.max_force, step.entanglement)
                    recorder.image(t_end, env.render())
                bar.set_postfix(
                    stroke=step.index + 1, f_max=f"{step.max_force:.1f}N", E=f"{step.entanglement:.2f}"
                )

            log = run_episode(
                env, policy, episode=ep, seed=args.seed + ep, policy_name=args.policy, on_step=on_step
            )
            offset += log.sim_time + 1.0
            logs.append(log)
            bar.update(1)
    finally:
        bar.close()
        env.close()
        if recorder is not None:
            recorder.close()
        if video is not None:
            video.close()
    episodes = [log.to_dict() for log in logs]
    for ep in episodes:
        print(
            f"episode {ep['episode']}: {ep['strokes']} strokes, max force {ep['max_force']:.2f} N, "
            f"pain violations {ep['pain_violations']}, entanglement {ep['entanglement_initial']:.2f} -> "
            f"{ep['final_entanglement']:.2f}, time {ep['time']:.1f} s{' (DIVERGED)' if ep['diverged'] else ''}"
        )
    if args.json:
        write_json(args.json, {"env": args.env, "wig": args.wig, "policy": args.policy, "episodes": episodes})
    if args.plot:
        plot_rollout(episodes, args.plot, force_threshold=env.unwrapped.force_threshold)
    for label, path in (
        ("recording", args.rerun),
        ("video", args.video),
        ("json", args.json),
        ("plot", args.plot),
    ):
        if path:
            print(f"wrote {label}: {path}")
    return 0


def _add_rollout(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "rollout", help="headless rollout of a policy on a brushing env (recording, video, plot)"
    )
    p.add_argument("--env", default="HairBrush-v0", choices=["HairBrush-v0", "HairBrushContinuous-v0"])
    p.add_argument("--wig", default="curly", help="wig preset name (see hairbrush_env.hair.PRESETS)")
    p.add_argument("--policy", default="full", help="registered policy name (e.g. full, random) or sb3:PATH")
    p.add_argument("--episodes", type=int, default=1)
    p.add_argument("--seed", type=int, default=0, help="episode k uses seed S + k")
    p.add_argument("--obs-mode", default="state+image", choices=["state", "image", "state+image"])
    p.add_argument("--rerun", metavar="OUT.rrd", help="write a rerun recording")
    p.add_argument("--video", metavar="OUT.mp4", help="write the webcam video (10 fps)")
    p.add_argument("--width", type=int, default=320, help="webcam image width (observation, render, video)")
    p.add_argument("--height", type=int, default=240, help="webcam image height")
    p.add_argument("--json", metavar="OUT.json", help="write per-episode metrics and per-stroke traces")
    p.add_argument("--plot", metavar="OUT.png", help="plot force vs time and max force per stroke")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_rollout)


def _cmd_compare(args: argparse.Namespace) -> int:
    from .compare import run_grid, summary_markdown

    if args.wigs == "all":
        from .hair import PRESETS

        wigs = list(PRESETS)
    else:
        wigs = [w.strip() for w in args.wigs.split(",") if w.strip()]
    policies = [p.strip() for p in args.policies.split(",") if p.strip()]
    try:
        rows = run_grid(
            wigs, policies, episodes=args.episodes, seed=args.seed, out=args.out, progress=not args.quiet
        )
    except ValueError as exc:
        raise SystemExit(f"hairbrush compare: {exc}") from exc
    print(summary_markdown(rows))
    print(f"wrote {args.out}/results.csv, summary.md, max_force_vs_curliness.png, time_vs_curliness.png")
    return 0


def _add_compare(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "compare", help="run a policy x wig grid on HairBrush-v0 (CSV, Markdown summary, plots)"
    )
    p.add_argument("--wigs", default="all", help="comma-separated preset names, or 'all' (default)")
    p.add_argument(
        "--policies", default="sigmoid,naive,full", help="comma-separated policy names or sb3:PATH"
    )
    p.add_argument("--episodes", type=int, default=3, help="episodes per (wig, policy)")
    p.add_argument("--seed", type=int, default=0, help="episode k uses seed S + k for every policy")
    p.add_argument("--out", default="runs/compare", help="output directory (resumes an interrupted grid)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_compare)


def _helix_setup(args: argparse.Namespace):
    from .studies.double_helix import CombingSetup, replace_setup

    changes = {}
    for item in args.set or []:
        key, sep, value = item.partition("=")
        if not sep:
            raise SystemExit(f"hairbrush helix: --set expects KEY=VALUE, got {item!r}")
        changes[key.strip()] = value.strip()
    try:
        return replace_setup(CombingSetup(), **changes)
    except (TypeError, ValueError) as exc:
        raise SystemExit(f"hairbrush helix: {exc}") from exc


def _cmd_helix_run(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from .studies.double_helix import run_combing, write_run

    setup = _helix_setup(args)
    with tqdm(total=100, desc="combing", unit="%") as bar:

        def progress(frac: float) -> None:
            bar.update(max(0, round(100 * frac) - bar.n))

        res = run_combing(setup, seed=args.seed, progress=progress)
    paths = write_run(res, args.out)
    print(
        f"f_max = {res.f_max:.3f} at x = {res.x_at_f_max:.2f}; jammed = {res.jammed} (peak/plateau "
        f"{res.jam_ratio:.2f}); Lk {res.lk0:.2f} -> {res.lk_end:.2f} (trapped above tine {res.lk_above:.2f}; "
        f"combable link left {100 * res.combed_lk_end_fraction:.1f} %); D = {res.D * 1e3:.1f} mm; "
        f"{res.wall_time:.1f} s"
    )
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0


def _cmd_helix_sweep(args: argparse.Namespace) -> int:
    import numpy as np

    from .io import write_json, write_text
    from .studies.double_helix import (
        CombingResult,
        _csv,
        optimal_q,
        plot_cost,
        plot_sweep,
        replace_setup,
        run_point,
    )
    from .studies.sweep import run_sweep

    base = _helix_setup(args)
    name, sep, values = args.vary.partition("=")
    if not sep or not values:
        raise SystemExit(f"hairbrush helix sweep: --vary expects NAME=v1,v2,..., got {args.vary!r}")
    name = name.strip()
    try:
        setups = [replace_setup(base, **{name: v.strip()}) for v in values.split(",")]
    except (TypeError, ValueError) as exc:
        raise SystemExit(f"hairbrush helix sweep: {exc}") from exc
    points = [{"setup": s.key(), "seed": seed} for s in setups for seed in range(args.seeds)]
    out = Path(args.out)
    raw = run_sweep(run_point, points, out / "cache", workers=args.workers, desc=f"sweep {name}")
    results = [CombingResult.from_dict(r) for r in raw]
    vkey = (lambda r: r.setup.q_effective) if name == "q" else (lambda r: float(getattr(r.setup, name)))
    rows = []
    curves = []
    for p, r in zip(points, results, strict=True):
        s = r.summary()
        rows.append(
            [vkey(r), p["seed"], r.f_max, r.x_at_f_max, r.jam_ratio, int(r.jammed), r.D, r.lk0, r.lk_end,
             r.lk_above, r.combed_lk_end_fraction, r.min_gap_tine / r.setup.radius,
             r.min_gap_strands / r.setup.radius, s["wall_time"]]
        )  # fmt: skip
        curves += [[vkey(r), p["seed"], *row] for row in r.csv_rows()[1].tolist()]
    header = ["value", "seed", "f_max", "x_at_f_max", "jam_ratio", "jammed", "D_m", "Lk0", "Lk_end", "Lk_above",
              "combed_lk_end_fraction", "min_gap_tine_over_r", "min_gap_strands_over_r", "wall_time_s"]  # fmt: skip
    write_text(out / f"sweep_{name}.csv", _csv(header, rows))
    write_text(out / f"sweep_{name}_curves.csv", _csv(["value", "seed", *results[0].csv_rows()[0]], curves))
    plot_sweep(results, name, out / f"sweep_{name}.png")
    print(f"{name:>10} {'f_max':>8} {'jammed':>7} {'Lk0':>6} {'Lk_end':>7} {'combed left':>11}")
    for row in rows:
        print(
            f"{row[0]:>10.3g} {row[2]:>8.3f} {row[5]:>7d} {row[7]:>6.2f} {row[8]:>7.2f} {100 * row[10]:>10.1f}%"
        )
    if name == "q":
        qs = np.array([vkey(r) for r in results])
        uq = np.unique(qs)
        fm = np.array([np.mean([r.f_max for r in results if vkey(r) == q]) for q in uq])
        gammas = np.linspace(0.0, 1.0, 11)
        best = {f"{g:.1f}": optimal_q(uq, fm, g) for g in gammas}
        write_json(out / "cost.json", {"q": uq, "f_max": fm, "optimal_q": best})
        plot_cost(uq, fm, out / "cost.png")
        print("optimal q per γ (eq. 2.8): " + ", ".join(f"γ={g}: q={q:g}" for g, q in best.items()))
    print(
        f"wrote {out}/sweep_{name}.csv, sweep_{name}_curves.csv, sweep_{name}.png"
        + (", cost.*" if name == "q" else "")
    )
    return 0


def _add_helix(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("helix", help="combing a double helix with one tine (thesis chapter 2)")
    hsub = p.add_subparsers(dest="action", required=True, metavar="ACTION")
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument(
        "--set",
        action="append",
        metavar="KEY=VALUE",
        help="override a CombingSetup field, e.g. --set P_over_r=18 --set q=4 (repeatable; q=none = midpoint)",
    )
    common.add_argument("--out", default="runs/helix", help="output directory (default: runs/helix)")
    run = hsub.add_parser(
        "run", parents=[common], help="one combing run: CSV, JSON and a PNG (Figs 2.2c,e, 2.8)"
    )
    run.add_argument("--seed", type=int, default=0)
    run.set_defaults(func=_cmd_helix_run)
    sweep = hsub.add_parser(
        "sweep",
        parents=[common],
        help="parallel, cached, resumable sweep of one field (q also writes the eq. 2.8 cost)",
    )
    sweep.add_argument("--vary", required=True, metavar="NAME=v1,v2,...", help="e.g. P_over_r=18,24,36,48")
    sweep.add_argument("--seeds", type=int, default=1, help="seeds per value (default: 1)")
    sweep.add_argument("--workers", type=int, default=2, help="worker processes (default: 2)")
    sweep.set_defaults(func=_cmd_helix_sweep)


def _cmd_census(args: argparse.Namespace) -> int:
    from .studies.curl_census import CurlSetup, plot_census, run_census_sweep, write_census

    try:
        setup = CurlSetup(n_hairs=args.hairs, n_edges=args.edges, settle_time=args.settle)
    except ValueError as exc:
        raise SystemExit(f"hairbrush census: {exc}") from exc
    out = Path(args.out)
    stats = run_census_sweep(setup, seeds=range(args.seeds), cache_dir=out / "cache", workers=args.workers)
    paths = write_census(stats, out)
    plot_census(stats, out / "census.png")
    for crit, table in stats["criteria"].items():
        cells = ", ".join(
            f"N={n}: {m:.1f}±{e:.1f}" for n, m, e in zip(table["N"], table["mean"], table["sem"], strict=True)
        )
        print(f"{crit:>8}: ρ_N [1/m] {cells}")
    print("wrote " + ", ".join(str(p) for p in [*paths, out / "census.png"]))
    return 0


def _add_census(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "census", help="N-body interaction census of a simulated 12-hair curl (thesis Figs 2.3b, 2.5)"
    )
    p.add_argument("--seeds", type=int, default=4, help="independent curls to average (default: 4)")
    p.add_argument("--hairs", type=int, default=12, help="hairs per curl (default: 12)")
    p.add_argument(
        "--edges", type=int, default=100, help="edges per hair (default: 100, δl = 2 mm as in Fig. 2.10)"
    )
    p.add_argument("--settle", type=float, default=1.5, help="simulated seconds of jostling + relaxation")
    p.add_argument("--workers", type=int, default=2, help="worker processes (default: 2)")
    p.add_argument("--out", default="runs/census", help="output directory (default: runs/census)")
    p.set_defaults(func=_cmd_census)


def _rodpile_summary(p) -> dict:
    import numpy as np

    from .studies.rod_pile import (
        bulk_rods,
        contact_numbers,
        orientations,
        packing_fraction,
        philipse_contact_number,
        pile_height,
    )

    phi = packing_fraction(p)
    alpha = p.aspect_ratio
    c = contact_numbers(p)
    bulk = bulk_rods(p)
    theta, _ = orientations(p)
    cb = float(c[bulk].mean()) if bulk.any() else float("nan")
    return {
        "n_rods": p.n_rods, "alpha": alpha, "diameter": p.diameter, "height": pile_height(p), "phi_f": phi,
        "phi_alpha": phi * alpha, "mean_contacts_all": float(c.mean()), "mean_contacts_bulk": cb,
        "n_bulk_rods": int(bulk.sum()), "philipse_contacts": philipse_contact_number(phi, alpha),
        "mean_cos_theta": float(np.cos(theta).mean()), "lost_rods": p.meta.get("lost_rods", 0),
    }  # fmt: skip


def _print_summary(tag: str, s: dict) -> None:
    print(
        f"{tag}: n={s['n_rods']} α={s['alpha']:.1f} H={s['height'] * 1e3:.1f} mm φ_f={s['phi_f']:.4f} "
        f"φα={s['phi_alpha']:.2f} ⟨c⟩bulk={s['mean_contacts_bulk']:.2f} (all {s['mean_contacts_all']:.2f}) "
        f"Philipse={s['philipse_contacts']:.2f} ⟨cosθ⟩={s['mean_cos_theta']:.3f}"
    )


def _cmd_rodpile_generate(args: argparse.Namespace) -> int:
    from .io import write_json
    from .studies.rod_pile import generate_packing, plot_structure

    out = Path(args.out)
    d = args.length / args.alpha
    try:
        p = generate_packing(
            args.n_rods, args.length, d, container_diameter=args.container * args.length, seed=args.seed,
            jostle=not args.no_jostle, batch_size=args.batch, friction=args.friction, progress=not args.quiet,
        )  # fmt: skip
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile generate: {exc}") from exc
    p.save(out)
    p.to_csv(out.with_suffix(".csv"))
    s = _rodpile_summary(p)
    write_json(out.with_name(out.stem + "_summary.json"), s)
    plot_structure({"generated": p}, out.with_name(out.stem + "_structure.png"))
    _print_summary(str(out), s)
    return 0


def _cmd_rodpile_sweep(args: argparse.Namespace) -> int:
    from .io import write_json
    from .studies.rod_pile import generate_packing, load_packing, plot_phi_alpha

    out = Path(args.out)
    rows = []
    for alpha, n in zip(args.alphas, args.n_rods, strict=True):
        path = out / f"pile_alpha{alpha:g}_seed{args.seed}.npz"
        if path.exists():  # resume: piles already generated are reused
            p = load_packing(path)
        else:
            p = generate_packing(n, args.length, args.length / alpha, container_diameter=args.container * args.length,
                                 seed=args.seed, friction=args.friction, batch_size=args.batch,
                                 progress=not args.quiet)  # fmt: skip
            p.save(path)
        s = _rodpile_summary(p)
        _print_summary(f"α={alpha:g}", s)
        rows.append(s)
        write_json(out / "sweep.json", rows)
    plot_phi_alpha([r["alpha"] for r in rows], [r["phi_f"] for r in rows], out / "phi_alpha.png",
                   contacts=[r["mean_contacts_bulk"] for r in rows])  # fmt: skip
    print(f"wrote {out / 'sweep.json'}, {out / 'phi_alpha.png'}")
    return 0


def _cmd_rodpile_compress(args: argparse.Namespace) -> int:
    from .io import write_json
    from .studies.rod_pile import compress, load_packing, plot_compression, plot_structure

    out = Path(args.out)
    try:
        p = load_packing(args.pile)
        res = compress(p, args.strain_max, args.cycles, args.rate, snapshot_strains=[args.strain_max],
                       progress=not args.quiet)  # fmt: skip
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile compress: {exc}") from exc
    res.save(out / "compression.npz")
    squeezed = res.snapshots[args.strain_max]
    squeezed.save(out / "compressed.npz")
    res.final.save(out / "after.npz")
    summary = {
        "h0": res.h0, "weight": res.weight, "max_load": res.max_load, "dissipated_J": res.dissipated,
        "before": _rodpile_summary(p), "after_unloading": _rodpile_summary(res.final),
    }  # fmt: skip
    write_json(out / "compression.json", summary)
    plot_compression(res, out / "compression.png")
    plot_structure({"ε = 0": p, f"ε = {args.strain_max:g}": squeezed}, out / "structure.png")
    print("max load per cycle [N]: " + ", ".join(f"{x:.4g}" for x in res.max_load))
    print("dissipated per cycle [mJ]: " + ", ".join(f"{x * 1e3:.4g}" for x in res.dissipated))
    print(f"wrote {out}/compression.npz, compressed.npz, after.npz, compression.json, compression.png")
    return 0


def _cmd_rodpile_tension(args: argparse.Namespace) -> int:
    from .io import write_json
    from .studies.rod_pile import load_packing, plot_tension, tension

    out = Path(args.out)
    try:
        res = tension(load_packing(args.pile), glue_depth=args.glue_depth, strain_max=args.strain_max,
                      progress=not args.quiet)  # fmt: skip
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile tension: {exc}") from exc
    write_json(out / "tension.json", {k: getattr(res, k) for k in res.__dataclass_fields__})
    plot_tension(res, out / "tension.png")
    print(f"disentanglement energy {res.energy * 1e3:.4g} mJ, separation at {res.separation * 1e3:.3g} mm "
          f"(glued: {res.n_glued_top} top, {res.n_glued_bottom} bottom)")  # fmt: skip
    return 0


def _cmd_rodpile_fields(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from .io import write_json
    from .studies.rod_fields import correlations, local_fields, plot_fields
    from .studies.rod_pile import load_packing

    out = Path(args.out)
    fields, summary = {}, {}
    for path in tqdm(args.piles, desc="fields", unit="pile", disable=args.quiet):
        try:
            p = load_packing(path)
            spacing = None if args.spacing is None else args.spacing * p.diameter
            f = local_fields(p, args.ls * p.diameter, spacing=spacing, shape=args.shape)
        except ValueError as exc:
            raise SystemExit(f"hairbrush rodpile fields: {exc}") from exc
        label = f"ε = {f.meta.get('strain', 0.0):.3g}"
        while label in fields:
            label += "'"
        fields[label] = f
        f.save(out / f"fields_{Path(path).stem}.npz")
        corr = correlations(f)
        summary[str(path)] = {
            "label": label, "cells": int(f.mask.sum()), "means": f.means(),
            "correlation_length_over_ls": {k: v[2] / f.cell_size for k, v in corr.items()},
        }  # fmt: skip
        means = ", ".join(f"{k}={v:.4g}" for k, v in f.means().items())
        xi = ", ".join(f"{k}:{v[2] / f.cell_size:.2f}" for k, v in corr.items())
        print(f"{path} [{label}, {f.mask.sum()} cells]: {means}\n  ξ/l_s: {xi}")
    write_json(out / "fields.json", summary)
    pngs = plot_fields(fields, out / "fields")
    print("wrote " + ", ".join(str(x) for x in [out / "fields.json", *pngs]))
    return 0


def _cmd_rodpile_plot(args: argparse.Namespace) -> int:
    from .studies.rod_fields import Fields, plot_fields

    out = Path(args.dir)
    files = sorted(out.glob("fields_*.npz"))
    if not files:
        raise SystemExit(f"hairbrush rodpile plot: no fields_*.npz in {out}")
    fields = {}
    for f in files:
        fl = Fields.load(f)
        fields[f"{f.stem[7:]} (ε = {fl.meta.get('strain', 0.0):.3g})"] = fl
    print("wrote " + ", ".join(str(x) for x in plot_fields(fields, out / "fields")))
    return 0


def _add_rodpile(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "rodpile", help="random packings of rigid rods: generate, compress, pull, fields (thesis ch. 4)"
    )
    rsub = p.add_subparsers(dest="action", required=True, metavar="ACTION")

    def common(q, pile_arg=True):
        if pile_arg:
            q.add_argument("pile", help="packing file (.npz from generate, or CSV of endpoints / rod,x,y,z)")
        q.add_argument("--quiet", action="store_true", help="no progress bars")

    g = rsub.add_parser("generate", help="drop, jostle and settle rods in a cylinder (§4.5.1)")
    g.add_argument("--n-rods", type=int, default=150)
    g.add_argument("--alpha", type=float, default=20.0, help="aspect ratio L/d (default 20)")
    g.add_argument("--length", type=float, default=0.05, help="rod length [m] (default 0.05)")
    g.add_argument(
        "--container", type=float, default=3.0, help="container diameter in rod lengths (default 3)"
    )
    g.add_argument("--friction", type=float, default=0.4)
    g.add_argument("--batch", type=int, default=10, help="rods dropped together (default 10)")
    g.add_argument("--seed", type=int, default=0)
    g.add_argument("--no-jostle", action="store_true")
    g.add_argument("--out", default="runs/rodpile/pile.npz")
    common(g, pile_arg=False)
    g.set_defaults(func=_cmd_rodpile_generate)

    s = rsub.add_parser("sweep", help="φ_f and ⟨c⟩ vs aspect ratio (Fig. 4.5); resumable")
    s.add_argument("--alphas", type=float, nargs="+", default=[38.0, 76.0, 100.0])
    s.add_argument("--n-rods", type=int, nargs="+", default=[400, 800, 1000], help="rods per α")
    s.add_argument("--length", type=float, default=0.05)
    s.add_argument("--container", type=float, default=3.0)
    s.add_argument("--friction", type=float, default=0.4)
    s.add_argument("--batch", type=int, default=20)
    s.add_argument("--seed", type=int, default=0)
    s.add_argument("--out", default="runs/rodpile/sweep")
    common(s, pile_arg=False)
    s.set_defaults(func=_cmd_rodpile_sweep)

    c = rsub.add_parser("compress", help="piston load–strain cycles (Figs 4.2, 4.6)")
    common(c)
    c.add_argument("--strain-max", type=float, default=0.15)
    c.add_argument("--cycles", type=int, default=3)
    c.add_argument("--rate", type=float, default=None, help="strain rate [1/s] (default: quasi-static)")
    c.add_argument("--out", default="runs/rodpile/compress")
    c.set_defaults(func=_cmd_rodpile_compress)

    t = rsub.add_parser("tension", help="glue top/bottom layers and pull apart (Fig. 5.3)")
    common(t)
    t.add_argument("--glue-depth", type=float, default=0.15, help="glued layer thickness / pile height")
    t.add_argument("--strain-max", type=float, default=1.0, help="plate lift / pile height")
    t.add_argument("--out", default="runs/rodpile/tension")
    t.set_defaults(func=_cmd_rodpile_tension)

    f = rsub.add_parser("fields", help="φ, S, e, n fields, histograms, maps, correlations (Figs 4.3, 4.4)")
    f.add_argument("piles", nargs="+", help="packings (e.g. pile.npz compressed.npz)")
    f.add_argument("--ls", type=float, default=10.0, help="cell size l_s in rod diameters (default 10)")
    f.add_argument("--spacing", type=float, default=None, help="grid spacing in diameters (default l_s)")
    f.add_argument("--shape", choices=("cube", "sphere"), default="cube")
    f.add_argument("--out", default="runs/rodpile/fields")
    f.add_argument("--quiet", action="store_true")
    f.set_defaults(func=_cmd_rodpile_fields)

    pl = rsub.add_parser("plot", help="redraw the field figures from fields_*.npz in a directory")
    pl.add_argument("dir")
    pl.set_defaults(func=_cmd_rodpile_plot)


#: Entry-point group through which other packages (e.g. ``controllers``) add subcommands: each entry point is a
#: function ``register(subparsers)``. hairbrush_env itself never imports them.
COMMAND_GROUP = "hairbrush_env.commands"


def _add_plugins(sub: argparse._SubParsersAction) -> None:
    from importlib import metadata

    for ep in sorted(metadata.entry_points(group=COMMAND_GROUP), key=lambda e: e.name):
        ep.load()(sub)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hairbrush",
        description="Robotic hair brushing in MuJoCo and the physics/topology toolkit behind it.",
    )
    parser.add_argument("--version", action="version", version=f"hairbrush_env {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    _add_topology(sub)
    _add_rollout(sub)
    _add_compare(sub)
    _add_helix(sub)
    _add_census(sub)
    _add_plugins(sub)
    _add_rodpile(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    # Headless rendering default for CLI runs; the library itself never forces a GL backend.
    os.environ.setdefault("MUJOCO_GL", "egl")
    args = build_parser().parse_args(argv)
    return int(args.func(args) or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
