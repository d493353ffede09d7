"""A saved stable-baselines3 model behind the policy protocol (``--policy sb3:PATH``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

ALGORITHMS = ("PPO", "SAC", "A2C", "TD3", "DDPG")


def load_sb3_model(path: str | Path, *, algo: str | None = None):
    """Load a model saved by ``scripts/train_rl.py``; the algorithm is read from ``algo.txt`` beside it if not given."""
    import stable_baselines3 as sb3

    p = Path(path)
    if p.is_dir():
        p = p / "model.zip"
    if not p.exists():
        raise ValueError(f"path: no saved model at {p}")
    if algo is None:
        marker = p.parent / "algo.txt"
        algo = marker.read_text().strip().upper() if marker.exists() else "PPO"
    if algo.upper() not in ALGORITHMS:
        raise ValueError(f"algo: expected one of {ALGORITHMS}, got {algo!r}")
    return getattr(sb3, algo.upper()).load(p, device="cpu")


class SB3Policy:
    """Deterministic actions of a trained SB3 agent."""

    def __init__(self, env: Any, *, path: str, algo: str | None = None, deterministic: bool = True) -> None:
        self.model = load_sb3_model(path, algo=algo)
        self.deterministic = deterministic
        want = self.model.observation_space
        have = env.observation_space
        if hasattr(want, "spaces") and hasattr(have, "spaces") and set(want.spaces) - set(have.spaces):
            missing = sorted(set(want.spaces) - set(have.spaces))
            raise ValueError(f"path: model expects observation keys {missing} the env does not provide")
        self._keys = list(want.spaces) if hasattr(want, "spaces") else None

    def _fit(self, key: str, value: Any) -> Any:
        """Zero-pad or cut a 1-D observation to the length the model was trained with.

        ``force_trace`` is sized to one full stroke of the env's wig (``default_trace_length``), so an agent trained
        on one wig meets longer or shorter traces on others. The trace is 0-padded after the stroke anyway; cutting
        drops the end of strokes longer than any the agent saw in training.
        """
        want = self.model.observation_space.spaces[key].shape
        arr = np.asarray(value)
        if arr.shape == want or arr.ndim != 1 or len(want) != 1:
            return value
        out = np.zeros(want, dtype=arr.dtype)
        n = min(want[0], arr.shape[0])
        out[:n] = arr[:n]
        return out

    def reset(self, seed: int | None = None) -> None:
        """SB3 policies here are feed-forward: no state to reset."""

    def act(self, obs: Any) -> np.ndarray:
        if self._keys is not None:
            obs = {k: self._fit(k, obs[k]) for k in self._keys}
        action, _ = self.model.predict(obs, deterministic=self.deterministic)
        return np.asarray(action, dtype=np.float32)
