"""N-body interaction census on hand-made bundles with known answers."""

from __future__ import annotations

import numpy as np
import pytest

from hairbrush_env.topology import clip_to_slab, double_helix, interaction_census


def line(p, q, n=11):
    return np.linspace(p, q, n)


def bundle():
    """Height 1 m along z, 10 layers of 0.1 m. Viewed side-on (x–z plane):

    - strands 0 and 1 cross (an X) in layer 2 (z ∈ [0.2, 0.3]) at x = 0;
    - strands 2, 3, 4 pairwise cross in layer 7 (z ∈ [0.7, 0.8]) — one 3-body cluster;
    - strand 5 is straight and far away.
    """
    s0 = np.vstack(
        [
            line([0, 0, 0], [0, 0, 0.2]),
            line([0, 0, 0.2], [0.2, 0.05, 0.3])[1:],
            line([0.2, 0.05, 0.3], [0.2, 0.05, 1])[1:],
        ]
    )
    s1 = np.vstack(
        [
            line([0.2, 0.1, 0], [0.2, 0.1, 0.2]),
            line([0.2, 0.1, 0.2], [0, 0.15, 0.3])[1:],
            line([0, 0.15, 0.3], [0, 0.15, 1])[1:],
        ]
    )
    xs = [(1.0, 1.2), (1.2, 1.0), (1.05, 1.15)]
    fans = []
    for k, (xa, xb) in enumerate(xs):
        y = 0.3 + 0.05 * k
        # the third strand runs the other diagonal offset so it crosses both others in projection
        fans.append(
            np.vstack(
                [
                    line([xa, y, 0], [xa, y, 0.7]),
                    line([xa, y, 0.7], [xb, y, 0.8])[1:],
                    line([xb, y, 0.8], [xb, y, 1])[1:],
                ]
            )
        )
    fans[2] = np.vstack(
        [
            line([1.1, 0.4, 0], [1.1, 0.4, 0.7]),
            line([1.1, 0.4, 0.7], [1.1, 0.4, 0.8])[1:],
            line([1.1, 0.4, 0.8], [1.1, 0.4, 1])[1:],
        ]
    )
    s5 = line([3, 3, 0], [3, 3, 1])
    return [s0, s1, *fans, s5]


def test_crossing_census_counts_hand_made_bundle():
    rho = interaction_census(bundle(), n_layers=10, criterion="crossing")
    assert rho == {2: pytest.approx(1.0), 3: pytest.approx(1.0)}  # one pair and one triple per metre


def test_contact_census():
    strands = bundle()
    # Where the X pair crosses in projection its strands are 0.1 m apart in depth (y); in layer 7 the fan strands
    # pass 0.05 m from their neighbours (2-3, 3-4) and 0.1 m from each other (2-4).
    near = interaction_census(strands, n_layers=10, criterion="contact", contact_distance=0.06)
    assert near == {2: pytest.approx(0.0), 3: pytest.approx(1.0)}  # chain 2-3-4 is one 3-body cluster
    far = interaction_census(strands, n_layers=10, criterion="contact", contact_distance=0.11)
    assert far == {2: pytest.approx(1.0), 3: pytest.approx(1.0)}
    with pytest.raises(ValueError, match="contact_distance"):
        interaction_census(strands, criterion="contact")


def test_link_census_double_helices():
    # two separate double helices (pairs), each with one full turn per layer => |Lk| per layer ≈ 1 > 0.4
    a, b = double_helix(0.01, 0.1, 10, 801)
    c, d = (x + np.array([1.0, 0, 0]) for x in double_helix(0.01, 0.1, 10, 801))
    rho = interaction_census([a, b, c, d], n_layers=10, criterion="link", lk_threshold=0.4)
    assert rho == {2: pytest.approx(2 * 10 / 1.0)}
    assert interaction_census([a, b, c, d], n_layers=10, criterion="link", lk_threshold=1.5) == {}


def test_clip_to_slab_exact_and_multiple_pieces():
    z = np.linspace(0, 4 * np.pi, 400)
    wave = np.column_stack([z, 0 * z, np.sin(z)])
    pieces = clip_to_slab(wave, 2, 0.5, 2.0)
    assert len(pieces) == 2  # the sine enters the slab z>0.5 twice
    for pc in pieces:
        assert pc[:, 2].min() >= 0.5 - 1e-12
        assert pc[0, 2] == pytest.approx(0.5) and pc[-1, 2] == pytest.approx(0.5)


def test_census_bad_input():
    with pytest.raises(ValueError, match="criterion"):
        interaction_census(bundle(), criterion="touch")
    with pytest.raises(ValueError, match="axis"):
        interaction_census(bundle(), axis=3)
    with pytest.raises(ValueError, match=r"strands\[1\]"):
        interaction_census([bundle()[0], np.zeros((3, 2))])
