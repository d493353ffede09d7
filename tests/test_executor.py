"""One executor seam (:mod:`hairbrush_env.executor`): local processes and Ray give the same results, failures are
reported per cell while the others finish, and a grid's results file is the same bit for bit on either."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import sys

import pytest

from hairbrush_env import stroke_study
from hairbrush_env.executor import CellLog, CellsFailed, ExecutorConfig, call_cell, ray_available, run_cells


def _ray_ships_this_module_by_value() -> None:
    """Ray workers import a cell's function by its module; this test module is not on their path (the package's
    own cell functions are), so Ray pickles it by value."""
    import ray.cloudpickle

    ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])


def _cell(x: int, fail_on: int | None = None) -> dict:
    """A cell whose value depends only on its own inputs (as every grid cell is seeded from its key)."""
    if x == fail_on:
        raise ValueError(f"bad cell {x}")
    return {"x": x, "y": x * x + 0.1}


def _cell_that_kills_its_worker(x: int) -> int:
    if x == 2:
        os._exit(3)  # the worker process dies, as under the OOM killer or a node going away
    return x


def _outcomes(executor: ExecutorConfig, fail_on: int | None = None) -> dict:
    cells = [(("c", x), (x, fail_on)) for x in range(6)]
    return {o.key: (o.value, o.error) for o in run_cells(_cell, cells, executor=executor, progress=False)}


def test_ray_is_installed_for_the_tests() -> None:
    assert ray_available()  # the dev extra includes ray, so the Ray tests below run wherever the suite runs


def test_config_checks() -> None:
    for bad in (0, -1, 1.5, True):
        with pytest.raises(ValueError, match="workers"):
            ExecutorConfig(workers=bad)
    with pytest.raises(ValueError, match="ray"):
        ExecutorConfig(ray=" ")
    with pytest.raises(ValueError, match="unique"):
        list(run_cells(_cell, [(1, (1,)), (1, (2,))], progress=False))


def test_call_cell_wraps_value_error_and_cost() -> None:
    ok = call_cell(_cell, "k", (3,))
    assert ok.ok and ok.value == {"x": 3, "y": 9.1} and ok.seconds >= 0.0 and ":" in ok.worker
    bad = call_cell(_cell, "k", (3, 3))
    assert not bad.ok and bad.error == "ValueError: bad cell 3" and "Traceback" in bad.traceback


def test_local_processes_give_what_this_process_gives_and_failures_do_not_stop_the_others() -> None:
    serial = _outcomes(ExecutorConfig(workers=1), fail_on=4)
    assert serial == _outcomes(ExecutorConfig(workers=2), fail_on=4)
    assert serial[("c", 4)] == (None, "ValueError: bad cell 4")
    assert all(serial[("c", x)][1] is None for x in (0, 1, 2, 3, 5))


def test_a_killed_local_worker_fails_only_its_own_cell_and_the_log_names_it(tmp_path) -> None:
    """A worker that dies breaks CPython's whole pool; the cells it took down with it run again, so only the cell
    that kills its worker fails, with its traceback-free error in cells.csv."""
    log = CellLog(tmp_path / "cells.csv", ExecutorConfig(workers=2))
    cells = [(x, (x,)) for x in range(5)]
    out = {}
    for o in run_cells(
        _cell_that_kills_its_worker, cells, executor=ExecutorConfig(workers=2), progress=False
    ):
        log.record(o)
        out[o.key] = o
    assert {o.key for o in log.failed} == {2} and "died" in out[2].error
    assert {k: o.value for k, o in out.items() if o.ok} == {0: 0, 1: 1, 3: 3, 4: 4}
    text = (tmp_path / "cells.csv").read_text()
    assert text.startswith("key,status,seconds") and text.count(",failed,") == 1 and "local ×2" in text
    assert "== cell 2" in (tmp_path / "cells_failed.txt").read_text()
    err = CellsFailed("cell(s)", log.failed)
    assert "cell 2:" in str(err) and "rerun" in str(err)


def _cell_returning_something_unpicklable(x: int):
    return (lambda: x) if x == 1 else x


def test_a_value_that_does_not_pickle_fails_its_cell_only() -> None:
    cells = [(x, (x,)) for x in range(3)]
    out = {o.key: o for o in run_cells(_cell_returning_something_unpicklable, cells, executor=ExecutorConfig(2),
                                        progress=False)}  # fmt: skip
    assert [k for k in sorted(out) if out[k].ok] == [0, 2] and "pickle" in out[1].error.lower()


def test_closing_the_stream_stops_the_local_workers() -> None:
    import time

    cells = [(x, (x,)) for x in range(4)]
    stream = run_cells(_sleeping_cell, cells, executor=ExecutorConfig(workers=2), progress=False)
    first = next(stream)
    t0 = time.perf_counter()
    stream.close()  # as when the caller is interrupted: running cells are terminated, not waited for
    assert first.ok and time.perf_counter() - t0 < 5.0


def test_a_killed_run_stops_its_local_workers(tmp_path) -> None:
    """``kill`` (SIGTERM) of a process running a grid on local workers stops the workers too, instead of leaving
    them to run their cells to the end."""
    import signal
    import subprocess
    import time

    (tmp_path / "grid.py").write_text(
        "import os, sys, time\n"
        "from hairbrush_env.executor import ExecutorConfig, run_cells\n"
        "def cell(x):\n"
        "    open(f'pid{x}', 'w').write(str(os.getpid()))\n"
        "    time.sleep(60)\n"
        "if __name__ == '__main__':\n"
        "    for _ in run_cells(cell, [(x, (x,)) for x in range(2)], executor=ExecutorConfig(workers=2),\n"
        "                       progress=False):\n"
        "        pass\n"
    )
    proc = subprocess.Popen([sys.executable, "grid.py"], cwd=tmp_path)
    pid_files = [tmp_path / f"pid{x}" for x in range(2)]
    deadline = time.monotonic() + 60
    while not all(f.exists() and f.read_text() for f in pid_files):
        assert time.monotonic() < deadline and proc.poll() is None, "the workers never started"
        time.sleep(0.1)
    workers = [int(f.read_text()) for f in pid_files]
    proc.send_signal(signal.SIGTERM)
    assert proc.wait(timeout=20) == 128 + signal.SIGTERM

    def alive(pid: int) -> bool:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return False
        return True

    deadline = time.monotonic() + 10
    while any(alive(p) for p in workers) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not any(alive(p) for p in workers)


def _sleeping_cell(x: int) -> int:
    import time

    time.sleep(0.0 if x == 0 else 30.0)
    return x


def _ray_gives_what_local_processes_give_and_retries_a_killed_worker() -> None:
    _ray_ships_this_module_by_value()
    local = _outcomes(ExecutorConfig(workers=2), fail_on=1)
    assert _outcomes(ExecutorConfig(workers=2, ray="auto"), fail_on=1) == local
    # Ray retries a cell whose worker died (RAY_MAX_RETRIES), then reports it; the other cells finish
    cells = [(x, (x,)) for x in range(4)]
    out = {o.key: o for o in run_cells(_cell_that_kills_its_worker, cells, executor=ExecutorConfig(2, "auto"),
                                        progress=False)}  # fmt: skip
    assert [k for k, o in sorted(out.items()) if o.ok] == [0, 1, 3] and out[3].value == 3
    assert not out[2].ok and out[2].error


def _a_stroke_grid_is_the_same_file_bit_for_bit_locally_and_on_ray(tmp_path) -> None:
    """The issue's check: the same inputs give the same results file, whichever executor ran the cells (each stroke
    is seeded from its own key, never from the order in which workers took the cells)."""
    grid = {"brush_lengths": [0.15, 0.3], "speeds": [0.2], "seeds": [0, 1], "progress": False}
    stroke_study.measure_strokes(["straight"], out=tmp_path / "local", **grid)
    stroke_study.measure_strokes(
        ["straight"], out=tmp_path / "ray", executor=ExecutorConfig(workers=2, ray="auto"), **grid
    )
    local = (tmp_path / "local" / "strokes.csv").read_bytes()
    assert local == (tmp_path / "ray" / "strokes.csv").read_bytes()
    assert local.count(b"\n") == 5  # header + 4 strokes
    cells = (tmp_path / "ray" / "cells.csv").read_text()
    assert cells.count(",ok,") == 4 and "ray auto ×2" in cells


def _rodpile_sweep_command_writes_the_same_sweep_on_ray_and_resumes(tmp_path) -> None:
    """``hairbrush rodpile sweep --ray auto``: the same sweep.json as local processes; piles are saved where the
    command runs, and a rerun reuses them instead of generating again."""
    from hairbrush_env.cli import main

    base = [
        "rodpile",
        "sweep",
        "--alphas",
        "10",
        "16",
        "--n-rods",
        "20",
        "20",
        "--container",
        "1.5",
        "--quiet",
    ]
    assert main([*base, "--out", str(tmp_path / "local"), "--workers", "2"]) == 0
    assert main([*base, "--out", str(tmp_path / "ray"), "--ray", "auto", "--workers", "2"]) == 0
    sweep = (tmp_path / "local" / "sweep.json").read_bytes()
    assert sweep == (tmp_path / "ray" / "sweep.json").read_bytes()
    assert len(list((tmp_path / "ray").glob("pile_alpha*.npz"))) == 2
    cells = (tmp_path / "ray" / "cells.csv").read_text()
    assert main([*base, "--out", str(tmp_path / "ray")]) == 0  # resume: both piles exist
    assert (tmp_path / "ray" / "cells.csv").read_text() == cells  # no cell ran again
    assert (tmp_path / "ray" / "sweep.json").read_bytes() == sweep


def test_ray_executor(tmp_path) -> None:
    """Every check that starts a local Ray instance, one after another in one test: two local instances started at
    once by two test workers on one machine crashed one of the workers (docs/cluster.md)."""
    _ray_gives_what_local_processes_give_and_retries_a_killed_worker()
    for name in ("strokes", "rodpile"):
        (tmp_path / name).mkdir()
    _a_stroke_grid_is_the_same_file_bit_for_bit_locally_and_on_ray(tmp_path / "strokes")
    _rodpile_sweep_command_writes_the_same_sweep_on_ray_and_resumes(tmp_path / "rodpile")


def test_bad_executor_flags_fail_before_anything_runs(capsys, monkeypatch) -> None:
    from hairbrush_env import executor
    from hairbrush_env.cli import main

    for argv in (
        ["strokes", "--workers", "0"],
        ["compare", "--ray", ""],
        ["compare", "--ray", "head-node"],
        ["rodpile", "sweep", "--workers", "-1"],
        ["strokes", "--brush-lengths", "0.3,0.3"],
    ):
        with pytest.raises(SystemExit) as exc:
            main(argv)
        assert exc.value.code == 2
    # an address nothing listens at is refused in seconds, before any cell runs (Ray itself retries for minutes)
    assert (
        main(["rodpile", "sweep", "--alphas", "10", "--n-rods", "20", "--ray", "127.0.0.1:1", "--quiet"]) == 2
    )
    assert "no Ray cluster answers" in capsys.readouterr().err
    monkeypatch.setattr(executor, "ray_available", lambda: False)
    with pytest.raises(SystemExit) as exc:
        main(["helix", "sweep", "--vary", "q=4,6", "--ray", "auto"])
    assert exc.value.code == 2 and "hairbrush-env[ray]" in capsys.readouterr().err
