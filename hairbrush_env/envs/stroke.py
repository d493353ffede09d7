"""HairBrush-v0: one step = one brush stroke (the thesis's decision level, chapter 3, Algorithm 1)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from gymnasium import spaces
from gymnasium.utils import EzPickle

from ..scene_build import SceneConfig
from .common import (
    FINISH_FORCE_TOLERANCE_N,
    LOAD_CELL_CAPACITY_N,
    MAX_COUNT,
    PAIN_THRESHOLD_N,
    SHARED_ENV_ARGS,
    BrushEnvBase,
    RewardConfig,
    check_action,
    check_positive,
)

#: The env's pull speed [m/s]: the scene's (``SceneConfig.stroke_speed``).
DEFAULT_STROKE_SPEED: float = SceneConfig.stroke_speed


def default_trace_length(hanging_length: float, stroke_speed: float = DEFAULT_STROKE_SPEED) -> int:
    """Samples of a full stroke at 10 Hz (the default ``trace_length``): the hanging length plus how far a jammed
    brush drags the curls below their rest ends before it comes out (a pull may go on to 0.22 m below the default
    free-end height, ``SceneConfig.pull_floor_z``). Envs on several wigs that must share one observation space
    (vectorized training) pass the largest of their wigs' values."""
    travel = hanging_length + 0.22
    return math.ceil(travel / stroke_speed * 10.0) + 2


class HairBrushEnv(BrushEnvBase, EzPickle):
    r"""Robotic hair brushing at the stroke level.

    ## Description
    A robot arm holds a sensorized brush next to a wig hanging from a head mount (thesis chapter 3). Each step is
    one downward brush stroke: the brush moves to the start height, at a fixed depth inside the hair, then pulls
    straight down past the free ends at a fixed speed while the load cell is sampled at 10 Hz; the stroke is
    aborted as soon as the force reaches `abort_force` (by default the pain threshold F_T: the inner loop of
    Algorithm 1, the robot's safety stop), or pulled through to the end with `abort_force=None` (how the thesis's
    naive robot and its human brushed, "significantly exceeding the pain threshold", Fig. 3.11). Policies declare
    the abort they use (`abort_force` attribute, read by `hairbrush rollout` and `compare`). Neighbouring hair
    wisps are entwined in homochiral pairs; strokes comb the link out through the free ends.

    ## Action Space
    `Box(-1, 1, (1,), float32)`: the normalized start height b_l (the thesis's brush length: the fraction of the
    brushable length measured up from the free ends; b_l = 1 starts as high as the brush head fits below the
    scalp, `BrushingSim.brushable_length`), rescaled linearly from [-1, 0.98] to [`min_brush_length`, 1]; the top
    band [0.98, 1] is the full stroke b_l = 1 (`FULL_STROKE_BAND`). Use :meth:`brush_length_to_action` /
    :meth:`action_to_brush_length` to convert. The band exists because the finish rule needs b_l = 1 exactly, which
    an agent with a tanh-squashed policy (SAC, PPO with squashing) only reaches with saturated outputs.

    ## Observation Space
    A `Dict` (one level):

    | key | space | meaning |
    |---|---|---|
    | `force_trace` | `Box(0, 100, (trace_length,), float32)` | brushing force [N], 10 Hz, last stroke, 0-padded |
    | `max_force` | `Box(0, 100, (1,), float32)` | maximum force of the last stroke [N] |
    | `brush_length` | `Box(0, 1, (1,), float32)` | b_l of the last stroke (0 before the first) |
    | `stroke_index` | `Box(0, 1e4, (1,), float32)` | strokes done in this episode |

    Forces saturate at the load cell's capacity of 100 N (negative readings, e.g. noise, are clipped to 0).
    | `image` | `Box(0, 255, (height, width, 3), uint8)` | fixed "webcam" view (with `obs_mode` containing "image") |

    The first observation after `reset` shows the tangled wig, so a vision policy can estimate curliness.

    ## Rewards
    `reward = reward_progress + reward_time + reward_pain + reward_finish` (see :class:`RewardConfig`): detangling
    progress (drop of the entanglement Σ|Lk| over entwined pairs, normalized by its initial value), minus a time
    cost (simulated stroke time plus a fixed repositioning overhead), minus a pain penalty (force above F_T, summed
    over samples), plus a finish bonus (5) on the stroke that ends the episode by termination. Each term is
    reported in `info`. The bonus closes a reward hack: without it, 30 painless strokes at the lowest b_l
    outscored every policy that brushes through (docs/rl.md, *Reward holes*).

    ## Starting State
    A pre-brushed wig: the wig is shaken into a reproducible tangled state chosen by the seed among
    `n_wig_states` cached states (so `reset` is fast); the brush waits above the hair.

    ## Episode End
    - Termination: the wig is detangled (entanglement ≤ `detangled_fraction` × initial) or the finish rule of
      thesis eq. 3.4 holds: |f_max,i − f_max,i−1| < 0.4 N and b_l ≥ 1, where neither stroke was aborted
      (an aborted stroke reads ≈ its abort force by construction; otherwise two aborted full strokes would end it).
    - Truncation: `max_episode_steps` strokes (set at registration, 30), or the simulation diverged
      (`info["diverged"] = True`; the episode ends, nothing is raised).

    ## Info
    `max_force` (the largest force the stroke read: with `scene_fields={"read_in_hair": True}` only while the brush
    was above the bottom of the hair), `pull_max_force` (the largest of the whole pull), `samples_read` (how many of
    `force_samples`, from the first, the stroke read), `pain_violations` (strokes so far whose force anywhere in the
    pull reached F_T, whatever the abort), `entanglement`
    (Σ|Lk| over the entwined pairs plus link made between any other two strands, `hair.Entanglement`),
    `entanglement_initial`, `curliness_true` (R/P of the wig), `sim_time` (simulated brushing time so far, s),
    `diverged`, `brush_length`, `aborted`, `wig` (preset name), `force_samples` (the stroke's 10 Hz force samples,
    unpadded) and `force_times` (their episode times, s), `finished_rule` (eq. 3.4), `detangled`, and the reward terms.

    ## Arguments
    `gymnasium.make("HairBrush-v0", wig="curly", obs_mode="state+image")`, keyword-only:

    | argument | default | meaning |
    |---|---|---|
    | `wig` | `"curly"` | preset name from `hairbrush_env.hair.PRESETS`, a `WigConfig`, or a list of them (each
      reset picks one with the env's RNG: one env, one observation space, several wigs, e.g. for training) |
    | `wig_fields` | `None` | `WigConfig` fields set on every wig (e.g. `{"friction": 0.15}`; v1 sets its contact
      model this way) |
    | `preset_fields` | `None` | `WigConfig` fields set on named presets only (`{"coily": {"curl_radius": 0.009}}`;
      v7 re-sizes its curliest presets' curls this way): a wig given by name, or as a config equal to the preset |
    | `scene_fields` | `None` | `SceneConfig` fields set on the scene (`{"read_in_hair": True}`: v10's strokes read
      the load cell only while the brush is above the bottom of the hair, as Algorithm 1 does). Given to
      `gymnasium.make("HairBrush-v10", ...)` it replaces v10's, so keep `"read_in_hair": True` in it |
    | `brush` | `"comb"` | preset name from `hairbrush_env.brush.BRUSH_PRESETS` (`"comb"`, `"soft_comb"`, `"paddle"`)
      or a `BrushConfig` |
    | `obs_mode` | `"state"` | `"state"`, `"image"` or `"state+image"` |
    | `render_mode` | `None` | `"rgb_array"` returns the webcam image |
    | `width`, `height` | 160, 120 | image size in pixels (observation and render) |
    | `force_threshold` | 10.0 | pain threshold F_T [N]: pain violations and the pain penalty count samples ≥ it |
    | `abort_force` | 10.0 | a stroke stops at the first sample ≥ this [N]; `None` pulls through (default: F_T, the
      closed loop's abort; a user brushing someone wants the robot to stop at pain unless asked otherwise) |
    | `stroke_speed` | 0.1 | brush speed during the pull [m/s] (the scene's default) |
    | `min_brush_length` | 0.1 | b_l for action −1 |
    | `trace_length` | auto | samples kept in `force_trace` (a full stroke at 10 Hz) |
    | `n_wig_states` | 4 | number of distinct pre-brushed states the seed chooses from (shake seeds 0 … n − 1) |
    | `wig_seeds` | `None` | the shake seeds to choose from instead (e.g. states never used in training) |
    | `state_cache_dir` | `None` | directory where shaken states are kept and shared between processes |
    | `detangled_fraction` | 0.05 | termination level of the entanglement |
    | `reward` | `RewardConfig()` | reward weights |
    | `load_cell_noise` | 0.02 | load-cell noise s.d. [N] |

    ## Version History
    - v0: initial release. Within v0 (issue #6): the finish bonus and the full-stroke action band were added, and
      the finish rule no longer counts strokes aborted at F_T. Issue #11: insertion and withdrawal went from 0.15 to 0.3
      m/s, and the progress reward divides by at least one link (`PROGRESS_FLOOR`; it only changes straight hair,
      whose ~1e-4 of initial link made its returns −10⁴), in every version.
    - v1 (issue #11): v0 with self-colliding strands, hair–hair friction 0.15 and the soft (nylon) comb
      (`hairbrush_env.envs.V1_PHYSICS`; docs/envs.md, *Versions*). Same spaces, rewards and episode rules.
    - v2 (issue #11): v1 with a tenth of the strands' joint damping, wisps of cohesion 16 and a quadratic drag on the
      strands while they are brushed (`hairbrush_env.envs.V2_PHYSICS`). Same spaces, rewards and episode rules.
    - v3 (issue #11): v2 with every group of strands a pair (no triples, which one tine cannot part) and the comb
      two tines wider to span the twelve pairs (`hairbrush_env.envs.V3_PHYSICS`). Same spaces, rewards and episode
      rules.
    - v4 (issue #11): v3 with each pair hanging straight below its roots for its own part of half a curl pitch
      before it curls (`WigConfig.root_run`), so that the pairs' helix phases differ and the comb parts most pairs
      at any start height; under v3 it parted all or none (`hairbrush_env.envs.V4_PHYSICS`). Same spaces, rewards
      and episode rules.
    - v5 (issue #11): v4 with every pair hanging straight for 12 mm below its roots before it curls
      (`WigConfig.root_run_min`), so that no link lies above a full stroke's tines
      (`hairbrush_env.envs.V5_PHYSICS`). Same spaces, rewards and episode rules.
    - v6 (issue #11): v5 with each strand's stress-free shape turned by π/2 about its root instead of π/3
      (`WigConfig.rest_splay`, the root's twist hinge first: `WigConfig.root_twist_first`), so that a combed pair's
      two strands hang apart across the tines instead of on one axis (`hairbrush_env.envs.V6_PHYSICS`). Same
      spaces, rewards and episode rules.
    - v7 (issue #11): v6 with smaller curls on `tight_curl` (10 mm), `coily` (9 mm) and `held_out_tight` (11 mm;
      12 mm before) at the same R/P, their rest shapes turned by 2π/3 (`preset_fields`), so that a full stroke's
      force grows with curliness (Fig. 3.7) (`hairbrush_env.envs.V7_PHYSICS`). Same spaces, rewards and episode
      rules; custom wigs brush as under v6.
    - v8 (issue #11): v7 with the `smooth_comb`, whose tines hair slides on at its own friction 0.15 (0.3 before:
      MuJoCo takes the larger coefficient), so that a curl a tine is pulled through turns round it instead of locking
      on it like a screw whose lead angle is below its friction angle (`hairbrush_env.envs.V8_PHYSICS`). Same spaces,
      rewards and episode rules.
    - v9 (issue #21): v8 with the strands' drag acting on the velocity across them only
      (`WigConfig.drag_normal_only`) and the `springy_comb` (a tenth of the tines' hinge damping), so that a 4× faster
      pull moves the maximum force by ≤ 25 % (Fig. 3.8) (`hairbrush_env.envs.V9_PHYSICS`). Same spaces, rewards and
      episode rules.
    - v10 (issue #21): v9 whose strokes read the load cell only while the brush is above the bottom of the hair
      (`SceneConfig.read_in_hair`), as thesis Algorithm 1 does: the abort and `max_force` (observation and info) see
      those samples; `force_trace` keeps the whole pull and pain is counted over it (`hairbrush_env.envs.V10_PHYSICS`).
      Same spaces and rewards.
    """

    #: Fraction of the action range, at its top, that maps to the full stroke b_l = 1.
    FULL_STROKE_BAND = 0.01

    def __init__(
        self,
        *,
        wig: Any = "curly",
        wig_fields: Mapping[str, Any] | None = None,
        preset_fields: Mapping[str, Mapping[str, Any]] | None = None,
        scene_fields: Mapping[str, Any] | None = None,
        brush: Any = "comb",
        obs_mode: str = "state",
        render_mode: str | None = None,
        width: int = 160,
        height: int = 120,
        force_threshold: float = PAIN_THRESHOLD_N,
        abort_force: float | None = PAIN_THRESHOLD_N,
        stroke_speed: float = DEFAULT_STROKE_SPEED,
        min_brush_length: float = 0.1,
        trace_length: int | None = None,
        n_wig_states: int = 4,
        wig_seeds: Sequence[int] | None = None,
        state_cache_dir: str | None = None,
        detangled_fraction: float = 0.05,
        reward: RewardConfig | None = None,
        load_cell_noise: float = 0.02,
    ) -> None:
        # the constructor's arguments, written once: pickled by EzPickle, the shared ones checked by _setup
        args = {k: v for k, v in locals().items() if k not in ("self", "__class__")}
        EzPickle.__init__(self, **args)
        self._setup(**{k: args[k] for k in SHARED_ENV_ARGS})
        if not (0.0 < min_brush_length < 1.0):
            raise ValueError(f"min_brush_length: must be in (0, 1), got {min_brush_length!r}")
        self.stroke_speed = check_positive("stroke_speed", stroke_speed)
        self._default_abort = None if abort_force is None else check_positive("abort_force", abort_force)
        self.abort_force = self._default_abort  # this episode's (reset options may override it)
        self.min_brush_length = float(min_brush_length)
        if trace_length is None:
            # one observation space for every wig the env holds: the longest wig's full stroke
            trace_length = max(
                default_trace_length(s.wig.hanging_length, self.stroke_speed) for s in self.sims
            )
        if int(trace_length) != trace_length or trace_length < 1:
            raise ValueError(f"trace_length: must be a positive integer, got {trace_length!r}")
        self.trace_length = int(trace_length)

        self.action_space = spaces.Box(-1.0, 1.0, shape=(1,), dtype=np.float32)
        obs_spaces: dict[str, spaces.Space] = {}
        if "state" in obs_mode:
            obs_spaces.update(
                force_trace=spaces.Box(
                    0.0, LOAD_CELL_CAPACITY_N, shape=(self.trace_length,), dtype=np.float32
                ),
                max_force=spaces.Box(0.0, LOAD_CELL_CAPACITY_N, shape=(1,), dtype=np.float32),
                brush_length=spaces.Box(0.0, 1.0, shape=(1,), dtype=np.float32),
                stroke_index=spaces.Box(0.0, MAX_COUNT, shape=(1,), dtype=np.float32),
            )
        if "image" in obs_mode:
            obs_spaces["image"] = self._image_space()
        self.observation_space = spaces.Dict(obs_spaces)

        self._last: dict[str, Any] = {}
        self._strokes = 0
        self._sim_time = 0.0
        self._prev_fmax: float | None = None

    # --- conversions -------------------------------------------------------------------------------------------
    def action_to_brush_length(self, action) -> float:
        """Map an action in [-1, 1] to the normalized brush length b_l in [min_brush_length, 1].

        Linear on [-1, 1 − 2·FULL_STROKE_BAND]; the band above it is the full stroke b_l = 1.
        """
        a = float(np.clip(np.asarray(action, dtype=np.float64).reshape(-1)[0], -1.0, 1.0))
        u = min((a + 1.0) * 0.5 / (1.0 - self.FULL_STROKE_BAND), 1.0)
        return self.min_brush_length + u * (1.0 - self.min_brush_length)

    def brush_length_to_action(self, brush_length: float) -> np.ndarray:
        """Inverse of :meth:`action_to_brush_length` (b_l clipped to the valid range; b_l = 1 → the band's bottom)."""
        b = float(np.clip(brush_length, self.min_brush_length, 1.0))
        u = (b - self.min_brush_length) / (1.0 - self.min_brush_length) * (1.0 - self.FULL_STROKE_BAND)
        return np.array([2.0 * u - 1.0], dtype=np.float32)

    # --- gymnasium API -----------------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict | None = None):
        """Start an episode. ``options={"abort_force": F or None}`` sets the abort of this episode only (how a
        rollout applies the abort its policy declares); without it the constructor's ``abort_force`` holds.
        ``options={"wig_seed": s}`` starts from the pre-brushed state ``s`` (one of ``wig_seeds``) instead of the one
        the seed draws (how a comparison gives its episodes distinct wigs)."""
        options = dict(options or {})
        self.abort_force = self._default_abort
        if "abort_force" in options:
            value = options.pop("abort_force")
            self.abort_force = None if value is None else check_positive("abort_force", value)
        wig_seed = options.pop("wig_seed", None)
        if options:
            raise ValueError(f"options: unknown keys {sorted(options)}; known: ['abort_force', 'wig_seed']")
        self._reset_sim(seed, wig_seed)
        self._strokes, self._sim_time = 0, 0.0
        self._prev_fmax = None
        self._last = {
            "force_trace": np.zeros(self.trace_length, np.float32),
            "max_force": 0.0,
            "brush_length": 0.0,
        }
        return self._obs(), self._info(diverged=False, aborted=False)

    def step(self, action):
        action = check_action(action, self.action_space)
        b_l = self.action_to_brush_length(action)
        result = self.sim.stroke(
            b_l, speed=self.stroke_speed, abort_force=self.abort_force, rng=self.np_random
        )
        forces = np.asarray(result.force_trace[1], dtype=np.float64)
        # episode time of each sample: the load cell's clock restarts at the pull, its first samples are the pull's
        times = self.sim.load_cell.times()[: len(forces)].tolist()
        self._strokes += 1
        self._sim_time += result.sim_time
        if result.diverged:
            self._last.update(
                force_trace=self._trace(forces), max_force=float(result.max_force), brush_length=b_l
            )
            info = self._info(diverged=True, aborted=result.aborted)
            info.update(
                RewardConfig.zero_terms(),
                force_samples=forces.tolist(),
                force_times=times,
                pull_max_force=float(result.pull_max_force),
                samples_read=int(result.samples_read),
            )
            return self._obs(), 0.0, False, True, info
        e_now = self.sim.entanglement()
        f_max = float(result.max_force)
        # thesis eq. 3.4, on strokes that went through: an aborted stroke's maximum is F_T by construction, so two
        # aborted full strokes would otherwise "finish" a wig the brush never got through
        finished = (
            self._prev_fmax is not None
            and not result.aborted
            and abs(f_max - self._prev_fmax) < FINISH_FORCE_TOLERANCE_N
            and b_l >= 1.0 - 1e-9
        )
        detangled = e_now <= self.detangled_fraction * self._e0
        terms = self.reward_config.terms(
            e_prev=self._e,
            e_now=e_now,
            e_initial=self._e0,
            elapsed=result.sim_time + self.reward_config.stroke_overhead_s,
            forces=forces,
            threshold=self.force_threshold,
            done=finished or detangled,
        )
        self._e = e_now
        self._pain += int(result.pull_max_force >= self.force_threshold)
        self._prev_fmax = None if result.aborted else f_max
        self._last.update(force_trace=self._trace(forces), max_force=f_max, brush_length=b_l)
        info = self._info(diverged=False, aborted=result.aborted)
        info.update(
            terms,
            finished_rule=finished,
            detangled=detangled,
            force_samples=forces.tolist(),
            force_times=times,
            pull_max_force=float(result.pull_max_force),
            samples_read=int(result.samples_read),
        )
        reward = float(sum(terms.values()))
        return self._obs(), reward, bool(finished or detangled), False, info

    # --- helpers -----------------------------------------------------------------------------------------------
    def _trace(self, forces: np.ndarray) -> np.ndarray:
        out = np.zeros(self.trace_length, np.float32)
        n = min(len(forces), self.trace_length)
        out[:n] = np.clip(forces[:n], 0.0, LOAD_CELL_CAPACITY_N)  # the load cell saturates at its capacity
        return out

    def _obs(self) -> dict[str, np.ndarray]:
        obs: dict[str, np.ndarray] = {}
        if "state" in self.obs_mode:
            obs["force_trace"] = self._last["force_trace"]
            obs["max_force"] = np.array(
                [np.clip(self._last["max_force"], 0.0, LOAD_CELL_CAPACITY_N)], np.float32
            )
            obs["brush_length"] = np.array([self._last["brush_length"]], np.float32)
            obs["stroke_index"] = np.array([min(self._strokes, MAX_COUNT)], np.float32)
        if "image" in self.obs_mode:
            obs["image"] = self.sim.render()
        return obs

    def _info(self, *, diverged: bool, aborted: bool) -> dict[str, Any]:
        return {
            **self._common_info(diverged),
            "max_force": float(self._last.get("max_force", 0.0)),
            "brush_length": float(self._last.get("brush_length", 0.0)),
            "sim_time": float(self._sim_time),
            "aborted": bool(aborted),
        }
