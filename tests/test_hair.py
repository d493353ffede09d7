"""Wigs (:mod:`hairbrush_env.hair`): presets, validation, ground-truth topology, and 1 s compile-and-step runs."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")  # before the first `import mujoco` of the session (rendering tests)

import mujoco
import numpy as np
import pytest

from hairbrush_env import hair, rods
from hairbrush_env.assets import load_part


def _wig_model(wig: hair.WigConfig, timestep: float = 0.01) -> tuple[mujoco.MjModel, hair.WigLayout]:
    spec = mujoco.MjSpec()
    rods.configure_rod_options(spec, timestep=timestep)
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_REFSAFE
    spec.attach(load_part("head"), frame=spec.worldbody.add_frame(pos=[0.62, 0.0, 0.0]), prefix="head/")
    layout = hair.add_wig(spec, wig, parent_body="head/scalp", root_offset=spec.site("head/scalp").pos)
    return spec.compile(), layout


def test_presets_span_straight_to_coily() -> None:
    names = list(hair.PRESETS)
    assert len(names) >= 5 and "straight" in names and "curly" in names
    rc = [w.curliness for w in hair.PRESETS.values()]
    assert rc[0] == 0.0 and rc[-1] >= 0.75 and rc == sorted(rc)
    assert len({w.length for w in hair.PRESETS.values()}) == len(names)
    assert all(w.name == n for n, w in hair.PRESETS.items())
    assert hair.get_wig("curly") is hair.PRESETS["curly"]
    assert hair.PRESETS[hair.DEFAULT_WIG].n_strands >= 24


def test_unknown_preset_lists_names() -> None:
    with pytest.raises(ValueError, match="straight") as err:
        hair.get_wig("afro-deluxe")
    assert "wig" in str(err.value)


def test_wig_lists_mix_names_and_sets() -> None:
    """``--wigs all,held_out`` is every preset and every held-out wig, once each, in order."""
    names = hair.wig_names("curly,all,held_out")
    assert names == ["curly", *[w for w in hair.PRESETS if w != "curly"], *hair.HELD_OUT_WIGS]
    with pytest.raises(ValueError, match="unknown wig held_out_curly"):
        hair.wig_names("all,held_out_curly", held_out=False)


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"strand_radius": -1e-3}, "strand_radius"),
        ({"curliness": 1.5}, "curliness"),
        ({"curliness": -0.1}, "curliness"),
        ({"curl_radius": -0.01}, "curl_radius"),
        ({"length": 0.0}, "length"),
        ({"n_strands": 24, "n_triples": 1}, "n_triples"),
        ({"n_strands": 1}, "n_strands"),
        ({"edges_per_turn": 3}, "edges_per_turn"),
        ({"young": -5.0}, "young"),
        ({"handedness": 0}, "handedness"),
        ({"curliness": 0.9, "curl_radius": 0.001}, "curl_radius"),
        ({"rest_splay": 4.0}, "rest_splay"),
        ({"group_rows": 0}, "group_rows"),
        ({"rest_splay": 0.5, "rod_kind": "flex"}, "rest_splay"),
        ({"quadratic_damping": -1e-4}, "quadratic_damping"),
        ({"drag_density": -1.0}, "drag_density"),
        ({"drag_density": 1e3, "rod_kind": "flex", "rest_splay": 0.0}, "drag_density"),
        ({"quadratic_damping": 1e-4, "rod_kind": "flex", "rest_splay": 0.0}, "quadratic_damping"),
        ({"self_collision": 1}, "self_collision"),
        ({"root_run": -0.1}, "root_run"),
        ({"root_run": 1.5}, "root_run"),
        ({"root_run": float("nan")}, "root_run"),
        ({"root_run_min": -0.01}, "root_run_min"),
        ({"root_run_min": 0.5, "length": 0.2}, "root_run_min"),
    ],
)
def test_bad_config_names_field(changes: dict, field: str) -> None:
    with pytest.raises(ValueError, match=f"WigConfig.{field}"):
        hair.WigConfig(**changes)


def test_wisp_scaling() -> None:
    w = hair.WigConfig()
    # 0.8 mm wisp = (800/40)² = 400 hairs; B_w = κ n B_h -> E_w = κ E_h / 400 (κ = 1: uncoupled hairs).
    assert hair.wisp_young(8e-4, cohesion=1.0) == pytest.approx(4e9 / 400)
    assert w.young_modulus == pytest.approx(hair.WISP_COHESION * 4e9 / 400)
    assert hair.wave1_wig(w).young_modulus == pytest.approx(hair.WAVE1_COHESION * 4e9 / 400)
    assert w.young_modulus == pytest.approx(1.25e8)
    assert hair.WigConfig(young=2e8).young_modulus == 2e8
    # every preset resolves its curls with >= 8 edges per turn (chain helical spring within 10 %, test_rods)
    for wig in hair.PRESETS.values():
        assert wig.n_edges <= 32
        assert wig.curliness == 0 or wig.n_edges >= 8 * wig.turns


@pytest.mark.parametrize("name", list(hair.PRESETS))
def test_layout_ground_truth_links(name: str) -> None:
    wig = hair.PRESETS[name]
    lay = hair.wig_layout(wig)
    assert len(lay.curves) == wig.n_strands and all(c.shape == (wig.n_edges + 1, 3) for c in lay.curves)
    assert sum(len(g) for g in lay.groups) == wig.n_strands
    assert sum(len(g) == 3 for g in lay.groups) == wig.n_triples
    # every strand's rest length is the configured length (uniform edges on the helix)
    for c in lay.curves:
        assert rods.polyline_length(c) == pytest.approx(wig.length, rel=1e-9)
    # entwined pairs link as many times as they share turns (open curves lose < 1 turn at the ends)
    lk = np.abs(lay.pair_link)
    # chords are shorter than the arcs they cut: at 4–5 edges per turn the polygon of the configured length has up
    # to ~13 % more turns than the smooth helix (hair.layout._polygon_turns); the links follow the polygon
    assert lay.turns == pytest.approx(wig.turns, rel=0.15) and lay.turns >= wig.turns
    assert np.all(lk <= lay.turns + 1e-9) and np.all(lk >= lay.turns - 1.0)
    assert np.all(np.sign(lay.pair_link[lk > 0.5]) == -wig.handedness)  # one chirality for all (homochiral)
    # different groups: separated and unlinked
    assert lay.min_cross_distance >= 2 * wig.strand_radius + wig.root_gap
    assert lay.max_cross_link < 0.4
    d = hair.min_distance_matrix(lay.curves)
    assert d[np.triu_indices(wig.n_strands, 1)].min() > 2 * wig.strand_radius


@pytest.mark.parametrize("name", list(hair.PRESETS))
def test_preset_hangs_at_the_contact_step_without_sinking(name: str) -> None:
    """Menagerie-style: every preset hangs 1 s from its built (entwined) state at the 1 ms contact step without
    warnings/NaN and keeps its length within 0.5 %. The prestress (``rest_splay``) presses the strands of a pair
    together, but, mass-scaled (``WigConfig.mass_scale``), they never come closer than the sum of radii (measured
    ≥ 1.29; at the 10 ms free step the same strands sank to 0.01, which is why the preparation runs at the contact
    step). The links change continuously as the prestressed strands turn: the topology is checked after the shake,
    in the scene tests."""
    wig = hair.PRESETS[name]
    model, layout = _wig_model(wig, timestep=1e-3)
    data = mujoco.MjData(model)
    ent = hair.Entanglement(model, layout)
    closest = np.inf
    for k in range(1000):
        mujoco.mj_step(model, data)
        if k % 10 == 9:
            d = hair.min_distance_matrix(ent.curves(data))
            closest = min(closest, float(d[np.triu_indices(wig.n_strands, 1)].min()))
    assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))
    counts = {mujoco.mjtWarning(i).name: int(w.number) for i, w in enumerate(data.warning) if w.number}
    assert not counts, counts
    for v in ent.views:
        assert v.length(data) == pytest.approx(wig.length, rel=5e-3)
    assert closest > 2.0 * wig.strand_radius


def test_entanglement_at_rest_equals_ground_truth() -> None:
    wig = hair.PRESETS["curly"].replace(n_strands=8, n_triples=0)
    model, layout = _wig_model(wig)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert hair.entanglement(model, data, layout) == pytest.approx(layout.n_links, rel=1e-9)
    assert layout.n_links == pytest.approx(np.abs(layout.pair_link).sum())


def test_link_by_depth_spreads_each_pairs_link_along_it() -> None:
    """At rest the bands hold all of the built-in link (Σ|Lk|), none of it above the roots or below the free ends,
    and a band edge moved past the strands' end changes nothing."""
    wig = hair.PRESETS["curly"].replace(n_strands=8, n_triples=0)
    model, layout = _wig_model(wig)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    meter = hair.Entanglement(model, layout)
    bands = meter.link_by_depth(data, [0.0, 0.02, 0.05, 1.0])
    assert bands.sum() == pytest.approx(np.abs(layout.pair_link).sum(), rel=1e-9)
    assert np.all(bands > 0.0)
    per_pair = meter.pair_link_by_depth(data, [0.0, 0.02, 0.05, 1.0])
    np.testing.assert_allclose(per_pair.sum(axis=1), meter.built_in_sign * meter.pair_links(data), rtol=1e-9)
    np.testing.assert_allclose(per_pair.sum(axis=0), bands)
    deeper = meter.link_by_depth(data, [0.0, 0.02, 0.05, 5.0])
    np.testing.assert_allclose(deeper, bands)
    with pytest.raises(ValueError, match="depths"):
        meter.link_by_depth(data, [0.05, 0.02])


def test_self_collision_lets_a_strand_touch_its_own_segments() -> None:
    """Off (the default), every non-adjacent segment pair of a strand is excluded from collision; on, none is."""
    wig = hair.PRESETS["curly"].replace(n_strands=4, n_triples=0)
    counts = []
    for on in (False, True):
        spec = mujoco.MjSpec()
        hair.add_wig(spec, wig.replace(self_collision=on), parent_body=spec.worldbody)
        counts.append(spec.compile().nexclude)
    n = wig.n_edges
    assert counts == [4 * (n - 1) * (n - 2) // 2, 0]


def test_group_rows_sets_the_depth_of_the_curtain() -> None:
    """One row of groups: every group axis in the plane x = 0, the groups side by side along the brush's rows."""
    wig = hair.PRESETS["curly"].replace(n_strands=10, n_triples=0, group_rows=1, min_spacing=0.04)
    lay = hair.wig_layout(wig)
    np.testing.assert_allclose(lay.axes[:, 0], 0.0)
    np.testing.assert_allclose(np.diff(np.sort(lay.axes[:, 1])), lay.spacing)
    assert lay.spacing == pytest.approx(0.04) and lay.max_cross_link < 0.4


def test_root_run_spreads_the_pairs_helix_phases() -> None:
    """``root_run``: each group hangs straight below its roots for its own part of ``root_run`` pitches, then curls;
    the roots stay where they were (across the tines), the strands keep their length, and at one height below the
    roots the pairs' helix phases differ, where without runs they are all equal (docs/detangling.md, *Where the comb
    goes in*)."""
    base = hair.PRESETS["curly"].replace(n_triples=0)
    plain, spread = hair.wig_layout(base), hair.wig_layout(base.replace(root_run=0.5))
    np.testing.assert_allclose(spread.roots, plain.roots)
    runs = [base.replace(root_run=0.5).root_run_length(g) for g in range(base.n_groups)]
    assert runs[0] == 0.0 and 0.0 < max(runs) < 0.5 * base.pitch
    assert len({round(r, 6) for r in runs}) == base.n_groups  # every group its own run
    for g, members in enumerate(spread.groups):
        for s in members:
            curve = spread.curves[s]
            assert np.linalg.norm(np.diff(curve, axis=0), axis=1).sum() == pytest.approx(
                base.length, rel=0.01
            )
            straight = curve[-curve[:, 2] <= runs[g] + 1e-12]
            np.testing.assert_allclose(straight[:, :2] - curve[0, :2], 0.0, atol=1e-12)  # hangs straight down

    def phases(lay: hair.WigLayout, depth: float) -> np.ndarray:
        """Angle of each pair's first strand about the pair axis where it first comes down to ``depth``."""
        out = []
        for (i, _), axis in zip(lay.pairs, lay.axes, strict=True):
            c = lay.curves[i]
            k = int(np.nonzero(-c[:, 2] >= depth)[0][0])
            out.append(np.arctan2(c[k, 1] - axis[1], c[k, 0] - axis[0]) % np.pi)
        return np.array(out)

    assert np.ptp(phases(plain, 0.03)) < 0.3  # one phase (to an edge's turn, 2π/8)
    assert np.ptp(phases(spread, 0.03)) > 0.6 * np.pi
    assert spread.max_cross_link < 0.4
    np.testing.assert_allclose(np.abs(spread.pair_link), np.abs(plain.pair_link), rtol=0.05)
    # root_run_min: every group straight at least that far, the spread on top
    based = base.replace(root_run=0.5, root_run_min=0.012)
    assert [based.root_run_length(g) for g in range(base.n_groups)] == pytest.approx(
        [0.012 + r for r in runs]
    )
    based_layout = hair.wig_layout(based)
    for members in based_layout.groups:
        for s in members:
            top = based_layout.curves[s]
            top = top[-top[:, 2] <= 0.012]
            np.testing.assert_allclose(top[:, :2] - top[0, :2], 0.0, atol=1e-12)


@pytest.mark.parametrize("name", ["wavy", "curly", "coily"])
def test_curtain_roots_lie_across_the_tines(name: str) -> None:
    """A comb tine (along x) parts two strands only by their y. In a one-row curtain every group's roots are spread
    along y: a pair's two roots 2R apart at the same x, a triple's three at distinct y. With pairs whose roots lay
    along x (the checkerboard's phase 0) a full stroke left them 2.65–2.88 of their 3.07 link, the pairs across
    the curtain 0.63–0.72 (curly, seed 0; docs/detangling.md, *Root orientation*)."""
    wig = hair.PRESETS[name]
    lay = hair.wig_layout(wig)
    assert wig.group_rows == 1
    for members in lay.groups:
        roots = lay.roots[list(members)]
        y = np.sort(roots[:, 1])
        if len(members) == 2:
            assert abs(roots[0, 0] - roots[1, 0]) < 1e-9
            assert y[1] - y[0] == pytest.approx(2.0 * wig.curl_radius)
        else:
            assert np.diff(y).min() > 0.8 * wig.curl_radius
    # with several group rows the checkerboard stays: some pairs' roots lie along x, others along y
    deep = hair.wig_layout(wig.replace(group_rows=2))
    along = [np.abs(np.diff(deep.roots[list(m)], axis=0))[0, :2] for m in deep.groups if len(m) == 2]
    assert any(dx < 1e-9 for dx, _ in along) and any(dy < 1e-9 for _, dy in along)
    assert deep.max_cross_link < 0.4


def test_entanglement_sees_link_made_between_any_two_strands() -> None:
    """A brush that winds strands of different groups round each other must not look like progress: link between
    non-entwined strands above the census threshold counts (issue 21)."""
    wig = hair.PRESETS["curly"].replace(n_strands=8, n_triples=0)
    model, layout = _wig_model(wig)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    ent = hair.Entanglement(model, layout)
    mat = ent.link_matrix(data)
    np.testing.assert_allclose(mat, mat.T)
    np.testing.assert_allclose(mat[layout.pairs[:, 0], layout.pairs[:, 1]], layout.pair_link, rtol=1e-9)
    assert ent.breakdown(data) == pytest.approx((layout.n_links, 0.0))  # at rest, groups are unlinked
    # Wind strand 0 round a strand of another group: read the centerlines through a stand-in of curve_array.
    curves = ent.curve_array(data)
    other = next(s for s in range(wig.n_strands) if not any(s in p and 0 in p for p in layout.pairs.tolist()))
    axis = curves[other].mean(axis=0)
    t = np.linspace(0.0, 1.0, curves.shape[1])
    curves[0] = np.column_stack(
        [
            axis[0] + 0.004 * np.cos(6 * np.pi * t),
            axis[1] + 0.004 * np.sin(6 * np.pi * t),
            curves[other][:, 2],
        ]
    )
    ent.curve_array = lambda _data: curves
    entwined, made = ent.breakdown(data)
    assert made > hair.CROSS_LINK_THRESHOLD and ent(data) == pytest.approx(entwined + made)


def test_state_cache_roundtrip(tmp_path) -> None:
    wig = hair.PRESETS["wavy"].replace(n_strands=4, n_triples=0)
    model, _ = _wig_model(wig)
    data = mujoco.MjData(model)
    for _ in range(20):
        mujoco.mj_step(model, data)
    state = hair.get_state(model, data)
    h = hair.StateCache.model_hash(model)
    hair.StateCache(tmp_path).put(wig, 3, h, state)
    fresh = hair.StateCache(tmp_path)  # another process: reads the file
    got = fresh.get(wig, 3, h)
    assert got is not None and np.array_equal(got, state)
    assert fresh.get(wig, 4, h) is None and fresh.get(wig.replace(name="other"), 3, h) is None
    # the state includes the rods' plastic reference frames
    assert mujoco.mj_stateSize(model, hair.STATE_SPEC) > mujoco.mj_stateSize(
        model, mujoco.mjtState.mjSTATE_PHYSICS
    )


def test_shake_acceleration_is_seeded() -> None:
    wig = hair.PRESETS["curly"]
    t = np.linspace(0, wig.shake_seconds, 50)
    a0, a1, b = (hair.shake_acceleration(wig, s, t) for s in (0, 0, 1))
    assert np.array_equal(a0, a1) and not np.allclose(a0, b)
    assert np.allclose(a0[0], 0) and np.allclose(a0[-1], 0, atol=1e-9)  # smooth start/end


@pytest.mark.parametrize(("splay", "linked"), [(0.0, True), (np.pi / 2, False)])
def test_stress_free_state_of_an_entwined_pair(splay: float, linked: bool) -> None:
    """What holds the link (docs/detangling.md): with stress-free entwined rest curves the entwined state is the
    pair's only stress-free state; with the rest shape splayed, strands free to pass through each other (no contact,
    no gravity) relax to two unlinked helices, so entwining is a prestressed state that combing can release."""
    wig = hair.PRESETS["curly"].replace(n_strands=2, n_triples=0, length=0.16, rest_splay=splay)
    spec = mujoco.MjSpec()
    rods.configure_rod_options(spec, timestep=1e-3)
    spec.option.gravity = [0.0, 0.0, 0.0]
    scalp = spec.worldbody.add_body(name="scalp", pos=[0.0, 0.0, 1.0])
    layout = hair.add_wig(spec, wig, parent_body=scalp, root_offset=[0.0, 0.0, 0.0], hair_hair=False)
    model = spec.compile()
    data = mujoco.MjData(model)
    for _ in range(4000):
        mujoco.mj_step(model, data)
    link = abs(hair.Entanglement(model, layout).pair_links(data)[0])
    turns = abs(layout.pair_link[0])
    assert turns > 1.5
    if linked:
        assert link == pytest.approx(turns, abs=0.05)
    else:
        assert link < 0.25  # measured: 1.60 built in, 0.13 left at ψ = π/2 (0.20 at π/3)


def test_still_entwined_counts_pairs_wound_in_their_built_in_sense() -> None:
    """Combed-apart neighbours keep a small link of the other sense; only pairs still wound as built count."""
    wig = hair.PRESETS["curly"].replace(n_strands=8, n_triples=0)
    model, layout = _wig_model(wig)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    ent = hair.Entanglement(model, layout)
    assert ent.still_entwined(data) == len(layout.pairs)
    curves = ent.curve_array(data)
    b = layout.pairs[0][1]
    curves[b] = curves[b] + np.array([0.0, 0.3, 0.0])  # pair 0 pulled apart: no link left
    ent.curve_array = lambda _data: curves
    assert abs(ent.pair_links(data)[0]) < 0.05
    assert ent.still_entwined(data) == len(layout.pairs) - 1
