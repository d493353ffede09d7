"""HairBrushContinuous-v0: 10 Hz velocity control of the brush."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from gymnasium import spaces
from gymnasium.utils import EzPickle

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

CONTROL_DT = 0.1  # 10 Hz, the load cell's rate
#: A pass counts as brushing while the brush TCP is within this of the stroke depth (``BrushingSim.depth_x``) [m].
PASS_DEPTH_TOLERANCE = 0.02
#: A full pass starts within this of the full stroke's start height (``BrushingSim.start_height(1)``) [m].
PASS_START_TOLERANCE = 0.01


class HairBrushContinuousEnv(BrushEnvBase, EzPickle):
    r"""Robotic hair brushing with velocity control at 10 Hz.

    ## Description
    The same scene as `HairBrush-v0` (arm, sensorized brush, pre-brushed wig on a head mount, webcam), but the agent
    commands the brush's vertical and depth velocity every 0.1 s; the arm's Cartesian controller keeps the brush
    level. It is the low-level counterpart of the stroke-level env, for agents that learn their own strokes.

    ## Action Space
    `Box(-1, 1, (2,), float32)`: vertical velocity (up positive) scaled by `max_vertical_speed` and depth
    velocity (into the hair positive) scaled by `max_depth_speed`.

    ## Observation Space
    A `Dict`: `force` `Box(-100, 100, (3,), float32)` (tared load-cell force in the world frame, N, saturating
    at the load cell's capacity), `brush_position` `Box(-1, 1, (3,), float32)` (brush TCP relative to the scalp
    (root) site, m), `elapsed` `Box(0, 1e4, (1,), float32)` (s), and `image`
    `Box(0, 255, (height, width, 3), uint8)` when `obs_mode` includes images.

    ## Rewards
    As `HairBrush-v0`: `reward_progress + reward_time + reward_pain + reward_finish`, with the time cost per
    control step (0.1 s), the pain penalty on the brushing force above F_T, no repositioning overhead, and the
    finish bonus when the episode ends by termination.

    **Full passes and the finish rule.** A *full pass* is the velocity-level full stroke: the brush inside the hair
    (TCP within `PASS_DEPTH_TOLERANCE` of the stroke depth) from the full stroke's start height (within
    `PASS_START_TOLERANCE`) straight down until the whole brush is below every strand or at the pull floor
    (`BrushingSim.pull_end_z`, where HairBrush-v0's pull ends too), never moving up or out on the way. Thesis eq. 3.4
    ends the episode when two consecutive full passes read maximum forces within 0.4 N. Without it the task could
    only end by detangling to `detangled_fraction`, which brushing seldom reaches, so an agent that brushes well and
    one that never touches the hair paid the same time cost for the whole episode, and any brushing that tangled a
    little or hurt scored below doing nothing: the stalling hole (issue #12).

    ## Starting State
    A pre-brushed wig (one of `n_wig_states` cached states picked by the seed); brush above the hair at the
    stroke depth.

    ## Episode End
    Termination when the entanglement falls to `detangled_fraction` of its initial value or the finish rule holds
    (`info["finished_rule"]`); truncation after
    `max_episode_steps` (600 = 60 s, set at registration) or on divergence (`info["diverged"]`).

    ## Arguments
    `wig`, `wig_fields`, `preset_fields`, `scene_fields`, `brush`, `obs_mode`, `render_mode`, `width`, `height`,
    `force_threshold`, `n_wig_states`, `wig_seeds`, `state_cache_dir`, `detangled_fraction`, `reward`,
    `load_cell_noise` as in `HairBrush-v0`, plus `max_vertical_speed` (0.2 m/s) and `max_depth_speed` (0.05 m/s).

    ## Version History
    - v0: initial release. Issue #11: the progress reward divides by at least one link (`PROGRESS_FLOOR`; only
      straight hair, with ~1e-4 of initial link, changes), in every version.
    - v1: v0 with the v1 physics of `HairBrush-v1` (self-colliding strands, hair–hair friction 0.15, soft comb).
    - v2: v0 with the v2 physics of `HairBrush-v2` (v1 with less joint damping, stiffer wisps, drag on the strands).
    - v3: v0 with the v3 physics of `HairBrush-v3` (v2 with every group a pair, the comb two tines wider).
    - v4: v0 with the v4 physics of `HairBrush-v4` (v3 with each pair curling from a different depth below its roots).
    - v5: v0 with the v5 physics of `HairBrush-v5` (v4 with every pair hanging straight for 12 mm below its roots).
    - v6: v0 with the v6 physics of `HairBrush-v6` (v5 with a pair's strands resting apart across the tines).
    - v7: v0 with the v7 physics of `HairBrush-v7` (v6 with smaller curls on the curliest presets).
    - v8: v0 with the v8 physics of `HairBrush-v8` (v7 with tines that hair slides on at its own friction).
    - v9: v0 with the v9 physics of `HairBrush-v9` (v8 with the drag across the strands only and springy tines).
    - v10: the same as v9: v10 changes only what a stroke of `HairBrush-v10` reads (`read_in_hair`), and this env
      has no strokes.
    """

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
        max_vertical_speed: float = 0.2,
        max_depth_speed: float = 0.05,
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
        self.max_vertical_speed = check_positive("max_vertical_speed", max_vertical_speed)
        self.max_depth_speed = check_positive("max_depth_speed", max_depth_speed)

        self.action_space = spaces.Box(-1.0, 1.0, shape=(2,), dtype=np.float32)
        obs_spaces: dict[str, spaces.Space] = {}
        if "state" in obs_mode:
            obs_spaces.update(
                force=spaces.Box(-LOAD_CELL_CAPACITY_N, LOAD_CELL_CAPACITY_N, shape=(3,), dtype=np.float32),
                brush_position=spaces.Box(-1.0, 1.0, shape=(3,), dtype=np.float32),
                elapsed=spaces.Box(0.0, MAX_COUNT, shape=(1,), dtype=np.float32),
            )
        if "image" in obs_mode:
            obs_spaces["image"] = self._image_space()
        self.observation_space = spaces.Dict(obs_spaces)
        self._force = np.zeros(3)
        self._t = 0.0
        self._max_force = 0.0
        self._pass_fmax: float | None = None  # the running full pass's maximum force (None: no pass running)
        self._prev_pass_fmax: float | None = None
        self._passes = 0

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        """Start an episode; ``options={"wig_seed": s}`` as in `HairBrush-v0`."""
        options = dict(options or {})
        wig_seed = options.pop("wig_seed", None)
        if options:
            raise ValueError(f"options: unknown keys {sorted(options)}; known: ['wig_seed']")
        self._reset_sim(seed, wig_seed)
        self._t, self._max_force = 0.0, 0.0
        self._force = np.zeros(3)
        self._pass_fmax, self._prev_pass_fmax, self._passes = None, None, 0
        return self._obs(), self._info(False)

    def step(self, action):
        action = check_action(action, self.action_space)
        v_z = float(action[0]) * self.max_vertical_speed
        v_depth = float(action[1]) * self.max_depth_speed
        result = self.sim.step_velocity(v_z, v_depth, CONTROL_DT)
        self._t += CONTROL_DT
        if result.diverged:
            info = self._info(True)
            info.update(RewardConfig.zero_terms())
            return self._obs(), 0.0, False, True, info
        latest = self.sim.load_cell.latest
        self._force = latest.force_world if latest is not None else np.zeros(3)
        brushing = float(result.force) if math.isfinite(result.force) else 0.0
        self._max_force = max(self._max_force, brushing)
        self._pain += int(brushing >= self.force_threshold)
        e_now = self.sim.entanglement()
        finished = self._track_pass(brushing, v_z)
        detangled = e_now <= self.detangled_fraction * self._e0
        terminated = finished or detangled
        terms = self.reward_config.terms(
            e_prev=self._e,
            e_now=e_now,
            e_initial=self._e0,
            elapsed=CONTROL_DT,
            forces=np.array([brushing]),
            threshold=self.force_threshold,
            done=terminated,
        )
        self._e = e_now
        info = self._info(False)
        info.update(
            terms,
            brushing_force=brushing,
            force_samples=[brushing],
            force_times=[self._t],
            finished_rule=finished,
            detangled=detangled,
        )
        return self._obs(), float(sum(terms.values())), bool(terminated), False, info

    def _track_pass(self, force: float, v_z: float) -> bool:
        """Update the running full pass with this control step; True when eq. 3.4 finishes the episode."""
        sim = self.sim
        p = sim.brush_position()
        inside = p[0] >= sim.depth_x - PASS_DEPTH_TOLERANCE
        if self._pass_fmax is None:
            if inside and p[2] >= sim.start_height(1.0) - PASS_START_TOLERANCE:
                self._pass_fmax = force
            return False
        if not inside or v_z > 0.0:
            self._pass_fmax = None  # left the hair or went back up: not a full pass
            return False
        self._pass_fmax = max(self._pass_fmax, force)
        # HairBrush-v0's pull ends the same way: below every strand, or at the pull floor (dragged curls can hang
        # below the workspace)
        if not (sim.brush_below_hair() or p[2] <= sim.pull_end_z + PASS_START_TOLERANCE):
            return False
        f, prev = self._pass_fmax, self._prev_pass_fmax
        self._pass_fmax, self._prev_pass_fmax = None, f
        self._passes += 1
        return prev is not None and abs(f - prev) < FINISH_FORCE_TOLERANCE_N

    def _obs(self) -> dict[str, np.ndarray]:
        obs: dict[str, np.ndarray] = {}
        if "state" in self.obs_mode:
            obs["force"] = np.clip(self._force, -LOAD_CELL_CAPACITY_N, LOAD_CELL_CAPACITY_N).astype(
                np.float32
            )
            rel = self.sim.brush_position() - self.sim.root_origin
            obs["brush_position"] = np.clip(rel, -1.0, 1.0).astype(np.float32)
            obs["elapsed"] = np.array([min(self._t, MAX_COUNT)], np.float32)
        if "image" in self.obs_mode:
            obs["image"] = self.sim.render()
        return obs

    def _info(self, diverged: bool) -> dict[str, Any]:
        return {
            **self._common_info(diverged),
            "max_force": float(self._max_force),
            "sim_time": float(self._t),
            "full_passes": int(self._passes),
        }
