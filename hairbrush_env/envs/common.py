"""Pieces shared by the stroke-level and velocity-level brushing envs: reward terms, action checks, images."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Pain threshold of the thesis (chapter 3, Algorithm 1): F_T ≈ 10 N.
PAIN_THRESHOLD_N = 10.0
#: Rated capacity of the simulated load cell [N]: readings saturate here, which bounds the observation spaces.
LOAD_CELL_CAPACITY_N = 100.0
#: Upper bound of counters/clocks in observations (episodes are far shorter).
MAX_COUNT = 10_000.0


@dataclass(frozen=True)
class RewardConfig:
    """Weights of the reward terms (each term is reported in ``info``; the reward is their sum).

    * progress: ``progress_weight · (E_prev − E_now) / E_initial`` — detangling progress, normalized so that a
      fully detangled wig has collected ``progress_weight`` in total;
    * time: ``−time_weight · Δt`` with Δt the simulated brushing time of the step plus ``stroke_overhead_s`` per
      stroke (repositioning the brush — without it, many tiny strokes would look free);
    * pain: ``−pain_weight · Σ max(0, f − F_T)`` over the load-cell samples of the step, in newtons.
    """

    progress_weight: float = 10.0
    time_weight: float = 0.05
    stroke_overhead_s: float = 2.0
    pain_weight: float = 1.0

    def __post_init__(self) -> None:
        for name in ("progress_weight", "time_weight", "stroke_overhead_s", "pain_weight"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"RewardConfig.{name}: must be a finite number >= 0, got {value!r}")

    def terms(
        self,
        *,
        e_prev: float,
        e_now: float,
        e_initial: float,
        elapsed: float,
        forces: np.ndarray,
        threshold: float,
    ) -> dict[str, float]:
        progress = self.progress_weight * (e_prev - e_now) / max(e_initial, 1e-12)
        excess = np.clip(np.asarray(forces, dtype=float) - threshold, 0.0, None)
        return {
            "reward_progress": float(progress),
            "reward_time": float(-self.time_weight * elapsed),
            "reward_pain": float(-self.pain_weight * excess.sum()),
        }


def check_action(action, space) -> np.ndarray:
    """Return ``action`` as float32 of the space's shape; ``ValueError`` for NaN/inf or a wrong shape."""
    arr = np.asarray(action, dtype=np.float32)
    if arr.shape != space.shape:
        arr = arr.reshape(space.shape) if arr.size == int(np.prod(space.shape)) else arr
    if arr.shape != space.shape:
        raise ValueError(f"action: expected shape {space.shape}, got {np.shape(action)}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"action: non-finite value {np.asarray(action).tolist()!r}")
    return np.clip(arr, space.low, space.high)


def check_positive(name: str, value: float) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name}: must be a positive finite number, got {value!r}")
    return v


def make_scene_config(wig, *, width: int, height: int, load_cell_noise: float):
    """The :class:`~hairbrush_env.scene.SceneConfig` of an env (wig, webcam size, load-cell noise)."""
    import dataclasses

    from ..scene import SceneConfig

    if not (math.isfinite(load_cell_noise) and load_cell_noise >= 0):
        raise ValueError(f"load_cell_noise: must be a finite number >= 0, got {load_cell_noise!r}")
    base = SceneConfig(wig=wig, width=int(width), height=int(height))
    return dataclasses.replace(
        base, load_cell=dataclasses.replace(base.load_cell, noise_std=float(load_cell_noise))
    )
