"""Fit the sigmoid steepness k of eq. 3.3 in simulation (thesis Fig. 3.9) — thin wrapper over controllers.sigmoid_fit.

    python scripts/fit_sigmoid.py [--physics v3] [--seeds 0,1] [--tol 0.05] [--wigs all] [--workers N | --ray auto] \
        --out runs/sigmoid

Writes OUT/sigmoid_fit.json (k, bounds, per-wig safe lengths), OUT/sigmoid_fit.png, OUT/safe_points.json (per wig,
as each finishes: a rerun with the same settings resumes) and OUT/cells.csv (per-wig timing and errors).
"""

from __future__ import annotations

import argparse
import json
import os
from dataclasses import asdict
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np

import hairbrush_env  # noqa: F401
from controllers.sigmoid import THESIS_K
from controllers.sigmoid_fit import SafePoint, fit_k, plot_fit, safe_point
from hairbrush_env.commands import add_executor_args, add_physics_arg, add_webcam_args, executor_from_args
from hairbrush_env.commands.checks import number_list, positive, seed, wig_names
from hairbrush_env.executor import CellLog, CellsFailed, run_cells
from hairbrush_env.io import write_json


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--wigs", type=wig_names(), default="all", help="comma-separated wig names, 'all' presets")
    p.add_argument("--seeds", type=number_list(seed), default="0,1", help="pre-brushed wigs tried per b_l")
    p.add_argument("--tol", type=positive, default=0.05, help="bisection tolerance on b_l")
    add_webcam_args(p)
    add_physics_arg(p)
    add_executor_args(p, workers=1, what="wigs")
    p.add_argument("--out", default="runs/sigmoid")
    a = p.parse_args()
    wigs, seeds = a.wigs, [int(s) for s in a.seeds]
    # per-wig points, rewritten after every wig: a rerun with the same settings skips the wigs already found
    out = Path(a.out)
    settings = {"seeds": seeds, "tol": a.tol, "width": a.width, "height": a.height, "physics": a.physics}
    saved = json.loads((out / "safe_points.json").read_text()) if (out / "safe_points.json").exists() else {}
    found = (
        {w: SafePoint(**pt) for w, pt in saved.get("points", {}).items()}
        if saved.get("settings") == settings
        else {}
    )
    cells = [(wig, (wig, seeds, a.tol, a.width, a.height, a.physics)) for wig in wigs if wig not in found]
    executor = executor_from_args(a)
    log = CellLog(out / "cells.csv", executor)
    for outcome in run_cells(
        safe_point, cells, executor=executor, desc="wigs", unit="wig", already_done=len(found)
    ):
        log.record(outcome)
        if outcome.ok:
            found[outcome.key] = outcome.value
            write_json(
                out / "safe_points.json",
                {"settings": settings, "points": {w: asdict(pt) for w, pt in found.items()}},
            )
    if log.failed:
        raise SystemExit(str(CellsFailed("wig(s)", log.failed)))
    points = [found[wig] for wig in wigs]  # in the order asked, whichever worker finished first
    k, lo, hi = fit_k([pt.rc for pt in points], [pt.safe_length for pt in points])
    write_json(
        f"{a.out}/sigmoid_fit.json",
        {
            "k": k,
            "k_lower": lo,
            "k_upper": hi if np.isfinite(hi) else None,  # None: unbounded (strict JSON has no Infinity)
            "thesis_k": THESIS_K,
            "physics": a.physics,
            "points": [pt.__dict__ for pt in points],
        },
    )
    plot_fit(points, k, f"{a.out}/sigmoid_fit.png", thesis_k=THESIS_K)
    for pt in points:
        print(
            f"{pt.wig:12s} R/P={pt.rp:.2f} R_c={pt.rc:.3f} safe b_l={pt.safe_length:.3f} ({pt.trials} strokes)"
        )
    print(f"fitted k = {k:.3f} (bounds {lo:.3f} .. {hi:.3f}); thesis k = {THESIS_K}")


if __name__ == "__main__":
    main()
