"""Train a stable-baselines3 agent on a brushing env (thin wrapper over controllers.rl_training).

    python scripts/train_rl.py --algo sac --total-timesteps 5000 --n-envs 2 --seed 0 --out runs/sac
    python scripts/train_rl.py --resume runs/sac                         # continue a stopped run
    python scripts/train_rl.py --resume runs/sac --total-timesteps 8000  # ... and extend it

Trains on the training wigs (hair.TRAIN_WIGS at shake seeds 0-3) and evaluates on the held-out wigs
(hair.HELD_OUT_WIGS at seeds 100-102) every --eval-freq steps. Writes OUT/model.zip, OUT/progress.csv,
OUT/eval/held_out.csv, OUT/learning_curves.png and a checkpoint every --checkpoint-freq steps (Ctrl-C writes one
too). Compare the result with the thesis controllers:
``hairbrush compare --wigs held_out --policies sigmoid,naive,human,sb3:OUT``.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

from controllers.learning_curves import plot_learning_curves
from controllers.rl_checkpoint import latest_checkpoint
from controllers.rl_training import ALGOS, TrainConfig, train

DEFAULTS = TrainConfig()


def parse(argv: list[str] | None = None) -> tuple[TrainConfig, Path, bool]:
    p = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=lambda prog: argparse.RawDescriptionHelpFormatter(prog, max_help_position=32),
    )
    d = DEFAULTS
    p.add_argument("--env", default=d.env, choices=["HairBrush-v0", "HairBrushContinuous-v0"], help="env id")
    p.add_argument("--algo", default=d.algo, choices=ALGOS, help=f"agent (default {d.algo})")
    p.add_argument("--total-timesteps", type=int, help=f"env steps in all (default {d.total_timesteps})")
    p.add_argument("--n-envs", type=int, default=d.n_envs, help=f"vectorized workers (default {d.n_envs})")
    p.add_argument("--seed", type=int, default=d.seed, help=f"seed (default {d.seed})")
    p.add_argument(
        "--wig", default=d.wig, help="training wigs: 'train', or comma-separated names (default train)"
    )
    p.add_argument("--eval-wigs", default=d.eval_wigs, help="evaluation wigs (default held_out)")
    p.add_argument(
        "--obs-mode", default=d.obs_mode, choices=["state", "image", "state+image"], help="observations"
    )
    p.add_argument(
        "--eval-freq", type=int, default=d.eval_freq, help=f"steps between evaluations ({d.eval_freq})"
    )
    p.add_argument(
        "--eval-episodes",
        type=int,
        default=d.eval_episodes,
        help="episodes per evaluation wig (0: no evaluation)",
    )
    p.add_argument("--checkpoint-freq", type=int, default=d.checkpoint_freq, help="steps between checkpoints")
    p.add_argument("--tensorboard", action="store_true", help="also log to OUT/tb")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument(
        "--vec-env", default=d.vec_env, choices=["subproc", "dummy"], help="worker processes or in-process"
    )
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--out", help="run directory of a new run")
    where.add_argument("--resume", metavar="DIR", help="continue the run in DIR from its last checkpoint")
    a = p.parse_args(argv)
    if a.resume and latest_checkpoint(a.resume) is None:
        p.error(f"--resume: {a.resume} has no checkpoint to resume from")
    if a.out and (Path(a.out) / "config.json").exists():
        p.error(f"--out: {a.out} already holds a training run (continue it with --resume {a.out})")
    try:
        if a.resume:
            # the run's own config; only the length and the progress bar may change
            cfg = TrainConfig.from_json(Path(a.resume) / "config.json")
            changes = {"progress_bar": not a.no_progress}
            if a.total_timesteps is not None:
                changes["total_timesteps"] = a.total_timesteps
            return dataclasses.replace(cfg, **changes), Path(a.resume), True
        cfg = TrainConfig(
            env=a.env,
            algo=a.algo,
            total_timesteps=d.total_timesteps if a.total_timesteps is None else a.total_timesteps,
            n_envs=a.n_envs,
            seed=a.seed,
            wig=a.wig,
            eval_wigs=a.eval_wigs,
            obs_mode=a.obs_mode,
            eval_freq=a.eval_freq,
            eval_episodes=a.eval_episodes,
            checkpoint_freq=a.checkpoint_freq,
            tensorboard=a.tensorboard,
            progress_bar=not a.no_progress,
            vec_env=a.vec_env,
        )
    except FileNotFoundError:
        p.error(f"--resume: {a.resume} has no config.json (not a training run)")
    except ValueError as e:
        p.error(f"--{str(e).split(':')[0].replace('_', '-')}: {str(e).split(':', 1)[-1].strip()}")
    return cfg, Path(a.out), False


def main(argv: list[str] | None = None) -> int:
    cfg, out, resume = parse(argv)
    try:
        train(cfg, out, resume=resume)
    except KeyboardInterrupt:
        print(f"\ninterrupted; checkpoint written. Continue with: python scripts/train_rl.py --resume {out}")
        return 130
    png = plot_learning_curves(out)
    print(f"wrote {out}/model.zip, {out}/progress.csv, {out}/eval/held_out.csv and {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
