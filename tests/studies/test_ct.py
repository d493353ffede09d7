"""CT segmentation of rod piles (thesis §4.6) validated on synthetic tomograms with known rods.

Default suite: the geometry convention on single rods, contacts (crossing, parallel, several rods touching one),
input checks, file round trips and the CLI, and the issue's acceptance criteria on a small MuJoCo pile (60 rods).
The full validation — ≥ 300 rods from ``generate_packing`` — is ``slow`` (numbers in docs/ct.md).
"""

from __future__ import annotations

import argparse
import math

import numpy as np
import pytest

from hairbrush_env.studies.ct import (
    VOXELS_PER_DIAMETER,
    Tomogram,
    load_tomogram,
    match_rods,
    segment_rods,
    synthetic_tomogram,
)
from hairbrush_env.studies.rod_fields import local_fields
from hairbrush_env.studies.rod_pile import Packing, generate_packing, load_packing

D = 0.002  # rod diameter [m]


def _axis(ep):
    u = ep[:, 1] - ep[:, 0]
    return u / np.linalg.norm(u, axis=1, keepdims=True)


def _segment(p: Packing, **kw) -> Packing:
    return segment_rods(synthetic_tomogram(p, seed=kw.pop("seed", 0)), diameter=p.diameter, **kw)


def _entanglement_error(truth: Packing, seg: Packing, l_s: float, spacing: float) -> tuple[float, float, int]:
    """Mean e of the segmented rods vs ground truth, same grid and mask (the truth's pile height)."""
    from hairbrush_env.studies.rod_pile import pile_height

    h = pile_height(truth)
    seg = Packing.from_endpoints(seg.endpoints, seg.diameter, truth.container_diameter)
    ft = local_fields(truth, l_s, spacing=spacing, height=h)
    fs = local_fields(seg, l_s, spacing=spacing, height=h)
    et, es = ft.means()["e"], fs.means()["e"]
    return et, es, int(ft.mask.sum())


# ------------------------------------------------------------------------------------- geometry, contacts


def test_voxel_world_convention_single_tilted_rod():
    rng = np.random.default_rng(5)
    for _ in range(3):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        c = rng.uniform(-0.01, 0.01, size=3)
        ep = np.array([[c - 6 * D * u, c + 6 * D * u]])
        p = Packing.from_endpoints(ep, D)
        tom = synthetic_tomogram(p)
        assert tom.voxel_size == pytest.approx(D / VOXELS_PER_DIAMETER)
        # voxel centres: origin + (ijk + ½)·voxel; the brightest voxel lies on the rod axis
        ijk = np.unravel_index(np.argmax(tom.volume), tom.volume.shape)
        x = tom.world(ijk)
        t = np.clip((x - ep[0, 0]) @ u, 0, 12 * D)
        assert np.linalg.norm(x - (ep[0, 0] + t * u)) < 0.5 * D
        seg = segment_rods(tom, diameter=D)
        assert seg.n_rods == 1
        m = match_rods(p, seg, tol=0.3)
        assert m.recovery == 1.0, m.end_error / D
        assert m.angle_error[0] < 1.0
        # the origin is honoured: shifting it shifts the rods
        shifted = segment_rods(
            tom.volume, tom.voxel_size, D, origin=tom.origin + np.array([0.01, -0.02, 0.06])
        )
        np.testing.assert_allclose(shifted.endpoints - [0.01, -0.02, 0.06], seg.endpoints, atol=1e-12)


def test_touching_rods_are_separated():
    r = D / 2
    L = 16 * D
    ep = np.array([
        # a "+" of two rods touching at the crossing (axes 1 d apart)
        [[-L / 2, 0, 0], [L / 2, 0, 0]],
        [[0, -L / 2, D], [0, L / 2, D]],
        # two parallel rods side by side, touching along their length, staggered by 5 d
        [[-L / 2, 0.06, 0], [L / 2, 0.06, 0]],
        [[-L / 2 + 5 * D, 0.06 + 2 * r, 0], [L / 2 + 5 * D, 0.06 + 2 * r, 0]],
        # one long rod crossed (touching) by four others: its skeleton is cut four times and must be repaired
        [[-L / 2, -0.06, 0], [L / 2, -0.06, 0]],
        *[[[x, -0.06 - L / 3, s * D], [x + 2 * D, -0.06 + L / 3, s * D]] for x, s in ((-0.012, 1), (-0.004, -1),
                                                                                    (0.004, 1), (0.012, -1))],
    ])  # fmt: skip
    p = Packing.from_endpoints(ep, D)
    seg = _segment(p)
    m = match_rods(p, seg)
    assert seg.n_rods == p.n_rods
    assert m.recovery == 1.0, m.end_error / D
    assert np.max(m.angle_error) < 2.0


def test_match_rods_is_order_and_orientation_free():
    rng = np.random.default_rng(1)
    c = rng.uniform(0, 0.05, size=(20, 3))
    u = _axis(rng.normal(size=(20, 2, 3)))
    ep = np.stack([c - 5 * D * u, c + 5 * D * u], axis=1)
    truth = Packing.from_endpoints(ep, D)
    perm = rng.permutation(20)
    flipped = ep[perm][:, ::-1]
    flipped[:3] += 2 * D  # three rods moved by 2·√3 d: not recovered at tol = 1 d
    m = match_rods(truth, Packing.from_endpoints(flipped, D))
    assert m.recovered.sum() == 17
    ok = m.pairs[m.recovered]
    assert np.all(perm[ok[:, 1]] == ok[:, 0])
    assert np.all(m.angle_error[m.recovered] < 1e-4)  # degrees (arccos near 1 is imprecise)


# -------------------------------------------------------------------------------------------- bad input


def test_bad_input_raises_naming_the_argument():
    p = Packing.from_endpoints(np.array([[[0, 0, 0], [10 * D, 0, 0]]]), D)
    tom = synthetic_tomogram(p)
    with pytest.raises(ValueError, match="voxel_size"):
        synthetic_tomogram(p, -1.0)
    with pytest.raises(ValueError, match="noise"):
        synthetic_tomogram(p, noise=-0.1)
    with pytest.raises(ValueError, match="packing"):
        synthetic_tomogram(np.zeros((1, 2, 3)))
    with pytest.raises(ValueError, match="volume"):
        segment_rods(np.zeros((4, 4)), 1e-3, D)
    with pytest.raises(ValueError, match="volume"):
        segment_rods(np.full((8, 8, 8), np.nan), 1e-3, D)
    with pytest.raises(ValueError, match="voxel_size"):
        segment_rods(tom.volume, None, D)
    with pytest.raises(ValueError, match="voxel_size"):
        segment_rods(tom.volume, D, D)  # 1 voxel per diameter: too coarse
    with pytest.raises(ValueError, match="diameter"):
        segment_rods(tom, diameter=0.0)
    with pytest.raises(ValueError, match="merge_angle"):
        segment_rods(tom, diameter=D, merge_angle=120)
    with pytest.raises(ValueError, match="core"):
        segment_rods(tom, diameter=D, core=1.5)
    with pytest.raises(ValueError, match="origin"):
        segment_rods(tom, diameter=D, origin=(0, 0))
    with pytest.raises(ValueError, match="volume"):
        segment_rods(np.zeros((8, 8, 8)), 1e-3, 4e-3)
    with pytest.raises(ValueError, match="path"):
        load_tomogram(__file__.replace(".py", ".missing.npy"))


# --------------------------------------------------------------------------------------- files and CLI


@pytest.mark.parametrize("suffix", [".npy", ".tif"])
def test_tomogram_round_trip(tmp_path, suffix):
    vol = np.random.default_rng(0).random((5, 6, 7)).astype(np.float32)
    tom = Tomogram(vol, 1e-4, np.array([0.1, -0.2, 0.3]), {"note": "x"})
    path = tom.save(tmp_path / f"v{suffix}")
    back = load_tomogram(path)
    np.testing.assert_array_equal(back.volume, vol)  # .tif is stored z, y, x and transposed back
    assert back.voxel_size == tom.voxel_size
    np.testing.assert_array_equal(back.origin, tom.origin)
    over = load_tomogram(path, voxel_size=2e-4, origin=(0, 0, 0))
    assert over.voxel_size == 2e-4 and not over.origin.any()
    (tmp_path / f"v{suffix}").with_suffix(".json").unlink()
    with pytest.raises(ValueError, match="voxel_size"):
        load_tomogram(path)
    # without a sidecar: npy is read as x, y, z and TIFF as z, y, x (both give the x, y, z volume back here)
    np.testing.assert_array_equal(load_tomogram(path, voxel_size=1e-4).volume, vol)
    swapped = load_tomogram(path, voxel_size=1e-4, axes="zyx" if suffix == ".npy" else "xyz")
    np.testing.assert_array_equal(swapped.volume, vol.transpose(2, 1, 0))
    with pytest.raises(ValueError, match="axes"):
        load_tomogram(path, voxel_size=1e-4, axes="yxz")


def test_cli_segment_output_feeds_fields(tmp_path):
    from hairbrush_env.commands.rodpile import register
    from hairbrush_env.commands.rodpile_segment import add_segment_parser

    # eight horizontal rods stacked 1.5 d apart (0.5 d gaps), each turned by 22.5°: crossings without contact
    L = 12 * D
    ang = np.arange(8) * np.pi / 8
    u = np.column_stack([np.cos(ang), np.sin(ang), np.zeros(8)])
    c = np.column_stack([np.zeros((8, 2)), (1 + 1.5 * np.arange(8)) * D])
    truth = Packing.from_endpoints(np.stack([c - u * L / 2, c + u * L / 2], axis=1), D, 0.04)
    truth.save(tmp_path / "truth.npz")
    parser = argparse.ArgumentParser()
    rsub = parser.add_subparsers(dest="action")
    add_segment_parser(rsub)
    args = parser.parse_args(["tomogram", str(tmp_path / "truth.npz"), "--out", str(tmp_path / "vol.tif")])
    assert args.func(args) == 0
    args = parser.parse_args([
        "segment", str(tmp_path / "vol.tif"), "--diameter", str(D), "--truth", str(tmp_path / "truth.npz"),
        "--out", str(tmp_path / "seg.npz"), "--quiet",
    ])  # fmt: skip
    assert args.func(args) == 0
    seg = load_packing(tmp_path / "seg.npz")
    assert seg.container_diameter == pytest.approx(0.04)  # from the synthetic tomogram's sidecar
    assert match_rods(truth, seg).recovery == 1.0
    assert load_packing(tmp_path / "seg.csv").n_rods == seg.n_rods
    root = argparse.ArgumentParser()
    register(root.add_subparsers(dest="command"))  # the real `hairbrush rodpile fields`
    fa = root.parse_args(["rodpile", "fields", str(tmp_path / "seg.npz"), "--ls", "5", "--out",
                          str(tmp_path / "fields"), "--quiet"])  # fmt: skip
    assert fa.func(fa) == 0
    assert (tmp_path / "fields" / "fields_seg.npz").exists()
    with pytest.raises(SystemExit) as exc:  # refused while parsing, before the volume is read
        parser.parse_args(["segment", str(tmp_path / "vol.tif"), "--diameter", "-1", "--out",
                           str(tmp_path / "x.npz"), "--quiet"])  # fmt: skip
    assert exc.value.code == 2


# ------------------------------------------------------------------------------------ acceptance criteria


def _acceptance(truth: Packing, seg: Packing, l_s: float, spacing: float):
    m = match_rods(truth, seg)
    et, es, cells = _entanglement_error(truth, seg, l_s, spacing)
    rel = abs(es - et) / et
    print(
        f"\n{truth.n_rods} rods (α = {truth.aspect_ratio:.0f}) → {seg.n_rods} segments; recovered "
        f"{m.recovered.sum()}/{m.n_truth} = {m.recovery:.1%}; median angle error {m.median_angle_error:.2f}°; "
        f"e mean {es:.4g} vs truth {et:.4g} ({cells} cells of {l_s / truth.diameter:g} d): {rel:.1%}"
    )
    return m, rel, cells


def test_small_mujoco_pile_meets_the_issue_criteria():
    # 60 rods (α = 16) in a 1.5 L container: a cheap generate_packing (no jostling) with real contacts.
    L = 16 * D
    truth = generate_packing(60, L, D, container_diameter=1.5 * L, seed=2, jostle=False, batch_size=20,
                             progress=False)  # fmt: skip
    seg = _segment(truth, container_diameter=truth.container_diameter)
    # the pile is ~10 d tall: fields on 5 d cells every 2.5 d (10 d cells would leave ≤ 1 cell in the mask)
    m, rel, cells = _acceptance(truth, seg, 5 * D, 2.5 * D)
    assert cells >= 20
    assert m.recovery >= 0.9
    assert m.median_angle_error < 2.0
    assert rel < 0.10


@pytest.mark.slow
def test_validation_300_rod_pile():
    # the docs/ct.md numbers: 300 rods, α = 16, 1.5 L container (a 3-D pile ~31 d tall), seed 1, default tomogram
    L = 0.05
    d = L / 16
    truth = generate_packing(300, L, d, container_diameter=1.5 * L, seed=1, progress=False)
    tom = synthetic_tomogram(truth)
    seg = segment_rods(tom, diameter=d, container_diameter=truth.container_diameter)
    assert truth.n_rods >= 300
    m, rel, _cells = _acceptance(truth, seg, 10 * d, 10 * d)  # `hairbrush rodpile fields` defaults
    assert m.recovery >= 0.9
    assert m.median_angle_error < 2.0
    assert rel < 0.10
    _m5, rel5, _ = _acceptance(truth, seg, 5 * d, 2.5 * d)
    assert rel5 < 0.10
    assert math.isfinite(m.median_angle_error)
