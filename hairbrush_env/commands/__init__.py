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
