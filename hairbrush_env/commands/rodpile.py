"""Rod-pile study (chapter 4): ``hairbrush rodpile generate|summary|sweep|compress|tension|fields|plot``."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from ..studies.rod_pile import pile_summary
from . import add_executor_args, executor_from_args
from .checks import (
    UsageError,
    count,
    input_file,
    non_negative,
    number,
    output_dir,
    output_file,
    positive,
    seed,
)


def _print_summary(tag: str, s: dict) -> None:
    print(
        f"{tag}: n={s['n_rods']} α={s['alpha']:.1f} H={s['height'] * 1e3:.1f} mm ({s['height_over_L']:.2f} L) "
        f"φ_f={s['phi_f']:.4f} φα={s['phi_alpha']:.2f} (bulk, ≥ L/2 from the wall: {s['phi_alpha_inner']:.2f}; "
        f"⟨c⟩bulk / Philipse there {s['contacts_bulk_over_philipse_inner']:.2f}) "
        f"⟨c⟩bulk={s['mean_contacts_bulk']:.2f} (all {s['mean_contacts_all']:.2f}) "
        f"Philipse={s['philipse_contacts']:.2f} (measured orientations {s['philipse_contacts_oriented']:.2f}; "
        f"at the φα={s['phi_seen_by_bulk_rods'] * s['alpha']:.2f} around bulk rods {s['philipse_contacts_local']:.2f}) "
        f"⟨cosθ⟩={s['mean_cos_theta']:.3f} "
        f"(bulk {s['mean_cos_theta_bulk']:.3f}) t_gen={s['generation_s']:.0f} s\n  profile (φα, ⟨cosθ⟩) by fifths "
        "of H: "
        + "  ".join(f"{r['phi_alpha']:.2f},{r['mean_cos_theta']:.2f}" for r in s["profile"])
        + "\n  φα in the inner cylinder R − m L, m = "
        + "  ".join(f"{k}: {v:.2f}" for k, v in s["phi_alpha_vs_wall_margin_over_L"].items())
        + "\n  φα in 6 equal-width annuli, axis → wall: "
        + "  ".join(f"{v:.2f}" for v in s["phi_alpha_annuli"])
    )


def _cmd_rodpile_generate(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..studies.rod_pile import generate_packing, plot_structure

    out = Path(args.out)
    d = args.length / args.alpha
    try:
        p = generate_packing(
            args.n_rods, args.length, d, container_diameter=args.container * args.length, seed=args.seed,
            jostle=not args.no_jostle, batch_size=args.batch, friction=args.friction, progress=not args.quiet,
            wall_friction=args.wall_friction, freeze_depth=args.freeze_depth, terminal_speed=args.terminal_speed,
            placement=args.placement,
        )  # fmt: skip
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile generate: {exc}") from exc
    p.save(out)
    p.to_csv(out.with_suffix(".csv"))
    s = pile_summary(p)
    write_json(out.with_name(out.stem + "_summary.json"), s)
    plot_structure({"generated": p}, out.with_name(out.stem + "_structure.png"))
    _print_summary(str(out), s)
    return 0


def _cmd_rodpile_gas(args: argparse.Namespace) -> int:
    from ..studies.rod_pile import random_rod_gas

    try:
        p = random_rod_gas(
            args.n_rods, args.length, args.length / args.alpha, seed=args.seed,
            container_diameter=args.container * args.length, height=args.height * args.length,
        )  # fmt: skip
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile gas: {exc}") from exc
    out = p.save(Path(args.out))
    _print_summary(str(out), pile_summary(p))
    return 0


def _cmd_rodpile_summary(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..studies.rod_pile import load_packing

    rows = []
    for path in args.piles:
        try:
            s = pile_summary(load_packing(path))
        except ValueError as exc:
            raise SystemExit(f"hairbrush rodpile summary: {exc}") from exc
        _print_summary(str(path), s)
        rows.append({"path": str(path), **s})
    if args.out:
        write_json(args.out, rows)
        print(f"wrote {args.out}")
    if args.plot:
        from ..studies.rod_pile import plot_phi_alpha

        bulk = [r["phi_f_inner"] for r in rows]
        plot_phi_alpha([r["alpha"] for r in rows], [r["phi_f"] for r in rows], args.plot,
                       contacts=[r["mean_contacts_bulk"] for r in rows],
                       phi_bulk=None if any(math.isnan(b) for b in bulk) else bulk)  # fmt: skip
        print(f"wrote {args.plot}")
    return 0


def _cmd_rodpile_sweep(args: argparse.Namespace) -> int:
    from ..executor import CellLog, CellsFailed, run_cells
    from ..io import write_json
    from ..studies.rod_pile import load_packing, plot_phi_alpha, sweep_pile

    if len(args.alphas) != len(args.n_rods):
        raise UsageError(
            "--n-rods", f"give one rod count per α: {len(args.alphas)} α, {len(args.n_rods)} counts"
        )
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    generate = {"length": args.length, "container_diameter": args.container * args.length, "seed": args.seed,
                "friction": args.friction, "batch_size": args.batch, "freeze_depth": args.freeze_depth}  # fmt: skip
    keys = list(zip(args.alphas, args.n_rods, strict=True))
    if len(set(keys)) != len(keys):
        raise UsageError("--alphas", f"each (α, rods) pair once, got {keys}")
    path = {(a, n): out / f"pile_alpha{a:g}_n{n}_seed{args.seed}.npz" for a, n in keys}
    summaries: dict = {}

    def finished(key, summary: dict) -> None:
        _print_summary(f"α={key[0]:g}", summary)
        s = dict(summary)
        s.pop("generation_s", None)  # timing lives in cells.csv: sweep.json is the same on any executor
        summaries[key] = s
        # in α order after every pile: an interrupt keeps every finished pile (and its .npz)
        write_json(out / "sweep.json", [summaries[k] for k in keys if k in summaries])

    for key in keys:  # resume: piles already generated are reused
        if path[key].exists():
            finished(key, pile_summary(load_packing(path[key])))
    cells = [((a, n), (n, a, generate)) for a, n in keys if (a, n) not in summaries]
    executor = executor_from_args(args)
    log = CellLog(out / "cells.csv", executor)
    for outcome in run_cells(
        sweep_pile, cells, executor=executor, desc="piles", unit="pile", progress=not args.quiet
    ):
        log.record(outcome)
        if outcome.ok:
            packing, summary = outcome.value
            packing.save(path[outcome.key])  # here, wherever the pile was generated
            finished(outcome.key, summary)
    rows = [summaries[k] for k in keys if k in summaries]
    if rows:
        plot_phi_alpha([r["alpha"] for r in rows], [r["phi_f"] for r in rows], out / "phi_alpha.png",
                       contacts=[r["mean_contacts_bulk"] for r in rows])  # fmt: skip
        print(f"wrote {out / 'sweep.json'}, {out / 'phi_alpha.png'}")
    if log.failed:
        raise CellsFailed("pile(s)", log.failed)
    return 0


def _cmd_rodpile_compress(args: argparse.Namespace) -> int:
    import numpy as np

    from ..io import write_json
    from ..studies.rod_pile import compress, load_packing, plot_compression, plot_structure

    out = Path(args.out)
    schedule = None
    if args.schedule is not None:
        start, stop, step = args.schedule
        if not (step > 0 and stop >= start):
            raise SystemExit("hairbrush rodpile compress: --schedule: need START ≤ STOP and STEP > 0")
        schedule = np.arange(start, stop + 0.5 * step, step)
    try:
        p = load_packing(args.pile)
        first = args.strain_max if schedule is None else float(schedule[0])
        res = compress(p, args.strain_max, args.cycles, args.rate, strain_schedule=schedule,
                       snapshot_strains=[first], progress=not args.quiet)  # fmt: skip
        single = None
        if args.compare_single:
            single = compress(p, float(res.cycle_strain_max.max()), 1, args.rate, progress=not args.quiet)
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile compress: {exc}") from exc
    res.save(out / "compression.npz")
    if single is not None:
        single.save(out / "compression_single.npz")
    squeezed = res.snapshots[first]
    squeezed.save(out / "compressed.npz")
    res.final.save(out / "after.npz")
    summary = {
        "h0": res.h0, "weight": res.weight, "cycle_strain_max": res.cycle_strain_max, "max_load": res.max_load,
        "dissipated_J": res.dissipated, "before": pile_summary(p), "after_unloading": pile_summary(res.final),
    }  # fmt: skip
    if len(res.max_load) >= 2 and np.ptp(res.cycle_strain_max) == 0:
        a, b = res.softening_fit()
        summary["softening_fit_N"] = {"a": a, "b_per_ln_cycle": b}
    if np.ptp(res.cycle_strain_max) > 0:
        summary["reload_load_at_previous_max"] = res.reload_load_at_previous_max()
    if single is not None:
        summary["single_cycle_max_load"] = float(single.max_load[0])
    write_json(out / "compression.json", summary)
    plot_compression(res, out / "compression.png", single=single)
    plot_structure({"ε = 0": p, f"ε = {first:g}": squeezed}, out / "structure.png")
    print("cycle ε_max: " + ", ".join(f"{x:.3g}" for x in res.cycle_strain_max))
    print("max load per cycle [N]: " + ", ".join(f"{x:.4g}" for x in res.max_load))
    print("dissipated per cycle [mJ]: " + ", ".join(f"{x * 1e3:.4g}" for x in res.dissipated))
    if "softening_fit_N" in summary:
        print(f"softening fit: max load ≈ {a:.4g} {b:+.4g} ln(cycle) N")
    if "reload_load_at_previous_max" in summary:
        print("reload load at previous ε_max [N]: "
              + ", ".join(f"{x:.4g}" for x in summary["reload_load_at_previous_max"]))  # fmt: skip
    if single is not None:
        print(f"single cycle to ε = {res.cycle_strain_max.max():.3g}: max load {single.max_load[0]:.4g} N")
    print(f"wrote {out}/compression.npz, compressed.npz, after.npz, compression.json, compression.png")
    return 0


def _cmd_rodpile_tension(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..studies.rod_pile import load_packing, plot_tension, tension

    out = Path(args.out)
    try:
        res = tension(load_packing(args.pile), glue_depth=args.glue_depth, strain_max=args.strain_max,
                      progress=not args.quiet)  # fmt: skip
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile tension: {exc}") from exc
    write_json(out / "tension.json", {k: getattr(res, k) for k in res.__dataclass_fields__})
    plot_tension(res, out / "tension.png")
    h = res.displacement[-1] / res.strain[-1]
    sep = (f"separated at a lift of {res.separation * 1e3:.3g} mm ({res.separation / h:.3g} H), "
           f"hanging weight {res.hanging_weight:.4g} N" if res.separated
           else f"NOT separated by the maximum lift {res.displacement[-1] * 1e3:.3g} mm")  # fmt: skip
    print(f"disentanglement energy {res.energy * 1e3:.4g} mJ; {sep} "
          f"(glued: {res.n_glued_top} top, {res.n_glued_bottom} bottom)")  # fmt: skip
    return 0


def _cmd_rodpile_fields(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from ..io import write_json
    from ..studies.rod_fields import correlations, local_fields, plot_fields
    from ..studies.rod_pile import load_packing

    out = Path(args.out)
    packings = {}
    for path in args.piles:  # every file is read before any field is computed
        try:
            packings[path] = load_packing(path)
        except (ValueError, OSError) as exc:
            raise UsageError("piles", f"cannot read {path!r}: {exc}") from None
    fields, summary = {}, {}
    for path, p in tqdm(packings.items(), desc="fields", unit="pile", disable=args.quiet):
        spacing = None if args.spacing is None else args.spacing * p.diameter
        f = local_fields(p, args.ls * p.diameter, spacing=spacing, shape=args.shape)
        if int(f.mask.sum()) < 2:
            raise UsageError(
                "--ls",
                f"cells of {args.ls:g} rod diameters leave {int(f.mask.sum())} cell(s) inside {path!r} (too small a "
                "pile for them); pass a smaller --ls",
            )
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
    """Redraw the figures of a results directory: fields (fields_*.npz) and/or compression (compression.npz)."""
    from ..studies.rod_fields import Fields, plot_fields
    from ..studies.rod_pile import CompressionResult, plot_compression

    out = Path(args.dir)
    files = sorted(out.glob("fields_*.npz"))
    comp = out / "compression.npz"
    if not files and not comp.exists():
        raise SystemExit(f"hairbrush rodpile plot: no fields_*.npz or compression.npz in {out}")
    written = []
    if files:
        fields = {}
        for f in files:
            fl = Fields.load(f)
            fields[f"{f.stem[7:]} (ε = {fl.meta.get('strain', 0.0):.3g})"] = fl
        written += plot_fields(fields, out / "fields")
    if comp.exists():
        res = CompressionResult.load_file(comp)
        single = out / "compression_single.npz"
        single_res = CompressionResult.load_file(single) if single.exists() else None
        written.append(plot_compression(res, out / "compression.png", single=single_res))
        print("max load per cycle [N]: " + ", ".join(f"{x:.4g}" for x in res.max_load))
    print("wrote " + ", ".join(str(x) for x in written))
    return 0


def _add_rodpile(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "rodpile", help="random packings of rigid rods: generate, compress, pull, fields (thesis ch. 4)"
    )
    rsub = p.add_subparsers(dest="action", required=True, metavar="ACTION")

    def common(q, pile_arg=True):
        if pile_arg:
            q.add_argument(
                "pile",
                type=input_file,
                help="packing file (.npz from generate, or CSV of endpoints / rod,x,y,z)",
            )
        q.add_argument("--quiet", action="store_true", help="no progress bars")

    g = rsub.add_parser("generate", help="drop, jostle and settle rods in a cylinder (§4.5.1)")
    g.add_argument("--n-rods", type=count, default=150, help="rods in the pile")
    g.add_argument("--alpha", type=number(1.0), default=20.0, help="aspect ratio L/d")
    g.add_argument("--length", type=positive, default=0.05, help="rod length [m]")
    g.add_argument("--container", type=positive, default=3.0, help="container diameter in rod lengths")
    g.add_argument("--friction", type=non_negative, default=0.4, help="rod–rod friction coefficient")
    g.add_argument(
        "--wall-friction", type=non_negative, default=None, help="rod–wall friction (default: --friction)"
    )
    g.add_argument("--batch", type=count, default=10, help="rods dropped together")
    g.add_argument("--seed", type=seed, default=0, help="seed of the drop positions and orientations")
    g.add_argument("--no-jostle", action="store_true", help="skip the jostling that compacts the pile")
    g.add_argument(
        "--freeze-depth",
        type=positive,
        default=None,
        help="freeze rods buried deeper than this many rod lengths while adding rods (speed-up)",
    )
    g.add_argument(
        "--terminal-speed",
        type=number(0.0, exclusive=True, maximum=0.5),
        default=0.25,
        help="deposition drag terminal speed in rod diameters per time step (at most 0.5)",
    )
    g.add_argument(
        "--placement",
        choices=("centered", "uniform"),
        default="centered",
        help="start positions of new rods: centered or uniform over all configurations that fit",
    )
    g.add_argument(
        "--out", type=output_file(".npz"), default="runs/rodpile/pile.npz", help="packing file to write"
    )
    common(g, pile_arg=False)
    g.set_defaults(func=_cmd_rodpile_generate)

    sm = rsub.add_parser("summary", help="φ_f α, contacts vs Philipse, orientations, profiles of saved piles")
    sm.add_argument("piles", nargs="+", type=input_file, help="packing files (.npz / CSV)")
    sm.add_argument("--out", type=output_file(".json"), default=None, help="write the summaries as JSON")
    sm.add_argument(
        "--plot",
        type=output_file(".png", ".pdf", ".svg"),
        default=None,
        help="draw φ_f α and ⟨c⟩ vs α of these piles",
    )
    sm.set_defaults(func=_cmd_rodpile_summary)

    gas = rsub.add_parser(
        "gas", help="geometric reference: overlapping isotropic rods placed inside the container"
    )
    gas.add_argument("--n-rods", type=count, default=600, help="rods placed")
    gas.add_argument("--alpha", type=number(1.0), default=20.0, help="aspect ratio L/d")
    gas.add_argument("--length", type=positive, default=0.05, help="rod length [m]")
    gas.add_argument("--container", type=positive, default=3.0, help="container diameter in rod lengths")
    gas.add_argument(
        "--height", type=positive, default=2.0, help="height of the centres' range in rod lengths"
    )
    gas.add_argument("--seed", type=seed, default=0, help="seed of the placement")
    gas.add_argument(
        "--out", type=output_file(".npz"), default="runs/rodpile/gas.npz", help="packing file to write"
    )
    gas.set_defaults(func=_cmd_rodpile_gas)

    s = rsub.add_parser("sweep", help="φ_f and ⟨c⟩ vs aspect ratio (Fig. 4.5); resumable")
    s.add_argument(
        "--alphas", type=number(1.0), nargs="+", default=[38.0, 76.0, 100.0], help="aspect ratios L/d"
    )
    s.add_argument("--n-rods", type=count, nargs="+", default=[400, 800, 1000], help="rods per α")
    s.add_argument("--length", type=positive, default=0.05, help="rod length [m]")
    s.add_argument("--container", type=positive, default=3.0, help="container diameter in rod lengths")
    s.add_argument("--friction", type=non_negative, default=0.4, help="rod–rod friction coefficient")
    s.add_argument("--batch", type=count, default=20, help="rods dropped together")
    s.add_argument("--seed", type=seed, default=0, help="seed of the first pile")
    s.add_argument(
        "--freeze-depth",
        type=positive,
        default=None,
        help="freeze rods buried deeper than this many rod lengths while adding rods (speed-up)",
    )
    s.add_argument("--out", type=output_dir, default="runs/rodpile/sweep", help="output directory (resumes)")
    add_executor_args(s, workers=1, what="piles")
    common(s, pile_arg=False)
    s.set_defaults(func=_cmd_rodpile_sweep)

    c = rsub.add_parser("compress", help="piston load–strain cycles (Figs 4.2, 4.6)")
    common(c)
    c.add_argument(
        "--strain-max",
        type=number(0.0, exclusive=True, maximum=0.9),
        default=0.15,
        help="largest strain ε_max",
    )
    c.add_argument("--cycles", type=count, default=3, help="load–unload cycles")
    c.add_argument("--rate", type=positive, default=None, help="strain rate [1/s] (default: quasi-static)")
    c.add_argument(
        "--schedule",
        type=positive,
        nargs=3,
        metavar=("START", "STOP", "STEP"),
        default=None,
        help="cycles of increasing ε_max START, START+STEP, ..., STOP (Fig. 4.6: 0.06 0.30 0.03)",
    )
    c.add_argument(
        "--compare-single",
        action="store_true",
        help="also run one cycle to the largest ε_max on the original pile (red curve of Fig. 4.6)",
    )
    c.add_argument("--out", type=output_dir, default="runs/rodpile/compress", help="output directory")
    c.set_defaults(func=_cmd_rodpile_compress)

    t = rsub.add_parser("tension", help="glue top/bottom layers and pull apart (Fig. 5.3)")
    common(t)
    t.add_argument(
        "--glue-depth",
        type=number(0.0, exclusive=True, maximum=0.5),
        default=0.15,
        help="glued layer thickness / pile height",
    )
    t.add_argument(
        "--strain-max",
        type=positive,
        default=2.0,
        help="maximum plate lift / pile height (the run stops earlier once the parts separate)",
    )
    t.add_argument("--out", type=output_dir, default="runs/rodpile/tension", help="output directory")
    t.set_defaults(func=_cmd_rodpile_tension)

    f = rsub.add_parser("fields", help="φ, S, e, n fields, histograms, maps, correlations (Figs 4.3, 4.4)")
    f.add_argument("piles", nargs="+", type=input_file, help="packings (e.g. pile.npz compressed.npz)")
    f.add_argument("--ls", type=positive, default=10.0, help="cell size l_s in rod diameters")
    f.add_argument("--spacing", type=positive, default=None, help="grid spacing in diameters (default: l_s)")
    f.add_argument("--shape", choices=("cube", "sphere"), default="cube", help="cell shape")
    f.add_argument("--out", type=output_dir, default="runs/rodpile/fields", help="output directory")
    f.add_argument("--quiet", action="store_true", help="no progress bar")
    f.set_defaults(func=_cmd_rodpile_fields)

    pl = rsub.add_parser("plot", help="redraw figures from fields_*.npz / compression.npz in a directory")
    pl.add_argument("dir", help="results directory of fields/compress")
    pl.set_defaults(func=_cmd_rodpile_plot)
    # CT stacks (thesis §4.6): `tomogram` renders a packing, `segment` recovers rods from a stack.
    from .rodpile_segment import add_segment_parser

    add_segment_parser(rsub)


def register(sub: argparse._SubParsersAction) -> None:
    _add_rodpile(sub)
