"""Baseline policies: full-length strokes, the naive thirds schedule, the shortest stroke and random actions.

They follow :class:`hairbrush_env.policies.Policy` and are registered under the entry-point group
``hairbrush_env.policies`` (names ``full``, ``naive``, ``shortest`` and ``random``) so ``hairbrush rollout --policy
NAME`` finds them. The first three work on ``HairBrush-v0`` (stroke level); ``random`` works on any env.
"""

from __future__ import annotations

from typing import Any

import numpy as np


def _stroke_env(env: Any):
    base = getattr(env, "unwrapped", env)
    if not hasattr(base, "brush_length_to_action"):
        raise ValueError(f"env: {type(base).__name__} is not a stroke-level env (HairBrush-v0)")
    return base


class _ConstantStroke:
    """Every stroke from the same start height (subclasses choose it from the env), pulled through to the end."""

    #: No force feedback: strokes are not aborted (the thesis's naive robot "significantly exceeding" F_T).
    abort_force: float | None = None

    def __init__(self, env: Any) -> None:
        base = _stroke_env(env)
        self._action = base.brush_length_to_action(self.brush_length(base))

    @staticmethod
    def brush_length(base: Any) -> float:
        raise NotImplementedError

    def reset(self, seed: int | None = None) -> None:
        """Stateless."""

    def act(self, obs: Any) -> np.ndarray:
        return self._action.copy()


class FullStrokePolicy(_ConstantStroke):
    """Always brush the whole length (b_l = 1): the thesis's no-strategy baseline (Fig. 3.7, longest strokes)."""

    @staticmethod
    def brush_length(base: Any) -> float:
        return 1.0


class ShortestStrokePolicy(_ConstantStroke):
    """Always the lowest start height (b_l = ``min_brush_length``): a reference for a reward that pays stalling.

    It never brushes through, so it never finishes (eq. 3.4) and rarely hurts; if an agent's return does not beat
    this policy's, the reward (not the agent) is what needs looking at (issue #6, "tiny strokes forever").
    """

    @staticmethod
    def brush_length(base: Any) -> float:
        return base.min_brush_length


class NaiveThirdsPolicy:
    """The thesis's naive strategy: b_l = 1/3, 2/3, 1, then full-length strokes (no force feedback, no abort)."""

    SCHEDULE = (1 / 3, 2 / 3, 1.0)
    abort_force: float | None = None

    def __init__(self, env: Any) -> None:
        self._env = _stroke_env(env)
        self._i = 0

    def reset(self, seed: int | None = None) -> None:
        self._i = 0

    def act(self, obs: Any) -> np.ndarray:
        b_l = self.SCHEDULE[min(self._i, len(self.SCHEDULE) - 1)]
        self._i += 1
        return self._env.brush_length_to_action(b_l)


class RandomPolicy:
    """Uniform samples from the action space, seeded by :meth:`reset` (reproducible rollouts)."""

    def __init__(self, env: Any) -> None:
        self._space = env.action_space
        self._space.seed(0)

    def reset(self, seed: int | None = None) -> None:
        self._space.seed(seed)

    def act(self, obs: Any) -> np.ndarray:
        return self._space.sample()
