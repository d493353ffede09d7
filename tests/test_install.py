"""A non-editable install works on its own: the wheel carries the MJCF assets (issue 23)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def installed(tmp_path_factory) -> Path:
    """The package built as a wheel and installed (no dependencies) into a directory of its own."""
    work = tmp_path_factory.mktemp("install")
    # a copy of the source: building in place would leave build/ in the checkout
    junk = shutil.ignore_patterns(".git", ".venv", "runs", "build", "*.egg-info", "__pycache__", ".*_cache")
    shutil.copytree(ROOT, work / "src", ignore=junk)
    pip = [sys.executable, "-m", "pip", "--disable-pip-version-check", "-q"]
    subprocess.run([*pip, "wheel", "--no-deps", "--no-build-isolation", "-w", str(work / "dist"), str(work / "src")],
                   check=True, capture_output=True, timeout=600)  # fmt: skip
    (wheel,) = (work / "dist").glob("hairbrush_env-*.whl")
    subprocess.run([*pip, "install", "--no-deps", "--target", str(work / "site"), str(wheel)],
                   check=True, capture_output=True, timeout=600)  # fmt: skip
    return work


def test_installed_wheel_rolls_out_from_another_directory(installed):
    """``hairbrush rollout --max-steps 1`` with the installed copy (not this checkout), run from elsewhere."""
    run_dir = installed / "elsewhere"
    run_dir.mkdir()
    env = {**os.environ, "PYTHONPATH": str(installed / "site"), "MUJOCO_GL": "egl"}
    env.pop("HAIRBRUSH_ASSETS_DIR", None)
    code = (
        "import sys, hairbrush_env, hairbrush_env.assets as a; "
        "print(hairbrush_env.__file__); print(a.ASSETS_DIR); "
        "from hairbrush_env.cli import main; "
        "sys.exit(main(['rollout', '--wig', 'straight', '--policy', 'full', '--max-steps', '1', '--quiet', "
        "'--json', 'out.json']))"
    )
    done = subprocess.run([sys.executable, "-c", code], cwd=run_dir, env=env, capture_output=True, text=True,
                          timeout=900)  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    module_file, assets_dir = done.stdout.splitlines()[:2]
    assert module_file.startswith(str(installed / "site")) and assets_dir.startswith(str(installed / "site"))
    assert (Path(assets_dir) / "arm" / "arm.xml").is_file() and (run_dir / "out.json").stat().st_size > 100
