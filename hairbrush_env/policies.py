"""The policy protocol and registry used by ``hairbrush rollout`` / ``hairbrush compare``.

Policies live outside the library (``controllers/`` or third-party packages) and are found by name through the
entry-point group ``hairbrush_env.policies`` declared in ``pyproject.toml``, e.g.::

    [project.entry-points."hairbrush_env.policies"]
    full = "controllers.baselines:FullStrokePolicy"

so ``hairbrush_env`` never imports ``controllers`` and third-party policies plug in the same way. An entry point
names a factory called as ``factory(env, **kwargs)`` that returns an object with ``reset(seed)`` and
``act(obs) -> action``. The special name ``sb3:PATH`` loads a saved stable-baselines3 model (issue #6).
"""

from __future__ import annotations

from importlib import metadata
from typing import Any, Protocol, runtime_checkable

import numpy as np

ENTRY_POINT_GROUP = "hairbrush_env.policies"


@runtime_checkable
class Policy(Protocol):
    """What a rollout needs from a policy."""

    def reset(self, seed: int | None = None) -> None:
        """Start a new episode (seed the policy's own randomness)."""

    def act(self, obs: Any) -> np.ndarray:
        """Return an action for ``obs`` (an element of the env's action space)."""


def available_policies() -> dict[str, metadata.EntryPoint]:
    """Registered policy names → entry points (installed distributions only)."""
    return {ep.name: ep for ep in metadata.entry_points(group=ENTRY_POINT_GROUP)}


def policy_entry_point(name: str) -> metadata.EntryPoint:
    """The entry point behind ``name`` (``sb3:PATH`` → the ``sb3`` loader); ``ValueError`` if none is registered, so
    callers can check names before they simulate anything."""
    registry = available_policies()
    if name.startswith("sb3:"):
        if "sb3" not in registry:
            raise ValueError("policy: 'sb3:PATH' needs the RL extra (pip install 'hairbrush-env[rl]')")
        return registry["sb3"]
    if name not in registry:
        known = ", ".join(sorted(registry)) or "none installed"
        raise ValueError(f"policy: unknown policy {name!r}; registered: {known} (or sb3:PATH)")
    return registry[name]


def make_policy(name: str, env: Any, **kwargs: Any) -> Policy:
    """Instantiate the policy registered as ``name`` for ``env`` (or ``sb3:PATH`` for a saved SB3 model)."""
    factory = policy_entry_point(name).load()
    if name.startswith("sb3:"):
        return factory(env, path=name[4:], **kwargs)
    policy = factory(env, **kwargs)
    if not isinstance(policy, Policy):
        raise TypeError(f"policy {name!r}: factory returned {type(policy).__name__} without reset()/act()")
    return policy
