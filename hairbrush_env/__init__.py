"""hairbrush_env — robotic hair brushing in MuJoCo, and the rod-physics / curve-topology toolkit behind it.

Science: T. B. Plumb-Reyes, *Some Topics in Topological Mechanics*, PhD thesis, Harvard University (2021).
Submodules are imported lazily so that ``import hairbrush_env`` stays cheap (no numba compile, no MuJoCo
model build) — a training script that only calls ``gymnasium.make`` pays only for what it uses.
"""

from __future__ import annotations

from importlib import metadata as _metadata

try:
    __version__ = _metadata.version("hairbrush-env")
except _metadata.PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.0.0+unknown"

__all__ = ["__version__"]

# `gymnasium.make("HairBrush-v0")` works after `import hairbrush_env`: registration uses string entry points, so
# this imports only gymnasium's registry, not MuJoCo or the env modules.
from .envs import register_envs as _register_envs

_register_envs()
