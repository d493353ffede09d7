"""Evaluation of a training agent on the held-out wigs (issue #12), as an SB3 callback.

Every ``every`` environment steps (summed over workers, and once before the first update) the agent brushes each
held-out wig ``episodes`` times, deterministically, from the same pre-brushed states each time (the eval workers are
reseeded before every evaluation, so two evaluations differ only by the agent). One row per episode is appended to
``eval/held_out.csv``: the training step, wig, return, strokes, pain violations, the episode's maximum force, the
remaining entanglement fraction, whether it finished (eq. 3.4 or detangled) and its simulated time. The best mean
return so far keeps its model in ``best/best_model.zip`` (written atomically).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from hairbrush_env.io import atomic_path

EVAL_COLUMNS = (
    "timesteps",
    "wig",
    "episode",
    "return",
    "strokes",
    "pain_violations",
    "max_force",
    "entanglement_left",
    "finished",
    "sim_time",
)


def read_evaluations(path: str | Path) -> list[dict[str, float | str]]:
    """Rows of ``eval/held_out.csv`` (numbers as floats)."""
    path = Path(path)
    if not path.exists():
        return []
    with path.open(newline="") as fh:
        return [
            {
                k: (v if k == "wig" else float(v == "True") if v in ("True", "False") else float(v))
                for k, v in r.items()
            }
            for r in csv.DictReader(fh)
        ]


def evaluation_means(path: str | Path) -> list[dict[str, float]]:
    """One row per evaluation of ``eval/held_out.csv``: ``timesteps`` and the means over its episodes of
    ``return``, ``pain_violations``, ``strokes``, ``entanglement_left`` and ``finished``."""
    by_step: dict[float, list[dict]] = {}
    for r in read_evaluations(path):
        by_step.setdefault(float(r["timesteps"]), []).append(r)
    keys = ("return", "pain_violations", "strokes", "entanglement_left", "finished")
    return [
        {"timesteps": t} | {k: float(np.mean([float(r[k]) for r in rows])) for k in keys}
        for t, rows in sorted(by_step.items())
    ]


def run_episodes(model, venv, episodes: int, seed: int) -> list[dict[str, float | str]]:
    """``episodes`` deterministic episodes on every worker of ``venv`` (worker i resets with ``seed + i`` first)."""
    n = venv.num_envs
    venv.seed(seed)
    obs = venv.reset()
    done_count = np.zeros(n, int)
    ret = np.zeros(n)
    strokes = np.zeros(n, int)
    fmax = np.zeros(n)
    rows: list[dict[str, float | str]] = []
    while (done_count < episodes).any():
        action, _ = model.predict(obs, deterministic=True)
        obs, reward, dones, infos = venv.step(action)
        for i in range(n):
            if done_count[i] >= episodes:
                continue
            ret[i] += float(reward[i])
            strokes[i] += 1
            fmax[i] = max(fmax[i], float(infos[i].get("max_force", 0.0)))
            if dones[i]:
                info = infos[i]
                rows.append(
                    {
                        "wig": str(info.get("wig")),
                        "episode": int(done_count[i]),
                        "return": float(ret[i]),
                        "strokes": int(strokes[i]),
                        "pain_violations": int(info.get("pain_violations", 0)),
                        "max_force": float(fmax[i]),
                        "entanglement_left": float(
                            info["entanglement"] / max(info["entanglement_initial"], 1e-12)
                        ),
                        "finished": not bool(
                            info.get("TimeLimit.truncated", False) or info.get("diverged", False)
                        ),
                        "sim_time": float(info.get("sim_time", 0.0)),
                    }
                )
                done_count[i] += 1
                ret[i], strokes[i], fmax[i] = 0.0, 0, 0.0
    return rows


def held_out_eval_callback(
    eval_env, out: str | Path, *, every: int, episodes: int, seed: int, best_return: float = -np.inf
):
    """The callback; ``best_return`` carries the best mean return over from a resumed run."""
    from stable_baselines3.common.callbacks import BaseCallback

    out = Path(out)

    class HeldOutEval(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.best_return = best_return
            self.csv_path = out / "eval" / "held_out.csv"

        def _on_training_start(self) -> None:
            done = {int(r["timesteps"]) for r in read_evaluations(self.csv_path)}
            if not done:
                # the first evaluation, before any update: what a learning curve is judged against
                self.evaluate()
            else:
                # a resumed run keeps the schedule: the next multiple of ``every`` after the last evaluation
                self.next_eval = self._after(max(done))

        def _after(self, steps: int) -> int:
            return (steps // every + 1) * every

        def _on_step(self) -> bool:
            if self.num_timesteps >= self.next_eval:
                self.evaluate()
            return True

        def evaluate(self) -> None:
            rows = run_episodes(self.model, eval_env, episodes, seed)
            self.csv_path.parent.mkdir(parents=True, exist_ok=True)
            new = not self.csv_path.exists() or self.csv_path.stat().st_size == 0
            with self.csv_path.open("a", newline="") as fh:
                writer = csv.DictWriter(fh, fieldnames=list(EVAL_COLUMNS), lineterminator="\n")
                if new:
                    writer.writeheader()
                for r in rows:
                    writer.writerow({"timesteps": self.num_timesteps, **r})
            mean = float(np.mean([r["return"] for r in rows]))
            self.logger.record("eval/held_out_return", mean)
            self.logger.record(
                "eval/held_out_entanglement_left", float(np.mean([r["entanglement_left"] for r in rows]))
            )
            if mean > self.best_return:
                self.best_return = mean
                best = out / "best" / "best_model.zip"
                best.parent.mkdir(parents=True, exist_ok=True)
                with atomic_path(best) as tmp:
                    self.model.save(tmp)
            self.next_eval = self._after(self.num_timesteps)

    return HeldOutEval()
