"""``hairbrush`` subcommands contributed by the controllers package (entry-point group
``hairbrush_env.commands``): ``hairbrush vision calibrate``."""

from __future__ import annotations

import argparse
from pathlib import Path

from hairbrush_env.commands import add_webcam_args
from hairbrush_env.commands.checks import count, integer, output_dir, wig_names


def _cmd_vision_calibrate(args: argparse.Namespace) -> int:
    import numpy as np

    from hairbrush_env.io import write_json, write_text

    from .vision_calibration import plot_calibration, rank_correlation, render_rows, rows_to_csv

    presets = args.wigs
    seeds = args.seeds
    try:
        rows = render_rows(
            presets,
            seeds=seeds,
            jitters=args.jitters,
            width=args.width,
            height=args.height,
            progress=not args.quiet,
        )
    except ValueError as exc:
        raise SystemExit(f"hairbrush vision calibrate: {exc}") from exc
    out = Path(args.out)
    rho = rank_correlation(rows, "rc")
    rho_ratio = rank_correlation(rows, "ratio")
    per_wig = {}
    for r in rows:
        per_wig.setdefault(r["wig"], {"rp": r["rp"], "rc": [], "ratio": []})
        per_wig[r["wig"]]["rc"].append(r["rc"])
        per_wig[r["wig"]]["ratio"].append(r["ratio"])
    means = {
        w: {"rp": v["rp"], "rc": float(np.mean(v["rc"])), "ratio": float(np.mean(v["ratio"]))}
        for w, v in per_wig.items()
    }
    write_text(out / "vision_calibration.csv", rows_to_csv(rows))
    write_json(
        out / "vision_calibration.json",
        {
            "spearman_rho": rho,
            "spearman_rho_unclipped": rho_ratio,
            "mean_per_wig": means,
            "n_images": len(rows),
            "resolution": [args.width, args.height],
        },
    )
    plot_calibration(rows, out / "vision_calibration.png")
    for w, v in means.items():
        print(f"{w:12s} R/P {v['rp']:.2f}  R_c {v['rc']:.3f}  unclipped {v['ratio']:.3f}")
    for cond in rho:
        print(f"Spearman rho vs R/P, {cond}: R_c {rho[cond]:.3f}, unclipped {rho_ratio[cond]:.3f}")
    print(f"wrote {out / 'vision_calibration.png'}, .csv, .json")
    return 0


def _seed_list(text: str) -> list[int]:
    return [integer(0)(v.strip()) for v in text.split(",") if v.strip()]


def register_vision(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("vision", help="vision curliness R_c (thesis eq. 3.5): calibration on rendered wigs")
    vsub = p.add_subparsers(dest="action", required=True, metavar="ACTION")
    cal = vsub.add_parser(
        "calibrate", help="R_c vs true R/P for every preset (thesis Fig. 3.4): PNG, CSV, JSON"
    )
    cal.add_argument(
        "--wigs", type=wig_names(allow_held_out=False), default="all", help="comma-separated presets or 'all'"
    )
    cal.add_argument(
        "--seeds", type=_seed_list, default="0,1,2", help="pre-brushed states per wig (comma-separated)"
    )
    cal.add_argument(
        "--jitters", type=count, default=3, help="camera placements per state (first is nominal)"
    )
    add_webcam_args(cal)
    cal.add_argument("--out", type=output_dir, default="runs/vision", help="output directory")
    cal.add_argument("--quiet", action="store_true", help="no progress bar")
    cal.set_defaults(func=_cmd_vision_calibrate)
