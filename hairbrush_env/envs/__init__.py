"""Gymnasium environments, registered by ``import hairbrush_env`` (string entry points, nothing imported eagerly).

- ``HairBrush-v0`` — one step per brush stroke (:class:`~hairbrush_env.envs.stroke.HairBrushEnv`);
- ``HairBrushContinuous-v0`` — 10 Hz brush velocity control
  (:class:`~hairbrush_env.envs.continuous.HairBrushContinuousEnv`).
"""

from __future__ import annotations

from .common import PAIN_THRESHOLD_N, RewardConfig

__all__ = ["PAIN_THRESHOLD_N", "RewardConfig", "register_envs"]

MAX_STROKES = 30  # HairBrush-v0 episode limit (strokes)
MAX_CONTROL_STEPS = 600  # HairBrushContinuous-v0 episode limit (60 s at 10 Hz)


def register_envs() -> None:
    """Register both envs with gymnasium (idempotent)."""
    from gymnasium.envs.registration import register, registry

    if "HairBrush-v0" not in registry:
        register(
            id="HairBrush-v0",
            entry_point="hairbrush_env.envs.stroke:HairBrushEnv",
            max_episode_steps=MAX_STROKES,
        )
    if "HairBrushContinuous-v0" not in registry:
        register(
            id="HairBrushContinuous-v0",
            entry_point="hairbrush_env.envs.continuous:HairBrushContinuousEnv",
            max_episode_steps=MAX_CONTROL_STEPS,
        )
