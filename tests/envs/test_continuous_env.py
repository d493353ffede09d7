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


def _brush_down_through(env) -> np.ndarray:
    """A scripted brusher: full passes (in at the top, straight down through the hair, out, back up), as
    HairBrush-v0's full stroke does at the velocity level; returns the next action."""
    sim = env.unwrapped.sim
    p = sim.brush_position()
    state = env.unwrapped.__dict__.setdefault("_script", {"phase": "up"})
    top = sim.start_height(1.0)
    if state["phase"] == "up":  # out of the hair, up to the full stroke's start height
        if p[0] > sim.retract_x + 0.005:
            return np.array([0.0, -1.0], np.float32)
        if p[2] < top - 0.002:
            return np.array([1.0, 0.0], np.float32)
        state["phase"] = "in"
    if state["phase"] == "in":
        if p[0] < sim.depth_x - 0.002:
            return np.array([0.0, 1.0], np.float32)
        state["phase"] = "down"
    if state["phase"] == "down":
        if not (sim.brush_below_hair() or p[2] <= sim.pull_end_z + 0.005):
            return np.array([-0.5, 0.0], np.float32)  # 0.1 m/s, HairBrush-v0's stroke speed
        state["phase"] = "up"
    return np.array([0.0, -1.0], np.float32)


def _episode(env, policy, seed: int = 0) -> tuple[float, int, dict]:
    env.reset(seed=seed)
    env.unwrapped.__dict__.pop("_script", None)
    total, steps, done, info = 0.0, 0, False, {}
    while not done:
        _, r, term, trunc, info = env.step(policy(env))
        total, steps = total + r, steps + 1
        done = term or trunc
    return total, steps, info


def test_full_passes_finish_by_eq_3_4_and_brushing_beats_doing_nothing(small_wig, small_wavy_wig):
    """The stalling hole (issue #12): without a finish rule a brusher and an idler paid the same time cost for the
    whole episode and brushing could only lose. Full passes now end the episode by eq. 3.4 with the bonus (wavy hair,
    whose passes read about the same force), and on curled hair the link they comb out pays more than idling
    (measured on the small curly wig: -0.59 against -1.09; its passes vary by more than 0.4 N, so 30 s end it)."""
    env = gym.make("HairBrushContinuous-v0", wig=small_wavy_wig, max_episode_steps=300)
    try:
        brushed, steps, info = _episode(env, _brush_down_through)
        print(f"wavy brushed: return {brushed:.2f} in {steps} steps, {info['full_passes']} full passes")
        assert info["finished_rule"] and info["full_passes"] >= 2 and info["reward_finish"] == 5.0
        idle, idle_steps, idle_info = _episode(env, lambda e: np.zeros(2, np.float32))
        print(f"wavy idle: return {idle:.2f} in {idle_steps} steps")
        assert idle_steps == 300 and idle_info["full_passes"] == 0 and not idle_info["finished_rule"]
        assert idle == pytest.approx(-0.05 * 0.1 * 300, abs=0.5)  # time cost, ~no progress
        assert brushed > idle + 5.0
    finally:
        env.close()
    env = gym.make("HairBrushContinuous-v0", wig=small_wig, max_episode_steps=300)
    try:
        brushed, _, info = _episode(env, _brush_down_through)
        idle, _, _ = _episode(env, lambda e: np.zeros(2, np.float32))
        print(f"curly: brushed {brushed:.2f} ({info['full_passes']} full passes), idle {idle:.2f}")
        assert info["full_passes"] >= 2 and not info["diverged"]
        assert brushed > idle + 0.2
    finally:
        env.close()


@pytest.mark.slow
def test_full_passes_finish_the_curly_preset_and_beat_doing_nothing():
    """The same on the default curly wig (60 s episodes): idle pays the whole time cost, brushing finishes."""
    env = gym.make("HairBrushContinuous-v0", wig="curly")
    try:
        brushed, steps, info = _episode(env, _brush_down_through)
        print(f"curly brushed: return {brushed:.2f} in {steps} steps, {info['full_passes']} full passes, "
              f"entanglement {info['entanglement']:.2f} / {info['entanglement_initial']:.2f}")  # fmt: skip
        assert info["finished_rule"] and brushed > -0.05 * 60.0 + 5.0
        assert info["entanglement"] < info["entanglement_initial"]
    finally:
        env.close()


def test_reset_options(env):
    """The continuous env takes the stroke env's ``wig_seed`` option and refuses options it does not know."""
    seeds = env.unwrapped.wig_seeds
    _, info = env.reset(seed=0, options={"wig_seed": seeds[-1]})
    assert info["wig_seed"] == seeds[-1]
    with pytest.raises(ValueError, match="options"):
        env.reset(seed=0, options={"abort_force": 5.0})


def test_unknown_brush_is_refused_before_anything_is_built():
    with pytest.raises(ValueError, match="brush: unknown preset 'nylon'"):
        gym.make("HairBrushContinuous-v0", brush="nylon")
