"""The package itself: importing it registers the envs and picks a headless GL backend when there is no display."""

from __future__ import annotations

import os
import subprocess
import sys

SNIPPET = """
import gymnasium as gym
import hairbrush_env
from hairbrush_env.hair import get_wig

wig = get_wig("curly").replace(name="test_headless", n_strands=4, n_triples=0, length=0.12)
env = gym.make("HairBrush-v0", wig=wig, obs_mode="state+image")
obs, info = env.reset(seed=0)
import os
print(os.environ["MUJOCO_GL"], obs["image"].shape, float(obs["image"].std()) > 1.0)
"""


def test_state_image_reset_works_in_a_fresh_shell_without_a_display():
    """README's first example in a shell with neither MUJOCO_GL nor a display (issue 23: it raised
    "Failed to import OpenGL backend (MUJOCO_GL='')")."""
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "DISPLAY", "WAYLAND_DISPLAY")}
    done = subprocess.run(
        [sys.executable, "-c", SNIPPET], capture_output=True, text=True, env=env, timeout=600
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.split()[0] == "egl" and "(120, 160, 3) True" in done.stdout


def test_a_users_backend_choice_wins():
    env = {**os.environ, "MUJOCO_GL": "osmesa"}
    code = "import hairbrush_env, os; print(os.environ['MUJOCO_GL'])"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert done.stdout.strip() == "osmesa"
