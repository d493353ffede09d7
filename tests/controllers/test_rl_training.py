"""Training smoke test (issue #6): a few hundred PPO steps through gymnasium.make, then the agent as a policy."""

from __future__ import annotations

import csv
import os

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
        eval_freq=10_000,
        checkpoint_freq=10_000,
        progress_bar=False,
    )
    train(cfg, tmp_path)
    assert (tmp_path / "model.zip").exists()


def test_wig_lists_spread_over_workers(tmp_path):
    """``--wig wavy,straight``: worker i trains on wig i mod 2, each with its own Monitor log."""
    from stable_baselines3.common.vec_env import DummyVecEnv

    from controllers.rl_training import _vec_env, training_wigs

    assert training_wigs("wavy, straight") == ["wavy", "straight"]
    with pytest.raises(ValueError, match="nope"):
        TrainConfig(wig="wavy,nope")
    venv = _vec_env(
        "hairbrush_env:HairBrushContinuous-v0", ["wavy", "straight"], 3, 0, {"obs_mode": "state"},
        DummyVecEnv, tmp_path / "monitor",
    )  # fmt: skip
    try:
        assert [e.unwrapped.sim.wig.name for e in venv.envs] == ["wavy", "straight", "wavy"]
        venv.reset()
        assert sorted(p.name for p in (tmp_path / "monitor").iterdir())[:1] == ["0.monitor.csv"]
    finally:
        venv.close()


def test_documented_training_command_runs_with_its_progress_bar(tmp_path):
    """README's `scripts/train_rl.py` command line, shortened to two strokes, with SB3's progress bar on (its
    default): a fresh `pip install -e ".[dev,rl]"` must bring what the bar needs (tqdm and rich, issue 22)."""
    import subprocess
    import sys
    from pathlib import Path

    script = Path(__file__).resolve().parents[2] / "scripts" / "train_rl.py"
    cmd = [sys.executable, str(script), "--env", "HairBrush-v0", "--algo", "sac", "--total-timesteps", "2",
           "--n-envs", "1", "--vec-env", "dummy", "--seed", "0", "--wig", "straight", "--eval-freq", "1000",
           "--checkpoint-freq", "1000", "--out", str(tmp_path)]  # fmt: skip
    done = subprocess.run(
        cmd, capture_output=True, text=True, timeout=600, env={**os.environ, "MUJOCO_GL": "egl"}
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert (tmp_path / "model.zip").exists() and (tmp_path / "learning_curves.png").exists()
