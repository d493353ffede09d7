"""N-body interaction census on hand-made bundles with known answers."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.sparse.csgraph import connected_components

from hairbrush_env.topology import (
    clip_to_slab,
    double_helix,
    empirical_lk_threshold,
    interaction_census,
    layer_link_matrices,
    link_census_from_matrices,
)


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


def wound_bundle(seed=0, n=5):
    """Strands that wander and wind around each other a little: random smooth lateral paths around a lattice."""
    rng = np.random.default_rng(seed)
    z = np.linspace(0, -1, 201)
    out = []
    for k in range(n):
        phase = rng.uniform(0, 2 * np.pi, 3)
        amp = rng.uniform(0.01, 0.03, 3)
        waves = [2 * np.pi * (m + 1) * 3 * z + p for m, p in enumerate(phase)]
        x = 0.02 * k + sum(a * np.cos(w) for a, w in zip(amp, waves, strict=True))
        y = sum(a * np.sin(w) for a, w in zip(amp, waves, strict=True))
        out.append(np.column_stack([x, y, z]))
    return out


def test_layer_link_matrices_give_the_link_census():
    strands = wound_bundle()
    mats, extent = layer_link_matrices(strands, n_layers=10)
    assert mats.shape == (10, 5, 5) and extent == pytest.approx(1.0)
    np.testing.assert_allclose(mats, np.transpose(mats, (0, 2, 1)))
    for t in (0.0, 0.01, 0.05, 0.2):
        assert link_census_from_matrices(mats, t, extent) == pytest.approx(
            interaction_census(strands, n_layers=10, criterion="link", lk_threshold=t)
        )
    # a strand absent from a layer gets NaN there and never interacts
    short = [*strands[:4], strands[4][:60]]
    m2, _ = layer_link_matrices(short, n_layers=10)
    assert np.isnan(m2[0, 4]).all() and np.isfinite(m2[0, :4, :4]).all()  # layer 0 is the bottom (z ≈ −1)


def _largest_cluster_fraction(mats, t):
    worst = 0.0
    for m in mats:
        present = ~np.isnan(np.diag(m))
        w = m[np.ix_(present, present)] > t
        np.fill_diagonal(w, False)
        n_comp, _ = connected_components(w, directed=False)
        worst = max(worst, float(n_comp == 1))
    return worst


def test_empirical_threshold_is_the_smallest_without_an_all_strand_cluster():
    mats = np.concatenate([layer_link_matrices(wound_bundle(seed), n_layers=10)[0] for seed in range(3)])
    m = empirical_lk_threshold(mats)
    assert m > 0
    assert _largest_cluster_fraction(mats, m) == 0.0  # at m: no layer is one cluster of every strand
    assert _largest_cluster_fraction(mats, m * (1 - 1e-9)) == 1.0  # just below: some layer is
    # the same answer by brute force over the distinct |Lk| values
    values = np.unique(mats[np.isfinite(mats) & (mats > 0)])
    brute = min([0.0, *values], key=lambda t: (_largest_cluster_fraction(mats, t), t))
    assert m == pytest.approx(brute)
    # unlinked straight strands: nothing to segregate
    straight = [
        np.column_stack([np.full(11, 0.1 * k), np.zeros(11), np.linspace(0, 1, 11)]) for k in range(3)
    ]
    assert empirical_lk_threshold(layer_link_matrices(straight, n_layers=5)[0]) == 0.0
    with pytest.raises(ValueError, match="mats"):
        empirical_lk_threshold(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="threshold"):
        link_census_from_matrices(mats, -1.0, 1.0)
