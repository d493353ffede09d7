"""The rigid MJCF parts compile standalone and are well-formed, menagerie-style."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest

from hairbrush_env import assets, collision
from hairbrush_env.assets import ASSETS_DIR, PARTS, load_part, part_path

HINGE = int(mujoco.mjtJoint.mjJNT_HINGE)


def _compile(name: str) -> tuple[mujoco.MjModel, mujoco.MjData]:
    model = load_part(name).compile()
    return model, mujoco.MjData(model)


def _arm_with_brush() -> mujoco.MjModel:
    arm = load_part("arm")
    arm.attach(load_part("brush"), site="attachment_site", prefix="brush/")
    return arm.compile()


def test_assets_dir_and_loader(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    assert (ASSETS_DIR / "arm" / "arm.xml").is_file()
    for name in PARTS:
        assert part_path(name).is_file()
        assert (ASSETS_DIR / name / "README.md").is_file()
    # Fresh spec per call: attaching one must not empty the next.
    a, b = load_part("brush"), load_part("brush")
    assert a is not b
    with pytest.raises(FileNotFoundError, match="nope"):
        load_part("nope")
    monkeypatch.setenv("HAIRBRUSH_ASSETS_DIR", str(tmp_path))
    assert assets._resolve_assets_dir() == tmp_path.resolve()
    monkeypatch.delenv("HAIRBRUSH_ASSETS_DIR")
    assert assets._resolve_assets_dir() == ASSETS_DIR


@pytest.mark.parametrize("name", PARTS)
def test_part_compiles_and_steps_cleanly(name: str) -> None:
    model, data = _compile(name)
    home = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    assert home >= 0, "every part needs a 'home' keyframe"
    mujoco.mj_resetDataKeyframe(model, data, home)
    n = round(1.0 / model.opt.timestep)
    for _ in range(n):
        mujoco.mj_step(model, data)
    assert data.time == pytest.approx(1.0)
    assert all(w.number == 0 for w in data.warning), [w.number for w in data.warning]
    assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))
    # Geom class convention: visual geoms never collide, collision geoms are hidden in group 3.
    visual = model.geom_group == 2
    collide = (model.geom_contype | model.geom_conaffinity) != 0
    assert np.any(model.geom_group == 3)
    assert np.all(~collide[visual & (model.geom_type != mujoco.mjtGeom.mjGEOM_CAPSULE)])


def test_arm_joints_actuators_and_flange() -> None:
    model, _ = _compile("arm")
    hinges = np.flatnonzero(model.jnt_type == HINGE)
    assert len(hinges) >= 4
    assert np.all(model.jnt_limited[hinges] == 1)
    assert np.all(model.jnt_range[hinges, 0] < model.jnt_range[hinges, 1])
    assert model.nu == len(hinges)
    for a in range(model.nu):
        j = model.actuator_trnid[a, 0]
        assert model.actuator_biastype[a] == mujoco.mjtBias.mjBIAS_AFFINE  # position servo
        kp = model.actuator_gainprm[a, 0]
        assert kp > 0 and model.actuator_biasprm[a, 1] == -kp
        np.testing.assert_allclose(model.actuator_ctrlrange[a], model.jnt_range[j])
        assert model.actuator_forcelimited[a] and model.actuator_forcerange[a, 1] > 0
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, "attachment_site") >= 0
    assert model.body_mass[1:].min() > 0
    assert np.all(model.body_inertia[1:] > 0)


@pytest.mark.parametrize("with_brush", [False, True])
def test_arm_holds_home_under_gravity(with_brush: bool) -> None:
    model = _arm_with_brush() if with_brush else load_part("arm").compile()
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("home").id)
    mujoco.mj_forward(model, data)
    site = model.site("attachment_site").id
    start = data.site_xpos[site].copy()
    drift = 0.0
    for _ in range(round(2.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
        drift = max(drift, float(np.linalg.norm(data.site_xpos[site] - start)))
    assert all(w.number == 0 for w in data.warning)
    assert drift < 1e-3, f"flange drifted {drift * 1e3:.2f} mm"
    # Flange level at home (z axis up) so that an attached brush is parallel to the ground.
    np.testing.assert_allclose(data.site_xmat[site].reshape(3, 3)[:, 2], [0, 0, 1], atol=2e-3)


def test_brush_load_cell_bristles_and_attachment() -> None:
    model, data = _compile("brush")
    load_cell = model.site("load_cell").id
    for name, kind in (
        ("brush_force", mujoco.mjtSensor.mjSENS_FORCE),
        ("brush_torque", mujoco.mjtSensor.mjSENS_TORQUE),
    ):
        s = model.sensor(name)
        assert s.type[0] == kind and s.objid[0] == load_cell
    for site in ("attachment_site", "brush_tcp"):
        assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, site) >= 0
    # The load-cell body is welded (no joint): otherwise the sensor would not see the whole brush.
    assert model.body_jntnum[model.site_bodyid[load_cell]] == 0

    tines = [g for g in range(model.ngeom) if (model.geom(g).name or "").startswith("tine_")]
    assert len(tines) >= 12
    for g in tines:
        assert model.geom_type[g] == mujoco.mjtGeom.mjGEOM_CAPSULE
        assert (int(model.geom_contype[g]), int(model.geom_conaffinity[g])) == collision.BRISTLE_GEOM
        assert 0.001 <= model.geom_size[g, 0] <= 0.002
        body = model.geom_bodyid[g]
        assert model.body_jntnum[body] == 1
        j = model.body_jntadr[body]
        assert model.jnt_type[j] == HINGE and model.jnt_limited[j]
        assert model.jnt_stiffness[j] > 0 and model.dof_damping[model.jnt_dofadr[j]] > 0
        # Horizontal bristles along +x (the tine's capsule axis), so they pierce a vertical hair curtain.
        mujoco.mj_forward(model, data)
        axis = data.geom_xmat[g].reshape(3, 3)[:, 2]
        np.testing.assert_allclose(np.abs(axis), [1, 0, 0], atol=1e-9)
        np.testing.assert_allclose(data.geom_xpos[g] - data.xpos[body], [0.0125, 0, 0], atol=1e-9)
        assert model.geom_size[g, 1] * 2 == pytest.approx(0.025)


def test_brush_sensor_sign_convention_reads_supporting_force() -> None:
    # Standalone, the brush hangs from the world: the sensor must read its weight as an UPWARD force
    # (force of the parent on the brush, site frame = world frame here).
    model, data = _compile("brush")
    for _ in range(500):  # let the tines settle on their springs: only then is the subtree static
        mujoco.mj_step(model, data)
    weight = model.body_subtreemass[model.body("brush").id] * -model.opt.gravity[2]
    np.testing.assert_allclose(data.sensor("brush_force").data, [0, 0, weight], atol=1e-6)


def test_head_scalp_and_free_hanging_hair() -> None:
    spec = load_part("head")
    model = spec.compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    scalp = model.site("scalp").id
    assert model.body(model.site_bodyid[scalp]).name == "scalp"
    np.testing.assert_allclose(data.site_xmat[scalp].reshape(3, 3)[:, 2], [0, 0, 1])  # horizontal patch
    # 0.35 m strands (1 cm safety radius) hanging from the patch corners must touch nothing of the head.
    root = data.site_xpos[scalp]
    half = model.site_size[scalp, :2]
    for dx in (-half[0], half[0]):
        for dy in (-half[1], half[1]):
            top = root + np.array([dx, dy, -0.011])
            spec.worldbody.add_geom(
                type=mujoco.mjtGeom.mjGEOM_CAPSULE,
                size=[0.01, 0, 0],
                fromto=[*top, *(top - [0, 0, 0.35])],
                contype=collision.HAIR_GEOM[0],
                conaffinity=collision.HAIR_GEOM[1],
            )
    probe_model = spec.compile()
    probe_data = mujoco.MjData(probe_model)
    mujoco.mj_forward(probe_model, probe_data)
    assert probe_data.ncon == 0
    # ... and the hair end stays above the head's base disc.
    assert root[2] - 0.35 > 0.1


def test_collision_convention_matches_parts() -> None:
    c = collision
    assert c.collides(c.BRISTLE_GEOM, c.HAIR_GEOM)
    assert c.collides(c.BRUSH_HEAD_GEOM, c.HAIR_GEOM)
    assert c.collides(c.ENV_GEOM, c.HAIR_GEOM)
    assert c.collides(c.ENV_GEOM, c.ROBOT_GEOM)
    assert not c.collides(c.BRISTLE_GEOM, c.BRISTLE_GEOM)
    assert not c.collides(c.ROBOT_GEOM, c.HAIR_GEOM)
    assert not c.collides(c.ROBOT_GEOM, c.ROBOT_GEOM)
    assert not c.collides(c.HAIR_GEOM, c.HAIR_GEOM)
    assert c.collides(c.HAIR_GEOM_SELF_COLLIDING, c.HAIR_GEOM_SELF_COLLIDING)
    assert not c.collides(c.SCALP_GEOM, c.HAIR_GEOM)

    def pairs(model: mujoco.MjModel) -> set[tuple[int, int]]:
        g = model.geom_group == 3
        return {
            (int(a), int(b)) for a, b in zip(model.geom_contype[g], model.geom_conaffinity[g], strict=True)
        }

    assert pairs(load_part("arm").compile()) == {c.ROBOT_GEOM}
    assert pairs(load_part("brush").compile()) == {c.ROBOT_GEOM, c.BRUSH_HEAD_GEOM}
    head = load_part("head").compile()
    assert pairs(head) == {c.ENV_GEOM, c.SCALP_GEOM}
    scalp_patch = head.geom("scalp_patch").id
    assert (int(head.geom_contype[scalp_patch]), int(head.geom_conaffinity[scalp_patch])) == c.SCALP_GEOM


def test_brush_attaches_at_flange() -> None:
    model = _arm_with_brush()
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("home").id)
    mujoco.mj_forward(model, data)
    flange = model.site("attachment_site").id
    mount = model.site("brush/attachment_site").id
    np.testing.assert_allclose(data.site_xpos[mount], data.site_xpos[flange], atol=1e-12)
    np.testing.assert_allclose(data.site_xmat[mount], data.site_xmat[flange], atol=1e-12)
    # The brush root is a child of the last arm link, so the load cell sees the arm/brush interface.
    brush = model.body("brush/brush").id
    assert model.body_parentid[brush] == model.site_bodyid[flange]
    assert model.nq == 6 + 24 and model.nu == 6
