"""The pre-brushed preparation: the wig shaken upside down in the head's frame (:mod:`hairbrush_env.hair`,
*Pre-brushed state*)."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from .config import WigConfig

__all__ = ["shake", "shake_acceleration"]


def shake_acceleration(wig: WigConfig, seed: int, t: np.ndarray) -> np.ndarray:
    """The seeded head acceleration ``a(t)`` [m/s²] of the pre-brushed preparation, shape ``(len(t), 3)``.

    Three sinusoids per axis with random frequencies around ``shake_frequency`` and random phases; the horizontal
    amplitude is ``shake_accel``, the vertical one half of it (it unloads gravity without turning the hair over,
    which would drive the strands into the skull). A raised-cosine envelope starts and ends the shake smoothly.
    """
    rng = np.random.default_rng(np.random.SeedSequence([int(seed), 0x5A4E]))
    t = np.asarray(t, dtype=float)
    out = np.zeros((t.size, 3))
    amp = wig.shake_accel * np.array([1.0, 1.0, 0.5]) / math.sqrt(3.0 / 2.0)
    for ax in range(3):
        f = wig.shake_frequency * rng.uniform(0.6, 1.6, 3)
        ph = rng.uniform(0.0, 2.0 * math.pi, 3)
        out[:, ax] = amp[ax] * np.sin(2.0 * math.pi * f[None, :] * t[:, None] + ph[None, :]).sum(axis=1)
    if wig.shake_seconds > 0:
        env = np.clip(np.minimum(t, wig.shake_seconds - t) / min(0.2, 0.5 * wig.shake_seconds), 0.0, 1.0)
        out *= (0.5 - 0.5 * np.cos(math.pi * env))[:, None]
    return out


def shake(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    wig: WigConfig,
    seed: int,
    *,
    strand_bodies: np.ndarray,
    on_step: object = None,
) -> None:
    """Run the seeded pre-brushed preparation in place (shake, then settle under gravity).

    Parameters
    ----------
    strand_bodies : np.ndarray
        Body ids of the moving hair vertices (they receive ``−m a(t)`` through ``xfrc_applied``).
    on_step : callable, optional
        ``on_step(model, data)`` after every step (e.g. to hold the arm's servo targets).
    """
    dt = model.opt.timestep
    n_shake = round(wig.shake_seconds / dt)
    n_settle = round(wig.settle_seconds / dt)
    acc = shake_acceleration(wig, seed, np.arange(n_shake) * dt)
    # the weight mass: a mass-scaled strand (WigConfig.mass_scale) is shaken as hard as the real one
    mass = (model.body_mass * (1.0 - model.body_gravcomp))[strand_bodies][:, None]
    for k in range(n_shake):
        data.xfrc_applied[strand_bodies, :3] = -mass * acc[k][None, :]
        mujoco.mj_step(model, data)
        if on_step is not None:
            on_step(model, data)  # type: ignore[operator]
    data.xfrc_applied[strand_bodies, :3] = 0.0
    for _ in range(n_settle):
        mujoco.mj_step(model, data)
        if on_step is not None:
            on_step(model, data)  # type: ignore[operator]
