"""Parallel parameter sweeps with a per-point cache: interrupt at any time, rerun to resume.

Every point is a JSON-serializable ``dict``; its cache file is ``<cache_dir>/<sha1 of the canonical JSON>.json``
holding ``{"point": ..., "result": ...}``, written atomically (:func:`hairbrush_env.io.write_json`), so a killed run
leaves either a complete file or none. A rerun loads the cached points and only computes the missing ones; a
corrupt or foreign cache file (hash collision, edited by hand) is recomputed rather than trusted.

Points run where :mod:`hairbrush_env.executor` puts them (this process, local worker processes or Ray); each
finished point is cached as soon as it arrives, in the parent, and one tqdm bar shows progress. On
``KeyboardInterrupt`` pending points are cancelled, the finished ones stay cached, and the interrupt is re-raised.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from ..executor import CellLog, CellsFailed, ExecutorConfig, run_cells

__all__ = ["cache_path", "load_cached", "point_key", "run_sweep"]


def point_key(point: dict[str, Any]) -> str:
    """Stable hash of a point (sorted-key JSON), the name of its cache file."""
    text = json.dumps(point, sort_keys=True, separators=(",", ":"), default=float)
    return hashlib.sha1(text.encode()).hexdigest()[:16]


def cache_path(cache_dir: str | Path, point: dict[str, Any]) -> Path:
    """Cache file of ``point`` in ``cache_dir``."""
    return Path(cache_dir) / f"{point_key(point)}.json"


def load_cached(cache_dir: str | Path, point: dict[str, Any]) -> dict[str, Any] | None:
    """The cached result of ``point``, or ``None`` if absent, unreadable or belonging to another point."""
    path = cache_path(cache_dir, point)
    try:
        blob = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    canonical = json.loads(json.dumps(point, sort_keys=True, default=float))
    if not isinstance(blob, dict) or blob.get("point") != canonical or "result" not in blob:
        return None
    return blob["result"]


def run_sweep(
    fn: Callable[[dict[str, Any]], Any],
    points: Sequence[dict[str, Any]],
    cache_dir: str | Path,
    *,
    executor: ExecutorConfig | None = None,
    desc: str = "sweep",
    progress: bool = True,
) -> list[Any]:
    """Evaluate ``fn(point)`` for every point, in parallel, caching each result; returns results in point order.

    Parameters
    ----------
    fn : callable
        A module-level (picklable) function returning a JSON-serializable value.
    points : sequence of dict
        JSON-serializable points (duplicates are computed once).
    cache_dir : path
        Directory of the per-point cache files (created if needed) and of ``cells.csv`` (per-point timing and
        errors, :class:`~hairbrush_env.executor.CellLog`).
    executor : ExecutorConfig, optional
        Where points run (default: this process; :mod:`hairbrush_env.executor`: local processes or Ray).
    desc : str
        Progress-bar label.
    progress : bool
        Show a tqdm progress bar.

    Returns
    -------
    list
        ``fn(point)`` (or its cached value) for every point, in order. A point that raises is reported while the
        others finish and are cached; then
        :class:`~hairbrush_env.executor.CellsFailed` names it.
    """
    from ..io import write_json

    cache = Path(cache_dir)
    cache.mkdir(parents=True, exist_ok=True)
    keys = [point_key(p) for p in points]
    results: dict[str, Any] = {}
    todo: dict[str, dict[str, Any]] = {}
    for key, point in zip(keys, points, strict=True):
        if key in results or key in todo:
            continue
        cached = load_cached(cache, point)
        if cached is not None:
            results[key] = cached
        else:
            todo[key] = point

    log = CellLog(cache / "cells.csv", executor)
    cells = [(key, (point,)) for key, point in todo.items()]
    for outcome in run_cells(
        fn, cells, executor=executor, desc=desc, unit="pt", progress=progress, already_done=len(results)
    ):
        log.record(outcome)
        if outcome.ok:
            key = outcome.key
            canonical = json.loads(json.dumps(todo[key], sort_keys=True, default=float))
            write_json(cache / f"{key}.json", {"point": canonical, "result": outcome.value})
            results[key] = json.loads(
                json.dumps(outcome.value, default=_jsonable)
            )  # same form as a cache hit
    if log.failed:
        raise CellsFailed("point(s)", log.failed, describe=lambda key: json.dumps(todo[key], sort_keys=True))
    return [results[k] for k in keys]


def _jsonable(o: Any) -> Any:
    if hasattr(o, "tolist"):
        return o.tolist()
    raise TypeError(f"not JSON serializable: {type(o).__name__}")
