"""The thesis' load cell: the brush's MuJoCo force/torque sensor turned into a sampled, noisy instrument.

MuJoCo side (``assets/brush/brush.xml``): the ``force``/``torque`` sensors on site ``load_cell`` report the
wrench that the *parent* (arm flange) exerts on the brush subtree (mount, head and tines), in the
``load_cell`` **site frame**, torque about the site origin.  (The XML reference words it as "the force
points from the child towards the parent"; the sign was checked numerically: a 1 kg body hanging from
the site reads +9.81 N along the site's up axis.)  The world-frame force is therefore

    F_world = R_site @ F_site,        R_site = data.site_xmat[load_cell].reshape(3, 3)

**Flex contacts.** MuJoCo 4.0's force/torque sensors (and ``cfrc_ext``) see the contacts of geoms — body-chain
hair, the default — but leave out contacts with flex elements: a flex rod resting on a sensorized plate reads as the
plate's weight alone (checked in ``tests/test_sensors.py``). For flex hair :meth:`LoadCell.raw` therefore adds the
missing term itself (it finds nothing to add for chains): for every contact between a geom
of the sensor's subtree and a flex, the contact force on the subtree (``mj_contactForce``, contact frame →
world) and its moment about the site; the parent must balance it, so the reading changes by minus that wrench.

Instrument model, in this order: sample-and-hold at ``rate_hz`` of *simulation* time → subtract the tare
(site frame, like a real cell's zeroing of its own channels) → add Gaussian noise (site frame) →
quantize to ``resolution`` → rotate to the world frame.

Brushing force: with the brush pulled along the unit ``direction`` (default straight down), the hair
resists with a force opposite to ``direction``; at constant speed the arm's pull on the brush balances it,
so the tared reading ``F_world · direction`` is **positive when the hair resists the pull** (newtons).
Taring at stroke start with the brush at rest and level removes the brush's weight; the tare is exact
only while the brush keeps the orientation it had when tared (true for a level stroke).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["DOWN", "LoadCell", "LoadCellConfig", "LoadCellSample"]

#: Default brushing direction: the brush is pulled straight down through the hair.
DOWN = np.array([0.0, 0.0, -1.0])


@dataclass(frozen=True)
class LoadCellConfig:
    """Load-cell instrument parameters.

    Attributes
    ----------
    rate_hz
        Sampling rate in samples per second of simulation time (> 0).  The thesis logged at 10 Hz.
    noise_std
        Standard deviation of the Gaussian noise on each force channel (N, >= 0).
    resolution
        Force quantization step (N, >= 0; 0 disables quantization).
    torque_noise_std
        Standard deviation of the noise on each torque channel (N m, >= 0).
    torque_resolution
        Torque quantization step (N m, >= 0; 0 disables quantization).
    force_sensor, torque_sensor
        Names of the MuJoCo sensors in the compiled model (the brush attached with ``prefix="brush/"``).
    """

    rate_hz: float = 10.0
    noise_std: float = 0.02
    resolution: float = 0.01
    torque_noise_std: float = 0.0005
    torque_resolution: float = 0.0001
    force_sensor: str = "brush/brush_force"
    torque_sensor: str = "brush/brush_torque"

    def __post_init__(self) -> None:
        if not (math.isfinite(self.rate_hz) and self.rate_hz > 0):
            raise ValueError(f"rate_hz must be a finite number > 0, got {self.rate_hz}")
        for name in ("noise_std", "resolution", "torque_noise_std", "torque_resolution"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0):
                raise ValueError(f"{name} must be a finite number >= 0, got {value}")
        for name in ("force_sensor", "torque_sensor"):
            if not getattr(self, name):
                raise ValueError(f"{name} must be a non-empty sensor name")


@dataclass(frozen=True)
class LoadCellSample:
    """One load-cell reading.

    Attributes
    ----------
    time
        Simulation time of the sample (s).
    force, torque
        Tared, noisy, quantized channels in the load-cell (site) frame (N, N m).
    rotation
        Site-to-world rotation matrix at the sample time.
    """

    time: float
    force: NDArray[np.float64]
    torque: NDArray[np.float64]
    rotation: NDArray[np.float64] = field(repr=False)

    @property
    def force_world(self) -> NDArray[np.float64]:
        """Force of the arm on the brush in the world frame (N)."""
        return self.rotation @ self.force

    @property
    def torque_world(self) -> NDArray[np.float64]:
        """Torque of the arm on the brush about the load-cell origin, world frame (N m)."""
        return self.rotation @ self.torque

    def brushing_force(self, direction: ArrayLike = DOWN) -> float:
        """Force along the brushing ``direction`` (N); positive = the hair resists the pull."""
        d = np.asarray(direction, dtype=float)
        return float(self.force_world @ (d / np.linalg.norm(d)))


class LoadCell:
    """Sampled, tared, noisy and quantized reading of the brush's force/torque sensors.

    Call :meth:`update` after every ``mj_step``; it returns a new :class:`LoadCellSample` whenever a
    sampling instant ``t0 + k / rate_hz`` (k = 1, 2, ...) has been reached, else ``None``.  ``t0`` is the
    simulation time at construction or at the last :meth:`reset`, so one second of simulation at 10 Hz
    yields exactly 10 samples (at t0 + 0.1, ..., t0 + 1.0).  If one step spans several sampling instants
    only one sample is taken (the rate should be below the physics rate anyway).

    Parameters
    ----------
    model
        Compiled model that contains the two sensors.
    config
        Instrument parameters.
    rng
        Source of the measurement noise (no global RNG, so runs are reproducible per seed).
    data
        If given, the sampling clock starts at ``data.time`` (else at 0).
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        config: LoadCellConfig | None = None,
        *,
        rng: np.random.Generator,
        data: mujoco.MjData | None = None,
    ) -> None:
        self.config = config if config is not None else LoadCellConfig()
        self.rng = rng
        self._force_adr, force_site = self._sensor(
            model, self.config.force_sensor, mujoco.mjtSensor.mjSENS_FORCE
        )
        self._torque_adr, torque_site = self._sensor(
            model, self.config.torque_sensor, mujoco.mjtSensor.mjSENS_TORQUE
        )
        if force_site != torque_site:
            raise ValueError("force and torque sensors must share one site (one 6-axis load cell)")
        self.site_id = force_site
        # Geoms of the body subtree the sensor weighs (the site's body and its descendants): their contacts
        # with flexes are added by hand (see the module docstring).
        root = int(model.site_bodyid[force_site])
        in_subtree = np.zeros(model.nbody, dtype=bool)
        for b in range(model.nbody):  # bodies are numbered parents first, so one pass suffices
            in_subtree[b] = b == root or (b > 0 and in_subtree[model.body_parentid[b]])
        self._subtree_geom = in_subtree[model.geom_bodyid]
        self._model = model
        self._tare = np.zeros(6)
        self.samples: list[LoadCellSample] = []
        self.reset(data)

    @staticmethod
    def _sensor(model: mujoco.MjModel, name: str, kind: mujoco.mjtSensor) -> tuple[int, int]:
        sid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, name)
        if sid < 0:
            raise ValueError(f"sensor {name!r} not found in the model")
        if int(model.sensor_type[sid]) != int(kind):
            raise ValueError(f"sensor {name!r} is not a {kind.name} sensor")
        return int(model.sensor_adr[sid]), int(model.sensor_objid[sid])

    # ------------------------------------------------------------------ clock and tare
    def reset(self, data: mujoco.MjData | None = None) -> None:
        """Restart the sampling clock at ``data.time`` (or 0); drops the recorded samples, keeps the tare."""
        self._t0 = 0.0 if data is None else float(data.time)
        self._last_index = 0
        self.samples = []

    def flex_contact_wrench(self, data: mujoco.MjData) -> NDArray[np.float64]:
        """World-frame ``[force, torque about the site]`` that flexes (hair) exert on the sensed subtree."""
        out = np.zeros(6)
        n = data.ncon
        if n == 0:
            return out
        geom = data.contact.geom[:n]
        flex = data.contact.flex[:n]
        ok = self._subtree_geom
        # slot s holds a subtree geom and the other slot a flex
        hits = [(i, 0) for i in np.flatnonzero((geom[:, 0] >= 0) & (flex[:, 1] >= 0)) if ok[geom[i, 0]]]
        hits += [(i, 1) for i in np.flatnonzero((geom[:, 1] >= 0) & (flex[:, 0] >= 0)) if ok[geom[i, 1]]]
        f6 = np.zeros(6)
        site = data.site_xpos[self.site_id]
        for i, slot in hits:
            mujoco.mj_contactForce(self._model, data, int(i), f6)
            frame = data.contact.frame[i].reshape(3, 3)
            # contact force acts on slot 1 along +normal (slot 0 → slot 1) and on slot 0 oppositely
            f_world = frame.T @ f6[:3] * (1.0 if slot == 1 else -1.0)
            out[:3] += f_world
            out[3:] += np.cross(data.contact.pos[i] - site, f_world)
        return out

    def raw(self, data: mujoco.MjData) -> NDArray[np.float64]:
        """Noise-free, un-tared wrench ``[force, torque]`` in the site frame: the sensors plus the flex contacts."""
        out = np.empty(6)
        out[:3] = data.sensordata[self._force_adr : self._force_adr + 3]
        out[3:] = data.sensordata[self._torque_adr : self._torque_adr + 3]
        ext = self.flex_contact_wrench(data)
        if ext.any():
            rot = data.site_xmat[self.site_id].reshape(3, 3)
            out[:3] -= rot.T @ ext[:3]  # the parent balances the hair's push: minus the external wrench
            out[3:] -= rot.T @ ext[3:]
        return out

    def tare(self, data: mujoco.MjData) -> None:
        """Zero the cell at the current (noise-free) wrench, e.g. with the brush at rest at stroke start."""
        self._tare = self.raw(data)

    def clear_tare(self) -> None:
        self._tare = np.zeros(6)

    @property
    def tare_offset(self) -> NDArray[np.float64]:
        """Current zero offset ``[force, torque]`` in the site frame."""
        return self._tare.copy()

    # ------------------------------------------------------------------ measuring
    def measure(self, data: mujoco.MjData) -> LoadCellSample:
        """Take one reading now, regardless of the sampling clock (not recorded in :attr:`samples`)."""
        cfg = self.config
        w = self.raw(data) - self._tare
        w[:3] += self.rng.normal(0.0, cfg.noise_std, 3) if cfg.noise_std > 0 else 0.0
        w[3:] += self.rng.normal(0.0, cfg.torque_noise_std, 3) if cfg.torque_noise_std > 0 else 0.0
        if cfg.resolution > 0:
            w[:3] = np.round(w[:3] / cfg.resolution) * cfg.resolution
        if cfg.torque_resolution > 0:
            w[3:] = np.round(w[3:] / cfg.torque_resolution) * cfg.torque_resolution
        rotation = data.site_xmat[self.site_id].reshape(3, 3).copy()
        return LoadCellSample(time=float(data.time), force=w[:3], torque=w[3:], rotation=rotation)

    def update(self, data: mujoco.MjData) -> LoadCellSample | None:
        """Sample if a sampling instant was reached since the last sample; call after each ``mj_step``."""
        # Integer sample index instead of accumulating 1/rate: no drift, and t = 0.1 s reached after
        # 50 steps of 2 ms must count as the first instant despite float round-off (hence the 1e-9).
        index = math.floor((data.time - self._t0) * self.config.rate_hz + 1e-9)
        if index <= self._last_index:
            return None
        self._last_index = index
        sample = self.measure(data)
        self.samples.append(sample)
        return sample

    # ------------------------------------------------------------------ convenience
    @property
    def latest(self) -> LoadCellSample | None:
        return self.samples[-1] if self.samples else None

    def brushing_force(self, direction: ArrayLike = DOWN) -> float:
        """Brushing force (N) of the latest sample; positive = hair resisting.  Raises if none yet."""
        if not self.samples:
            raise RuntimeError("no load-cell sample yet: call update() after stepping")
        return self.samples[-1].brushing_force(direction)

    def times(self) -> NDArray[np.float64]:
        return np.array([s.time for s in self.samples])

    def brushing_forces(self, direction: ArrayLike = DOWN) -> NDArray[np.float64]:
        """Brushing force (N) of every recorded sample."""
        return np.array([s.brushing_force(direction) for s in self.samples])
