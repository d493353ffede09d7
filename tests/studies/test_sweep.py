"""Parallel sweep runner: per-point cache, resume after an interrupt, no recomputation."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from hairbrush_env.executor import CellsFailed, ExecutorConfig
from hairbrush_env.studies.sweep import cache_path, load_cached, point_key, run_sweep


def _square(point):
    """Top-level (picklable) worker that also leaves a trace of every evaluation."""
    stop = Path(point["trace"]).parent / "STOP"
    if stop.exists() and int(stop.read_text()) == point["x"]:
        raise KeyboardInterrupt  # simulates Ctrl-C while this point runs
    if point["x"] < 0:
        raise ValueError(f"x must not be negative, got {point['x']}")
    trace = Path(point["trace"]) / f"{point['x']}.{os.getpid()}.{os.urandom(4).hex()}"
    trace.write_text("")
    return {"y": point["x"] ** 2}


def _evaluations(trace: Path) -> list[int]:
    return sorted(int(p.name.split(".")[0]) for p in trace.iterdir())


def test_point_key_is_order_independent():
    assert point_key({"a": 1, "b": 2.0}) == point_key({"b": 2.0, "a": 1})
    assert point_key({"a": 1}) != point_key({"a": 2})


@pytest.mark.parametrize("workers", [1, 2])
def test_results_in_order_and_cached(tmp_path, workers):
    trace = tmp_path / "trace"
    trace.mkdir()
    points = [{"x": x, "trace": str(trace)} for x in (3, 1, 2, 1)]  # a duplicate is computed once
    res = run_sweep(
        _square, points, tmp_path / "cache", executor=ExecutorConfig(workers=workers), progress=False
    )
    assert [r["y"] for r in res] == [9, 1, 4, 1]
    assert _evaluations(trace) == [1, 2, 3]
    blob = json.loads(cache_path(tmp_path / "cache", points[0]).read_text())
    assert blob["result"] == {"y": 9} and blob["point"]["x"] == 3
    # a second run only reads the cache
    res2 = run_sweep(
        _square, points, tmp_path / "cache", executor=ExecutorConfig(workers=workers), progress=False
    )
    assert res2 == res and _evaluations(trace) == [1, 2, 3]


def test_resume_after_interrupt_keeps_finished_points(tmp_path):
    trace = tmp_path / "trace"
    trace.mkdir()
    (tmp_path / "STOP").write_text("3")
    points = [{"x": x, "trace": str(trace)} for x in (1, 2, 3, 4)]
    with pytest.raises(KeyboardInterrupt):
        run_sweep(_square, points, tmp_path / "cache", executor=ExecutorConfig(workers=1), progress=False)
    assert [load_cached(tmp_path / "cache", p) for p in points] == [{"y": 1}, {"y": 4}, None, None]
    assert not list((tmp_path / "cache").glob(".*"))  # no half-written temporary files
    assert _evaluations(trace) == [1, 2]
    (tmp_path / "STOP").unlink()
    res = run_sweep(_square, points, tmp_path / "cache", executor=ExecutorConfig(workers=2), progress=False)
    assert [r["y"] for r in res] == [1, 4, 9, 16]
    assert _evaluations(trace) == [1, 2, 3, 4]  # 1 and 2 were not recomputed


def test_corrupt_cache_is_recomputed(tmp_path):
    trace = tmp_path / "trace"
    trace.mkdir()
    p = {"x": 5, "trace": str(trace)}
    path = cache_path(tmp_path / "cache", p)
    path.parent.mkdir(parents=True)
    path.write_text("{not json")
    assert run_sweep(
        _square, [p], tmp_path / "cache", executor=ExecutorConfig(workers=1), progress=False
    ) == [{"y": 25}]
    assert _evaluations(trace) == [5]


def test_a_failing_point_is_reported_after_the_others_are_cached(tmp_path):
    trace = tmp_path / "trace"
    trace.mkdir()
    points = [{"x": x, "trace": str(trace)} for x in (1, -1, 3)]  # _square rejects negative x
    with pytest.raises(CellsFailed, match="1 point") as exc:
        run_sweep(_square, points, tmp_path / "cache", executor=ExecutorConfig(workers=2), progress=False)
    assert "negative" in exc.value.failures[0].error
    assert [load_cached(tmp_path / "cache", p) for p in points] == [{"y": 1}, None, {"y": 9}]
    assert ",failed," in (tmp_path / "cache" / "cells.csv").read_text()
