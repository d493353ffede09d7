"""A human-like brushing baseline (thesis Introduction and §3.5, the third row of Fig. 3.11).

The thesis describes how people with long hair brush it: "start combing away the tangles close to the free hair
ends, and work steadily upward towards the scalp", with short strokes that "ease the process of detangling hair, but
at the expense of a longer time", and a brusher who is "sensitive to the feelings" of the person brushed. Its human
baseline brushed with the sensorized brush and no force limit. :class:`HumanPolicy` turns that into a rule: the first
stroke combs the lowest ``step`` of the hair; while a stroke's maximum force stays above ``comfort_force`` the same
section is brushed again (at most ``max_repeats`` times in a row, a person does not stall), otherwise the next stroke
starts ``step`` higher, until full-length strokes finish the hair (eq. 3.4 ends the episode). Strokes are pulled
through (``abort_force = None``): a person feels the pull but does not stop mid-stroke.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from hairbrush_env.constants import PAIN_THRESHOLD_N


class HumanPolicy:
    """Short strokes from the free ends upward, re-brushing a section while its force stays high."""

    #: Pulled through, like the thesis's human (no force cut-off).
    abort_force: float | None = None

    def __init__(
        self, env: Any, *, step: float = 0.25, comfort_force: float | None = None, max_repeats: int = 3
    ) -> None:
        base = getattr(env, "unwrapped", env)
        if not hasattr(base, "brush_length_to_action"):
            raise ValueError(f"env: {type(base).__name__} is not a stroke-level env (HairBrush-v0)")
        if not (math.isfinite(step) and 0.0 < step <= 1.0):
            raise ValueError(f"step: must be in (0, 1], got {step!r}")
        if comfort_force is None:
            # half the pain threshold: the level at which Algorithm 1 stops lengthening strokes
            comfort_force = 0.5 * float(getattr(base, "force_threshold", PAIN_THRESHOLD_N))
        if not (math.isfinite(comfort_force) and comfort_force > 0.0):
            raise ValueError(f"comfort_force: must be a positive finite number, got {comfort_force!r}")
        if not (isinstance(max_repeats, int) and max_repeats >= 0):
            raise ValueError(f"max_repeats: must be an integer >= 0, got {max_repeats!r}")
        self._env = base
        self.step, self.comfort_force, self.max_repeats = float(step), float(comfort_force), max_repeats
        self.reset()

    def reset(self, seed: int | None = None) -> None:
        self.b_l: float | None = None
        self._repeats = 0

    def act(self, obs: Any) -> np.ndarray:
        if self.b_l is None:
            self.b_l = self.step
        else:
            if "max_force" not in obs:
                raise ValueError("obs: HumanPolicy needs 'max_force' (a state observation)")
            f_max = float(np.asarray(obs["max_force"]).reshape(-1)[0])
            if f_max > self.comfort_force and self._repeats < self.max_repeats:
                self._repeats += 1  # still tangled here: brush this section again
            else:
                self._repeats = 0
                self.b_l = min(1.0, self.b_l + self.step)
        return self._env.brush_length_to_action(self.b_l)
