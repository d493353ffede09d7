"""HairBrush-v0: API conformance, determinism, robustness (issue #4 reliability list)."""

from __future__ import annotations

import pickle
import tracemalloc
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import hairbrush_env  # noqa: F401  (registers the envs)
from hairbrush_env.brush import get_brush
from hairbrush_env.envs.common import RewardConfig
from hairbrush_env.envs.stroke import HairBrushEnv
from hairbrush_env.scene_build import SCENE_TINE_PREFIX


@pytest.fixture(scope="module")
def env(small_wig):
    e = gym.make("HairBrush-v0", wig=small_wig, obs_mode="state+image", render_mode="rgb_array")
    yield e
    e.close()


def test_registered_with_time_limit(small_wig):
    spec = gym.spec("HairBrush-v0")
    assert spec.entry_point == "hairbrush_env.envs.stroke:HairBrushEnv"
    assert spec.max_episode_steps == 30


def test_gymnasium_check_env(env):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped, skip_render_check=False)
    ours = [w for w in caught if "hairbrush" in str(w.filename) or "gymnasium" in str(w.filename)]
    assert not ours, [str(w.message) for w in ours]


def test_sb3_check_env(small_wig):
    sb3_checker = pytest.importorskip("stable_baselines3.common.env_checker")
    e = HairBrushEnv(wig=small_wig, obs_mode="state")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sb3_checker.check_env(e, warn=True)
    e.close()
    assert not [w for w in caught if issubclass(w.category, UserWarning)], [str(w.message) for w in caught]


def test_first_observation_shows_the_wig(env):
    obs, info = env.reset(seed=3)
    img = obs["image"]
    assert img.dtype == np.uint8 and img.shape == (120, 160, 3)
    assert img.std() > 5  # not a blank frame: hair in front of the backdrop
    assert obs["stroke_index"][0] == 0 and obs["max_force"][0] == 0
    assert info["entanglement"] == info["entanglement_initial"] > 0
    np.testing.assert_array_equal(env.render(), img)


def test_same_seed_same_rollout_and_reward_is_sum_of_terms(env):
    def rollout():
        obs, _ = env.reset(seed=7)
        out = [obs]
        for a in (-0.2, 1.0):
            obs, reward, _term, _trunc, info = env.step(np.array([a], np.float32))
            assert reward == pytest.approx(sum(v for k, v in info.items() if k.startswith("reward_")))
            assert set(k for k in info if k.startswith("reward_")) == set(RewardConfig.zero_terms())
            assert len(info["force_samples"]) >= 1 and info["brush_length"] > 0
            out += [obs, reward, info["entanglement"]]
        return out

    first, second = rollout(), rollout()
    for x, y in zip(first, second, strict=True):
        if isinstance(x, dict):
            for k in x:
                np.testing.assert_array_equal(x[k], y[k])
        else:
            assert x == y


def test_actions_validated(env):
    env.reset(seed=0)
    for bad in (np.array([np.nan], np.float32), np.array([np.inf], np.float32)):
        with pytest.raises(ValueError, match="action"):
            env.step(bad)
    with pytest.raises(ValueError, match="action: expected shape"):
        env.step(np.zeros(3, np.float32))


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"wig": "afro-ish"}, "wig"),
        ({"brush": "nylon"}, "brush"),
        ({"obs_mode": "pixels"}, "obs_mode"),
        ({"force_threshold": -1.0}, "force_threshold"),
        ({"min_brush_length": 1.5}, "min_brush_length"),
        ({"n_wig_states": 0}, "n_wig_states"),
        ({"width": 7}, "width"),
        ({"wig_fields": {"colour": "red"}}, "wig_fields"),
        ({"wig_fields": {"friction": -0.1}}, "wig_fields"),
        ({"scene_fields": {"colour": "red"}}, "scene_fields"),
        ({"scene_fields": {"wig": "coily"}}, "scene_fields"),
        ({"scene_fields": {"read_in_hair": "yes"}}, "scene_fields.*read_in_hair"),
        ({"scene_fields": ["read_in_hair"]}, "scene_fields"),
    ],
)
def test_bad_config_raises(kwargs, field):
    with pytest.raises(ValueError, match=field):
        gym.make("HairBrush-v0", **kwargs)


def test_brush_argument_builds_the_scene_with_that_brush(small_wig):
    """``brush="soft_comb"``: the comb's tines on hinges that bend to ±1.2 rad; the default comb's are rigid."""

    def tine_joints(e: HairBrushEnv) -> list[int]:
        m = e.sim.model
        return [j for j in range(m.njnt) if m.joint(j).name.startswith(SCENE_TINE_PREFIX)]

    soft = HairBrushEnv(wig=small_wig, brush="soft_comb")
    joints = tine_joints(soft)
    assert len(joints) == get_brush("soft_comb").columns
    assert np.allclose(soft.sim.model.jnt_range[joints], [-1.2, 1.2])
    soft.close()
    rigid = HairBrushEnv(wig=small_wig)
    assert tine_joints(rigid) == [] and rigid.sim.brush == get_brush("comb")
    rigid.close()


def test_v1_brushes_with_the_v1_physics_and_v0_is_unchanged(small_wig):
    """``HairBrush-v1``: self-colliding strands, hair–hair friction 0.15 on every wig (names and custom configs)
    and the soft comb; v0 keeps the defaults, and constructor arguments override what v1 sets."""
    v1 = gym.make("HairBrush-v1", wig=[small_wig, "wavy"])
    for sim in v1.unwrapped.sims:
        assert sim.wig.self_collision and sim.wig.friction == pytest.approx(0.15)
        assert sim.brush == get_brush("soft_comb")
    assert v1.unwrapped.sims[0].wig.name == small_wig.name and v1.spec.max_episode_steps == 30
    v1.close()
    v0 = gym.make("HairBrush-v0", wig=small_wig)
    assert v0.unwrapped.sim.wig == small_wig and v0.unwrapped.sim.brush == get_brush("comb")
    v0.close()
    rigid = gym.make("HairBrush-v1", wig=small_wig, brush="comb")
    assert rigid.unwrapped.sim.brush == get_brush("comb") and rigid.unwrapped.sim.wig.self_collision
    rigid.close()


def test_v2_brushes_with_drag_and_less_damping(small_wig):
    """``HairBrush-v2``: v1's contact model and comb plus v2's dissipation on every wig, and one stroke runs with
    the drag acting on the strands."""
    v2 = gym.make("HairBrush-v2", wig=small_wig)
    sim = v2.unwrapped.sim
    assert (
        sim.wig.self_collision
        and sim.wig.friction == pytest.approx(0.15)
        and sim.brush == get_brush("soft_comb")
    )
    assert (sim.wig.damping, sim.wig.drag_density, sim.wig.young) == (0.002, 1000.0, 1.6e8)
    v2.reset(seed=0)
    _, _, _, truncated, info = v2.step(np.array([1.0], np.float32))
    assert not info["diverged"] and not truncated
    assert np.abs(sim.data.xfrc_applied).max() > 0.0  # the strand drag of the last physics step
    v2.close()


def test_v10_reads_the_stroke_in_the_hair_and_counts_pain_over_the_pull(small_wig):
    """``HairBrush-v10``: ``max_force`` (observation and info) is the largest of the samples the stroke read, the
    first ``samples_read`` of ``force_samples``, taken while the brush was above the bottom of the hair; the pull's
    own maximum is reported beside it, and pain is counted on it."""
    v10 = gym.make("HairBrush-v10", wig=small_wig, force_threshold=0.05, abort_force=None)
    assert v10.unwrapped.sim.config.read_in_hair
    v10.reset(seed=0)
    obs, _, _, _, info = v10.step(v10.unwrapped.brush_length_to_action(0.5))
    f, n = np.array(info["force_samples"]), info["samples_read"]
    assert not info["diverged"] and 0 < n < f.size
    assert (
        info["max_force"] == pytest.approx(f[:n].max()) == pytest.approx(float(obs["max_force"][0]), abs=1e-5)
    )
    assert info["pull_max_force"] == pytest.approx(f.max())
    assert info["pain_violations"] == int(f.max() >= 0.05)
    v10.close()


def test_divergence_truncates_without_raising(env):
    env.reset(seed=0)
    sim = env.unwrapped.sim
    sim.data.qvel[:] = 1e12  # inject a blow-up
    obs, reward, terminated, truncated, info = env.step(np.array([0.0], np.float32))
    assert truncated and not terminated and info["diverged"]
    assert reward == 0.0 and env.observation_space.contains(obs)
    obs, info = env.reset(seed=0)  # a reset recovers
    assert not info["diverged"] and np.all(np.isfinite(obs["force_trace"]))


def test_pickle_round_trip(small_wig):
    e = gym.make("HairBrush-v0", wig=small_wig, obs_mode="state")
    clone = pickle.loads(pickle.dumps(e))
    a, _ = e.reset(seed=11)
    b, _ = clone.reset(seed=11)
    for k in a:
        np.testing.assert_array_equal(a[k], b[k])
    e.close()
    clone.close()


def test_async_vector_env_two_workers(small_wig):
    venv = gym.vector.AsyncVectorEnv(
        [lambda: gym.make("HairBrush-v0", wig=small_wig, obs_mode="state") for _ in range(2)],
        shared_memory=False,
    )
    obs, _ = venv.reset(seed=[1, 2])
    assert obs["force_trace"].shape[0] == 2
    obs, rewards, _term, _trunc, _infos = venv.step(np.array([[-0.8], [-0.8]], np.float32))
    assert rewards.shape == (2,) and np.all(np.isfinite(rewards))
    venv.close()


def test_resets_do_not_leak_memory(small_wig):
    e = gym.make("HairBrush-v0", wig=small_wig, obs_mode="state")
    for seed in range(20):  # warm up: every cached state, allocator pools
        e.reset(seed=seed)
    tracemalloc.start()
    before = tracemalloc.take_snapshot()
    for seed in range(200):
        e.reset(seed=seed)
    after = tracemalloc.take_snapshot()
    tracemalloc.stop()
    growth = sum(s.size_diff for s in after.compare_to(before, "filename"))
    e.close()
    assert growth < 256 * 1024, f"{growth} bytes retained over 200 resets"


def test_brush_length_action_mapping(env):
    base = env.unwrapped
    for b in (base.min_brush_length, 0.5, 1.0):
        assert base.action_to_brush_length(base.brush_length_to_action(b)) == pytest.approx(b)
    # the top band of the action range is the full stroke, so squashed (tanh) policies can finish (eq. 3.4)
    band_bottom = 1.0 - 2 * base.FULL_STROKE_BAND
    assert base.brush_length_to_action(1.0)[0] == pytest.approx(band_bottom)
    for a in (band_bottom, 0.99, 0.999, 1.0):
        assert base.action_to_brush_length([a]) == 1.0
    assert base.action_to_brush_length([band_bottom - 0.01]) < 1.0
    grid = np.linspace(-1, 1, 101)
    assert np.all(np.diff([base.action_to_brush_length([a]) for a in grid]) >= 0)


def test_finish_bonus_is_paid_once_when_the_finish_rule_ends_the_episode(small_wavy_wig):
    """Issue #6 reward fix: finishing (eq. 3.4) pays ``finish_bonus`` on the ending stroke and never before."""
    env = gym.make("HairBrush-v0", wig=small_wavy_wig)
    env.reset(seed=0)
    bonus = env.unwrapped.reward_config.finish_bonus
    paid = []
    for _ in range(8):  # full strokes: wavy hair reads about the same force every stroke
        _, _, terminated, truncated, info = env.step(np.array([1.0], np.float32))
        paid.append(info["reward_finish"])
        if terminated or truncated:
            break
    env.close()
    assert terminated and (info["finished_rule"] or info["detangled"])
    assert paid[-1] == bonus > 0 and all(p == 0.0 for p in paid[:-1])


def test_finish_bonus_outweighs_stalling_for_the_whole_episode():
    """The hack the bonus closes: strokes at the lowest b_l until the limit cost at least the repositioning
    overhead (30 · 2 s · 0.05 = 3); finishing must be worth more, or never brushing through wins."""
    cfg = RewardConfig()
    max_strokes = gym.spec("HairBrush-v0").max_episode_steps
    assert cfg.finish_bonus > max_strokes * cfg.stroke_overhead_s * cfg.time_weight
    with pytest.raises(ValueError, match="finish_bonus"):
        RewardConfig(finish_bonus=-1.0)
    terms = cfg.terms(e_prev=1.0, e_now=1.0, e_initial=1.0, elapsed=1.0, forces=np.zeros(3), threshold=10.0)
    assert terms["reward_finish"] == 0.0 and set(terms) == set(RewardConfig.zero_terms())


def test_progress_on_hair_with_almost_no_link_is_normalized_by_one_link():
    """Straight hair starts with ~1e-4 of link; normalized by that, the 0.86 a stroke made scored −43 000. The
    progress term divides by at least one link, and by the initial entanglement of any curled wig (30–60)."""
    from hairbrush_env.envs.common import PROGRESS_FLOOR

    cfg = RewardConfig()
    made = cfg.terms(e_prev=2e-4, e_now=0.86, e_initial=2e-4, elapsed=0.0, forces=np.zeros(1), threshold=10.0)
    assert PROGRESS_FLOOR == 1.0
    assert made["reward_progress"] == pytest.approx(-cfg.progress_weight * (0.86 - 2e-4))
    combed = cfg.terms(
        e_prev=40.0, e_now=30.0, e_initial=40.0, elapsed=0.0, forces=np.zeros(1), threshold=10.0
    )
    assert combed["reward_progress"] == pytest.approx(cfg.progress_weight * 0.25)


def test_aborted_full_strokes_never_finish(small_wig):
    """Eq. 3.4 only counts strokes that went through: two strokes aborted at F_T read ≈ F_T both, and used to end
    the episode (and, with the finish bonus, pay for it) although the brush never got through the hair."""
    env = gym.make("HairBrush-v0", wig=small_wig, force_threshold=0.05, abort_force=0.05)
    env.reset(seed=0)
    for _ in range(4):
        _, _, terminated, truncated, info = env.step(np.array([1.0], np.float32))
        assert info["aborted"] and not info["finished_rule"] and info["reward_finish"] == 0.0
        assert not (terminated or truncated)
    assert info["pain_violations"] == 4
    env.close()


def test_abort_force_belongs_to_the_episode(small_wig):
    """``abort_force=None`` pulls through (pain is still counted at F_T); a reset option sets one episode's abort."""
    env = gym.make("HairBrush-v0", wig=small_wig, force_threshold=0.05, abort_force=None)
    env.reset(seed=0)
    _, _, _, _, info = env.step(np.array([1.0], np.float32))
    assert not info["aborted"] and info["max_force"] >= 0.05 and info["pain_violations"] == 1
    pulled_through = len(info["force_samples"])
    env.reset(seed=0, options={"abort_force": 0.05})
    _, _, _, _, info = env.step(np.array([1.0], np.float32))
    assert info["aborted"] and len(info["force_samples"]) < pulled_through
    env.reset(seed=0)  # no option: the constructor's abort again
    assert env.unwrapped.abort_force is None
    with pytest.raises(ValueError, match="abort_force"):
        env.reset(seed=0, options={"abort_force": -1.0})
    with pytest.raises(ValueError, match="options"):
        env.reset(seed=0, options={"bogus": 1})
    env.close()
    with pytest.raises(ValueError, match="abort_force"):
        HairBrushEnv(wig=small_wig, abort_force=0.0)


def test_wig_seed_option_names_the_pre_brushed_state(small_wig):
    """``options={"wig_seed": s}`` starts from state ``s`` whatever the seed draws (a comparison gives its episodes
    distinct wigs that way); a state the env does not hold is refused, naming the option."""
    env = gym.make("HairBrush-v0", wig=small_wig, n_wig_states=2)
    _, drawn = env.reset(seed=0)
    other = 1 - drawn["wig_seed"]
    _, info = env.reset(seed=0, options={"wig_seed": other})
    assert info["wig_seed"] == other
    assert info["entanglement_initial"] != pytest.approx(drawn["entanglement_initial"], abs=1e-9)
    _, again = env.reset(seed=0)
    assert again["wig_seed"] == drawn["wig_seed"]
    with pytest.raises(ValueError, match="wig_seed 7"):
        env.reset(seed=0, options={"wig_seed": 7})
    env.close()
