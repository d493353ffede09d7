"""The brush's tines as a config: the default is brush.xml's own brush; custom brushes size plate and TCP."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from hairbrush_env.assets import load_part
from hairbrush_env.brush import (
    NYLON_YOUNG,
    TINE_PREFIX,
    BrushConfig,
    brush_spec,
    get_brush,
    tine_hinge_stiffness,
)


def test_default_config_reproduces_the_xml_brush():
    xml, ours = load_part("brush").compile(), brush_spec().compile()
    assert (xml.nbody, xml.njnt, xml.ngeom) == (ours.nbody, ours.njnt, ours.ngeom)
    for field in (
        "body_pos",
        "body_mass",
        "body_inertia",
        "geom_size",
        "geom_pos",
        "geom_friction",
        "site_pos",
        "jnt_stiffness",
        "jnt_range",
        "dof_damping",
        "dof_armature",
    ):
        np.testing.assert_allclose(getattr(ours, field), getattr(xml, field), atol=1e-12, err_msg=field)
    assert [xml.geom(i).name for i in range(xml.ngeom)] == [ours.geom(i).name for i in range(ours.ngeom)]


def test_custom_brush_sizes_plate_and_tcp_and_rigid_tines_have_no_joints():
    cfg = BrushConfig(rows=1, columns=9, column_pitch=0.0135, tine_length=0.1, hinged=False)
    model = brush_spec(cfg).compile()
    tines = [g for g in range(model.ngeom) if model.geom(g).name.startswith("tine_")]
    assert len(tines) == 9 and model.njnt == 0
    np.testing.assert_allclose(model.geom_size[tines, 1], 0.05)  # capsule half length
    ys = np.sort(model.geom_pos[tines, 1])
    np.testing.assert_allclose(np.diff(ys), 0.0135)
    assert model.geom("head_plate").size[1] > ys.max() + cfg.tine_radius
    assert model.site("brush_tcp").pos[0] == pytest.approx(0.065 + 0.05)
    assert cfg.half_height == pytest.approx(cfg.tine_radius) and cfg.half_width == pytest.approx(
        0.054 + 0.0015
    )
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)  # compiles and runs standalone


@pytest.mark.parametrize(
    "kw, name",
    [
        ({"rows": 0}, "rows"),
        ({"columns": 2.5}, "columns"),
        ({"tine_length": -1.0}, "tine_length"),
        ({"column_pitch": 0.002}, "column_pitch"),
        ({"row_pitch": float("nan")}, "row_pitch"),
        ({"deflection_limit": 0.0}, "deflection_limit"),
        ({"deflection_limit": 2.0}, "deflection_limit"),
        ({"friction": -0.1}, "friction"),
    ],
)
def test_bad_brush_configs_name_the_field(kw, name):
    with pytest.raises(ValueError, match=name):
        BrushConfig(**kw)


def test_friction_is_every_tine_geoms_sliding_friction():
    """``BrushConfig.friction`` sets the tines' sliding coefficient (default: brush.xml's 0.3, checked above);
    torsional and rolling friction stay brush.xml's."""
    m = brush_spec(BrushConfig(friction=0.12)).compile()
    tines = [i for i in range(m.ngeom) if m.geom(i).name.startswith(TINE_PREFIX)]
    assert len(tines) == BrushConfig().rows * BrushConfig().columns
    np.testing.assert_allclose(m.geom_friction[tines], [[0.12, 0.005, 0.0001]] * len(tines))


def test_presets_resolve_by_name():
    assert get_brush("paddle") == BrushConfig()
    assert get_brush("comb").tine_length == pytest.approx(0.06) and not get_brush("comb").hinged
    with pytest.raises(ValueError, match="valid names"):
        get_brush("nope")


def test_soft_comb_tine_bends_like_a_nylon_cantilever_at_the_curtain():
    """A 1 N load at mid-tine (where the hair hangs) moves that point as a clamped nylon rod would: F a³ / (3 E I)."""
    cfg = get_brush("soft_comb")
    assert cfg.hinged and cfg.tine_length == get_brush("comb").tine_length
    model = brush_spec(cfg).compile()
    model.opt.gravity[:] = 0.0
    data = mujoco.MjData(model)
    body = model.body("tine_0_11").id  # the middle tine
    a = 0.5 * cfg.tine_length  # its centre of mass, where xfrc_applied acts
    data.xfrc_applied[body, 2] = 1.0  # the hair resisting a downward pull lifts the tine
    for _ in range(3000):
        mujoco.mj_step(model, data)
    theta = float(data.qpos[model.jnt_qposadr[model.joint("tine_0_11").id]])
    moment_of_area = np.pi * cfg.tine_radius**4 / 4
    expected = 1.0 * a**3 / (3 * NYLON_YOUNG * moment_of_area)
    assert abs(a * np.sin(theta)) == pytest.approx(expected, rel=0.02)
    assert abs(theta) < model.jnt_range[model.joint("tine_0_11").id, 1]  # the load did not reach the stop


def test_deflection_limit_is_the_hinge_range_of_every_tine():
    """The paddle keeps brush.xml's ±0.35 rad; a wider limit lets a loaded tine bend on past it."""
    paddle = brush_spec(BrushConfig()).compile()
    assert np.allclose(paddle.jnt_range, [-0.35, 0.35])
    cfg = BrushConfig(
        rows=1, columns=2, column_pitch=0.02, tine_length=0.06, stiffness=1.1, deflection_limit=1.2
    )
    model = brush_spec(cfg).compile()
    assert model.njnt == 2 and np.allclose(model.jnt_range, [-1.2, 1.2]) and model.jnt_limited.all()
    model.opt.gravity[:] = 0.0
    data = mujoco.MjData(model)
    body = model.body("tine_0_0").id
    force, arm = 20.0, 0.5 * cfg.tine_length
    data.xfrc_applied[body, 2] = force  # lifts mid-tine: ~0.49 rad, past brush.xml's 0.35 rad stop
    for _ in range(3000):
        mujoco.mj_step(model, data)
    theta = abs(float(data.qpos[model.jnt_qposadr[model.joint("tine_0_0").id]]))
    # static balance of the hinge: K θ = F a cos θ (the vertical load's arm shortens as the tine turns)
    assert cfg.stiffness * theta == pytest.approx(force * arm * np.cos(theta), rel=0.02)
    assert 0.35 < theta < 1.2


def test_tine_hinge_stiffness_rejects_bad_input():
    with pytest.raises(ValueError, match="radius"):
        tine_hinge_stiffness(0.06, -1.0)
