"""The load-cell instrument: rate, tare, noise, quantization and the frame transform of the readback."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from hairbrush_env.arm_control import CartesianController
from hairbrush_env.assets import load_part
from hairbrush_env.sensors import DOWN, LoadCell, LoadCellConfig

IDEAL = LoadCellConfig(
    noise_std=0.0,
    resolution=0.0,
    torque_noise_std=0.0,
    torque_resolution=0.0,
    force_sensor="brush_force",
    torque_sensor="brush_torque",
)
STANDALONE = {"force_sensor": "brush_force", "torque_sensor": "brush_torque"}


def _brush() -> tuple[mujoco.MjModel, mujoco.MjData]:
    """Standalone brush welded to the world, tines settled (static load = its weight)."""
    model = load_part("brush").compile()
    data = mujoco.MjData(model)
    for _ in range(250):
        mujoco.mj_step(model, data)
    return model, data


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("rate_hz", 0.0),
        ("rate_hz", float("inf")),
        ("noise_std", -0.1),
        ("resolution", -1e-3),
        ("torque_noise_std", float("nan")),
        ("torque_resolution", -1.0),
        ("force_sensor", ""),
    ],
)
def test_config_validation_names_the_field(field: str, value: object) -> None:
    with pytest.raises(ValueError, match=field):
        LoadCellConfig(**{field: value})


def test_wrong_sensor_names_raise() -> None:
    model, _ = _brush()
    with pytest.raises(ValueError, match="not found"):
        LoadCell(model, LoadCellConfig(), rng=np.random.default_rng(0))  # prefixed names, standalone brush
    with pytest.raises(ValueError, match="not a"):
        LoadCell(
            model,
            LoadCellConfig(force_sensor="brush_torque", torque_sensor="brush_torque"),
            rng=np.random.default_rng(0),
        )


@pytest.mark.parametrize(("rate", "expected"), [(10.0, 10), (25.0, 25), (3.0, 3)])
def test_sampling_rate_counts_samples(rate: float, expected: int) -> None:
    model, data = _brush()
    cell = LoadCell(
        model, LoadCellConfig(rate_hz=rate, **STANDALONE), rng=np.random.default_rng(0), data=data
    )
    t0 = data.time
    new = 0
    while data.time < t0 + 1.0 - 1e-9:
        mujoco.mj_step(model, data)
        new += cell.update(data) is not None
    assert new == expected == len(cell.samples)
    np.testing.assert_allclose(np.diff(cell.times()), 1.0 / rate, atol=model.opt.timestep)
    assert cell.times()[-1] == pytest.approx(t0 + 1.0)


def test_tare_zeroes_constant_offset() -> None:
    model, data = _brush()
    cell = LoadCell(model, IDEAL, rng=np.random.default_rng(0))
    weight = model.body_subtreemass[1] * 9.81
    # Before tare: the flange holds the brush up, so the pull along DOWN is -weight.
    assert cell.measure(data).brushing_force(DOWN) == pytest.approx(-weight, rel=1e-4)
    cell.tare(data)
    np.testing.assert_allclose(cell.tare_offset[:3], [0, 0, weight], rtol=1e-4, atol=1e-9)
    reading = cell.measure(data)
    np.testing.assert_allclose(reading.force, 0.0, atol=1e-12)
    np.testing.assert_allclose(reading.torque, 0.0, atol=1e-12)
    # With noise, the tared mean is zero within the noise's standard error.
    noisy = LoadCell(
        model, LoadCellConfig(noise_std=0.02, resolution=0.0, **STANDALONE), rng=np.random.default_rng(1)
    )
    noisy.tare(data)
    mean = np.mean([noisy.measure(data).force for _ in range(400)], axis=0)
    assert np.all(np.abs(mean) < 4 * 0.02 / np.sqrt(400))
    cell.clear_tare()
    assert cell.measure(data).force[2] == pytest.approx(weight, rel=1e-4)


@pytest.mark.parametrize("std", [0.02, 0.1])
def test_noise_std_matches_config(std: float) -> None:
    model, data = _brush()
    cell = LoadCell(
        model, LoadCellConfig(noise_std=std, resolution=0.0, **STANDALONE), rng=np.random.default_rng(2)
    )
    cell.tare(data)
    forces = np.array([cell.measure(data).force for _ in range(2000)])
    measured = forces.std(axis=0)
    np.testing.assert_allclose(measured, std, rtol=0.10)
    # Reproducible per seed, independent of any global RNG.
    a = LoadCell(model, LoadCellConfig(**STANDALONE), rng=np.random.default_rng(7)).measure(data).force
    np.random.seed(123)  # noqa: NPY002 -- deliberately disturb the legacy global RNG
    b = LoadCell(model, LoadCellConfig(**STANDALONE), rng=np.random.default_rng(7)).measure(data).force
    np.testing.assert_array_equal(a, b)


def test_quantization_step() -> None:
    model, data = _brush()
    res = 0.05
    cell = LoadCell(
        model, LoadCellConfig(noise_std=0.013, resolution=res, **STANDALONE), rng=np.random.default_rng(3)
    )
    forces = np.array([cell.measure(data).force for _ in range(500)])
    steps = forces / res
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-9)
    # z carries the weight 1.2287 N plus noise: the readings are the neighbouring multiples of 0.05 N.
    assert set(np.round(forces[:, 2] / res).astype(int)) <= {23, 24, 25, 26, 27}
    assert len(np.unique(forces[:, 2])) >= 2


@pytest.fixture(scope="module")
def arm_brush() -> mujoco.MjModel:
    arm = load_part("arm")
    arm.attach(load_part("brush"), site="attachment_site", prefix="brush/")
    return arm.compile()


@pytest.mark.parametrize("yaw_deg", [0.0, 30.0])
def test_known_static_load_read_back_after_tare(arm_brush: mujoco.MjModel, yaw_deg: float) -> None:
    """An external force on the brush head (as hair would exert) is read back through the frame transform."""
    model = arm_brush
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("home").id)
    ctl = CartesianController(model)
    h = np.deg2rad(yaw_deg) / 2
    quat = np.array([np.cos(h), 0, 0, np.sin(h)])  # a yawed brush: site frame != world frame
    q = ctl.solve(data, (0.48, 0.05, 0.75), quat)
    ctl.apply(data, q)
    for _ in range(750):
        mujoco.mj_step(model, data)

    cell = LoadCell(model, LoadCellConfig(), rng=np.random.default_rng(4), data=data)  # default noise
    cell.tare(data)
    hair = np.array([0.4, -0.6, 3.0])  # mostly upward: hair resisting a downward pull, 3 N
    data.xfrc_applied[model.body("brush/brush").id, :3] = hair
    for _ in range(750):
        mujoco.mj_step(model, data)
    reads = [cell.measure(data) for _ in range(50)]  # average out the 0.02 N noise
    brushing = np.mean([r.brushing_force(DOWN) for r in reads])
    assert brushing == pytest.approx(hair[2], rel=0.01)
    world = np.mean([r.force_world for r in reads], axis=0)
    # The arm balances the external load: F_arm_on_brush = -F_hair, within 1 % of |F_hair|.
    assert np.linalg.norm(world + hair) < 0.01 * np.linalg.norm(hair)
    if yaw_deg:
        # The raw site-frame channels differ from the world vector: the transform was really exercised.
        site_frame = np.mean([r.force for r in reads], axis=0)
        assert np.linalg.norm(site_frame[:2] - world[:2]) > 0.2


@pytest.mark.parametrize("kind", ["chain", "flex"])
def test_rod_contacts_reach_the_load_cell(kind: str):
    """A rod resting on a sensorized plate reads as plate + rod weight, with the rod's moment about the site
    (statics, exact). MuJoCo's force sensor sees a chain's capsule contacts but ignores flex contacts, which
    LoadCell adds itself."""
    from hairbrush_env.rods import RodSpec, add_rod, configure_rod_options, straight_rod_points

    spec = mujoco.MjSpec()
    configure_rod_options(spec, timestep=2e-3, kind=kind)
    plate = spec.worldbody.add_body(name="plate", pos=[0, 0, 0.1])
    plate.add_site(name="cell")
    plate.add_geom(type=mujoco.mjtGeom.mjGEOM_BOX, size=[0.2, 0.2, 0.005], mass=0.1)
    for name, sensor in (("f", mujoco.mjtSensor.mjSENS_FORCE), ("t", mujoco.mjtSensor.mjSENS_TORQUE)):
        spec.add_sensor(name=name, type=sensor, objtype=mujoco.mjtObj.mjOBJ_SITE, objname="cell")
    rod = RodSpec(
        name="rod",
        points=straight_rod_points([0.0, 0, 0.115], [1, 0, 0], 0.15, n_edges=10),
        radius=0.004,
        young=1e8,
        density=1300,
        clamp=None,
        friction=0.5,
        kind=kind,
    )
    add_rod(spec, rod)
    model = spec.compile()
    data = mujoco.MjData(model)
    quiet = LoadCellConfig(force_sensor="f", torque_sensor="t", noise_std=0, resolution=0, torque_noise_std=0,
                           torque_resolution=0)  # fmt: skip
    cell = LoadCell(model, quiet, rng=np.random.default_rng(0))
    for _ in range(2000):
        mujoco.mj_step(model, data)
    w_rod = rod.length * rod.linear_density * 9.81
    if kind == "flex":
        assert data.sensordata[2] == pytest.approx(0.1 * 9.81)  # the bare sensor misses the rod entirely
    wrench = cell.raw(data)
    assert wrench[2] == pytest.approx(0.1 * 9.81 + w_rod, rel=1e-6)
    from hairbrush_env.rods import rod_vertices

    mujoco.mj_forward(model, data)
    ends = rod_vertices(model, data, "rod")[[0, -1]]
    com_x = float(ends[:, 0].mean())  # straight uniform rod, ~7.5 cm along +x (it may slide a few µm)
    assert com_x == pytest.approx(0.075, abs=1e-4)
    assert wrench[4] == pytest.approx(-com_x * w_rod, rel=1e-4)
