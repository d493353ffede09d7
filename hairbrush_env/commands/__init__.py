"""``hairbrush`` subcommand groups; each module has ``register(subparsers)``."""

from __future__ import annotations

import argparse

from ..constants import WEBCAM_SIZE


def add_webcam_args(parser: argparse.ArgumentParser) -> None:
    """``--width`` / ``--height`` of the webcam images (observation, render, video)."""
    from .checks import integer

    parser.add_argument(
        "--width",
        type=integer(16, 2048),
        default=WEBCAM_SIZE[0],
        help="webcam image width [px]; the vision R_c needs ~640x480 to resolve tight coils",
    )
    parser.add_argument(
        "--height", type=integer(16, 2048), default=WEBCAM_SIZE[1], help="webcam image height [px]"
    )


def add_executor_args(parser: argparse.ArgumentParser, *, workers: int, what: str) -> None:
    """``--workers`` / ``--ray``: where the command's independent cells run (:mod:`hairbrush_env.executor`)."""
    from .checks import count, ray_address

    parser.add_argument(
        "--workers",
        type=count,
        default=workers,
        help=f"{what} run in this many local processes (1: in this process); with --ray auto and no running "
        "cluster, the CPUs of the local Ray instance it starts",
    )
    parser.add_argument(
        "--ray",
        type=ray_address,
        default=None,
        metavar="ADDRESS",
        help="run on Ray: 'auto' (the running cluster, else a new local one) or a cluster address "
        "(e.g. 10.0.0.5:6379); needs the ray extra. Default: local processes",
    )


def executor_from_args(args: argparse.Namespace):
    """The :class:`~hairbrush_env.executor.ExecutorConfig` of ``--workers`` / ``--ray``."""
    from ..executor import ExecutorConfig

    return ExecutorConfig(workers=args.workers, ray=args.ray)


def add_physics_arg(parser: argparse.ArgumentParser) -> None:
    """``--physics``: the version of the brushing physics (:mod:`hairbrush_env.physics`; vN = ``HairBrush-vN``)."""
    from ..physics import PHYSICS, physics_help

    parser.add_argument(
        "--physics",
        choices=list(PHYSICS),
        default="v0",
        help=f"brushing physics, vN = HairBrush-vN's: {physics_help()}",
    )
