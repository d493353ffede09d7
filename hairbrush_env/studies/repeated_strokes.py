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
from collections.abc import Callable
from typing import Any

from ..pass_through import PassThroughMonitor
from ..scene import BrushingSim

__all__ = ["plateau_stroke", "repeated_strokes"]


def repeated_strokes(
    sim: BrushingSim,
    *,
    seed: int = 0,
    brush_length: float = 1.0,
    n_strokes: int = 6,
    abort_force: float | None = None,
    monitor: bool = True,
    on_stroke: Callable[[dict[str, Any]], None] | None = None,
) -> list[dict[str, Any]]:
    """``n_strokes`` strokes from ``b_l = brush_length`` on the pre-brushed wig of ``seed``.

    Returns one row per stroke (row 0 is the state before brushing, with ``stroke = 0``): ``max_force`` [N],
    ``entwined`` and ``made`` (``Σ |Lk|``), ``entanglement`` (their sum), ``crossings``, ``min_hair_hair`` and
    ``min_hair_bristle`` (fractions of the sum of radii, over the stroke's physics steps), ``cpu_s`` (process CPU
    time of the stroke, monitor included), ``sim_s`` (simulated time), ``steps`` (physics steps), ``aborted``,
    ``diverged``. ``on_stroke`` is called with each row as it is made (progress, checkpointing).
    """
    if not (isinstance(n_strokes, int) and n_strokes >= 1):
        raise ValueError(f"n_strokes must be an integer >= 1, got {n_strokes!r}")
    sim.reset(seed)
    entwined, made = sim.entanglement_meter.breakdown(sim.data)
    rows = [
        dict(stroke=0, max_force=0.0, entwined=entwined, made=made, entanglement=entwined + made, crossings=0,
             min_hair_hair=math.nan, min_hair_bristle=math.nan, cpu_s=0.0, sim_s=0.0, steps=0, aborted=False,
             diverged=False)
    ]  # fmt: skip
    if on_stroke is not None:
        on_stroke(rows[0])
    for k in range(1, n_strokes + 1):
        mon = PassThroughMonitor(sim) if monitor else None
        steps0 = sim.n_steps
        t0 = time.process_time()
        res = sim.stroke(brush_length, abort_force=abort_force)
        cpu = time.process_time() - t0
        if mon is not None:
            mon.detach()
        entwined, made = sim.entanglement_meter.breakdown(sim.data)
        row = dict(
            stroke=k,
            max_force=res.max_force,
            entwined=entwined,
            made=made,
            entanglement=entwined + made,
            crossings=len(mon.crossings) if mon is not None else -1,
            min_hair_hair=mon.hair_hair_fraction if mon is not None else math.nan,
            min_hair_bristle=mon.hair_bristle_fraction if mon is not None else math.nan,
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


def plateau_stroke(max_forces: list[float], tolerance: float = 0.4) -> int | None:
    """First stroke (1-based) whose maximum differs from the previous one by less than ``tolerance`` (eq. 3.4)."""
    for k in range(1, len(max_forces)):
        if abs(max_forces[k] - max_forces[k - 1]) < tolerance:
            return k + 1
    return None
