"""Sigmoid start height (eq. 3.3, corrected sign) and the Algorithm 1 update / eq. 3.4 finish rule."""

from __future__ import annotations

import itertools
import math

import pytest

from controllers.sigmoid import ClosedLoopConfig, finished, next_brush_length, start_height


def test_start_height_corrected_sign():
    assert start_height(0.5, k=8.5) == pytest.approx(0.5)
    assert start_height(0.0, k=8.5) == pytest.approx(1 / (1 + math.exp(-4.25)))  # straight hair: long strokes
    assert start_height(1.0, k=8.5) == pytest.approx(1 / (1 + math.exp(4.25)))  # curly hair: short strokes
    # the printed "+0.5" would cap every stroke at 1/(1+e^{4.25}) = 1.4 %:
    assert 1 / (1 + math.exp(8.5 * 0.5)) == pytest.approx(0.014, abs=1e-3)
    values = [start_height(r / 10) for r in range(11)]
    assert all(a > b for a, b in itertools.pairwise(values))
    with pytest.raises(ValueError, match="k"):
        start_height(0.3, k=-1)


def test_algorithm_1_update():
    cfg = ClosedLoopConfig(increment=0.2, force_threshold=10.0)
    assert next_brush_length(0.5, 20.0, cfg) == pytest.approx(0.25)  # overshoot: scale by F_T/F_max
    assert next_brush_length(0.5, 0.0, cfg) == pytest.approx(0.7)  # no force: add the full increment
    assert next_brush_length(0.5, 5.0, cfg) == pytest.approx(0.5)  # at F_T/2 the length holds
    assert next_brush_length(0.5, 8.0, cfg) < 0.5  # between F_T/2 and F_T it shrinks
    assert next_brush_length(0.95, 0.0, cfg) == 1.0  # clipped to the full length


def test_finish_rule_eq_3_4():
    cfg = ClosedLoopConfig()
    assert finished(3.0, 3.3, 1.0, cfg)
    assert not finished(3.0, 3.5, 1.0, cfg)
    assert not finished(3.0, 3.1, 0.9, cfg)
    assert not finished(3.0, None, 1.0, cfg)


def test_config_validation():
    with pytest.raises(ValueError, match="increment"):
        ClosedLoopConfig(increment=0)


def test_policy_reads_rc_on_the_rigs_hair_crop():
    import os

    os.environ.setdefault("MUJOCO_GL", "egl")
    import gymnasium as gym

    import hairbrush_env  # noqa: F401  (registers the envs)
    from controllers.sigmoid import SigmoidPolicy
    from controllers.vision import curliness, gradient_ratio

    env = gym.make("HairBrush-v0", wig="curly", obs_mode="state+image", width=640, height=480)
    try:
        obs, _ = env.reset(seed=0)
        policy = SigmoidPolicy(env)
        policy.act(obs)
        # curly: R/P = 0.5, so the side-on helix ratio 4R/P = 2 saturates the clip (controllers/vision.py)
        assert policy.r_c == pytest.approx(curliness(obs["image"], roi=env.unwrapped.hair_roi()))
        assert policy.r_c > 0.95
        # the whole frame (head, pole, arm: long straight outlines) dilutes the hair's own gradients
        roi = env.unwrapped.hair_roi()
        assert gradient_ratio(obs["image"], roi="auto") < 0.9 * gradient_ratio(obs["image"], roi=roi)
        assert policy.b_l == pytest.approx(max(start_height(policy.r_c), policy.config.min_brush_length))
    finally:
        env.close()
    small = gym.make("HairBrush-v0", wig="curly", obs_mode="state+image", width=160, height=120)
    try:
        with pytest.warns(UserWarning, match="160x120"):
            SigmoidPolicy(small).act(small.reset(seed=0)[0])
    finally:
        small.close()
