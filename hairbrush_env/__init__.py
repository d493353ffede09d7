"""hairbrush_env — robotic hair brushing in MuJoCo, and the rod-physics / curve-topology toolkit behind it.

Science: T. B. Plumb-Reyes, *Some Topics in Topological Mechanics*, PhD thesis, Harvard University (2021).
Submodules are imported lazily so that ``import hairbrush_env`` stays cheap (no numba compile, no MuJoCo
model build) — a training script that only calls ``gymnasium.make`` pays only for what it uses.
"""

from __future__ import annotations

import os as _os
import sys as _sys
from importlib import metadata as _metadata


def _default_headless_gl() -> None:
    """Pick EGL (which renders on the CPU through Mesa, or on a GPU) when no display is present and the user chose
    no backend: MuJoCo reads ``MUJOCO_GL`` once, when it is imported, and its default (GLFW) needs a display, so a
    fresh shell on a server failed at the first image with "Failed to import OpenGL backend". A user's own setting,
    and any display, win."""
    no_display = not (_os.environ.get("DISPLAY") or _os.environ.get("WAYLAND_DISPLAY"))
    if _sys.platform.startswith("linux") and no_display and "MUJOCO_GL" not in _os.environ:
        if "mujoco" not in _sys.modules:  # too late otherwise: MuJoCo has chosen its backend
            _os.environ["MUJOCO_GL"] = "egl"


_default_headless_gl()

try:
    __version__ = _metadata.version("hairbrush-env")
except _metadata.PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.0.0+unknown"

__all__ = ["__version__"]

# `gymnasium.make("HairBrush-v0")` works after `import hairbrush_env`: registration uses string entry points, so
# this imports only gymnasium's registry, not MuJoCo or the env modules.
from .envs import register_envs as _register_envs  # noqa: E402 (after the GL default, before any MuJoCo import)

_register_envs()
