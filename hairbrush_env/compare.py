"""Policy × wig comparison grid (thesis Figs 3.7, 3.8, 3.11 in simulation), used by ``hairbrush compare``.

Every (wig, policy, episode) cell runs one episode on ``HairBrush-<physics>`` (``v0`` by default, ``v1``:
:mod:`hairbrush_env.physics`; recorded in ``physics.json``) with seed ``seed + episode``, from the
``episode``-th pre-brushed state of the wig (cycling through them) — the same seeds and states for every policy, so
policies meet the same pre-brushed wigs and the episodes of a cell meet distinct ones. Finished rows are appended to
``results.csv`` as they complete (atomically rewritten), so an interrupted grid keeps its rows and a rerun skips
them.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .constants import PAIN_THRESHOLD_N
from .executor import CellLog, CellOutcome, CellsFailed, ExecutorConfig, run_cells
from .io import read_csv_rows, write_csv_rows, write_text

COLUMNS = [
    "wig",
    "R_over_P",
    "policy",
    "abort_force",
    "episode",
    "seed",
    "wig_seed",
    "max_force",
    "pull_max_force",
    "sim_time",
    "strokes",
    "pain_violations",
    "entanglement_final",
    "entanglement_initial",
    "total_reward",
    "diverged",
]


def read_results(path: str | Path) -> list[dict[str, Any]]:
    """Rows of a results CSV with numeric columns converted (``abort_force``: a float, or None = pulled through)."""
    rows = read_csv_rows(
        path,
        floats=(
            "R_over_P",
            "max_force",
            "sim_time",
            "entanglement_final",
            "entanglement_initial",
            "total_reward",
        ),
        ints=("episode", "seed", "strokes", "pain_violations"),
        bools=("diverged",),
        fallbacks={"pull_max_force": "max_force"},  # absent from grids run before v10 read part of a pull
    )
    for row in rows:
        value = row.get("abort_force", "")
        row["abort_force"] = float(value) if value not in ("", "None", None) else None
        value = row.get("wig_seed", "")  # absent from grids run before episodes were given distinct wigs
        row["wig_seed"] = int(value) if value not in ("", "None", None) else None
    return rows


#: One env per wig and process, built on first use (building a scene takes seconds; episodes reuse it).
_ENVS: dict[tuple[str, str, str], Any] = {}


def run_cell(
    wig: str,
    policy_name: str,
    episode: int,
    seed: int,
    env_kwargs: dict[str, Any],
    env_id: str = "HairBrush-v0",
) -> dict:
    """One episode of the grid, seeded by its own cell (``seed + episode``): the executor's worker function."""
    from .envs import make_version
    from .hair import brushing_seeds
    from .policies import make_policy
    from .rollout import run_episode

    # held-out wigs are brushed from the held-out pre-brushed states (RL's test set), the others from seeds 0-3;
    # episode k starts from the k-th of them (cycling), so the episodes of a cell meet distinct wigs and every policy
    # meets the same ones (drawn by the seed, two of three episodes met the same wig)
    env_kwargs = {"wig_seeds": brushing_seeds([wig]), **env_kwargs}
    wig_seeds = tuple(env_kwargs["wig_seeds"])
    key = (env_id, wig, repr(sorted(env_kwargs.items())))
    if key not in _ENVS:
        _ENVS[key] = make_version(env_id, wig=wig, obs_mode="state+image", **env_kwargs)
    env = _ENVS[key]
    policy = make_policy(policy_name, env)
    log = run_episode(
        env,
        policy,
        episode=episode,
        seed=seed + episode,
        policy_name=policy_name,
        wig_seed=wig_seeds[episode % len(wig_seeds)],
    )
    return log.summary()


def close_envs() -> None:
    """Close the envs this process built for grid cells."""
    while _ENVS:
        _ENVS.popitem()[1].close()


def _check_names(wigs: Sequence[str], policies: Sequence[str]) -> None:
    """Unknown wigs and policies are reported before anything is simulated (a grid can run for hours)."""
    from .hair import get_wig
    from .policies import policy_entry_point

    for wig in wigs:
        get_wig(wig)  # ValueError listing the presets
    for name in policies:
        policy_entry_point(name)  # ValueError listing the registered policies


def run_grid(
    wigs: Sequence[str],
    policies: Sequence[str],
    *,
    episodes: int,
    seed: int,
    out: str | Path,
    env_kwargs: dict[str, Any] | None = None,
    executor: ExecutorConfig | None = None,
    progress: bool = True,
    physics: str = "v0",
) -> list[dict[str, Any]]:
    """Run (or resume) the grid; returns all rows and writes ``out/results.csv``, ``summary.md``, plots and the
    per-episode timing and errors ``cells.csv``.

    ``executor`` runs the episodes (default: this process; :mod:`hairbrush_env.executor`: local worker processes
    or Ray, each worker building its own envs). A failed episode is reported while the others finish, then raises
    :class:`~hairbrush_env.executor.CellsFailed` naming it; a rerun retries it.
    """
    from .physics import claim_physics, get_physics

    if episodes < 1:
        raise ValueError(f"episodes: must be >= 1, got {episodes}")
    env_id = f"HairBrush-{get_physics(physics).name}"
    _check_names(wigs, policies)
    executor = executor if executor is not None else ExecutorConfig()
    out = Path(out)
    csv_path = out / "results.csv"
    rows = read_results(csv_path) if csv_path.exists() else []
    claim_physics(out, physics, resuming=bool(rows))
    done = {(r["wig"], r["policy"], r["episode"]) for r in rows}
    todo = [(w, p, e) for w in wigs for p in policies for e in range(episodes) if (w, p, e) not in done]
    kwargs = dict(env_kwargs or {})
    log = CellLog(out / "cells.csv", executor)
    cells = [((w, p, e), (w, p, e, seed, kwargs, env_id)) for w, p, e in todo]

    def postfix(o: CellOutcome) -> dict[str, Any]:
        return {"wig": o.value["wig"], "policy": o.value["policy"], "f_max": f"{o.value['max_force']:.1f}"}

    try:
        for outcome in run_cells(
            run_cell,
            cells,
            executor=executor,
            desc="compare",
            unit="episode",
            progress=progress,
            postfix=postfix,
        ):
            log.record(outcome)
            if outcome.ok:
                rows.append(outcome.value)
                # after every episode: an interrupt loses at most the episodes still running
                write_csv_rows(csv_path, _sorted(rows), COLUMNS)
    finally:
        close_envs()
    rows = _sorted(rows)
    write_csv_rows(csv_path, rows, COLUMNS)
    write_text(out / "summary.md", summary_markdown(rows))
    if rows:
        plot_grid(rows, out / "max_force_vs_curliness.png", out / "time_vs_curliness.png")
    if log.failed:
        raise CellsFailed("episode(s)", log.failed)
    return rows


def _sorted(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    return sorted(rows, key=lambda r: (r["R_over_P"], r["wig"], r["policy"], r["episode"]))


#: Columns of the summary, each as mean ± std over a cell's episodes (the RL issue's comparison table).
SUMMARY_KEYS = (
    "total_reward",
    "max_force",
    "pull_max_force",
    "sim_time",
    "strokes",
    "pain_violations",
    "entanglement_final",
)


def summarize(rows: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """Mean ± std over episodes per (wig, policy)."""
    groups: dict[tuple[str, str], list[dict[str, Any]]] = {}
    for r in rows:
        groups.setdefault((r["wig"], r["policy"]), []).append(r)
    table = []
    for (wig, policy), rs in groups.items():
        entry: dict[str, Any] = {"wig": wig, "policy": policy, "R_over_P": rs[0]["R_over_P"], "n": len(rs)}
        for key in SUMMARY_KEYS:
            vals = np.array([r[key] for r in rs], dtype=float)
            entry[key] = (float(vals.mean()), float(vals.std(ddof=1)) if len(vals) > 1 else 0.0)
        table.append(entry)
    table.sort(key=lambda e: (e["R_over_P"], e["wig"], e["policy"]))
    return table


def summary_markdown(rows: Sequence[dict[str, Any]]) -> str:
    lines = [
        "| wig | R/P | policy | n | return | max force [N] | max of the pulls [N] | time [s] | strokes "
        "| pain violations | final entanglement |",
        "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for e in summarize(rows):
        cells = [f"{m:.2f} ± {s:.2f}" for m, s in (e[k] for k in SUMMARY_KEYS)]
        lines.append(
            f"| {e['wig']} | {e['R_over_P']:.2f} | {e['policy']} | {e['n']} | " + " | ".join(cells) + " |"
        )
    return "\n".join(lines) + "\n"


def plot_grid(rows: Sequence[dict[str, Any]], force_png: str | Path, time_png: str | Path) -> None:
    """Max force and brushing time versus curliness, one line per policy (mean ± std)."""
    from .viz import PALETTE, new_figure, save_figure

    table = summarize(rows)
    policies = sorted({e["policy"] for e in table})
    for key, path, label in (
        ("max_force", force_png, "max force [N]"),
        ("sim_time", time_png, "brushing time [s]"),
    ):
        fig, axes = new_figure(1, 1, width=6.0, height=4.2)
        ax = axes[0, 0]
        for i, pol in enumerate(policies):
            es = [e for e in table if e["policy"] == pol]
            x = [e["R_over_P"] for e in es]
            m = np.array([e[key][0] for e in es])
            s = np.array([e[key][1] for e in es])
            ax.errorbar(x, m, yerr=s, fmt="o-", color=PALETTE[i % len(PALETTE)], capsize=3, label=pol)
        if key == "max_force":
            ax.axhline(PAIN_THRESHOLD_N, color="k", ls="--", lw=1, label="pain threshold F_T")
        ax.set(xlabel="curliness R/P", ylabel=label, title=f"{label.split(' [')[0]} vs curliness")
        ax.legend()
        save_figure(fig, path)
