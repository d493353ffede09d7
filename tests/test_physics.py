"""Physics versions (``hairbrush_env.physics``): what v1 sets, and studies that refuse to mix versions."""

from __future__ import annotations

import dataclasses

import pytest

from hairbrush_env.brush import get_brush
from hairbrush_env.envs import (
    ENV_IDS,
    V1_PHYSICS,
    V2_PHYSICS,
    V3_PHYSICS,
    V4_PHYSICS,
    V5_PHYSICS,
    V6_PHYSICS,
    V7_PHYSICS,
    V8_PHYSICS,
    V9_PHYSICS,
)
from hairbrush_env.hair import get_wig
from hairbrush_env.physics import PHYSICS, claim_physics, get_physics


def test_v0_is_the_defaults_and_v1_sets_contact_and_brush() -> None:
    v0, v1 = get_physics("v0"), get_physics("v1")
    assert v0.wig("curly") == get_wig("curly") and v0.env_kwargs() == {}
    assert v0.scene_config("curly").brush == get_brush("comb")
    custom = get_wig("coily").replace(name="mine", length=0.2)
    w = v1.wig(custom)
    assert (w.name, w.length, w.self_collision, w.friction) == ("mine", 0.2, True, 0.15)
    assert v1.scene_config("curly").brush == get_brush("soft_comb")
    assert ENV_IDS["HairBrush-v1"][2] == V1_PHYSICS == v1.env_kwargs()
    assert set(PHYSICS) == {"v0", "v1", "v2", "v3", "v4", "v5", "v6", "v7", "v8", "v9", "v10"}


def test_v2_is_v1_with_drag_instead_of_most_of_the_damping() -> None:
    """v2 keeps v1's contact model and comb and changes only the dissipation and the wisp stiffness; a custom wig keeps
    its own shape."""
    v1, v2 = get_physics("v1"), get_physics("v2")
    assert v2.brush == v1.brush == "soft_comb"
    assert {k: v2.wig_fields[k] for k in v1.wig_fields} == dict(v1.wig_fields)
    w = v2.wig(get_wig("coily").replace(name="mine", length=0.2))
    assert (w.name, w.length, w.curliness) == ("mine", 0.2, 0.8)
    assert w.damping == 0.002 and w.drag_density == 1000.0
    assert w.young_modulus == pytest.approx(16 / 12.5 * get_wig("coily").young_modulus)
    assert ENV_IDS["HairBrush-v2"][2] == ENV_IDS["HairBrushContinuous-v2"][2] == V2_PHYSICS == v2.env_kwargs()


def _pairs_parted_by_a_tine(version: str, wig: str) -> list[bool]:
    """For each entwined pair of ``wig`` under ``version``: whether a tine of the version's comb passes between the
    pair's two roots across the curtain (a tine runs along x, so only the roots' y tells), with room for the tine
    and a strand on both sides."""
    import numpy as np

    from hairbrush_env.hair import wig_layout

    v = get_physics(version)
    layout, brush = wig_layout(v.wig(wig)), get_brush(v.brush)
    tines = (np.arange(brush.columns) - 0.5 * (brush.columns - 1)) * brush.column_pitch
    room = brush.tine_radius + layout.wig.strand_radius
    out = []
    for i, j in layout.pairs:
        lo, hi = sorted(layout.roots[[i, j], 1])
        out.append(bool(np.any((tines > lo + room) & (tines < hi - room))))
    return out


def test_v3_is_v2_with_pairs_only_and_a_comb_spanning_them() -> None:
    """v3 changes only the groups (pairs, no triples) and the comb's width. Why: under v2 a triple's strand 0 hangs
    on the line of the tine through the group's axis, so its two pairs have no tine cleanly between their roots;
    the tine pushes strand 0 to one side and parts one of them, and the other keeps its link through every stroke
    (docs/detangling.md, *What holds the link under v2*). Under v3 every pair of every preset has a tine between
    its roots, and the wider comb spans the twelve-pair curtain."""
    v2, v3 = get_physics("v2"), get_physics("v3")
    assert {k: v3.wig_fields[k] for k in v2.wig_fields} == dict(v2.wig_fields)
    assert v3.wig_fields["n_triples"] == 0 and get_brush(v3.brush).columns == get_brush(v2.brush).columns + 2
    assert ENV_IDS["HairBrush-v3"][2] == ENV_IDS["HairBrushContinuous-v3"][2] == V3_PHYSICS == v3.env_kwargs()
    w = v3.wig(get_wig("curly"))
    assert (w.n_strands, w.n_groups) == (24, 12)
    v2_parted = _pairs_parted_by_a_tine("v2", "curly")
    assert [k for k, ok in enumerate(v2_parted) if not ok] == [0, 1, 3, 4]  # triples (0, 1, 2), (3, 4, 5)
    for name in ("wavy", "loose_curl", "curly", "tight_curl", "coily", "held_out_curly"):
        assert all(_pairs_parted_by_a_tine("v3", name)), name


def test_v4_is_v3_with_pairs_curling_from_different_depths() -> None:
    v3, v4 = get_physics("v3"), get_physics("v4")
    assert v4.brush == v3.brush
    assert dict(v4.wig_fields) == {**v3.wig_fields, "root_run": 0.5}
    assert ENV_IDS["HairBrush-v4"][2] == ENV_IDS["HairBrushContinuous-v4"][2] == V4_PHYSICS == v4.env_kwargs()
    assert all(_pairs_parted_by_a_tine("v4", "curly"))  # the roots stay across the tines


def test_v5_is_v4_with_a_straight_run_below_every_root() -> None:
    v4, v5 = get_physics("v4"), get_physics("v5")
    assert v5.brush == v4.brush
    assert dict(v5.wig_fields) == {**v4.wig_fields, "root_run_min": 0.012}
    assert ENV_IDS["HairBrush-v5"][2] == ENV_IDS["HairBrushContinuous-v5"][2] == V5_PHYSICS == v5.env_kwargs()
    for name in ("curly", "coily"):
        wig = v5.wig(name)
        runs = [wig.root_run_length(g) for g in range(wig.n_groups)]
        # every pair hangs straight for 12 mm at least, and the runs still spread over v4's half pitch
        assert min(runs) >= 0.012 and max(runs) - min(runs) > 0.4 * wig.pitch * 0.5, (name, runs)
        # a full stroke's tines go in 8 mm below the roots: above them every pair hangs straight, so holds no link
        assert min(runs) > get_physics("v5").scene_config(name).scalp_clearance + 0.003, name
    assert all(_pairs_parted_by_a_tine("v5", "curly"))  # the roots stay across the tines


def _root_middle_rest_deg(version: str, wig: str) -> float:
    """Largest rest angle of the middle root hinge (the one whose ±90° is the gimbal lock) over ``wig``'s strands."""
    import math

    import mujoco

    from hairbrush_env import rods
    from hairbrush_env.hair import add_wig

    cfg = get_physics(version).wig(wig)
    spec = mujoco.MjSpec()
    rods.configure_rod_options(spec, timestep=1e-3, kind="chain")
    add_wig(spec, cfg, parent_body=spec.worldbody)
    model = spec.compile()
    roots = [b for b in range(model.nbody) if model.body(b).name.endswith("_0") and model.body_jntnum[b] == 3]
    middle = [
        model.body_jntadr[b] + 1 for b in roots
    ]  # a body's hinges compose in order: the second is the middle
    return max(abs(math.degrees(float(model.qpos_spring[model.jnt_qposadr[j]]))) for j in middle)


def test_v6_is_v5_with_the_strands_of_a_pair_resting_apart_across_the_tines() -> None:
    """v6 turns each strand's stress-free shape by π/2 about its root (v5: π/3). A strand's own helix axis then sits
    2R (1 − cos ψ) across the tines from its partner's: 2R under v6, so the tine through the group axis lies between
    the two rest coils, not inside both (v5: R, the coils overlap by R across the tines and a full stroke gathers
    both onto that tine; docs/detangling.md, *HairBrush-v6*). Its roots hang straight, so the turn is a pure twist:
    v6 puts the twist hinge first, and no root rests near the hinges' lock (v5's middle hinge rests at 60°)."""
    import math

    v5, v6 = get_physics("v5"), get_physics("v6")
    assert v6.brush == v5.brush
    assert dict(v6.wig_fields) == {**v5.wig_fields, "rest_splay": math.pi / 2, "root_twist_first": True}
    assert ENV_IDS["HairBrush-v6"][2] == ENV_IDS["HairBrushContinuous-v6"][2] == V6_PHYSICS == v6.env_kwargs()
    for name in ("curly", "coily"):
        across = {
            v.name: 2 * v.wig(name).curl_radius * (1 - math.cos(v.wig(name).rest_splay)) for v in (v5, v6)
        }
        assert across["v5"] < 2 * v5.wig(name).curl_radius <= across["v6"] + 1e-12, name
    assert _root_middle_rest_deg("v5", "coily") == pytest.approx(60.0, abs=0.1)
    for name in ("wavy", "curly", "coily", "held_out_curly"):
        assert _root_middle_rest_deg("v6", name) < 25.0, name
    assert all(_pairs_parted_by_a_tine("v6", "curly"))  # the roots stay across the tines


def _curl_curvature(w) -> float:
    """Curvature of a wig's rest helix, R / (R² + (P/2π)²) [1/m] (0 for straight hair)."""
    import math

    if w.curliness == 0:
        return 0.0
    return w.curl_radius / (w.curl_radius**2 + (w.pitch / (2 * math.pi)) ** 2)


def test_v7_is_v6_with_curvature_growing_with_curliness_on_the_presets_only() -> None:
    """v7 shrinks the curls of tight_curl, coily and held_out_tight at the same R/P (v6: all three at 12 mm, like
    curly), so that the curls' curvature, which sets the force of drawing them straight over the tines, grows with
    curliness from preset to preset, and turns their rest shapes by 2π/3 so that each coil still reaches round the
    tine between groups (docs/detangling.md, *HairBrush-v7*). Every preset keeps 8 edges per turn (the
    chain's curl stiffness is within 10 % from 8 on). A custom wig, or a preset with a field of its own, is used as
    given; unknown presets or fields in ``preset_fields`` are errors naming it."""
    import math

    from hairbrush_env.envs.common import apply_wig_fields
    from hairbrush_env.hair import PRESETS
    from hairbrush_env.physics import preset_fields_of

    v6, v7 = get_physics("v6"), get_physics("v7")
    assert v7.brush == v6.brush and dict(v7.wig_fields) == dict(v6.wig_fields)
    assert ENV_IDS["HairBrush-v7"][2] == ENV_IDS["HairBrushContinuous-v7"][2] == V7_PHYSICS == v7.env_kwargs()
    kappa = [_curl_curvature(v7.wig(name)) for name in PRESETS]  # straightest first
    assert kappa == sorted(kappa) and len(set(kappa)) == len(kappa), kappa
    v6_kappa = [_curl_curvature(v6.wig(n)) for n in ("curly", "tight_curl", "coily")]
    assert max(v6_kappa) < 1.1 * min(v6_kappa)  # v6: within 10 % from curly to coily
    for name in (*PRESETS, "held_out_curly", "held_out_tight"):
        w6, w7 = v6.wig(name), v7.wig(name)
        assert w7.curliness == w6.curliness and w7.length == w6.length, name
        assert w7.n_edges >= math.ceil(w7.edges_per_turn * w7.turns) and w7.edges_per_turn == 8, name
        changed = name in ("tight_curl", "coily", "held_out_tight")
        assert (w7.curl_radius < w6.curl_radius) == changed and (w7.digest() != w6.digest()) == changed, name
    # Each strand's helix axis rests a = R (1 − cos ψ) across the tines from its group's axis, which a tine runs
    # through; the next tine (between groups) is one pitch out. v7's coils clear the middle tine and reach round
    # their own: at v6's ψ = π/2 a 9 mm coil spans 0–18 mm and reaches no tine.
    pitch = get_brush(v7.brush).column_pitch
    for name in ("tight_curl", "coily", "held_out_tight"):
        w = v7.wig(name)
        a = w.curl_radius * (1 - math.cos(w.rest_splay))
        assert a - w.curl_radius > w.strand_radius and a + w.curl_radius > pitch, name
    assert 2 * v7.wig("coily").curl_radius < pitch
    assert v7.wig("coily").rest_splay == pytest.approx(2 * math.pi / 3)  # a preset's own fields win
    assert v7.wig(PRESETS["coily"]).curl_radius == 0.009  # a config equal to the preset is the preset
    assert v7.wig(v7.wig("coily")) == v7.wig(
        "coily"
    )  # and a version's preset stays itself (the studies do this)
    assert v7.scene_config(v7.wig("coily")).wig_config == v7.wig("coily")
    mine = get_wig("coily").replace(length=0.31)
    assert v7.wig(mine).curl_radius == mine.curl_radius == 0.012  # your own coily is yours
    assert apply_wig_fields(["coily", mine], None, v7.preset_fields)[0].curl_radius == 0.009
    kw = V7_PHYSICS
    assert apply_wig_fields([v7.wig("coily")], kw["wig_fields"], kw["preset_fields"]) == [v7.wig("coily")]
    with pytest.raises(ValueError, match=r"preset_fields.*unknown preset 'frizzy'"):
        preset_fields_of("coily", {"frizzy": {"curl_radius": 0.01}})
    with pytest.raises(ValueError, match=r"preset_fields\['coily'\]"):
        preset_fields_of("coily", {"coily": {"curl_radius": -1.0}})


def test_v8_is_v7_with_tines_every_preset_curl_turns_round() -> None:
    """v8 changes only the comb's tine friction, to the hair's own 0.15 (MuJoCo takes the larger coefficient, so under
    v7 hair slid on tines at 0.3). A curl is a screw to a tine pulled through it
    (:mod:`hairbrush_env.studies.screw_lock`): it turns only below its lead angle's tangent P / (2πR). Under v8 every
    curled preset's curls are below it, under v7 tight_curl's and coily's were above it (docs/detangling.md,
    *HairBrush-v8*)."""
    from hairbrush_env.hair import PRESETS
    from hairbrush_env.studies.screw_lock import lead_tangent

    v7, v8 = get_physics("v7"), get_physics("v8")
    assert dict(v8.wig_fields) == dict(v7.wig_fields) and dict(v8.preset_fields) == dict(v7.preset_fields)
    b7, b8 = get_brush(v7.brush), get_brush(v8.brush)
    assert dataclasses.replace(b8, friction=b7.friction) == b7
    assert ENV_IDS["HairBrush-v8"][2] == ENV_IDS["HairBrushContinuous-v8"][2] == V8_PHYSICS == v8.env_kwargs()
    for name in (*PRESETS, "held_out_curly", "held_out_tight"):
        w7, w8 = v7.wig(name), v8.wig(name)
        assert w8 == w7, name
        if w8.curliness == 0:
            continue
        tan_lead = lead_tangent(w8.curl_radius, w8.pitch)
        mu7, mu8 = max(b7.friction, w7.friction), max(b8.friction, w8.friction)
        assert mu8 == w8.friction == 0.15 and mu8 < 0.8 * tan_lead, (
            name
        )  # turns with a margin (screw_lock's test)
        if name in ("tight_curl", "coily"):
            assert mu7 > tan_lead, name  # locked under v7


def test_v9_is_v8_with_the_cross_flow_drag_and_springy_tines() -> None:
    """v9 changes two things against v8, both what a slow pull should not feel: the strands' drag acts on the velocity
    across them only (``drag_normal_only``), and the comb's tines keep a tenth of their hinge damping (ζ ≈ 0.075 with
    the tine's inertia; v1–v8: 0.75). Wigs, curls, contacts and the tines' friction and stiffness stay v8's
    (docs/detangling.md, *HairBrush-v9*)."""
    from hairbrush_env.hair import PRESETS

    v8, v9 = get_physics("v8"), get_physics("v9")
    assert dict(v9.wig_fields) == {**v8.wig_fields, "drag_normal_only": True}
    assert dict(v9.preset_fields) == dict(v8.preset_fields)
    b8, b9 = get_brush(v8.brush), get_brush(v9.brush)
    assert dataclasses.replace(b9, damping=b8.damping) == b8 and b9.damping == pytest.approx(0.1 * b8.damping)
    assert ENV_IDS["HairBrush-v9"][2] == ENV_IDS["HairBrushContinuous-v9"][2] == V9_PHYSICS == v9.env_kwargs()
    for name in (*PRESETS, "held_out_curly", "held_out_tight"):
        assert v9.wig(name) == v8.wig(name).replace(drag_normal_only=True), name


def test_v10_is_v9_reading_the_load_cell_in_the_hair_only() -> None:
    """v10 keeps v9's wigs, curls and comb and changes how its strokes are read (``SceneConfig.read_in_hair``): the
    envs of both ids get it as a scene field, and a version's scene config carries it."""
    from hairbrush_env.envs import V10_PHYSICS
    from hairbrush_env.hair import PRESETS

    v9, v10 = get_physics("v9"), get_physics("v10")
    assert (v10.brush, dict(v10.wig_fields), dict(v10.preset_fields)) == (
        v9.brush,
        dict(v9.wig_fields),
        dict(v9.preset_fields),
    )
    assert v10.env_kwargs() == {**v9.env_kwargs(), "scene_fields": {"read_in_hair": True}}
    assert (
        ENV_IDS["HairBrush-v10"][2]
        == ENV_IDS["HairBrushContinuous-v10"][2]
        == V10_PHYSICS
        == v10.env_kwargs()
    )
    assert v10.scene_config("curly").read_in_hair and not v9.scene_config("curly").read_in_hair
    assert v10.scene_config("curly", read_in_hair=False) == v9.scene_config("curly")
    for name in (*PRESETS, "held_out_curly", "held_out_tight"):
        assert v10.wig(name) == v9.wig(name), name


def _parted_after_insertion(version: str, wig: str, seed: int, b_l: float) -> int:
    """How many entwined pairs have a tine between their strands at the first physics step of the pull."""
    from hairbrush_env.scene import BrushingSim

    sim = BrushingSim(get_physics(version).scene_config(wig))
    sim.reset(seed)
    z0 = sim.start_height(b_l)
    seen: list[int] = []

    def observe(s: BrushingSim) -> None:
        tcp = s.brush_position()
        if not seen and abs(tcp[0] - s.depth_x) < 2e-3 and tcp[2] < z0 - 1e-3:
            seen.append(int(s.pairs_parted().sum()))

    sim.add_step_observer(observe)
    sim.stroke(b_l, abort_force=0.5)  # the pull stops at the first sample of 0.5 N, after the insertion
    assert seen, "the pull never started"
    return seen[0]


def test_v4_comb_goes_in_between_pairs_where_v3_meets_them_head_on() -> None:
    """Under v3 every pair of a one-row curtain curls from its roots in one phase, so at some start heights the comb
    goes in with no tine between any pair's strands (curly, seed 0, b_l 0.7, 30 mm below the roots: 0 of 12, and the
    stroke reads 1.05 N and leaves 1.06 of the link, against 12 of 12, 7.88 N and 0.42 at b_l 0.725). v4's root runs
    spread the phases: measured 11 of 12 there (``scripts/probe_insertion.py``; docs/detangling.md, *Where the comb
    goes in*)."""
    assert _parted_after_insertion("v3", "curly", 0, 0.7) == 0
    assert _parted_after_insertion("v4", "curly", 0, 0.7) >= 9


def test_a_wig_v3_cannot_build_names_the_version() -> None:
    """25 strands need a triple; v3 has none, and its error says so."""
    odd = get_wig("curly").replace(name="odd", n_strands=25, n_triples=1)
    with pytest.raises(ValueError, match=r"wig 'odd' under physics v3 \(which sets .*n_triples=0\)"):
        get_physics("v3").wig(odd)


def test_unknown_version_is_refused() -> None:
    with pytest.raises(ValueError, match="physics: unknown version 'v11'; valid: v0, v1, v2, v3"):
        get_physics("v11")


def test_a_study_directory_keeps_one_version(tmp_path) -> None:
    claim_physics(tmp_path, "v1", resuming=False)
    claim_physics(tmp_path, "v1", resuming=True)  # resuming under the same version is fine
    with pytest.raises(ValueError, match="holds results under v1; got 'v0'"):
        claim_physics(tmp_path, "v0", resuming=True)
    old = tmp_path / "old"
    old.mkdir()
    with pytest.raises(ValueError, match="holds results under v0"):  # written before physics.json existed
        claim_physics(old, "v1", resuming=True)


def test_naming_v0_on_purpose_skips_gymnasium_upgrade_warning() -> None:
    """``make_version`` (used where a version is chosen by flag or by the agent's training env) builds v0 without
    gymnasium's "out of date" warning; a plain ``gymnasium.make`` still shows it."""
    import warnings

    import gymnasium as gym

    from hairbrush_env.envs import make_version

    wig = get_wig("curly").replace(name="test_small", n_strands=6, n_triples=0, length=0.12)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        make_version("HairBrush-v0", wig=wig).close()
    assert not [w for w in caught if "out of date" in str(w.message)]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        gym.make("HairBrush-v0", wig=wig).close()
    assert [w for w in caught if "out of date" in str(w.message)]
