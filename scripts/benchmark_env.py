"""Benchmark the brushing envs (prints tables).

    python scripts/benchmark_env.py [--quick] [--wig curly]

1. Strokes per second of HairBrush-v0 (one step = one stroke, the same seeded actions), body-chain strands vs the
   wave-1 flex wig, and 1 vs 2 vectorized workers (gymnasium AsyncVectorEnv, strokes/s summed over workers).
2. Env steps per second and simulated seconds per wall-clock second of HairBrush-v0 and HairBrushContinuous-v0
   (one step = 0.1 s) with state vs state+image observations.

All rows come from one run, so compare ratios between rows; the machine is shared.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("MUJOCO_GL", "egl")

import gymnasium as gym
import numpy as np

import hairbrush_env  # noqa: F401  (registers the envs)
from hairbrush_env.hair import PRESETS, wave1_wig


def _policy_action(env_id: str, space, rng) -> np.ndarray:
    if env_id == "HairBrush-v0":
        return rng.uniform(-1, 1, size=space.shape).astype(np.float32)
    # continuous: mostly pull down through the hair, a little depth jitter
    a = np.array([-0.5, 0.0], np.float32) + rng.normal(0, 0.1, 2).astype(np.float32)
    return np.clip(a, -1, 1)


def bench_single(env_id: str, obs_mode: str, steps: int, wig: str) -> tuple[float, float]:
    env = gym.make(env_id, wig=wig, obs_mode=obs_mode)
    rng = np.random.default_rng(0)
    env.reset(seed=0)
    sim_t = 0.0
    t0 = time.perf_counter()
    for _ in range(steps):
        _, _, term, trunc, info = env.step(_policy_action(env_id, env.action_space, rng))
        if term or trunc:
            sim_t += info["sim_time"]
            env.reset()
    sim_t += info["sim_time"]
    wall = time.perf_counter() - t0
    env.close()
    return steps / wall, sim_t / wall


def bench_vector(env_id: str, obs_mode: str, steps: int, workers: int, wig: str) -> float:
    venv = gym.vector.AsyncVectorEnv(
        [lambda: gym.make(env_id, wig=wig, obs_mode=obs_mode) for _ in range(workers)], shared_memory=False
    )
    rng = np.random.default_rng(0)
    venv.reset(seed=0)
    t0 = time.perf_counter()
    for _ in range(steps):
        venv.step(np.stack([_policy_action(env_id, venv.single_action_space, rng) for _ in range(workers)]))
    wall = time.perf_counter() - t0
    venv.close()
    return steps * workers / wall


def strand_models(name: str) -> dict[str, object]:
    """The default (chain) preset and the wave-1 flex wig of the same preset (``hair.wave1_wig``: 5 edges per turn,
    ≤ 16 edges, κ = 50, compact lattice), both in the env's default scene."""
    wig = PRESETS[name]
    return {"chain": wig, "flex wave 1": wave1_wig(wig)}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true", help="fewer steps")
    p.add_argument("--wig", default="curly", choices=list(PRESETS))
    a = p.parse_args()
    n_stroke, n_cont = (3, 20) if a.quick else (10, 100)
    print(
        f"## HairBrush-v0 strokes/s on '{a.wig}', chain vs flex, 1 vs 2 workers ({n_stroke} strokes each)\n"
    )
    print("| strands | workers | strokes/s | × flex | × 1 worker |")
    print("|---|---:|---:|---:|---:|")
    rates = {
        (label, workers): bench_vector("HairBrush-v0", "state", n_stroke, workers, wig)
        for label, wig in strand_models(a.wig).items()
        for workers in (1, 2)
    }
    for (label, workers), sps in rates.items():
        vs_flex = sps / rates[("flex wave 1", workers)]
        print(f"| {label} | {workers} | {sps:.3f} | {vs_flex:.2f} | {sps / rates[(label, 1)]:.2f} |")
    print(f"\n## Env speed by observation mode on '{a.wig}'\n")
    print("| env | obs | workers | steps/s | sim s / wall s |")
    print("|---|---|---:|---:|---:|")
    for env_id, n in (("HairBrush-v0", n_stroke), ("HairBrushContinuous-v0", n_cont)):
        for obs_mode in ("state", "state+image"):
            sps, rtf = bench_single(env_id, obs_mode, n, a.wig)
            print(f"| {env_id} | {obs_mode} | 1 | {sps:.2f} | {rtf:.2f} |", flush=True)
        for workers in (1, 2):
            sps = bench_vector(env_id, "state", n, workers, a.wig)
            print(f"| {env_id} | state (AsyncVectorEnv) | {workers} | {sps:.2f} | — |", flush=True)


if __name__ == "__main__":
    main()
