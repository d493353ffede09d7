"""Training stable-baselines3 agents on the brushing envs through ``gymnasium.make`` (issue #6).

State observations (the fast default) and images both come as a Dict, so the agents use SB3's
``MultiInputPolicy``: an MLP over the force features, plus a CNN for the image when ``obs_mode`` includes it.
Outputs in ``out``: ``model.zip`` (final), ``best/best_model.zip`` (eval callback), ``checkpoints/``,
``progress.csv`` (SB3's CSV logger), ``eval/evaluations.npz``, ``monitor/*.monitor.csv`` (one row per training
episode), ``steps.csv`` (one row per env step: action, b_l, force, reward terms), ``algo.txt`` and ``config.json``.
"""

from __future__ import annotations

import csv
import json
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

ALGOS = ("ppo", "sac")
# info entries the training Monitor logs per episode (their final-step values), for the reward-hacking analysis
MONITOR_INFO = ("max_force", "pain_violations", "entanglement", "entanglement_initial", "sim_time")


@dataclass(frozen=True)
class TrainConfig:
    env: str = "HairBrush-v0"
    algo: str = "ppo"
    total_timesteps: int = 2000
    n_envs: int = 2
    seed: int = 0
    wig: Any = "curly"  # preset name, WigConfig, or comma-separated presets (worker i trains on wig i mod n)
    obs_mode: str = "state"
    max_episode_steps: int | None = None  # None: the registered limit
    eval_freq: int = 500  # env steps (summed over workers) between evaluations
    eval_episodes: int = 2
    checkpoint_freq: int = 1000
    tensorboard: bool = False
    progress_bar: bool = True
    vec_env: str = "subproc"  # "subproc" (one process per worker) or "dummy" (in-process)

    def __post_init__(self) -> None:
        if self.algo not in ALGOS:
            raise ValueError(f"algo: expected one of {ALGOS}, got {self.algo!r}")
        if self.env not in ("HairBrush-v0", "HairBrushContinuous-v0"):
            raise ValueError(f"env: expected HairBrush-v0 or HairBrushContinuous-v0, got {self.env!r}")
        for name in ("total_timesteps", "n_envs", "eval_freq", "eval_episodes", "checkpoint_freq"):
            if int(getattr(self, name)) < 1:
                raise ValueError(f"{name}: must be a positive integer, got {getattr(self, name)!r}")
        training_wigs(self.wig)  # unknown preset names fail here, not in a worker process
        if self.vec_env not in ("subproc", "dummy"):
            raise ValueError(f"vec_env: expected 'subproc' or 'dummy', got {self.vec_env!r}")


def _make_algo(cfg: TrainConfig, venv, log_dir: Path):
    import stable_baselines3 as sb3

    common = dict(policy="MultiInputPolicy", env=venv, seed=cfg.seed, device="cpu", verbose=0)
    if cfg.tensorboard:
        common["tensorboard_log"] = str(log_dir / "tb")
    if cfg.algo == "ppo":
        # Episodes are short (≤ 30 strokes) and each step is expensive: small rollouts, several epochs.
        n_steps = max(8, min(128, cfg.total_timesteps // max(cfg.n_envs, 1) // 2))
        batch = max(8, min(64, n_steps * cfg.n_envs // 2))
        return sb3.PPO(n_steps=n_steps, batch_size=batch, n_epochs=10, gamma=0.95, **common)
    return sb3.SAC(
        learning_starts=min(200, cfg.total_timesteps // 4), buffer_size=50_000, gamma=0.95, **common
    )


STEP_LOG_INFO = ("brush_length", "max_force", "aborted", "finished_rule")


def _step_log_callback(path: Path):
    """An SB3 callback appending every env step to ``path`` (CSV): the agent's actions and what they earned.

    The Monitor keeps one row per episode; the reward-hacking check needs the strokes themselves (e.g. whether the
    agent drifts to the shortest b_l). Append-only and flushed per step: a killed run keeps what it logged.
    """
    from stable_baselines3.common.callbacks import BaseCallback

    class StepLog(BaseCallback):
        def _on_training_start(self) -> None:
            self._fh = path.open("a", newline="")
            self._writer = None

        def _on_step(self) -> bool:
            actions = np.asarray(self.locals.get("actions"))
            rewards = np.asarray(self.locals.get("rewards"))
            dones = np.asarray(self.locals.get("dones"))
            for i, info in enumerate(self.locals.get("infos", [])):
                row = {"timesteps": self.num_timesteps, "env": i}
                row.update({f"action_{j}": float(a) for j, a in enumerate(np.ravel(actions[i]))})
                row.update(reward=float(rewards[i]), done=bool(dones[i]))
                row.update({k: v for k, v in info.items() if k.startswith("reward_") or k in STEP_LOG_INFO})
                if self._writer is None:
                    self._writer = csv.DictWriter(self._fh, fieldnames=list(row), extrasaction="ignore")
                    if self._fh.tell() == 0:
                        self._writer.writeheader()
                self._writer.writerow(row)
            self._fh.flush()
            return True

        def _on_training_end(self) -> None:
            self._fh.close()

    return StepLog()


def training_wigs(wig: Any) -> list[Any]:
    """The wigs of a run: a WigConfig or preset name → one; ``"wavy,curly"`` → several (validated names)."""
    if not isinstance(wig, str):
        return [wig]
    from hairbrush_env.hair import PRESETS

    names = [w.strip() for w in wig.split(",") if w.strip()]
    bad = [w for w in names if w not in PRESETS]
    if not names or bad:
        raise ValueError(f"wig: unknown preset(s) {bad or [wig]!r}; known: {sorted(PRESETS)}")
    return names


def _vec_env(env_id, wigs, n_envs, seed, env_kwargs, vec_cls, monitor_dir):
    """``n_envs`` workers, worker i on ``wigs[i % len(wigs)]``, each wrapped in a Monitor (CSV if ``monitor_dir``).

    What SB3's ``make_vec_env`` does, plus a wig per worker.
    """

    def maker(rank: int):
        def make():
            import gymnasium as gym
            from stable_baselines3.common.monitor import Monitor

            env = gym.make(env_id, **{**env_kwargs, "wig": wigs[rank % len(wigs)]})
            path = None if monitor_dir is None else str(Path(monitor_dir) / str(rank))
            return Monitor(env, filename=path, info_keywords=MONITOR_INFO)

        return make

    if monitor_dir is not None:
        Path(monitor_dir).mkdir(parents=True, exist_ok=True)
    venv = vec_cls([maker(i) for i in range(n_envs)])
    venv.seed(seed)  # worker i resets with seed + i, as make_vec_env does
    return venv


def train(cfg: TrainConfig, out: str | Path):
    """Train, evaluate and save; returns the trained model."""
    from stable_baselines3.common.callbacks import CallbackList, CheckpointCallback, EvalCallback
    from stable_baselines3.common.logger import configure
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    env_kwargs: dict[str, Any] = {"wig": cfg.wig, "obs_mode": cfg.obs_mode}
    if cfg.max_episode_steps is not None:
        env_kwargs["max_episode_steps"] = int(cfg.max_episode_steps)  # consumed by gymnasium.make
    vec_cls = SubprocVecEnv if (cfg.vec_env == "subproc" and cfg.n_envs > 1) else DummyVecEnv
    # "module:EnvId" makes gymnasium import hairbrush_env (which registers the envs) inside each worker process;
    # SB3 starts SubprocVecEnv workers with forkserver, which does not inherit the parent's registry.
    env_id = f"hairbrush_env:{cfg.env}"
    wigs = training_wigs(cfg.wig)
    if cfg.env == "HairBrush-v0" and len(wigs) > 1:
        # one observation space for all workers: the force trace of the longest wig's full stroke
        from hairbrush_env.envs.stroke import default_trace_length
        from hairbrush_env.hair import get_wig

        env_kwargs["trace_length"] = max(default_trace_length(get_wig(w).hanging_length) for w in wigs)
    # one Monitor CSV per worker: every training episode's return, length and info terms (the learning curve)
    venv = _vec_env(env_id, wigs, cfg.n_envs, cfg.seed, env_kwargs, vec_cls, out / "monitor")
    # same VecEnv type as training (SB3 warns otherwise); one eval env per training wig
    eval_env = _vec_env(env_id, wigs, len(wigs), cfg.seed + 10_000, env_kwargs, vec_cls, None)
    n_eval = max(cfg.eval_episodes, len(wigs))
    # written first, so checkpoints of an interrupted run can be loaded and described
    (out / "algo.txt").write_text(cfg.algo.upper() + "\n")
    (out / "config.json").write_text(json.dumps(asdict(cfg), indent=2, default=str) + "\n")
    try:
        model = _make_algo(cfg, venv, out)
        model.set_logger(configure(str(out), ["csv"] + (["tensorboard"] if cfg.tensorboard else [])))
        callbacks = CallbackList(
            [
                EvalCallback(
                    eval_env,
                    n_eval_episodes=n_eval,
                    eval_freq=max(cfg.eval_freq // cfg.n_envs, 1),
                    best_model_save_path=str(out / "best"),
                    log_path=str(out / "eval"),
                    deterministic=True,
                ),
                CheckpointCallback(
                    save_freq=max(cfg.checkpoint_freq // cfg.n_envs, 1), save_path=str(out / "checkpoints")
                ),
                _step_log_callback(out / "steps.csv"),
            ]
        )
        model.learn(total_timesteps=cfg.total_timesteps, callback=callbacks, progress_bar=cfg.progress_bar)
        model.save(out / "model.zip")
    finally:
        venv.close()
        eval_env.close()
    return model
