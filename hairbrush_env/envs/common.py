"""Pieces shared by the stroke-level and velocity-level brushing envs: reward terms, action checks, images."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields
from typing import Any, ClassVar

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from ..constants import FINISH_FORCE_TOLERANCE_N, LOAD_CELL_CAPACITY_N, PAIN_THRESHOLD_N

__all__ = ["FINISH_FORCE_TOLERANCE_N", "LOAD_CELL_CAPACITY_N", "PAIN_THRESHOLD_N"]  # re-exported for the envs
#: Upper bound of counters/clocks in observations (episodes are far shorter).
MAX_COUNT = 10_000.0


#: Smallest entanglement [Σ|Lk|] the progress reward is normalized by: one shared turn of a pair (curled presets start
#: with 30–60; straight hair with ~1e-4, by which any link brushing makes would be multiplied by 10⁴).
PROGRESS_FLOOR = 1.0

#: The reward terms every step reports in ``info`` (the reward is their sum).
REWARD_TERMS = ("reward_progress", "reward_time", "reward_pain", "reward_finish")


@dataclass(frozen=True)
class RewardConfig:
    """Weights of the reward terms (each term is reported in ``info``; the reward is their sum).

    * progress: ``progress_weight · (E_prev − E_now) / max(E_initial, PROGRESS_FLOOR)`` — detangling progress,
      normalized so that a fully detangled wig has collected ``progress_weight`` in total. The floor of one link
      (:data:`PROGRESS_FLOOR`) is for straight hair, which starts with next to none (1e-4): brushing that links
      two of its strands by 0.86 scored −43 000 against its initial 2e-4, swamping every other term
      (``hairbrush compare --physics v3 --wigs straight``);
    * time: ``−time_weight · Δt`` with Δt the simulated brushing time of the step plus ``stroke_overhead_s`` per
      stroke (repositioning the brush — without it, many tiny strokes would look free);
    * pain: ``−pain_weight · Σ max(0, f − F_T)`` over the load-cell samples of the step, in newtons;
    * finish: ``finish_bonus`` on the step that ends the task (the finish rule of eq. 3.4, or the wig detangled).

    Why the finish bonus (issue #6): without it the reward ranked "never brush through" above the thesis's
    controller. Curled wigs barely detangle in a few strokes, so progress is ~0 and an episode is scored by its
    costs alone: on curly (seed 0), 30 strokes at the lowest b_l (short, painless, never finishing) scored −5.2 and
    the sigmoid closed loop −6.2 — the "tiny strokes forever" hack. With the bonus, finishing (a full stroke that
    goes through, twice, with a stable force; the thesis's goal) is worth more than the repositioning overhead of a
    whole 30-stroke episode (30 · 2 s · 0.05 = 3), so stalling loses wherever finishing is possible. The stroke env
    only counts strokes that were not aborted at F_T for the finish rule; otherwise two painful aborted strokes
    would collect the bonus.
    """

    progress_weight: float = 10.0
    time_weight: float = 0.05
    stroke_overhead_s: float = 2.0
    pain_weight: float = 1.0
    finish_bonus: float = 5.0

    def __post_init__(self) -> None:
        for name in ("progress_weight", "time_weight", "stroke_overhead_s", "pain_weight", "finish_bonus"):
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
        done: bool = False,
    ) -> dict[str, float]:
        progress = self.progress_weight * (e_prev - e_now) / max(e_initial, PROGRESS_FLOOR)
        excess = np.clip(np.asarray(forces, dtype=float) - threshold, 0.0, None)
        return {
            "reward_progress": float(progress),
            "reward_time": float(-self.time_weight * elapsed),
            "reward_pain": float(-self.pain_weight * excess.sum()),
            "reward_finish": float(self.finish_bonus if done else 0.0),
        }

    @staticmethod
    def zero_terms() -> dict[str, float]:
        """The terms of a step that earns nothing (a diverged simulation)."""
        return dict.fromkeys(REWARD_TERMS, 0.0)


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


def check_wig_seeds(wig_seeds: Sequence[int] | None, n_wig_states: int) -> tuple[int, ...]:
    """The shake seeds an env's episodes pick from: ``wig_seeds``, or ``0 … n_wig_states − 1`` when it is None."""
    if wig_seeds is None:
        return tuple(range(int(n_wig_states)))
    seeds = tuple(wig_seeds)
    if not seeds or any(not isinstance(v, (int, np.integer)) or isinstance(v, bool) or v < 0 for v in seeds):
        raise ValueError(f"wig_seeds: expected a non-empty sequence of integers >= 0, got {wig_seeds!r}")
    return tuple(int(v) for v in seeds)


#: SceneConfig fields an env sets from its own arguments, which ``scene_fields`` may not set.
_OWN_SCENE_FIELDS = ("wig", "brush", "width", "height", "load_cell")


def make_scene_config(
    wig,
    *,
    width: int,
    height: int,
    load_cell_noise: float,
    brush: Any = "comb",
    scene_fields: Mapping[str, Any] | None = None,
):
    """The :class:`~hairbrush_env.scene.SceneConfig` of an env (wig, brush, webcam size, load-cell noise) with the
    SceneConfig fields ``scene_fields`` set (a version's stroke rules, e.g. v10's ``read_in_hair``)."""
    import dataclasses

    from ..scene import SceneConfig

    if not (math.isfinite(load_cell_noise) and load_cell_noise >= 0):
        raise ValueError(f"load_cell_noise: must be a finite number >= 0, got {load_cell_noise!r}")
    base = SceneConfig(
        wig=wig, brush=brush, width=int(width), height=int(height), **check_scene_fields(scene_fields)
    )
    return dataclasses.replace(
        base, load_cell=dataclasses.replace(base.load_cell, noise_std=float(load_cell_noise))
    )


def check_scene_fields(scene_fields: Mapping[str, Any] | None) -> Mapping[str, Any]:
    """``scene_fields`` (None or a mapping of SceneConfig field names) checked: ``ValueError`` names an unknown field
    or one the env sets from its own arguments."""
    from ..scene import SceneConfig

    if scene_fields is None:
        return {}
    if not isinstance(scene_fields, Mapping):
        raise ValueError(f"scene_fields: expected a mapping of SceneConfig fields, got {scene_fields!r}")
    known = sorted({f.name for f in fields(SceneConfig)} - set(_OWN_SCENE_FIELDS))
    bad = sorted(set(scene_fields) - set(known))
    if bad:
        raise ValueError(
            f"scene_fields: unknown or env-owned SceneConfig field(s) {bad}; valid: {', '.join(known)}"
        )
    try:
        SceneConfig(**scene_fields)  # a bad value, named by SceneConfig, before any wig is built
    except (TypeError, ValueError) as err:
        raise ValueError(f"scene_fields: {err}") from None
    return scene_fields


def apply_wig_fields(
    wigs: Sequence[Any],
    wig_fields: Mapping[str, Any] | None,
    preset_fields: Mapping[str, Mapping[str, Any]] | None = None,
) -> list[Any]:
    """``wigs`` (preset names or WigConfigs) with the WigConfig fields ``wig_fields`` set on every one, then
    ``preset_fields[name]`` on the presets it names (:func:`hairbrush_env.physics.versioned_wig`).

    An env version fixes the hair's contact model this way for every wig it is given (``HairBrush-v1``:
    self-colliding strands, hair–hair friction 0.15) and re-sizes presets (``HairBrush-v7``: smaller curls on the
    curliest presets); without either the wigs are returned as given.
    """
    from ..hair import WigConfig
    from ..physics import preset_fields_of, versioned_wig

    if wig_fields is None and not preset_fields:
        return list(wigs)
    if wig_fields is not None and not isinstance(wig_fields, Mapping):
        raise ValueError(f"wig_fields: expected a mapping of WigConfig fields, got {wig_fields!r}")
    known = {f.name for f in fields(WigConfig)} - {"name"}
    unknown = sorted(set(wig_fields or {}) - known)
    if unknown:
        raise ValueError(
            f"wig_fields: unknown WigConfig field(s) {unknown}; valid: {', '.join(sorted(known))}"
        )
    out = []
    for w in wigs:
        preset_fields_of(
            w, preset_fields
        )  # "wig: unknown preset ..." / "preset_fields[...]: ..." named as such
        try:
            out.append(versioned_wig(w, wig_fields, preset_fields))
        except (
            TypeError,
            ValueError,
        ) as err:  # a WigConfig validation error names the field; say where it came from
            raise ValueError(f"wig_fields: {err}") from err
    return out


OBS_MODES = ("state", "image", "state+image")
#: Constructor arguments both envs take and :meth:`BrushEnvBase._setup` checks.
SHARED_ENV_ARGS = (
    "wig",
    "wig_fields",
    "preset_fields",
    "scene_fields",
    "brush",
    "obs_mode",
    "render_mode",
    "width",
    "height",
    "force_threshold",
    "n_wig_states",
    "wig_seeds",
    "state_cache_dir",
    "detangled_fraction",
    "reward",
    "load_cell_noise",
)


class BrushEnvBase(gym.Env):
    """What both brushing envs share: argument checks, the compiled scene, webcam images, reset, info."""

    metadata: ClassVar[dict[str, Any]] = {"render_modes": ["rgb_array"], "render_fps": 10}

    def _setup(
        self,
        *,
        wig: Any,
        brush: Any,
        obs_mode: str,
        render_mode: str | None,
        width: int,
        height: int,
        force_threshold: float,
        n_wig_states: int,
        detangled_fraction: float,
        reward: RewardConfig | None,
        load_cell_noise: float,
        wig_seeds: Sequence[int] | None = None,
        state_cache_dir: str | None = None,
        wig_fields: Mapping[str, Any] | None = None,
        preset_fields: Mapping[str, Mapping[str, Any]] | None = None,
        scene_fields: Mapping[str, Any] | None = None,
    ) -> None:
        from ..brush import get_brush
        from ..hair import StateCache
        from ..scene import BrushingSim  # deferred: importing the package must stay cheap

        brush = get_brush(brush)  # "brush: unknown preset ..." before anything is built
        check_scene_fields(scene_fields)  # "scene_fields: ..." before anything is built

        if obs_mode not in OBS_MODES:
            raise ValueError(f"obs_mode: expected one of {OBS_MODES}, got {obs_mode!r}")
        if render_mode not in (None, *self.metadata["render_modes"]):
            raise ValueError(f"render_mode: expected None or 'rgb_array', got {render_mode!r}")
        if int(n_wig_states) != n_wig_states or n_wig_states < 1:
            raise ValueError(f"n_wig_states: must be a positive integer, got {n_wig_states!r}")
        self.wig_seeds = check_wig_seeds(wig_seeds, n_wig_states)
        wigs = list(wig) if isinstance(wig, (list, tuple)) else [wig]
        if not wigs:
            raise ValueError("wig: expected a preset name, a WigConfig or a non-empty list of them, got []")
        wigs = apply_wig_fields(
            wigs, wig_fields, preset_fields
        )  # "wig: unknown preset ..." / "wig_fields: ..." before any build
        if not (0.0 <= detangled_fraction < 1.0):
            raise ValueError(f"detangled_fraction: must be in [0, 1), got {detangled_fraction!r}")
        for name, value in (("width", width), ("height", height)):
            if int(value) != value or not 16 <= value <= 2048:
                raise ValueError(f"{name}: must be an integer in [16, 2048], got {value!r}")
        self.obs_mode = obs_mode
        self.render_mode = render_mode
        self.width, self.height = int(width), int(height)
        self.force_threshold = check_positive("force_threshold", force_threshold)
        self.n_wig_states = len(self.wig_seeds)
        self.detangled_fraction = float(detangled_fraction)
        self.reward_config = reward if reward is not None else RewardConfig()
        # one compiled scene per wig (built once; reset picks the episode's wig, so switching costs nothing)
        # a cache directory lets processes (vectorized workers, resumed runs) share the shaken states
        cache = StateCache(directory=state_cache_dir)
        self.sims = [
            BrushingSim(
                make_scene_config(
                    w,
                    brush=brush,
                    width=width,
                    height=height,
                    load_cell_noise=load_cell_noise,
                    scene_fields=scene_fields,
                ),
                cache=cache,
            )
            for w in wigs
        ]
        self.sim = self.sims[0]
        self.wig_seed: int | None = None  # the pre-brushed state of the running episode (set by reset)
        self._e0 = self._e = 1.0
        self._pain = 0

    def _image_space(self) -> spaces.Box:
        return spaces.Box(0, 255, shape=(self.height, self.width, 3), dtype=np.uint8)

    def _reset_sim(self, seed: int | None, wig_seed: int | None = None) -> None:
        """Seed the env, restore a pre-brushed wig and reset the episode's bookkeeping.

        ``wig_seed`` (reset option) names the pre-brushed state, one of ``wig_seeds``; by default the seed draws it.
        """
        if wig_seed is not None and wig_seed not in self.wig_seeds:
            raise ValueError(
                f"options: wig_seed {wig_seed!r} is not one of this env's pre-brushed states {self.wig_seeds}"
            )
        super().reset(seed=seed)
        # The seed picks the wig (when the env holds several) and one of a few cached pre-brushed states (shaking a
        # wig anew on every reset would cost seconds); the load-cell noise of the episode also comes from
        # self.np_random.
        if len(self.sims) > 1:
            self.sim = self.sims[int(self.np_random.integers(len(self.sims)))]
        if wig_seed is None:
            wig_seed = self.wig_seeds[int(self.np_random.integers(len(self.wig_seeds)))]
        self.wig_seed = int(wig_seed)
        self.sim.reset(self.wig_seed)
        self.sim.load_cell.rng = self.np_random
        self._e0 = self._e = self.sim.entanglement()
        self._pain = 0

    def _common_info(self, diverged: bool) -> dict[str, Any]:
        return {
            "wig_seed": self.wig_seed,
            "pain_violations": self._pain,
            "entanglement": float(self._e),
            "entanglement_initial": float(self._e0),
            "curliness_true": float(self.sim.curliness_true),
            "diverged": bool(diverged),
            "wig": self.sim.wig.name,
        }

    def hair_roi(self) -> tuple[int, int, int, int]:
        """Crop ``(y0, y1, x0, x1)`` of the hair in the ``image`` observation (the rig's fixed crop, thesis §3.3)."""
        return self.sim.hair_window()

    def render(self):
        if self.render_mode == "rgb_array":
            return self.sim.render()
        return None

    def close(self):
        for sim in self.sims:
            sim.close()
