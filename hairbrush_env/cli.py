"""``hairbrush`` — one command-line tool with subcommands.

Each built-in subcommand group is a module of :mod:`hairbrush_env.commands` with ``register(subparsers)``; other
packages add groups through the ``hairbrush_env.commands`` entry-point group. Handlers import their heavy
dependencies lazily, so ``hairbrush --help`` is instant.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from collections.abc import Sequence

from . import __version__

#: Entry-point group through which other packages (e.g. ``controllers``) add subcommands: each entry point is a
#: function ``register(subparsers)``. hairbrush_env itself never imports them.
COMMAND_GROUP = "hairbrush_env.commands"


def _add_plugins(sub: argparse._SubParsersAction) -> None:
    from importlib import metadata

    for ep in sorted(metadata.entry_points(group=COMMAND_GROUP), key=lambda e: e.name):
        ep.load()(sub)


#: Built-in command groups, each a module of :mod:`hairbrush_env.commands` with ``register(subparsers)``.
BUILTIN_COMMANDS = ("topology", "rollout", "compare", "helix", "rodpile")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hairbrush",
        description="Robotic hair brushing in MuJoCo and the physics/topology toolkit behind it.",
    )
    parser.add_argument("--version", action="version", version=f"hairbrush_env {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in BUILTIN_COMMANDS:
        importlib.import_module(f"{__package__}.commands.{name}").register(sub)
    _add_plugins(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    # Headless rendering default for CLI runs; the library itself never forces a GL backend.
    os.environ.setdefault("MUJOCO_GL", "egl")
    args = build_parser().parse_args(argv)
    return int(args.func(args) or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
