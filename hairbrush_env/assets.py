"""Locate the MJCF parts (``assets/<part>/<part>.xml``) and load them as :class:`mujoco.MjSpec`.

The parts live at the repository top level (``<repo>/assets``), next to the package, so an editable install
and a source checkout find them relative to this file.  Resolution order of :data:`ASSETS_DIR`:

1. ``$HAIRBRUSH_ASSETS_DIR`` if set (an explicit override, e.g. for a relocated asset tree);
2. ``<repo>/assets`` next to the package directory (source tree / editable install);
3. ``hairbrush_env/assets`` inside the installed package, via :mod:`importlib.resources` (for a wheel
   that ships the assets as package data).
"""

from __future__ import annotations

import os
from importlib import resources
from pathlib import Path

import mujoco

__all__ = ["ASSETS_DIR", "PARTS", "load_part", "part_path"]

#: Parts shipped with the package (directory name = file stem).
PARTS = ("arm", "brush", "head")


def _resolve_assets_dir() -> Path:
    env = os.environ.get("HAIRBRUSH_ASSETS_DIR")
    if env:
        return Path(env).expanduser().resolve()
    repo_assets = Path(__file__).resolve().parent.parent / "assets"
    if (repo_assets / "arm").is_dir():
        return repo_assets
    packaged = resources.files("hairbrush_env") / "assets"
    if packaged.is_dir():
        # A regular installed package is a real directory, so the Traversable is a path.
        return Path(str(packaged))
    # Returned anyway so that error messages name the place that was looked at.
    return repo_assets


ASSETS_DIR: Path = _resolve_assets_dir()


def part_path(name: str) -> Path:
    """Path of ``assets/<name>/<name>.xml``; raises ``FileNotFoundError`` naming the searched path."""
    path = ASSETS_DIR / name / f"{name}.xml"
    if not path.is_file():
        raise FileNotFoundError(f"MJCF part {name!r} not found at {path} (known parts: {', '.join(PARTS)})")
    return path


def load_part(name: str) -> mujoco.MjSpec:
    """Parse a part into a fresh, independent :class:`mujoco.MjSpec`.

    Every call returns a new spec, because ``MjSpec.attach`` moves (does not copy) the child's elements
    into the parent: a spec can be attached as a whole only once.
    """
    return mujoco.MjSpec.from_file(str(part_path(name)))
