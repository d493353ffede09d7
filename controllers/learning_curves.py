"""Learning curves of a training run written by :func:`controllers.rl_training.train` (issue #6).

Reads the per-worker Monitor CSVs (every training episode: return, length and the final-step env info) and the
held-out evaluations (``eval/held_out.csv``, :mod:`controllers.held_out_eval`), and draws one PNG: episode return,
pain violations, remaining entanglement and strokes per episode against the env steps taken so far. The same table
is what the reward-hacking check reads: an agent that games the reward shows rising returns without falling
entanglement.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np

from hairbrush_env.viz import PALETTE, new_figure, save_figure


def training_episodes(run_dir: str | Path) -> list[dict[str, float]]:
    """Training episodes from ``run_dir/monitor/*.monitor.csv``, in the order they ended.

    Each row has the return ``r``, length ``l``, wall time ``t`` (s since the first worker started), the logged
    info keys, and ``timesteps``: env steps summed over workers when the episode ended (steps of episodes still
    running are not counted, so this slightly undercounts with several workers).
    """
    mon = Path(run_dir) / "monitor"
    files = sorted(mon.glob("*.monitor.csv"))
    if not files:
        raise ValueError(
            f"run_dir: no Monitor CSVs in {mon} (was it written by controllers.rl_training.train?)"
        )
    rows: list[dict[str, float]] = []
    starts = []
    for f in files:
        with f.open() as fh:
            header = json.loads(fh.readline().lstrip("#"))
            starts.append(float(header["t_start"]))
            for r in csv.DictReader(fh):
                rows.append({k: float(v) for k, v in r.items() if v not in ("", None)} | {"_t0": starts[-1]})
    t_first = min(starts)
    for r in rows:
        r["t"] = r.pop("_t0") + r["t"] - t_first
    rows.sort(key=lambda r: r["t"])
    steps = np.cumsum([r["l"] for r in rows])
    for r, s in zip(rows, steps, strict=True):
        r["timesteps"] = float(s)
    return rows


def evaluations(run_dir: str | Path) -> list[dict[str, float]]:
    """Held-out evaluations of ``run_dir`` (``eval/held_out.csv``), one row per evaluation (means over its
    episodes, :func:`controllers.held_out_eval.evaluation_means`)."""
    from .held_out_eval import evaluation_means

    return evaluation_means(Path(run_dir) / "eval" / "held_out.csv")


def training_steps(run_dir: str | Path) -> list[dict[str, float]]:
    """Rows of ``run_dir/steps.csv`` (one per env step of training) as floats; empty if the run has no step log."""
    p = Path(run_dir) / "steps.csv"
    if not p.exists():
        return []
    out = []
    with p.open(newline="") as fh:
        for r in csv.DictReader(fh):
            out.append(
                {k: (float(v == "True") if v in ("True", "False") else float(v)) for k, v in r.items() if v}
            )
    return out


def stroke_summary(
    run_dir: str | Path, *, parts: int = 4, min_brush_length: float = 0.1
) -> list[dict[str, float]]:
    """What the agent did in each of ``parts`` equal slices of its training steps (stroke-level env only).

    Columns: steps range, mean b_l, share of strokes at the lowest b_l (within 0.01 of ``min_brush_length``), share
    of full strokes (b_l = 1), share of strokes that reached F_T (``aborted``), finish bonuses collected, mean
    reward. Rising reward with b_l collapsing to the minimum and no finishes is the "tiny strokes forever" hack.
    """
    rows = [r for r in training_steps(run_dir) if "brush_length" in r]
    if not rows:
        return []
    chunks = np.array_split(np.arange(len(rows)), parts)
    table = []
    for idx in chunks:
        if len(idx) == 0:
            continue
        part = [rows[i] for i in idx]
        b = np.array([r["brush_length"] for r in part])
        table.append(
            {
                "steps": f"{int(part[0]['timesteps'])}–{int(part[-1]['timesteps'])}",
                "mean_b_l": float(b.mean()),
                "at_min": float(np.mean(b <= min_brush_length + 0.01)),
                "full": float(np.mean(b >= 1.0 - 1e-9)),
                "reached_F_T": float(np.mean([r.get("aborted", 0.0) for r in part])),
                "finishes": float(sum(r.get("reward_finish", 0.0) > 0 for r in part)),
                "mean_reward": float(np.mean([r["reward"] for r in part])),
            }
        )
    return table


def stroke_summary_markdown(table: list[dict[str, float]]) -> str:
    lines = [
        "| training steps | mean b_l | at lowest b_l | full strokes | reached F_T | finishes | mean reward |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for t in table:
        lines.append(
            f"| {t['steps']} | {t['mean_b_l']:.2f} | {t['at_min']:.0%} | {t['full']:.0%} | {t['reached_F_T']:.0%} "
            f"| {t['finishes']:.0f} | {t['mean_reward']:.3f} |"
        )
    return "\n".join(lines) + "\n"


def _smooth(y: np.ndarray, window: int) -> np.ndarray:
    if len(y) < window or window < 2:
        return y
    kernel = np.ones(window) / window
    head = np.array([y[: i + 1].mean() for i in range(window - 1)])
    return np.concatenate([head, np.convolve(y, kernel, mode="valid")])


def plot_learning_curves(run_dir: str | Path, path: str | Path | None = None, *, window: int = 5) -> Path:
    """Draw the learning curves of ``run_dir`` (default ``run_dir/learning_curves.png``); returns the path."""
    run_dir = Path(run_dir)
    path = Path(path) if path is not None else run_dir / "learning_curves.png"
    rows = training_episodes(run_dir)
    x = np.array([r["timesteps"] for r in rows])
    fig, axes = new_figure(3, 2, width=4.2, height=3.2)
    panels = [
        ("r", "episode return", axes[0, 0]),
        ("pain_violations", "pain violations / episode", axes[0, 1]),
        ("entanglement_fraction", "final / initial entanglement", axes[1, 0]),
        ("l", "strokes (steps) / episode", axes[1, 1]),
    ]
    for r in rows:
        if "entanglement" in r and r.get("entanglement_initial", 0) > 0:
            r["entanglement_fraction"] = r["entanglement"] / r["entanglement_initial"]
    for key, label, ax in panels:
        y = np.array([r.get(key, np.nan) for r in rows], dtype=float)
        ax.plot(x, y, "o", ms=3, color=PALETTE[0], alpha=0.5, label="training episodes")
        ax.plot(x, _smooth(y, window), "-", color=PALETTE[0], label=f"running mean ({window})")
        ax.set_xlabel("env steps")
        ax.set_ylabel(label)
    steps = training_steps(run_dir)
    per_step = (("brush_length", "b_l chosen", axes[0, 2]), ("max_force", "max force / step [N]", axes[1, 2]))
    for key, label, ax in per_step:
        pts = [(r["timesteps"], r[key]) for r in steps if key in r]
        if pts:
            sx, sy = np.array(pts).T
            ax.plot(sx, sy, ".", ms=2, color=PALETTE[2], alpha=0.4, label="training steps")
            ax.plot(sx, _smooth(sy, 20), "-", color=PALETTE[2], label="running mean (20)")
            ax.legend(fontsize=7)
        ax.set_xlabel("env steps")
        ax.set_ylabel(label)
    evals = evaluations(run_dir)
    if evals:
        ex = [e["timesteps"] for e in evals]
        held_out = (("return", axes[0, 0]), ("pain_violations", axes[0, 1]), ("strokes", axes[1, 1]))
        for key, ax in (*held_out, ("entanglement_left", axes[1, 0])):
            ax.plot(
                ex, [e[key] for e in evals], "s-", color=PALETTE[1], label="held-out eval (deterministic)"
            )
    for ax in axes[:2, :2].ravel():
        ax.legend(fontsize=7)
    cfg = run_dir / "config.json"
    title = run_dir.name
    if cfg.exists():
        c = json.loads(cfg.read_text())
        title = f"{c.get('algo', '').upper()} on {c.get('env')} ({c.get('wig')}, {c.get('n_envs')} workers)"
    fig.suptitle(title, fontsize=10)
    save_figure(fig, path)
    return path
