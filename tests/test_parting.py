"""Which pairs a tine lies between (:mod:`hairbrush_env.parting`), on drawn strands."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hairbrush_env.parting import crossing_y, pairs_parted


def _strand(x: float, y: float, length: float = 0.1) -> np.ndarray:
    """A straight strand hanging from (x, y, 0), root first."""
    z = np.linspace(0.0, -length, 11)
    return np.column_stack([np.full_like(z, x), np.full_like(z, y), z])


def test_crossing_y_interpolates_the_first_crossing() -> None:
    bent = np.array([[0.0, 0.0, 0.0], [0.0, 0.01, -0.01], [0.0, 0.03, -0.02], [0.0, -0.05, -0.03]])
    assert crossing_y(bent, -0.015) == pytest.approx(0.02)
    assert math.isnan(crossing_y(bent, -0.05))  # never comes down that far
    assert math.isnan(crossing_y(bent, 0.01))  # above the root


def test_a_tine_parts_strands_side_by_side_not_one_behind_the_other() -> None:
    room = 0.002
    tines = np.array([-0.02, 0.0, 0.02])
    curves = np.array(
        [
            _strand(0.0, -0.01),
            _strand(0.0, 0.01),  # pair 0: across the tine at y 0
            _strand(-0.01, 0.04),
            _strand(0.01, 0.04),  # pair 1: one behind the other on y 0.04, between no tine
            _strand(0.0, 0.058),
            _strand(0.0, 0.061),  # pair 2: a tine at 0.06 would pass, but not at 0.04 or 0.02
            _strand(0.0, -0.001),
            _strand(
                0.0, 0.001, length=0.01
            ),  # pair 3: side by side, but too close for the tine and one short
        ]
    )
    pairs = np.array([[0, 1], [2, 3], [4, 5], [6, 7]])
    np.testing.assert_array_equal(
        pairs_parted(curves, pairs, tines, -0.05, room), [True, False, False, False]
    )
    np.testing.assert_array_equal(
        pairs_parted(curves, pairs, np.array([0.0595]), -0.05, 0.001), [False, False, True, False]
    )
    assert not pairs_parted(curves, pairs, tines, -0.05, 0.011)[0]  # no room for tine and strand
