"""Rod-pile fields (thesis §4.3.3–4.3.4, eqs 4.1–4.2) on synthetic packings with known answers; no MuJoCo."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hairbrush_env.studies.rod_fields import correlation, correlation_length, local_fields
from hairbrush_env.studies.rod_pile import Packing, load_packing, orientations, philipse_contact_number
from hairbrush_env.topology import average_crossing_number, pair_gauss_matrix
from hairbrush_env.topology.segments import grouped_pair_acn, segment_pair_gauss

D = 0.001


def _random_rods(n, length, box, rng):
    c = rng.uniform(length, box - length, size=(n, 3))
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    return np.stack([c - u * length / 2, c + u * length / 2], axis=1)


def test_segment_pair_gauss_matches_topology_library():
    rng = np.random.default_rng(0)
    a0, a1, b0, b1 = (rng.normal(size=(200, 3)) for _ in range(4))
    g, bad = segment_pair_gauss(a0, a1, b0, b1)
    ref = np.array(
        [
            pair_gauss_matrix(np.array([p, q]), np.array([r, s]))[0, 0]
            for p, q, r, s in zip(a0, a1, b0, b1, strict=True)
        ]
    )
    assert not bad.any()
    np.testing.assert_allclose(g, ref, atol=1e-13)


def test_grouped_acn_sums_polyline_pieces_before_abs():
    rng = np.random.default_rng(1)
    curves = [np.cumsum(rng.normal(size=(5, 3)), axis=0) for _ in range(3)]
    p0 = np.concatenate([c[:-1] for c in curves])
    p1 = np.concatenate([c[1:] for c in curves])
    owner = np.repeat(np.arange(3), 4)
    acn, nbad = grouped_pair_acn(p0, p1, owner, np.array([0, 12]))
    # |open Gauss integral| of each pair of whole curves (the thesis's e for curves inside Ω)
    ref = sum(abs(pair_gauss_matrix(curves[i], curves[j]).sum()) for i in range(3) for j in range(i + 1, 3))
    assert nbad[0] == 0
    assert acn[0] == pytest.approx(ref, abs=1e-12)
    # and it is not the per-segment |G| sum (that is the ACN of eq. 4.1 with pieces split)
    assert acn[0] <= sum(
        average_crossing_number(curves[i], curves[j]) for i in range(3) for j in range(i + 1, 3)
    )


def test_single_cell_values_are_exact():
    l_s = 10 * D
    # two perpendicular rods crossing one cube (centre (5,5,5) mm) at a 1-diameter gap, plus a vertical rod
    ep = np.array([
        [[-0.01, 0.005, 0.005], [0.02, 0.005, 0.005]],
        [[0.005, -0.01, 0.006], [0.005, 0.02, 0.006]],
        [[0.002, 0.002, 0.0], [0.002, 0.002, 0.02]],
    ])  # fmt: skip
    p = Packing.from_endpoints(ep, D)
    f = local_fields(p, l_s, height=0.02)
    i, j, k = (math.floor((0.005 - f.origin[a]) / l_s) for a in range(3))
    area = math.pi * D * D / 4
    assert f.phi[i, j, k] == pytest.approx(3 * l_s * area / l_s**3)
    assert f.n[i, j, k] == 3
    # S about vertical: (1 + 2·(−½))/3 = 0
    assert f.S_vertical[i, j, k] == pytest.approx(0.0, abs=1e-12)
    # three orthogonal equal pieces: Q = 0, so S about the director is 0 too
    assert f.S_director[i, j, k] == pytest.approx(0.0, abs=1e-12)
    clipped = [
        np.array([[0.0, 0.005, 0.005], [0.01, 0.005, 0.005]]),
        np.array([[0.005, 0.0, 0.006], [0.005, 0.01, 0.006]]),
        np.array([[0.002, 0.002, 0.0], [0.002, 0.002, 0.01]]),
    ]
    ref = sum(abs(pair_gauss_matrix(clipped[a], clipped[b])[0, 0]) for a in range(3) for b in range(a + 1, 3))
    assert f.e[i, j, k] == pytest.approx(ref, rel=1e-12)
    assert f.e[i, j, k] > 0.1  # two crossing perpendicular rods one diameter apart are strongly "entangled"
    # an empty cell: φ = e = n = 0, S = 1 (thesis convention)
    emp = (0, 0, 1)
    assert f.phi[emp] == 0 and f.e[emp] == 0 and f.n[emp] == 0 and f.S_director[emp] == 1.0


def test_length_is_conserved_and_isotropic_order_vanishes():
    rng = np.random.default_rng(2)
    box = 0.2
    ep = _random_rods(3000, 0.03, box, rng)
    p = Packing.from_endpoints(ep, D)
    f = local_fields(p, 0.02, height=box)
    cell_vol = 0.02**3
    total = f.phi.sum() * cell_vol / (math.pi * D * D / 4)
    assert total == pytest.approx(3000 * 0.03, rel=1e-9)  # cubes tile space: clipped lengths add up exactly
    occupied = f.n > 20
    assert abs(np.average(f.S_vertical[occupied])) < 0.03  # isotropic: ⟨P2(cos θ)⟩ = 0
    # about the local director a finite sample is always ordered a bit, ~ 1/sqrt(n)
    assert 0.05 < np.mean(f.S_director[occupied]) < 0.4
    th, _ = orientations(p)
    assert np.cos(th).mean() == pytest.approx(0.5, abs=0.02)


def test_sphere_cells():
    ep = np.array([[[0.0, 0.0, 0.0], [0.03, 0.03, 0.03]]])
    p = Packing.from_endpoints(ep, D)
    l_s = 0.01
    f = local_fields(p, l_s, shape="sphere", height=0.03)
    c = f.origin + 1.5 * l_s  # centre of cell (1, 1, 1) lies on the rod
    assert np.allclose(c, 0.015)
    assert f.phi[1, 1, 1] == pytest.approx(l_s * math.pi * D * D / 4 / (math.pi / 6 * l_s**3))


def test_correlation_white_noise_and_exponential():
    rng = np.random.default_rng(3)
    noise = rng.normal(size=(24, 24, 24))
    mask = np.ones_like(noise, bool)
    r, c = correlation(noise, noise, mask, 1.0)
    assert c[0] == pytest.approx(1.0)
    assert np.all(np.abs(c[1:8]) < 0.05)
    assert correlation_length(r, c) < 1.0
    # an exponential curve: ξ is recovered exactly by the 1/e crossing
    rr = np.arange(10.0)
    assert correlation_length(rr, np.exp(-rr / 2.5)) == pytest.approx(2.5, rel=0.05)
    with pytest.raises(ValueError, match="mask"):
        correlation(noise, noise, np.zeros_like(mask), 1.0)


def test_packing_io_roundtrip(tmp_path):
    rng = np.random.default_rng(4)
    ep = _random_rods(10, 0.03, 0.1, rng)
    p = Packing.from_endpoints(ep, D, 0.15, {"seed": 4})
    q = load_packing(p.save(tmp_path / "p.npz"))
    np.testing.assert_array_equal(q.endpoints, ep)
    assert q.container_diameter == 0.15 and q.meta["seed"] == 4
    q2 = load_packing(p.to_csv(tmp_path / "p.csv"))
    np.testing.assert_allclose(q2.endpoints, ep, rtol=1e-8)
    assert q2.diameter == D
    # 6-column endpoint CSV with a header line needs diameter=
    np.savetxt(tmp_path / "e.csv", ep.reshape(-1, 6), delimiter=",", header="x0,y0,z0,x1,y1,z1", comments="")
    with pytest.raises(ValueError, match="diameter"):
        load_packing(tmp_path / "e.csv")
    q3 = load_packing(tmp_path / "e.csv", diameter=D)
    assert q3.n_rods == 10 and np.isnan(q3.container_diameter)
    # polylines (CT centerlines): fields still work
    f = local_fields(q2, 0.02)
    assert f.mask.any()
    with pytest.raises(ValueError, match="offsets"):
        Packing(np.zeros((3, 3)), np.array([0, 1, 3]), D)
    with pytest.raises(ValueError, match="l_s"):
        local_fields(p, -1.0)


def test_philipse_limits():
    assert philipse_contact_number(0.64, 0.0) == pytest.approx(8 * 0.64)  # spheres: ⟨c⟩ = 8φ
    assert philipse_contact_number(0.05, 1000) == pytest.approx(2 * 0.05 * 1000, rel=0.01)  # ⟨c⟩ → 2φα
