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
    parser = HelpfulParser(
        prog="hairbrush",
        description="Robotic hair brushing in MuJoCo and the physics/topology toolkit behind it.",
    )
    parser.add_argument("--version", action="version", version=f"hairbrush_env {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in BUILTIN_COMMANDS:
        importlib.import_module(f"{__package__}.commands.{name}").register(sub)
    _add_plugins(sub)
    return parser


class DefaultsFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Shows an option's default unless it has none (None, a flag's False) or its help already names it."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        no_default = action.default is None or action.default is False or action.default == argparse.SUPPRESS
        if no_default or "default" in text:
            return text
        return super()._get_help_string(action) or text


class HelpfulParser(argparse.ArgumentParser):
    """Every (sub)command shows each option's default in ``--help``."""

    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("formatter_class", DefaultsFormatter)
        super().__init__(*args, **kwargs)


def main(argv: Sequence[str] | None = None) -> int:
    from .commands.checks import UsageError
    from .executor import CellsFailed, ExecutorUnavailable

    # Headless rendering default for CLI runs (the package picks EGL too when there is no display).
    os.environ.setdefault("MUJOCO_GL", "egl")
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except UsageError as exc:  # found by a handler before it simulated: one line, exit 2, as argparse does
        prog = f"{parser.prog} {args.command}" + (f" {args.action}" if getattr(args, "action", None) else "")
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 2
    except ExecutorUnavailable as exc:  # before any cell ran
        print(f"{parser.prog} {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except CellsFailed as exc:  # the grid finished without them; its files hold every cell that succeeded
        print(f"{parser.prog} {args.command}: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
