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
import multiprocessing
import signal
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from hairbrush_env.io import atomic_path, write_json

ALGOS = ("ppo", "sac")
# info entries the training Monitor logs per episode (their final-step values), for the reward-hacking analysis
MONITOR_INFO = ("max_force", "pain_violations", "entanglement", "entanglement_initial", "sim_time")


@dataclass(frozen=True)
class TrainConfig:
    env: str = "HairBrush-v0"
    algo: str = "sac"
    total_timesteps: int = 2000
    n_envs: int = 2
    seed: int = 0
    # training wigs: "train" (hair.TRAIN_WIGS), preset names (comma-separated) or a WigConfig; every worker holds
    # them all and each episode picks one, at the training shake seeds hair.TRAIN_WIG_SEEDS
    wig: Any = "train"
    # evaluation wigs: "held_out" (hair.HELD_OUT_WIGS at hair.HELD_OUT_SEEDS), names or a WigConfig
    eval_wigs: Any = "held_out"
    obs_mode: str = "state"
    max_episode_steps: int | None = None  # None: the registered limit
    eval_freq: int = 500  # env steps (summed over workers) between evaluations
    eval_episodes: int = 1  # episodes per evaluation wig; 0: no evaluation
    checkpoint_freq: int = 50  # env steps between checkpoints (a stroke costs ~20 s of CPU: lose little)
    tensorboard: bool = False
    progress_bar: bool = True
    vec_env: str = "subproc"  # "subproc" (one process per worker) or "dummy" (in-process)

    def __post_init__(self) -> None:
        if self.algo not in ALGOS:
            raise ValueError(f"algo: expected one of {ALGOS}, got {self.algo!r}")
        if self.env not in ("HairBrush-v0", "HairBrushContinuous-v0"):
            raise ValueError(f"env: expected HairBrush-v0 or HairBrushContinuous-v0, got {self.env!r}")
        for name in ("total_timesteps", "n_envs", "eval_freq", "checkpoint_freq"):
            if int(getattr(self, name)) < 1:
                raise ValueError(f"{name}: must be a positive integer, got {getattr(self, name)!r}")
        if int(self.eval_episodes) < 0:
            raise ValueError(f"eval_episodes: must be an integer >= 0, got {self.eval_episodes!r}")
        if int(self.seed) < 0:
            raise ValueError(f"seed: must be an integer >= 0, got {self.seed!r}")
        training_wigs(self.wig)  # unknown names fail here, not in a worker process
        training_wigs(self.eval_wigs)
        if self.vec_env not in ("subproc", "dummy"):
            raise ValueError(f"vec_env: expected 'subproc' or 'dummy', got {self.vec_env!r}")

    @classmethod
    def from_json(cls, path: str | Path) -> TrainConfig:
        """The config a run wrote into its ``config.json`` (custom WigConfigs are stored by name only)."""
        raw = json.loads(Path(path).read_text())
        return cls(**{k: v for k, v in raw.items() if k in cls.__dataclass_fields__})


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
    # the buffer holds the whole run (strokes are expensive, none is worth forgetting) and stays small to checkpoint;
    # two gradient steps per collected stroke: an update costs milliseconds, a stroke 10-40 s of physics
    return sb3.SAC(
        learning_starts=min(200, cfg.total_timesteps // 4),
        gradient_steps=2 * max(cfg.n_envs, 1),
        buffer_size=max(1_000, min(50_000, cfg.total_timesteps)),
        gamma=0.95,
        **common,
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
                    self._writer = csv.DictWriter(
                        self._fh, fieldnames=list(row), extrasaction="ignore", lineterminator="\n"
                    )
                    if self._fh.tell() == 0:
                        self._writer.writeheader()
                self._writer.writerow(row)
            self._fh.flush()
            return True

        def _on_training_end(self) -> None:
            self._fh.close()

    return StepLog()


def training_wigs(wig: Any) -> list[Any]:
    """The wigs of a wig argument: a WigConfig → itself; ``"train"`` → :data:`hair.TRAIN_WIGS`; ``"held_out"`` →
    :data:`hair.HELD_OUT_WIGS`; ``"wavy,curly"`` → those names (validated)."""
    from hairbrush_env.hair import wig_names

    if not isinstance(wig, str):
        return [wig]
    try:
        return wig_names(wig, sets=("train", "held_out"))
    except ValueError as exc:
        raise ValueError(f"wig: {exc}") from None


def wig_seeds_for(wig: Any) -> tuple[int, ...]:
    """Shake seeds of a wig set (:func:`hairbrush_env.hair.brushing_seeds`)."""
    from hairbrush_env.hair import brushing_seeds

    return brushing_seeds(training_wigs(wig))


def _vec_env(env_id, worker_wigs, seed, env_kwargs, vec_cls, monitor_dir, monitor_prefix="0"):
    """One worker per entry of ``worker_wigs`` (a wig or a list of wigs the worker's episodes pick from), each
    wrapped in a Monitor (CSV ``monitor_dir/<prefix>-<rank>.monitor.csv`` if ``monitor_dir``).

    What SB3's ``make_vec_env`` does, plus the wigs per worker and a file prefix per resumed segment.
    """

    def maker(rank: int):
        def make():
            from stable_baselines3.common.monitor import Monitor

            from hairbrush_env.envs import make_version

            if multiprocessing.parent_process() is not None:
                # a worker process: Ctrl-C is the trainer's to handle (it finishes the step and checkpoints)
                signal.signal(signal.SIGINT, signal.SIG_IGN)
            wigs = worker_wigs[rank]
            env = make_version(env_id, **{**env_kwargs, "wig": wigs[0] if len(wigs) == 1 else list(wigs)})
            path = None if monitor_dir is None else str(Path(monitor_dir) / f"{monitor_prefix}-{rank}")
            return Monitor(env, filename=path, info_keywords=MONITOR_INFO)

        return make

    if monitor_dir is not None:
        Path(monitor_dir).mkdir(parents=True, exist_ok=True)
    venv = vec_cls([maker(i) for i in range(len(worker_wigs))])
    venv.seed(seed)  # worker i resets with seed + i, as make_vec_env does
    return venv


def _env_kwargs(cfg: TrainConfig) -> dict[str, Any]:
    """Keyword arguments of every env of a run (training and evaluation share one observation space)."""
    kwargs: dict[str, Any] = {"obs_mode": cfg.obs_mode}
    if cfg.max_episode_steps is not None:
        kwargs["max_episode_steps"] = int(cfg.max_episode_steps)  # consumed by gymnasium.make
    if cfg.env == "HairBrush-v0":
        # the force trace of the longest wig's full stroke, over training and evaluation wigs
        from hairbrush_env.envs.stroke import default_trace_length
        from hairbrush_env.hair import get_wig

        wigs = training_wigs(cfg.wig) + (training_wigs(cfg.eval_wigs) if cfg.eval_episodes else [])
        kwargs["trace_length"] = max(default_trace_length(get_wig(w).hanging_length) for w in wigs)
    return kwargs


class RunExistsError(ValueError):
    """``out`` already holds a training run (resume it or choose another directory)."""


def train(cfg: TrainConfig, out: str | Path, *, resume: bool = False):
    """Train (or, with ``resume``, continue the run in ``out`` from its last checkpoint), evaluate on the held-out
    wigs and save; returns the trained model.

    An interrupt (Ctrl-C) writes a checkpoint before it propagates; a killed process loses the steps since the
    last periodic checkpoint (``checkpoint_freq``). Logs are appended across resumes.
    """
    import stable_baselines3 as sb3
    from stable_baselines3.common.callbacks import CallbackList
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv

    from .held_out_eval import evaluation_means, held_out_eval_callback
    from .rl_checkpoint import (
        appending_csv_logger,
        checkpoint_callback,
        checkpoint_state,
        latest_checkpoint,
        load_checkpoint,
        save_checkpoint,
        truncate_logs,
    )

    out = Path(out)
    ckpt = latest_checkpoint(out)
    if resume and ckpt is None:
        raise ValueError(f"resume: no checkpoint in {out / 'checkpoint'} to resume from")
    if not resume and (out / "config.json").exists():
        raise RunExistsError(
            f"out: {out} already holds a training run; resume it with --resume {out} or choose another --out"
        )
    out.mkdir(parents=True, exist_ok=True)
    state = checkpoint_state(ckpt) if resume else {"num_timesteps": 0, "segment": -1}
    done_steps, segment = int(state["num_timesteps"]), int(state.get("segment", -1)) + 1
    if done_steps >= cfg.total_timesteps:
        print(f"{out}: already trained {done_steps} >= {cfg.total_timesteps} steps; nothing to do")
        model = load_checkpoint(ckpt, getattr(sb3, cfg.algo.upper()), None)
        with atomic_path(out / "model.zip") as tmp:
            model.save(tmp)
        return model
    if resume:
        truncate_logs(out, done_steps, float(state["wall_time"]))
    vec_cls = SubprocVecEnv if (cfg.vec_env == "subproc" and cfg.n_envs > 1) else DummyVecEnv
    # "module:EnvId" makes gymnasium import hairbrush_env (which registers the envs) inside each worker process;
    # SB3 starts SubprocVecEnv workers with forkserver, which does not inherit the parent's registry.
    env_id = f"hairbrush_env:{cfg.env}"
    kwargs = _env_kwargs(cfg) | {"state_cache_dir": str(out / "state_cache")}  # workers shake each state once
    wigs = training_wigs(cfg.wig)
    # a resumed segment seeds its workers from the step count: new episodes, not a replay of the first segment's
    venv = _vec_env(
        env_id, [wigs] * cfg.n_envs, cfg.seed + done_steps, {**kwargs, "wig_seeds": wig_seeds_for(cfg.wig)},
        vec_cls, out / "monitor", monitor_prefix=str(segment),
    )  # fmt: skip
    eval_env = None
    if cfg.eval_episodes:
        eval_wigs = training_wigs(cfg.eval_wigs)
        eval_cls = SubprocVecEnv if (cfg.vec_env == "subproc" and len(eval_wigs) > 1) else DummyVecEnv
        eval_env = _vec_env(
            env_id, [[w] for w in eval_wigs], cfg.seed + 10_000,
            {**kwargs, "wig_seeds": wig_seeds_for(cfg.eval_wigs)}, eval_cls, None,
        )  # fmt: skip
    # written first, so checkpoints of an interrupted run can be loaded and described
    (out / "algo.txt").write_text(cfg.algo.upper() + "\n")
    write_json(
        out / "config.json", asdict(cfg) | {"wig": _describe(cfg.wig), "eval_wigs": _describe(cfg.eval_wigs)}
    )
    try:
        if resume:
            model = load_checkpoint(ckpt, getattr(sb3, cfg.algo.upper()), venv)
        else:
            model = _make_algo(cfg, venv, out)
        model.set_logger(appending_csv_logger(out, cfg.tensorboard))
        checkpoints = checkpoint_callback(out, cfg.checkpoint_freq, segment=segment)
        callbacks = [checkpoints, _step_log_callback(out / "steps.csv")]
        if eval_env is not None:
            evals = evaluation_means(out / "eval" / "held_out.csv")
            best = max((e["return"] for e in evals), default=-np.inf)
            callbacks.insert(
                0,
                held_out_eval_callback(
                    eval_env, out, every=cfg.eval_freq, episodes=cfg.eval_episodes, seed=cfg.seed + 10_000,
                    best_return=best,
                ),
            )  # fmt: skip
        try:
            model.learn(
                total_timesteps=cfg.total_timesteps - done_steps,
                callback=CallbackList(callbacks),
                progress_bar=cfg.progress_bar,
                reset_num_timesteps=not resume,
            )
        finally:
            checkpoints.restore_handler()  # SB3 skips on_training_end when a callback raises
        save_checkpoint(model, out, segment=segment)
        with atomic_path(out / "model.zip") as tmp:
            model.save(tmp)
    finally:
        venv.close()
        if eval_env is not None:
            eval_env.close()
    return model


def _describe(wig: Any) -> Any:
    return wig if isinstance(wig, str) else getattr(wig, "name", str(wig))
