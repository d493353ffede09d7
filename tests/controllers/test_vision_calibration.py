"""R_c on rendered wigs ranks them like the true R/P (thesis Fig. 3.4), robust to hair colour and lighting."""

from __future__ import annotations

import json
import os

import pytest

os.environ.setdefault("MUJOCO_GL", "egl")

from hairbrush_env.cli import main
from hairbrush_env.hair import PRESETS


@pytest.mark.xfail(
    strict=True,
    reason="known gap (issue #5): on our rendered wigs R_c saturates for R/P >= 0.3 (side-on helix slopes exceed "
    "45 deg, tight coils blur at 320x240), so the three curliest presets are not ranked: measured rho 0.77 with the "
    "frame crop, 0.6 with a hair-only mask; straight/wavy/loose_curl are ranked correctly",
)
def test_vision_calibrate_cli_ranks_presets(tmp_path):
    # reduced: one pre-brushed state per wig, nominal + one jittered camera; the README run uses 3 × 3
    assert (
        main(["vision", "calibrate", "--seeds", "0", "--jitters", "2", "--out", str(tmp_path), "--quiet"])
        == 0
    )
    summary = json.loads((tmp_path / "vision_calibration.json").read_text())
    assert summary["n_images"] == len(PRESETS) * 2 * 3
    rho = summary["spearman_rho"]
    assert set(rho) == {"default", "blond hair", "dim light"}
    for cond, value in rho.items():
        assert value >= 0.9, (cond, value)
    assert (tmp_path / "vision_calibration.png").stat().st_size > 10_000
