"""Cartesian control of the arm with the brush attached: IK accuracy, level brush, stroke tracking."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from hairbrush_env.arm_control import LEVEL_QUAT, CartesianController, plan_stroke
from hairbrush_env.assets import load_part

POS_TOL = 2e-3  # m
LEVEL_TOL = np.deg2rad(2.0)


@pytest.fixture(scope="module")
def model() -> mujoco.MjModel:
    arm = load_part("arm")
    arm.attach(load_part("brush"), site="attachment_site", prefix="brush/")
    return arm.compile()


def _home(model: mujoco.MjModel) -> mujoco.MjData:
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("home").id)
    mujoco.mj_forward(model, data)
    return data


def _yaw(deg: float) -> np.ndarray:
    h = np.deg2rad(deg) / 2
    return np.array([np.cos(h), 0.0, 0.0, np.sin(h)])


def _tilt(data: mujoco.MjData, site: int) -> float:
    """Angle between the brush's up axis and world up: 'parallel to the ground' means 0."""
    up = data.site_xmat[site].reshape(3, 3)[:, 2]
    return float(np.arccos(np.clip(up[2], -1.0, 1.0)))


def test_controller_resolves_arm_chain_only(model: mujoco.MjModel) -> None:
    ctl = CartesianController(model)
    names = [model.joint(j).name for j in ctl.joint_ids]
    assert names == [f"joint{i}" for i in range(1, 7)]  # tine joints are not on the TCP's chain
    assert [model.actuator(a).name for a in ctl.actuator_ids] == [f"actuator{i}" for i in range(1, 7)]
    with pytest.raises(ValueError, match="not found"):
        CartesianController(model, site="no_such_site")


# Targets over the brushing workspace: the hair curtain is at x ≈ 0.50, z ∈ [0.60, 0.93] (see docs/wigs.md).
TARGETS = [
    ((0.50, 0.00, 0.90), None),
    ((0.50, 0.00, 0.60), None),
    ((0.42, 0.08, 0.75), None),
    ((0.48, -0.10, 0.65), None),
    ((0.45, 0.05, 0.80), _yaw(25.0)),
]


@pytest.mark.parametrize(("pos", "quat"), TARGETS)
def test_ik_reaches_targets_level(model: mujoco.MjModel, pos: tuple[float, float, float], quat) -> None:
    ctl = CartesianController(model)
    data = _home(model)
    before = data.qpos.copy()
    q = ctl.solve(data, pos, quat)
    np.testing.assert_array_equal(data.qpos, before)  # solve() works on a scratch copy
    assert np.all(q >= ctl.q_lower) and np.all(q <= ctl.q_upper)

    # Kinematic accuracy of the solution itself.
    kin = mujoco.MjData(model)
    kin.qpos[ctl.qpos_adr] = q
    mujoco.mj_forward(model, kin)
    pos_err, rot_err = ctl.pose_error(kin, pos, quat)
    assert pos_err < 1e-4 and rot_err < 1e-3

    # Closed loop: the position servos bring the real brush there under gravity.
    ctl.apply(data, q)
    for _ in range(round(1.5 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    pos_err, rot_err = ctl.pose_error(data, pos, quat)
    assert pos_err < POS_TOL, f"TCP {pos_err * 1e3:.2f} mm from target"
    assert rot_err < LEVEL_TOL
    assert _tilt(data, ctl.site_id) < LEVEL_TOL
    assert all(w.number == 0 for w in data.warning)


def test_ik_respects_joint_limits_for_unreachable_target(model: mujoco.MjModel) -> None:
    ctl = CartesianController(model)
    data = _home(model)
    q = ctl.solve(data, (1.5, 0.0, 0.75))  # twice the reach
    assert np.all(q >= ctl.q_lower - 1e-12) and np.all(q <= ctl.q_upper + 1e-12)
    kin = mujoco.MjData(model)
    kin.qpos[ctl.qpos_adr] = q
    mujoco.mj_forward(model, kin)
    assert ctl.pose_error(kin, (1.5, 0.0, 0.75))[0] > 0.5  # honest: it cannot be reached


def test_plan_stroke_constant_speed() -> None:
    start, end = np.array([0.5, 0.0, 0.9]), np.array([0.5, 0.0, 0.6])
    pts = plan_stroke(start, end, speed=0.1, dt=0.002)
    np.testing.assert_allclose(pts[0], start)
    np.testing.assert_allclose(pts[-1], end)
    steps = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    np.testing.assert_allclose(steps[:-1], 0.1 * 0.002, rtol=1e-9)
    assert 0 < steps[-1] <= 0.1 * 0.002 + 1e-12
    np.testing.assert_allclose(pts[:, :2], np.broadcast_to(start[:2], (len(pts), 2)))  # straight, vertical
    assert len(pts) == 1501
    with pytest.raises(ValueError, match="speed"):
        plan_stroke(start, end, speed=0.0, dt=0.002)
    with pytest.raises(ValueError, match="dt"):
        plan_stroke(start, end, speed=0.1, dt=-1.0)


def test_vertical_stroke_tracking(model: mujoco.MjModel) -> None:
    ctl = CartesianController(model)
    data = _home(model)
    dt = model.opt.timestep
    start, end, speed = np.array([0.50, 0.0, 0.90]), np.array([0.50, 0.0, 0.60]), 0.1

    q = ctl.solve(data, start)
    ctl.apply(data, q)
    for _ in range(round(1.0 / dt)):
        mujoco.mj_step(model, data)
    assert ctl.pose_error(data, start)[0] < POS_TOL

    pts = plan_stroke(start, end, speed, dt)
    vel = speed * (end - start) / np.linalg.norm(end - start)
    errors, tilts, z = [], [], []
    for k, target in enumerate(pts[:-1]):
        q = ctl.track(data, target, vel, LEVEL_QUAT, q_init=q)
        mujoco.mj_step(model, data)
        errors.append(ctl.pose_error(data, pts[k + 1])[0])
        tilts.append(_tilt(data, ctl.site_id))
        z.append(data.site_xpos[ctl.site_id, 2])
    errors_mm = 1e3 * np.asarray(errors)
    assert errors_mm.max() < 3.0, f"max tracking error {errors_mm.max():.2f} mm"
    assert np.median(errors_mm) < 1.0
    assert max(tilts) < np.deg2rad(1.0)
    # Constant speed: mid-stroke TCP velocity (finite difference over 0.5 s) within 2 % of the command.
    n = round(0.5 / dt)
    mid = len(z) // 2
    measured = (z[mid] - z[mid + n]) / (n * dt)
    assert measured == pytest.approx(speed, rel=0.02)
    assert all(w.number == 0 for w in data.warning)


def test_stroke_in_full_scene_clears_the_head() -> None:
    """Arm + brush + head + floor composed as documented: the stroke path never touches the head."""
    scene = mujoco.MjSpec()
    scene.option.timestep = 0.001
    scene.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_PLANE, size=[2, 2, 0.1], contype=8, conaffinity=7)
    arm = load_part("arm")
    arm.attach(load_part("brush"), site="attachment_site", prefix="brush/")
    arm.compile()  # compile before nesting, so that the brush keyframe is namespaced arm/brush/home
    scene.attach(arm, frame=scene.worldbody.add_frame(), prefix="arm/")
    scene.attach(load_part("head"), frame=scene.worldbody.add_frame(pos=[0.62, 0, 0]), prefix="head/")
    model = scene.compile()
    assert {model.key(i).name for i in range(model.nkey)} == {"arm/home", "arm/brush/home", "head/home"}
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("arm/home").id)
    np.testing.assert_allclose(data.site_xpos[model.site("head/scalp").id], 0)  # before forward
    mujoco.mj_forward(model, data)
    np.testing.assert_allclose(data.site_xpos[model.site("head/scalp").id], [0.50, 0, 0.945], atol=1e-12)

    ctl = CartesianController(model, site="arm/brush/brush_tcp")
    start, end = np.array([0.50, 0.0, 0.92]), np.array([0.50, 0.0, 0.60])
    q = ctl.solve(data, start)
    ctl.apply(data, q)
    contacts = 0
    for _ in range(500):
        mujoco.mj_step(model, data)
        contacts += data.ncon
    for target in plan_stroke(start, end, 0.2, model.opt.timestep)[1:]:
        q = ctl.track(data, target, (0, 0, -0.2), q_init=q)
        mujoco.mj_step(model, data)
        contacts += data.ncon
    assert contacts == 0
    assert ctl.pose_error(data, end)[0] < POS_TOL
