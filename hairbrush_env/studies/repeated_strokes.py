"""Repeated strokes at one brush length: does brushing detangle? (thesis Fig. 3.6(i), eq. 3.4).

The thesis brushes "the same hair at a repeated height for 6 iterations" and sees the maximum force fall from the
first stroke and plateau as entanglements are removed. :func:`repeated_strokes` does the same on
:class:`~hairbrush_env.scene.BrushingSim`: from the pre-brushed wig of ``seed``, ``n_strokes`` pull-through strokes
(no pain abort unless ``abort_force`` is given), recording per stroke the maximum load-cell force, the entanglement
(entwined pairs and link made between other strands, :meth:`hairbrush_env.hair.Entanglement.breakdown`), the
pass-through check of every physics step (:class:`~hairbrush_env.pass_through.PassThroughMonitor`) and the CPU
time.
"""

from __future__ import annotations

import math
import time
from collections import Counter
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..io import read_csv_rows, write_csv_rows, write_text
from ..pass_through import PassThroughMonitor
from ..scene import MAX_STROKE_Y, BrushingSim

if TYPE_CHECKING:
    from ..hair import WigConfig

__all__ = [
    "COLUMNS",
    "plateau_stroke",
    "plot_repeated",
    "repeated_strokes",
    "run_repeated",
    "summary_markdown",
]

COLUMNS = [
    "wig", "seed", "brush_length", "stroke", "max_force", "entwined", "made", "entanglement", "crossings",
    "min_hair_hair", "min_hair_bristle", "min_self", "cpu_s", "sim_s", "steps", "aborted", "diverged",
    "still_entwined", "pull_max_force",
]  # fmt: skip


def repeated_strokes(
    sim: BrushingSim,
    *,
    seed: int = 0,
    brush_length: float = 1.0,
    n_strokes: int = 6,
    abort_force: float | None = None,
    monitor: bool = True,
    on_stroke: Callable[[dict[str, Any]], None] | None = None,
    y: float | Sequence[float] = 0.0,
) -> list[dict[str, Any]]:
    """``n_strokes`` strokes from ``b_l = brush_length`` on the pre-brushed wig of ``seed``.

    Returns one row per stroke (row 0 is the state before brushing, with ``stroke = 0``): ``max_force`` [N],
    ``entwined`` and ``made`` (``Σ |Lk|``), ``entanglement`` (their sum), ``crossings``, ``min_hair_hair`` and
    ``min_hair_bristle`` (fractions of the sum of radii, over the stroke's physics steps), ``min_self`` (the smallest
    distance between two non-neighbouring segments of one strand, as a fraction of its diameter: below 0.5 a strand
    passes through itself, which it can without ``WigConfig.self_collision``), ``cpu_s`` (process CPU
    time of the stroke, monitor included), ``sim_s`` (simulated time), ``steps`` (physics steps), ``aborted``,
    ``diverged``, ``still_entwined`` (entwined pairs still wound in their built-in sense,
    :meth:`~hairbrush_env.hair.Entanglement.still_entwined`). ``on_stroke`` is called with each row as it is made
    (progress, checkpointing). ``y``: the brush's sideways offset [m] (``BrushingSim.stroke(y=...)``), or a
    sequence that stroke ``k`` cycles through (``y[(k - 1) % len(y)]``).
    """
    if not (isinstance(n_strokes, int) and n_strokes >= 1):
        raise ValueError(f"n_strokes must be an integer >= 1, got {n_strokes!r}")
    ys = [float(y)] if isinstance(y, (int, float)) else [float(v) for v in y]
    if not ys or any(not abs(v) <= MAX_STROKE_Y for v in ys):
        raise ValueError(
            f"y must be a number or a non-empty sequence of numbers within ±{MAX_STROKE_Y}, got {y!r}"
        )
    sim.reset(seed)
    rows = [
        dict(stroke=0, max_force=0.0, pull_max_force=0.0, **_entanglement_columns(sim), crossings=0,
             min_hair_hair=math.nan, min_hair_bristle=math.nan, min_self=math.nan, cpu_s=0.0, sim_s=0.0, steps=0,
             aborted=False, diverged=False)
    ]  # fmt: skip
    if on_stroke is not None:
        on_stroke(rows[0])
    for k in range(1, n_strokes + 1):
        mon = PassThroughMonitor(sim) if monitor else None
        steps0 = sim.n_steps
        t0 = time.process_time()
        res = sim.stroke(brush_length, abort_force=abort_force, y=ys[(k - 1) % len(ys)])
        cpu = time.process_time() - t0
        if mon is not None:
            mon.detach()
        row = dict(
            stroke=k,
            max_force=res.max_force,
            pull_max_force=res.pull_max_force,
            **_entanglement_columns(sim),
            crossings=len(mon.crossings) if mon is not None else -1,
            min_hair_hair=mon.hair_hair_fraction if mon is not None else math.nan,
            min_hair_bristle=mon.hair_bristle_fraction if mon is not None else math.nan,
            min_self=mon.hair_self_fraction if mon is not None else math.nan,
            cpu_s=cpu,
            sim_s=res.sim_time,
            steps=sim.n_steps - steps0,
            aborted=res.aborted,
            diverged=res.diverged,
        )
        rows.append(row)
        if on_stroke is not None:
            on_stroke(row)
        if res.diverged:
            break
    return rows


def _entanglement_columns(sim: BrushingSim) -> dict[str, Any]:
    """``entwined``, ``made``, ``entanglement`` and ``still_entwined`` of the current state, from one link matrix."""
    meter = sim.entanglement_meter
    link = meter.link_matrix(sim.data)
    entwined, made = meter.breakdown(sim.data, link=link)
    return dict(entwined=entwined, made=made, entanglement=entwined + made,
                still_entwined=meter.still_entwined(sim.data, link=link))  # fmt: skip


def plateau_stroke(max_forces: list[float], tolerance: float = 0.4) -> int | None:
    """First stroke (1-based) whose maximum differs from the previous one by less than ``tolerance`` (eq. 3.4)."""
    for k in range(1, len(max_forces)):
        if abs(max_forces[k] - max_forces[k - 1]) < tolerance:
            return k + 1
    return None


def _read(path: Path) -> list[dict[str, Any]]:
    rows = read_csv_rows(
        path,
        floats=("brush_length", "max_force", "entwined", "made", "entanglement", "min_hair_hair",
                "min_hair_bristle", "min_self", "cpu_s", "sim_s"),
        ints=("seed", "stroke", "crossings", "steps", "still_entwined"),
        bools=("aborted", "diverged"),
        fallbacks={"pull_max_force": "max_force"},  # absent before v10 read part of a pull
    )  # fmt: skip
    for row in rows:
        row.setdefault("min_self", math.nan)  # written before the column existed
    return rows


def run_repeated(
    wigs: Sequence[str | WigConfig],
    *,
    seeds: Sequence[int] = (0, 1, 2),
    n_strokes: int = 6,
    brush_length: float = 1.0,
    out: str | Path | None = None,
    progress: bool = True,
    physics: str = "v0",
) -> list[dict[str, Any]]:
    """Fig. 3.6(i) for every ``(wig, seed)``: :func:`repeated_strokes` rows with ``wig``, ``seed`` and
    ``brush_length`` added (columns :data:`COLUMNS`). Wigs are preset names or
    :class:`~hairbrush_env.hair.WigConfig` (keyed by name), brushed under the physics version ``physics``
    (:mod:`hairbrush_env.physics`; recorded in ``out/physics.json``).

    With ``out``, ``repeat.csv`` is rewritten atomically after every stroke; a rerun keeps the series that were
    complete and re-runs the others from their pre-brushed wig. ``summary.md`` and ``repeat.png`` follow at the end.
    """
    from tqdm import tqdm

    from ..physics import claim_physics, get_physics

    if not wigs:
        raise ValueError("wigs: need at least one wig")
    version = get_physics(physics)
    try:
        configs = {c.name: c for c in map(version.wig, wigs)}
    except ValueError as exc:
        raise ValueError(f"wigs: {exc}") from exc
    names = list(configs)
    if not (isinstance(n_strokes, int) and n_strokes >= 1):
        raise ValueError(f"strokes: must be an integer >= 1, got {n_strokes!r}")
    if not (math.isfinite(brush_length) and 0.0 < brush_length <= 1.0):
        raise ValueError(f"brush_length: must be in (0, 1], got {brush_length!r}")
    csv_path = Path(out) / "repeat.csv" if out is not None else None
    rows = _read(csv_path) if csv_path is not None and csv_path.exists() else []
    if out is not None:
        claim_physics(out, version.name, resuming=bool(rows))
    counts = Counter((r["wig"], r["seed"]) for r in rows if r["brush_length"] == brush_length)
    complete = {key for key, n in counts.items() if n == n_strokes + 1}
    rows = [r for r in rows if (r["wig"], r["seed"]) in complete or r["brush_length"] != brush_length]
    todo = [(w, int(s)) for w in names for s in seeds if (w, int(s)) not in complete]
    bar = tqdm(total=len(todo) * n_strokes, desc="strokes", unit="stroke", disable=not progress)
    try:
        for wig in dict.fromkeys(w for w, _ in todo):
            with BrushingSim(version.scene_config(configs[wig])) as sim:
                for _, seed in (t for t in todo if t[0] == wig):

                    def record(row: dict[str, Any], wig: str = wig, seed: int = seed) -> None:
                        rows.append(dict(row, wig=wig, seed=seed, brush_length=brush_length))
                        if csv_path is not None:
                            write_csv_rows(csv_path, rows, COLUMNS)
                        if row["stroke"] > 0:
                            bar.set_postfix(wig=wig, seed=seed, f_max=f"{row['max_force']:.1f}")
                            bar.update(1)

                    repeated_strokes(
                        sim, seed=seed, brush_length=brush_length, n_strokes=n_strokes, on_stroke=record
                    )
    finally:
        bar.close()
    rows.sort(key=lambda r: (names.index(r["wig"]) if r["wig"] in names else -1, r["seed"], r["stroke"]))
    if out is not None:
        write_csv_rows(csv_path, rows, COLUMNS)
        write_text(Path(out) / "summary.md", summary_markdown(rows))
        plot_repeated(rows, Path(out) / "repeat.png")
    return rows


def _series(rows: Sequence[dict[str, Any]]) -> dict[tuple[str, int], list[dict[str, Any]]]:
    out: dict[tuple[str, int], list[dict[str, Any]]] = {}
    for r in rows:
        out.setdefault((r["wig"], r["seed"]), []).append(r)
    return {k: sorted(v, key=lambda r: r["stroke"]) for k, v in out.items()}


def summary_markdown(rows: Sequence[dict[str, Any]]) -> str:
    """One line per ``(wig, seed)``: forces per stroke, the eq. 3.4 plateau, entanglement left, pass-through
    (between strands: crossings and the smallest hair–hair distance / Σr; within a strand: ``min_self`` / 2r)."""
    lines = [
        "| wig | seed | b_l | F_max per stroke [N] | plateau (eq. 3.4) | Σ|Lk| start | left after each stroke "
        "| entwined pairs (start → end) | crossings | min hair–hair | min self |",
        "|---|---:|---:|---|---:|---:|---|---:|---:|---:|---:|",
    ]
    for (wig, seed), rs in _series(rows).items():
        e0 = rs[0]["entanglement"]
        forces = [r["max_force"] for r in rs[1:]]
        plateau = plateau_stroke(forces)
        hh = min((r["min_hair_hair"] for r in rs[1:]), default=math.nan)
        own = min((r.get("min_self", math.nan) for r in rs[1:]), default=math.nan)
        left = " ".join(f"{r['entanglement'] / max(e0, 1e-9):.2f}" for r in rs[1:])
        lines.append(
            f"| {wig} | {seed} | {rs[0]['brush_length']:.2f} | {' '.join(f'{f:.1f}' for f in forces)} | "
            f"{plateau if plateau is not None else '–'} | {e0:.1f} | "
            f"{left} | {rs[0].get('still_entwined', '?')} → {rs[-1].get('still_entwined', '?')} | "
            f"{sum(r['crossings'] for r in rs[1:])} | {hh:.2f} | {own:.2f} |"
        )
    return "\n".join(lines) + "\n"


def plot_repeated(rows: Sequence[dict[str, Any]], path: str | Path) -> Path:
    """Fig. 3.6(i): maximum force and the fraction of the entanglement left per stroke, mean ± std over seeds."""
    from ..scene import PAIN_THRESHOLD
    from ..viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(2, 1, width=10.0, height=4.0)
    by_wig: dict[str, list[list[dict[str, Any]]]] = {}
    for (wig, _), rs in _series(rows).items():
        by_wig.setdefault(wig, []).append(rs)
    for i, (wig, series) in enumerate(by_wig.items()):
        n = min(len(rs) for rs in series)
        k = np.arange(1, n)
        force = np.array([[r["max_force"] for r in rs[1:n]] for rs in series])
        left = np.array(
            [[r["entanglement"] / max(rs[0]["entanglement"], 1e-9) for r in rs[:n]] for rs in series]
        )
        c = PALETTE[i % len(PALETTE)]
        label = f"{wig} ({len(series)} seeds)"
        axes[0, 0].errorbar(k, force.mean(0), yerr=force.std(0), fmt="o-", capsize=3, color=c, label=label)
        axes[0, 1].errorbar(
            np.arange(n), left.mean(0), yerr=left.std(0), fmt="o-", capsize=3, color=c, label=label
        )
    axes[0, 0].axhline(PAIN_THRESHOLD, color="k", ls="--", lw=1, label="pain threshold F_T")
    axes[0, 0].set(xlabel="stroke", ylabel="max brushing force [N]", title="force per stroke (Fig. 3.6(i))")
    axes[0, 1].axhline(0.3, color="k", ls=":", lw=1, label="30 % left")
    axes[0, 1].set(xlabel="stroke", ylabel="entanglement left (Σ|Lk| / start)", ylim=(0, None),
                   title="entanglement per stroke")  # fmt: skip
    for ax in axes[0]:
        ax.legend(fontsize=7)
    save_figure(fig, path)
    return Path(path)
