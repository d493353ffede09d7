"""Training smoke test (issue #6): a few hundred PPO steps through gymnasium.make, then the agent as a policy."""

from __future__ import annotations

import csv
import os
import signal

os.environ.setdefault("MUJOCO_GL", "egl")

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

import hairbrush_env  # noqa: F401
from controllers.learning_curves import plot_learning_curves, training_episodes
from controllers.rl_training import TrainConfig, train
from hairbrush_env.hair import get_wig
from hairbrush_env.policies import make_policy


def test_ppo_smoke_trains_saves_and_plays(tmp_path):
    wig = get_wig("curly").replace(name="test_rl_tiny", n_strands=4, n_triples=0, length=0.12)
    cfg = TrainConfig(
        env="HairBrushContinuous-v0",
        algo="ppo",
        total_timesteps=256,
        n_envs=1,
        vec_env="dummy",
        wig=wig,
        eval_wigs=wig,
        max_episode_steps=32,
        eval_freq=128,
        eval_episodes=1,
        checkpoint_freq=128,
        progress_bar=False,
    )
    train(cfg, tmp_path)
    assert (tmp_path / "model.zip").exists() and (tmp_path / "best" / "best_model.zip").exists()
    rows = list(csv.DictReader((tmp_path / "progress.csv").open()))
    assert rows and int(float(rows[-1]["time/total_timesteps"])) >= 256
    episodes = training_episodes(tmp_path)  # the Monitor logs every training episode with its info terms
    assert len(episodes) >= 256 // 32 - 1 and all(e["l"] <= 32 for e in episodes)
    assert all(0 < e["entanglement_initial"] for e in episodes)
    assert plot_learning_curves(tmp_path).exists()
    steps = list(csv.DictReader((tmp_path / "steps.csv").open()))  # every env step, for the hacking check
    assert len(steps) >= 256 and {"action_0", "action_1", "reward", "reward_finish", "max_force"} <= set(
        steps[0]
    )
    total = sum(float(r["reward"]) for r in steps[: int(episodes[0]["l"])])
    assert total == pytest.approx(episodes[0]["r"], abs=1e-3)  # the step log adds up to the Monitor's return
    env = gym.make("HairBrushContinuous-v0", wig=wig, max_episode_steps=8)
    policy = make_policy(f"sb3:{tmp_path}", env)
    # observations of another length (a wig with a longer or shorter force trace) are zero-padded or cut
    np.testing.assert_array_equal(policy._fit("force", np.array([1.0, 2.0, 3.0, 4.0])), [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(policy._fit("force", np.array([1.0, 2.0])), [1.0, 2.0, 0.0])
    obs, _ = env.reset(seed=0)
    policy.reset(0)
    action = policy.act(obs)
    assert env.action_space.contains(np.asarray(action, np.float32))
    env.step(action)
    env.close()


def test_train_config_validation():
    with pytest.raises(ValueError, match="algo"):
        TrainConfig(algo="dqn")
    with pytest.raises(ValueError, match="n_envs"):
        TrainConfig(n_envs=0)


def test_subprocess_workers_find_the_envs(tmp_path):
    """SB3 starts SubprocVecEnv workers with forkserver: they must register the envs themselves."""
    wig = get_wig("curly").replace(name="test_rl_tiny", n_strands=4, n_triples=0, length=0.12)
    cfg = TrainConfig(
        env="HairBrushContinuous-v0",
        total_timesteps=32,
        n_envs=2,
        vec_env="subproc",
        wig=wig,
        max_episode_steps=8,
        eval_episodes=0,
        checkpoint_freq=10_000,
        progress_bar=False,
    )
    train(cfg, tmp_path)
    assert (tmp_path / "model.zip").exists()


def test_wig_sets_resolve_and_every_worker_holds_all_training_wigs(tmp_path):
    """``--wig wavy,straight``: every worker holds both wigs and each episode picks one (from the env's RNG)."""
    from stable_baselines3.common.vec_env import DummyVecEnv

    from controllers.rl_training import _vec_env, training_wigs, wig_seeds_for
    from hairbrush_env.hair import HELD_OUT_SEEDS, HELD_OUT_WIGS, TRAIN_WIG_SEEDS, TRAIN_WIGS

    assert training_wigs("wavy, straight") == ["wavy", "straight"]
    assert training_wigs("train") == list(TRAIN_WIGS) and training_wigs("held_out") == list(HELD_OUT_WIGS)
    assert wig_seeds_for("held_out") == HELD_OUT_SEEDS and wig_seeds_for("train") == TRAIN_WIG_SEEDS
    assert not set(HELD_OUT_SEEDS) & set(TRAIN_WIG_SEEDS) and not set(HELD_OUT_WIGS) & set(TRAIN_WIGS)
    with pytest.raises(ValueError, match="nope"):
        TrainConfig(wig="wavy,nope")
    venv = _vec_env(
        "hairbrush_env:HairBrushContinuous-v0", [["wavy", "straight"]] * 2, 0, {"obs_mode": "state"},
        DummyVecEnv, tmp_path / "monitor",
    )  # fmt: skip
    try:
        assert all([s.wig.name for s in e.unwrapped.sims] == ["wavy", "straight"] for e in venv.envs)
        seen = set()
        for seed in range(6):
            venv.envs[0].reset(seed=seed)
            seen.add(venv.envs[0].unwrapped.sim.wig.name)
        assert seen == {"wavy", "straight"}
        assert sorted(p.name for p in (tmp_path / "monitor").iterdir()) == [
            "0-0.monitor.csv",
            "0-1.monitor.csv",
        ]
    finally:
        venv.close()


def _tiny_run(**changes) -> TrainConfig:
    wig = get_wig("curly").replace(name="test_rl_tiny", n_strands=4, n_triples=0, length=0.12)
    base = dict(
        env="HairBrushContinuous-v0", algo="sac", total_timesteps=40, n_envs=1, vec_env="dummy", wig=wig,
        eval_wigs=wig, max_episode_steps=8, eval_freq=16, eval_episodes=1, checkpoint_freq=8, progress_bar=False,
    )  # fmt: skip
    return TrainConfig(**(base | changes))


def _stop_at(monkeypatch, step: int, exc: BaseException | None) -> None:
    """Make the next training run raise ``exc`` after env step ``step`` (after that step was logged); None: send
    the process a SIGINT, as Ctrl-C does."""
    from stable_baselines3.common.callbacks import BaseCallback, CallbackList

    import controllers.rl_training as rl

    monkeypatch.undo()  # a second stop replaces the first
    original = rl._step_log_callback

    class Stop(BaseCallback):
        def _on_step(self) -> bool:
            if self.num_timesteps == step:
                if exc is None:
                    os.kill(os.getpid(), signal.SIGINT)
                else:
                    raise exc
            return True

    monkeypatch.setattr(rl, "_step_log_callback", lambda path: CallbackList([original(path), Stop()]))


def test_interrupted_runs_resume_where_they_stopped(tmp_path, monkeypatch):
    """Ctrl-C finishes the step and writes a checkpoint; a crash (a killed process) falls back to the last periodic
    one and the logs written after it are cut; each resume continues the step count and appends to every log."""
    import json

    from controllers.held_out_eval import read_evaluations
    from controllers.rl_checkpoint import checkpoint_state, latest_checkpoint

    cfg = _tiny_run()
    _stop_at(monkeypatch, 12, None)
    with pytest.raises(KeyboardInterrupt, match="stopped at 12 steps"):
        train(cfg, tmp_path)
    assert checkpoint_state(latest_checkpoint(tmp_path))["num_timesteps"] == 12
    with pytest.raises(ValueError, match="already holds a training run"):
        train(cfg, tmp_path)  # a new run may not overwrite this one
    _stop_at(monkeypatch, 30, RuntimeError("killed"))
    with pytest.raises(RuntimeError, match="killed"):
        train(cfg, tmp_path, resume=True)
    state = checkpoint_state(latest_checkpoint(tmp_path))
    assert state["num_timesteps"] == 24 and state["segment"] == 1  # the periodic checkpoint before the crash
    monkeypatch.undo()
    model = train(cfg, tmp_path, resume=True)
    assert model.num_timesteps == 40 and model.replay_buffer.size() == 40
    steps = [int(r["timesteps"]) for r in csv.DictReader((tmp_path / "steps.csv").open())]
    assert steps == list(range(1, 41))  # steps 25-30 of the crashed segment were cut, then re-run once
    progress = [float(r["time/total_timesteps"]) for r in csv.DictReader((tmp_path / "progress.csv").open())]
    assert progress == sorted(progress) and progress[-1] <= 40
    monitors = sorted(p.name for p in (tmp_path / "monitor").iterdir())
    assert monitors == ["0-0.monitor.csv", "1-0.monitor.csv", "2-0.monitor.csv"]
    episodes = training_episodes(tmp_path)
    assert 40 - 3 * 8 <= sum(e["l"] for e in episodes) <= 40  # episodes cut by an interrupt are not logged
    evals = read_evaluations(tmp_path / "eval" / "held_out.csv")
    at = [int(r["timesteps"]) for r in evals]
    assert at[0] == 0 and at == sorted(set(at)) and at[-1] >= 32  # first evaluation before any update
    assert all(
        t % 16 == 0 for t in at
    )  # every --eval-freq steps, also across resumes (no extra one at a resume)
    assert json.loads((tmp_path / "config.json").read_text())["wig"] == "test_rl_tiny"
    assert plot_learning_curves(tmp_path).exists()


def test_documented_training_command_runs_with_its_progress_bar(tmp_path):
    """The documented `scripts/train_rl.py` command line, shortened to two strokes, with SB3's progress bar on (its
    default): a fresh `pip install -e ".[dev,rl]"` must bring what the bar needs (tqdm and rich, issue 22)."""
    import subprocess
    import sys
    from pathlib import Path

    script = Path(__file__).resolve().parents[2] / "scripts" / "train_rl.py"
    cmd = [sys.executable, str(script), "--env", "HairBrush-v0", "--algo", "sac", "--total-timesteps", "2",
           "--n-envs", "1", "--vec-env", "dummy", "--seed", "0", "--wig", "straight", "--eval-episodes", "0",
           "--checkpoint-freq", "1000", "--out", str(tmp_path)]  # fmt: skip
    done = subprocess.run(
        cmd, capture_output=True, text=True, timeout=600, env={**os.environ, "MUJOCO_GL": "egl"}
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert (tmp_path / "model.zip").exists() and (tmp_path / "learning_curves.png").exists()
