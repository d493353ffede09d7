"""Sigmoid start height (thesis eq. 3.3) and the closed-loop brushing controller (Algorithm 1, eq. 3.4).

Eq. 3.3 prints ``b_l0 = 1 / (1 + exp(k (R_c + 0.5)))``, which for k = 8.5 caps every first stroke at 1.4 % of
the hair for any R_c ≥ 0; the behaviour the thesis describes (long strokes for straight hair, short for curly)
needs the midpoint at +0.5: ``b_l0 = 1 / (1 + exp(k (R_c − c)))`` with c = 0.5.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from hairbrush_env.constants import PAIN_THRESHOLD_N, WEBCAM_SIZE

from .vision import curliness

#: Smallest webcam image height at which R_c ranks the curled presets (docs/policies.md, "Vision curliness").
MIN_IMAGE_HEIGHT = WEBCAM_SIZE[1]
#: Steepness fitted on real wigs in the thesis (Fig. 3.9).
THESIS_K = 8.5
#: Steepness fitted in simulation by ``scripts/fit_sigmoid.py`` (see docs/policies.md); the default of the policy.
DEFAULT_K = THESIS_K


def start_height(curliness_rc: float, *, k: float = DEFAULT_K, c: float = 0.5) -> float:
    """Initial normalized brush length b_l0 = 1 / (1 + exp(k (R_c − c))) (eq. 3.3, sign corrected)."""
    rc = float(curliness_rc)
    if not math.isfinite(rc):
        raise ValueError(f"curliness_rc: must be finite, got {curliness_rc!r}")
    if not (math.isfinite(k) and k > 0):
        raise ValueError(f"k: must be a positive finite number, got {k!r}")
    z = k * (rc - c)
    return 1.0 / (1.0 + math.exp(z)) if z < 700 else 0.0


@dataclass(frozen=True)
class ClosedLoopConfig:
    """Parameters of Algorithm 1 (defaults: thesis values where it gives them)."""

    k: float = DEFAULT_K  # eq. 3.3 steepness
    c: float = 0.5  # eq. 3.3 midpoint
    increment: float = 0.2  # b_i: length added per stroke when the force is well below F_T
    force_threshold: float = PAIN_THRESHOLD_N  # F_T [N]
    finish_tolerance: float = 0.4  # eq. 3.4 [N]
    min_brush_length: float = 0.02  # floor so a hard knot cannot drive b_l to zero

    def __post_init__(self) -> None:
        for name in ("k", "increment", "force_threshold", "finish_tolerance", "min_brush_length"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"ClosedLoopConfig.{name}: must be a positive finite number, got {v!r}")


def next_brush_length(b_l: float, f_max: float, cfg: ClosedLoopConfig) -> float:
    """Algorithm 1 update: shrink in proportion to the overshoot, else grow by b_i·(1 − f_max / (0.5 F_T))."""
    f_t = cfg.force_threshold
    if f_max >= f_t:
        new = b_l * f_t / f_max
    else:
        new = b_l + cfg.increment - cfg.increment * f_max / (0.5 * f_t)
    return float(np.clip(new, cfg.min_brush_length, 1.0))


def finished(f_max: float, f_max_prev: float | None, b_l: float, cfg: ClosedLoopConfig) -> bool:
    """Eq. 3.4: full-length stroke and the max force changed by less than 0.4 N since the previous stroke."""
    return f_max_prev is not None and abs(f_max - f_max_prev) < cfg.finish_tolerance and b_l >= 1.0 - 1e-9


class SigmoidPolicy:
    """Closed-loop brushing of thesis Algorithm 1 on ``HairBrush-v0``.

    On the first observation it estimates R_c from the webcam image (eq. 3.5), starts at b_l0 (eq. 3.3) and then
    adapts b_l after every stroke from the stroke's maximum force. Without an image in the observation it uses
    ``curliness_hint`` (e.g. ground truth R/P) if given, else raises.
    """

    def __init__(
        self, env: Any, *, config: ClosedLoopConfig | None = None, curliness_hint: float | None = None
    ):
        base = getattr(env, "unwrapped", env)
        if not hasattr(base, "brush_length_to_action"):
            raise ValueError(f"env: {type(base).__name__} is not a stroke-level env (HairBrush-v0)")
        self._env = base
        self.config = config or ClosedLoopConfig(
            force_threshold=getattr(base, "force_threshold", PAIN_THRESHOLD_N)
        )
        self.curliness_hint = curliness_hint
        #: Algorithm 1's inner loop stops a stroke at F_T.
        self.abort_force: float | None = self.config.force_threshold
        self.reset()

    def reset(self, seed: int | None = None) -> None:
        self.b_l: float | None = None
        self.r_c: float | None = None
        self.history: list[tuple[float, float]] = []  # (b_l, f_max) per stroke

    def _estimate(self, obs: dict) -> float:
        if "image" in obs:
            image = np.asarray(obs["image"])
            if image.shape[0] < MIN_IMAGE_HEIGHT:
                warnings.warn(
                    f"SigmoidPolicy: a {image.shape[1]}x{image.shape[0]} webcam image blurs tight coils and "
                    "lowers their R_c (docs/policies.md, 'Vision curliness'); make the env with "
                    f"width={WEBCAM_SIZE[0]}, height={WEBCAM_SIZE[1]}",
                    stacklevel=3,
                )
            # crop to the hair as the thesis does; the env knows where its webcam sees the hair
            roi = self._env.hair_roi() if hasattr(self._env, "hair_roi") else "auto"
            return curliness(image, roi=roi)
        if self.curliness_hint is not None:
            return float(self.curliness_hint)
        raise ValueError(
            "obs: SigmoidPolicy needs an 'image' observation (obs_mode with images) or curliness_hint"
        )

    def act(self, obs: dict) -> np.ndarray:
        if self.b_l is None:
            self.r_c = self._estimate(obs)
            self.b_l = max(
                start_height(self.r_c, k=self.config.k, c=self.config.c), self.config.min_brush_length
            )
        else:
            if "max_force" not in obs:
                raise ValueError("obs: SigmoidPolicy needs 'max_force' (use obs_mode='state+image')")
            f_max = float(np.asarray(obs["max_force"]).reshape(-1)[0])
            self.history.append((self.b_l, f_max))
            self.b_l = next_brush_length(self.b_l, f_max, self.config)
        return self._env.brush_length_to_action(self.b_l)
