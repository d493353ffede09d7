"""Single-stroke force measurements: max force vs curliness, brush length and speed (thesis Figs 3.7, 3.8).

The thesis measured the maximum brushing force of one downward stroke while varying the normalized brush length
``b_l`` on wigs of different curliness (Fig. 3.7) and the brushing speed at a fixed length (Fig. 3.8; "the wigs are
reset between each test"). :func:`measure_strokes` does the same on :class:`~hairbrush_env.scene.BrushingSim`: every
cell ``(wig, b_l, speed, seed)`` restores the pre-brushed wig of that seed, makes one stroke without the pain abort
(``F_T = ∞``, so the whole force profile is seen) and records its maximum load-cell force. Seeds are the
repetitions: they give different pre-brushed wigs and load-cell noise, and the mean ± std over them is what the
thesis plots.

Rows are written to ``out/strokes.csv`` after every cell (atomically), so an interrupted run keeps its rows and a
rerun skips them. Cells run where :mod:`hairbrush_env.executor` puts them (this process, local workers or Ray).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .executor import CellLog, CellOutcome, CellsFailed, ExecutorConfig, run_cells
from .io import read_csv_rows, write_csv_rows, write_text

COLUMNS = [
    "wig",
    "R_over_P",
    "brush_length",
    "speed",
    "seed",
    "max_force",
    "sim_time",
    "diverged",
    "pull_max_force",
]


def read_strokes(path: str | Path) -> list[dict[str, Any]]:
    """Rows of a ``strokes.csv`` with numeric columns converted (``pull_max_force``, absent from files written before
    v10 read part of a pull, is then ``max_force``: the whole pull was read)."""
    return read_csv_rows(
        path,
        floats=("R_over_P", "brush_length", "speed", "max_force", "sim_time"),
        ints=("seed",),
        bools=("diverged",),
        fallbacks={"pull_max_force": "max_force"},
    )


def _check(name: str, values: Sequence[float], lo: float, hi: float) -> list[float]:
    vals = [float(v) for v in values]
    if not vals:
        raise ValueError(f"{name}: need at least one value")
    for v in vals:
        if not (math.isfinite(v) and lo <= v <= hi):
            raise ValueError(f"{name}: values must be in [{lo}, {hi}], got {v!r}")
    if len(set(vals)) != len(vals):
        raise ValueError(f"{name}: values must not repeat, got {vals!r}")
    return vals


#: One simulator per wig and process, built on first use (building a scene takes seconds; strokes reuse it).
_SIMS: dict[str, Any] = {}


def stroke_cell(wig: str, b_l: float, speed: float, seed: int, physics: str = "v0") -> dict[str, Any]:
    """One cell: the pre-brushed wig of ``seed``, one stroke without abort, load-cell noise seeded by ``seed``
    (the executor's worker function)."""
    from .physics import get_physics
    from .scene import BrushingSim

    key = f"{physics}:{wig}"
    if key not in _SIMS:
        _SIMS[key] = BrushingSim(get_physics(physics).scene_config(wig))
    sim = _SIMS[key]
    sim.reset(seed)
    res = sim.stroke(b_l, speed=speed, abort_force=None, rng=np.random.default_rng(seed))
    return {
        "wig": wig,
        "R_over_P": sim.curliness_true,
        "brush_length": b_l,
        "speed": speed,
        "seed": seed,
        "max_force": res.max_force,
        "pull_max_force": res.pull_max_force,
        "sim_time": res.sim_time,
        "diverged": res.diverged,
    }


def close_sims() -> None:
    """Close the simulators this process built for stroke cells."""
    while _SIMS:
        _SIMS.popitem()[1].close()


def measure_strokes(
    wigs: Sequence[str],
    *,
    brush_lengths: Sequence[float] = (1.0,),
    speeds: Sequence[float] = (0.1,),
    seeds: Sequence[int] = (0,),
    out: str | Path | None = None,
    executor: ExecutorConfig | None = None,
    progress: bool = True,
    physics: str = "v0",
) -> list[dict[str, Any]]:
    """Max force of one stroke for every ``(wig, brush_length, speed, seed)``.

    Parameters
    ----------
    wigs : sequence of str
        Preset names (:data:`hairbrush_env.hair.PRESETS`).
    brush_lengths : sequence of float
        Normalized start heights ``b_l ∈ (0, 1]`` (fraction of the hanging length above the free ends).
    speeds : sequence of float
        Pull speeds [m/s], in ``(0, 0.5]`` (the arm's tracking limit).
    seeds : sequence of int
        Pre-brushed wig / noise seeds (the repetitions).
    out : path, optional
        Directory for ``strokes.csv`` (resumed if present), ``summary.md``, ``force_vs_*.png`` and the per-stroke
        timing and errors ``cells.csv``.
    executor : ExecutorConfig, optional
        Where strokes run (default: this process; :mod:`hairbrush_env.executor`).
    progress : bool
        Show a progress bar.
    physics : str
        Version of the brushing physics (:mod:`hairbrush_env.physics`; recorded in ``out/physics.json``).

    Returns
    -------
    list of dict
        One row per stroke, columns :data:`COLUMNS`. A failed stroke is reported while the others finish, then
        raises :class:`~hairbrush_env.executor.CellsFailed` naming it.
    """
    from . import hair
    from .physics import claim_physics, get_physics

    get_physics(physics)
    unknown = [w for w in wigs if w not in hair.PRESETS]
    if unknown or not wigs:
        raise ValueError(f"wigs: unknown preset(s) {unknown!r}; choose from {list(hair.PRESETS)}")
    lengths = _check("brush_lengths", brush_lengths, 1e-3, 1.0)
    speed_list = _check("speeds", speeds, 1e-3, 0.5)
    seed_list = [int(s) for s in seeds]
    if not seed_list or len(set(seed_list)) != len(seed_list):
        raise ValueError(f"seeds: need distinct seeds, got {seed_list!r}")

    csv_path = Path(out) / "strokes.csv" if out is not None else None
    rows = read_strokes(csv_path) if csv_path is not None and csv_path.exists() else []
    if out is not None:
        claim_physics(out, physics, resuming=bool(rows))
    done = {(r["wig"], r["brush_length"], r["speed"], r["seed"]) for r in rows}
    cells = [
        ((w, b, v, s), (w, b, v, s, physics))
        for w in wigs
        for b in lengths
        for v in speed_list
        for s in seed_list
        if (w, b, v, s) not in done
    ]
    log = CellLog(Path(out) / "cells.csv" if out is not None else None, executor)

    def postfix(o: CellOutcome) -> dict[str, Any]:
        w, b, v, _ = o.key
        return {"wig": w, "b_l": b, "v": v, "f_max": f"{o.value['max_force']:.1f}"}

    try:
        for outcome in run_cells(
            stroke_cell,
            cells,
            executor=executor,
            desc="strokes",
            unit="stroke",
            progress=progress,
            postfix=postfix,
        ):
            log.record(outcome)
            if outcome.ok:
                rows.append(outcome.value)
                # after every stroke: an interrupt loses at most the strokes still running
                if csv_path is not None:
                    write_csv_rows(csv_path, _sorted(rows), COLUMNS)
    finally:
        close_sims()
    rows = _sorted(rows)
    if out is not None:
        write_csv_rows(Path(out) / "strokes.csv", rows, COLUMNS)
        write_text(Path(out) / "summary.md", summary_markdown(rows))
        if rows:
            plot_strokes(rows, out)
    if log.failed:
        raise CellsFailed("stroke(s)", log.failed)
    return rows


def _sorted(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    return sorted(rows, key=lambda r: (r["R_over_P"], r["wig"], r["brush_length"], r["speed"], r["seed"]))


def summarize(rows: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """Mean, std and count of the max force per ``(wig, brush_length, speed)`` (diverged strokes excluded)."""
    groups: dict[tuple[str, float, float], list[dict[str, Any]]] = {}
    for r in rows:
        if not r["diverged"]:
            groups.setdefault((r["wig"], r["brush_length"], r["speed"]), []).append(r)
    table = []
    for (wig, b_l, speed), rs in groups.items():
        f = np.array([r["max_force"] for r in rs])
        table.append(
            {
                "wig": wig,
                "R_over_P": rs[0]["R_over_P"],
                "brush_length": b_l,
                "speed": speed,
                "n": len(rs),
                "mean": float(f.mean()),
                "std": float(f.std(ddof=1)) if len(f) > 1 else 0.0,
            }
        )
    table.sort(key=lambda e: (e["R_over_P"], e["wig"], e["brush_length"], e["speed"]))
    return table


def summary_markdown(rows: Sequence[dict[str, Any]]) -> str:
    lines = ["| wig | R/P | b_l | speed [m/s] | n | max force [N] |", "|---|---:|---:|---:|---:|---:|"]
    for e in summarize(rows):
        lines.append(
            f"| {e['wig']} | {e['R_over_P']:.2f} | {e['brush_length']:.2f} | {e['speed']:.3f} | {e['n']} | "
            f"{e['mean']:.2f} ± {e['std']:.2f} |"
        )
    return "\n".join(lines) + "\n"


def plot_strokes(rows: Sequence[dict[str, Any]], out: str | Path) -> list[Path]:
    """``force_vs_brush_length.png`` (Fig. 3.7) and ``force_vs_speed.png`` (Fig. 3.8), one line per wig
    (and speed / brush length), mean ± std over seeds, with the pain threshold."""
    from .scene import PAIN_THRESHOLD
    from .viz import PALETTE, new_figure, save_figure

    table = summarize(rows)
    written = []
    for x_key, other, fname, xlabel in (
        ("brush_length", "speed", "force_vs_brush_length.png", "normalized brush length b_l"),
        ("speed", "brush_length", "force_vs_speed.png", "brushing speed [m/s]"),
    ):
        fig, axes = new_figure(1, 1, width=6.0, height=4.2)
        ax = axes[0, 0]
        series = sorted({(e["R_over_P"], e["wig"], e[other]) for e in table})
        for i, (_, wig, o) in enumerate(series):
            es = sorted((e for e in table if e["wig"] == wig and e[other] == o), key=lambda e: e[x_key])
            label = f"{wig} ({other.replace('_', ' ')} {o:g})"
            ax.errorbar(
                [e[x_key] for e in es],
                [e["mean"] for e in es],
                yerr=[e["std"] for e in es],
                fmt="o-",
                capsize=3,
                color=PALETTE[i % len(PALETTE)],
                label=label,
            )
        ax.axhline(PAIN_THRESHOLD, color="k", ls="--", lw=1, label="pain threshold F_T")
        ax.set(
            xlabel=xlabel, ylabel="max brushing force [N]", title=f"max force vs {x_key.replace('_', ' ')}"
        )
        ax.legend(fontsize=7)
        path = Path(out) / fname
        save_figure(fig, path)
        written.append(path)
    return written
