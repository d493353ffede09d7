"""Train a stable-baselines3 agent on a brushing env (thin wrapper over controllers.rl_training).

    python scripts/train_rl.py --env HairBrush-v0 --algo ppo --total-timesteps 20000 --n-envs 2 --seed 0 --out runs/ppo

Writes OUT/model.zip and OUT/progress.csv (plus best model, checkpoints, eval log). Compare the result with the
thesis controllers: ``hairbrush compare --policies sigmoid,naive,full,sb3:OUT``.
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("MUJOCO_GL", "egl")

from controllers.learning_curves import plot_learning_curves
from controllers.rl_training import ALGOS, TrainConfig, train


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--env", default="HairBrush-v0", choices=["HairBrush-v0", "HairBrushContinuous-v0"])
    p.add_argument("--algo", default="ppo", choices=ALGOS)
    p.add_argument("--total-timesteps", type=int, default=20_000)
    p.add_argument("--n-envs", type=int, default=2)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument(
        "--wig", default="curly", help="preset, or comma-separated presets: worker i trains on wig i mod n"
    )
    p.add_argument("--obs-mode", default="state", choices=["state", "image", "state+image"])
    p.add_argument("--eval-freq", type=int, default=500)
    p.add_argument("--eval-episodes", type=int, default=2)
    p.add_argument("--checkpoint-freq", type=int, default=2000)
    p.add_argument("--tensorboard", action="store_true")
    p.add_argument("--no-progress", action="store_true")
    p.add_argument("--vec-env", default="subproc", choices=["subproc", "dummy"])
    p.add_argument("--out", required=True)
    a = p.parse_args()
    cfg = TrainConfig(
        env=a.env,
        algo=a.algo,
        total_timesteps=a.total_timesteps,
        n_envs=a.n_envs,
        seed=a.seed,
        wig=a.wig,
        obs_mode=a.obs_mode,
        eval_freq=a.eval_freq,
        eval_episodes=a.eval_episodes,
        checkpoint_freq=a.checkpoint_freq,
        tensorboard=a.tensorboard,
        progress_bar=not a.no_progress,
        vec_env=a.vec_env,
    )
    train(cfg, a.out)
    png = plot_learning_curves(a.out)
    print(f"wrote {a.out}/model.zip, {a.out}/progress.csv and {png}")


if __name__ == "__main__":
    main()
