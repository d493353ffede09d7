"""Fit the sigmoid steepness k of eq. 3.3 in simulation (thesis Fig. 3.9) — thin wrapper over controllers.sigmoid_fit.

    python scripts/fit_sigmoid.py [--seeds 0,1] [--tol 0.05] [--wigs all] --out runs/sigmoid

Writes OUT/sigmoid_fit.json (k, bounds, per-wig safe lengths) and OUT/sigmoid_fit.png.
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("MUJOCO_GL", "egl")

import gymnasium as gym
import numpy as np
from tqdm import tqdm

import hairbrush_env  # noqa: F401
from controllers.sigmoid import THESIS_K
from controllers.sigmoid_fit import SafePoint, fit_k, max_safe_length, plot_fit
from controllers.vision import curliness
from hairbrush_env.commands import add_webcam_args
from hairbrush_env.hair import PRESETS
from hairbrush_env.io import write_json


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--wigs", default="all")
    p.add_argument("--seeds", default="0,1")
    p.add_argument("--tol", type=float, default=0.05)
    add_webcam_args(p)
    p.add_argument("--out", default="runs/sigmoid")
    a = p.parse_args()
    wigs = list(PRESETS) if a.wigs == "all" else a.wigs.split(",")
    seeds = [int(s) for s in a.seeds.split(",")]
    points = []
    for wig in tqdm(wigs, desc="wigs"):
        env = gym.make("HairBrush-v0", wig=wig, obs_mode="state+image", width=a.width, height=a.height)
        rc = float(
            np.mean([curliness(env.reset(seed=s)[0]["image"], roi=env.unwrapped.hair_roi()) for s in seeds])
        )
        safe, trials = max_safe_length(env, seeds, tol=a.tol)
        points.append(SafePoint(wig, env.unwrapped.sim.curliness_true, rc, safe, trials))
        env.close()
    k, lo, hi = fit_k([pt.rc for pt in points], [pt.safe_length for pt in points])
    write_json(
        f"{a.out}/sigmoid_fit.json",
        {
            "k": k,
            "k_lower": lo,
            "k_upper": hi if np.isfinite(hi) else None,  # None: unbounded (strict JSON has no Infinity)
            "thesis_k": THESIS_K,
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
