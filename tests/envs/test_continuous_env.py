"""HairBrushContinuous-v0: API conformance, determinism, robustness."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import hairbrush_env  # noqa: F401


@pytest.fixture(scope="module")
def env(small_wig):
    e = gym.make("HairBrushContinuous-v0", wig=small_wig, obs_mode="state", render_mode="rgb_array")
    yield e
    e.close()


def test_registered():
    assert gym.spec("HairBrushContinuous-v0").max_episode_steps == 600


def test_checkers(env, small_wig):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    assert not [w for w in caught if "gymnasium" in str(w.filename)], [str(w.message) for w in caught]
    sb3_checker = pytest.importorskip("stable_baselines3.common.env_checker")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sb3_checker.check_env(env.unwrapped, warn=True)
    assert not [w for w in caught if issubclass(w.category, UserWarning)], [str(w.message) for w in caught]


def test_velocity_moves_the_brush_and_reward_is_sum_of_terms(env):
    obs, info = env.reset(seed=0)
    start = obs["brush_position"].copy()
    for _ in range(5):
        # full speed up (the brush is parked just below the free ends, near the bottom of its workspace)
        obs, reward, _, _, info = env.step(np.array([1.0, 0.0], np.float32))
        assert reward == pytest.approx(sum(v for k, v in info.items() if k.startswith("reward_")))
    # 0.5 s at 0.2 m/s is 0.1 m up, clipped at the top of the brushing workspace (below the scalp); the servos
    # settle within a few mm of the target
    sim = env.unwrapped.sim
    expected = min(start[2] + 0.1, sim.top_z - sim.root_origin[2])
    assert obs["brush_position"][2] == pytest.approx(expected, abs=0.005)
    assert obs["brush_position"][2] > start[2] + 0.02
    assert info["sim_time"] == pytest.approx(0.5)
    assert env.observation_space.contains(obs)


def test_determinism(env):
    def run():
        env.reset(seed=5)
        out = []
        for a in ([0.5, 1.0], [-1.0, 0.2], [-1.0, -0.3]):
            obs, reward, *_ = env.step(np.array(a, np.float32))
            out.append((obs["force"].copy(), obs["brush_position"].copy(), reward))
        return out

    for (f1, p1, r1), (f2, p2, r2) in zip(run(), run(), strict=True):
        np.testing.assert_array_equal(f1, f2)
        np.testing.assert_array_equal(p1, p2)
        assert r1 == r2


def test_bad_action_and_divergence(env):
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action"):
        env.step(np.array([np.nan, 0.0], np.float32))
    env.unwrapped.sim.data.qpos[:] = np.nan  # inject a blow-up
    _, reward, terminated, truncated, info = env.step(np.zeros(2, np.float32))
    assert truncated and not terminated and info["diverged"] and reward == 0.0


def test_render_and_close(small_wig):
    e = gym.make("HairBrushContinuous-v0", wig=small_wig, obs_mode="image", render_mode="rgb_array")
    obs, _ = e.reset(seed=0)
    frame = e.render()
    assert frame.shape == obs["image"].shape == (120, 160, 3)
    e.close()
    assert e.unwrapped.sim._renderer is None
