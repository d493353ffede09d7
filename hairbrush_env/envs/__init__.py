"""Gymnasium environments, registered by ``import hairbrush_env`` (string entry points, nothing imported eagerly).

- ``HairBrush-v0`` — one step per brush stroke (:class:`~hairbrush_env.envs.stroke.HairBrushEnv`);
- ``HairBrushContinuous-v0`` — 10 Hz brush velocity control
  (:class:`~hairbrush_env.envs.continuous.HairBrushContinuousEnv`).
- ``HairBrush-v1``, ``HairBrushContinuous-v1`` — the same envs with the v1 physics (:data:`V1_PHYSICS`).
- ``HairBrush-v2``, ``HairBrushContinuous-v2`` — the same envs with the v2 physics (:data:`V2_PHYSICS`).
- ``HairBrush-v3``, ``HairBrushContinuous-v3`` — the same envs with the v3 physics (:data:`V3_PHYSICS`).
- ``HairBrush-v4``, ``HairBrushContinuous-v4`` — the same envs with the v4 physics (:data:`V4_PHYSICS`).
- ``HairBrush-v5``, ``HairBrushContinuous-v5`` — the same envs with the v5 physics (:data:`V5_PHYSICS`).
- ``HairBrush-v6``, ``HairBrushContinuous-v6`` — the same envs with the v6 physics (:data:`V6_PHYSICS`).
- ``HairBrush-v7``, ``HairBrushContinuous-v7`` — the same envs with the v7 physics (:data:`V7_PHYSICS`).
- ``HairBrush-v8``, ``HairBrushContinuous-v8`` — the same envs with the v8 physics (:data:`V8_PHYSICS`).
- ``HairBrush-v9``, ``HairBrushContinuous-v9`` — the same envs with the v9 physics (:data:`V9_PHYSICS`).
- ``HairBrush-v10``, ``HairBrushContinuous-v10`` — the same envs with the v10 physics (:data:`V10_PHYSICS`).

A change of the brushing physics is a new version, never a change under v0: agents trained on v0 (the RL reference
run, docs/rl.md) are evaluated on the physics they were trained on.
"""

from __future__ import annotations

from ..physics import PHYSICS
from .common import PAIN_THRESHOLD_N, RewardConfig

__all__ = [
    "ENV_IDS",
    "PAIN_THRESHOLD_N",
    "STROKE_ENV_IDS",
    "V1_PHYSICS",
    "V2_PHYSICS",
    "V3_PHYSICS",
    "V4_PHYSICS",
    "V5_PHYSICS",
    "V6_PHYSICS",
    "V7_PHYSICS",
    "V8_PHYSICS",
    "V9_PHYSICS",
    "V10_PHYSICS",
    "RewardConfig",
    "make_version",
    "register_envs",
]

MAX_STROKES = 30  # HairBrush-v0 episode limit (strokes)
MAX_CONTROL_STEPS = 600  # HairBrushContinuous-v0 episode limit (60 s at 10 Hz)

#: What v1 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v1"]`` (self-colliding strands, hair–hair
#: friction 0.15, the soft comb). Constructor arguments override it (``gymnasium.make("HairBrush-v1", brush="comb")``).
V1_PHYSICS: dict = PHYSICS["v1"].env_kwargs()
#: What v2 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v2"]`` (v1 with a tenth of the joint damping,
#: stiffer wisps and a quadratic drag on the strands while they are brushed).
V2_PHYSICS: dict = PHYSICS["v2"].env_kwargs()
#: What v3 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v3"]`` (v2 with every group a pair, the
#: comb two tines wider).
V3_PHYSICS: dict = PHYSICS["v3"].env_kwargs()
#: What v4 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v4"]`` (v3 with each pair curling from a
#: different distance below its roots, ``WigConfig.root_run``).
V4_PHYSICS: dict = PHYSICS["v4"].env_kwargs()
#: What v5 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v5"]`` (v4 with every pair hanging straight
#: for 12 mm below its roots, ``WigConfig.root_run_min``).
V5_PHYSICS: dict = PHYSICS["v5"].env_kwargs()
#: What v6 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v6"]`` (v5 with each strand's rest shape
#: turned by π/2 about its root, ``WigConfig.rest_splay``, so a pair's combed-apart strands rest apart).
V6_PHYSICS: dict = PHYSICS["v6"].env_kwargs()
#: What v7 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v7"]`` (v6 with smaller curls on the
#: curliest presets, ``preset_fields``, so their curvature grows with their curliness).
V7_PHYSICS: dict = PHYSICS["v7"].env_kwargs()
#: What v8 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v8"]`` (v7 with the ``smooth_comb``, whose
#: tines hair slides on at its own friction 0.15, so curls turn round a tine instead of locking on it).
V8_PHYSICS: dict = PHYSICS["v8"].env_kwargs()
#: What v9 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v9"]`` (v8 with the strands' drag on the
#: velocity across them only, ``WigConfig.drag_normal_only``, and the ``springy_comb``, whose tines are lightly damped).
V9_PHYSICS: dict = PHYSICS["v9"].env_kwargs()
#: What v10 changes against v0: :data:`hairbrush_env.physics.PHYSICS` ``["v10"]`` (v9 whose strokes read the load
#: cell only while the brush is above the bottom of the hair, ``SceneConfig.read_in_hair``, as Algorithm 1 does).
V10_PHYSICS: dict = PHYSICS["v10"].env_kwargs()


#: Every registered env id: (entry point, episode limit, default kwargs).
ENV_IDS: dict[str, tuple[str, int, dict]] = {
    "HairBrush-v0": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, {}),
    "HairBrushContinuous-v0": ("hairbrush_env.envs.continuous:HairBrushContinuousEnv", MAX_CONTROL_STEPS, {}),
    "HairBrush-v1": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V1_PHYSICS),
    "HairBrushContinuous-v1": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V1_PHYSICS,
    ),
    "HairBrush-v2": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V2_PHYSICS),
    "HairBrushContinuous-v2": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V2_PHYSICS,
    ),
    "HairBrush-v3": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V3_PHYSICS),
    "HairBrushContinuous-v3": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V3_PHYSICS,
    ),
    "HairBrush-v4": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V4_PHYSICS),
    "HairBrushContinuous-v4": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V4_PHYSICS,
    ),
    "HairBrush-v5": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V5_PHYSICS),
    "HairBrushContinuous-v5": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V5_PHYSICS,
    ),
    "HairBrush-v6": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V6_PHYSICS),
    "HairBrushContinuous-v6": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V6_PHYSICS,
    ),
    "HairBrush-v7": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V7_PHYSICS),
    "HairBrushContinuous-v7": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V7_PHYSICS,
    ),
    "HairBrush-v8": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V8_PHYSICS),
    "HairBrushContinuous-v8": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V8_PHYSICS,
    ),
    "HairBrush-v9": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V9_PHYSICS),
    "HairBrushContinuous-v9": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V9_PHYSICS,
    ),
    "HairBrush-v10": ("hairbrush_env.envs.stroke:HairBrushEnv", MAX_STROKES, V10_PHYSICS),
    "HairBrushContinuous-v10": (
        "hairbrush_env.envs.continuous:HairBrushContinuousEnv",
        MAX_CONTROL_STEPS,
        V10_PHYSICS,
    ),
}
#: The stroke-level ids (``hairbrush compare``, the sigmoid fit and RL training take one of these).
STROKE_ENV_IDS = tuple(k for k, v in ENV_IDS.items() if v[0].endswith(":HairBrushEnv"))


def register_envs() -> None:
    """Register every env of :data:`ENV_IDS` with gymnasium (idempotent)."""
    from gymnasium.envs.registration import register, registry

    for env_id, (entry_point, limit, kwargs) in ENV_IDS.items():
        if env_id not in registry:
            register(id=env_id, entry_point=entry_point, max_episode_steps=limit, kwargs=dict(kwargs))


def make_version(env_id: str, **kwargs):
    """``gymnasium.make(env_id, **kwargs)`` without gymnasium's "out of date, consider upgrading" warning for v0.

    For callers that name a version on purpose (``--physics v0``, an agent evaluated on the physics it was trained
    on); a user's own ``gymnasium.make("HairBrush-v0")`` still gets the warning.
    """
    import warnings

    import gymnasium as gym

    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=r".*is out of date\. You should consider upgrading")
        return gym.make(env_id, **kwargs)
