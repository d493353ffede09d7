"""Benchmark SB3 training throughput (env steps per second) with 1 vs 2 workers (prints a table).

    python scripts/benchmark_rl.py [--env HairBrushContinuous-v0] [--steps 512] [--wig curly]

Both rows come from one run (the machine is shared: compare the ratio). 1 worker runs in-process (DummyVecEnv),
2 workers in subprocesses (SubprocVecEnv), as ``scripts/train_rl.py`` does.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time

os.environ.setdefault("MUJOCO_GL", "egl")

from controllers.rl_training import TrainConfig, train


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument(
        "--env", default="HairBrushContinuous-v0", choices=["HairBrush-v0", "HairBrushContinuous-v0"]
    )
    p.add_argument("--algo", default="ppo", choices=["ppo", "sac"])
    p.add_argument("--steps", type=int, default=512)
    p.add_argument("--wig", default="curly", help="training wigs ('train' or names; default curly)")
    a = p.parse_args()
    rows = []
    for n_envs, vec in ((1, "dummy"), (2, "subproc")):
        cfg = TrainConfig(
            env=a.env,
            algo=a.algo,
            total_timesteps=a.steps,
            n_envs=n_envs,
            vec_env=vec,
            wig=a.wig,
            eval_episodes=0,  # no evaluation inside the timed run
            checkpoint_freq=10 * a.steps,
            progress_bar=False,
        )
        with tempfile.TemporaryDirectory() as out:
            t0 = time.perf_counter()
            train(cfg, out)
            wall = time.perf_counter() - t0
        rows.append((n_envs, vec, a.steps / wall, wall))
    print(
        f"| workers | vec env | env steps/s | wall [s] |  ({a.env}, {a.algo}, {a.steps} steps, wig {a.wig})"
    )
    print("|---:|---|---:|---:|")
    for n, vec, sps, wall in rows:
        print(f"| {n} | {vec} | {sps:.2f} | {wall:.1f} |")
    print(f"\nspeed-up 2 workers vs 1 (same run): {rows[1][2] / rows[0][2]:.2f}x")


if __name__ == "__main__":
    main()
