"""The MJCF parts (``hairbrush_env/assets/<part>/<part>.xml``, menagerie style) and their loader.

The parts ship inside the package (package data), so an editable install, a wheel and a source checkout all find
them next to this file. ``$HAIRBRUSH_ASSETS_DIR`` overrides the location (e.g. for a relocated or modified asset
tree).
"""

from __future__ import annotations

import os
from pathlib import Path

import mujoco

__all__ = ["ASSETS_DIR", "PARTS", "load_part", "part_path"]

#: Parts shipped with the package (directory name = file stem).
PARTS = ("arm", "brush", "head")


def _resolve_assets_dir() -> Path:
    env = os.environ.get("HAIRBRUSH_ASSETS_DIR")
    if env:
        return Path(env).expanduser().resolve()
    return Path(__file__).resolve().parent


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
