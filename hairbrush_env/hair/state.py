"""Saving, restoring and caching the full MuJoCo state of a prepared wig (:class:`StateCache`)."""

from __future__ import annotations

import hashlib
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np

from .config import WigConfig

__all__ = ["STATE_SPEC", "StateCache", "get_state", "set_state"]

STATE_SPEC = mujoco.mjtState.mjSTATE_INTEGRATION
"""What is cached: the full integration state (time, qpos, qvel, act, ctrl, warm start, ..., incl. PLASTIC)."""


@dataclass
class StateCache:
    """Settled wig states per (wig digest, seed, model hash), in memory and optionally on disk.

    Parameters
    ----------
    directory : str or Path, optional
        If given, states are also written as ``<wig>-<digest>-s<seed>-<model>.npy`` (atomically) and read back by
        later processes.
    """

    directory: str | Path | None = None
    _memory: dict[tuple[str, int, str], np.ndarray] = field(default_factory=dict, repr=False)

    @staticmethod
    def model_hash(model: mujoco.MjModel) -> str:
        """SHA-256 (16 hex) of the compiled model's binary."""
        buf = np.zeros(mujoco.mj_sizeModel(model), dtype=np.uint8)
        mujoco.mj_saveModel(model, None, buf)
        return hashlib.sha256(buf.tobytes()).hexdigest()[:16]

    def _path(self, wig: WigConfig, seed: int, model_hash: str) -> Path | None:
        if self.directory is None:
            return None
        return Path(self.directory) / f"{wig.name}-{wig.digest()}-s{int(seed)}-{model_hash}.npy"

    def get(self, wig: WigConfig, seed: int, model_hash: str) -> np.ndarray | None:
        key = (wig.digest(), int(seed), model_hash)
        if key in self._memory:
            return self._memory[key]
        path = self._path(wig, seed, model_hash)
        if path is not None and path.is_file():
            state = np.load(path)
            self._memory[key] = state
            return state
        return None

    def put(self, wig: WigConfig, seed: int, model_hash: str, state: np.ndarray) -> None:
        state = np.array(state, dtype=float)
        state.setflags(write=False)
        self._memory[(wig.digest(), int(seed), model_hash)] = state
        path = self._path(wig, seed, model_hash)
        if path is not None:
            path.parent.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".npy.tmp")
            with os.fdopen(fd, "wb") as fh:
                np.save(fh, state)
            os.replace(tmp, path)

    def clear(self) -> None:
        """Forget the in-memory states (files stay)."""
        self._memory.clear()


def get_state(model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
    """Full integration state (incl. plastic rod frames) of ``data``."""
    out = np.empty(mujoco.mj_stateSize(model, STATE_SPEC))
    mujoco.mj_getState(model, data, out, STATE_SPEC)
    return out


def set_state(model: mujoco.MjModel, data: mujoco.MjData, state: np.ndarray) -> None:
    """Restore a state from :func:`get_state` and recompute derived quantities (``mj_forward``)."""
    mujoco.mj_setState(model, data, np.asarray(state, dtype=float), STATE_SPEC)
    mujoco.mj_forward(model, data)
