"""Checkpoints a stopped training run resumes from (issue #12).

A run directory holds ``checkpoint/step-<N>/`` (the newest complete one named by ``checkpoint/latest``):

- ``model.zip`` — SB3's save: the policy and value networks, *their optimizers*, the step and update counters
  (``num_timesteps``, ``_n_updates``, ``_episode_num``) and the action space's RNG;
- ``replay_buffer.pkl`` — the replay buffer of off-policy agents (SAC); PPO's rollout buffer is not kept (a resumed
  PPO run starts a new rollout, losing at most ``n_steps`` environment steps per worker);
- ``rng.pt`` — the global torch / numpy / ``random`` generator states;
- ``state.json`` — the step count, the wall-clock time of the save and the run's own counters.

A checkpoint directory is written under a temporary name and renamed, and ``latest`` is replaced atomically, so a
run killed at any moment leaves the previous checkpoint intact. Logs written after the checkpoint (the episodes and
steps whose experience died with the process) are cut on resume by :func:`truncate_logs`, so every log continues
exactly where the model does. Episodes running at the interrupt are lost; the resumed run starts new ones.
"""

from __future__ import annotations

import csv
import io
import json
import os
import random
import shutil
import time
from pathlib import Path
from typing import Any

import numpy as np

from hairbrush_env.io import write_text

CHECKPOINT_DIR = "checkpoint"
LATEST = "latest"


def save_checkpoint(model, out: str | Path, **counters: Any) -> Path:
    """Write a checkpoint of ``model`` (and the global RNGs) into ``out/checkpoint``; returns its directory."""
    import torch

    root = Path(out) / CHECKPOINT_DIR
    root.mkdir(parents=True, exist_ok=True)
    name = f"step-{int(model.num_timesteps):09d}"
    tmp = root / f".{name}.tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir()
    model.save(tmp / "model.zip")
    if getattr(model, "replay_buffer", None) is not None:
        model.save_replay_buffer(tmp / "replay_buffer.pkl")
    torch.save(
        {
            "torch": torch.get_rng_state(),
            "numpy": np.random.get_state(),  # noqa: NPY002 (SB3 seeds the global generator)
            "random": random.getstate(),
        },
        tmp / "rng.pt",
    )
    state = {"num_timesteps": int(model.num_timesteps), "wall_time": time.time(), **counters}
    (tmp / "state.json").write_text(json.dumps(state, indent=2) + "\n")
    final = root / name
    shutil.rmtree(final, ignore_errors=True)
    os.replace(tmp, final)
    write_text(root / LATEST, name + "\n")
    for old in root.glob("step-*"):
        if old != final:
            shutil.rmtree(old, ignore_errors=True)
    return final


def latest_checkpoint(out: str | Path) -> Path | None:
    """The newest complete checkpoint directory of run ``out`` (None if it has none)."""
    marker = Path(out) / CHECKPOINT_DIR / LATEST
    if not marker.exists():
        return None
    path = marker.parent / marker.read_text().strip()
    return path if (path / "state.json").exists() else None


def checkpoint_state(path: str | Path) -> dict[str, Any]:
    return json.loads((Path(path) / "state.json").read_text())


def load_checkpoint(path: str | Path, algo_cls, env):
    """The model of checkpoint ``path`` on ``env``, with its replay buffer and the global RNG states restored."""
    import torch

    path = Path(path)
    model = algo_cls.load(path / "model.zip", env=env, device="cpu")
    if (path / "replay_buffer.pkl").exists():
        model.load_replay_buffer(path / "replay_buffer.pkl")
    rng = torch.load(path / "rng.pt", weights_only=False)
    torch.set_rng_state(rng["torch"])
    np.random.set_state(rng["numpy"])  # noqa: NPY002
    random.setstate(rng["random"])
    # The saved last observation belongs to episodes that died with the old process: None makes SB3 reset the new
    # workers when learning resumes.
    model._last_obs = None
    model._last_original_obs = None
    return model


def truncate_logs(out: str | Path, num_timesteps: int, wall_time: float) -> None:
    """Cut every log of run ``out`` back to a checkpoint taken at ``num_timesteps`` (and ``wall_time``)."""
    out = Path(out)
    _filter_csv(out / "progress.csv", lambda r: _num(r.get("time/total_timesteps")) <= num_timesteps)
    _filter_csv(out / "steps.csv", lambda r: _num(r.get("timesteps")) <= num_timesteps)
    _filter_csv(out / "eval" / "held_out.csv", lambda r: _num(r.get("timesteps")) <= num_timesteps)
    for mon in sorted((out / "monitor").glob("*.monitor.csv")):
        lines = mon.read_text().splitlines(keepends=True)
        if not lines:
            continue
        t_start = float(json.loads(lines[0].lstrip("#"))["t_start"])
        _filter_csv(mon, lambda r, t0=t_start: t0 + _num(r.get("t")) <= wall_time, preamble=1)


def _num(value: Any) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        return -np.inf  # rows without the column (e.g. SB3's first dump) are kept


def _filter_csv(path: Path, keep, preamble: int = 0) -> None:
    """Rewrite CSV ``path`` (atomically) with the rows ``keep(row)`` accepts; ``preamble`` lines pass through."""
    if not path.exists():
        return
    lines = path.read_text().splitlines(keepends=True)
    head, body = lines[:preamble], lines[preamble:]
    if not body:
        return
    reader = csv.DictReader(io.StringIO("".join(body)))
    fields = reader.fieldnames or []
    buf = io.StringIO()
    buf.write("".join(head))
    writer = csv.DictWriter(buf, fieldnames=fields, lineterminator="\n")
    writer.writeheader()
    for row in reader:
        if keep(row):
            writer.writerow(row)
    write_text(path, buf.getvalue())


def appending_csv_logger(out: str | Path, tensorboard: bool = False):
    """SB3's logger writing ``out/progress.csv`` *after* the rows already there (SB3's own CSV writer truncates)."""
    from stable_baselines3.common.logger import CSVOutputFormat, Logger, make_output_format

    class AppendingCSV(CSVOutputFormat):
        def __init__(self, filename: str) -> None:
            old = Path(filename).read_text() if Path(filename).exists() else ""
            super().__init__(filename)  # opens "w+": SB3 rewrites the header in place when new keys appear
            if old.strip():
                self.file.write(old)
                self.file.flush()
                self.keys = next(csv.reader([old.splitlines()[0]]))

    out = Path(out)
    formats = [AppendingCSV(str(out / "progress.csv"))]
    if tensorboard:
        formats.append(make_output_format("tensorboard", str(out / "tb")))
    return Logger(folder=str(out), output_formats=formats)


class TrainingInterrupted(KeyboardInterrupt):
    """A run stopped by Ctrl-C after writing a consistent checkpoint (resume it with ``--resume``)."""


def checkpoint_callback(out: str | Path, every: int, **counters: Any):
    """An SB3 callback writing a checkpoint each time the step count passes a multiple of ``every``, and stopping
    the run cleanly on Ctrl-C.

    Checkpoints are taken only where the agent's state is consistent: at the start of a rollout (after the previous
    step's transition is stored and trained on: every step for SAC, every ``n_steps`` for PPO). The first Ctrl-C
    asks for a stop: SAC finishes its current step, PPO drops its unfinished rollout (its policy does not change
    inside a rollout, so the checkpoint is the state at the rollout's start); then a checkpoint is written and
    :class:`TrainingInterrupted` raised. A second Ctrl-C interrupts at once (the last checkpoint stands).
    """
    import signal
    import threading

    from stable_baselines3.common.callbacks import BaseCallback

    class Checkpoint(BaseCallback):
        def _on_training_start(self) -> None:
            self.next = (self.num_timesteps // every + 1) * every
            self.rollout_start = self.num_timesteps
            self.stop_requested = False
            self.previous_handler = None
            if threading.current_thread() is threading.main_thread():
                self.previous_handler = signal.signal(signal.SIGINT, self._request_stop)

        def _request_stop(self, signum, frame) -> None:
            print("\nstopping: writing a checkpoint (Ctrl-C again to quit at once)", flush=True)
            self.stop_requested = True
            signal.signal(signal.SIGINT, signal.default_int_handler)

        def _stop(self) -> None:
            save_checkpoint(self.model, out, **counters)
            raise TrainingInterrupted(f"stopped at {self.model.num_timesteps} steps")

        def _on_rollout_start(self) -> None:
            self.rollout_start = self.num_timesteps
            if self.stop_requested:
                self._stop()
            if self.num_timesteps >= self.next:
                save_checkpoint(self.model, out, **counters)
                self.next = (self.num_timesteps // every + 1) * every

        def _on_step(self) -> bool:
            if self.stop_requested and getattr(self.model, "replay_buffer", None) is None:
                self.model.num_timesteps = self.rollout_start  # on-policy: the unfinished rollout is dropped
                self._stop()
            return True

        def _on_training_end(self) -> None:
            self.restore_handler()

        def restore_handler(self) -> None:
            if self.previous_handler is not None:
                signal.signal(signal.SIGINT, self.previous_handler)
                self.previous_handler = None

    return Checkpoint()
