"""``hairbrush`` subcommand groups; each module has ``register(subparsers)``."""

from __future__ import annotations

import argparse

#: Webcam resolution at which the vision R_c ranks every preset (README "Vision curliness").
WEBCAM_SIZE = (640, 480)


def add_webcam_args(parser: argparse.ArgumentParser) -> None:
    """``--width`` / ``--height`` of the webcam images (observation, render, video)."""
    parser.add_argument(
        "--width",
        type=int,
        default=WEBCAM_SIZE[0],
        help="webcam image width [px]; the vision R_c needs ~640x480 to resolve tight coils (README)",
    )
    parser.add_argument("--height", type=int, default=WEBCAM_SIZE[1], help="webcam image height [px]")
