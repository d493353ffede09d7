"""Headless rollouts of a policy on a brushing env: per-stroke logs, optional rerun recording and video.

Used by ``hairbrush rollout`` and ``hairbrush compare``. A rollout never raises on a diverging simulation: the
env truncates the episode with ``info["diverged"] = True`` and the log records it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import Any

SAMPLE_DT = 0.1  # load-cell period (10 Hz)


@dataclass
class StepLog:
    """One env step (a stroke for HairBrush-v0, a 0.1 s control step for HairBrushContinuous-v0)."""

    index: int
    t_start: float  # simulated brushing time at the start of the step [s]
    forces: list[float]  # brushing-force samples at 10 Hz [N]
    times: list[float]  # episode time of each sample [s]
    max_force: float
    entanglement: float
    reward: float
    brush_length: float | None = None
    aborted: bool = False
    #: Largest sample of the whole step; ``max_force`` is the largest the stroke read (``info["samples_read"]``).
    pull_max_force: float = 0.0


@dataclass
class EpisodeLog:
    episode: int
    seed: int
    wig: str
    policy: str
    curliness_true: float
    entanglement_initial: float
    steps: list[StepLog] = field(default_factory=list)
    total_reward: float = 0.0
    pain_violations: int = 0
    sim_time: float = 0.0
    terminated: bool = False
    truncated: bool = False
    diverged: bool = False
    abort_force: float | None = None
    wig_seed: int | None = None

    @property
    def max_force(self) -> float:
        return max((s.max_force for s in self.steps), default=0.0)

    @property
    def pull_max_force(self) -> float:
        """Largest force sample of any stroke's whole pull (what pain is counted on; ``max_force``: what the strokes
        read, which a version with ``read_in_hair`` limits to the brush in the hair)."""
        return max((s.pull_max_force for s in self.steps), default=0.0)

    @property
    def final_entanglement(self) -> float:
        return self.steps[-1].entanglement if self.steps else self.entanglement_initial

    def summary(self) -> dict[str, Any]:
        """Flat per-episode metrics (the columns of results tables)."""
        return {
            "episode": self.episode,
            "seed": self.seed,
            "wig": self.wig,
            "R_over_P": self.curliness_true,
            "policy": self.policy,
            "abort_force": self.abort_force,
            "wig_seed": self.wig_seed,
            "max_force": self.max_force,
            "pull_max_force": self.pull_max_force,
            "sim_time": round(self.sim_time, 3),
            "strokes": len(self.steps),
            "pain_violations": self.pain_violations,
            "entanglement_initial": self.entanglement_initial,
            "entanglement_final": self.final_entanglement,
            "total_reward": self.total_reward,
            "terminated": self.terminated,
            "truncated": self.truncated,
            "diverged": self.diverged,
        }

    def to_dict(self) -> dict[str, Any]:
        return {**self.summary(), "steps": [asdict(s) for s in self.steps]}


def run_episode(
    env: Any,
    policy: Any,
    *,
    episode: int,
    seed: int,
    policy_name: str,
    on_step: Callable[[EpisodeLog, StepLog, dict], None] | None = None,
    wig_seed: int | None = None,
) -> EpisodeLog:
    """Run one episode to its end (termination or truncation) and return its log.

    ``on_step(log, step, info)`` is called after every env step (recording, progress). A policy with an
    ``abort_force`` attribute (a force [N], or ``None`` to pull through) has the stroke env abort its strokes there
    (``reset(options={"abort_force": ...})``), so every policy brushes as it would in the thesis. ``wig_seed`` names
    the pre-brushed state to start from (``reset(options={"wig_seed": ...})``); by default the seed draws it.
    """
    options: dict[str, Any] = {"abort_force": policy.abort_force} if hasattr(policy, "abort_force") else {}
    if wig_seed is not None:
        options["wig_seed"] = int(wig_seed)
    obs, info = env.reset(seed=seed, options=options or None)
    policy.reset(seed)
    log = EpisodeLog(
        episode=episode,
        seed=seed,
        wig=str(info.get("wig", "custom")),
        policy=policy_name,
        curliness_true=float(info["curliness_true"]),
        entanglement_initial=float(info["entanglement_initial"]),
        abort_force=getattr(getattr(env, "unwrapped", env), "abort_force", None),
        wig_seed=info.get("wig_seed"),
    )
    while True:
        t_start = float(info.get("sim_time", 0.0))
        obs, reward, terminated, truncated, info = env.step(policy.act(obs))
        forces = [float(f) for f in info.get("force_samples", ())]
        read = int(
            info.get("samples_read", len(forces))
        )  # what the stroke read (HairBrush-v10: the brush in the hair)
        step = StepLog(
            index=len(log.steps),
            t_start=t_start,
            forces=forces,
            times=[float(t) for t in info.get("force_times", ())],
            max_force=float(max(forces[:read], default=0.0)),
            entanglement=float(info["entanglement"]),
            reward=float(reward),
            brush_length=info.get("brush_length"),
            aborted=bool(info.get("aborted", False)),
            pull_max_force=float(max(forces, default=0.0)),
        )
        log.steps.append(step)
        log.total_reward += float(reward)
        log.pain_violations = int(info.get("pain_violations", 0))
        log.sim_time = float(info.get("sim_time", 0.0))
        if on_step is not None:
            on_step(log, step, info)
        if terminated or truncated:
            log.terminated, log.truncated = bool(terminated), bool(truncated)
            log.diverged = bool(info.get("diverged", False))
            return log
