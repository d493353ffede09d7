"""Policy × wig comparison grid (thesis Figs 3.7, 3.8, 3.11 in simulation), used by ``hairbrush compare``.

Every (wig, policy, episode) cell runs one episode on ``HairBrush-v0`` with seed ``seed + episode`` — the same
seeds for every policy, so policies meet the same pre-brushed wigs. Finished rows are appended to
``results.csv`` as they complete (atomically rewritten), so an interrupted grid keeps its rows and a rerun skips
them.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .io import read_csv_rows, write_csv_rows, write_text

COLUMNS = [
    "wig",
    "curliness",
    "policy",
    "episode",
    "seed",
    "max_force",
    "time",
    "strokes",
    "pain_violations",
    "final_entanglement",
    "entanglement_initial",
    "total_reward",
    "diverged",
]


def read_results(path: str | Path) -> list[dict[str, Any]]:
    """Rows of a results CSV with numeric columns converted."""
    return read_csv_rows(
        path,
        floats=(
            "curliness",
            "max_force",
            "time",
            "final_entanglement",
            "entanglement_initial",
            "total_reward",
        ),
        ints=("episode", "seed", "strokes", "pain_violations"),
        bools=("diverged",),
    )


def run_grid(
    wigs: Sequence[str],
    policies: Sequence[str],
    *,
    episodes: int,
    seed: int,
    out: str | Path,
    env_kwargs: dict[str, Any] | None = None,
    progress: bool = True,
) -> list[dict[str, Any]]:
    """Run (or resume) the grid; returns all rows and writes ``out/results.csv``, ``summary.md`` and plots."""
    import gymnasium as gym
    from tqdm import tqdm

    from .policies import make_policy
    from .rollout import run_episode

    if episodes < 1:
        raise ValueError(f"episodes: must be >= 1, got {episodes}")
    out = Path(out)
    csv_path = out / "results.csv"
    rows = read_results(csv_path) if csv_path.exists() else []
    done = {(r["wig"], r["policy"], r["episode"]) for r in rows}
    todo = [(w, p, e) for w in wigs for p in policies for e in range(episodes) if (w, p, e) not in done]
    bar = tqdm(total=len(todo), desc="compare", unit="episode", disable=not progress)
    envs: dict[str, Any] = {}
    try:
        for wig, policy_name, ep in todo:
            if wig not in envs:
                envs[wig] = gym.make("HairBrush-v0", wig=wig, obs_mode="state+image", **(env_kwargs or {}))
            env = envs[wig]
            policy = make_policy(policy_name, env)
            log = run_episode(env, policy, episode=ep, seed=seed + ep, policy_name=policy_name)
            rows.append(log.summary())
            write_csv_rows(csv_path, rows, COLUMNS)  # after every episode: an interrupt loses at most one
            bar.set_postfix(wig=wig, policy=policy_name, f_max=f"{log.max_force:.1f}")
            bar.update(1)
    finally:
        bar.close()
        for env in envs.values():
            env.close()
    rows.sort(key=lambda r: (r["curliness"], r["wig"], r["policy"], r["episode"]))
    write_csv_rows(csv_path, rows, COLUMNS)
    write_text(out / "summary.md", summary_markdown(rows))
    plot_grid(rows, out / "max_force_vs_curliness.png", out / "time_vs_curliness.png")
    return rows


def summarize(rows: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """Mean ± std over episodes per (wig, policy)."""
    groups: dict[tuple[str, str], list[dict[str, Any]]] = {}
    for r in rows:
        groups.setdefault((r["wig"], r["policy"]), []).append(r)
    table = []
    for (wig, policy), rs in groups.items():
        entry: dict[str, Any] = {"wig": wig, "policy": policy, "curliness": rs[0]["curliness"], "n": len(rs)}
        for key in ("max_force", "time", "strokes", "pain_violations", "final_entanglement"):
            vals = np.array([r[key] for r in rs], dtype=float)
            entry[key] = (float(vals.mean()), float(vals.std(ddof=1)) if len(vals) > 1 else 0.0)
        table.append(entry)
    table.sort(key=lambda e: (e["curliness"], e["wig"], e["policy"]))
    return table


def summary_markdown(rows: Sequence[dict[str, Any]]) -> str:
    lines = [
        "| wig | R/P | policy | n | max force [N] | time [s] | strokes | pain violations | final entanglement |",
        "|---|---:|---|---:|---:|---:|---:|---:|---:|",
    ]
    for e in summarize(rows):
        cells = [f"{m:.2f} ± {s:.2f}" for m, s in (e[k] for k in ("max_force", "time", "strokes"))]
        cells += [f"{m:.2f} ± {s:.2f}" for m, s in (e[k] for k in ("pain_violations", "final_entanglement"))]
        lines.append(
            f"| {e['wig']} | {e['curliness']:.2f} | {e['policy']} | {e['n']} | " + " | ".join(cells) + " |"
        )
    return "\n".join(lines) + "\n"


def plot_grid(rows: Sequence[dict[str, Any]], force_png: str | Path, time_png: str | Path) -> None:
    """Max force and brushing time versus curliness, one line per policy (mean ± std)."""
    from .viz import PALETTE, new_figure, save_figure

    table = summarize(rows)
    policies = sorted({e["policy"] for e in table})
    for key, path, label in (
        ("max_force", force_png, "max force [N]"),
        ("time", time_png, "brushing time [s]"),
    ):
        fig, axes = new_figure(1, 1, width=6.0, height=4.2)
        ax = axes[0, 0]
        for i, pol in enumerate(policies):
            es = [e for e in table if e["policy"] == pol]
            x = [e["curliness"] for e in es]
            m = np.array([e[key][0] for e in es])
            s = np.array([e[key][1] for e in es])
            ax.errorbar(x, m, yerr=s, fmt="o-", color=PALETTE[i % len(PALETTE)], capsize=3, label=pol)
        if key == "max_force":
            ax.axhline(10.0, color="k", ls="--", lw=1, label="pain threshold F_T")
        ax.set(xlabel="curliness R/P", ylabel=label, title=f"{label.split(' [')[0]} vs curliness")
        ax.legend()
        save_figure(fig, path)
