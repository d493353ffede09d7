"""Shared fixtures: a small wig so env tests stay fast (full presets are exercised by tests/test_scene.py)."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")  # headless rendering for tests; the library never forces it

import pytest

from hairbrush_env.hair import get_wig


@pytest.fixture(scope="session")
def small_wig():
    """A short curly wig of 6 wisps (2 entwined pairs + … as the layout decides), for speed."""
    return get_wig("curly").replace(name="test_small", n_strands=6, n_triples=0, length=0.12)


@pytest.fixture(scope="session")
def small_wavy_wig():
    """Six short wavy wisps: entwined, but full strokes read forces within 0.4 N of each other, so eq. 3.4 ends an
    episode of full strokes within a few strokes (tests of the finish rule's reward)."""
    return get_wig("wavy").replace(name="test_small_wavy", n_strands=6, n_triples=0, length=0.12)
