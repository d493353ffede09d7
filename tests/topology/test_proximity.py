from __future__ import annotations

import numpy as np
import pytest

from hairbrush_env.topology.proximity import min_self_distance, segment_distances


def test_min_self_distance_of_a_hairpin_is_the_gap_between_its_legs():
    h = 0.3
    hairpin = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, h, 0], [1, h, 0], [0, h, 0]], dtype=float)
    straight = np.column_stack([np.arange(6.0), np.zeros(6), np.zeros(6)])  # segments 2 apart: 1 apart
    assert min_self_distance(np.stack([hairpin, straight])) == pytest.approx([h, 1.0])
    # neighbours sharing a vertex are never compared; skip = 3 leaves only the legs' far pairs
    assert min_self_distance(hairpin[None], skip=3)[0] == pytest.approx(h)


def test_min_self_distance_matches_brute_force_on_random_curls():
    rng = np.random.default_rng(3)
    curves = np.cumsum(rng.normal(size=(4, 12, 3)), axis=1)
    got = min_self_distance(curves)
    for c, value in zip(curves, got, strict=True):
        n = len(c) - 1
        ref = min(
            float(segment_distances(c[i], c[i + 1], c[j : j + 1], c[j + 1 : j + 2])[0])
            for i in range(n)
            for j in range(i + 2, n)
        )
        assert value == pytest.approx(ref)


@pytest.mark.parametrize("skip", [1, 2.0])
def test_min_self_distance_refuses_a_skip_that_would_compare_neighbours(skip):
    with pytest.raises(ValueError, match="skip"):
        min_self_distance(np.zeros((1, 4, 3)), skip=skip)
