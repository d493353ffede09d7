"""Chapter-2 studies: ``hairbrush helix run|sweep`` and ``hairbrush census``."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from . import add_executor_args, executor_from_args
from .checks import UsageError, count, integer, output_dir, positive, seed


def _helix_setup(args: argparse.Namespace):
    from ..studies.double_helix import CombingSetup, replace_setup

    changes = {}
    for item in args.set or []:
        key, sep, value = item.partition("=")
        if not sep:
            raise UsageError("--set", f"expected KEY=VALUE, got {item!r}")
        changes[key.strip()] = value.strip()
    try:
        return replace_setup(CombingSetup(), **changes)
    except (TypeError, ValueError) as exc:
        raise UsageError("--set", str(exc)) from None


def _cmd_helix_run(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from ..studies.double_helix import run_combing, write_run

    setup = _helix_setup(args)
    with tqdm(total=100, desc="combing", unit="%") as bar:

        def progress(frac: float) -> None:
            bar.update(max(0, round(100 * frac) - bar.n))

        res = run_combing(setup, seed=args.seed, progress=progress)
    paths = write_run(res, args.out)
    print(
        f"f_max = {res.f_max:.3f} at x = {res.x_at_f_max:.2f}; jammed = {res.jammed} (peak/plateau "
        f"{res.jam_ratio:.2f}); Lk {res.lk0:.2f} -> {res.lk_end:.2f} (trapped above tine {res.lk_above:.2f}; "
        f"combable link left {100 * res.combed_lk_end_fraction:.1f} %); braid bend below the tine "
        f"{res.bend_max:.1f} deg at x = {res.x_at_bend_max:.2f} (kinked = {res.kinked}); break-throughs: "
        f"{res.kink_jams} at a kink (kink jams), {res.kink_free_drops} kink-free; D = {res.D * 1e3:.1f} mm; "
        f"{res.wall_time:.1f} s"
    )
    for b in res.breakthroughs():
        kind = "no bend measured" if math.isnan(b.bend) else ("KINK JAM" if b.kinked else "kink-free drop")
        print(
            f"  break-through at x = {b.x_peak:.3f}: f {b.f_peak:.2f} -> {b.f_drop:.2f} by x = {b.x_drop:.3f}, "
            f"braid bend {b.bend:.1f} deg ({kind})"
        )
    if res.strand_crossings or res.tine_crossings:
        print(
            f"WARNING: topology violated: {res.strand_crossings} strand-strand and {res.tine_crossings} strand-tine "
            f"passages at d = {', '.join(f'{1e3 * d:.1f}' for d in res.crossing_d)} mm (contacts gave way); "
            f"Lk without them {res.lk_end_faithful:.2f}"
        )
    print("wrote " + ", ".join(str(p) for p in paths))
    return 0


def _cmd_helix_sweep(args: argparse.Namespace) -> int:
    import numpy as np

    from ..io import csv_text, write_json, write_text
    from ..studies.double_helix import (
        CombingResult,
        optimal_q,
        plot_cost,
        plot_sweep,
        replace_setup,
        run_point,
    )
    from ..studies.sweep import run_sweep

    base = _helix_setup(args)
    name, sep, values = args.vary.partition("=")
    if not sep or not values:
        raise UsageError("--vary", f"expected NAME=v1,v2,..., got {args.vary!r}")
    name = name.strip()
    try:
        setups = [replace_setup(base, **{name: v.strip()}) for v in values.split(",")]
    except (TypeError, ValueError) as exc:
        raise UsageError("--vary", str(exc)) from None
    points = [{"setup": s.key(), "seed": seed} for s in setups for seed in range(args.seeds)]
    out = Path(args.out)
    raw = run_sweep(run_point, points, out / "cache", executor=executor_from_args(args), desc=f"sweep {name}")
    results = [CombingResult.from_dict(r) for r in raw]
    vkey = (lambda r: r.setup.q_effective) if name == "q" else (lambda r: float(getattr(r.setup, name)))
    rows = []
    curves = []
    for p, r in zip(points, results, strict=True):
        s = r.summary()
        rows.append(
            [vkey(r), p["seed"], r.f_max, r.x_at_f_max, r.jam_ratio, int(r.jammed), r.D, r.lk0, r.lk_end,
             r.lk_above, r.combed_lk_end_fraction, r.min_gap_tine / r.setup.radius,
             r.min_gap_strands / r.setup.radius, r.strand_crossings, r.tine_crossings, r.lk_end_faithful,
             r.bend_max, r.x_at_bend_max, int(r.kinked), r.kink_jams, r.kink_free_drops, s["wall_time"]]
        )  # fmt: skip
        curves += [[vkey(r), p["seed"], *row] for row in r.csv_rows()[1].tolist()]
    header = ["value", "seed", "f_max", "x_at_f_max", "jam_ratio", "jammed", "D_m", "Lk0", "Lk_end", "Lk_above",
              "combed_lk_end_fraction", "min_gap_tine_over_r", "min_gap_strands_over_r", "strand_crossings",
              "tine_crossings", "Lk_end_faithful", "bend_max_deg", "x_at_bend_max", "kinked",
              "kink_jams", "kink_free_drops", "wall_time_s"]  # fmt: skip
    write_text(out / f"sweep_{name}.csv", csv_text(header, rows))
    write_text(
        out / f"sweep_{name}_curves.csv", csv_text(["value", "seed", *results[0].csv_rows()[0]], curves)
    )
    plot_sweep(results, name, out / f"sweep_{name}.png")
    print(
        f"{name:>10} {'f_max':>8} {'jammed':>7} {'Lk0':>6} {'Lk_end':>7} {'combed left':>11} {'crossings':>9}"
        f" {'bend':>6} {'kink jams':>9} {'kink-free drops':>15}"
    )
    for row in rows:
        print(
            f"{row[0]:>10.3g} {row[2]:>8.3f} {row[5]:>7d} {row[7]:>6.2f} {row[8]:>7.2f} {100 * row[10]:>10.1f}%"
            f" {row[13]:>4d}/{row[14]:<4d} {row[16]:>6.1f} {row[19]:>9d} {row[20]:>15d}"
        )
    print(
        "crossings = strand-strand / strand-tine passages (topology violations; -1 = cached before the check)\n"
        "bend = largest bend of the braid below the tine [deg] (kink, thesis Fig. 2.2a; nan = never 3 pitches below "
        "the tine, or cached before the measure)\n"
        "kink jams = break-throughs (force drop >= 20 %) at a bend >= 30 deg, the jam cycle of thesis §2.4; "
        "kink-free drops = break-throughs with the braid straighter than that"
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
        help="override a CombingSetup field, e.g. --set P_over_r=18 --set q=4 (repeatable; q=none = midpoint, "
        "q=clamp = half a pitch below the clamp)",
    )
    common.add_argument("--out", type=output_dir, default="runs/helix", help="output directory")
    run = hsub.add_parser(
        "run", parents=[common], help="one combing run: CSV, JSON and a PNG (Figs 2.2c,e, 2.8)"
    )
    run.add_argument("--seed", type=seed, default=0, help="seed of the run")
    run.set_defaults(func=_cmd_helix_run)
    sweep = hsub.add_parser(
        "sweep",
        parents=[common],
        help="parallel, cached, resumable sweep of one field (q also writes the eq. 2.8 cost)",
    )
    sweep.add_argument("--vary", required=True, metavar="NAME=v1,v2,...", help="e.g. P_over_r=18,24,36,48")
    sweep.add_argument("--seeds", type=count, default=1, help="seeds per value")
    add_executor_args(sweep, workers=2, what="sweep points")
    sweep.set_defaults(func=_cmd_helix_sweep)


def _cmd_census(args: argparse.Namespace) -> int:
    from ..studies.curl_census import CurlSetup, plot_census, run_census_sweep, write_census

    try:
        setup = CurlSetup(n_hairs=args.hairs, n_edges=args.edges, settle_time=args.settle)
    except ValueError as exc:
        raise UsageError("--hairs/--edges/--settle", str(exc)) from None
    out = Path(args.out)
    stats = run_census_sweep(
        setup, seeds=range(args.seeds), cache_dir=out / "cache", executor=executor_from_args(args)
    )
    paths = write_census(stats, out)
    plot_census(stats, out / "census.png")
    for crit, table in stats["criteria"].items():
        cells = ", ".join(
            f"N={n}: {m:.1f}±{e:.1f}" for n, m, e in zip(table["N"], table["mean"], table["sem"], strict=True)
        )
        print(f"{crit:>9}: ρ_N [1/m] {cells}")
    q = stats["layer_lk_quantiles"]
    print(
        f"link_auto: |Lk| > {stats['lk_threshold_auto']:.3f}, the smallest threshold with no all-hair cluster in any"
        f" layer (the thesis's rule; it found 0.4). Layer-pair |Lk|: median {q['50']:.3f}, 99 % {q['99']:.3f},"
        f" max {q['100']:.3f}"
    )
    print("wrote " + ", ".join(str(p) for p in [*paths, out / "census.png"]))
    return 0


def _add_census(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "census", help="N-body interaction census of a simulated 12-hair curl (thesis Figs 2.3b, 2.5)"
    )
    p.add_argument("--seeds", type=count, default=4, help="independent curls to average")
    p.add_argument("--hairs", type=integer(2), default=12, help="hairs per curl")
    p.add_argument(
        "--edges", type=integer(4), default=100, help="edges per hair (100: δl = 2 mm as in Fig. 2.10)"
    )
    p.add_argument("--settle", type=positive, default=1.5, help="simulated seconds of jostling + relaxation")
    add_executor_args(p, workers=2, what="seeds")
    p.add_argument("--out", type=output_dir, default="runs/census", help="output directory")
    p.set_defaults(func=_cmd_census)


def register(sub: argparse._SubParsersAction) -> None:
    _add_helix(sub)
    _add_census(sub)
