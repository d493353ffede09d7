"""One executor for every parallel command: local processes by default, a Ray cluster on request.

The project's long jobs are grids of independent *cells* — an episode of a comparison grid, one stroke of a force
study, one point of a sweep, one rod pile. :func:`run_cells` runs a module-level function on every cell and yields
each :class:`CellOutcome` as it finishes, whichever executor ran it:

* ``ExecutorConfig(workers=1)``: in this process, one cell after another (no pickling; easiest to debug);
* ``ExecutorConfig(workers=N)``: ``N`` local worker processes (``spawn``: MuJoCo and numba hold threads, which
  ``fork`` would copy in an undefined state);
* ``ExecutorConfig(ray="auto" | ADDRESS)``: Ray tasks, one CPU each. ``"auto"`` connects to the cluster this machine
  belongs to (``ray start``) or, if there is none, starts a local Ray instance with ``workers`` CPUs; an address
  (``"10.0.0.5:6379"``, ``"ray://head:10001"``) connects to that cluster, where Ray runs one cell per CPU.

Outcomes arrive in completion order, which depends on scheduling; callers store each outcome under its key and write
their results files in key order, and every cell is seeded from its own key, so the same inputs give the same
results file whichever executor ran it. A cell that raises is reported as a failed outcome (key, error, traceback)
while the others go on. A worker process that dies (killed, out of memory) is survived: locally, the cells its
broken pool lost run again, then in a process each, so only a cell that kills its own worker fails; Ray retries
such a cell :data:`RAY_MAX_RETRIES` times.
:class:`CellLog` keeps the per-cell timing and errors beside the results (``cells.csv``).
"""

from __future__ import annotations

import math
import os
import re
import shutil
import socket
import tempfile
import time
import traceback
from collections.abc import Callable, Hashable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = [
    "CellLog",
    "CellOutcome",
    "CellsFailed",
    "ExecutorConfig",
    "ExecutorUnavailable",
    "cluster_address",
    "ray_available",
    "run_cells",
]

#: Ray retries a cell whose worker process died this many times (a cell that raises is not retried).
RAY_MAX_RETRIES = 2
#: Object store of a local Ray instance [bytes].
LOCAL_OBJECT_STORE = 256 * 1024**2


@dataclass(frozen=True)
class ExecutorConfig:
    """Where cells run.

    Parameters
    ----------
    workers : int
        Local worker processes (``1``: in this process). Under Ray, the CPUs of a local Ray instance that
        ``ray="auto"`` starts when no cluster is running; a cluster runs one cell per CPU it has.
    ray : str or None
        ``None``: local processes. ``"auto"``: the running Ray cluster, else a new local one. Anything else: the
        address of a Ray cluster (``ray.init(address=...)``).
    """

    workers: int = 1
    ray: str | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.workers, int) or isinstance(self.workers, bool) or self.workers < 1:
            raise ValueError(f"workers: must be a positive integer, got {self.workers!r}")
        if self.ray is not None and (not isinstance(self.ray, str) or not self.ray.strip()):
            raise ValueError(f"ray: must be 'auto' or a cluster address, got {self.ray!r}")

    @property
    def label(self) -> str:
        """Short description for logs and tables, e.g. ``"local ×2"`` or ``"ray auto ×2"``."""
        return f"local ×{self.workers}" if self.ray is None else f"ray {self.ray} ×{self.workers}"


@dataclass(frozen=True)
class CellOutcome:
    """What one cell produced: its value, or the error it raised, and what it cost."""

    key: Hashable
    value: Any = None
    error: str | None = None
    traceback: str | None = None
    seconds: float = math.nan  # wall time of the cell in its worker
    cpu_seconds: float = math.nan  # CPU time of the worker process during the cell
    worker: str = ""  # host:pid

    @property
    def ok(self) -> bool:
        return self.error is None


class CellsFailed(RuntimeError):
    """Some cells of a grid failed; the others finished and were written. A rerun retries the failed ones.

    ``describe`` turns a key into what the message shows (default: the key itself).
    """

    def __init__(
        self, what: str, failures: Sequence[CellOutcome], describe: Callable[[Hashable], str] = str
    ) -> None:
        self.failures = list(failures)
        lines = "\n".join(f"  cell {describe(o.key)}: {o.error}" for o in self.failures)
        head = f"{len(self.failures)} {what} failed (the others were written; a rerun retries these)"
        super().__init__(f"{head}:\n{lines}")


class ExecutorUnavailable(RuntimeError):
    """The requested executor cannot run (Ray not installed, no cluster at the address); nothing has run yet."""


def ray_available() -> bool:
    """Whether the optional ``ray`` extra is installed."""
    import importlib.util

    return importlib.util.find_spec("ray") is not None


def call_cell(fn: Callable[..., Any], key: Hashable, args: tuple) -> CellOutcome:
    """Run one cell and wrap its value or error (the function every executor runs in its workers)."""
    t0, c0 = time.perf_counter(), time.process_time()
    worker = f"{socket.gethostname()}:{os.getpid()}"
    try:
        value = fn(*args)
    except Exception as exc:  # a failed cell is reported, the grid goes on
        return CellOutcome(
            key,
            error=f"{type(exc).__name__}: {exc}",
            traceback=traceback.format_exc(),
            seconds=time.perf_counter() - t0,
            cpu_seconds=time.process_time() - c0,
            worker=worker,
        )
    return CellOutcome(
        key, value, seconds=time.perf_counter() - t0, cpu_seconds=time.process_time() - c0, worker=worker
    )


def run_cells(
    fn: Callable[..., Any],
    cells: Sequence[tuple[Hashable, tuple]],
    *,
    executor: ExecutorConfig | None = None,
    desc: str = "cells",
    unit: str = "cell",
    progress: bool = True,
    postfix: Callable[[CellOutcome], dict[str, Any]] | None = None,
    already_done: int = 0,
) -> Iterator[CellOutcome]:
    """Run ``fn(*args)`` for every ``(key, args)`` of ``cells``; yield each outcome as it finishes.

    Parameters
    ----------
    fn : callable
        A module-level function (picklable by reference) whose arguments and return value pickle.
    cells : sequence of (key, args)
        Keys must be unique and hashable.
    executor : ExecutorConfig, optional
        Default: this process.
    desc, unit, progress
        One tqdm bar over all cells.
    postfix : callable, optional
        Progress-bar postfix from each finished outcome.
    already_done : int
        Cells of the same grid finished before (a resumed run): the bar starts there.

    Yields
    ------
    CellOutcome
        In completion order. On ``KeyboardInterrupt`` (or the caller closing the generator) pending cells are
        cancelled and the workers stopped; outcomes already yielded are the caller's to keep.
    """
    from tqdm import tqdm

    executor = executor if executor is not None else ExecutorConfig()
    keys = [k for k, _ in cells]
    if len(set(keys)) != len(keys):
        raise ValueError("cells: keys must be unique")
    if not cells:  # nothing to run (e.g. a resumed grid): no pool, no Ray
        return
    bar = tqdm(
        total=len(cells) + already_done, initial=already_done, desc=desc, unit=unit, disable=not progress
    )
    outcomes: Iterator[CellOutcome] = iter(())
    try:
        if executor.ray is not None:
            outcomes = _run_ray(fn, cells, executor)
        elif executor.workers == 1 or len(cells) <= 1:
            outcomes = (call_cell(fn, k, a) for k, a in cells)
        else:
            outcomes = _run_local(fn, cells, executor.workers)
        for outcome in outcomes:
            if postfix is not None and outcome.ok:
                bar.set_postfix(postfix(outcome))
            bar.update(1)
            yield outcome
    finally:
        close = getattr(outcomes, "close", None)
        if close is not None:  # stop the executor's workers now, not when the generator is garbage-collected
            close()
        bar.close()


def _run_local(fn, cells, workers: int) -> Iterator[CellOutcome]:
    """Cells in ``workers`` spawned processes. A worker that dies breaks the whole pool (CPython fails every
    unfinished future), so unfinished cells are run again in a fresh pool; if that one breaks too, each remaining
    cell runs in a process of its own, so that only a cell that kills its own worker fails."""
    args = dict(cells)
    todo = [k for k, _ in cells]
    for _ in range(2):  # the pool, then once more for what a dead worker took down with it
        unfinished: list[Hashable] = []
        yield from _run_pool(fn, args, todo, workers, unfinished)
        if not unfinished:
            return
        todo = unfinished
    for key in todo:  # isolation: the remaining cells one process each
        lost: list[Hashable] = []
        yield from _run_pool(fn, args, [key], 1, lost)
        if lost:
            yield CellOutcome(
                key, error="worker process died while running this cell (killed, out of memory?)"
            )


def _run_pool(fn, args: dict, keys: list, workers: int, unfinished: list) -> Iterator[CellOutcome]:
    """One process pool over ``keys``; cells lost to a broken pool are appended to ``unfinished``."""
    import multiprocessing
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
    from concurrent.futures.process import BrokenProcessPool

    pool = ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn"))
    pending = {pool.submit(call_cell, fn, k, args[k]): k for k in keys}
    # A `kill` (SIGTERM) of this process would end it without the cleanup below and leave its workers running their
    # cells to the end; as SystemExit it runs the cleanup.
    restore = _exit_on_sigterm()
    try:
        while pending:
            done, _ = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                key = pending.pop(fut)
                try:
                    outcome = fut.result()
                except BrokenProcessPool:  # a worker died: this cell did not finish
                    unfinished.append(key)
                    continue
                except (
                    Exception
                ) as exc:  # e.g. a value that does not pickle: this cell fails, the others go on
                    outcome = CellOutcome(
                        key, error=f"{type(exc).__name__}: {exc}", traceback=traceback.format_exc()
                    )
                yield outcome
    finally:
        if pending:  # interrupted, or the caller stopped iterating: stop the cells still running
            for fut in pending:
                fut.cancel()
            # no public API before Python 3.14 (terminate_workers); running cells would otherwise block exit
            for proc in list(getattr(pool, "_processes", {}).values()):
                proc.terminate()
        pool.shutdown(wait=True, cancel_futures=True)
        restore()


def _exit_on_sigterm():
    """Turn SIGTERM into ``SystemExit(143)`` in the main thread; returns a function that restores the old handler."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return lambda: None

    def _exit(signum, frame):
        raise SystemExit(128 + signum)

    old = signal.signal(signal.SIGTERM, _exit)
    return lambda: signal.signal(signal.SIGTERM, old)


def _ray_init(executor: ExecutorConfig) -> tuple[bool, str | None]:
    """Connect to (or start) Ray. Returns whether this call connected (and so must shut down) and the private temp
    directory of a local instance it started (removed after the shutdown)."""
    try:
        import ray
    except ImportError as exc:
        raise ExecutorUnavailable(
            f"--ray {executor.ray}: Ray is not installed: pip install 'hairbrush-env[ray]'"
        ) from exc
    if ray.is_initialized():
        return False, None
    # Workers must render headless like this process (hairbrush_env picks EGL when no display is present).
    env_vars = {k: os.environ[k] for k in ("MUJOCO_GL", "PYOPENGL_PLATFORM") if k in os.environ}
    common = dict(
        include_dashboard=False,
        log_to_driver=False,
        configure_logging=True,
        logging_level="ERROR",
        runtime_env={"env_vars": env_vars} if env_vars else None,
    )
    if executor.ray == "auto":
        try:
            ray.init(address="auto", **common)
        except ConnectionError:  # no running cluster: a local one with the requested CPUs
            # in a private temp dir, so that no other command's --ray auto joins this command's instance (and
            # loses it when this command ends)
            private = tempfile.mkdtemp(prefix="hb-ray-")
            # cells pass small values: a small object store (Ray's default takes 30 % of the RAM per instance)
            ray.init(
                num_cpus=executor.workers, object_store_memory=LOCAL_OBJECT_STORE, _temp_dir=private, **common
            )
            return True, private
    else:
        _probe(executor.ray)  # ray.init retries an unreachable address for minutes
        try:
            ray.init(address=executor.ray, **common)
        except (ConnectionError, ValueError, RuntimeError) as exc:
            raise ExecutorUnavailable(
                f"--ray {executor.ray}: cannot connect to a Ray cluster there: {exc}"
            ) from exc
    return True, None


def cluster_address(text: str) -> tuple[str, int] | None:
    """``(host, port)`` of a Ray cluster address ``HOST:PORT`` or ``ray://HOST:PORT``; ``None`` if it is not one."""
    host, sep, port = text.split("://", 1)[-1].rpartition(":")
    return (host, int(port)) if host and sep and port.isdigit() else None


def _probe(address: str, timeout: float = 5.0) -> None:
    """Refuse a cluster address nothing listens at, in seconds instead of Ray's minutes of retries."""
    parsed = cluster_address(address)
    if parsed is None:
        raise ExecutorUnavailable(f"--ray {address}: expected 'auto' or HOST:PORT (or ray://HOST:PORT)")
    try:
        socket.create_connection(parsed, timeout=timeout).close()
    except OSError as exc:
        raise ExecutorUnavailable(f"--ray {address}: no Ray cluster answers there ({exc})") from exc


def _run_ray(fn, cells, executor: ExecutorConfig) -> Iterator[CellOutcome]:
    import ray

    started, private = _ray_init(executor)
    remote = ray.remote(num_cpus=1, max_retries=RAY_MAX_RETRIES)(call_cell)
    fn_ref = ray.put(fn)
    pending = {remote.remote(fn_ref, k, a): k for k, a in cells}
    try:
        while pending:
            done, _ = ray.wait(list(pending), num_returns=1)
            for ref in done:
                key = pending.pop(ref)
                try:
                    yield ray.get(ref)
                except ray.exceptions.RayError as exc:  # the worker died more often than Ray retries
                    text = re.sub(r"\x1b\[[0-9;]*m", "", str(exc)).strip()  # Ray colours its messages
                    yield CellOutcome(key, error=f"{type(exc).__name__}: {text}")
    finally:
        for ref in pending:
            ray.cancel(ref, force=True)
        if started:
            ray.shutdown()
        if private is not None:
            shutil.rmtree(private, ignore_errors=True)


class CellLog:
    """Per-cell timing and errors of a grid, ``cells.csv`` beside its results, rewritten atomically after each cell.

    The results file holds what the cells computed (the same whichever executor ran them); this log holds how they
    ran: status, error, wall and CPU seconds, worker. A rerun updates the rows of the cells it runs again. The
    tracebacks of the cells that failed in this run go to ``cells_failed.txt``.
    """

    COLUMNS = ("key", "status", "seconds", "cpu_seconds", "worker", "executor", "error")

    def __init__(self, path: str | Path | None, executor: ExecutorConfig | None = None) -> None:
        from .io import read_csv_rows

        self.path = Path(path) if path is not None else None  # None: failures kept in memory only
        self.executor = (executor or ExecutorConfig()).label
        rows = read_csv_rows(self.path) if self.path is not None and self.path.exists() else []
        self._rows: dict[str, dict[str, Any]] = {r["key"]: r for r in rows}
        self.failed: list[CellOutcome] = []

    def record(self, outcome: CellOutcome) -> None:
        from .io import write_csv_rows, write_text

        key = (
            "/".join(str(part) for part in outcome.key)
            if isinstance(outcome.key, tuple)
            else str(outcome.key)
        )
        self._rows[key] = {
            "key": key,
            "status": "ok" if outcome.ok else "failed",
            "seconds": f"{outcome.seconds:.3f}",
            "cpu_seconds": f"{outcome.cpu_seconds:.3f}",
            "worker": outcome.worker,
            "executor": self.executor,
            "error": outcome.error or "",
        }
        if not outcome.ok:
            self.failed.append(outcome)
        if self.path is None:
            return
        if not outcome.ok:
            # the tracebacks of this run's failed cells, beside the log (workers' own output is not shown)
            write_text(
                self.path.with_name(self.path.stem + "_failed.txt"),
                "".join(f"== cell {o.key}: {o.error}\n{o.traceback or ''}\n" for o in self.failed),
            )
        write_csv_rows(self.path, list(self._rows.values()), list(self.COLUMNS))
